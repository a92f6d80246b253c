//! The minimum cycle time of an S7 CPU (`min_cycle`, an awlsim project's `cycle_time_target_us`):
//! the cycle end waits until the minimum has passed since the cycle start, interrupts run in
//! the wait, and the trace and the timeline show the wait as a stretch of its own.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, RunOptions};
use awl::source::Files;
use common::{of, traced};

/// OB 1 counts its cycles in MW 10, the cyclic interrupt OB 35 its runs in MW 20.
const PROGRAM: &str = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L MW 10;\n      L 1;\n      +I;\n\
                       T MW 10;\nEND_ORGANIZATION_BLOCK\n\
                       ORGANIZATION_BLOCK OB 35\nBEGIN\n      L MW 20;\n      L 1;\n      +I;\n\
                       T MW 20;\nEND_ORGANIZATION_BLOCK\n";

const TEN_MS: u64 = 10_000_000;

#[test]
fn every_cycle_lasts_the_minimum_and_ob_35_runs_in_the_wait() {
    let scenario = "cpu = \"speed7\"\nmin_cycle = \"10ms\"\nrun = { for = \"50ms\" }\n\
                    [ob35]\ninterval = \"5ms\"\n\
                    [expect]\n\"MW 10\" = 5\n\"MW 20\" = 10\n";
    let (ran, events) = traced("min_cycle_ob35", PROGRAM, scenario);
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let times = &ran.cpu.cycle_times;
    assert_eq!(times.count, 5);
    assert!(times.min_ns >= TEN_MS, "{times:?}");
    for end in of(&events, "cycle_end") {
        assert!(end["cycle_time_ns"].as_u64().unwrap() >= TEN_MS, "{end}");
    }
    // Each OB 35 runs between a stretch of the wait and the cycle's end: in the wait.
    let mut in_wait = false;
    let mut serviced_in_wait = 0;
    for event in &events {
        match event["ev"].as_str().unwrap() {
            "cycle_wait" => in_wait = true,
            "cycle_end" => in_wait = false,
            "irq_service" if in_wait && event["ob"] == 35 => serviced_in_wait += 1,
            _ => {}
        }
    }
    assert_eq!(serviced_in_wait, 10);
    let during: Vec<&str> = of(&events, "irq_request")
        .iter()
        .filter_map(|request| request["during"].as_str())
        .collect();
    assert!(
        during
            .iter()
            .all(|place| *place == "wait for the minimum cycle time"),
        "{during:?}"
    );
    // The wait starts after the operating-system time, each stretch up to the next thing due.
    let first_wait = of(&events, "cycle_wait")[0];
    let os_time = of(&events, "os_time")[0];
    assert_eq!(
        first_wait["t_ns"].as_u64(),
        Some(os_time["t_ns"].as_u64().unwrap() + os_time["duration_ns"].as_u64().unwrap())
    );
    assert_eq!(
        first_wait["t_ns"].as_u64().unwrap() + first_wait["duration_ns"].as_u64().unwrap(),
        5_000_000,
        "up to OB 35's first request"
    );
}

#[test]
fn without_a_minimum_the_next_cycle_starts_at_once() {
    let (ran, events) = traced(
        "min_cycle_none",
        PROGRAM,
        "cpu = \"speed7\"\nrun = { cycles = 3 }\n",
    );
    assert!(of(&events, "cycle_wait").is_empty());
    assert!(ran.cpu.cycle_times.max_ns < 1_000_000);
}

#[test]
fn the_timeline_shows_the_wait_in_the_system_strip() {
    let path = common::write_scenario(
        "min_cycle_timeline",
        PROGRAM,
        "cpu = \"speed7\"\nmin_cycle = \"2ms\"\nrun = { cycles = 3 }\n",
    );
    let svg = path.with_file_name("run.svg");
    let options = RunOptions {
        scenario: Some(path),
        timeline: Some(svg.clone()),
        ..RunOptions::default()
    };
    common::ran(runner::run(&options));
    let picture = std::fs::read_to_string(svg).unwrap();
    let waits = picture.matches(r#"class="cycle-wait""#).count();
    assert_eq!(waits, 3, "one wait per cycle");
    assert!(
        picture.contains("wait for the minimum cycle time, "),
        "the wait's title"
    );
    assert!(picture.contains(">wait</text>"), "the wait's label");
}

/// Every error of a scenario, rendered.
fn errors(cpu: &str, program: &str, scenario: &str) -> String {
    let scenario = format!("cpu = \"{cpu}\"\nrun = {{ cycles = 1 }}\n{scenario}");
    match common::run_scenario(&format!("min_cycle_errors_{cpu}"), program, &scenario) {
        Err(NotRun::Failed(reports)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        Err(NotRun::SourceErrors(..) | NotRun::Usage(_)) => panic!("not a scenario error"),
        Ok(_) => panic!("{scenario}: the scenario ran"),
    }
}

#[test]
fn a_step_5_cpu_has_no_minimum_cycle_time() {
    let program = "OB 1\n      L  FW 10\n      T  FW 10\n      BE\n";
    let text = errors("s5-115u-944", program, "min_cycle = \"10ms\"\n");
    assert!(
        text.contains("the s5-115u-944 CPU has no minimum cycle time"),
        "{text}"
    );
    assert!(text.contains("S7 CPU's hardware configuration"), "{text}");
    assert!(
        text.contains("S7 profiles:") && text.contains("speed7"),
        "{text}"
    );
}

#[test]
fn the_minimum_is_above_zero_and_below_the_watchdog() {
    for scenario in [
        "min_cycle = \"0ms\"\n",
        "min_cycle = \"150ms\"\n",
        "watchdog = \"20ms\"\nmin_cycle = \"30ms\"\n",
    ] {
        let text = errors("speed7", PROGRAM, scenario);
        assert!(
            text.contains("must be above 0 and below the watchdog"),
            "{text}"
        );
    }
    let text = errors("speed7", PROGRAM, "min_cycle = 10\n");
    assert!(text.contains("`min_cycle` takes a duration"), "{text}");
    let text = errors("speed7", PROGRAM, "min_cylce = \"10ms\"\n");
    assert!(text.contains("did you mean `min_cycle`?"), "{text}");
}

/// Runs an awlsim project with `config` as its CPU configuration's attributes.
fn project_run(config: &str) -> awl::runner::Ran {
    let project = format!(
        "<awlsim_project format_version=\"1\"><cpu><config {config}/></cpu>\
         <language_awl><source name=\"OB 1\" type=\"0\"><![CDATA[\n{PROGRAM}]]></source>\
         </language_awl></awlsim_project>"
    );
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awlpro"), project.into_bytes());
    common::ran(runner::run(&RunOptions {
        files: vec![PathBuf::from("p.awlpro")],
        store: Files::Memory(Arc::new(files)),
        limit: Some(awl::vm::cycle::RunLimit::Cycles(4)),
        ..RunOptions::default()
    }))
}

#[test]
fn an_awlsim_project_s_cycle_time_target_is_the_minimum() {
    let ran = project_run("cycle_time_target_us=\"3000\"");
    assert_eq!(ran.cpu.engine.config.min_cycle_ns, 3_000_000);
    assert!(ran.cpu.cycle_times.min_ns >= 3_000_000);
    // At most half the cycle time limit, as awlsim holds it.
    let ran = project_run("cycle_time_limit_us=\"4000\" cycle_time_target_us=\"3000\"");
    assert_eq!(ran.cpu.engine.config.min_cycle_ns, 2_000_000);
    let ran = project_run("cycle_time_target_us=\"0\"");
    assert_eq!(ran.cpu.engine.config.min_cycle_ns, 0);
}
