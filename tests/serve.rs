//! `awl serve` with real clients: python-snap7 and pymodbus (in the environment
//! tests/common/python.rs makes under target/, or the Python at `AWL_PYTHON`) talk to the binary
//! on 127.0.0.1, on ports the system picks. Where the clients cannot be had, the tests that need
//! them fail, naming the command that installs them.

mod common;

use std::io::Read;
use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const AWL: &str = env!("CARGO_BIN_EXE_awl");

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The Python with both clients.
fn python() -> PathBuf {
    common::python::with("snap7, pymodbus")
}

/// A running `awl serve` and the ports it printed.
struct Served {
    child: Child,
    s7: u16,
    modbus: u16,
    stdout: mpsc::Receiver<String>,
}

/// Starts `awl serve ARGS --s7 127.0.0.1:0 --modbus 127.0.0.1:0` and waits for its listening
/// lines.
fn serve(args: &[&str]) -> Served {
    let mut child = Command::new(AWL)
        .arg("serve")
        .args(args)
        .args(["--s7", "127.0.0.1:0", "--modbus", "127.0.0.1:0"])
        .current_dir(repo("."))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("awl starts");
    let stdout = common::lines(child.stdout.take().expect("piped"));
    let (mut s7, mut modbus) = (0, 0);
    let deadline = Instant::now() + Duration::from_secs(60);
    while s7 == 0 || modbus == 0 {
        let line = common::next_line(&mut child, &stdout, deadline, "listening lines");
        let port = || {
            line.rsplit(':')
                .next()
                .and_then(|port| port.trim().parse().ok())
                .unwrap_or(0)
        };
        if line.starts_with("S7 server listening on ") {
            s7 = port();
        } else if line.starts_with("Modbus TCP server listening on ") {
            modbus = port();
        }
    }
    Served {
        child,
        s7,
        modbus,
        stdout,
    }
}

impl Served {
    /// Runs a client script of tests/clients with the two ports; it must succeed.
    fn client(&self, python: &Path, script: &str) {
        self.client_with(python, script, &[]);
    }

    /// [`Served::client`] with more arguments after the ports.
    fn client_with(&self, python: &Path, script: &str, more: &[String]) {
        let output = common::python::command(python)
            .arg(repo("tests/clients").join(script))
            .args([self.s7.to_string(), self.modbus.to_string()])
            .args(more)
            .output()
            .expect("python runs");
        assert!(
            output.status.success(),
            "{script} failed:\n{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
    }

    /// Ends the serve with SIGTERM, as a service manager does; its exit status and output.
    fn terminate(self) -> (Option<i32>, String, String) {
        let pid = self.child.id().to_string();
        let sent = Command::new("kill").args(["-TERM", &pid]).status();
        assert!(sent.is_ok_and(|status| status.success()), "kill -TERM");
        self.finish()
    }

    /// Waits for the serve to end by itself (at most a minute).
    fn finish(mut self) -> (Option<i32>, String, String) {
        let deadline = Instant::now() + Duration::from_secs(60);
        let status = loop {
            if let Some(status) = self.child.try_wait().expect("waits") {
                break status;
            }
            if Instant::now() > deadline {
                let _ = self.child.kill();
                panic!("awl serve did not end");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut stderr = String::new();
        let _ = self
            .child
            .stderr
            .take()
            .map(|mut err| err.read_to_string(&mut stderr));
        // The reader ends at the end of the output, which the exit has brought.
        let stdout: Vec<String> = self.stdout.iter().collect();
        (status.code(), stdout.join("\n"), stderr)
    }
}

#[test]
fn an_s7_program_on_speed7_is_read_written_stopped_and_restarted() {
    let python = python();
    let served = serve(&["programs/s7/tank_hmi.awl", "--cpu", "speed7"]);
    served.client(&python, "serve_speed7.py");
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("served: "), "{stdout}");
    assert!(stdout.contains("mode at end: RUN"), "{stdout}");
}

#[test]
fn an_s5_program_on_an_s5_115u_is_read_written_stopped_and_restarted() {
    let python = python();
    let served = serve(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    served.client(&python, "serve_s5.py");
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn a_forced_input_beats_a_client_s_write_and_a_forced_output_is_what_it_reads() {
    let python = python();
    let served = serve(&["programs/s7/tank_hmi.awl", "--http", "127.0.0.1:0"]);
    let deadline = Instant::now() + Duration::from_secs(60);
    let http = loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let line = served.stdout.recv_timeout(left).expect("the online line");
        if let Some(address) = line.strip_prefix("Online page at http://127.0.0.1:") {
            break address.trim_end_matches('/').to_string();
        }
    };
    served.client_with(&python, "online_force.py", &[http]);
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn eight_clients_at_once_get_every_value_right() {
    let python = python();
    let served = serve(&["programs/s7/tank_hmi.awl"]);
    served.client(&python, "serve_eight_clients.py");
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("over 9 connections"), "{stdout}");
}

#[test]
fn malformed_packets_are_refused_and_working_clients_served_after_them() {
    let python = python();
    let served = serve(&["programs/s7/tank_hmi.awl"]);
    served.client(&python, "serve_malformed.py");
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("mode at end: RUN"), "{stdout}");
}

#[test]
fn read_only_serves_reads_and_refuses_writes_and_control() {
    let python = python();
    let served = serve(&["programs/s7/tank_hmi.awl", "--read-only"]);
    served.client(&python, "serve_read_only.py");
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn a_client_s_input_write_raises_ob_40_and_the_trace_shows_both() {
    let python = python();
    let trace = std::env::temp_dir().join(format!("awl-serve-{}.jsonl", std::process::id()));
    let trace_arg = trace.display().to_string();
    let timeline = trace.with_extension("svg");
    let timeline_arg = timeline.display().to_string();
    let served = serve(&[
        "--scenario",
        "tests/inputs/serve/tank_alarm.toml",
        "--trace",
        &trace_arg,
        "--trace-format",
        "jsonl",
        "--timeline",
        &timeline_arg,
    ]);
    served.client(&python, "serve_interrupt_input.py");
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    let trace = std::fs::read_to_string(&trace).expect("the trace is written");
    common::assert_write_raises(&trace, "IB 8", 40);
    let picture = std::fs::read_to_string(&timeline).expect("the timeline is drawn");
    assert!(
        picture.contains("class=\"client-write\""),
        "the writes on the timeline"
    );
    assert!(picture.contains("s7 #1"), "named by their client");
}

#[test]
fn sigterm_ends_the_serve_with_the_summary_and_the_state() {
    let served = serve(&[
        "programs/tank_hmi_115u.awl",
        "--cpu",
        "s5-115u-944",
        "--state",
    ]);
    std::thread::sleep(Duration::from_millis(300));
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("cycle time min/mean/max"), "{stdout}");
    assert!(stdout.contains("served: 0 requests"), "{stdout}");
    assert!(stdout.contains("state at the end: mode RUN"), "{stdout}");
}

#[test]
fn the_run_length_ends_the_serve_no_sooner_than_the_wall_clock() {
    let started = Instant::now();
    let served = serve(&["programs/s7/tank_hmi.awl", "--for", "300ms"]);
    let (code, stdout, stderr) = served.finish();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        started.elapsed() >= Duration::from_millis(300),
        "paced to the clock"
    );
    assert!(stdout.contains("cycles started late by"), "{stdout}");
    let started = Instant::now();
    let faster = serve(&["programs/s7/tank_hmi.awl", "--for", "1s", "--speed", "10"]);
    let (code, _, stderr) = faster.finish();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        started.elapsed() >= Duration::from_millis(100),
        "one tenth of the clock"
    );
}

#[test]
fn a_port_in_use_is_one_error_that_names_a_free_alternative() {
    let taken = TcpListener::bind("127.0.0.1:0").expect("a free port");
    let port = taken.local_addr().expect("bound").port();
    let output: Output = Command::new(AWL)
        .args(["serve", "programs/s7/tank_hmi.awl", "--s7"])
        .arg(format!("127.0.0.1:{port}"))
        .current_dir(repo("."))
        .output()
        .expect("awl runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("awl::serve::bind"), "{stderr}");
    assert!(stderr.contains("--s7 127.0.0.1:1102"), "{stderr}");
    assert!(stderr.contains("tcp_port=1102"), "{stderr}");
    assert!(output.stdout.is_empty(), "no listening line");
}

#[test]
fn the_readme_s_snippets_run_as_printed() {
    let python = python();
    let served = serve(&["--scenario", "programs/s7/tank_hmi_serve.toml"]);
    for (name, printed) in [("s7", "300\n1\n0\n1\nTrue\n"), ("modbus", "[300]\nFalse\n")] {
        // The README serves on ports 1102 and 1502; here the system picked them.
        let snippet = common::readme_snippet(name)
            .replace("1102", &served.s7.to_string())
            .replace("1502", &served.modbus.to_string());
        let output = common::python::command(&python)
            .args(["-c", &snippet])
            .output()
            .expect("python runs");
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        assert_eq!(
            String::from_utf8_lossy(&output.stdout),
            printed,
            "the {name} snippet"
        );
    }
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn on_a_terminal_one_status_line_shows_the_mode_and_ctrl_c_ends_the_serve() {
    let mut command = Command::new(AWL);
    command
        .args(["serve", "programs/s7/tank_hmi.awl", "--s7", "127.0.0.1:0"])
        .current_dir(repo("."));
    let mut session = rexpect::session::spawn_command(command, Some(30_000)).expect("a pty");
    session
        .exp_string("S7 server listening on 127.0.0.1:")
        .expect("listening");
    session.exp_string("RUN  cycle ").expect("the status line");
    session.exp_string("0 clients").expect("the clients");
    session
        .exp_string("requests/s  (s Enter: snapshot, Ctrl-C ends)")
        .expect("the requests");
    session.send_control('c').expect("Ctrl-C");
    session
        .exp_string("served: 0 requests")
        .expect("the summary");
    session.exp_eof().expect("the end");
    match session.process().wait().expect("waits") {
        rexpect::process::WaitStatus::Exited(_, code) => assert_eq!(code, 0),
        other => panic!("not a normal exit: {other:?}"),
    }
}
