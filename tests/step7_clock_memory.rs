//! The S7 CPU's clock memory byte (`clock_memory = n` in the scenario, as a CPU's hardware
//! configuration sets it): bit 0 toggles every 50 ms (10 Hz) … bit 7 every second (0.5 Hz),
//! on simulated time, written at each cycle start.

mod common;

use awl::runner::{NotRun, Ran};

const OB1: &str = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L MB 100;\n      T MB 0;\n\
                   END_ORGANIZATION_BLOCK\n";

fn run(cpu: &str, scenario: &str) -> Result<Ran, NotRun> {
    common::step7::run_on(cpu, OB1, scenario)
}

#[test]
fn the_clock_bits_follow_simulated_time() {
    // At 75 ms: 10 Hz in its second half, 5 Hz in its first. At 1.33 s: 1330/50 = 26 (even:
    // 0), /100 = 13 (1), /200 = 6 (0), /250 = 5 (1), /400 = 3 (1), /500 = 2 (0), /800 = 1
    // (1), /1000 = 1 (1): 2#1101_1010. The program copies the byte to MB 0.
    let Ok(ran) = run(
        "speed7",
        "clock_memory = 100\nrun = { for = \"1.33s\" }\n\
         [[check]]\nat = \"75ms\"\n\"M 100.0\" = 1\n\"M 100.1\" = 0\n\
         [[check]]\nat = \"130ms\"\n\"M 100.0\" = 0\n\"M 100.1\" = 1\n\"M 100.2\" = 0\n\
         [expect]\n\"MB 100\" = 218\n\"MB 0\" = 218\n",
    ) else {
        panic!("the scenario runs");
    };
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
}

#[test]
fn without_the_setting_the_flag_byte_is_the_program_s() {
    let Ok(ran) = run(
        "speed7",
        "run = { for = \"1.33s\" }\n[expect]\n\"MB 100\" = 0\n",
    ) else {
        panic!("the scenario runs");
    };
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
}

fn scenario_error(cpu: &str, scenario: &str) -> String {
    match run(cpu, scenario) {
        // On an S5 CPU the S7 program is a source error too; both are reported.
        Err(NotRun::Failed(reports) | NotRun::SourceErrors(reports, _)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        _ => panic!("a scenario error"),
    }
}

#[test]
fn the_clock_memory_is_a_flag_byte_of_an_s7_cpu() {
    let text = scenario_error("speed7", "clock_memory = 8192\n");
    assert!(text.contains("no flag byte MB 8192"), "{text}");
    assert!(text.contains("MB 0 to MB 8191"), "{text}");
    let text = scenario_error("s5-115u", "clock_memory = 10\n");
    assert!(text.contains("has no clock memory byte"), "{text}");
    assert!(text.contains("speed7"), "{text}");
}
