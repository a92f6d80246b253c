//! Any bytes as a scenario file, checked against a sample program with every interrupt OB:
//! reading, checking, scheduling and the expectations never panic and every error renders;
//! a scenario without errors runs (its length capped). Seeds: the `.toml` files of `programs/`.
#![no_main]

use std::path::Path;

use awl::diagnostics::render_plain;
use awl::frontend;
use awl::profile::InterruptPoints;
use awl::scenario::Scenario;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::EngineConfig;
use libfuzzer_sys::fuzz_target;

/// OB 1 with a block call, a timer and a data block, and every interrupt OB of every CPU.
const PROGRAM: &str = "OB 1\n      C  DB 10\n      JU PB 3\n      A  I 0.0\n      L  KT 010.1\n      SD T 1\n      A  T 1\n      =  Q 4.0\n      BE\nPB 3\n      L  IW 0\n      T  QW 4\n      BE\nDB 10\n 0: KF +1\n 1: KF +2\n";
const INTERRUPT_OBS: [u8; 13] = [2, 3, 4, 5, 6, 7, 13, 40, 41, 82, 85, 100, 21];

/// The longest run a fuzz input may ask for: 20 ms or 20 cycles.
fn capped(limit: Option<RunLimit>) -> RunLimit {
    match limit {
        Some(RunLimit::Cycles(cycles)) => RunLimit::Cycles(cycles.min(20)),
        Some(RunLimit::Duration(ns)) => RunLimit::Duration(ns.min(20_000_000)),
        None => RunLimit::Cycles(3),
    }
}

fuzz_target!(|bytes: &[u8]| {
    let text = String::from_utf8_lossy(bytes);
    let (scenario, errors) = Scenario::parse(Path::new("fuzz.toml"), &text, None);
    for error in &errors {
        assert!(!render_plain(error).is_empty());
    }
    let profile = scenario.profile;
    let mut source = PROGRAM.to_string();
    for ob in INTERRUPT_OBS {
        source.push_str(&format!(
            "OB {ob}\n      L  PY 0\n      T  PY 1\n      BE\n"
        ));
    }
    let built = frontend::build_text("program.awl", &source, profile);
    let set = awl_fuzz::mnemonics(&built);
    let program = &built.compiled.program;
    let schedule = scenario.schedule(program, set);
    let expectations = scenario.expectations(program, set);
    let schedule_errors = schedule.as_ref().err().into_iter().flatten();
    for error in schedule_errors.chain(expectations.as_ref().err().into_iter().flatten()) {
        assert!(!render_plain(error).is_empty());
    }
    let (Ok(schedule), Ok(_), true) = (schedule, expectations, errors.is_empty()) else {
        return;
    };
    let config = EngineConfig {
        points: scenario.points.unwrap_or(InterruptPoints::Block),
        special_mode: scenario.special_mode.unwrap_or(false),
        ob13: scenario.ob13,
        hw_modules: scenario.hw_modules.clone(),
        watchdog_ns: scenario.watchdog_ns.unwrap_or(profile.watchdog_ns),
    };
    awl_fuzz::run(built, profile, config, schedule, capped(scenario.limit));
});
