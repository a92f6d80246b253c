//! The step debugger: a probe on the stepping loop that pauses before an operation — at the
//! start of OB 1, after a step, at a breakpoint, at a request or service of an interrupt OB —
//! and reads commands while simulated time stands still. After the run (its end, a STOP) the
//! CPU can still be inspected.

pub mod command;
pub mod condition;
pub mod engine;
pub mod input;
pub mod show;

pub use show::{force, write};

use std::io::Write;

use miette::Report;

use crate::mnemonics::MnemonicSet;
use crate::state::{self, State};
use crate::trace::format_ms;
use crate::vm::Cpu;
use crate::vm::probe::Flow;
use crate::vm::stop::Stop;

use command::{BreakAt, COMMANDS, Command, CommandError};
pub use engine::{Debugger, Engine, Front, Pause, Resume, describe, named_block};
use input::{Input, Line};

/// Whether a Ctrl-C asked to pause (the command line's handler).
pub type Interrupted = fn() -> bool;

pub struct Session {
    input: Input,
    mnemonics: MnemonicSet,
    engine: Engine,
    interrupted: Interrupted,
    /// The last command that ran the CPU on: an empty line at the prompt repeats it.
    last_resume: Option<Command>,
    /// Commands that could not be taken.
    pub failed_commands: u64,
    /// `quit`, the end of the commands, or an output that is gone.
    pub quit: bool,
    /// Where the session's words go when they are not printed (the playground shows them).
    transcript: Option<String>,
}

fn say(text: &str) -> bool {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .is_ok()
}

impl Session {
    pub fn new(input: Input, mnemonics: MnemonicSet, interrupted: Interrupted) -> Self {
        Session {
            input,
            mnemonics,
            engine: Engine::default(),
            interrupted,
            last_resume: None,
            failed_commands: 0,
            quit: false,
            transcript: None,
        }
    }

    /// A session on a script whose words are kept for [`Session::take_transcript`], not
    /// printed.
    pub fn recording(commands: &str, mnemonics: MnemonicSet) -> Self {
        Session {
            transcript: Some(String::new()),
            ..Session::new(Input::script(commands), mnemonics, || false)
        }
    }

    /// What a recording session said so far.
    pub fn take_transcript(&mut self) -> String {
        self.transcript
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    fn out(&mut self, text: &str) {
        match &mut self.transcript {
            Some(transcript) => transcript.push_str(text),
            None => {
                if !say(text) {
                    self.quit = true;
                }
            }
        }
    }

    fn fail(&mut self, error: CommandError) {
        self.failed_commands += 1;
        let report = Report::new(error);
        match &mut self.transcript {
            Some(transcript) => transcript.push_str(&crate::diagnostics::render_plain(&report)),
            None => {
                let _ = writeln!(std::io::stderr(), "{report:?}");
            }
        }
    }

    /// Reads and runs commands until one lets the CPU run on.
    fn pause(&mut self, cpu: &mut Cpu, reason: &str) -> Flow {
        self.out(&format!("[{reason}] {}", show::location(cpu)));
        while !self.quit {
            let command = match self.next_command() {
                Some(command) => command,
                None => continue,
            };
            match command {
                Command::Quit => self.quit = true,
                command if command.resumes() => {
                    self.engine.resume = Resume::after(cpu, &command);
                    self.last_resume = Some(command);
                    return Flow::Go;
                }
                Command::Set { operand, value } => {
                    match show::force(cpu, &operand, value, self.mnemonics) {
                        Ok(text) => self.out(&text),
                        Err(reason) => self.fail(command::usage("set", reason)),
                    }
                }
                Command::Fire(ob) => self.fire(cpu, ob),
                Command::Break(at) => self.add_breakpoint(cpu, at),
                Command::BreakNamed { symbol, line } => match named_block(cpu, &symbol) {
                    Ok(block) => self.add_breakpoint(cpu, BreakAt::Block { block, line }),
                    Err(error) => self.fail(error),
                },
                other => self.inspect(cpu, None, &other),
            }
        }
        Flow::Halt
    }

    /// The next command, `None` when the line held none (or could not be parsed).
    fn next_command(&mut self) -> Option<Command> {
        let mut echoed = String::new();
        let line = self.input.next_line(&mut |echo| echoed.push_str(echo));
        self.out(&echoed);
        let line = match line {
            Line::Text(line) => line,
            Line::Cancelled => return None,
            Line::End => {
                // A recording session pauses where its commands end: the playground goes on
                // from there with the next command.
                if self.input.is_script() && self.transcript.is_none() {
                    self.out("(end of commands: quit)\n");
                }
                self.quit = true;
                return None;
            }
        };
        match command::parse(&line) {
            Some(Ok(command)) => Some(command),
            Some(Err(error)) => {
                self.fail(error);
                None
            }
            // An empty line at the prompt runs the last step, next, … again.
            None if !self.input.is_script() && line.trim().is_empty() => self.last_resume.clone(),
            None => None,
        }
    }

    fn fire(&mut self, cpu: &mut Cpu, ob: u8) {
        if cpu.profile.interrupt_ob(ob).is_none() {
            let reason = format!("OB {ob} is no interrupt OB of the {}", cpu.profile.name);
            return self.fail(command::usage("fire", reason));
        }
        let text = if cpu.fire(ob) {
            format!(
                "OB {ob} requested at {}: it runs at the next interrupt point where it outranks the running level\n",
                format_ms(cpu.clock)
            )
        } else {
            format!(
                "the request for OB {ob} is not pending: the program has no OB {ob}, it is pending already, or the CPU ignores it now\n"
            )
        };
        self.out(&text);
    }

    fn add_breakpoint(&mut self, cpu: &Cpu, at: BreakAt) {
        match self.engine.add(cpu, at) {
            Ok(n) => {
                let place = self.engine.breakpoints[n - 1]
                    .as_ref()
                    .and_then(|b| b.place);
                self.out(&format!("breakpoint {n}: {}\n", describe(cpu, at, place)));
            }
            Err(error) => self.fail(error),
        }
    }

    /// The commands that only look (and those on breakpoints), live or after the run.
    fn inspect(&mut self, cpu: &Cpu, stop: Option<&Stop>, command: &Command) {
        let text = match command {
            Command::Breakpoints => {
                let listed: Vec<String> = self
                    .engine
                    .breakpoints
                    .iter()
                    .enumerate()
                    .filter_map(|(n, b)| b.as_ref().map(|b| (n, b)))
                    .map(|(n, b)| format!("{}: {}\n", n + 1, describe(cpu, b.at, b.place)))
                    .collect();
                if listed.is_empty() {
                    "no breakpoints\n".to_string()
                } else {
                    listed.concat()
                }
            }
            Command::Delete(None) => {
                let breakpoints = &mut self.engine.breakpoints;
                let count = breakpoints.iter().flatten().count() as u64;
                breakpoints.iter_mut().for_each(|b| *b = None);
                format!(
                    "deleted {}\n",
                    crate::diagnostics::plural(count, "breakpoint")
                )
            }
            Command::Delete(Some(n)) => match self.engine.breakpoints.get_mut(n.wrapping_sub(1)) {
                Some(slot @ Some(_)) => {
                    *slot = None;
                    format!("deleted breakpoint {n}\n")
                }
                _ => return self.fail(command::usage("delete", format!("no breakpoint {n}"))),
            },
            Command::Print(operands) => match show::print(cpu, operands, self.mnemonics) {
                Ok(text) => text,
                Err(reason) => return self.fail(command::usage("print", reason)),
            },
            Command::Accu => show::accumulators(cpu),
            Command::Status => show::status_word(cpu),
            Command::Stack => show::stack(cpu),
            Command::Levels => match stop {
                Some(stop) => show::levels(&state::levels(cpu, stop)),
                None => show::levels(&state::levels_now(cpu)),
            },
            Command::List => show::listing(cpu),
            Command::State => {
                let title = format!("state at {}", format_ms(cpu.clock));
                state::text::render_titled(&State::capture(cpu, stop), &title)
            }
            Command::Help => COMMANDS
                .iter()
                .map(|(_, short, usage)| match short {
                    &"" => format!("  {usage}\n"),
                    short => format!("  {usage}   [{short}]\n"),
                })
                .collect(),
            Command::Break(_)
            | Command::BreakNamed { .. }
            | Command::Step
            | Command::Next
            | Command::Finish
            | Command::Continue
            | Command::Until(_)
            | Command::Set { .. }
            | Command::Fire(_)
            | Command::Quit => {
                let command = command.name();
                return self.fail(CommandError::RunEnded { command });
            }
        };
        self.out(&text);
    }

    /// After the run: says how it ended, then takes inspection commands until `quit`.
    pub fn after_run(&mut self, cpu: &Cpu, stop: Option<&Stop>) {
        if self.quit {
            return;
        }
        let how = match stop {
            Some(stop) => format!("the CPU went to STOP ({})", stop.cause.code()),
            None => "the run reached its end".to_string(),
        };
        self.out(&format!(
            "[end] {how} at {}, after {}\n",
            format_ms(cpu.clock),
            crate::diagnostics::plural(cpu.cycle, "cycle")
        ));
        while !self.quit {
            match self.next_command() {
                Some(Command::Quit) => self.quit = true,
                Some(command) => self.inspect(cpu, stop, &command),
                None => {}
            }
        }
    }
}

impl Front for Session {
    fn engine(&mut self) -> &mut Engine {
        &mut self.engine
    }

    fn interrupted(&mut self, _cpu: &mut Cpu) -> bool {
        (self.interrupted)()
    }

    fn pause(&mut self, cpu: &mut Cpu, pause: &Pause) -> Flow {
        Session::pause(self, cpu, &pause.to_string())
    }

    fn log(&mut self, text: &str) {
        self.out(&format!("{text}\n"));
    }
}
