//! What the fuzz targets share: the checks every diagnostic and every run must pass.
//!
//! A target panics (and libFuzzer keeps the input) when awl panics, when a diagnostic points
//! outside its source, or when a run's books do not balance.

use std::sync::Arc;

use awl::diagnostics::{self, render_plain};
use awl::frontend::Frontend;
use awl::mnemonics::MnemonicSet;
use awl::profile::{self, Profile};
use awl::runner::{self, Ran};
use awl::scenario::expect;
use awl::trace::{TraceFormat, Tracer};
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Scheduled};
use awl::vm::{Cpu, Mode};
use miette::Diagnostic;

/// The CPU a header byte picks.
pub fn cpu(byte: u8) -> &'static Profile {
    &profile::PROFILES[usize::from(byte) % profile::PROFILES.len()]
}

/// Every diagnostic lies inside its file, on character boundaries, and renders.
pub fn check_diagnostics(built: &Frontend) {
    for diagnostic in &built.diagnostics {
        let span = diagnostic.span();
        let text = &built.sources.get(span.file).text;
        assert!(span.start <= span.end, "{diagnostic:?}");
        assert!(
            text.is_char_boundary(span.start as usize) && text.is_char_boundary(span.end as usize),
            "{diagnostic:?} splits a character or leaves the text"
        );
        for label in diagnostic.labels().into_iter().flatten() {
            assert!(
                label.offset() + label.len() <= text.len(),
                "{diagnostic:?}: label past the end"
            );
        }
        let rendered = render_plain(&diagnostics::report(&built.sources, diagnostic));
        assert!(!rendered.is_empty());
    }
}

/// Runs a compiled program with the engine set up as given, tracing as text to nowhere, and
/// renders what `awl run` would print: the summary and, at a STOP, the STOP report.
pub fn run(
    built: Frontend,
    profile: &'static Profile,
    config: EngineConfig,
    schedule: Vec<Scheduled>,
    limit: RunLimit,
) {
    let program = Arc::new(built.compiled.program.clone());
    let mut cpu = Cpu::new(program, Arc::new(built.sources.clone()));
    let points = config.points;
    cpu.engine = Engine::new(profile, config, schedule);
    cpu.tracer = Tracer::new(TraceFormat::Text, Box::new(std::io::sink()));
    let outcome = cpu.run(limit);
    assert!(cpu.tracer.finish(cpu.clock).is_empty(), "a sink takes everything");
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
    };
    assert!(!awl::report::summary(&ran).is_empty());
    if let Some(stop) = &ran.outcome.stop {
        assert!(!render_plain(&runner::stop_report(&ran, stop)).is_empty());
    }
}

/// The mnemonic set the first file was read in.
pub fn mnemonics(built: &Frontend) -> MnemonicSet {
    built
        .mnemonics
        .first()
        .copied()
        .unwrap_or(MnemonicSet::English)
}
