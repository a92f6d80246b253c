//! SFC 64 TIME_TCK: the system time, milliseconds of simulated time since the CPU started,
//! as a TIME ("System Software for S7-300/400 System and Standard Functions", SFC 64); its
//! RET_VAL checked as the interface declares it.

mod common;

use awl::runner::NotRun;
use common::step7::run;

#[test]
fn time_tck_is_the_time_since_the_start() {
    // OB 100 takes the time at startup; OB 1 each cycle. After 1.33 s the last cycle began
    // within a cycle of the end: between 1300 and 1330 ms.
    let program = "ORGANIZATION_BLOCK OB 100\nBEGIN\n      CALL SFC 64 (RET_VAL := MD 0);\n\
                   END_ORGANIZATION_BLOCK\n\
                   ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL SFC 64 (RET_VAL := MD 4);\n\
                   L MD 4;\n      L L#1300;\n      >=D;\n      = M 8.0;\n\
                   L MD 4;\n      L L#1330;\n      <=D;\n      = M 8.1;\n\
                   END_ORGANIZATION_BLOCK\n";
    let Ok(ran) = run(
        program,
        "run = { for = \"1.33s\" }\n[expect]\n\"MD 0\" = 0\n\"M 8.0\" = 1\n\"M 8.1\" = 1\n",
    ) else {
        panic!("the program runs");
    };
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
}

fn errors(call: &str) -> String {
    let program = format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n      {call}\nEND_ORGANIZATION_BLOCK\n");
    match run(&program, "") {
        Err(NotRun::SourceErrors(reports, _)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        _ => panic!("`{call}` has errors"),
    }
}

#[test]
fn ret_val_is_a_double_word_and_the_only_parameter() {
    let narrow = errors("CALL SFC 64 (RET_VAL := MW 4);");
    assert!(narrow.contains("awl::check::param_mismatch"), "{narrow}");
    assert!(narrow.contains("a TIME"), "{narrow}");
    let unknown = errors("CALL SFC 64 (OUT := MD 4);");
    assert!(unknown.contains("awl::check::unknown_param"), "{unknown}");
    assert!(unknown.contains("SFC 64 has RET_VAL"), "{unknown}");
    let missing = errors("CALL SFC 64;");
    assert!(missing.contains("awl::check::param_count"), "{missing}");
    assert!(missing.contains("RET_VAL := MD 4"), "{missing}");
}
