//! The debugger on a terminal: a line-editing prompt, commands typed one by one, Ctrl-C that
//! pauses a long `continue`, and a clean end on `quit`.

use std::process::Command;

use rexpect::process::WaitStatus;
use rexpect::session::PtySession;

const AWL: &str = env!("CARGO_BIN_EXE_awl");

fn debug(args: &[&str]) -> PtySession {
    let mut command = Command::new(AWL);
    command.arg("debug").args(args);
    rexpect::session::spawn_command(command, Some(30_000)).unwrap()
}

#[test]
fn a_session_at_the_prompt() {
    let mut session = debug(&["programs/conveyor.awl"]);
    session.exp_string("[start] OB 1 line 7").unwrap();
    session.exp_string("(awl) ").unwrap();
    session.send_line("step").unwrap();
    session.exp_string("[step] PB 1 line 12").unwrap();
    session.exp_string("(awl) ").unwrap();
    // An empty line repeats the last step.
    session.send_line("").unwrap();
    session.exp_string("[step] PB 1 line 13").unwrap();
    session.send_line("set I 0.0 1").unwrap();
    session.exp_string("I 0.0 = 1").unwrap();
    session.send_line("break PB 2").unwrap();
    session.exp_string("breakpoint 1: PB 2 line 19").unwrap();
    session.send_line("c").unwrap();
    session
        .exp_string("[breakpoint 1] PB 2 line 19, cycle 1")
        .unwrap();
    session.send_line("print F 20.0").unwrap();
    session.exp_string("F 20.0 = 0").unwrap();
    session.send_line("quit").unwrap();
    assert_exits_with(&session, 0);
}

#[test]
fn ctrl_c_pauses_a_long_continue() {
    let mut session = debug(&["programs/conveyor.awl", "--for", "36000s"]);
    session.exp_string("(awl) ").unwrap();
    session.send_line("continue").unwrap();
    std::thread::sleep(std::time::Duration::from_millis(500));
    session.send_control('c').unwrap();
    session.exp_string("[interrupted]").unwrap();
    session.exp_string("(awl) ").unwrap();
    session.send_line("quit").unwrap();
    assert_exits_with(&session, 0);
}

fn assert_exits_with(session: &PtySession, code: i32) {
    match session.process().wait().unwrap() {
        WaitStatus::Exited(_, exited) => assert_eq!(exited, code),
        other => panic!("{other:?}"),
    }
}
