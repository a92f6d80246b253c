//! `--trace-format chrome`: the trace-event JSON Perfetto and chrome://tracing open. It loads
//! into the format's schema, its slices nest on every thread, every flow has both ends, and a
//! small run's trace is kept as a snapshot.

use std::collections::{BTreeMap, BTreeSet};
use std::path::PathBuf;

use awl::runner::{self, RunOptions};
use awl::trace::TraceFormat;
use serde::Deserialize;

mod common;

/// The trace-event format's fields (an unknown one is an error).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct TraceEvent {
    name: String,
    ph: String,
    ts: f64,
    dur: Option<f64>,
    pid: u32,
    tid: u32,
    cat: Option<String>,
    id: Option<u64>,
    s: Option<String>,
    bp: Option<String>,
    args: Option<serde_json::Value>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "camelCase")]
struct TraceFile {
    display_time_unit: String,
    trace_events: Vec<TraceEvent>,
}

fn chrome_trace(name: &str, options: RunOptions) -> String {
    let path: PathBuf =
        std::env::temp_dir().join(format!("awl-chrome-{}-{name}.json", std::process::id()));
    let options = RunOptions {
        trace: Some(path.clone()),
        trace_format: Some(TraceFormat::Chrome),
        ..options
    };
    runner::run(&options).unwrap_or_else(|_| panic!("{name} runs"));
    let text = std::fs::read_to_string(&path).expect("the trace was written");
    let _ = std::fs::remove_file(path);
    text
}

/// Checks the schema's rules awl relies on; the parsed file.
fn checked(text: &str) -> TraceFile {
    let file: TraceFile = serde_json::from_str(text).expect("the trace-event schema");
    assert_eq!(file.display_time_unit, "ns");
    let mut starts = BTreeSet::new();
    let mut ends = BTreeSet::new();
    // In whole nanoseconds, as Perfetto reads them.
    let ns = |micros: f64| (micros * 1000.0).round() as i64;
    let mut slices: BTreeMap<u32, Vec<(i64, i64)>> = BTreeMap::new();
    for event in &file.trace_events {
        assert_eq!(event.pid, 1);
        assert!(event.ts >= 0.0);
        match event.ph.as_str() {
            "M" => assert!(event.args.is_some(), "{event:?}"),
            "X" => {
                let dur = event.dur.expect("a complete slice has a duration");
                assert!(dur >= 0.0 && event.cat.is_some(), "{event:?}");
                let start = ns(event.ts);
                slices
                    .entry(event.tid)
                    .or_default()
                    .push((start, start + ns(dur)));
            }
            "i" => assert!(matches!(event.s.as_deref(), Some("t" | "g")), "{event:?}"),
            "s" => assert!(starts.insert(event.id.expect("a flow has an id"))),
            "f" => {
                assert_eq!(event.bp.as_deref(), Some("e"));
                assert!(ends.insert(event.id.expect("a flow has an id")));
            }
            "C" => assert!(event.args.as_ref().is_some_and(|a| a["value"].is_number())),
            other => panic!("unexpected phase {other} in {event:?}"),
        }
        assert!(!event.name.is_empty());
    }
    assert_eq!(starts, ends, "every flow has both ends");
    for (tid, mut spans) in slices {
        // Nested or apart, never half over each other (longest first at equal starts).
        spans.sort_by_key(|&(start, end)| (start, std::cmp::Reverse(end)));
        let mut open: Vec<i64> = Vec::new();
        for (start, end) in spans {
            while open.last().is_some_and(|top| *top <= start) {
                open.pop();
            }
            if let Some(top) = open.last() {
                assert!(end <= *top, "thread {tid}: {start}..{end} ns crosses {top}");
            }
            open.push(end);
        }
    }
    file
}

#[test]
fn a_small_run_s_chrome_trace() {
    let text = chrome_trace(
        "fig5_2",
        RunOptions {
            scenario: Some("programs/fig5_2_interrupt.toml".into()),
            ..RunOptions::default()
        },
    );
    checked(&text);
    insta::assert_snapshot!(text);
}

#[test]
fn every_sample_s_chrome_trace_keeps_to_the_schema() {
    for scenario in common::sample_scenarios() {
        let name = scenario.file_stem().unwrap().to_string_lossy().to_string();
        let text = chrome_trace(
            &name,
            RunOptions {
                scenario: Some(scenario),
                ..RunOptions::default()
            },
        );
        let file = checked(&text);
        assert!(file.trace_events.iter().any(|e| e.ph == "X"), "{name}");
    }
}

#[test]
fn watched_values_inputs_and_outputs_are_counters() {
    let text = chrome_trace(
        "counters",
        RunOptions {
            scenario: Some("programs/two_motors.toml".into()),
            watch: vec!["QB 4".into()],
            ..RunOptions::default()
        },
    );
    let file = checked(&text);
    let counters: BTreeSet<&str> = file
        .trace_events
        .iter()
        .filter(|event| event.ph == "C")
        .map(|event| event.name.as_str())
        .collect();
    assert!(counters.contains("QB 4"), "{counters:?}");
    assert!(
        counters.iter().any(|name| name.starts_with("I ")),
        "{counters:?}"
    );
    assert!(
        counters.iter().any(|name| name.starts_with("Q ")),
        "{counters:?}"
    );
}

#[test]
fn a_window_clips_the_slices() {
    let text = chrome_trace(
        "window",
        RunOptions {
            scenario: Some("programs/fig5_2_interrupt.toml".into()),
            from_ns: Some(30_000),
            to_ns: Some(60_000),
            ..RunOptions::default()
        },
    );
    let file = checked(&text);
    for event in file.trace_events.iter().filter(|e| e.ph != "M") {
        let end = event.ts + event.dur.unwrap_or(0.0);
        assert!(event.ts >= 30.0 && end <= 60.0 + 1e-9, "{event:?}");
    }
}
