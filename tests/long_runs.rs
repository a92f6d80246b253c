//! Long runs on a terminal: a progress line after about a second (never from the background),
//! and Ctrl-C or SIGTERM halting at the next cycle boundary with a finished trace, the summary
//! and exit code 130.

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

/// An interactive shell on a terminal, with job control, in the repository.
fn shell() -> rexpect::session::PtyReplSession {
    let mut shell = rexpect::spawn_bash(Some(30_000)).unwrap();
    shell.send_line("set -m").unwrap();
    shell.wait_for_prompt().unwrap();
    shell
}

#[test]
fn a_background_run_draws_nothing_and_halts_with_its_summary() {
    let mut shell = shell();
    shell
        .send_line(&format!(
            "{AWL} run programs/fig5_2.awl --for 3600s & sleep 2; kill -TERM $!; wait $!; echo EXIT=$?"
        ))
        .unwrap();
    let output = shell.exp_string("EXIT=130").unwrap();
    assert!(output.contains("halted: interrupted"), "{output}");
    assert!(output.contains("cpu: sinumerik-840c"), "{output}");
    assert!(
        !output.contains("running:"),
        "no progress line from the background: {output}"
    );
}

#[test]
fn a_run_under_timeout_on_a_terminal_ends_with_its_summary() {
    let mut shell = shell();
    shell
        .send_line(&format!(
            "timeout 2 {AWL} run programs/fig5_2.awl --cycles 100000000; echo EXIT=$?"
        ))
        .unwrap();
    let output = shell.exp_string("EXIT=124").unwrap();
    assert!(output.contains("halted: interrupted"), "{output}");
    assert!(output.contains("instructions:"), "{output}");
}

#[test]
fn the_debugger_does_not_prompt_from_the_background() {
    let mut shell = shell();
    shell
        .send_line(&format!(
            "{AWL} debug programs/fig5_2.awl & wait $!; echo EXIT=$?"
        ))
        .unwrap();
    let output = shell.exp_string("EXIT=2").unwrap();
    assert!(output.contains("awl::debug::background"), "{output}");
    assert!(output.contains("--commands"), "{output}");
}
