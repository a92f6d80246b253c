//! One run, as `awl run` and `awl test` do it: scenario, front end, CPU, trace, expectations.
//! Nothing is printed here: every diagnostic comes back as a report for the caller to show.

pub mod memory;
mod stop_report;
pub mod warnings;

use std::fs::File;
use std::io::{BufWriter, ErrorKind, Write};
use std::path::PathBuf;
use std::sync::Arc;

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::analyze;
use crate::compiler::Program;
use crate::diagnostics;
use crate::frontend::{self, Frontend, Language};
use crate::mnemonics::MnemonicSet;
use crate::profile::{Family, InterruptPoints, Profile};
use crate::program_files::{ProgramFiles, read_program};
use crate::project::Project;
use crate::retain::RetainOptions;
use crate::scenario::check::{CheckOutcome, Checker};
use crate::scenario::expect::{self, Mismatch};
use crate::scenario::modify::Modifier;
use crate::scenario::operand::{Target, parse_target};
use crate::scenario::{Plan, Scenario};
use crate::source::Files;
use crate::state::watch::{Format, WatchTable};
use crate::timeline;
use crate::trace::{self, Kind, TraceFilter, TraceFormat};
use crate::vm::Cpu;
use crate::vm::cycle::{RunLimit, RunOutcome};
use crate::vm::interrupts::{Engine, EngineConfig};

pub use memory::Persistence;
pub use stop_report::{cpu_stop_report, stop_report};
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
    /// The kinds of events the trace shows (`--trace-filter`); empty for all.
    pub trace_filter: Vec<Kind>,
    /// The window of simulated time the trace and the timeline show (`--from`, `--to`).
    pub from_ns: Option<u64>,
    pub to_ns: Option<u64>,
    /// The timeline picture's file (`.svg` or `.html`).
    pub timeline: Option<PathBuf>,
    /// Assignment lists (`--symbols`), after the scenario's `symbols`.
    pub symbols: Vec<PathBuf>,
    /// Where the scenario, program and symbol files are read from.
    pub store: Files,
    /// The command line's language (`--mnemonics`, `--dialect`, `--extended`); a dialect it
    /// leaves open is the scenario's `dialect`, else detected per file.
    pub language: Language,
    /// The cycle monitoring time, over the scenario's `watchdog` and the profile's.
    pub watchdog_ns: Option<u64>,
    /// Operands to watch (`--watch "Q 4.0, FW 10"`), added to the scenario's `watch`.
    pub watch: Vec<String>,
    /// A watch table file (`--watch-file`): its rows follow `watch`'s.
    pub watch_file: Option<PathBuf>,
    /// A watch row every this much simulated time instead of one per change.
    pub watch_every_ns: Option<u64>,
    /// Retentive memory kept in a file (`--retain`).
    pub retain: Option<RetainOptions>,
    /// A snapshot to continue from (`--from SNAPSHOT`).
    pub from_snapshot: Option<PathBuf>,
    /// Load what still fits of a retentive memory file or snapshot (`--retain-what-fits`).
    pub what_fits: bool,
    /// Write a snapshot (`--snapshot FILE`), at the first cycle end at or after the time given
    /// (`--snapshot-at`), else at the run's end.
    pub snapshot_to: Option<(PathBuf, Option<u64>)>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum RunError {
    #[error("`--from {from}` sets where the trace and the timeline start, and neither is written")]
    #[diagnostic(
        code(awl::cli::window_needs_output),
        help(
            "add `--trace FILE` or `--timeline FILE`; to continue from a snapshot, name its file"
        )
    )]
    WindowNeedsOutput { from: String },
    #[error("`--from` names two times or two snapshots")]
    #[diagnostic(
        code(awl::cli::from_twice),
        help(
            "give `--from` at most once with a time (the trace's start) and once with a snapshot file"
        )
    )]
    FromTwice,
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
    #[error("`{other}` and `--trace -` both want stdout")]
    #[diagnostic(
        code(awl::cli::stdout_twice),
        help("write the trace to a file (`--trace run.jsonl`), or {instead}")
    )]
    StdoutTwice {
        /// The other option that writes to stdout.
        other: &'static str,
        /// What to do instead of it.
        instead: &'static str,
    },
    #[error("cannot watch `{operand}`: {reason}")]
    #[diagnostic(code(awl::cli::watch_operand))]
    WatchOperand {
        operand: String,
        reason: String,
        #[help]
        help: &'static str,
    },
    #[error("`{operand}` cannot be shown as {format}")]
    #[diagnostic(code(awl::cli::watch_format), help("{why}"))]
    WatchFormat {
        operand: String,
        format: &'static str,
        why: &'static str,
    },
    #[error("cannot read the watch table `{path}`: {reason}")]
    #[diagnostic(
        code(awl::cli::watch_file),
        help(
            "a watch table is text: one operand a line, a display format after it if wanted (`MW 10 HEX`), `//` comments"
        )
    )]
    WatchFile { path: String, reason: String },
    #[error("the window from {from} to {to} holds no time")]
    #[diagnostic(
        code(awl::cli::empty_window),
        help("`--from` must come before `--to`, e.g. `--from 10ms --to 20ms`")
    )]
    EmptyWindow { from: String, to: String },
    #[error("cannot write the timeline to `{path}`: {reason}")]
    #[diagnostic(
        code(awl::cli::timeline_write),
        help("check that the directory exists and is writable")
    )]
    TimelineWrite { path: String, reason: String },
}

/// Everything a finished run has to say.
pub struct Ran {
    pub frontend: Frontend,
    /// How the memory began with `--retain`, and its file.
    pub retain_start: Option<(crate::retain::keeper::Start, PathBuf)>,
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
    /// The trace and timeline files written to the end.
    pub written: Vec<Written>,
}

/// A trace or timeline file written to the end: what it is, where, how many events and bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    /// `trace` or `timeline`.
    pub what: &'static str,
    pub path: String,
    pub events: u64,
    pub bytes: u64,
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
    /// The program has errors: every diagnostic of the front end, warnings included, and
    /// their counts.
    SourceErrors(Vec<Report>, crate::diagnostics::Totals),
    /// The scenario, the files or the trace output are at fault.
    Failed(Vec<Report>),
}

/// The trace's output: stdout for `-`, else the file, created before the run.
fn open_trace(path: &PathBuf) -> Result<Box<dyn Write>, NotRun> {
    if path.as_os_str() == "-" {
        return Ok(Box::new(BufWriter::new(std::io::stdout())));
    }
    let file = File::create(path).map_err(|error| {
        NotRun::Failed(vec![Report::new(RunError::TraceWrite {
            path: path.display().to_string(),
            reason: error.to_string(),
        })])
    })?;
    Ok(Box::new(BufWriter::new(file)))
}

/// The timeline's file, created before the run so a wrong path is told at once.
fn open_timeline(path: &PathBuf) -> Result<Box<dyn Write>, NotRun> {
    let file = File::create(path).map_err(|error| {
        NotRun::Failed(vec![Report::new(RunError::TimelineWrite {
            path: path.display().to_string(),
            reason: error.to_string(),
        })])
    })?;
    Ok(Box::new(BufWriter::new(file)))
}

/// The trace and the timeline the options ask for, on `cpu`'s tracer.
fn add_outputs(
    cpu: &mut Cpu,
    options: &RunOptions,
    levels: trace::Levels,
    caption: String,
) -> Result<(), NotRun> {
    if let (Some(from), Some(to)) = (options.from_ns, options.to_ns)
        && from >= to
    {
        return Err(NotRun::Usage(Report::new(RunError::EmptyWindow {
            from: trace::format_ms(from),
            to: trace::format_ms(to),
        })));
    }
    let window = TraceFilter::all().window(options.from_ns, options.to_ns);
    if let Some(path) = &options.trace {
        let format = options.trace_format.unwrap_or(TraceFormat::Jsonl);
        let filter = window.kinds(&options.trace_filter);
        let symbols = cpu.program.symbols.clone();
        let sink = trace::trace_sink(format, open_trace(path)?, filter, levels.clone(), symbols);
        cpu.tracer.add(&path.display().to_string(), sink, filter);
    }
    if let Some(path) = &options.timeline {
        let out = open_timeline(path)?;
        let sink = timeline::sink(timeline::Format::of(path), out, window, levels, caption);
        cpu.tracer.add(&path.display().to_string(), sink, window);
    }
    Ok(())
}

/// What a picture says it shows: the scenario or the program, the CPU and how it ran.
fn caption(
    options: &RunOptions,
    files: &[PathBuf],
    config: &EngineConfig,
    profile: &Profile,
) -> String {
    let what = match &options.scenario {
        Some(path) => path.display().to_string(),
        None => files
            .iter()
            .map(|path| path.display().to_string())
            .collect::<Vec<_>>()
            .join(", "),
    };
    let mode = if profile.family == Family::Sinumerik840c {
        if config.special_mode {
            ", special mode"
        } else {
            ", normal mode"
        }
    } else {
        ""
    };
    format!(
        "{what} — {}{mode}, {} points",
        profile.name,
        config.points.name()
    )
}

/// Builds and runs to the limit or a STOP.
pub fn run(options: &RunOptions) -> Result<Ran, NotRun> {
    Ok(prepare(options)?.run(&mut |_| true))
}

/// Runs a CPU to a limit, calling the observer at every cycle boundary; see
/// [`Prepared::run_driven`].
pub type Drive<'a> =
    dyn FnMut(&mut Cpu, RunLimit, &mut dyn FnMut(&mut Cpu) -> bool) -> RunOutcome + 'a;

/// A run set up and ready to go: the CPU in STOP with its program, engine and trace.
pub struct Prepared {
    pub frontend: Frontend,
    pub cpu: Cpu,
    pub limit: RunLimit,
    /// Whether the command line or the scenario set the limit (else it is [`DEFAULT_RUN`]).
    pub limit_given: bool,
    /// The mnemonic set operands are written in (the first file's).
    pub mnemonics: MnemonicSet,
    scenario: Option<Scenario>,
    expectations: Vec<expect::Expectation>,
    checker: Checker,
    /// The data block writes of `set`, made at cycle boundaries.
    modifier: Modifier,
    watch: WatchTable,
    points: InterruptPoints,
    timeline: Option<PathBuf>,
    trace_to_stdout: bool,
    warnings: Vec<Report>,
    /// The snapshot continued from, the retentive memory kept, the snapshot to write.
    pub persistence: Persistence,
}

/// Reads the scenario and the program and sets up the CPU; every error found on the way is
/// reported at once.
pub fn prepare(options: &RunOptions) -> Result<Prepared, NotRun> {
    // A scenario's errors are reported together with those found once the program is
    // compiled (its operands), so a file shows all of them at once.
    let (mut scenario, mut scenario_errors) = match &options.scenario {
        Some(path) => {
            let (scenario, errors) = Scenario::load_in(&options.store, path)
                .map_err(|error| NotRun::Failed(vec![error]))?;
            (Some(scenario), errors)
        }
        None => (None, Vec::new()),
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
        scenario_errors.push(Report::new(RunError::NoProgram));
        return Err(NotRun::Failed(scenario_errors));
    }
    // A list named twice (by the scenario and on the command line) is read once.
    let mut symbol_paths: Vec<PathBuf> = Vec::new();
    for path in scenario
        .iter()
        .flat_map(|scenario| scenario.symbols.iter())
        .chain(&options.symbols)
    {
        let same = |known: &PathBuf| {
            known == path
                || known
                    .canonicalize()
                    .ok()
                    .is_some_and(|known| path.canonicalize().ok() == Some(known))
        };
        if !symbol_paths.iter().any(same) {
            symbol_paths.push(path.clone());
        }
    }
    let read = read_program(&options.store, &files, &symbol_paths).map_err(|errors| {
        scenario_errors.extend(errors);
        NotRun::Failed(std::mem::take(&mut scenario_errors))
    })?;
    let ProgramFiles {
        sources,
        symbol_files,
        project,
    } = read;
    let language = language(options.language, scenario.as_ref(), project.as_ref());
    // A CPU the command line or the scenario names is taken as it is; else the program's
    // dialect's, set as the project asks.
    let named = options.cpu.or(scenario.as_ref().and_then(|s| s.cpu));
    let profile_of = |dialect| {
        named.unwrap_or_else(|| {
            let default = crate::profile::default_for(dialect);
            project
                .as_ref()
                .map_or(default, |project| project.cpu(default))
        })
    };
    let built = frontend::build_for_dialect(sources, symbol_files, language, profile_of);
    let profile = built.compiled.program.profile;
    if options.special_mode.is_some() && profile.family != Family::Sinumerik840c {
        return Err(NotRun::Usage(Report::new(RunError::ModeNotForCpu {
            cpu: profile.name,
        })));
    }
    if let Some(scenario) = &mut scenario {
        scenario_errors.extend(scenario.settle_cpu(profile));
    }
    let mut warnings: Vec<Report> = built
        .diagnostics
        .iter()
        .map(|diagnostic| diagnostics::report(&built.sources, diagnostic))
        .collect();
    if built.has_errors() {
        warnings.append(&mut scenario_errors);
        let totals = diagnostics::Totals::of(&built.diagnostics, built.sources.files.len());
        return Err(NotRun::SourceErrors(warnings, totals));
    }
    let program = Arc::new(built.compiled.program.clone());
    // The CPU as the program set it (`__FEATURE 0, 4`: four accumulators).
    let profile = program.profile;
    warnings.extend(analyze::warnings::no_ob1(&program));
    warnings.extend(analyze::warnings::obs_not_on_cpu(&program, &built.sources));
    let set = built
        .mnemonics
        .first()
        .copied()
        .unwrap_or(MnemonicSet::English);
    // Watched operands are checked with the scenario's other operands, so all are reported.
    let watched = watched(options, scenario.as_ref(), &program, set);
    let (plan, expectations, checks) = match &scenario {
        Some(scenario) => {
            let plan = scenario.plan(&program, set);
            let expectations = scenario.expectations(&program, set);
            let checks = scenario.checks(&program, set);
            match (plan, expectations, checks) {
                (Ok(plan), Ok(expectations), Ok(checks)) if scenario_errors.is_empty() => {
                    (plan, expectations, checks)
                }
                (plan, expectations, checks) => {
                    scenario_errors.extend(plan.err().into_iter().flatten());
                    scenario_errors.extend(expectations.err().into_iter().flatten());
                    scenario_errors.extend(checks.err().into_iter().flatten());
                    if let Err(NotRun::Failed(reports)) = watched {
                        scenario_errors.extend(reports);
                    }
                    return Err(NotRun::Failed(scenario_errors));
                }
            }
        }
        None => (Plan::default(), Vec::new(), Vec::new()),
    };
    let watch = WatchTable::new(watched?, options.watch_every_ns);
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
        hw_addresses: scenario
            .as_ref()
            .map(|s| s.hw_addresses.clone())
            .unwrap_or_default(),
        ob35_interval_ns: scenario
            .as_ref()
            .and_then(|s| s.ob35_interval_ns)
            .unwrap_or(crate::vm::interrupts::OB35_DEFAULT_NS),
        watchdog_ns: options
            .watchdog_ns
            .or(scenario.as_ref().and_then(|s| s.watchdog_ns))
            .or(project.as_ref().map(|project| project.cycle_limit_ns))
            .unwrap_or(profile.watchdog_ns),
        interrupt_inputs: plan.interrupt_inputs,
        min_cycle_ns: scenario
            .as_ref()
            .and_then(|s| s.min_cycle_ns)
            .or(project.as_ref().and_then(|project| project.min_cycle_ns))
            .filter(|_| profile.runs_step7())
            .unwrap_or(0),
    };
    if profile.family == Family::Sinumerik840c && !special_mode {
        warnings.extend(warnings::normal_mode_calls(&program, &built.sources));
    }
    warnings.extend(warnings::obs_never_run(&program, &built.sources, &config));
    // A run time limit of no time ends at the first cycle end, as awlsim checks it there.
    let project_limit = project
        .as_ref()
        .and_then(|project| project.max_runtime_ns)
        .map(|limit| RunLimit::Duration(limit.max(1)));
    let given_limit = options
        .limit
        .or(scenario.as_ref().and_then(|s| s.limit))
        .or(project_limit);
    let sources = Arc::new(built.sources.clone());
    let levels = trace::levels(profile, &program);
    let caption = caption(options, &files, &config, profile);
    let mut cpu = Cpu::new(program, sources);
    cpu.engine = Engine::new(profile, config, plan.schedule);
    // A project's clock memory byte is one of awlsim's 2048 flag bytes, which a CPU set by
    // the command line or the scenario may lack.
    let flag_bytes = cpu.program.profile.sizes.flag_bytes;
    cpu.clock_memory = scenario
        .as_ref()
        .and_then(|s| s.clock_memory)
        .or(project
            .as_ref()
            .and_then(|project| project.clock_memory)
            .filter(|&byte| byte < flag_bytes))
        .map(|byte| cpu.program.layout.flag_base() + byte);
    if let Some(project) = &project {
        cpu.writes_start_info = project.start_info;
        cpu.set_local_bytes(project.local_bytes as usize);
    }
    let trace_to_stdout = options
        .trace
        .as_ref()
        .is_some_and(|path| path.as_os_str() == "-");
    add_outputs(&mut cpu, options, levels, caption)?;
    let ranges = scenario
        .as_ref()
        .and_then(|s| s.retentive)
        .unwrap_or(profile.retentive().ranges);
    let persistence = Persistence::begin(options, &mut cpu, ranges)?;
    let mut checker = Checker::new(checks);
    let mut modifier = Modifier::new(plan.writes);
    if options.from_snapshot.is_some() {
        checker.skip_until(cpu.clock);
        modifier.skip_until(cpu.clock);
    }
    Ok(Prepared {
        frontend: built,
        cpu,
        limit: given_limit.unwrap_or(DEFAULT_RUN),
        limit_given: given_limit.is_some(),
        mnemonics: set,
        scenario,
        expectations,
        checker,
        modifier,
        persistence,
        watch,
        points,
        timeline: options.timeline.clone(),
        trace_to_stdout,
        warnings,
    })
}

impl Prepared {
    /// Where the Modbus server's tables lie: the scenario's `[modbus]`, else the defaults.
    pub fn modbus_map(&self) -> Result<crate::address::modbus_map::Map, Vec<Report>> {
        match &self.scenario {
            Some(scenario) => scenario.modbus_map(&self.cpu.program, self.mnemonics),
            None => Ok(crate::address::modbus_map::Map::default()),
        }
    }

    /// The warnings found so far (the program's, the setup's), to show before the run.
    pub fn take_warnings(&mut self) -> Vec<Report> {
        std::mem::take(&mut self.warnings)
    }

    /// Runs to the limit, a STOP, or a halt (`go_on`, a probe).
    pub fn run(self, go_on: &mut dyn FnMut(&Cpu) -> bool) -> Ran {
        self.run_driven(&mut |cpu, limit, observe| {
            cpu.run_watched(limit, &mut |cpu| observe(cpu) && go_on(cpu))
        })
    }

    /// As [`Prepared::run`], with `drive` running the CPU to `limit`: it calls `observe` at
    /// every cycle boundary (the watch table, the checks, the scenario's writes) and may run
    /// the CPU in several stretches (`awl serve`: a STOP and a restart between them).
    pub fn run_driven(self, drive: &mut Drive) -> Ran {
        let Prepared {
            frontend,
            mut cpu,
            limit,
            scenario,
            expectations,
            mut checker,
            mut modifier,
            mut watch,
            points,
            timeline,
            trace_to_stdout,
            mut warnings,
            mut persistence,
            ..
        } = self;
        // The cycle end is seen as it is; a data block write comes after, before the next cycle.
        let outcome = drive(&mut cpu, limit, &mut |cpu| {
            watch.observe(cpu);
            checker.observe(cpu);
            modifier.observe(cpu);
            persistence.at_control_point(cpu);
            true
        });
        warnings.extend(persistence.finish(&cpu));
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
        let mut written = Vec::new();
        for finished in cpu.tracer.finish(cpu.clock) {
            let is_timeline = timeline
                .as_ref()
                .is_some_and(|path| path.display().to_string() == finished.name);
            let what = if is_timeline { "timeline" } else { "trace" };
            match finished.error {
                Some(error) if finished.name == "-" && error.kind() == ErrorKind::BrokenPipe => {
                    trace_closed = true;
                }
                Some(error) => warnings.push(Report::new(RunWarning::TraceIncomplete {
                    what,
                    path: finished.name,
                    reason: error.to_string(),
                })),
                None if finished.name == "-" => {}
                None => written.push(Written {
                    what,
                    bytes: std::fs::metadata(&finished.name).map_or(0, |file| file.len()),
                    path: finished.name,
                    events: finished.events,
                }),
            }
        }
        let mismatches = expect::check(&cpu, &outcome, &expectations);
        Ran {
            frontend,
            retain_start: persistence.start,
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
            written,
        }
    }
}

/// The language the program is read in: the command line's choices, the scenario's where the
/// command line leaves them open, then the project's.
fn language(
    command_line: Language,
    scenario: Option<&Scenario>,
    project: Option<&Project>,
) -> Language {
    let given = Language {
        dialect: command_line
            .dialect
            .or(scenario.and_then(|scenario| scenario.dialect)),
        extensions: command_line.extensions || scenario.is_some_and(|scenario| scenario.extended),
        ..command_line
    };
    project.map_or(given, |project| project.language(given))
}

/// The watched operands: the scenario's `watch`, then the command line's, then the watch table
/// file's, each with its display format.
fn watched(
    options: &RunOptions,
    scenario: Option<&Scenario>,
    program: &Program,
    set: MnemonicSet,
) -> Result<Vec<Watched>, NotRun> {
    let mut rows: Vec<Watched> = match scenario {
        Some(scenario) => scenario
            .watch_targets(program, set)
            .map_err(NotRun::Failed)?
            .into_iter()
            .map(|(operand, target)| (operand, target, None))
            .collect(),
        None => Vec::new(),
    };
    let usage = |error| NotRun::Usage(Report::new(error));
    let mut asked: Vec<(String, Option<Format>)> = options
        .watch
        .iter()
        .map(|operand| (operand.clone(), None))
        .collect();
    if let Some(path) = &options.watch_file {
        let text = std::fs::read_to_string(path).map_err(|error| {
            usage(RunError::WatchFile {
                path: path.display().to_string(),
                reason: error.to_string(),
            })
        })?;
        asked.extend(crate::state::watch::table_rows(&text));
    }
    for (operand, format) in asked {
        let target = watch_row(&operand, format, set, program).map_err(usage)?;
        // A column with a format says so (`MW 10 HEX`).
        let name = match format {
            Some(format) => format!("{operand} {}", format.name(program.s7.step7)),
            None => operand,
        };
        rows.push((name, target, format));
    }
    Ok(rows)
}

/// A watch table's column: its name, target and display format (`None`: the dialect's own).
pub type Watched = (String, Target, Option<Format>);

/// A watch row's operand, checked against its display format: the rows of `--watch`, of a
/// watch table file and of the online page.
pub fn watch_row(
    operand: &str,
    format: Option<Format>,
    set: MnemonicSet,
    program: &Program,
) -> Result<Target, RunError> {
    let target = watch_target(operand, set, program)?;
    match format.and_then(|format| Some((format, format.misfit(target)?))) {
        Some((format, why)) => Err(RunError::WatchFormat {
            operand: operand.to_string(),
            format: format.name(program.s7.step7),
            why,
        }),
        None => Ok(target),
    }
}

/// An operand as `--watch` takes it, and the online page: the one way the command line's
/// operands are resolved.
pub fn watch_target(
    operand: &str,
    set: MnemonicSet,
    program: &Program,
) -> Result<Target, RunError> {
    parse_target(operand, (0, 0).into(), set, program).map_err(|error| RunError::WatchOperand {
        operand: operand.to_string(),
        reason: error.reason(),
        help: if program.s7.step7 {
            "write operands as `--state` names them, as in a scenario's [expect]: `Q 4.0`, `MW 10`, `T 1`, `C 2`, `DB1.DBW 2`, `DB1.level`"
        } else {
            "write operands as `--state` names them, as in a scenario's [expect]: `Q 4.0`, `FW 10`, `T 1`, `C 2`, `DB 10 DW 3`"
        },
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::dialect::Dialect;

    fn scenario(text: &str) -> Scenario {
        let (scenario, errors) = Scenario::parse(Path::new("s.toml"), text);
        assert!(errors.is_empty());
        scenario
    }

    #[test]
    fn the_command_line_s_dialect_wins_over_the_scenario_s() {
        let s7 = scenario("dialect = \"s7\"\nextended = true\n");
        let open = Language::default();
        assert_eq!(
            language(open, Some(&s7), None),
            Language {
                dialect: Some(Dialect::Step7),
                extensions: true,
                mnemonics: None
            }
        );
        let s5 = Language {
            dialect: Some(Dialect::Step5),
            mnemonics: Some(MnemonicSet::German),
            extensions: false,
        };
        assert_eq!(
            language(s5, Some(&s7), None),
            Language {
                extensions: true,
                ..s5
            }
        );
        assert_eq!(language(s5, None, None), s5);
        assert_eq!(language(open, Some(&scenario("")), None), open);
        // A project's mnemonics and STEP 7 count where the command line leaves them open.
        let project = Project {
            mnemonics: Some(MnemonicSet::English),
            ..Project::default()
        };
        assert_eq!(
            language(open, None, Some(&project)),
            Language {
                dialect: Some(Dialect::Step7),
                mnemonics: Some(MnemonicSet::English),
                extensions: false
            }
        );
        assert_eq!(language(s5, None, Some(&project)), s5);
    }
}
