//! An awlsim project's CPU settings as a run takes them, and the command line's and the
//! scenario's over them.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::profile;
use awl::runner::{self, NotRun, Prepared, RunOptions};
use awl::source::Files;
use awl::vm::cycle::RunLimit;

const PROJECT: &str = r#"<awlsim_project format_version="1">
  <cpu>
    <specs nr_accus="4" nr_inputs="512" nr_outputs="512" nr_localbytes="512" />
    <config clock_memory_byte="100" ob_startinfo_enable="0" mnemonics="2"
            cycle_time_limit_us="5000" run_time_limit_us="3000" />
  </cpu>
  <language_awl>
    <source name="OB 1" type="0"><![CDATA[
ORGANIZATION_BLOCK OB 1
BEGIN
      U     E 0.0;
      =     A 4.0;
END_ORGANIZATION_BLOCK
]]></source>
  </language_awl>
</awlsim_project>
"#;

fn prepared(scenario: Option<&str>, options: RunOptions) -> Prepared {
    prepared_project(PROJECT, scenario, options)
}

fn prepared_project(project: &str, scenario: Option<&str>, options: RunOptions) -> Prepared {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awlpro"), project.as_bytes().to_vec());
    if let Some(text) = scenario {
        files.insert(PathBuf::from("s.toml"), text.as_bytes().to_vec());
    }
    let options = RunOptions {
        files: vec![PathBuf::from("p.awlpro")],
        scenario: scenario.map(|_| PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..options
    };
    match runner::prepare(&options) {
        Ok(prepared) => prepared,
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

#[test]
fn the_project_sets_what_nothing_else_does() {
    let run = prepared(None, RunOptions::default());
    let cpu = &run.cpu;
    let profile = cpu.program.profile;
    assert_eq!(profile.name, "speed7");
    assert_eq!((profile.accumulators, profile.sizes.image_bytes), (4, 512));
    assert_eq!(cpu.clock_memory, Some(cpu.program.layout.flag_base() + 100));
    assert!(!cpu.writes_start_info);
    assert_eq!(cpu.local_bytes(), 512);
    assert_eq!(cpu.engine.config.watchdog_ns, 5_000_000);
    assert_eq!(run.limit, RunLimit::Duration(3_000_000));
    assert!(run.limit_given);
}

#[test]
fn the_command_line_and_the_scenario_win() {
    let speed7 = profile::find("speed7");
    let run = prepared(
        Some("clock_memory = 20\nwatchdog = \"2ms\"\nrun = { cycles = 3 }\n"),
        RunOptions {
            cpu: speed7,
            ..RunOptions::default()
        },
    );
    let cpu = &run.cpu;
    assert_eq!(cpu.program.profile.accumulators, 2);
    assert_eq!(
        cpu.program.profile.sizes.image_bytes,
        speed7.unwrap().sizes.image_bytes
    );
    assert_eq!(cpu.clock_memory, Some(cpu.program.layout.flag_base() + 20));
    assert_eq!(cpu.engine.config.watchdog_ns, 2_000_000);
    assert_eq!(run.limit, RunLimit::Cycles(3));
}

#[test]
fn an_ob_whose_local_data_do_not_fit_the_project_s_l_stack_stops_the_cpu() {
    // OB 1's 40 bytes of temporaries do not fit the project's 32-byte L stack: the CPU stops
    // as OB 1 would start, before its first operation.
    let project = PROJECT
        .replace("nr_localbytes=\"512\"", "nr_localbytes=\"32\"")
        .replace(
            "BEGIN\n      U     E 0.0;",
            "VAR_TEMP\n  big : ARRAY [1 .. 40] OF BYTE;\nEND_VAR\nBEGIN\n      U     E 0.0;",
        );
    let ran = prepared_project(&project, None, RunOptions::default()).run(&mut |_| true);
    let stop = ran.outcome.stop.as_ref().expect("a STOP");
    assert_eq!(stop.cause.code(), "LSTACK");
    assert_eq!(ran.cpu.instructions, 0, "OB 1 did not run");
    let report = awl::diagnostics::render_plain(&runner::stop_report(&ran, stop));
    assert!(
        report.contains("the local data of OB 1 need 40 bytes of the L stack, which has 32"),
        "{report}"
    );
    assert!(report.contains("OB 1 starts here"), "{report}");
    // Without `nr_localbytes`, awlsim's 1024 bytes.
    let project = PROJECT.replace(" nr_localbytes=\"512\"", "");
    let run = prepared_project(&project, None, RunOptions::default());
    assert_eq!(run.cpu.local_bytes(), 1024);
}
