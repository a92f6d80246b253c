//! Long runs on a terminal: a progress line after about a second, and Ctrl-C or SIGTERM halting
//! at the next cycle boundary with a finished trace, the summary and exit code 130.

use std::path::PathBuf;
use std::process::Command;

use rexpect::process::{Signal, WaitStatus};
use rexpect::session::PtySession;

const AWL: &str = env!("CARGO_BIN_EXE_awl");

/// `awl run` of an hour of simulated time, on a terminal.
fn endless_run(trace: &PathBuf) -> PtySession {
    let mut command = Command::new(AWL);
    command.args(["run", "programs/fig5_2.awl", "--for", "3600s", "--trace"]);
    command.arg(trace);
    rexpect::session::spawn_command(command, Some(30_000)).unwrap()
}

fn trace_path(name: &str) -> PathBuf {
    let dir = PathBuf::from("target/test-long-runs");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Every line of the trace is a whole JSON object, the last one included.
fn assert_whole_lines(trace: &PathBuf) {
    let text = std::fs::read_to_string(trace).unwrap();
    assert!(text.ends_with('\n'), "the last line is finished");
    for line in text.lines() {
        serde_json::from_str::<serde_json::Value>(line)
            .unwrap_or_else(|error| panic!("torn line {line:?}: {error}"));
    }
    assert!(text.lines().count() > 100);
}

fn halted_with_summary(mut session: PtySession) {
    session
        .exp_string("halted: interrupted (Ctrl-C or SIGTERM) at the cycle boundary")
        .unwrap();
    session.exp_string("cpu: sinumerik-840c").unwrap();
    session.exp_string("instructions:").unwrap();
    session.exp_eof().unwrap();
    match session.process().wait().unwrap() {
        WaitStatus::Exited(_, code) => assert_eq!(code, 130),
        other => panic!("not a normal exit: {other:?}"),
    }
}

#[test]
fn ctrl_c_halts_after_showing_progress() {
    let trace = trace_path("ctrl_c.jsonl");
    let mut session = endless_run(&trace);
    session.exp_string("running: simulated").unwrap();
    session.exp_string("M instr/s").unwrap();
    session.send_control('c').unwrap();
    halted_with_summary(session);
    assert_whole_lines(&trace);
}

#[test]
fn sigterm_halts_with_a_whole_trace() {
    let trace = trace_path("sigterm.jsonl");
    let mut session = endless_run(&trace);
    session.exp_string("running: simulated").unwrap();
    session.process_mut().signal(Signal::SIGTERM).unwrap();
    halted_with_summary(session);
    assert_whole_lines(&trace);
}

#[test]
fn a_short_run_shows_no_progress() {
    let mut command = Command::new(AWL);
    command.args(["run", "programs/fig5_2.awl", "--cycles", "3"]);
    let mut session = rexpect::session::spawn_command(command, Some(30_000)).unwrap();
    let output = session.exp_eof().unwrap();
    assert!(!output.contains("running:"), "{output}");
    assert!(output.contains("cycles: 3"), "{output}");
}
