//! Four accumulators on the S7 CPU (`__FEATURE 0, 4`, awlsim's test operation; an S7-400 has
//! ACCU 1 to 4): `ENT`, `LEAVE`, `PUSH`, `POP` move the whole stack and two-operand
//! arithmetic moves ACCU 3 to ACCU 2 and ACCU 4 to ACCU 3 ("Statement List (STL) for S7-300
//! and S7-400 Programming", accumulator and integer instructions).

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, RunOptions};
use awl::source::Files;

/// Runs OB 1 with `body` once, with awlsim's test operations, and checks `expect`.
fn passes(body: &str, expect: &str) {
    let program = format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n{body}END_ORGANIZATION_BLOCK\n");
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.into_bytes());
    let scenario = format!(
        "program = [\"p.awl\"]\ncpu = \"speed7\"\nextended = true\nrun = {{ cycles = 1 }}\n\
         [expect]\n{expect}"
    );
    files.insert(PathBuf::from("s.toml"), scenario.into_bytes());
    let ran = match runner::run(&RunOptions {
        scenario: Some(PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    }) {
        Ok(ran) => ran,
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    };
    assert!(
        !ran.failed() && ran.outcome.stop.is_none(),
        "{:#?} {:?}",
        ran.mismatches,
        ran.outcome.stop
    );
}

/// ACCU 1 to 4 hold 4, 3, 2, 1.
const FILLED: &str = "      __FEATURE 0, 4;\n      L 1;\n      L 2;\n      ENT;\n      L 3;\n      \
                      ENT;\n      L 4;\n";

/// ACCU 1 to 4 to MW 0, 2, 4, 6 (each `POP` moves the stack up by one).
const STORE: &str = "      T MW 0;\n      TAK;\n      T MW 2;\n      TAK;\n      POP;\n      \
                     POP;\n      T MW 4;\n      POP;\n      T MW 6;\n";

#[test]
fn ent_fills_the_stack() {
    passes(
        &format!("{FILLED}{STORE}"),
        "\"MW 0\" = 4\n\"MW 2\" = 3\n\"MW 4\" = 2\n\"MW 6\" = 1\n",
    );
}

#[test]
fn add_int_moves_accu_3_and_4_down() {
    // 3 + 4 = 7; ACCU 2 = old ACCU 3 (2), ACCU 3 = ACCU 4 = 1.
    passes(
        &format!("{FILLED}      +I;\n{STORE}"),
        "\"MW 0\" = 7\n\"MW 2\" = 2\n\"MW 4\" = 1\n\"MW 6\" = 1\n",
    );
}

#[test]
fn leave_moves_accu_3_to_2_and_4_to_3() {
    passes(
        &format!("{FILLED}      LEAVE;\n{STORE}"),
        "\"MW 0\" = 4\n\"MW 2\" = 2\n\"MW 4\" = 1\n\"MW 6\" = 1\n",
    );
}

#[test]
fn push_and_pop_move_the_whole_stack() {
    // PUSH: 4 4 3 2; then POP: 4 3 2 2.
    passes(
        &format!("{FILLED}      PUSH;\n      T MW 8;\n      POP;\n{STORE}"),
        "\"MW 8\" = 4\n\"MW 0\" = 4\n\"MW 2\" = 3\n\"MW 4\" = 2\n\"MW 6\" = 2\n",
    );
}

#[test]
fn the_feature_reports_the_accumulators() {
    passes(
        "      __FEATURE 0, 4;\n      __FEATURE 0;\n      T MW 0;\n",
        "\"MW 0\" = 4\n",
    );
    passes("      __FEATURE 0;\n      T MW 0;\n", "\"MW 0\" = 2\n");
}
