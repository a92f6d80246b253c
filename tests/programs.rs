//! Every scenario in programs/ (the STEP 5 samples), programs/s7/ (the STEP 7 samples) and
//! programs/bench/ passes and states the mode it ends in, and every sample program has one.

mod common;

use awl::runner::{self, RunOptions};

/// The folders of samples, each program with its scenarios beside it.
const SAMPLE_DIRS: [&str; 3] = ["programs", "programs/s7", "programs/bench"];

fn files(dir: &str, extension: &str) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == extension))
        .collect();
    files.sort();
    files
}

#[test]
fn every_scenario_passes() {
    let scenarios: Vec<_> = SAMPLE_DIRS
        .iter()
        .flat_map(|dir| files(dir, "toml"))
        .collect();
    assert!(scenarios.len() >= 20);
    for scenario in scenarios {
        let ran = common::ran(runner::run(&RunOptions {
            scenario: Some(scenario.clone()),
            ..RunOptions::default()
        }));
        assert!(
            ran.expectations > 0,
            "{}: no expectations",
            scenario.display()
        );
        assert!(
            ran.mismatches.is_empty(),
            "{}: {:?}",
            scenario.display(),
            ran.mismatches
        );
    }
}

/// Every scenario says how the run must end: `mode` in its `[expect]` table.
#[test]
fn every_scenario_states_its_final_mode() {
    for scenario in SAMPLE_DIRS.iter().flat_map(|dir| files(dir, "toml")) {
        let text = std::fs::read_to_string(&scenario).unwrap();
        let table: toml::Table = text.parse().unwrap();
        let mode = table
            .get("expect")
            .and_then(|expect| expect.get("mode"))
            .and_then(toml::Value::as_str);
        assert!(
            matches!(mode, Some("RUN" | "STOP")),
            "{}: no `mode` in [expect]",
            scenario.display()
        );
    }
}

#[test]
fn every_program_has_a_scenario() {
    for dir in SAMPLE_DIRS {
        let scenarios: String = files(dir, "toml")
            .iter()
            .map(|path| std::fs::read_to_string(path).unwrap())
            .collect();
        for program in files(dir, "awl") {
            let name = program.file_name().unwrap().to_str().unwrap();
            assert!(
                scenarios.contains(&format!("\"{name}\"")),
                "{name} has no scenario"
            );
        }
    }
}
