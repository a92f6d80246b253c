//! Output that cannot be written: a full disk is one line and exit 1, a closed pipe ends
//! quietly with the command's own exit code; never a panic (exit 101).

use std::fs::File;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

const AWL: &str = env!("CARGO_BIN_EXE_awl");

fn full() -> Stdio {
    Stdio::from(File::options().write(true).open("/dev/full").unwrap())
}

/// Runs `awl args` with standard output (or standard error) on /dev/full.
fn on_full_disk(args: &[&str], stderr_full: bool) -> (i32, String) {
    let mut command = Command::new(AWL);
    command.args(args);
    if stderr_full {
        command.stdout(Stdio::null()).stderr(full());
    } else {
        command.stdout(full()).stderr(Stdio::piped());
    }
    let output = command.output().unwrap();
    (
        output.status.code().unwrap(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn a_full_stdout_is_one_line_and_exit_1() {
    let commands: [&[&str]; 5] = [
        &["cpus"],
        &["check", "programs/fig5_2.awl"],
        &["dump", "programs/fig5_2.awl"],
        &["run", "programs/fig5_2.awl", "--cycles", "1"],
        &["test", "programs/fig5_2.toml"],
    ];
    for args in commands {
        let (code, stderr) = on_full_disk(args, false);
        assert_eq!(code, 1, "{args:?}: {stderr}");
        assert_eq!(
            stderr, "awl: cannot write to standard output: No space left on device (os error 28)\n",
            "{args:?}"
        );
    }
}

#[test]
fn a_full_stderr_does_not_panic() {
    let commands: [&[&str]; 3] = [
        &["check", "tests/cmd/bad.awl"],
        &["run", "tests/cmd/bad.awl"],
        &["run", "programs/weck.awl", "--cpu", "s5-95f"],
    ];
    for args in commands {
        let (code, _) = on_full_disk(args, true);
        assert_eq!(code, 1, "{args:?}");
    }
}

/// `awl … | head -1`: reads one line, closes the pipe, and waits for the exit.
fn first_line_then_close(args: &[&str]) -> (String, i32, String) {
    let mut child = Command::new(AWL)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let output = child.wait_with_output().unwrap();
    (
        line,
        output.status.code().unwrap(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn a_closed_pipe_ends_quietly() {
    // A dump long enough not to fit in the pipe's buffer: awl is still writing when it closes.
    let dir = std::path::Path::new("target/test-output");
    std::fs::create_dir_all(dir).unwrap();
    let big = dir.join("big.awl");
    let block = "      A  I 0.0\n      =  Q 4.0\n".repeat(400);
    let text: String = (0..=255)
        .map(|n| format!("PB {n}\n{block}      BE\n"))
        .collect();
    std::fs::write(&big, text).unwrap();
    let (line, code, stderr) = first_line_then_close(&["dump", big.to_str().unwrap()]);
    assert!(line.starts_with("PB 0"), "{line}");
    assert_eq!((code, stderr.as_str()), (0, ""));

    let (line, code, stderr) = first_line_then_close(&[
        "run",
        "programs/fig5_2.awl",
        "--for",
        "2s",
        "--trace",
        "-",
        "--trace-format",
        "text",
    ]);
    assert!(line.contains("mode STOP → STARTUP"), "{line}");
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("cpu: sinumerik-840c"),
        "the summary still goes to standard error: {stderr}"
    );
    assert!(!stderr.contains("trace_incomplete"), "{stderr}");
}
