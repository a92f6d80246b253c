//! The debugger's engine, apart from any front end: the breakpoints (with their conditions, hit
//! counts and log messages), where the CPU pauses next, and why. The terminal prompt
//! ([`super::Session`]) and the debug adapter (`awl dap`) drive the same engine through
//! [`Front`], and [`Debugger`] is the probe that hands each operation to it.

use std::cell::RefCell;
use std::fmt;
use std::rc::Rc;

use crate::ast::BlockId;
use crate::compiler::Op;
use crate::trace::format_ms;
use crate::vm::probe::{Flow, Probe};
use crate::vm::stop::Stop;
use crate::vm::{Cpu, Mode};

use super::command::{self, BreakAt, Command, CommandError, Until};
use super::condition::{Condition, HitCondition, LogMessage};

/// When the CPU pauses next, apart from breakpoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resume {
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

impl Resume {
    /// How `command` (step, next, finish, continue, until) lets the CPU at `cpu` run on.
    pub fn after(cpu: &Cpu, command: &Command) -> Resume {
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

    fn reached(self, cpu: &Cpu) -> bool {
        let (levels, frames) = (cpu.levels.len(), cpu.frames.len());
        match self {
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
        }
    }
}

/// A breakpoint and what qualifies it (the debug adapter's conditions, hit counts and log
/// messages; the prompt sets none of them).
#[derive(Debug, Clone)]
pub struct Breakpoint {
    pub at: BreakAt,
    /// A block breakpoint's block and op.
    pub place: Option<(u16, u32)>,
    pub condition: Option<Condition>,
    pub hit_condition: Option<HitCondition>,
    /// A log point's message: logged, with `{OPERAND}`s replaced by their values, instead of a
    /// pause.
    pub log: Option<LogMessage>,
    /// How often it was reached with its condition true.
    pub hits: u64,
}

impl Breakpoint {
    pub fn new(at: BreakAt, place: Option<(u16, u32)>) -> Breakpoint {
        Breakpoint {
            at,
            place,
            condition: None,
            hit_condition: None,
            log: None,
            hits: 0,
        }
    }
}

/// What made the CPU pause.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Pause {
    /// Ctrl-C, or the editor's pause.
    Interrupted,
    /// Breakpoint `n` (counted from 1).
    Breakpoint(usize),
    /// Interrupt requests and services the breakpoints or the filters watch for.
    Events(Vec<Event>),
    /// The stepping command came to its end.
    Resumed(Resume),
}

/// An interrupt OB requested or serviced, which pauses before the next operation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    pub text: String,
    /// The breakpoint that watched for it; `None` for an exception filter.
    pub breakpoint: Option<usize>,
}

impl fmt::Display for Pause {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Pause::Interrupted => f.write_str("interrupted"),
            Pause::Breakpoint(n) => write!(f, "breakpoint {n}"),
            Pause::Events(events) => {
                let texts: Vec<&str> = events.iter().map(|event| event.text.as_str()).collect();
                f.write_str(&texts.join("; "))
            }
            Pause::Resumed(resume) => match resume {
                Resume::Start => f.write_str("start"),
                Resume::Step => f.write_str("step"),
                Resume::Next { .. } => f.write_str("next"),
                Resume::Finish { .. } => f.write_str("finish"),
                Resume::Continue => f.write_str("continue"),
                Resume::Until(ns) => write!(f, "until {}", format_ms(*ns)),
            },
        }
    }
}

/// Interrupt OBs to pause at without a breakpoint of their own (the editor's exception
/// filters).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Filters {
    /// When any interrupt OB starts being serviced.
    pub interrupt: bool,
    /// When any interrupt OB is requested.
    pub request: bool,
}

pub struct Engine {
    /// Deleted ones stay as `None`, so the numbers of the others hold.
    pub breakpoints: Vec<Option<Breakpoint>>,
    pub resume: Resume,
    pub filters: Filters,
    events: Vec<Event>,
    /// What log points said since the front end last took it.
    logged: Vec<String>,
}

impl Default for Engine {
    fn default() -> Self {
        Engine {
            breakpoints: Vec::new(),
            resume: Resume::Start,
            filters: Filters::default(),
            events: Vec::new(),
            logged: Vec::new(),
        }
    }
}

impl Engine {
    /// The number of the first breakpoint that `hits`, counted from 1 as the user counts them.
    pub fn breakpoint(&self, hits: impl Fn(&Breakpoint) -> bool) -> Option<usize> {
        let index = self
            .breakpoints
            .iter()
            .position(|b| b.as_ref().is_some_and(&hits));
        index.map(|index| index + 1)
    }

    /// Why the CPU pauses before the operation it is at, if it does; `interrupted` is the
    /// front end's pause.
    pub fn pause_reason(&mut self, cpu: &Cpu, interrupted: bool) -> Option<Pause> {
        if interrupted {
            return Some(Pause::Interrupted);
        }
        if !self.events.is_empty() {
            return Some(Pause::Events(std::mem::take(&mut self.events)));
        }
        if let Some(n) = self.breakpoint_here(cpu) {
            return Some(Pause::Breakpoint(n));
        }
        self.resume
            .reached(cpu)
            .then_some(Pause::Resumed(self.resume))
    }

    /// The first breakpoint at the operation `cpu` is at whose condition holds and whose hit
    /// count is reached; a log point there logs and lets the CPU go on.
    fn breakpoint_here(&mut self, cpu: &Cpu) -> Option<usize> {
        let here = Some((cpu.level.block, cpu.level.pc));
        for (index, slot) in self.breakpoints.iter_mut().enumerate() {
            let Some(breakpoint) = slot.as_mut().filter(|b| b.place == here) else {
                continue;
            };
            if !breakpoint.condition.as_ref().is_none_or(|c| c.holds(cpu)) {
                continue;
            }
            breakpoint.hits += 1;
            let hits = breakpoint.hits;
            if !breakpoint.hit_condition.is_none_or(|h| h.reached(hits)) {
                continue;
            }
            match &breakpoint.log {
                Some(message) => self.logged.push(message.render(cpu)),
                None => return Some(index + 1),
            }
        }
        None
    }

    /// What log points said since the last call.
    pub fn take_logged(&mut self) -> Vec<String> {
        std::mem::take(&mut self.logged)
    }

    /// Where a breakpoint on `block` (on `line`, or at its first operation) stops.
    pub fn block_place(
        cpu: &Cpu,
        block: BlockId,
        line: Option<u32>,
    ) -> Result<(u16, u32), CommandError> {
        let Some(index) = cpu.program.block_index(block) else {
            let reason = format!("the program has no {block}");
            return Err(command::usage("break", reason));
        };
        let lines = cpu.program.blocks[usize::from(index)].spans.len() as u32;
        let pc = match line {
            None => Some(0),
            Some(line) => (0..lines).find(|pc| cpu.line_of(index, *pc) == line),
        };
        let Some(pc) = pc.filter(|_| lines > 0) else {
            let (first, last) = (cpu.line_of(index, 0), cpu.line_of(index, lines.max(1) - 1));
            let reason = format!(
                "{block} has no operation on line {}; its operations are on lines {first}–{last}",
                line.unwrap_or(0)
            );
            return Err(command::usage("break", reason));
        };
        Ok((index, pc))
    }

    /// Checks `at` against the program and adds it; its number.
    pub fn add(&mut self, cpu: &Cpu, at: BreakAt) -> Result<usize, CommandError> {
        let place = match at {
            BreakAt::Block { block, line } => Some(Engine::block_place(cpu, block, line)?),
            BreakAt::Request(ob) | BreakAt::Service(ob) => {
                if cpu.profile.interrupt_ob(ob).is_none() {
                    let reason = format!("OB {ob} is no interrupt OB of the {}", cpu.profile.name);
                    return Err(command::usage("break", reason));
                }
                None
            }
        };
        Ok(self.insert(Breakpoint::new(at, place)))
    }

    /// Adds a breakpoint already checked; its number.
    pub fn insert(&mut self, breakpoint: Breakpoint) -> usize {
        self.breakpoints.push(Some(breakpoint));
        self.breakpoints.len()
    }

    /// The interrupt request for `ob`, made at `at_ns`, has been taken in.
    pub fn requested(&mut self, cpu: &Cpu, ob: u8, at_ns: u64) {
        let breakpoint = self.breakpoint(|b| b.at == BreakAt::Request(ob));
        if breakpoint.is_none() && !self.filters.request {
            return;
        }
        let taken = format!(
            "request for OB {ob}, made at {}, taken in at {}",
            format_ms(at_ns),
            format_ms(cpu.clock)
        );
        let text = match breakpoint {
            Some(n) => format!("breakpoint {n}: {taken}"),
            None => taken,
        };
        self.events.push(Event { text, breakpoint });
    }

    /// The engine starts servicing `ob`.
    pub fn serviced(&mut self, cpu: &Cpu, ob: u8) {
        let breakpoint = self.breakpoint(|b| b.at == BreakAt::Service(ob));
        if breakpoint.is_none() && !self.filters.interrupt {
            return;
        }
        let serviced = format!("OB {ob} serviced at {}", format_ms(cpu.clock));
        let text = match breakpoint {
            Some(n) => format!("breakpoint {n}: {serviced}"),
            None => serviced,
        };
        self.events.push(Event { text, breakpoint });
    }
}

/// The block `symbol` (`"Valve"`, `-FILL`) names in the program's symbols; the close block
/// names when it names none.
pub fn named_block(cpu: &Cpu, symbol: &str) -> Result<BlockId, CommandError> {
    let symbols = &cpu.program.symbols;
    symbols.block_of(symbol).ok_or_else(|| {
        let reason = match symbols.suggest_block(symbol) {
            Some(hint) => format!("no block is named {symbol}; {hint}"),
            None => format!("no block is named {symbol}"),
        };
        command::usage("break", reason)
    })
}

pub fn describe(cpu: &Cpu, at: BreakAt, place: Option<(u16, u32)>) -> String {
    match (at, place) {
        (BreakAt::Request(ob), _) => format!("requests for OB {ob}"),
        (BreakAt::Service(ob), _) => format!("OB {ob} being serviced"),
        (BreakAt::Block { block, .. }, Some((index, pc))) => {
            format!("{block} line {}", cpu.line_of(index, pc))
        }
        (BreakAt::Block { block, .. }, None) => block.to_string(),
    }
}

/// A front end of the engine: where it asks what to do when the CPU pauses.
pub trait Front {
    fn engine(&mut self) -> &mut Engine;

    /// Whether the user asked for a pause (looked at before every operation, so it is cheap).
    fn interrupted(&mut self, cpu: &mut Cpu) -> bool;

    /// The CPU pauses before its next operation: takes commands until one lets it go on.
    fn pause(&mut self, cpu: &mut Cpu, pause: &Pause) -> Flow;

    /// What a log point said.
    fn log(&mut self, text: &str);

    /// The CPU is about to go to STOP: a front end may pause there (the `stop` filter).
    fn stopping(&mut self, _cpu: &mut Cpu, _stop: &Stop) {}
}

/// The probe the CPU holds; the front end is kept outside too, for after the run.
pub struct Debugger<F>(pub Rc<RefCell<F>>);

impl<F: Front> Probe for Debugger<F> {
    fn before(&mut self, cpu: &mut Cpu) -> Flow {
        let mut front = self.0.borrow_mut();
        let interrupted = front.interrupted(cpu);
        let pause = front.engine().pause_reason(cpu, interrupted);
        for text in front.engine().take_logged() {
            front.log(&text);
        }
        match pause {
            Some(pause) => front.pause(cpu, &pause),
            None => Flow::Go,
        }
    }

    fn after(&mut self, _cpu: &Cpu, _block: u16, _pc: u32, _op: Op) -> Flow {
        Flow::Go
    }

    fn requested(&mut self, cpu: &Cpu, ob: u8, at_ns: u64) {
        self.0.borrow_mut().engine().requested(cpu, ob, at_ns);
    }

    fn serviced(&mut self, cpu: &Cpu, ob: u8) {
        self.0.borrow_mut().engine().serviced(cpu, ob);
    }

    fn stopping(&mut self, cpu: &mut Cpu, stop: &Stop) {
        self.0.borrow_mut().stopping(cpu, stop);
    }
}
