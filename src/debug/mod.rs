//! The step debugger: a probe on the stepping loop that pauses before an operation — at the
//! start of OB 1, after a step, at a breakpoint, at a request or service of an interrupt OB —
//! and reads commands while simulated time stands still. After the run (its end, a STOP) the
//! CPU can still be inspected.

pub mod command;
pub mod input;
mod show;

pub use show::{force, write};

use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

use miette::Report;

use crate::compiler::Op;
use crate::mnemonics::MnemonicSet;
use crate::state::{self, State};
use crate::trace::format_ms;
use crate::vm::probe::{Flow, Probe};
use crate::vm::stop::Stop;
use crate::vm::{Cpu, Mode};

use command::{BreakAt, COMMANDS, Command, CommandError, Until};
use input::{Input, Line};

/// When the CPU pauses next, apart from breakpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Resume {
    /// Before the first operation of OB 1 (or of any block, without one).
    Start,
    Step,
    /// At the next operation on this level at this depth or above.
    Next {
        levels: usize,
        frames: usize,
    },
    /// Once the running block has returned (or its level, or OB 1's cycle, has ended).
    Finish {
        levels: usize,
        frames: usize,
        cycle: u64,
    },
    Continue,
    /// At the first operation at or after this simulated time.
    Until(u64),
}

#[derive(Debug, Clone, Copy)]
struct Breakpoint {
    at: BreakAt,
    /// A block breakpoint's block and op.
    place: Option<(u16, u32)>,
}

/// Whether a Ctrl-C asked to pause (the command line's handler).
pub type Interrupted = fn() -> bool;

pub struct Session {
    input: Input,
    mnemonics: MnemonicSet,
    breakpoints: Vec<Option<Breakpoint>>,
    resume: Resume,
    /// Why the next operation pauses, from request and service breakpoints.
    events: Vec<String>,
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
            breakpoints: Vec::new(),
            resume: Resume::Start,
            events: Vec::new(),
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

    /// The number of the first breakpoint that `hits`, counted from 1 as the user counts them.
    fn breakpoint(&self, hits: impl Fn(&Breakpoint) -> bool) -> Option<usize> {
        let index = self
            .breakpoints
            .iter()
            .position(|b| b.is_some_and(|b| hits(&b)));
        index.map(|index| index + 1)
    }

    /// Why the CPU pauses before the operation it is at, if it does.
    fn pause_reason(&mut self, cpu: &Cpu) -> Option<String> {
        if (self.interrupted)() {
            return Some("interrupted".into());
        }
        if !self.events.is_empty() {
            return Some(std::mem::take(&mut self.events).join("; "));
        }
        let here = (cpu.level.block, cpu.level.pc);
        if let Some(n) = self.breakpoint(|b| b.place == Some(here)) {
            return Some(format!("breakpoint {n}"));
        }
        let (levels, frames) = (cpu.levels.len(), cpu.frames.len());
        let pause = match self.resume {
            Resume::Start => cpu.program.ob(1).is_none_or(|ob1| {
                cpu.mode == Mode::Run && cpu.level.block == ob1 && cpu.level.pc == 0
            }),
            Resume::Step => true,
            Resume::Next {
                levels: l,
                frames: f,
            } => levels < l || (levels == l && frames <= f),
            Resume::Finish {
                levels: l,
                frames: f,
                cycle,
            } => levels < l || (levels == l && (frames < f || cpu.cycle != cycle)),
            Resume::Continue => false,
            Resume::Until(ns) => cpu.clock >= ns,
        };
        pause.then(|| match self.resume {
            Resume::Start => "start".to_string(),
            Resume::Step => "step".to_string(),
            Resume::Next { .. } => "next".to_string(),
            Resume::Finish { .. } => "finish".to_string(),
            Resume::Continue => "continue".to_string(),
            Resume::Until(ns) => format!("until {}", format_ms(ns)),
        })
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
                    self.resume = self.resume_for(cpu, &command);
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

    fn resume_for(&self, cpu: &Cpu, command: &Command) -> Resume {
        let (levels, frames) = (cpu.levels.len(), cpu.frames.len());
        match command {
            Command::Step => Resume::Step,
            Command::Next => Resume::Next { levels, frames },
            Command::Finish => Resume::Finish {
                levels,
                frames,
                cycle: cpu.cycle,
            },
            Command::Until(Until::At(ns)) => Resume::Until(*ns),
            Command::Until(Until::After(ns)) => Resume::Until(cpu.clock.saturating_add(*ns)),
            _ => Resume::Continue,
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
        let place = match at {
            BreakAt::Block { block, line } => {
                let Some(index) = cpu.program.block_index(block) else {
                    let reason = format!("the program has no {block}");
                    return self.fail(command::usage("break", reason));
                };
                let lines = cpu.program.blocks[usize::from(index)].spans.len() as u32;
                let pc = match line {
                    None => Some(0),
                    Some(line) => (0..lines).find(|pc| cpu.line_of(index, *pc) == line),
                };
                let Some(pc) = pc.filter(|_| lines > 0) else {
                    let (first, last) = (cpu.line_of(index, 0), cpu.line_of(index, lines - 1));
                    let reason = format!(
                        "{block} has no operation on line {}; its operations are on lines {first}–{last}",
                        line.unwrap_or(0)
                    );
                    return self.fail(command::usage("break", reason));
                };
                Some((index, pc))
            }
            BreakAt::Request(ob) | BreakAt::Service(ob) => {
                if cpu.profile.interrupt_ob(ob).is_none() {
                    let reason = format!("OB {ob} is no interrupt OB of the {}", cpu.profile.name);
                    return self.fail(command::usage("break", reason));
                }
                None
            }
        };
        self.breakpoints.push(Some(Breakpoint { at, place }));
        let n = self.breakpoints.len();
        self.out(&format!("breakpoint {n}: {}\n", describe(cpu, at, place)));
    }

    /// The commands that only look (and those on breakpoints), live or after the run.
    fn inspect(&mut self, cpu: &Cpu, stop: Option<&Stop>, command: &Command) {
        let text = match command {
            Command::Breakpoints => {
                let listed: Vec<String> = self
                    .breakpoints
                    .iter()
                    .enumerate()
                    .filter_map(|(n, b)| b.map(|b| (n, b)))
                    .map(|(n, b)| format!("{}: {}\n", n + 1, describe(cpu, b.at, b.place)))
                    .collect();
                if listed.is_empty() {
                    "no breakpoints\n".to_string()
                } else {
                    listed.concat()
                }
            }
            Command::Delete(None) => {
                let count = self.breakpoints.iter().flatten().count() as u64;
                self.breakpoints.iter_mut().for_each(|b| *b = None);
                format!(
                    "deleted {}\n",
                    crate::diagnostics::plural(count, "breakpoint")
                )
            }
            Command::Delete(Some(n)) => match self.breakpoints.get_mut(n.wrapping_sub(1)) {
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

/// The block `symbol` (`"Valve"`, `-FILL`) names in the program's symbols; the close block
/// names when it names none.
fn named_block(cpu: &Cpu, symbol: &str) -> Result<crate::ast::BlockId, CommandError> {
    let symbols = &cpu.program.symbols;
    symbols.block_of(symbol).ok_or_else(|| {
        let reason = match symbols.suggest_block(symbol) {
            Some(hint) => format!("no block is named {symbol}; {hint}"),
            None => format!("no block is named {symbol}"),
        };
        command::usage("break", reason)
    })
}

fn describe(cpu: &Cpu, at: BreakAt, place: Option<(u16, u32)>) -> String {
    match (at, place) {
        (BreakAt::Request(ob), _) => format!("requests for OB {ob}"),
        (BreakAt::Service(ob), _) => format!("OB {ob} being serviced"),
        (BreakAt::Block { block, .. }, Some((index, pc))) => {
            format!("{block} line {}", cpu.line_of(index, pc))
        }
        (BreakAt::Block { block, .. }, None) => block.to_string(),
    }
}

/// The probe the CPU holds; the command line keeps the session for after the run.
pub struct Debugger(pub Rc<RefCell<Session>>);

impl Probe for Debugger {
    fn before(&mut self, cpu: &mut Cpu) -> Flow {
        let mut session = self.0.borrow_mut();
        match session.pause_reason(cpu) {
            Some(reason) => session.pause(cpu, &reason),
            None => Flow::Go,
        }
    }

    fn after(&mut self, _cpu: &Cpu, _block: u16, _pc: u32, _op: Op) -> Flow {
        Flow::Go
    }

    fn requested(&mut self, cpu: &Cpu, ob: u8, at_ns: u64) {
        let mut session = self.0.borrow_mut();
        if let Some(n) = session.breakpoint(|b| b.at == BreakAt::Request(ob)) {
            session.events.push(format!(
                "breakpoint {n}: request for OB {ob}, made at {}, taken in at {}",
                format_ms(at_ns),
                format_ms(cpu.clock)
            ));
        }
    }

    fn serviced(&mut self, cpu: &Cpu, ob: u8) {
        let mut session = self.0.borrow_mut();
        if let Some(n) = session.breakpoint(|b| b.at == BreakAt::Service(ob)) {
            session.events.push(format!(
                "breakpoint {n}: OB {ob} serviced at {}",
                format_ms(cpu.clock)
            ));
        }
    }
}
