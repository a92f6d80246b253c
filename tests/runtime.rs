//! STOP reports and scenario errors as users see them, determinism, and timers on simulated time.

mod common;

use awl::diagnostics::render_plain;
use awl::runner::{self, NotRun};
use common::*;

fn stop_rendering(name: &str, program: &str, scenario: &str) -> String {
    let ran = ran(run_scenario(name, program, scenario));
    let stop = ran
        .outcome
        .stop
        .as_ref()
        .unwrap_or_else(|| panic!("{name}: no STOP"));
    render_plain(&runner::stop_report(&ran, stop))
}

#[test]
fn every_stop_cause_renders_with_line_and_block_stack() {
    let cases = [
        (
            "awl::stop::zyk",
            "FB 1\nNAME :LOOP\nM001 :JU =M001\n      BE\nOB 1\n      JU FB 1\nNAME :LOOP\n      BE\n",
            "run = { cycles = 1 }\n",
        ),
        (
            "awl::stop::stueb",
            "OB 1\n      JU PB 1\n      BE\nPB 1\n      JU PB 2\n      BE\nPB 2\n      JU PB 1\n      BE\n",
            "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n",
        ),
        (
            "awl::stop::lstack",
            "ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  big : ARRAY [1 .. 30000] OF DWORD;\nEND_VAR\nBEGIN\n      L #big[1];\n      T MB 0;\nEND_ORGANIZATION_BLOCK\n",
            "cpu = \"speed7\"\nrun = { cycles = 1 }\n",
        ),
        (
            "awl::stop::lzf_block",
            "OB 1\n      JU PB 1\n      BE\nPB 1\n      A  I 0.0\n      JU PB 9\n      BE\n",
            "run = { cycles = 1 }\n",
        ),
        (
            "awl::stop::lzf_data",
            "OB 1\n      C  DB 5\n      L  DW 3\n      BE\nDB 5\n 0: KF +1\n",
            "run = { cycles = 1 }\n",
        ),
        (
            "awl::stop::bcf",
            // The brackets balance in the text; the jump skips the `A(`.
            "OB 1\n      JU FB 1\nNAME :SKIP\n      BE\nFB 1\nNAME :SKIP\n      JU =M001\n      A(\nM001 :A  I 0.0\n      )\n      BE\n",
            "run = { cycles = 1 }\n",
        ),
        (
            "awl::stop::stp",
            "OB 1\n      A  I 0.0\n      STP\n      BE\n",
            "run = { cycles = 5 }\n",
        ),
        (
            "awl::stop::weck",
            "OB 1\n      BE\nOB 13\n      JU FB 1\nNAME :WAIT\n      BE\nFB 1\nNAME :WAIT\n      L  KF +3000\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n",
            "cpu = \"s5-95f\"\nrun = { for = \"100ms\" }\n[ob13]\ninterval = \"10ms\"\n",
        ),
        (
            "awl::stop::ob85",
            "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n",
            "cpu = \"speed7\"\nrun = { for = \"10ms\" }\n[[hw_module]]\nmodule = 4\nob = 40\n[[event]]\nat = \"2ms\"\nhw_interrupt = { module = 4, channel = 1, active_for = \"1ms\" }\n",
        ),
        (
            "awl::stop::ob80",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\n      NOP 0;\nEND_ORGANIZATION_BLOCK\nORGANIZATION_BLOCK OB 35\nBEGIN\n      L 200;\nm:    T MW 0;\n      L 1000;\nn:    LOOP n;\n      L MW 0;\n      LOOP m;\nEND_ORGANIZATION_BLOCK\n",
            "cpu = \"speed7\"\nrun = { for = \"5ms\" }\n[ob35]\ninterval = \"1ms\"\n",
        ),
        (
            "awl::stop::ob86",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A I 0.0;\n      = Q 4.0;\nEND_ORGANIZATION_BLOCK\n",
            "cpu = \"speed7\"\nrun = { for = \"5ms\" }\n[[event]]\nat = \"2ms\"\nstation = { number = 3, failed = true }\n",
        ),
    ];
    for (code, program, scenario) in cases {
        let rendered = stop_rendering(&code.replace("::", "_"), program, scenario);
        assert!(rendered.contains(code), "{code}:\n{rendered}");
        assert!(rendered.contains("BSTACK"), "{rendered}");
        insta::assert_snapshot!(code.replace("::", "__"), rendered);
    }
}

fn scenario_error(name: &str, program: &str, scenario: &str) -> String {
    match run_scenario(name, program, scenario) {
        Err(NotRun::Failed(reports)) => reports.iter().map(render_plain).collect(),
        Err(NotRun::SourceErrors(..) | NotRun::Usage(_)) => panic!("{name}: not a scenario error"),
        Ok(_) => panic!("{name}: the scenario ran"),
    }
}

#[test]
fn every_scenario_error_names_its_key_and_line() {
    let program = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n";
    let cases = [
        (
            "awl::scenario::syntax",
            "run = { cycles = 1 }\nwatchdog = \"1s\n",
        ),
        (
            "awl::scenario::unknown_key",
            "run = { cycles = 1 }\nwatchdgo = \"1s\"\n",
        ),
        (
            "awl::scenario::unknown_operand",
            "[expect]\n\"X 4.0\" = 1\n",
        ),
        ("awl::scenario::bad_value", "[expect]\n\"Q 4.0\" = 2\n"),
        (
            "awl::scenario::unknown_ob",
            "[[event]]\nat = \"1ms\"\ninterrupt = \"OB 9\"\n",
        ),
        ("awl::scenario::bad_duration", "run = { for = \"100\" }\n"),
        ("awl::scenario::wrong_type", "run = \"3s\"\n"),
        (
            "awl::scenario::invalid",
            "cpu = \"s5-95f\"\nmode = \"special\"\n",
        ),
    ];
    for (code, scenario) in cases {
        let rendered = scenario_error(&code.replace("::", "_"), program, scenario);
        assert!(rendered.contains(code), "{code}:\n{rendered}");
        insta::assert_snapshot!(code.replace("::", "__"), rendered);
    }
}

#[test]
fn a_typo_for_a_key_of_expect_or_check_is_corrected() {
    let program = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n";
    for (name, scenario, typo, meant) in [
        ("expect_mdoe", "[expect]\nmdoe = \"RUN\"\n", "mdoe", "mode"),
        (
            "expect_stop_caus",
            "[expect]\nstop_caus = \"ZYK\"\n",
            "stop_caus",
            "stop_cause",
        ),
        (
            "check_att",
            "[[check]]\natt = \"1ms\"\n\"Q 4.0\" = 1\n",
            "att",
            "at",
        ),
    ] {
        let rendered = scenario_error(name, program, scenario);
        assert!(
            rendered.contains(&format!("unknown key `{typo}`")),
            "{rendered}"
        );
        assert!(
            rendered.contains(&format!("did you mean `{meant}`?")),
            "{rendered}"
        );
        assert_eq!(rendered.matches("awl::scenario::").count(), 1, "{rendered}");
    }
}

#[test]
fn a_check_s_moment_is_asked_for_as_a_duration() {
    let rendered = scenario_error(
        "check_at_number",
        "OB 1\n      BE\n",
        "[[check]]\nat = 100\n\"Q 4.0\" = 0\n",
    );
    assert!(
        rendered.contains("`at` in [[check]] takes a duration in quotes"),
        "{rendered}"
    );
    assert!(rendered.contains("at = \"250ms\""), "{rendered}");
}

#[test]
fn set_accepts_inputs_only() {
    let rendered = scenario_error(
        "set_output",
        "OB 1\n      BE\n",
        "[[event]]\nat = \"1ms\"\nset = { \"Q 4.0\" = 1 }\n",
    );
    assert!(
        rendered.contains("`set` changes process inputs only"),
        "{rendered}"
    );
}

#[test]
fn unreadable_scenario_is_reported() {
    let options = runner::RunOptions {
        scenario: Some("no/such/scenario.toml".into()),
        ..Default::default()
    };
    let Err(NotRun::Failed(reports)) = runner::run(&options) else {
        panic!("ran")
    };
    assert_eq!(reports.len(), 1);
    assert!(render_plain(&reports[0]).contains("awl::scenario::read"));
}

fn jsonl_trace(name: &str) -> Vec<u8> {
    let dir = std::path::PathBuf::from("target/test-scenarios").join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let trace = dir.join("trace.jsonl");
    let options = runner::RunOptions {
        scenario: Some("programs/fig5_2_interrupt.toml".into()),
        trace: Some(trace.clone()),
        ..Default::default()
    };
    ran(runner::run(&options));
    std::fs::read(trace).unwrap()
}

#[test]
fn two_runs_give_byte_identical_traces() {
    let first = jsonl_trace("determinism_1");
    let second = jsonl_trace("determinism_2");
    assert!(first.len() > 1000);
    assert_eq!(first, second);
}

/// The on-delay of conveyor.awl through a scenario, at both sides of its edge.
#[test]
fn on_delay_timer_edges_on_simulated_time() {
    let program = "OB 1\n      A  I 0.0\n      L  KT 010.1\n      SD T 1\n      A  T 1\n      =  Q 4.0\n      BE\n";
    for (run_for, expected) in [("1.09s", 0), ("1.11s", 1)] {
        let scenario = format!(
            "run = {{ for = \"{run_for}\" }}\n[[event]]\nat = \"100ms\"\nset = {{ \"I 0.0\" = 1 }}\n[expect]\n\"Q 4.0\" = {expected}\n"
        );
        let ran = ran(run_scenario("on_delay", program, &scenario));
        assert!(ran.mismatches.is_empty(), "{run_for}: {:?}", ran.mismatches);
    }
}

/// A STOP between cycles in a program without any block still gets a report, not a panic.
#[test]
fn stop_between_cycles_without_blocks() {
    let scenario = "cpu = \"speed7\"\nrun = { for = \"3ms\" }\n[[hw_module]]\nmodule = 4\nob = 40\n[[event]]\nat = \"1ms\"\nhw_interrupt = { module = 4, channel = 1, active_for = \"5us\" }\n";
    let ran = ran(run_scenario(
        "empty_program",
        "; no blocks at all\n",
        scenario,
    ));
    let stop = ran.outcome.stop.as_ref().expect("STOP OB85");
    assert_eq!(stop.block, None);
    let rendered = render_plain(&runner::stop_report(&ran, stop));
    assert!(
        rendered.contains("awl::stop::ob85") && rendered.contains("BSTACK: empty"),
        "{rendered}"
    );
}

/// A STOP found at an interrupt point names the operation that led there: the block call, the
/// operation (with operation points), or the `DO` whose parameter was bad.
#[test]
fn stops_at_points_name_the_operation_that_led_there() {
    let program = "OB 1\n      L  KF +1\n      L  KF +2\n      X  F\n      X  F\n      JU PB 2\n      BE\nPB 2\n      BE\n";
    let result = ran(run_scenario(
        "zyk_at_call",
        program,
        "run = { cycles = 1 }\nwatchdog = \"20us\"\n",
    ));
    let stop = result.outcome.stop.as_ref().expect("ZYK");
    assert_eq!(stop.cause.code(), "ZYK");
    assert_eq!(
        (stop.stack[0].block.as_str(), stop.stack[0].line),
        ("OB 1", 6),
        "the call of PB 2 found the watchdog expired"
    );
    let result = ran(run_scenario(
        "zyk_at_operation",
        program,
        "run = { cycles = 1 }\nwatchdog = \"20us\"\ninterrupt_points = \"operation\"\n",
    ));
    let stop = result.outcome.stop.as_ref().expect("ZYK");
    assert_eq!(
        (stop.stack[0].block.as_str(), stop.stack[0].line),
        ("OB 1", 5),
        "the second X F ends after 20 us (24.7 us)"
    );
    let bad_do = "OB 1\n      JU FB 1\nNAME :D\n      BE\nFB 1\nNAME :D\n      L  KF +999\n      T  FW 0\n      DO FW 0\n      A  I 0.0\n      BE\n";
    let result = ran(run_scenario("bad_do", bad_do, "run = { cycles = 1 }\n"));
    let stop = result.outcome.stop.as_ref().expect("BCF");
    assert_eq!(stop.cause.code(), "BCF");
    assert_eq!(
        (stop.stack[0].block.as_str(), stop.stack[0].line),
        ("FB 1", 9)
    );
}

/// With operation points a taken jump ends at a point like any operation: a watchdog found
/// there names the jump, also when it goes back to the block's first operation.
#[test]
fn a_jump_that_ends_at_a_point_is_the_operation_named() {
    for target in ["M000", "M001"] {
        let program = format!(
            "OB 1\n      JU FB 1\nNAME :LOOP\n      BE\nFB 1\nNAME :LOOP\n\
             M000: L  KF +1\nM001: I  1\n      JU ={target}\n      BE\n"
        );
        let result = ran(run_scenario(
            "zyk_at_jump",
            &program,
            "cpu = \"speed7\"\nwatchdog = \"21us\"\n",
        ));
        let stop = result.outcome.stop.as_ref().expect("ZYK");
        assert_eq!(stop.cause.code(), "ZYK");
        assert_eq!(
            (stop.stack[0].block.as_str(), stop.stack[0].line),
            ("FB 1", 9),
            "the jump to {target} ran past 21 us"
        );
    }
}

/// Of two blocks with the same longest stretch, the summary names the first one reached.
#[test]
fn longest_block_is_the_first_of_equals() {
    let program = "OB 1\n      JU PB 2\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      X  F\n      BE\nPB 2\n      L  KF +1\n      X  F\n      BE\n";
    let result = ran(run_scenario(
        "equal_blocks",
        program,
        "run = { cycles = 1 }\n",
    ));
    let summary = awl::report::summary(&result);
    assert!(summary.contains("longest block: PB 2"), "{summary}");
}

/// A STOP found at a block end names the block that ended, with its caller's return point.
#[test]
fn stops_at_a_block_end_name_the_block_that_ended() {
    let program = "OB 1\n      JU PB 2\n      BE\nPB 2\n      L  KF +1\n      L  KF +2\n      X  F\n      X  F\n      BE\n";
    let result = ran(run_scenario(
        "zyk_at_end",
        program,
        "run = { cycles = 1 }\nwatchdog = \"30us\"\n",
    ));
    let stop = result.outcome.stop.as_ref().expect("ZYK");
    let stack: Vec<(&str, u32)> = stop
        .stack
        .iter()
        .map(|entry| (entry.block.as_str(), entry.line))
        .collect();
    assert_eq!(stack, [("PB 2", 9), ("OB 1", 2)]);
}

/// Expectations read double words of the flags.
#[test]
fn expectations_read_double_words() {
    let program = "OB 1\n      L  DH 12345678\n      T  FD 8\n      BE\n";
    let result = ran(run_scenario(
        "fd_expect",
        program,
        "run = { cycles = 1 }\n[expect]\n\"FD 8\" = 305419896\n\"FD 9\" = 878082048\n",
    ));
    assert!(result.mismatches.is_empty(), "{:?}", result.mismatches);
}
