//! The playground's functions (what the browser page calls through WebAssembly), run natively:
//! every sample gives the summary `awl run` prints, diagnostics point at their lines, the
//! debugger steps, live mode flips inputs, lights outputs and services requested OBs, and a long
//! run reports its progress from inside a cycle without changing its outcome.

mod common;

use std::cell::RefCell;
use std::rc::Rc;
use std::time::Duration;

use awl::playground::{self, Live, Place, Progress, Pulse, Request};
use common::{cli_summary, playground_files as catalogue};

/// A pulse that reports at every look (the looks come every microsecond of simulated time, the
/// closest they come), and what it heard.
fn listening() -> (Pulse, Rc<RefCell<Vec<Progress>>>) {
    let heard = Rc::new(RefCell::new(Vec::new()));
    let listener = Rc::clone(&heard);
    let pulse = Pulse::new(
        Duration::ZERO,
        Box::new(move |progress| listener.borrow_mut().push(progress)),
    );
    (pulse, heard)
}

fn silent() -> Pulse {
    Pulse::new(Duration::MAX, Box::new(|_| {}))
}

fn scenario(name: &str) -> Request {
    Request {
        files: catalogue(),
        scenario: Some(name.to_string()),
        ..Request::default()
    }
}

fn program(name: &str) -> Request {
    Request {
        files: catalogue(),
        program: Some(name.to_string()),
        ..Request::default()
    }
}

#[test]
fn every_sample_gives_the_summary_awl_run_prints() {
    let scenarios: Vec<String> = catalogue()
        .into_keys()
        .filter(|name| name.ends_with(".toml"))
        .collect();
    assert!(scenarios.len() > 20, "{scenarios:?}");
    // One thread per sample: the benchmarks' long runs overlap.
    std::thread::scope(|scope| {
        for name in &scenarios {
            scope.spawn(move || the_sample_gives_the_summary_awl_run_prints(name));
        }
    });
}

fn the_sample_gives_the_summary_awl_run_prints(name: &str) {
    let outcome = playground::run(&scenario(name));
    assert!(outcome.ran, "{name}: {:#?}", outcome.diagnostics);
    // `awl run` prints the watch table above the summary; the page shows it apart.
    let printed = outcome.watch.clone().unwrap_or_default() + &outcome.summary;
    assert_eq!(printed, cli_summary(name), "{name}");
    let timeline = outcome.timeline.unwrap();
    assert!(
        timeline.starts_with("<svg") && timeline.contains("<title>"),
        "{name}"
    );
    assert!(outcome.state.unwrap().contains("ACCU"), "{name}");
}

#[test]
fn the_interrupt_example_is_serviced_once() {
    let outcome = playground::run(&scenario("fig5_2_interrupt.toml"));
    assert!(outcome.summary.contains("OB 3: requested 1, serviced 1"));
    assert!(outcome.stop.is_none());
}

/// The STEP 7 samples of programs/s7/ are in the catalogue under `s7/`, their scenarios find
/// their programs beside them, and the SPEED7 sample loses and holds its hardware interrupts
/// as the VIPA SPEED7 operation list (OB 40/OB 41) says.
#[test]
fn the_step7_samples_are_in_the_catalogue() {
    let files = catalogue();
    for sample in [
        "traffic_light",
        "motor_fb",
        "ob40_alarm",
        "speed7_critical",
        "speed7_lines",
        "speed7_ob85",
        "speed7_stop",
    ] {
        for extension in ["awl", "toml"] {
            let name = format!("s7/{sample}.{extension}");
            assert!(files.contains_key(&name), "{name}");
        }
    }
    let outcome = playground::run(&scenario("s7/ob40_alarm.toml"));
    assert!(outcome.ran, "{:#?}", outcome.diagnostics);
    assert!(outcome.stop.is_none());
    for line in [
        "expectations: 12 of 12 met",
        "OB 40: requested 5, serviced 3, lost 2",
        "OB 82: requested 1, serviced 1, lost 0",
    ] {
        assert!(outcome.summary.contains(line), "{}", outcome.summary);
    }
    let critical = playground::run(&scenario("s7/speed7_critical.toml"));
    for line in [
        "expectations: 10 of 10 met",
        "OB 40: waited beyond the response bound: 3 because SFC 41 DIS_AIRT delayed it",
    ] {
        assert!(critical.summary.contains(line), "{}", critical.summary);
    }
    let alone = playground::run(&program("s7/motor_fb.awl"));
    assert!(alone.summary.contains("cpu: speed7"), "{}", alone.summary);
}

#[test]
fn source_errors_come_with_their_lines_and_help() {
    let outcome = playground::run(&program("mistakes.awl"));
    assert!(!outcome.ran);
    assert_eq!(outcome.summary, "not run: 3 errors in the program\n");
    let lines: Vec<u32> = outcome
        .diagnostics
        .iter()
        .map(|diagnostic| diagnostic.at.as_ref().unwrap().line)
        .collect();
    assert_eq!(lines, [5, 7, 8, 13], "{:#?}", outcome.diagnostics);
    let severities: Vec<_> = outcome.diagnostics.iter().map(|d| d.severity).collect();
    assert_eq!(severities, ["error", "warning", "error", "error"]);
    assert!(outcome.diagnostics.iter().all(|diagnostic| {
        diagnostic.code.is_some() && diagnostic.rendered.contains("mistakes.awl")
    }));
    assert!(outcome.diagnostics.iter().any(|d| d.help.is_some()));
}

#[test]
fn a_stop_comes_with_its_report_and_line() {
    let outcome = playground::run(&scenario("speed7_stop.toml"));
    assert!(outcome.ran);
    assert!(outcome.summary.contains("mode at end: STOP"));
    assert!(outcome.stop.unwrap().contains("STOP OB85"));
    let place = outcome.stop_at.unwrap();
    assert_eq!((place.file.as_str(), place.line), ("speed7_stop.awl", 6));
}

#[test]
fn the_watch_table_comes_with_the_scenario_that_asks_for_it() {
    let outcome = playground::run(&scenario("press_en.toml"));
    assert!(outcome.watch.unwrap().contains("-VALVEDOWN"));
    assert!(playground::run(&scenario("fig5_2.toml")).watch.is_none());
}

#[test]
fn selectors_override_the_scenario() {
    let mut request = scenario("fig5_2_interrupt.toml");
    request.points = Some("operation".into());
    let outcome = playground::run(&request);
    assert!(outcome.ran);
    assert!(outcome.timeline.unwrap().contains("operation points"));
    let mut request = scenario("fig5_2.toml");
    request.cpu = Some("speed7".into());
    let outcome = playground::run(&request);
    assert!(
        outcome.summary.contains("cpu: speed7"),
        "{}",
        outcome.summary
    );
}

#[test]
fn a_program_without_a_scenario_runs_a_second() {
    let outcome = playground::run(&program("fig5_2.awl"));
    assert!(outcome.ran, "{:#?}", outcome.diagnostics);
    assert!(
        outcome.summary.contains("simulated: 1000."),
        "{}",
        outcome.summary
    );
}

#[test]
fn each_bad_selector_is_refused_with_its_code() {
    let cases = [
        ("cpu", "awl::playground::cpu"),
        ("points", "awl::playground::points"),
        ("mode", "awl::playground::mode"),
    ];
    for (selector, code) in cases {
        let mut request = scenario("fig5_2.toml");
        match selector {
            "cpu" => request.cpu = Some("s7-1500".into()),
            "points" => request.points = Some("anywhere".into()),
            _ => request.mode = Some("fast".into()),
        }
        let outcome = playground::run(&request);
        assert!(!outcome.ran);
        assert_eq!(outcome.summary, "not run: 1 error in the request\n");
        assert_eq!(outcome.diagnostics[0].code.as_deref(), Some(code));
        assert!(outcome.diagnostics[0].help.is_some());
    }
    let nothing = Request::default();
    let outcome = playground::run(&nothing);
    assert_eq!(
        outcome.diagnostics[0].code.as_deref(),
        Some("awl::playground::nothing")
    );
}

#[test]
fn a_scenario_naming_a_missing_file_is_refused() {
    let mut request = scenario("fig5_2.toml");
    request.files.remove("fig5_2.awl");
    let outcome = playground::run(&request);
    assert!(!outcome.ran);
    assert!(
        outcome
            .summary
            .starts_with("not run: 1 error in the scenario")
    );
    assert!(outcome.diagnostics[0].message.contains("fig5_2.awl"));
}

#[test]
fn the_debugger_steps_and_stops_at_a_breakpoint() {
    let request = scenario("fig5_2_interrupt.toml");
    let paused = playground::debug(&request, "step\nstep\n");
    assert!(paused.outcome.is_none());
    assert!(
        paused.transcript.contains("(awl) step"),
        "{}",
        paused.transcript
    );
    let first = paused.paused_at.unwrap();
    assert_eq!(first.file, "fig5_2_interrupt.awl");
    assert!(paused.state.unwrap().contains("ACCU"));

    let at_break = playground::debug(&request, "break PB 3 line 21\ncontinue\n");
    let place = at_break.paused_at.expect("paused at the breakpoint");
    assert!(place.line > first.line, "{place:?} after {first:?}");

    let finished = playground::debug(&request, "continue\n");
    assert!(finished.paused_at.is_none());
    let outcome = finished.outcome.unwrap();
    assert!(outcome.summary.contains("OB 3: requested 1, serviced 1"));
}

/// A loop that never ends its cycle: the watchdog (here 20 ms) ends it with STOP ZYK.
fn endless(cpu: &str, points: &str) -> Request {
    let mut files = catalogue();
    files.insert(
        "endless.awl".into(),
        "OB 1\n      JU FB 1\nNAME :LOOP\n      BE\nFB 1\nNAME :LOOP\nM001: L  KF +1\n      JU =M001\n      BE\n".into(),
    );
    files.insert(
        "endless.toml".into(),
        format!("program = \"endless.awl\"\ncpu = \"{cpu}\"\ninterrupt_points = \"{points}\"\nwatchdog = \"20ms\"\n"),
    );
    Request {
        files,
        scenario: Some("endless.toml".into()),
        ..Request::default()
    }
}

/// The pulse is heard from inside a level that never ends: the clock moves on in cycle 1, at
/// backward jumps (block points) and after operations (operation points).
#[test]
fn a_loop_in_a_level_reports_its_progress() {
    for (cpu, points) in [("sinumerik-840c", "block"), ("speed7", "operation")] {
        let (pulse, heard) = listening();
        let outcome = playground::run_reporting(&endless(cpu, points), pulse);
        assert!(outcome.summary.contains("STOP"), "{}", outcome.summary);
        let heard = heard.borrow();
        let in_cycle_1 = heard.iter().filter(|progress| progress.cycle == 1).count();
        assert!(
            in_cycle_1 > 100,
            "{cpu}: heard {in_cycle_1} times in cycle 1"
        );
        assert!(heard.iter().all(|progress| progress.cycle <= 1), "{cpu}");
        assert!(
            heard
                .windows(2)
                .all(|two| two[0].clock_ns < two[1].clock_ns),
            "{cpu}: the clock moves on"
        );
        let last = heard.last().unwrap().clock_ns;
        assert!(last > 19_000_000 && last <= 20_000_000, "{cpu}: {last}");
    }
}

/// Listening changes nothing: every sample ends as it does without a pulse (summary, STOP,
/// state, watch table, timeline), and so does a debugger session. (The benchmarks are left
/// out: millions of looks at the clock take long in a test build.)
#[test]
fn a_run_with_a_pulse_ends_as_one_without() {
    let scenarios: Vec<String> = catalogue()
        .into_keys()
        .filter(|name| name.ends_with(".toml") && !name.starts_with("bench/"))
        .collect();
    std::thread::scope(|scope| {
        for name in &scenarios {
            scope.spawn(move || {
                let request = scenario(name);
                let (pulse, heard) = listening();
                let reported = playground::run_reporting(&request, pulse);
                assert!(!heard.borrow().is_empty(), "{name}");
                let plain = playground::run(&request);
                assert_eq!(
                    serde_json::to_value(&reported).unwrap(),
                    serde_json::to_value(&plain).unwrap(),
                    "{name}"
                );
            });
        }
    });
    let request = scenario("fig5_2_interrupt.toml");
    let commands = "break PB 3 line 21\ncontinue\nstep\ncontinue\n";
    let (pulse, _) = listening();
    assert_eq!(
        serde_json::to_value(playground::debug_reporting(&request, commands, pulse)).unwrap(),
        serde_json::to_value(playground::debug(&request, commands)).unwrap()
    );
}

#[test]
fn the_debugger_reports_a_request_it_cannot_run() {
    let debugged = playground::debug(&program("mistakes.awl"), "step\n");
    assert!(!debugged.outcome.unwrap().ran);
    assert!(debugged.transcript.is_empty());
}

#[test]
fn live_mode_flips_inputs_and_lights_outputs() {
    let mut live = Live::start(&scenario("press_en.toml")).unwrap();
    live.advance(50_000_000, 10_000_000);
    let view = live.view(10_000_000);
    assert_eq!(view.mode, "RUN");
    assert!(view.cycles > 0);
    let names: Vec<_> = view
        .inputs
        .iter()
        .filter_map(|bit| bit.name.clone())
        .collect();
    assert!(names.contains(&"TWOHAND1".to_string()), "{names:?}");
    let valve = |view: &playground::LiveView| {
        view.outputs
            .iter()
            .find(|bit| bit.name.as_deref() == Some("VALVEDOWN"))
            .unwrap()
            .value
    };
    assert!(!valve(&view));
    live.set_input("-TWOHAND1", true).unwrap();
    live.set_input("-TWOHAND2", true).unwrap();
    live.advance(10_000_000, 10_000_000);
    let view = live.view(10_000_000);
    assert!(valve(&view));
    assert!(view.timeline.starts_with("<svg"));
    assert!(live.set_input("I 99.9", true).is_err());
}

#[test]
fn live_mode_services_a_requested_interrupt() {
    let mut live = Live::start(&scenario("fig5_2_interrupt.toml")).unwrap();
    live.advance(1_000_000, 1_000_000);
    let view = live.view(1_000_000);
    assert_eq!(view.interrupt_obs, [3]);
    assert!(live.request(3));
    live.advance(1_000_000, 1_000_000);
    assert!(live.view(2_000_000).timeline.contains("OB 3 serviced"));
}

#[test]
fn live_mode_shows_a_stop_and_stays_there() {
    let mut live = Live::start(&scenario("speed7_stop.toml")).unwrap();
    live.advance(5_000_000, 5_000_000);
    let view = live.view(5_000_000);
    assert_eq!(view.mode, "STOP");
    assert!(view.stop.unwrap().contains("STOP OB85"));
    assert_eq!(
        view.stop_at,
        Some(Place {
            file: "speed7_stop.awl".into(),
            line: 6,
            column: 1
        })
    );
    let clock = view.clock;
    live.advance(5_000_000, 5_000_000);
    assert_eq!(live.view(5_000_000).clock, clock);
}

#[test]
fn live_mode_refuses_a_program_with_errors() {
    let refused = Live::start(&program("mistakes.awl")).err().unwrap();
    assert_eq!(refused.diagnostics.len(), 4);
}

#[test]
fn the_editor_colours_the_words_of_both_sets() {
    let words = playground::words();
    for operation in ["A", "U", "JU", "SPA", "BE", "L", "T"] {
        assert!(words.operations.contains(&operation), "{operation}");
    }
    for area in ["I", "E", "Q", "A", "FW", "MW"] {
        assert!(words.areas.contains(&area), "{area}");
    }
    assert!(words.constants.contains(&"KF"));
    assert!(words.blocks.contains(&"PB"));
    assert!(words.keywords.contains(&"BEZ"));
    for operation in ["OPN", "AUF", "SPBNB", "JCN", "CALL", "L"] {
        assert!(words.step7.operations.contains(&operation), "{operation}");
    }
    for area in ["DBW", "DIX", "PEW", "PIW"] {
        assert!(words.step7.areas.contains(&area), "{area}");
    }
    for keyword in [
        "FUNCTION_BLOCK",
        "VAR_INPUT",
        "BEGIN",
        "TITLE",
        "S5TIME",
        "NETWORK",
    ] {
        assert!(words.step7.keywords.contains(&keyword), "{keyword}");
    }
}

#[test]
fn json_requests_run_and_malformed_ones_are_refused() {
    let request = serde_json::json!({ "files": catalogue(), "scenario": "fig5_2_interrupt.toml" });
    let outcome: serde_json::Value =
        serde_json::from_str(&playground::json::run(&request.to_string(), silent())).unwrap();
    assert!(outcome["summary"].as_str().unwrap().contains("serviced 1"));
    assert!(outcome["timeline"].as_str().unwrap().starts_with("<svg"));

    for malformed in [
        "",
        "{",
        r#"{"files": {}, "colour": "red"}"#,
        r#"{"files": 3}"#,
    ] {
        let refused: serde_json::Value =
            serde_json::from_str(&playground::json::run(malformed, silent())).unwrap();
        assert_eq!(refused["ran"], false, "{malformed}");
        let summary = refused["summary"].as_str().unwrap();
        assert!(
            summary.starts_with("not run: the page sent a malformed request"),
            "{summary}"
        );
        let debugged = playground::json::debug(malformed, "step\n", silent());
        assert!(debugged.contains("malformed request"), "{debugged}");
        let live = playground::json::start_live(malformed).err().unwrap();
        assert!(live.contains("malformed request"), "{live}");
    }
}

#[test]
fn the_catalogue_lists_files_profiles_and_words() {
    let catalogue: serde_json::Value =
        serde_json::from_str(&playground::json::catalogue(&[("a.awl", "OB 1\nBE\n")])).unwrap();
    assert_eq!(catalogue["files"]["a.awl"], "OB 1\nBE\n");
    let cpus = catalogue["cpus"].as_array().unwrap();
    assert!(cpus.iter().any(|cpu| cpu["name"] == "sinumerik-840c"));
    assert!(catalogue["words"]["operations"].as_array().unwrap().len() > 50);
}
