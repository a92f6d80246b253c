//! Nothing silent: `awl run --trace FILE` and `--timeline FILE` end with one line on standard
//! error saying what was written where, with its events and size.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("awl-written-{}-{name}", std::process::id()))
}

/// Runs the Fig. 5.2 interrupt scenario with `outputs`; whether it succeeded, and its stderr.
fn run_fig5_2<I: AsRef<OsStr>>(outputs: impl IntoIterator<Item = I>) -> (bool, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["run", "--scenario", "programs/fig5_2_interrupt.toml"])
        .args(outputs)
        .output()
        .expect("awl runs");
    let stderr = String::from_utf8(output.stderr).expect("UTF-8");
    (output.status.success(), stderr)
}

/// The lines of a file and its size in bytes.
fn lines_and_bytes(path: &Path) -> (usize, u64) {
    let text = std::fs::read_to_string(path).expect("the file written");
    (text.lines().count(), text.len() as u64)
}

#[test]
fn a_trace_and_a_timeline_each_end_with_what_was_written_where() {
    let (trace, picture) = (temp("run.jsonl"), temp("run.svg"));
    let (ok, stderr) = run_fig5_2([
        OsStr::new("--trace"),
        trace.as_os_str(),
        OsStr::new("--timeline"),
        picture.as_os_str(),
    ]);
    assert!(ok);
    let (events, trace_bytes) = lines_and_bytes(&trace);
    let (_, picture_bytes) = lines_and_bytes(&picture);
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(
        lines[lines.len() - 2..],
        [
            format!(
                "trace: {events} events written to {} ({:.1} KiB)",
                trace.display(),
                trace_bytes as f64 / 1024.0
            ),
            format!(
                "timeline: {events} events written to {} ({:.1} KiB)",
                picture.display(),
                picture_bytes as f64 / 1024.0
            ),
        ],
        "{stderr}"
    );
    let _ = std::fs::remove_file(trace);
    let _ = std::fs::remove_file(picture);
}

#[test]
fn a_filtered_trace_counts_the_events_it_holds() {
    let trace = temp("interrupts.jsonl");
    let (_, stderr) = run_fig5_2([
        OsStr::new("--trace-filter"),
        OsStr::new("interrupts"),
        OsStr::new("--trace"),
        trace.as_os_str(),
    ]);
    let (events, bytes) = lines_and_bytes(&trace);
    assert!(bytes < 1024);
    assert_eq!(
        stderr.lines().last(),
        Some(
            format!(
                "trace: {events} events written to {} ({bytes} bytes)",
                trace.display()
            )
            .as_str()
        )
    );
    let _ = std::fs::remove_file(trace);
}

#[test]
fn a_trace_on_standard_output_adds_no_line() {
    let (_, stderr) = run_fig5_2(["--trace", "-"]);
    assert!(!stderr.contains("written to"), "{stderr}");
}
