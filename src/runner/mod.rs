//! One run, as `awl run` and `awl test` do it: scenario, front end, CPU, trace, expectations.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::Arc;

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::diagnostics;
use crate::frontend::{self, Frontend};
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, InterruptPoints, Profile};
use crate::scenario::Scenario;
use crate::scenario::expect::{self, Mismatch};
use crate::source::Span;
use crate::trace::{TraceFormat, Tracer};
use crate::vm::Cpu;
use crate::vm::cycle::{RunLimit, RunOutcome};
use crate::vm::interrupts::sinumerik840c::normal_mode_skips;
use crate::vm::interrupts::{Engine, EngineConfig};
use crate::vm::stop::{Stop, StopCause, StopDetail, StopError};

/// The default run length when neither the command line nor the scenario gives one.
pub const DEFAULT_RUN: RunLimit = RunLimit::Duration(1_000_000_000);

#[derive(Debug, Default, Clone)]
pub struct RunOptions {
    pub files: Vec<PathBuf>,
    pub scenario: Option<PathBuf>,
    pub cpu: Option<String>,
    pub limit: Option<RunLimit>,
    pub points: Option<InterruptPoints>,
    pub special_mode: Option<bool>,
    pub trace: Option<PathBuf>,
    pub trace_format: Option<TraceFormat>,
    pub mnemonics: Option<MnemonicSet>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum RunError {
    #[error("no program files")]
    #[diagnostic(
        code(awl::cli::no_program),
        help("name .awl files, or a scenario with `program = [...]`")
    )]
    NoProgram,
    #[error("the program has no OB 1: the cycles run no user program")]
    #[diagnostic(
        code(awl::run::no_ob1),
        severity(Warning),
        help("OB 1 is the cyclic program; add it, or load the file that holds it")
    )]
    NoOb1,
    #[error("the program calls {ob}, which normal mode does not process")]
    #[diagnostic(
        code(awl::run::ob_call_normal_mode),
        severity(Warning),
        help(
            "SINUMERIK 840C PLC manual, 5.3.1: OB 2 and OB 5 \"cannot be called up in normal mode\"; this call runs {ob} as an ordinary block. Use `mode = \"special\"`, or move the code into a PB"
        )
    )]
    ObCallNormalMode {
        ob: String,
        #[label("called here")]
        at: Span,
    },
    #[error("`--mode` belongs to the sinumerik-840c profile, not to {cpu}")]
    #[diagnostic(
        code(awl::cli::mode_not_for_cpu),
        help("normal and special mode are the SINUMERIK 840C's; leave `--mode` out for this CPU")
    )]
    ModeNotForCpu { cpu: &'static str },
    #[error("cannot write the trace to `{path}`: {reason}")]
    #[diagnostic(
        code(awl::cli::trace_write),
        help("check that the directory exists and is writable")
    )]
    TraceWrite { path: String, reason: String },
}

/// Everything a finished run has to say.
pub struct Ran {
    pub frontend: Frontend,
    pub cpu: Cpu,
    pub outcome: RunOutcome,
    pub mismatches: Vec<Mismatch>,
    pub expectations: usize,
    pub points: InterruptPoints,
    pub trace_to_stdout: bool,
}

/// Why a run did not get to run.
pub enum NotRun {
    /// Reports were printed already (source errors).
    SourceErrors,
    /// A report to print (scenario, files, trace).
    Failed(Report),
}

fn open_trace(path: &PathBuf, format: TraceFormat) -> Result<Tracer, NotRun> {
    let out: Box<dyn Write> = if path.as_os_str() == "-" {
        Box::new(BufWriter::new(std::io::stdout()))
    } else {
        let file = File::create(path).map_err(|error| {
            NotRun::Failed(Report::new(RunError::TraceWrite {
                path: path.display().to_string(),
                reason: error.to_string(),
            }))
        })?;
        Box::new(BufWriter::new(file))
    };
    Ok(Tracer::new(format, out))
}

/// Builds and runs. Diagnostics of the program are printed to stderr as they are found.
pub fn run(options: &RunOptions) -> Result<Ran, NotRun> {
    let scenario = match &options.scenario {
        Some(path) => Some(Scenario::load(path).map_err(NotRun::Failed)?),
        None => None,
    };
    let files = if options.files.is_empty() {
        scenario
            .as_ref()
            .map(|s| s.programs.clone())
            .unwrap_or_default()
    } else {
        options.files.clone()
    };
    if files.is_empty() {
        return Err(NotRun::Failed(Report::new(RunError::NoProgram)));
    }
    let profile: &'static Profile = options
        .cpu
        .as_deref()
        .and_then(profile::find)
        .or(scenario.as_ref().and_then(|s| s.cpu))
        .unwrap_or_else(|| profile::find(profile::DEFAULT_PROFILE).expect("default profile"));
    if options.special_mode.is_some() && profile.family != crate::profile::Family::Sinumerik840c {
        return Err(NotRun::Failed(Report::new(RunError::ModeNotForCpu {
            cpu: profile.name,
        })));
    }
    let sources =
        frontend::read_sources(&files).map_err(|error| NotRun::Failed(Report::new(error)))?;
    let built = frontend::build(sources, options.mnemonics, profile);
    for diagnostic in &built.diagnostics {
        eprintln!("{:?}", diagnostics::report(&built.sources, diagnostic));
    }
    if built.has_errors() {
        return Err(NotRun::SourceErrors);
    }
    let program = Arc::new(built.compiled.program.clone());
    if program.ob(1).is_none() {
        eprintln!("{:?}", Report::new(RunError::NoOb1));
    }
    let set = built
        .mnemonics
        .first()
        .copied()
        .unwrap_or(MnemonicSet::English);
    let (schedule, expectations) = match &scenario {
        Some(scenario) => {
            let schedule = scenario
                .schedule(&program, set)
                .map_err(|error| NotRun::Failed(scenario.report(error)))?;
            let expectations = scenario
                .expectations(&program, set)
                .map_err(|error| NotRun::Failed(scenario.report(error)))?;
            (schedule, expectations)
        }
        None => (Vec::new(), Vec::new()),
    };
    let points = options
        .points
        .or(scenario.as_ref().and_then(|s| s.points))
        .unwrap_or(profile.default_points);
    let special_mode = options
        .special_mode
        .or(scenario.as_ref().and_then(|s| s.special_mode))
        .unwrap_or(false);
    if profile.family == crate::profile::Family::Sinumerik840c && !special_mode {
        warn_normal_mode_calls(&built, &program);
    }
    let config = EngineConfig {
        points,
        special_mode,
        ob13: scenario.as_ref().and_then(|s| s.ob13),
        hw_modules: scenario
            .as_ref()
            .map(|s| s.hw_modules.clone())
            .unwrap_or_default(),
        watchdog_ns: scenario
            .as_ref()
            .and_then(|s| s.watchdog_ns)
            .unwrap_or(profile.watchdog_ns),
    };
    let limit = options
        .limit
        .or(scenario.as_ref().and_then(|s| s.limit))
        .unwrap_or(DEFAULT_RUN);
    let sources = Arc::new(built.sources.clone());
    let mut cpu = Cpu::new(program, sources);
    cpu.engine = Engine::new(profile, config, schedule);
    let trace_to_stdout = options
        .trace
        .as_ref()
        .is_some_and(|path| path.as_os_str() == "-");
    if let Some(path) = &options.trace {
        cpu.tracer = open_trace(path, options.trace_format.unwrap_or(TraceFormat::Jsonl))?;
    }
    let outcome = cpu.run(limit);
    if let Err(error) = cpu.tracer.finish() {
        let path = options
            .trace
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        return Err(NotRun::Failed(Report::new(RunError::TraceWrite {
            path,
            reason: error.to_string(),
        })));
    }
    let mismatches = expect::check(&cpu, &outcome, &expectations);
    Ok(Ran {
        frontend: built,
        cpu,
        outcome,
        mismatches,
        expectations: expectations.len(),
        points,
        trace_to_stdout,
    })
}

/// Program calls of OB 2 or OB 5 on the 840C in normal mode get a warning each.
fn warn_normal_mode_calls(built: &Frontend, program: &crate::compiler::Program) {
    for block in &program.blocks {
        for (op, span) in block.code.iter().zip(&block.spans) {
            let crate::compiler::Op::Call { block: target, .. } = *op else {
                continue;
            };
            let id = program.blocks[usize::from(target)].id;
            if id.kind == crate::mnemonics::BlockKind::Ob && normal_mode_skips(id.number) {
                let warning = RunError::ObCallNormalMode {
                    ob: id.to_string(),
                    at: *span,
                };
                eprintln!(
                    "{:?}",
                    diagnostics::with_source(&built.sources, *span, warning)
                );
            }
        }
    }
}

fn stack_text(stop: &Stop) -> String {
    if stop.stack.is_empty() {
        return "BSTACK: empty, no block was running".to_string();
    }
    let mut text = String::from("BSTACK, innermost first:");
    for (index, entry) in stop.stack.iter().enumerate() {
        let role = if index == 0 {
            "stopped here"
        } else {
            "return point"
        };
        text.push_str(&format!(
            "\n  {:<6} line {:<5} {role}",
            entry.block, entry.line
        ));
    }
    text
}

/// The STOP as a miette report with the source line.
pub fn stop_report(ran: &Ran, stop: &Stop) -> Report {
    let program = &ran.cpu.program;
    // Between cycles in a program without OB 1 there is no block: the label goes to the start
    // of the first file.
    let (at, name) = match stop.block.map(|index| &program.blocks[usize::from(index)]) {
        Some(block) => {
            let at: Span = block
                .spans
                .get(stop.pc as usize)
                .copied()
                .unwrap_or(block.header);
            (at, block.id.to_string())
        }
        None => (
            Span::default(),
            "the operating system (between cycles)".to_string(),
        ),
    };
    let stack = stack_text(stop);
    let detail = match &stop.detail {
        StopDetail::Text(text) => text.clone(),
        _ => String::new(),
    };
    let error = match (stop.cause, &stop.detail) {
        (
            StopCause::Zyk,
            StopDetail::Cycle {
                cycle_ns,
                watchdog_ns,
            },
        ) => StopError::CycleTime {
            cycle_ms: format!("{:.3}", *cycle_ns as f64 / 1e6),
            watchdog_ms: format!("{:.3}", *watchdog_ns as f64 / 1e6),
            block: name,
            at,
            stack,
        },
        (StopCause::Zyk, _) => StopError::CycleTime {
            cycle_ms: "?".into(),
            watchdog_ms: "?".into(),
            block: name,
            at,
            stack,
        },
        (StopCause::Stueb, _) => StopError::Nesting {
            limit: program.profile.nesting_limit,
            block: name,
            at,
            stack,
        },
        (StopCause::LzfBlock, _) => StopError::BlockNotLoaded {
            target: detail,
            at,
            stack,
        },
        (StopCause::LzfData, _) => StopError::DataAccess {
            problem: detail,
            at,
            stack,
        },
        (StopCause::Bcf, _) => StopError::Operation {
            problem: detail,
            at,
            stack,
        },
        (StopCause::Stp, _) => StopError::StopOperation { at, stack },
        (StopCause::Weck, StopDetail::Ob(ob)) => StopError::WakeUp { ob: *ob, at, stack },
        (
            StopCause::Weck,
            StopDetail::Ob13Interval {
                interval_ns,
                max_delay_ns,
            },
        ) => StopError::IntervalNotAboveDelay {
            interval_ms: format!("{:.3}", *interval_ns as f64 / 1e6),
            max_delay_ms: format!("{:.3}", *max_delay_ns as f64 / 1e6),
            at,
        },
        (StopCause::Weck, _) => StopError::WakeUp { ob: 13, at, stack },
        (StopCause::Ob85, StopDetail::Module { module, ob }) => StopError::MissingOb85 {
            module: *module,
            ob: *ob,
            at,
            stack,
        },
        (StopCause::Ob85, _) => StopError::MissingOb85 {
            module: 0,
            ob: 40,
            at,
            stack,
        },
    };
    diagnostics::with_source(&ran.frontend.sources, at, error)
}
