//! A fuzzed run: the program runs as `awl run` would run it, and its books must balance.

use std::sync::Arc;

use awl::frontend::Frontend;
use awl::profile::Profile;
use awl::runner::{self, Ran};
use awl::scenario::expect;
use awl::trace::{TraceFormat, Tracer};
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Scheduled};
use awl::vm::{Cpu, Mode};

use crate::check_report;

/// How a run is set up.
pub struct Setup {
    pub profile: &'static Profile,
    pub config: EngineConfig,
    pub schedule: Vec<Scheduled>,
    pub limit: RunLimit,
    /// The run halts (as at a Ctrl-C) after this many cycles, whatever its limit.
    pub max_cycles: u64,
    /// The trace's format (written to nowhere); `None` runs without a trace.
    pub trace: Option<TraceFormat>,
    /// Whether the STOP report is rendered in full.
    pub render: bool,
}

/// Runs a compiled program with the engine set up as given, and builds what `awl run` would
/// print: the summary and, at a STOP, the STOP report.
pub fn run(built: Frontend, setup: Setup) {
    let program = Arc::new(built.compiled.program.clone());
    let mut cpu = Cpu::new(program, Arc::new(built.sources.clone()));
    let points = setup.config.points;
    cpu.engine = Engine::new(setup.profile, setup.config, setup.schedule);
    if let Some(format) = setup.trace {
        cpu.tracer = Tracer::new(format, Box::new(std::io::sink()));
    }
    let max_cycles = setup.max_cycles;
    let outcome = cpu.run_watched(setup.limit, &mut |cpu| cpu.cycle < max_cycles);
    assert!(
        cpu.tracer
            .finish(cpu.clock)
            .iter()
            .all(|output| output.error.is_none()),
        "a sink takes everything"
    );
    assert_eq!(outcome.stop.is_some(), outcome.mode == Mode::Stop);
    for (ob, stats) in cpu.engine.requested_obs() {
        let waiting = cpu.engine.waiting(ob);
        assert_eq!(
            stats.requested,
            stats.serviced + stats.lost + stats.ignored + waiting,
            "OB {ob}: every request is accounted for"
        );
    }
    let ran = Ran {
        mismatches: expect::check(&cpu, &outcome, &[]),
        frontend: built,
        cpu,
        outcome,
        expectations: 0,
        points,
        trace_to_stdout: false,
        warnings: Vec::new(),
        trace_closed: false,
        watch: awl::state::watch::WatchTable::default(),
        checks: Vec::new(),
        written: Vec::new(),
        retain_start: None,
    };
    assert!(!awl::report::summary(&ran).is_empty());
    if let Some(stop) = &ran.outcome.stop {
        let text = &ran.frontend.sources.get(0).text;
        check_report(&runner::stop_report(&ran, stop), text, setup.render);
    }
}
