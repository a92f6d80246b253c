//! Any bytes as a scenario file, checked against a sample program with every interrupt OB:
//! reading, checking, scheduling and the expectations never panic, and every error has a
//! message and a code and points into the file (one input in 16 renders them in full); a
//! scenario without errors runs, at most 20 cycles or 20 ms with at most 1,000 events.
//! Seeds: the `.toml` files of `programs/`.
#![no_main]

use std::path::Path;
use std::sync::LazyLock;

use awl::dialect::Dialect;
use awl::frontend;
use awl::profile::{InterruptPoints, default_for};
use awl::scenario::Scenario;
use awl::vm::interrupts::{EngineConfig, OB35_DEFAULT_NS};
use libfuzzer_sys::fuzz_target;

/// OB 1 with a block call, a timer and a data block, and every interrupt OB of every CPU.
static PROGRAM: LazyLock<String> = LazyLock::new(|| {
    const INTERRUPT_OBS: [u8; 13] = [2, 3, 4, 5, 6, 7, 13, 40, 41, 82, 85, 100, 21];
    let mut source = "OB 1\n      C  DB 10\n      JU PB 3\n      A  I 0.0\n      L  KT 010.1\n      SD T 1\n      A  T 1\n      =  Q 4.0\n      BE\nPB 3\n      L  IW 0\n      T  QW 4\n      BE\nDB 10\n 0: KF +1\n 1: KF +2\n".to_string();
    for ob in INTERRUPT_OBS {
        source.push_str(&format!(
            "OB {ob}\n      L  PY 0\n      T  PY 1\n      BE\n"
        ));
    }
    source
});

fuzz_target!(
    init: awl_fuzz::quiet_reports(),
    |bytes: &[u8]| {
        let bytes = awl_fuzz::bounded(bytes);
        let render = awl_fuzz::renders_in_full(bytes);
        let text = String::from_utf8_lossy(bytes);
        let (mut scenario, mut errors) = Scenario::parse(Path::new("fuzz.toml"), &text);
        let profile = scenario.cpu.unwrap_or(default_for(Dialect::Step5));
        errors.extend(scenario.settle_cpu(profile));
        for error in &errors {
            awl_fuzz::check_report(error, &text, render);
        }
        let built = frontend::build_text("program.awl", &PROGRAM, profile);
        let set = awl_fuzz::mnemonics(&built);
        let program = &built.compiled.program;
        let schedule = scenario.schedule_at_most(program, set, awl_fuzz::MAX_EVENTS);
        let expectations = scenario.expectations(program, set);
        let modbus = scenario.modbus_map(program, set);
        let schedule_errors = schedule.as_ref().err().into_iter().flatten();
        let modbus_errors = modbus.as_ref().err().into_iter().flatten();
        let expectation_errors = expectations.as_ref().err().into_iter().flatten();
        for error in schedule_errors.chain(expectation_errors).chain(modbus_errors) {
            awl_fuzz::check_report(error, &text, render);
        }
        let (Ok(schedule), Ok(_), true) = (schedule, expectations, errors.is_empty()) else {
            return;
        };
        let config = EngineConfig {
            points: scenario.points.unwrap_or(InterruptPoints::Block),
            special_mode: scenario.special_mode.unwrap_or(false),
            ob13: scenario.ob13,
            hw_modules: scenario.hw_modules.clone(),
            hw_addresses: scenario.hw_addresses.clone(),
            ob35_interval_ns: scenario.ob35_interval_ns.unwrap_or(OB35_DEFAULT_NS),
            watchdog_ns: scenario.watchdog_ns.unwrap_or(profile.watchdog_ns),
            interrupt_inputs: Vec::new(),
            min_cycle_ns: scenario.min_cycle_ns.unwrap_or(0),
        };
        let setup = awl_fuzz::Setup {
            profile,
            config,
            schedule,
            limit: awl_fuzz::capped(scenario.limit),
            max_cycles: awl_fuzz::MAX_CYCLES,
            trace: None,
            render,
        };
        awl_fuzz::run(built, setup);
    }
);
