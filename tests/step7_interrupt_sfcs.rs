//! SFC 39 DIS_IRT, SFC 40 EN_IRT, SFC 41 DIS_AIRT, SFC 42 EN_AIRT ("System Software for
//! S7-300/400 System and Standard Functions", 12.2 to 12.5) and the cyclic interrupt OB 35 with
//! its time error OB 80 (the same manual, 1.16; VIPA SPEED7 operation list, OB 35 and OB 80) on
//! the speed7 CPU.

mod common;

use awl::diagnostics::render_plain;
use awl::runner::{self, NotRun};
use common::{of, ran, run_scenario, traced};
use serde_json::Value;

const HEADER: &str = "cpu = \"speed7\"\n";

/// A scenario of the speed7 CPU with `rest`.
fn scenario(rest: &str) -> String {
    format!("{HEADER}{rest}")
}

/// The rendered errors of a run that did not start.
fn errors(result: Result<awl::runner::Ran, NotRun>) -> String {
    match result {
        Ok(_) => panic!("the run started"),
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => reports
            .iter()
            .map(|report| format!("{report:?}"))
            .collect::<Vec<_>>()
            .join("\n"),
        Err(NotRun::Usage(report)) => format!("{report:?}"),
    }
}

fn t(event: &Value) -> u64 {
    event["t_ns"].as_u64().unwrap()
}

/// OB 1 calls `body` once (MB 100 marks the first cycle).
fn once_in_ob1(body: &str) -> String {
    format!(
        "ORGANIZATION_BLOCK OB 1
VAR_TEMP
  info : ARRAY [1..20] OF BYTE;
END_VAR
BEGIN
      L     MB 100;
      L     0;
      ==I;
      SPBN  done;
      L     1;
      T     MB 100;
{body}
done: NOP   0;
END_ORGANIZATION_BLOCK
"
    )
}

#[test]
fn dis_irt_and_en_irt_take_three_modes_and_answer_8090_and_8091() {
    let program = once_in_ob1(
        "      CALL SFC 39 (MODE := B#16#0, OB_NR := 0, RET_VAL := MW 0);
      CALL SFC 40 (MODE := B#16#0, OB_NR := 0, RET_VAL := MW 2);
      CALL SFC 39 (MODE := B#16#1, OB_NR := 40, RET_VAL := MW 4);
      CALL SFC 40 (MODE := B#16#1, OB_NR := 40, RET_VAL := MW 6);
      CALL SFC 39 (MODE := B#16#2, OB_NR := 35, RET_VAL := MW 8);
      CALL SFC 40 (MODE := B#16#2, OB_NR := 35, RET_VAL := MW 10);
      CALL SFC 39 (MODE := B#16#1, OB_NR := 35, RET_VAL := MW 12);
      CALL SFC 39 (MODE := B#16#2, OB_NR := 1, RET_VAL := MW 14);
      CALL SFC 40 (MODE := B#16#2, OB_NR := 121, RET_VAL := MW 16);
      CALL SFC 39 (MODE := B#16#3, OB_NR := 35, RET_VAL := MW 18);
      CALL SFC 40 (MODE := MB 50, OB_NR := MW 52, RET_VAL := MW 20);
      CALL SFC 39 (MODE := B#16#0, OB_NR := 0, RET_VAL := MW 22);
      U     BIE;
      =     M 30.0;
      CALL SFC 39 (MODE := B#16#7, OB_NR := 0, RET_VAL := MW 24);
      U     BIE;
      =     M 30.1;",
    );
    let ran = ran(run_scenario(
        "irt_modes",
        &program,
        &scenario(
            "run = { cycles = 2 }
[expect]
\"MW 0\" = 0
\"MW 2\" = 0
\"MW 4\" = 0
\"MW 6\" = 0
\"MW 8\" = 0
\"MW 10\" = 0
\"MW 12\" = 0x8090
\"MW 14\" = 0x8090
\"MW 16\" = 0x8090
\"MW 18\" = 0x8091
\"MW 20\" = 0
\"M 30.0\" = 1
\"M 30.1\" = 0
",
        ),
    ));
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
}

#[test]
fn dis_airt_counts_its_calls_and_en_airt_answers_8080_without_one() {
    let program = once_in_ob1(
        "      CALL SFC 41 (RET_VAL := MW 0);
      CALL SFC 41 (RET_VAL := MW 2);
      CALL SFC 42 (RET_VAL := MW 4);
      CALL SFC 42 (RET_VAL := MW 6);
      CALL SFC 42 (RET_VAL := MW 8);
      U     BIE;
      =     M 30.0;",
    );
    let (ran, events) = traced(
        "airt_counts",
        &program,
        &scenario(
            "run = { cycles = 2 }
[expect]
\"MW 0\" = 1
\"MW 2\" = 2
\"MW 4\" = 1
\"MW 6\" = 0
\"MW 8\" = 0x8080
\"M 30.0\" = 0
",
        ),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let calls = of(&events, "irt_call");
    let names: Vec<&str> = calls.iter().map(|c| c["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        ["DIS_AIRT", "DIS_AIRT", "EN_AIRT", "EN_AIRT", "EN_AIRT"]
    );
    assert_eq!(calls[4]["ret_val"], -32640);
    let ends = of(&events, "delay_end");
    assert_eq!(ends.len(), 1);
    assert_eq!(ends[0]["by"], "EN_AIRT");
}

/// A loop of about 2 ms: 200 times 1000 LOOPs of 0.01 us.
const LONG: &str = "      L     200;
long: T     MW 90;
      L     1000;
innr: LOOP  innr;
      L     MW 90;
      LOOP  long;";

const OB40: &str = "
ORGANIZATION_BLOCK OB 40
VAR_TEMP
  info : ARRAY [1..20] OF BYTE;
END_VAR
BEGIN
      L     MW 40;
      +     1;
      T     MW 40;
END_ORGANIZATION_BLOCK
";

const MODULE: &str = "[[hw_module]]
module = 1
ob = 40

[[event]]
at = \"0.5ms\"
hw_interrupt = { module = 1, channel = 0, active_for = \"5ms\" }
";

#[test]
fn a_delayed_interrupt_runs_after_en_airt() {
    let program = once_in_ob1(&format!(
        "      CALL SFC 41 (RET_VAL := MW 0);
{LONG}
      L     MW 40;
      T     MW 2;
      CALL SFC 42 (RET_VAL := MW 4);
      L     MW 40;
      T     MW 6;"
    )) + OB40;
    let (ran, events) = traced(
        "airt_delayed",
        &program,
        &scenario(&format!(
            "run = {{ for = \"10ms\" }}
{MODULE}
[expect]
\"MW 2\" = 0
\"MW 6\" = 1
\"MW 40\" = 1
"
        )),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let delayed = of(&events, "irq_delayed");
    assert_eq!(delayed.len(), 1);
    assert_eq!(
        (delayed[0]["ob"].as_u64(), delayed[0]["delays"].as_u64()),
        (Some(40), Some(1))
    );
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["waited"], "delayed");
    let enable = of(&events, "irt_call")
        .into_iter()
        .find(|call| call["name"] == "EN_AIRT")
        .unwrap();
    assert!(t(service) >= t(enable) && t(delayed[0]) < t(enable));
    assert_eq!(of(&events, "delay_end")[0]["by"], "EN_AIRT");
    assert_eq!(ran.cpu.engine.stats(40).waited[3], 1);
}

#[test]
fn the_delay_ends_with_the_ob_that_called_dis_airt() {
    let program = once_in_ob1(&format!(
        "      CALL SFC 41 (RET_VAL := MW 0);
{LONG}
      L     MW 40;
      T     MW 2;"
    )) + OB40;
    let (ran, events) = traced(
        "airt_ob_end",
        &program,
        &scenario(&format!(
            "run = {{ for = \"10ms\" }}
{MODULE}
[expect]
\"MW 2\" = 0
\"MW 40\" = 1
"
        )),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let end = of(&events, "delay_end")[0];
    assert_eq!(
        (end["ob"].as_u64(), end["by"].as_str()),
        (Some(1), Some("OB end"))
    );
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["waited"], "delayed");
    assert!(t(service) >= t(end));
    // OB 1's next cycle runs without the delay: it ended with the OB.
    assert_eq!(of(&events, "irq_delayed").len(), 1);
}

#[test]
fn a_disabled_interrupt_is_discarded_not_delayed() {
    let program = once_in_ob1(&format!(
        "      CALL SFC 39 (MODE := B#16#2, OB_NR := 40, RET_VAL := MW 0);
{LONG}
      CALL SFC 40 (MODE := B#16#2, OB_NR := 40, RET_VAL := MW 4);"
    )) + OB40;
    let (ran, events) = traced(
        "irt_discarded",
        &program,
        &scenario(&format!(
            "run = {{ for = \"10ms\" }}
{MODULE}
[expect]
\"MW 0\" = 0
\"MW 4\" = 0
\"MW 40\" = 0
"
        )),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let discarded = of(&events, "irq_discarded");
    assert_eq!(discarded.len(), 1);
    assert_eq!(discarded[0]["ob"], 40);
    assert!(of(&events, "irq_service").is_empty());
    assert!(of(&events, "irq_delayed").is_empty());
    let stats = ran.cpu.engine.stats(40);
    assert_eq!(
        (stats.requested, stats.discarded, stats.serviced),
        (1, 1, 0)
    );
}

const OB35_COUNTS: &str = "
ORGANIZATION_BLOCK OB 35
VAR_TEMP
  OB35_EV_CLASS : BYTE;
  OB35_STRT_INF : BYTE;
  OB35_PRIORITY : BYTE;
  OB35_OB_NUMBR : BYTE;
  OB35_RESERVED_1 : BYTE;
  OB35_RESERVED_2 : BYTE;
  OB35_PHASE_OFFSET : WORD;
  OB35_RESERVED_3 : INT;
  OB35_EXC_FREQ : INT;
  OB35_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      L     MW 60;
      +     1;
      T     MW 60;
      L     #OB35_EV_CLASS;
      T     MB 62;
      L     #OB35_STRT_INF;
      T     MB 63;
      L     #OB35_PRIORITY;
      T     MB 64;
      L     #OB35_OB_NUMBR;
      T     MB 65;
      L     #OB35_EXC_FREQ;
      T     MW 66;
END_ORGANIZATION_BLOCK
";

const OB1_EMPTY: &str = "
ORGANIZATION_BLOCK OB 1
BEGIN
      NOP   0;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob35_runs_at_its_interval_with_its_start_information() {
    let program = format!("{OB1_EMPTY}{OB35_COUNTS}");
    let (ran, events) = traced(
        "ob35_interval",
        &program,
        &scenario(
            "run = { for = \"45ms\" }
[ob35]
interval = \"10ms\"
[expect]
\"MW 60\" = 4
\"MB 62\" = 0x11
\"MB 63\" = 0x36
\"MB 64\" = 12
\"MB 65\" = 35
\"MW 66\" = 10
",
        ),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let requests: Vec<u64> = of(&events, "irq_request")
        .iter()
        .filter(|r| r["ob"] == 35)
        .map(|r| t(r))
        .collect();
    assert_eq!(requests, [10_000_000, 20_000_000, 30_000_000, 40_000_000]);
}

#[test]
fn ob35_defaults_to_100_ms() {
    let program = format!("{OB1_EMPTY}{OB35_COUNTS}");
    let ran = ran(run_scenario(
        "ob35_default",
        &program,
        &scenario(
            "run = { for = \"250ms\" }
[expect]
\"MW 60\" = 2
\"MW 66\" = 100
",
        ),
    ));
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
}

/// OB 35's first run takes about 2 ms, longer than its 1 ms interval; the others are short.
const OB35_SLOW: &str = "
ORGANIZATION_BLOCK OB 35
VAR_TEMP
  info : ARRAY [1..20] OF BYTE;
END_VAR
BEGIN
      L     MW 60;
      +     1;
      T     MW 60;
      L     MW 60;
      L     1;
      >I;
      BEB;
      L     200;
long: T     MW 90;
      L     1000;
innr: LOOP  innr;
      L     MW 90;
      LOOP  long;
END_ORGANIZATION_BLOCK
";

const OB80: &str = "
ORGANIZATION_BLOCK OB 80
VAR_TEMP
  OB80_EV_CLASS : BYTE;
  OB80_FLT_ID : BYTE;
  OB80_PRIORITY : BYTE;
  OB80_OB_NUMBR : BYTE;
  OB80_RESERVED_1 : BYTE;
  OB80_RESERVED_2 : BYTE;
  OB80_ERROR_INFO : WORD;
  OB80_ERR_EV_CLASS : BYTE;
  OB80_ERR_EV_NUM : BYTE;
  OB80_OB_PRIORITY : BYTE;
  OB80_OB_NUM : BYTE;
  OB80_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      L     MW 70;
      +     1;
      T     MW 70;
      L     #OB80_EV_CLASS;
      T     MB 72;
      L     #OB80_FLT_ID;
      T     MB 73;
      L     #OB80_PRIORITY;
      T     MB 74;
      L     #OB80_OB_NUMBR;
      T     MB 75;
      L     #OB80_ERR_EV_CLASS;
      T     MB 76;
      L     #OB80_ERR_EV_NUM;
      T     MB 77;
      L     #OB80_OB_PRIORITY;
      T     MB 78;
      L     #OB80_OB_NUM;
      T     MB 79;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob35_falling_behind_starts_ob80() {
    let program = format!("{OB1_EMPTY}{OB35_SLOW}{OB80}");
    let (ran, events) = traced(
        "ob35_ob80",
        &program,
        &scenario(
            "run = { for = \"5ms\" }
[ob35]
interval = \"1ms\"
[expect]
\"MB 72\" = 0x35
\"MB 73\" = 0x02
\"MB 74\" = 26
\"MB 75\" = 80
\"MB 76\" = 0x11
\"MB 77\" = 0x36
\"MB 78\" = 12
\"MB 79\" = 35
\"MW 70\" = 2
mode = \"RUN\"
",
        ),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    // OB 35's first run spans the requests of 2 ms (OB 35 runs: the request waits, a time
    // error) and 3 ms (one is still pending: lost, a time error).
    let ob80 = ran.cpu.engine.stats(80);
    assert_eq!((ob80.requested, ob80.serviced), (2, 2), "{ob80:?}");
    let ob35 = ran.cpu.engine.stats(35);
    assert_eq!(
        (ob35.requested, ob35.lost, ob35.serviced),
        (5, 1, 4),
        "{ob35:?}"
    );
    let lost = of(&events, "irq_lost");
    assert_eq!((lost.len(), t(lost[0])), (1, 3_000_000));
    assert_eq!(ran.cpu.engine.stats(80).requested, 2);
}

#[test]
fn ob35_falling_behind_without_ob80_stops_the_cpu() {
    let program = format!("{OB1_EMPTY}{OB35_SLOW}");
    let (ran, events) = traced(
        "ob35_no_ob80",
        &program,
        &scenario(
            "run = { for = \"5ms\" }
[ob35]
interval = \"1ms\"
[expect]
mode = \"STOP\"
stop_cause = \"OB80\"
",
        ),
    );
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    assert_eq!(of(&events, "stop")[0]["cause"], "OB80");
    let stop = ran.outcome.stop.as_ref().expect("STOP OB80");
    let rendered = render_plain(&runner::stop_report(&ran, stop));
    assert!(rendered.contains("awl::stop::ob80"), "{rendered}");
}

#[test]
fn a_disabled_ob35_is_discarded_and_never_falls_behind() {
    let program = once_in_ob1("      CALL SFC 39 (MODE := B#16#1, OB_NR := 30, RET_VAL := MW 0);")
        + OB35_SLOW;
    let ran = ran(run_scenario(
        "ob35_disabled",
        &program,
        &scenario(
            "run = { for = \"5ms\" }
[ob35]
interval = \"1ms\"
[expect]
\"MW 60\" = 0
mode = \"RUN\"
",
        ),
    ));
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    assert_eq!(ran.cpu.engine.stats(35).discarded, 5);
}

#[test]
fn ob35_intervals_the_s7_cpu_cannot_have_are_errors() {
    let program = format!("{OB1_EMPTY}{OB35_COUNTS}");
    for (interval, said) in [
        ("0ms", "interval `0ms` is not a whole number"),
        ("1.5ms", "interval `1.5ms` is not a whole number"),
        ("61s", "interval `61s` is not a whole number"),
        ("soon", "soon"),
    ] {
        let text = errors(run_scenario(
            "ob35_bad_interval",
            &program,
            &scenario(&format!("[ob35]\ninterval = \"{interval}\"\n")),
        ));
        assert!(text.contains(said), "{interval}: {text}");
    }
}

#[test]
fn ob35_belongs_to_the_speed7() {
    let text = errors(run_scenario(
        "ob35_s5",
        "OB 1\n      BE\n",
        "cpu = \"s5-115u\"\n[ob35]\ninterval = \"10ms\"\n",
    ));
    assert!(
        text.contains("[ob35] belongs to the speed7 profile"),
        "{text}"
    );
}

#[test]
fn the_interrupt_sfcs_need_their_parameters() {
    for (call, said) in [
        ("CALL SFC 41;", "expects 1 parameters"),
        ("UC SFC 42;", "expects 1 parameters"),
        (
            "CALL SFC 39 (MODE := B#16#0, RET_VAL := MW 0);",
            "missing: OB_NR",
        ),
        (
            "CALL SFC 41 (RET_VAL := MW 0, MODE := B#16#0);",
            "has no parameter `MODE`",
        ),
        (
            "CALL SFC 42 (RET_VAL := 5);",
            "does not accept this operand",
        ),
        (
            "CALL SFC 40 (MODE := MW 2, OB_NR := 40, RET_VAL := MW 0);",
            "does not accept this operand",
        ),
        (
            "CALL SFC 39 (MODE := B#16#0, OB_NR := MB 3, RET_VAL := MW 0);",
            "does not accept this operand",
        ),
    ] {
        let program = once_in_ob1(&format!("      {call}"));
        let text = errors(run_scenario("irt_params", &program, HEADER));
        assert!(text.contains(said), "{call}: {text}");
    }
}

#[test]
fn the_timeline_marks_calls_delays_and_discards() {
    let program = once_in_ob1(&format!(
        "      CALL SFC 39 (MODE := B#16#2, OB_NR := 35, RET_VAL := MW 0);
      CALL SFC 41 (RET_VAL := MW 2);
{LONG}
      CALL SFC 42 (RET_VAL := MW 4);"
    )) + OB40
        + OB35_COUNTS;
    let path = common::write_scenario(
        "irt_timeline",
        &program,
        &scenario(&format!(
            "run = {{ for = \"12ms\" }}\n[ob35]\ninterval = \"10ms\"\n{MODULE}"
        )),
    );
    let svg_path = path.with_file_name("timeline.svg");
    ran(runner::run(&runner::RunOptions {
        scenario: Some(path),
        timeline: Some(svg_path.clone()),
        ..runner::RunOptions::default()
    }));
    let svg = std::fs::read_to_string(svg_path).unwrap();
    for class in [
        "class=\"delayed\"",
        "class=\"irt-call\"",
        "class=\"discarded\"",
        "sfc-legend",
    ] {
        assert!(svg.contains(class), "{class}");
    }
    // The three calls, two of them merged into one mark of the same pixel.
    let calls: u32 = svg
        .split("<g class=\"irt-call\" data-count=\"")
        .skip(1)
        .map(|rest| rest[..rest.find('"').unwrap()].parse::<u32>().unwrap())
        .sum();
    assert_eq!(calls, 3);
}
