//! The command line: `awl check | dump | run | status | debug | analyze | test | conformance |
//! cpus | help`. Each command reports through a [`Console`], so no output failure can panic.

mod analyze;
mod conformance;
mod console;
mod debug;
mod help;
mod memory;
mod run;
mod serve;
mod snapshot_key;
mod source;
mod status;
mod terminal;
mod test;
mod watch;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use crate::dialect::Dialect;
use crate::frontend::Language;
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Profile};

pub use console::Console;

#[derive(Debug, Parser)]
#[command(
    name = "awl",
    version,
    about = "Run STEP 5 and STEP 7 STL (AWL) programs on a simulated S5 or S7 CPU with interrupts",
    after_help = "The language, the mnemonics and the formats (scenario files, traces, listings, \
        symbols, …): `awl help` lists them, `awl help scenario` prints one; `awl help error CODE` \
        explains a diagnostic.",
    disable_help_subcommand = true
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

#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum DialectName {
    /// STEP 5 STL
    S5,
    /// STEP 7 STL
    S7,
}

impl From<DialectName> for Dialect {
    fn from(value: DialectName) -> Self {
        match value {
            DialectName::S5 => Dialect::Step5,
            DialectName::S7 => Dialect::Step7,
        }
    }
}

/// How the source files are read: every command that reads them shares these.
#[derive(Debug, clap::Args)]
pub struct LanguageArgs {
    /// Mnemonic set, instead of detecting it per file [default: detected per file]
    #[arg(long, value_enum)]
    pub mnemonics: Option<Mnemonics>,
    /// STL dialect: STEP 5 or STEP 7, instead of detecting it per file [default: detected per
    /// file]
    #[arg(long, value_enum)]
    pub dialect: Option<DialectName>,
    /// Accept awlsim's test operations (`__ASSERT==`, `__STWRST` and the like), which no real
    /// CPU knows [default: off]
    #[arg(long)]
    pub extended: bool,
}

impl LanguageArgs {
    pub fn language(&self) -> Language {
        Language {
            mnemonics: self.mnemonics.map(Into::into),
            dialect: self.dialect.map(Into::into),
            extensions: self.extended,
        }
    }
}

/// Options every command that reads source files shares.
#[derive(Debug, clap::Args)]
pub struct SourceOptions {
    /// STL source files (.awl) or an awlsim project (.awlpro)
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// CPU profile (see `awl cpus`) [default: the program's dialect's: speed7 for STEP 7 (an
    /// awlsim project is STEP 7), sinumerik-840c for STEP 5]
    #[arg(long, value_parser = profile::names())]
    pub cpu: Option<String>,
    #[command(flatten)]
    pub language: LanguageArgs,
    /// Assignment list giving operands names (`-START`), or a STEP 7 symbol table (`"Motor"`);
    /// repeatable [default: none]
    #[arg(long = "symbols", value_name = "FILE")]
    pub symbols: Vec<PathBuf>,
}

#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub source: SourceOptions,
    #[command(flatten)]
    pub output: run::OutputArgs,
}

#[derive(Debug, clap::Args)]
pub struct DumpArgs {
    #[command(flatten)]
    pub source: SourceOptions,
    /// Print the program as a STEP 5 PG listing (segments, statement numbers, `***`) that
    /// parses back to the same bytecode [default: off: the bytecode with annotations]
    #[arg(long)]
    pub listing: bool,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Parse and compile; print every error found
    Check(CheckArgs),
    /// Print each block's bytecode with source line numbers
    Dump(DumpArgs),
    /// Compile, start the CPU (STOP → STARTUP → RUN), run, print a summary
    Run(run::RunArgs),
    /// Program status: one invocation of a block, line by line (RLO, STA, ACCU 1/2, operand)
    Status(status::StatusArgs),
    /// Step debugger: breakpoints, stepping, operands, interrupts on request; simulated time
    /// stands still at the prompt
    Debug(debug::DebugArgs),
    /// The worst cases from the program, before it runs: each block's time and longest
    /// stretch, the response bounds, the nesting, the wake-up and watchdog risks
    Analyze(analyze::AnalyzeArgs),
    /// A virtual PLC: run the program in real time, reached over S7comm and Modbus TCP by
    /// HMIs, plant simulations and test scripts
    Serve(serve::ServeArgs),
    /// A language server over stdio for editors: diagnostics as you type, hover, go to
    /// definition, references, symbols, completion, quick fixes, semantic tokens, formatting
    #[command(
        after_long_help = "The editor starts it. `awl help lsp` gives the setup of VS Code, \
Neovim and Helix, the settings (`cpu`, `symbols`) and what the server offers."
    )]
    Lsp,
    /// A debug adapter over stdio for editors (the Debug Adapter Protocol): launch a program
    /// or attach to `awl serve --http`, breakpoints, stepping, OB levels as threads, registers
    #[command(
        after_long_help = "The editor starts it. `awl help dap` gives the setup of VS Code, \
Neovim (nvim-dap) and Helix, the launch and attach settings, and what the adapter offers."
    )]
    Dap,
    /// Run scenario files and check their [expect] and [[check]] tables
    Test(test::TestArgs),
    /// Run awlsim's test files (STEP 7 STL with `__ASSERT…`) as awlsim's harness does: PASS or
    /// FAIL per file
    Conformance(conformance::ConformanceArgs),
    /// List the CPU profiles with their rules and timings
    Cpus,
    /// Print the language, the mnemonics, a format (`awl help scenario`, `trace`, …), a
    /// diagnostic's page (`awl help error CODE`) or a command's help (`awl help run`)
    Help(help::HelpArgs),
}

pub const EXIT_OK: u8 = 0;
pub const EXIT_SOURCE_ERRORS: u8 = 1;
pub const EXIT_USAGE: u8 = 2;
pub const EXIT_STOP: u8 = 3;
pub const EXIT_EXPECTATION: u8 = 4;

pub fn run(cli: Cli) -> ExitCode {
    let mut console = Console::default();
    let code = match cli.command {
        Command::Check(options) => source::check(&options, &mut console),
        Command::Dump(options) => source::dump(&options, &mut console),
        Command::Run(args) => run::run(&args, &mut console),
        Command::Status(args) => status::status(&args, &mut console),
        Command::Debug(args) => debug::debug(&args, &mut console),
        Command::Test(args) => test::test(&args, &mut console),
        Command::Serve(args) => serve::serve(&args, &mut console),
        Command::Lsp => lsp(&mut console),
        Command::Dap => {
            crate::dap::serve_stdio();
            EXIT_OK
        }
        Command::Conformance(args) => conformance::conformance(&args, &mut console),
        Command::Analyze(args) => analyze::analyze(&args, &mut console),
        Command::Help(args) => help::help(&args, &mut console),
        Command::Cpus => {
            console.out(&crate::report::cpus());
            EXIT_OK
        }
    };
    console.finish(code)
}

/// `awl lsp`: the server speaks on stdout, so only its failure is reported (on stderr).
fn lsp(console: &mut Console) -> u8 {
    match crate::lsp::serve_stdio() {
        Ok(()) => EXIT_OK,
        Err(error) => {
            console.report(&miette::Report::new(error));
            EXIT_USAGE
        }
    }
}

/// The profile a `--cpu` value names (clap has checked it).
fn selected_profile(name: &str) -> &'static Profile {
    profile::find(name).expect("clap checked the profile's name")
}

pub use crate::diagnostics::plural;
