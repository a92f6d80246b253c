//! `awl debug`: the step debugger on a prompt, or on a script of commands.

use std::cell::RefCell;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::rc::Rc;

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::debug::input::Input;
use crate::debug::{Debugger, Session};
use crate::runner;

use super::run::{ProgramArgs, RunLength, not_run, program_options};
use super::terminal::in_foreground;
use super::watch::{install_handler, take_interrupt};
use super::{Console, EXIT_OK, EXIT_STOP, EXIT_USAGE};

#[derive(Debug, clap::Args)]
pub struct DebugArgs {
    #[command(flatten)]
    pub program: ProgramArgs,
    #[command(flatten)]
    pub length: RunLength,
    /// Run the commands in FILE, one per line, echoed, instead of prompting (standard input
    /// that is no terminal is read the same way) [default: a prompt on a terminal]
    #[arg(long, value_name = "FILE")]
    pub commands: Option<PathBuf>,
}

#[derive(Debug, Error, Diagnostic)]
#[error("cannot read the commands in `{path}`: {reason}")]
#[diagnostic(
    code(awl::debug::commands_file),
    help("give a text file with one debugger command per line")
)]
struct CommandsFileError {
    path: String,
    reason: String,
}

#[derive(Debug, Error, Diagnostic)]
#[error("awl debug runs in the background, so the terminal is not its to prompt on")]
#[diagnostic(
    code(awl::debug::background),
    help("run it in the foreground (`fg`), or give the commands with `--commands FILE`")
)]
struct BackgroundError;

#[derive(Debug, Error, Diagnostic)]
enum InputError {
    #[error(transparent)]
    #[diagnostic(transparent)]
    CommandsFile(#[from] CommandsFileError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Background(#[from] BackgroundError),
}

fn input(args: &DebugArgs) -> Result<Input, InputError> {
    let stdin = std::io::stdin();
    match &args.commands {
        Some(path) => std::fs::read_to_string(path)
            .map(|text| Input::script(&text))
            .map_err(|error| {
                CommandsFileError {
                    path: path.display().to_string(),
                    reason: error.to_string(),
                }
                .into()
            }),
        None if in_foreground(&stdin) => Ok(Input::prompt().unwrap_or_else(Input::stdin)),
        // Reading a terminal another job holds would stop awl (SIGTTIN) until it is killed.
        None if stdin.is_terminal() => Err(BackgroundError.into()),
        None => Ok(Input::stdin()),
    }
}

pub fn debug(args: &DebugArgs, console: &mut Console) -> u8 {
    let input = match input(args) {
        Ok(input) => input,
        Err(error) => {
            console.report(&Report::new(error));
            return EXIT_USAGE;
        }
    };
    let options = runner::RunOptions {
        limit: args.length.limit(),
        ..program_options(&args.program)
    };
    let mut prepared = match runner::prepare(&options) {
        Ok(prepared) => prepared,
        Err(reason) => return not_run("debug", reason, console),
    };
    console.reports(&prepared.take_warnings());
    install_handler();
    let session = Rc::new(RefCell::new(Session::new(
        input,
        prepared.mnemonics,
        take_interrupt,
    )));
    prepared.cpu.probe = Some(Box::new(Debugger(Rc::clone(&session))));
    let ran = prepared.run(&mut |_| true);
    console.reports(&ran.warnings);
    if let Some(stop) = &ran.outcome.stop {
        console.err(&format!("{:?}\n", runner::stop_report(&ran, stop)));
    }
    let mut session = session.borrow_mut();
    session.after_run(&ran.cpu, ran.outcome.stop.as_ref());
    if session.failed_commands > 0 {
        EXIT_USAGE
    } else if ran.outcome.stop.is_some() {
        EXIT_STOP
    } else {
        EXIT_OK
    }
}
