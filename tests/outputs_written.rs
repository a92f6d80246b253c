//! Nothing silent: `awl run --trace FILE` and `--timeline FILE` end with one line on standard
//! error saying what was written where, with its events and size.

use std::path::PathBuf;
use std::process::Command;

fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("awl-written-{}-{name}", std::process::id()))
}

#[test]
fn a_trace_and_a_timeline_each_end_with_what_was_written_where() {
    let (trace, picture) = (temp("run.jsonl"), temp("run.svg"));
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args([
            "run",
            "--scenario",
            "programs/fig5_2_interrupt.toml",
            "--trace",
        ])
        .arg(&trace)
        .arg("--timeline")
        .arg(&picture)
        .output()
        .expect("awl runs");
    assert!(output.status.success());
    let stderr = String::from_utf8(output.stderr).expect("UTF-8");
    let events = std::fs::read_to_string(&trace)
        .expect("the trace")
        .lines()
        .count();
    let trace_bytes = std::fs::metadata(&trace).expect("the trace").len();
    let picture_bytes = std::fs::metadata(&picture).expect("the picture").len();
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
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["run", "--scenario", "programs/fig5_2_interrupt.toml"])
        .args(["--trace-filter", "interrupts", "--trace"])
        .arg(&trace)
        .output()
        .expect("awl runs");
    let stderr = String::from_utf8(output.stderr).expect("UTF-8");
    let events = std::fs::read_to_string(&trace)
        .expect("the trace")
        .lines()
        .count();
    let bytes = std::fs::metadata(&trace).expect("the trace").len();
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
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args([
            "run",
            "--scenario",
            "programs/fig5_2_interrupt.toml",
            "--trace",
            "-",
        ])
        .output()
        .expect("awl runs");
    let stderr = String::from_utf8(output.stderr).expect("UTF-8");
    assert!(!stderr.contains("written to"), "{stderr}");
}
