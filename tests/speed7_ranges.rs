//! The speed7 CPU's operand ranges as the VIPA SPEED7 CPU manuals' technical data give them:
//! 512 S7 timers and 512 S7 counters (an S7-300 has 256), each bound accepted and the next
//! number a source error naming the range; the timers and counters past 255 run and show in
//! the state.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

fn in_ob1(statements: &str) -> String {
    format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n{statements}\nEND_ORGANIZATION_BLOCK\n")
}

fn source_errors(statements: &str) -> String {
    match run(&in_ob1(statements), "run = { cycles = 1 }\n") {
        Err(NotRun::SourceErrors(reports, _)) => {
            reports.iter().map(|report| format!("{report:?}")).collect()
        }
        Err(_) => panic!("{statements}: not a source error"),
        Ok(_) => panic!("{statements}: ran"),
    }
}

#[test]
fn timers_and_counters_past_255_run_up_to_511() {
    let program = in_ob1(
        "      SET;\n      L S5T#10S;\n      SE T 256;\n      A T 256;\n      = M 10.0;\n\
         \x20     SET;\n      L S5T#10S;\n      SE T 511;\n      A T 511;\n      = M 10.1;\n\
         \x20     SET;\n      L C#300;\n      S C 300;\n      L C 300;\n      T MW 2;\n\
         \x20     SET;\n      L C#511;\n      S C 511;\n      L C 511;\n      T MW 4;",
    );
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"M 10.0\" = true\n\"M 10.1\" = true\n\
         \"MW 2\" = 300\n\"MW 4\" = 511\n",
    );
}

#[test]
fn the_timer_and_counter_past_511_are_source_errors_with_the_range() {
    let timer = source_errors("      A T 512;");
    assert!(timer.contains("operand_range"), "{timer}");
    assert!(timer.contains("T 0 to 511"), "{timer}");
    let counter = source_errors("      L C 512;");
    assert!(counter.contains("operand_range"), "{counter}");
    assert!(counter.contains("C 0 to 511"), "{counter}");
}

#[test]
fn the_flags_and_peripheral_bytes_end_at_8191() {
    passes(
        &in_ob1("      L 7;\n      T MB 8191;"),
        "run = { cycles = 1 }\n[expect]\n\"MB 8191\" = 7\n",
    );
    assert!(source_errors("      L MB 8192;").contains("M bytes 0 to 8191"));
    assert!(source_errors("      L PIB 8192;").contains("operand_range"));
}
