//! The master control relay in STEP 7 programs ("Statement List (STL) for S7-300 and S7-400
//! Programming", the MCR instructions): `=` and `T` write 0 and `S`/`R` leave their bit while
//! the MCR is off, only between `MCRA` and `MCRD` of the block that has them; the MCR stack
//! is 8 deep and its over- or underflow stops the CPU.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, Ran, RunOptions};
use awl::source::Files;

fn run(program: &str, scenario: &str) -> Ran {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.as_bytes().to_vec());
    let scenario = format!("program = [\"p.awl\"]\ncpu = \"speed7\"\n{scenario}");
    files.insert(PathBuf::from("s.toml"), scenario.into_bytes());
    match runner::run(&RunOptions {
        scenario: Some(PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    }) {
        Ok(ran) => ran,
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

fn passes(program: &str, expect: &str) {
    let ran = run(
        program,
        &format!("run = {{ cycles = 1 }}\n[expect]\n{expect}"),
    );
    assert!(
        !ran.failed() && ran.expectations > 0 && ran.outcome.stop.is_none(),
        "{:#?} {:?}",
        ran.mismatches,
        ran.outcome.stop
    );
}

/// The STOP report of a program that must stop.
fn stop_report(program: &str) -> String {
    let ran = run(program, "run = { cycles = 1 }\n");
    let stop = ran.outcome.stop.as_ref().expect("a STOP");
    awl::diagnostics::render_plain(&runner::stop_report(&ran, stop))
}

fn ob1(body: &str) -> String {
    format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n{body}END_ORGANIZATION_BLOCK\n")
}

#[test]
fn with_the_mcr_off_assign_and_transfer_write_zero_set_and_reset_leave_the_bit() {
    let program = ob1(
        "      SET;\n      = M 0.1;\n      = Q 0.2;\n      CLR;\n      \
         = M 0.2;\n      L 1234;\n      T MW 10;\n      T MD 12;\n      \
         MCRA;\n      CLR;\n      MCR(;\n      L 99;\n      T MW 10;\n      T MD 12;\n      \
         SET;\n      = Q 0.0;\n      S M 0.2;\n      R M 0.1;\n      R Q 0.2;\n      \
         )MCR;\n      SET;\n      = Q 0.1;\n      MCRD;\n",
    );
    passes(
        &program,
        "\"Q 0.0\" = false\n\"Q 0.1\" = true\n\"Q 0.2\" = true\n\"M 0.1\" = true\n\
         \"M 0.2\" = false\n\"MW 10\" = 0\n\"MD 12\" = 0\n",
    );
}

#[test]
fn with_the_mcr_on_the_writes_are_as_without_it() {
    let program = ob1(
        "      MCRA;\n      SET;\n      MCR(;\n      L 77;\n      T MW 10;\n      \
         = Q 0.0;\n      S M 0.2;\n      )MCR;\n      MCRD;\n",
    );
    passes(
        &program,
        "\"Q 0.0\" = true\n\"M 0.2\" = true\n\"MW 10\" = 77\n",
    );
}

#[test]
fn without_mcra_the_writes_do_not_depend_on_the_mcr() {
    let program = ob1(
        "      CLR;\n      MCR(;\n      SET;\n      = Q 0.0;\n      L 5;\n      \
         T MW 10;\n      )MCR;\n",
    );
    passes(&program, "\"Q 0.0\" = true\n\"MW 10\" = 5\n");
}

#[test]
fn nested_zones_the_mcr_is_on_only_while_every_entry_is_one() {
    let program = ob1(
        "      MCRA;\n      SET;\n      MCR(;\n      CLR;\n      MCR(;\n      \
         SET;\n      MCR(;\n      = Q 0.0;\n      )MCR;\n      )MCR;\n      SET;\n      \
         = Q 0.1;\n      )MCR;\n      MCRD;\n",
    );
    passes(&program, "\"Q 0.0\" = false\n\"Q 0.1\" = true\n");
}

#[test]
fn the_dependency_belongs_to_the_block_and_the_mcr_stack_to_the_level() {
    // FC 1 has no MCRA: its writes are free. FC 2 has its own MCRA: it is inside OB 1's
    // open zone with RLO 0. After the calls OB 1's dependency is back.
    let program = "FUNCTION FC 1 : VOID\nBEGIN\n      SET;\n      = Q 0.1;\nEND_FUNCTION\n\
         FUNCTION FC 2 : VOID\nBEGIN\n      SET;\n      = Q 0.2;\n      MCRA;\n      SET;\n      \
         = Q 0.3;\nEND_FUNCTION\n"
        .to_string()
        + &ob1(
            "      MCRA;\n      CLR;\n      MCR(;\n      CALL FC 1;\n      CALL FC 2;\n      \
             SET;\n      = Q 0.4;\n      )MCR;\n      MCRD;\n",
        );
    passes(
        &program,
        "\"Q 0.1\" = true\n\"Q 0.2\" = true\n\"Q 0.3\" = false\n\"Q 0.4\" = false\n",
    );
}

#[test]
fn a_ninth_mcr_zone_stops_the_cpu_with_the_mcr_stack_fault() {
    let report = stop_report(&ob1(&"      MCR(;\n".repeat(9)));
    assert!(report.contains("awl::stop::bcf"), "{report}");
    assert!(report.contains("MCR stack fault (MCRF)"), "{report}");
    assert!(report.contains("8 entries"), "{report}");
}

#[test]
fn a_close_without_a_zone_stops_the_cpu() {
    let report = stop_report(&ob1("      MCR(;\n      )MCR;\n      )MCR;\n"));
    assert!(report.contains("MCR stack fault (MCRF)"), "{report}");
    assert!(report.contains("no MCR( open"), "{report}");
}

#[test]
fn the_mcr_stack_starts_empty_every_cycle() {
    // An open zone left at the end of the cycle does not carry over: eight more fit in
    // each cycle.
    let ran = run(&ob1(&"      MCR(;\n".repeat(8)), "run = { cycles = 3 }\n");
    assert!(ran.outcome.stop.is_none(), "{:?}", ran.outcome.stop);
}
