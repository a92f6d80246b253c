//! One run, as `awl run` and `awl test` do it: scenario, front end, CPU, trace, expectations.
//! Nothing is printed here: every diagnostic comes back as a report for the caller to show.

mod stop_report;
pub mod warnings;

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::Arc;

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::compiler::Program;
use crate::diagnostics;
use crate::frontend::{self, Frontend};
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Family, InterruptPoints, Profile};
use crate::scenario::Scenario;
use crate::scenario::check::{CheckOutcome, Checker};
use crate::scenario::expect::{self, Mismatch};
use crate::scenario::operand::{Target, parse_target};
use crate::state::watch::WatchTable;
use crate::trace::{TraceFormat, Tracer};
use crate::vm::Cpu;
use crate::vm::cycle::{RunLimit, RunOutcome};
use crate::vm::interrupts::{Engine, EngineConfig};

pub use stop_report::stop_report;
pub use warnings::RunWarning;

/// The default run length when neither the command line nor the scenario gives one.
pub const DEFAULT_RUN: RunLimit = RunLimit::Duration(1_000_000_000);

#[derive(Debug, Default, Clone)]
pub struct RunOptions {
    pub files: Vec<PathBuf>,
    pub scenario: Option<PathBuf>,
    /// The command line's CPU; it overrides the scenario's.
    pub cpu: Option<&'static Profile>,
    pub limit: Option<RunLimit>,
    pub points: Option<InterruptPoints>,
    pub special_mode: Option<bool>,
    pub trace: Option<PathBuf>,
    pub trace_format: Option<TraceFormat>,
    pub mnemonics: Option<MnemonicSet>,
    /// Operands to watch (`--watch "Q 4.0, FW 10"`), added to the scenario's `watch`.
    pub watch: Vec<String>,
    /// A watch row every this much simulated time instead of one per change.
    pub watch_every_ns: Option<u64>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum RunError {
    #[error("no program files")]
    #[diagnostic(
        code(awl::cli::no_program),
        help("name .awl files, or a scenario with `program = [...]`")
    )]
    NoProgram,
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
    #[error("`--state-format json` and `--trace -` both want stdout")]
    #[diagnostic(
        code(awl::cli::stdout_twice),
        help("write the trace to a file (`--trace run.jsonl`), or print the state as text")
    )]
    StdoutTwice,
    #[error("cannot watch `{operand}`: {reason}")]
    #[diagnostic(
        code(awl::cli::watch_operand),
        help(
            "write operands as in a scenario's [expect]: `Q 4.0`, `FW 10`, `T 1`, `C 2`, `DB 10 DW 3`"
        )
    )]
    WatchOperand { operand: String, reason: String },
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
    /// The program's warnings, the setup's (OBs that never run, events after the end) and an
    /// incomplete trace, in that order.
    pub warnings: Vec<Report>,
    /// The trace could not be written to the end because its output was closed (a pipe).
    pub trace_closed: bool,
    /// The watch table's rows (empty without `--watch` or `watch = [...]`).
    pub watch: WatchTable,
    /// The scenario's `[[check]]` tables, verified or not reached.
    pub checks: Vec<CheckOutcome>,
}

impl Ran {
    /// Whether an `[expect]` entry or a `[[check]]` did not hold.
    pub fn failed(&self) -> bool {
        !self.mismatches.is_empty() || self.checks.iter().any(|check| !check.passed())
    }

    /// Every operand and state the scenario expects, `[[check]]` operands included.
    pub fn expectation_count(&self) -> usize {
        self.expectations
            + self
                .checks
                .iter()
                .map(|check| check.operands)
                .sum::<usize>()
    }
}

/// Why a run did not get to run.
pub enum NotRun {
    /// The command line asks for what cannot be (exit code 2).
    Usage(Report),
    /// The program has errors: every diagnostic of the front end, warnings included.
    SourceErrors(Vec<Report>),
    /// The scenario, the files or the trace output are at fault.
    Failed(Vec<Report>),
}

fn open_trace(path: &PathBuf, format: TraceFormat) -> Result<Tracer, NotRun> {
    let out: Box<dyn Write> = if path.as_os_str() == "-" {
        Box::new(BufWriter::new(std::io::stdout()))
    } else {
        let file = File::create(path).map_err(|error| {
            NotRun::Failed(vec![Report::new(RunError::TraceWrite {
                path: path.display().to_string(),
                reason: error.to_string(),
            })])
        })?;
        Box::new(BufWriter::new(file))
    };
    Ok(Tracer::new(format, out))
}

fn default_profile() -> &'static Profile {
    profile::find(profile::DEFAULT_PROFILE).expect("default profile")
}

/// Builds and runs to the limit or a STOP.
pub fn run(options: &RunOptions) -> Result<Ran, NotRun> {
    Ok(prepare(options)?.run(&mut |_| true))
}

/// A run set up and ready to go: the CPU in STOP with its program, engine and trace.
pub struct Prepared {
    pub frontend: Frontend,
    pub cpu: Cpu,
    pub limit: RunLimit,
    /// The mnemonic set operands are written in (the first file's).
    pub mnemonics: MnemonicSet,
    scenario: Option<Scenario>,
    expectations: Vec<expect::Expectation>,
    checker: Checker,
    watch: WatchTable,
    points: InterruptPoints,
    trace: Option<PathBuf>,
    trace_to_stdout: bool,
    warnings: Vec<Report>,
}

/// Reads the scenario and the program and sets up the CPU; every error found on the way is
/// reported at once.
pub fn prepare(options: &RunOptions) -> Result<Prepared, NotRun> {
    // A scenario's errors are reported together with those found once the program is
    // compiled (its operands), so a file shows all of them at once.
    let (scenario, mut scenario_errors) = match &options.scenario {
        Some(path) => {
            let (scenario, errors) =
                Scenario::load(path, options.cpu).map_err(|error| NotRun::Failed(vec![error]))?;
            (Some(scenario), errors)
        }
        None => (None, Vec::new()),
    };
    let profile = match &scenario {
        Some(scenario) => scenario.profile,
        None => options.cpu.unwrap_or_else(default_profile),
    };
    if options.special_mode.is_some() && profile.family != Family::Sinumerik840c {
        return Err(NotRun::Usage(Report::new(RunError::ModeNotForCpu {
            cpu: profile.name,
        })));
    }
    let files = if options.files.is_empty() {
        scenario
            .as_ref()
            .map(|s| s.programs.clone())
            .unwrap_or_default()
    } else {
        options.files.clone()
    };
    if files.is_empty() {
        scenario_errors.push(Report::new(RunError::NoProgram));
        return Err(NotRun::Failed(scenario_errors));
    }
    let sources = frontend::read_sources(&files).map_err(|errors| {
        scenario_errors.extend(errors.into_iter().map(Report::new));
        NotRun::Failed(std::mem::take(&mut scenario_errors))
    })?;
    let built = frontend::build(sources, options.mnemonics, profile);
    let mut warnings: Vec<Report> = built
        .diagnostics
        .iter()
        .map(|diagnostic| diagnostics::report(&built.sources, diagnostic))
        .collect();
    if built.has_errors() {
        warnings.append(&mut scenario_errors);
        return Err(NotRun::SourceErrors(warnings));
    }
    let program = Arc::new(built.compiled.program.clone());
    if program.ob(1).is_none() {
        warnings.push(Report::new(RunWarning::NoOb1));
    }
    let set = built
        .mnemonics
        .first()
        .copied()
        .unwrap_or(MnemonicSet::English);
    let (schedule, expectations, checks) = match &scenario {
        Some(scenario) => {
            let schedule = scenario.schedule(&program, set);
            let expectations = scenario.expectations(&program, set);
            let checks = scenario.checks(&program, set);
            match (schedule, expectations, checks) {
                (Ok(schedule), Ok(expectations), Ok(checks)) if scenario_errors.is_empty() => {
                    (schedule, expectations, checks)
                }
                (schedule, expectations, checks) => {
                    scenario_errors.extend(schedule.err().into_iter().flatten());
                    scenario_errors.extend(expectations.err().into_iter().flatten());
                    scenario_errors.extend(checks.err().into_iter().flatten());
                    return Err(NotRun::Failed(scenario_errors));
                }
            }
        }
        None => (Vec::new(), Vec::new(), Vec::new()),
    };
    let watch = WatchTable::new(
        watched(options, scenario.as_ref(), &program, set)?,
        options.watch_every_ns,
    );
    let points = options
        .points
        .or(scenario.as_ref().and_then(|s| s.points))
        .unwrap_or(profile.default_points);
    let special_mode = options
        .special_mode
        .or(scenario.as_ref().and_then(|s| s.special_mode))
        .unwrap_or(false);
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
    if profile.family == Family::Sinumerik840c && !special_mode {
        warnings.extend(warnings::normal_mode_calls(&program, &built.sources));
    }
    warnings.extend(warnings::obs_never_run(&program, &built.sources, &config));
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
    Ok(Prepared {
        frontend: built,
        cpu,
        limit,
        mnemonics: set,
        scenario,
        expectations,
        checker: Checker::new(checks),
        watch,
        points,
        trace: options.trace.clone(),
        trace_to_stdout,
        warnings,
    })
}

impl Prepared {
    /// The warnings found so far (the program's, the setup's), to show before the run.
    pub fn take_warnings(&mut self) -> Vec<Report> {
        std::mem::take(&mut self.warnings)
    }

    /// Runs to the limit, a STOP, or a halt (`go_on`, a probe).
    pub fn run(self, go_on: &mut dyn FnMut(&Cpu) -> bool) -> Ran {
        let Prepared {
            frontend,
            mut cpu,
            limit,
            scenario,
            expectations,
            mut checker,
            mut watch,
            points,
            trace,
            trace_to_stdout,
            mut warnings,
            ..
        } = self;
        let outcome = cpu.run_watched(limit, &mut |cpu| {
            watch.observe(cpu);
            checker.observe(cpu);
            go_on(cpu)
        });
        watch.observe(&mut cpu);
        // The run's end is a cycle end unless it went to STOP or was halted inside a cycle.
        if outcome.stop.is_none() && !outcome.halted {
            checker.observe(&cpu);
        }
        if let Some(scenario) = &scenario
            && outcome.stop.is_none()
            && !outcome.halted
        {
            warnings.extend(scenario.events_after(outcome.clock_ns));
        }
        let mut trace_closed = false;
        if let Err(error) = cpu.tracer.finish() {
            trace_closed = trace_to_stdout && error.kind() == std::io::ErrorKind::BrokenPipe;
            if !trace_closed {
                warnings.push(Report::new(RunWarning::TraceIncomplete {
                    path: trace
                        .as_ref()
                        .map(|p| p.display().to_string())
                        .unwrap_or_default(),
                    reason: error.to_string(),
                }));
            }
        }
        let mismatches = expect::check(&cpu, &outcome, &expectations);
        Ran {
            frontend,
            cpu,
            outcome,
            mismatches,
            expectations: expectations.len(),
            points,
            trace_to_stdout,
            warnings,
            trace_closed,
            watch,
            checks: checker.finish(),
        }
    }
}

/// The watched operands: the scenario's `watch`, then the command line's.
fn watched(
    options: &RunOptions,
    scenario: Option<&Scenario>,
    program: &Program,
    set: MnemonicSet,
) -> Result<Vec<(String, Target)>, NotRun> {
    let mut targets = match scenario {
        Some(scenario) => scenario
            .watch_targets(program, set)
            .map_err(NotRun::Failed)?,
        None => Vec::new(),
    };
    for operand in &options.watch {
        let target = parse_target(operand, (0, 0).into(), set, program.profile, program.layout)
            .map_err(|error| {
                NotRun::Usage(Report::new(RunError::WatchOperand {
                    operand: operand.clone(),
                    reason: error.reason(),
                }))
            })?;
        targets.push((operand.clone(), target));
    }
    Ok(targets)
}
