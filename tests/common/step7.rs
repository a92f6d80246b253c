//! STEP 7 programs run from memory on the speed7 CPU, with a scenario.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, Ran, RunOptions};
use awl::source::Files;

/// Runs `program` on speed7 with the scenario `scenario` (its `program` and `cpu` keys are
/// added).
pub fn run(program: &str, scenario: &str) -> Result<Ran, NotRun> {
    run_on("speed7", program, scenario)
}

/// Runs `program` on `cpu` with the scenario `scenario` (its `program` and `cpu` keys are
/// added).
pub fn run_on(cpu: &str, program: &str, scenario: &str) -> Result<Ran, NotRun> {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.as_bytes().to_vec());
    let scenario = format!("program = [\"p.awl\"]\ncpu = \"{cpu}\"\n{scenario}");
    files.insert(PathBuf::from("s.toml"), scenario.into_bytes());
    runner::run(&RunOptions {
        scenario: Some(PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    })
}

/// `program` runs and meets every expectation of `scenario` (which has some).
pub fn passes(program: &str, scenario: &str) {
    match run(program, scenario) {
        Ok(ran) => {
            assert!(
                !ran.failed() && ran.expectations > 0,
                "{:#?}",
                ran.mismatches
            );
        }
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => {
            panic!("{reports:?}")
        }
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}
