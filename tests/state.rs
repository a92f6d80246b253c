//! The JSON state (`--state-format json`) keeps its documented schema, and watch rows reach
//! the jsonl trace as `watch` events.

use std::process::Command;

use serde_json::Value;

fn awl(args: &[&str]) -> (String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(args)
        .output()
        .expect("awl runs");
    (
        String::from_utf8(output.stdout).unwrap(),
        String::from_utf8(output.stderr).unwrap(),
    )
}

fn keys(value: &Value) -> Vec<&str> {
    let mut keys: Vec<&str> = value
        .as_object()
        .expect("an object")
        .keys()
        .map(String::as_str)
        .collect();
    keys.sort_unstable();
    keys
}

#[test]
fn json_state_has_the_documented_schema() {
    let (stdout, stderr) = awl(&[
        "run",
        "--scenario",
        "tests/scenarios/istack.toml",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).expect("stdout is the JSON alone");
    assert!(
        stderr.contains("mode at end: STOP"),
        "the summary went to stderr"
    );
    assert_eq!(
        keys(&state),
        [
            "accu",
            "counters",
            "data_blocks",
            "images",
            "levels",
            "mode",
            "open_db",
            "status",
            "timers"
        ]
    );
    assert_eq!(state["mode"], "STOP");
    assert_eq!(
        state["accu"].as_array().unwrap().len(),
        4,
        "the 840C has four"
    );
    assert_eq!(
        keys(&state["status"]),
        ["cc0", "cc1", "first_check", "or", "os", "ov", "rlo", "sta"]
    );
    assert_eq!(keys(&state["images"]), ["F", "I", "Q"]);
    assert_eq!(state["data_blocks"]["DB 10"]["0"], 42);
    let levels = state["levels"].as_array().unwrap();
    assert_eq!(
        levels.len(),
        2,
        "OB 3 running, PB 3 of OB 1's level interrupted"
    );
    assert_eq!(levels[0]["block"], "OB 3");
    assert_eq!(levels[1]["open_db"], 10);
    assert_eq!(levels[1]["return_points"][0]["block"], "OB 1");
}

#[test]
fn a_run_without_stop_has_no_levels_and_shows_timers_and_counters() {
    let (stdout, _) = awl(&[
        "run",
        "programs/traffic_light.awl",
        "--for",
        "6.5s",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).unwrap();
    assert!(state.get("levels").is_none());
    assert_eq!(state["mode"], "RUN");
    assert_eq!(state["images"]["Q"]["4"], 4, "green lamp Q 4.2");
    let counter = &state["counters"][0];
    assert_eq!(
        (counter["number"].as_u64(), counter["value"].as_u64()),
        (Some(1), Some(1))
    );
    let running: Vec<u64> = state["timers"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|timer| timer["running"] == true)
        .map(|timer| timer["number"].as_u64().unwrap())
        .collect();
    assert_eq!(running, [12], "only the green phase's timer runs at 6.5 s");
}

#[test]
fn watch_rows_are_trace_events() {
    let (stdout, _) = awl(&[
        "run",
        "--scenario",
        "tests/scenarios/watch.toml",
        "--trace",
        "-",
    ]);
    let rows: Vec<Value> = stdout
        .lines()
        .map(|line| serde_json::from_str::<Value>(line).unwrap())
        .filter(|event| event["ev"] == "watch")
        .collect();
    assert_eq!(
        rows.len(),
        5,
        "the start, then each change of the lamps or C 1"
    );
    assert_eq!(rows[3]["values"]["Q 4.2"], "1");
    assert_eq!(rows[3]["values"]["C 1"], "KZ 001 (1)");
}
