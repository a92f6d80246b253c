//! `awl run` and `awl test`: runs, their reports, and their exit codes.

use std::path::PathBuf;

use clap::ValueEnum;

use crate::profile::{self, InterruptPoints};
use crate::runner::{self, NotRun, Prepared, Ran, RunOptions};
use crate::state::State;
use crate::trace::{Kind, TraceFormat};
use crate::vm::cycle::RunLimit;

use super::memory::MemoryArgs;
use super::watch::{EXIT_HALTED, Watch};
use super::{
    Console, EXIT_EXPECTATION, EXIT_OK, EXIT_SOURCE_ERRORS, EXIT_STOP, EXIT_USAGE, LanguageArgs,
    selected_profile,
};

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Points {
    Block,
    Operation,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum CpuMode {
    Normal,
    Special,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Format {
    Text,
    Jsonl,
    /// The trace-event JSON of Perfetto (ui.perfetto.dev) and chrome://tracing
    Chrome,
}

impl Format {
    pub fn trace_format(self) -> TraceFormat {
        match self {
            Format::Text => TraceFormat::Text,
            Format::Jsonl => TraceFormat::Jsonl,
            Format::Chrome => TraceFormat::Chrome,
        }
    }
}

/// A kind of trace events (`--trace-filter`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TraceKind {
    /// Requests, services, interrupt OB ends, lost, ignored, discarded (SFC 39) and delayed
    /// (SFC 41) requests, delay ends, SFC 39-42 calls, module events
    Interrupts,
    /// Block calls and ends
    Blocks,
    /// Cycles, data cycles, operating-system time
    Cycles,
    /// Input and output changes, watch rows
    Io,
    /// Everything
    All,
}

/// How diagnostics are printed (`--format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DiagnosticFormat {
    /// Text with the source lines, on stderr
    Text,
    /// One JSON object per diagnostic and line, on stdout
    Json,
}

/// How a command reports: the diagnostics' format and `--quiet`.
#[derive(Debug, clap::Args)]
pub struct OutputArgs {
    /// Diagnostics as text, or as JSON lines on stdout (`code`, `severity`, `file`, `line`,
    /// `column`, `message`, `labels`, `help`) with everything else on stderr [default: text]
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub format: Option<DiagnosticFormat>,
    /// Print only what is wrong: error diagnostics, a STOP, failed expectations and checks,
    /// FAIL lines, and the outputs asked for (--state, --watch, a trace); no warnings, notes,
    /// summary, totals or progress line [default: off]
    #[arg(long, short)]
    pub quiet: bool,
}

impl OutputArgs {
    /// Sets `console` to print as asked.
    pub fn apply(&self, console: &mut Console) {
        console.set_output(self.format == Some(DiagnosticFormat::Json), self.quiet);
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum StateFormat {
    Text,
    Json,
}

/// What every command that sets up a CPU with a program shares: the program, the scenario and
/// the CPU.
#[derive(Debug, clap::Args)]
pub struct ProgramArgs {
    /// STL source files (.awl) or an awlsim project (.awlpro); optional with a scenario that
    /// names them
    #[arg(required_unless_present = "scenario")]
    pub files: Vec<PathBuf>,
    /// Scenario file (TOML; `awl help scenario` describes its keys) [default: none: no
    /// events, the CPU's own settings]
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// CPU profile (see `awl cpus`); overrides the scenario's [default: the scenario's, else
    /// the program's dialect's: speed7 for STEP 7 (an awlsim project is STEP 7),
    /// sinumerik-840c for STEP 5]
    #[arg(long, value_parser = profile::names())]
    pub cpu: Option<String>,
    /// Where interrupts are serviced [default: the scenario's, else the CPU's: block on the
    /// S5 CPUs, operation on speed7]
    #[arg(long, value_enum)]
    pub interrupt_points: Option<Points>,
    /// SINUMERIK 840C mode: normal ignores OB 2 and OB 5, special runs them [default: the
    /// scenario's, else normal]
    #[arg(long, value_enum)]
    pub mode: Option<CpuMode>,
    #[command(flatten)]
    pub language: LanguageArgs,
    /// Assignment list giving operands names (`-START`), or a STEP 7 symbol table (`"Motor"`);
    /// repeatable, added to the scenario's
    /// [default: the scenario's, else none]
    #[arg(long = "symbols", value_name = "FILE")]
    pub symbols: Vec<PathBuf>,
}

/// How long a command that runs the program runs it.
#[derive(Debug, clap::Args)]
pub struct RunLength {
    /// Run this many cycles (at least 1) [default: the scenario's run, else 1 s]
    #[arg(long, conflicts_with = "duration", value_parser = clap::value_parser!(u64).range(1..))]
    pub cycles: Option<u64>,
    /// Run for this much simulated time, e.g. 250ms (ends at the next cycle end) [default: the
    /// scenario's run, else 1 s]
    #[arg(long = "for", value_name = "DURATION", value_parser = parse_duration_arg)]
    pub duration: Option<u64>,
}

impl RunLength {
    /// The limit given on the command line, if any.
    pub fn limit(&self) -> Option<RunLimit> {
        self.cycles
            .map(RunLimit::Cycles)
            .or(self.duration.map(RunLimit::Duration))
    }
}

#[derive(Debug, clap::Args)]
#[command(group = clap::ArgGroup::new("outputs").args(["trace", "timeline"]).multiple(true))]
pub struct RunArgs {
    #[command(flatten)]
    pub program: ProgramArgs,
    #[command(flatten)]
    pub length: RunLength,
    /// Write a trace to FILE (`-` for stdout); `awl help trace` describes its events [default:
    /// no trace]
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Trace format [default: jsonl]
    #[arg(long, value_enum, requires = "trace")]
    pub trace_format: Option<Format>,
    /// Only these kinds of events in the trace (comma list); mode changes and a STOP always
    /// [default: all]
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        requires = "trace",
        value_name = "KINDS"
    )]
    pub trace_filter: Vec<TraceKind>,
    /// Draw the run's timeline into FILE: `.svg`, or `.html` with pan, zoom and hover details
    /// [default: no timeline]
    #[arg(long, value_name = "FILE")]
    pub timeline: Option<PathBuf>,
    /// A time (e.g. 10ms): the trace and the timeline start there. A snapshot file: the run
    /// continues from it, to the scenario's or the command line's end. Both may be given
    /// [default: the run's start, from the program as loaded]
    #[arg(long, value_name = "TIME|SNAPSHOT", value_parser = parse_from_arg)]
    pub from: Vec<From>,
    /// The trace and the timeline end at this simulated time, e.g. 20ms [default: the run's
    /// end]
    #[arg(long, value_name = "TIME", value_parser = parse_time_arg, requires = "outputs")]
    pub to: Option<u64>,
    /// Print the CPU's state at the end: ACCUs, status word, images, timers, counters, DBs
    /// [default: off]
    #[arg(long)]
    pub state: bool,
    /// The state as text after the summary, or as JSON alone on stdout (the summary then goes
    /// to stderr); implies --state [default: text]
    #[arg(long, value_enum)]
    pub state_format: Option<StateFormat>,
    /// Watch operands (STATUS VAR), e.g. "Q 4.0, FW 10, T 1, C 2, DB 10 DW 3", or
    /// "MW 10, DB5.DBW 4, DB5.level": every name --state shows; a row each time one changed
    /// at a cycle end [default: the scenario's `watch`, else none]
    #[arg(long, value_name = "OPERANDS")]
    pub watch: Option<String>,
    /// Watch the operands of a watch table file (the online page's Save): one a line, a
    /// display format after it if wanted (`MW 10 HEX`), `//` comments [default: none]
    #[arg(long, value_name = "FILE")]
    pub watch_file: Option<PathBuf>,
    /// A watch row every DURATION of simulated time (at the next cycle end) instead of on change
    /// [default: a row on each change]
    #[arg(long, value_name = "DURATION", value_parser = parse_duration_arg)]
    pub watch_every: Option<u64>,
    #[command(flatten)]
    pub memory: MemoryArgs,
    /// Write a snapshot of the whole CPU to FILE (at the run's end, or at the first cycle end
    /// at --snapshot-at); continue from it with `--from FILE` [default: none]
    #[arg(long, value_name = "FILE")]
    pub snapshot: Option<PathBuf>,
    /// The simulated time the snapshot is taken at (the next cycle end), e.g. 1.5s [default:
    /// the run's end]
    #[arg(long, value_name = "TIME", requires = "snapshot", value_parser = parse_time_arg)]
    pub snapshot_at: Option<u64>,
    #[command(flatten)]
    pub output: OutputArgs,
}

/// What `--from` names: where the trace starts, or the snapshot the run continues from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum From {
    /// The time, and as it was written.
    Time(u64, String),
    Snapshot(PathBuf),
}

/// A time, else an existing file (a snapshot).
fn parse_from_arg(text: &str) -> Result<From, String> {
    if let Ok(ns) = parse_time_arg(text) {
        return Ok(From::Time(ns, text.to_string()));
    }
    let path = PathBuf::from(text);
    if path.is_file() {
        return Ok(From::Snapshot(path));
    }
    Err(format!(
        "`{text}` is neither a time (0, 250us, 10ms, 2s) nor a snapshot file"
    ))
}

pub(super) fn parse_duration_arg(text: &str) -> Result<u64, String> {
    match crate::scenario::parse_duration(text) {
        Some(0) => Err("a run of no time: give a duration above zero".into()),
        Some(ns) => Ok(ns),
        None => Err(format!(
            "`{text}` is not a duration; write e.g. 250ms, 2s, 500us"
        )),
    }
}

/// A point in simulated time: 0 or a duration from the start.
fn parse_time_arg(text: &str) -> Result<u64, String> {
    match text.trim() {
        "0" => Ok(0),
        text => crate::scenario::parse_duration(text)
            .ok_or_else(|| format!("`{text}` is not a time; write e.g. 0, 250us, 10ms, 2s")),
    }
}

/// The run a program's arguments ask for.
pub(super) fn program_options(args: &ProgramArgs) -> RunOptions {
    RunOptions {
        files: args.files.clone(),
        scenario: args.scenario.clone(),
        cpu: args.cpu.as_deref().map(selected_profile),
        points: args.interrupt_points.map(|points| match points {
            Points::Block => InterruptPoints::Block,
            Points::Operation => InterruptPoints::Operation,
        }),
        special_mode: args.mode.map(|mode| matches!(mode, CpuMode::Special)),
        language: args.language.language(),
        symbols: args.symbols.clone(),
        ..RunOptions::default()
    }
}

fn run_options(args: &RunArgs) -> Result<RunOptions, NotRun> {
    let mut window_from: Option<(u64, &str)> = None;
    let mut from_snapshot = None;
    for from in &args.from {
        let twice = match from {
            From::Time(ns, text) => window_from.replace((*ns, text)).is_some(),
            From::Snapshot(path) => from_snapshot.replace(path.clone()).is_some(),
        };
        if twice {
            let error = runner::RunError::FromTwice;
            return Err(NotRun::Usage(miette::Report::new(error)));
        }
    }
    if let Some((_, text)) = window_from
        && args.trace.is_none()
        && args.timeline.is_none()
    {
        let error = runner::RunError::WindowNeedsOutput {
            from: text.to_string(),
        };
        return Err(NotRun::Usage(miette::Report::new(error)));
    }
    Ok(RunOptions {
        trace: args.trace.clone(),
        trace_format: args.trace_format.map(Format::trace_format),
        trace_filter: trace_kinds(&args.trace_filter),
        from_ns: window_from.map(|(ns, _)| ns),
        from_snapshot,
        retain: args.memory.retain_options(),
        what_fits: args.memory.retain_what_fits,
        snapshot_to: args.snapshot.clone().map(|path| (path, args.snapshot_at)),
        to_ns: args.to,
        timeline: args.timeline.clone(),
        watch: args
            .watch
            .iter()
            .flat_map(|list| crate::address::operand::list(list))
            .collect(),
        watch_file: args.watch_file.clone(),
        watch_every_ns: args.watch_every,
        limit: args.length.limit(),
        ..program_options(&args.program)
    })
}

/// The kinds `--trace-filter` names (none, or `all` among them: every kind).
fn trace_kinds(kinds: &[TraceKind]) -> Vec<Kind> {
    if kinds.contains(&TraceKind::All) {
        return Vec::new();
    }
    kinds
        .iter()
        .map(|kind| match kind {
            TraceKind::Interrupts => Kind::Interrupts,
            TraceKind::Blocks => Kind::Blocks,
            TraceKind::Cycles => Kind::Cycles,
            TraceKind::Io | TraceKind::All => Kind::Io,
        })
        .collect()
}

/// Prints why `awl COMMAND` did not run, source errors followed by their totals line; its
/// exit code.
pub(super) fn not_run(command: &str, reason: NotRun, console: &mut Console) -> u8 {
    match reason {
        NotRun::Usage(report) => {
            console.report(&report);
            EXIT_USAGE
        }
        NotRun::SourceErrors(reports, totals) => {
            console.reports(&reports);
            console.totals(command, totals);
            EXIT_SOURCE_ERRORS
        }
        NotRun::Failed(reports) => {
            console.reports(&reports);
            EXIT_SOURCE_ERRORS
        }
    }
}

/// Runs with Ctrl-C, and the progress line unless `console` is quiet; whether the run was
/// halted.
fn watched_run(options: &RunOptions, console: &Console) -> (Result<Ran, NotRun>, bool) {
    match runner::prepare(options) {
        Ok(prepared) => {
            let (ran, halted) = watched_as(prepared, console);
            (Ok(ran), halted)
        }
        Err(reason) => (Err(reason), false),
    }
}

/// Runs a prepared run with the progress line and Ctrl-C; whether Ctrl-C halted it.
pub(super) fn watched(prepared: Prepared) -> (Ran, bool) {
    watched_as(prepared, &Console::default())
}

/// [`watched`], without the progress line when `console` is quiet.
fn watched_as(prepared: Prepared, console: &Console) -> (Ran, bool) {
    let mut watch = Watch::start();
    if console.is_quiet() {
        watch = watch.without_progress();
    }
    let ran = prepared.run(&mut |cpu| watch.go_on(cpu));
    let halted = watch.finish();
    (ran, halted)
}

pub fn run(args: &RunArgs, console: &mut Console) -> u8 {
    args.output.apply(console);
    let state = args
        .state_format
        .or(args.state.then_some(StateFormat::Text));
    let trace_to_stdout = args
        .trace
        .as_ref()
        .is_some_and(|path| path.as_os_str() == "-");
    let other_on_stdout = if state == Some(StateFormat::Json) {
        Some(("--state-format json", "print the state as text"))
    } else if console.is_json() {
        Some(("--format json", "print the diagnostics as text"))
    } else {
        None
    };
    if let (Some((other, instead)), true) = (other_on_stdout, trace_to_stdout) {
        let error = runner::RunError::StdoutTwice { other, instead };
        return not_run("run", NotRun::Usage(miette::Report::new(error)), console);
    }
    let options = match run_options(args) {
        Ok(options) => options,
        Err(reason) => return not_run("run", reason, console),
    };
    let (ran, halted) = match watched_run(&options, console) {
        (Ok(ran), halted) => (ran, halted),
        (Err(reason), _) => return not_run("run", reason, console),
    };
    console.reports(&ran.warnings);
    if ran.trace_closed {
        console.close_out();
    }
    if let Some(stop) = &ran.outcome.stop {
        let report = runner::stop_report(&ran, stop);
        if console.is_json() {
            console.report(&report);
        } else {
            console.err(&format!("{report:?}\n"));
        }
    }
    let stdout_taken = ran.trace_to_stdout || state == Some(StateFormat::Json) || console.is_json();
    let mut report = if ran.watch.is_empty() {
        String::new()
    } else {
        ran.watch.render()
    };
    if console.is_quiet() {
        report.extend(
            failures(&ran)
                .iter()
                .map(|failure| format!("failed: {failure}\n")),
        );
    } else {
        report.push_str(&crate::report::summary(&ran));
    }
    if stdout_taken {
        console.err(&report);
    } else {
        console.out(&report);
    }
    if let Some(format) = state {
        print_state(&ran, format, console);
    }
    if !console.is_quiet() {
        console.err(&crate::report::written(&ran));
    }
    if halted {
        EXIT_HALTED
    } else if ran.failed() {
        EXIT_EXPECTATION
    } else if ran.outcome.stop.is_some() {
        EXIT_STOP
    } else {
        EXIT_OK
    }
}

/// The CPU's state at the end (`--state`), as text or as JSON.
pub(super) fn print_state(ran: &Ran, format: StateFormat, console: &mut Console) {
    let state = State::capture(&ran.cpu, ran.outcome.stop.as_ref());
    match format {
        StateFormat::Text => console.out_text(&crate::state::render(&state)),
        StateFormat::Json => console.out(&format!(
            "{}\n",
            serde_json::to_string_pretty(&state).expect("the state is plain data")
        )),
    }
}

/// What did not hold: `[expect]` entries, then `[[check]]` operands with their time.
pub(super) fn failures(ran: &Ran) -> Vec<String> {
    let symbols = &ran.cpu.program.symbols;
    let mut failures: Vec<String> = ran
        .mismatches
        .iter()
        .map(|m| {
            let name = symbols.describe(&m.name);
            format!("{name} expected {}, got {}", m.expected, m.actual)
        })
        .collect();
    for check in &ran.checks {
        match check.verified {
            None => failures.push(format!("check at {} not reached", check.at)),
            Some((at_ns, _)) => failures.extend(check.mismatches.iter().map(|m| {
                format!(
                    "{} at {} expected {}, got {}",
                    symbols.describe(&m.name),
                    crate::trace::format_ms(at_ns),
                    m.expected,
                    m.actual
                )
            })),
        }
    }
    failures
}
