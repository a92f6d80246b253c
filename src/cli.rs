//! The command line: `awl check | dump | run | test | cpus`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use crate::diagnostics;
use crate::frontend::{self, Frontend};
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Profile};

#[derive(Debug, Parser)]
#[command(name = "awl", version, about = "Run STEP 5 STL (AWL) programs on a simulated S5 CPU with interrupts")]
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
    /// List the CPU profiles with their rules and timings
    Cpus,
}

pub const EXIT_OK: u8 = 0;
pub const EXIT_SOURCE_ERRORS: u8 = 1;

pub fn run(cli: Cli) -> ExitCode {
    let code = match cli.command {
        Command::Check(options) => check(&options),
        Command::Dump(options) => dump(&options),
        Command::Cpus => {
            print!("{}", crate::report::cpus());
            EXIT_OK
        }
    };
    ExitCode::from(code)
}

fn selected_profile(name: Option<&str>) -> &'static Profile {
    name.and_then(profile::find).unwrap_or_else(|| profile::find(profile::DEFAULT_PROFILE).expect("default profile exists"))
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
    let Some(built) = build(options, None) else { return EXIT_SOURCE_ERRORS };
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
    let Some(built) = build(options, None) else { return EXIT_SOURCE_ERRORS };
    if built.has_errors() {
        eprintln!("awl dump: {}", count_summary(&built));
        return EXIT_SOURCE_ERRORS;
    }
    print!("{}", crate::dump::dump(&built.compiled.program, &built.sources));
    EXIT_OK
}
