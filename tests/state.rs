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
fn json_state_of_a_step7_program_has_bytes_registers_and_br() {
    let (stdout, _) = awl(&[
        "run",
        "--scenario",
        "tests/inputs/s7/tank.toml",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).expect("stdout is the JSON alone");
    assert_eq!(
        keys(&state),
        [
            "accu",
            "counters",
            "data_blocks",
            "declared_data_blocks",
            "images",
            "mode",
            "open_db",
            "registers",
            "status",
            "timers"
        ]
    );
    assert_eq!(
        keys(&state["status"]),
        [
            "br",
            "cc0",
            "cc1",
            "first_check",
            "or",
            "os",
            "ov",
            "rlo",
            "sta"
        ]
    );
    assert_eq!(keys(&state["registers"]), ["ar1", "ar2", "db", "di", "stw"]);
    assert_eq!(state["registers"]["db"], 5, "DB5.DBB 2 opened DB 5 last");
    assert_eq!(state["open_db"], 5, "the DB register's DB");
    assert_eq!(
        keys(&state["images"]),
        ["I", "M", "Q"],
        "flags are M in STEP 7"
    );
    assert_eq!(state["images"]["M"]["1"], 3, "MB 1 from DB5.DBB 2");
    let db5 = &state["data_blocks"]["DB 5"];
    assert_eq!(db5["2"], 3, "DB5.DBB 2 written by the scenario");
    assert_eq!(
        (&db5["4"], &db5["5"]),
        (&0xFF.into(), &0xEC.into()),
        "DBW 4 = -20"
    );
    let real: Vec<u8> = (6..10)
        .map(|byte| db5[byte.to_string()].as_u64().unwrap_or(0) as u8)
        .collect();
    assert_eq!(
        real,
        4.0f32.to_bits().to_be_bytes(),
        "DBD 6 = 4.0, byte by byte"
    );
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

/// The lines of `--state` after its header: the images and data blocks.
fn state_lines(program: &str) -> Vec<String> {
    let (stdout, stderr) = awl(&["run", program, "--cycles", "1", "--state"]);
    assert!(stderr.is_empty(), "{stderr}");
    stdout
        .lines()
        .skip_while(|line| !line.starts_with("  open DB"))
        .skip(1)
        .map(|line| line.trim().to_string())
        .collect()
}

#[test]
fn the_state_shows_words_and_double_words_where_the_program_wrote_them_in_address_order() {
    let lines = state_lines("tests/inputs/state_widths.awl");
    assert_eq!(
        lines,
        [
            "QW 4    = KF -2 = KH FFFE",
            "FW 0    = KF +750 = KH 02EE",
            "FY 2    = KH 07 = 0000 0111",
            "FD 4    = DH 00010002 = +65538",
            "FY 10   = KH 07 = 0000 0111",
            "FY 20   = KH 07 = 0000 0111",
            "DB 2 DW 1    = KF +4 = KH 0004",
            "DB 10 DW 0    = KF +1 = KH 0001",
            "DB 10 DW 2    = KF +5 = KH 0005",
            "DB 10 DD 4    = DH 00030004 = +196612",
            "DB 10 DW 11   = KF +4 = KH 0004",
        ]
    );
}

#[test]
fn the_json_state_keeps_its_bytes_and_words() {
    let (stdout, _) = awl(&[
        "run",
        "tests/inputs/state_widths.awl",
        "--cycles",
        "1",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).expect("JSON");
    let flags = &state["images"]["F"];
    assert_eq!(
        (flags["0"].as_u64(), flags["1"].as_u64()),
        (Some(2), Some(0xEE))
    );
    assert_eq!(state["images"]["Q"]["4"].as_u64(), Some(0xFF));
    let db10 = &state["data_blocks"]["DB 10"];
    assert_eq!((db10["4"].as_u64(), db10["5"].as_u64()), (Some(3), Some(4)));
    assert!(state.get("widths").is_none());
}

#[test]
fn the_readme_s_state_examples_are_what_awl_prints() {
    let readme = std::fs::read_to_string("README.md").unwrap();
    for scenario in ["programs/mixer_de.toml", "tests/inputs/s7/tank.toml"] {
        let command =
            format!("cargo run --release -- run --scenario {scenario} --state\n```\n```\n");
        let start = readme.find(&command).expect("the README's example") + command.len();
        let shown = &readme[start..start + readme[start..].find("```").unwrap()];
        let (stdout, _) = awl(&["run", "--scenario", scenario, "--state"]);
        let state = &stdout[stdout.find("state at the end").expect("the state")..];
        assert_eq!(shown, state, "{scenario}");
    }
}

#[test]
fn an_fb_s_word_parameter_and_a_word_to_an_output_module_are_words() {
    let lines = state_lines("tests/inputs/state_widths_fb.awl");
    assert_eq!(
        lines,
        ["QW 6    = KF +300 = KH 012C", "FW 8    = KF -2 = KH FFFE"]
    );
}

/// The `--state` lines of a STEP 7 program from its first data block on.
fn step7_data_lines(program: &str) -> Vec<String> {
    let (stdout, stderr) = awl(&["run", program, "--cycles", "2", "--state"]);
    assert!(stderr.is_empty(), "{stderr}");
    stdout
        .lines()
        .skip_while(|line| !line.trim_start().starts_with("DB5."))
        .map(|line| line.trim().to_string())
        .collect()
}

#[test]
fn a_step7_data_block_shows_by_its_declaration_and_an_instance_db_by_its_fb() {
    let lines = step7_data_lines("tests/inputs/s7/state_declared.awl");
    assert_eq!(
        lines,
        [
            "DB5.setpoint      = 1234",
            "DB5.gain          = L#70000",
            "DB5.on            = TRUE",
            "DB5.ratio         = 1.5",
            "DB5.delay         = T#1S500MS",
            "DB5.pulse         = S5T#25S",
            "DB5.letter        = 'A'",
            "DB5.mask          = W#16#0063",
            "DB5.table[1]      = 0",
            "DB5.table[2]      = 7",
            "DB5.table[3]      = 0",
            "DB5.motor.speed   = 0",
            "DB5.motor.running = FALSE",
            "DB6.start = TRUE",
            "DB6.count = 2",
        ]
    );
}

#[test]
fn the_json_state_adds_the_declared_view_beside_the_bytes() {
    let (stdout, _) = awl(&[
        "run",
        "tests/inputs/s7/state_declared.awl",
        "--cycles",
        "2",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).expect("JSON");
    assert_eq!(state["data_blocks"]["DB 5"]["1"], 0xD2, "the bytes stay");
    let db5 = state["declared_data_blocks"]["DB 5"].as_array().unwrap();
    assert_eq!(keys(&db5[1]), ["address", "name", "type", "value"]);
    assert_eq!(
        (
            &db5[1]["name"],
            &db5[1]["type"],
            &db5[1]["address"],
            &db5[1]["value"]
        ),
        (
            &Value::from("gain"),
            &Value::from("DINT"),
            &Value::from("2.0"),
            &Value::from("L#70000")
        )
    );
    assert_eq!(state["declared_data_blocks"]["DB 6"][1]["value"], "2");
}

#[test]
fn a_step5_state_has_no_declared_view() {
    let (stdout, _) = awl(&[
        "run",
        "tests/inputs/state_widths.awl",
        "--cycles",
        "1",
        "--state-format",
        "json",
    ]);
    let state: Value = serde_json::from_str(&stdout).expect("JSON");
    assert!(state.get("declared_data_blocks").is_none());
}

/// The names `--state` shows for the program's memory: what stands before ` = ` on each line
/// but the registers'.
fn state_names(program: &str) -> Vec<String> {
    let (stdout, stderr) = awl(&["run", program, "--cycles", "2", "--state"]);
    assert!(stderr.is_empty(), "{stderr}");
    let registers = ["ACCU", "AR1", "AR2"];
    stdout
        .lines()
        .skip_while(|line| !line.starts_with("state at the end"))
        .skip(1)
        .filter_map(|line| line.split_once(" = "))
        .map(|(name, _)| name.trim().to_string())
        .filter(|name| !registers.iter().any(|register| name.starts_with(register)))
        .collect()
}

/// Every name `--state` shows is an operand `--watch` takes, and shows in its header: images,
/// timers, counters, data words and double words, a STEP 7 data block's values by name (members
/// of structures and UDTs, array elements, an instance DB's interface, a multi-instance's
/// members); a STRING is no operand, and says so.
#[test]
fn every_name_the_state_shows_is_watched_by_that_name() {
    for program in [
        "tests/inputs/state_widths.awl",
        "tests/inputs/s7/state_names.awl",
    ] {
        let names = state_names(program);
        assert!(names.len() > 10, "{names:?}");
        let (strings, watched): (Vec<String>, Vec<String>) =
            names.into_iter().partition(|name| name == "DB5.label");
        let list = watched.join(", ");
        let (stdout, stderr) = awl(&["run", program, "--cycles", "1", "--watch", &list]);
        assert!(stderr.is_empty(), "{program}: {stderr}");
        let header = stdout.lines().next().unwrap_or_default();
        for name in &watched {
            assert!(header.contains(name.as_str()), "{name} in {header}");
        }
        for string in strings {
            let (_, stderr) = awl(&["run", program, "--cycles", "1", "--watch", &string]);
            let said: Vec<&str> = stderr
                .split_whitespace()
                .filter(|word| *word != "│")
                .collect();
            assert!(
                said.join(" ").contains(
                    "cannot watch `DB5.label`: a STRING[8]: an operand is a BOOL or a value of 1, 2 or 4 bytes"
                ),
                "{stderr}"
            );
        }
    }
}
