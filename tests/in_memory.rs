//! Runs from files held in memory (as the browser playground, which has no file system, will
//! run them) give the same report as runs from the disk, for every sample.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, RunOptions};
use awl::source::Files;

fn report(options: &RunOptions) -> String {
    let ran = match runner::run(options) {
        Ok(ran) => ran,
        Err(_) => panic!("{:?} runs", options.scenario),
    };
    // The last line tells the wall time, which differs from run to run.
    let summary = awl::report::summary(&ran);
    summary
        .lines()
        .filter(|line| !line.starts_with("instructions:"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn every_sample_runs_the_same_from_memory() {
    let mut files = BTreeMap::new();
    let mut scenarios = Vec::new();
    let entries = common::SAMPLE_DIRS
        .iter()
        .flat_map(|dir| std::fs::read_dir(dir).unwrap());
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_file() {
            files.insert(path.clone(), std::fs::read(&path).unwrap());
            if path.extension().is_some_and(|ext| ext == "toml") {
                scenarios.push(path);
            }
        }
    }
    scenarios.sort();
    let store = Files::Memory(Arc::new(files));
    for scenario in scenarios {
        let disk = RunOptions {
            scenario: Some(scenario.clone()),
            ..RunOptions::default()
        };
        let memory = RunOptions {
            store: store.clone(),
            ..disk.clone()
        };
        assert_eq!(report(&memory), report(&disk), "{}", scenario.display());
    }
}

#[test]
fn a_file_missing_from_memory_is_reported() {
    let store = Files::Memory(Arc::new(BTreeMap::new()));
    let options = RunOptions {
        scenario: Some(PathBuf::from("programs/fig5_2.toml")),
        store,
        ..RunOptions::default()
    };
    assert!(runner::run(&options).is_err());
}
