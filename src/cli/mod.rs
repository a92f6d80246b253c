//! The command line: `awl check | dump | run | test | cpus`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use crate::diagnostics;
use crate::frontend::{self, Frontend};
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, InterruptPoints, Profile};
use crate::runner::{self, NotRun, RunOptions};
use crate::trace::TraceFormat;
use crate::vm::cycle::RunLimit;

#[derive(Debug, Parser)]
#[command(
    name = "awl",
    version,
    about = "Run STEP 5 STL (AWL) programs on a simulated S5 CPU with interrupts"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Mnemonics {
    En,
    De,
}

impl From<Mnemonics> for MnemonicSet {
    fn from(value: Mnemonics) -> Self {
        match value {
            Mnemonics::En => MnemonicSet::English,
            Mnemonics::De => MnemonicSet::German,
        }
    }
}

/// Options every command that reads source files shares.
#[derive(Debug, clap::Args)]
pub struct SourceOptions {
    /// STL source files (.awl)
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// CPU profile (see `awl cpus`)
    #[arg(long, value_parser = profile::names())]
    pub cpu: Option<String>,
    /// Mnemonic set, instead of detecting it per file
    #[arg(long, value_enum)]
    pub mnemonics: Option<Mnemonics>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Parse and compile; print every error found
    Check(SourceOptions),
    /// Print each block's bytecode with source line numbers
    Dump(SourceOptions),
    /// Compile, start the CPU (STOP → STARTUP → RUN), run, print a summary
    Run(RunArgs),
    /// Run scenario files and check their [expect] tables
    Test(TestArgs),
    /// List the CPU profiles with their rules and timings
    Cpus,
}

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
}

#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// STL source files (.awl); optional with a scenario that names them
    pub files: Vec<PathBuf>,
    /// Scenario file (TOML)
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// CPU profile (see `awl cpus`)
    #[arg(long, value_parser = profile::names())]
    pub cpu: Option<String>,
    /// Run this many cycles
    #[arg(long, conflicts_with = "duration")]
    pub cycles: Option<u64>,
    /// Run for this much simulated time, e.g. 250ms (ends at the next cycle end)
    #[arg(long = "for", value_name = "DURATION", value_parser = parse_duration_arg)]
    pub duration: Option<u64>,
    /// Where interrupts are serviced
    #[arg(long, value_enum)]
    pub interrupt_points: Option<Points>,
    /// SINUMERIK 840C mode: normal ignores OB 2 and OB 5, special runs them
    #[arg(long, value_enum)]
    pub mode: Option<CpuMode>,
    /// Write a trace to FILE (`-` for stdout)
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Trace format
    #[arg(long, value_enum, default_value = "jsonl")]
    pub trace_format: Format,
    /// Mnemonic set, instead of detecting it per file
    #[arg(long, value_enum)]
    pub mnemonics: Option<Mnemonics>,
}

#[derive(Debug, clap::Args)]
pub struct TestArgs {
    /// Scenario files (TOML)
    #[arg(required = true)]
    pub scenarios: Vec<PathBuf>,
}

fn parse_duration_arg(text: &str) -> Result<u64, String> {
    crate::scenario::parse_duration(text)
        .ok_or_else(|| format!("`{text}` is not a duration; write e.g. 250ms, 2s, 500us"))
}

pub const EXIT_OK: u8 = 0;
pub const EXIT_SOURCE_ERRORS: u8 = 1;
pub const EXIT_STOP: u8 = 3;
pub const EXIT_EXPECTATION: u8 = 4;

pub fn run(cli: Cli) -> ExitCode {
    let code = match cli.command {
        Command::Check(options) => check(&options),
        Command::Dump(options) => dump(&options),
        Command::Run(args) => run_command(&args),
        Command::Test(args) => test_command(&args),
        Command::Cpus => {
            print!("{}", crate::report::cpus());
            EXIT_OK
        }
    };
    ExitCode::from(code)
}

fn selected_profile(name: Option<&str>) -> &'static Profile {
    name.and_then(profile::find)
        .unwrap_or_else(|| profile::find(profile::DEFAULT_PROFILE).expect("default profile exists"))
}

/// Runs the front end and prints its diagnostics; `None` when a file could not be read.
pub fn build(options: &SourceOptions, cpu: Option<&str>) -> Option<Frontend> {
    let sources = match frontend::read_sources(&options.files) {
        Ok(sources) => sources,
        Err(error) => {
            eprintln!("{:?}", miette::Report::new(error));
            return None;
        }
    };
    let profile = selected_profile(cpu.or(options.cpu.as_deref()));
    let built = frontend::build(sources, options.mnemonics.map(Into::into), profile);
    for diagnostic in &built.diagnostics {
        eprintln!("{:?}", diagnostics::report(&built.sources, diagnostic));
    }
    Some(built)
}

fn count_summary(built: &Frontend) -> String {
    let errors = built.diagnostics.iter().filter(|d| !d.is_warning()).count();
    let warnings = built.diagnostics.len() - errors;
    let plural = |n: usize, word: &str| format!("{n} {word}{}", if n == 1 { "" } else { "s" });
    format!(
        "{}, {} in {}",
        plural(errors, "error"),
        plural(warnings, "warning"),
        plural(built.sources.files.len(), "file")
    )
}

fn check(options: &SourceOptions) -> u8 {
    let Some(built) = build(options, None) else {
        return EXIT_SOURCE_ERRORS;
    };
    let blocks = built.compiled.program.blocks.len() + built.compiled.program.data_blocks.len();
    if built.has_errors() {
        eprintln!("awl check: {}", count_summary(&built));
        EXIT_SOURCE_ERRORS
    } else {
        println!("awl check: ok, {blocks} blocks, {}", count_summary(&built));
        EXIT_OK
    }
}

fn dump(options: &SourceOptions) -> u8 {
    let Some(built) = build(options, None) else {
        return EXIT_SOURCE_ERRORS;
    };
    if built.has_errors() {
        eprintln!("awl dump: {}", count_summary(&built));
        return EXIT_SOURCE_ERRORS;
    }
    print!(
        "{}",
        crate::dump::dump(&built.compiled.program, &built.sources)
    );
    EXIT_OK
}

fn run_options(args: &RunArgs) -> RunOptions {
    RunOptions {
        files: args.files.clone(),
        scenario: args.scenario.clone(),
        cpu: args.cpu.clone(),
        limit: args
            .cycles
            .map(RunLimit::Cycles)
            .or(args.duration.map(RunLimit::Duration)),
        points: args.interrupt_points.map(|points| match points {
            Points::Block => InterruptPoints::Block,
            Points::Operation => InterruptPoints::Operation,
        }),
        special_mode: args.mode.map(|mode| matches!(mode, CpuMode::Special)),
        trace: args.trace.clone(),
        trace_format: Some(match args.trace_format {
            Format::Text => TraceFormat::Text,
            Format::Jsonl => TraceFormat::Jsonl,
        }),
        mnemonics: args.mnemonics.map(Into::into),
    }
}

fn run_command(args: &RunArgs) -> u8 {
    let ran = match runner::run(&run_options(args)) {
        Ok(ran) => ran,
        Err(NotRun::SourceErrors) => return EXIT_SOURCE_ERRORS,
        Err(NotRun::Failed(report)) => {
            eprintln!("{report:?}");
            return EXIT_SOURCE_ERRORS;
        }
    };
    if let Some(stop) = &ran.outcome.stop {
        eprintln!("{:?}", runner::stop_report(&ran, stop));
    }
    let summary = crate::report::summary(&ran);
    if ran.trace_to_stdout {
        eprint!("{summary}");
    } else {
        print!("{summary}");
    }
    if !ran.mismatches.is_empty() {
        EXIT_EXPECTATION
    } else if ran.outcome.stop.is_some() {
        EXIT_STOP
    } else {
        EXIT_OK
    }
}

fn test_command(args: &TestArgs) -> u8 {
    let (mut passed, mut failed) = (0, 0);
    for path in &args.scenarios {
        let options = RunOptions {
            scenario: Some(path.clone()),
            ..RunOptions::default()
        };
        let verdict = match runner::run(&options) {
            Ok(ran) if ran.mismatches.is_empty() => Ok(ran),
            Ok(ran) => Err(ran
                .mismatches
                .iter()
                .map(|m| format!("{} expected {}, got {}", m.name, m.expected, m.actual))
                .collect::<Vec<_>>()
                .join("; ")),
            Err(NotRun::SourceErrors) => Err("the program has errors".to_string()),
            Err(NotRun::Failed(report)) => {
                eprintln!("{report:?}");
                Err("the scenario could not run".to_string())
            }
        };
        match verdict {
            Ok(ran) => {
                passed += 1;
                println!(
                    "PASS {}  ({} expectations, {} cycles, mode {})",
                    path.display(),
                    ran.expectations,
                    ran.outcome.cycles,
                    ran.outcome.mode.name()
                );
            }
            Err(reason) => {
                failed += 1;
                println!("FAIL {}  {reason}", path.display());
            }
        }
    }
    println!("{passed} passed, {failed} failed");
    if failed == 0 {
        EXIT_OK
    } else {
        EXIT_EXPECTATION
    }
}
