//! Program status (a PG's STATUS BAUSTEIN): one invocation of a block, recorded operation by
//! operation — RLO, STA, ACCU 1, ACCU 2 and the operand after each — by a [`Probe`] on the
//! stepping loop. A loop body keeps its last pass and a count.

pub mod block;
pub(crate) mod operand;
mod text;

use std::cell::RefCell;
use std::rc::Rc;

use crate::compiler::Op;
use crate::vm::Cpu;
use crate::vm::probe::{Flow, Probe};

pub use block::BlockRef;
pub use text::{accu, render, statements};

/// Which invocation to record.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Window {
    /// The first one in this cycle.
    Cycle(u64),
    /// The first one that begins at or after this simulated time.
    At(u64),
}

impl Window {
    fn is_open(self, cpu: &Cpu) -> bool {
        match self {
            Window::Cycle(cycle) => cpu.cycle == cycle,
            Window::At(ns) => cpu.clock >= ns,
        }
    }

    fn has_passed(self, cpu: &Cpu) -> bool {
        matches!(self, Window::Cycle(cycle) if cpu.cycle > cycle)
    }
}

/// What one operation left behind on its last pass.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OpStatus {
    /// How often it ran in the invocation (a loop runs it more than once).
    pub runs: u64,
    pub rlo: bool,
    pub sta: bool,
    pub accu1: u32,
    pub accu2: u32,
    pub operand: Option<String>,
}

/// When the recorded invocation began, and on which processing level.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Invocation {
    pub cycle: u64,
    pub t_ns: u64,
    /// The OB at the bottom of the level that ran it.
    pub level: String,
    levels: usize,
    frames: usize,
}

/// An interrupt OB that ran inside the recorded invocation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Interruption {
    /// The op of the block after which it was serviced; `None`: before the first.
    pub after_pc: Option<u32>,
    pub ob: u8,
    pub t_ns: u64,
}

/// The recording: per op of the block, its status (`None`: not run).
#[derive(Debug, Clone, Default)]
pub struct Recording {
    pub invocation: Option<Invocation>,
    pub ops: Vec<Option<OpStatus>>,
    pub interruptions: Vec<Interruption>,
    /// The invocation ran to its block end.
    pub complete: bool,
    /// A STEP 7 program: values in STEP 7 spelling.
    pub step7: bool,
}

/// The probe that records one invocation of `block`, then halts the run (or, going on, leaves
/// the CPU).
pub struct Recorder {
    block: u16,
    window: Window,
    /// Only an invocation on the level of this OB (its block index).
    level: Option<u16>,
    /// The run goes on after the invocation; the probe leaves.
    going_on: bool,
    recording: Rc<RefCell<Recording>>,
    /// The last op of the block ran was a jump back to its first op (no new invocation).
    jumped_to_start: bool,
    /// A conditional block end ran: whether it ended the block shows at the next op.
    conditional_end: Option<u32>,
    /// The invocation's last op that ran.
    last_pc: Option<u32>,
}

impl Recorder {
    pub fn new(block: u16, ops: usize, window: Window) -> (Recorder, Rc<RefCell<Recording>>) {
        let recording = Rc::new(RefCell::new(Recording {
            ops: vec![None; ops],
            ..Recording::default()
        }));
        let recorder = Recorder {
            block,
            window,
            level: None,
            going_on: false,
            recording: Rc::clone(&recording),
            jumped_to_start: false,
            conditional_end: None,
            last_pc: None,
        };
        (recorder, recording)
    }

    /// Records only an invocation on the level of OB block `level` (the online page's
    /// "calling level").
    pub fn on_level(self, level: u16) -> Recorder {
        Recorder {
            level: Some(level),
            ..self
        }
    }

    /// Lets the run go on after the invocation, without the probe (the online page's program
    /// status, on a running CPU).
    pub fn going_on(self) -> Recorder {
        Recorder {
            going_on: true,
            ..self
        }
    }

    fn inside(&self, cpu: &Cpu, block: u16) -> bool {
        let recording = self.recording.borrow();
        recording.invocation.as_ref().is_some_and(|invocation| {
            block == self.block
                && cpu.levels.len() == invocation.levels
                && cpu.frames.len() == invocation.frames
        })
    }

    fn begin(&mut self, cpu: &Cpu) {
        self.recording.borrow_mut().step7 = cpu.program.s7.step7;
        self.recording.borrow_mut().invocation = Some(Invocation {
            cycle: cpu.cycle,
            t_ns: cpu.clock,
            level: cpu.block_id(cpu.level_block()).to_string(),
            levels: cpu.levels.len(),
            frames: cpu.frames.len(),
        });
    }

    fn finish(&mut self) -> Flow {
        self.recording.borrow_mut().complete = true;
        if self.going_on { Flow::Go } else { Flow::Halt }
    }
}

impl Probe for Recorder {
    fn before(&mut self, cpu: &mut Cpu) -> Flow {
        if let Some(end_pc) = self.conditional_end.take() {
            let fell_through = self.inside(cpu, cpu.level.block) && cpu.level.pc == end_pc + 1;
            if !fell_through {
                return self.finish();
            }
        }
        let started = self.recording.borrow().invocation.is_some();
        if started {
            return Flow::Go;
        }
        if self.window.has_passed(cpu) {
            return Flow::Halt;
        }
        let entry = cpu.level.block == self.block && cpu.level.pc == 0 && !self.jumped_to_start;
        let on_level = self.level.is_none_or(|level| cpu.level_block() == level);
        if entry && on_level && self.window.is_open(cpu) {
            self.begin(cpu);
        }
        Flow::Go
    }

    fn after(&mut self, cpu: &Cpu, block: u16, pc: u32, op: Op) -> Flow {
        self.jumped_to_start = block == self.block && matches!(op, Op::Jump(_, 0));
        if !self.inside(cpu, block) {
            return Flow::Go;
        }
        self.last_pc = Some(pc);
        {
            let mut recording = self.recording.borrow_mut();
            let Some(slot) = recording.ops.get_mut(pc as usize) else {
                return Flow::Go;
            };
            let runs = slot.as_ref().map_or(0, |status| status.runs) + 1;
            *slot = Some(OpStatus {
                runs,
                rlo: cpu.level.status.rlo(),
                sta: cpu.level.status.sta(),
                accu1: cpu.level.accu1,
                accu2: cpu.level.accu2,
                operand: operand::value(cpu, op),
            });
        }
        match op {
            Op::BlockEnd | Op::BlockEndUnconditional => self.finish(),
            Op::BlockEndConditional => {
                self.conditional_end = Some(pc);
                Flow::Go
            }
            _ => Flow::Go,
        }
    }

    fn done(&self) -> bool {
        self.going_on && self.recording.borrow().complete
    }

    fn serviced(&mut self, cpu: &Cpu, ob: u8) {
        let mut recording = self.recording.borrow_mut();
        if recording.invocation.is_some() && !recording.complete {
            recording.interruptions.push(Interruption {
                after_pc: self.last_pc,
                ob,
                t_ns: cpu.clock,
            });
        }
    }
}

/// Why program status has nothing to show.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
pub enum StatusError {
    #[error("the program has no {block}")]
    /// `hint`: a did-you-mean for a symbol, ending in a space, or empty.
    #[diagnostic(
        code(awl::status::unknown_block),
        help("{hint}its logic blocks: {known}")
    )]
    UnknownBlock {
        block: String,
        hint: String,
        known: String,
    },
    #[error("{block} is a data block: program status shows logic blocks")]
    #[diagnostic(
        code(awl::status::data_block),
        help(
            "name an OB, PB, SB, FB or FX (STEP 7: OB, FC, FB); `awl run --state` shows the data blocks' words"
        )
    )]
    DataBlock { block: String },
    #[error("{block} did not run {window}")]
    #[diagnostic(
        code(awl::status::did_not_run),
        help(
            "the run ended at {ended}; check that {block} is called then, or choose another `--cycle` or `--at`"
        )
    )]
    DidNotRun {
        block: String,
        window: String,
        ended: String,
    },
    #[error("{window} is past the end of the run: it ran {cycles} ({ended})")]
    #[diagnostic(
        code(awl::status::past_the_end),
        help("{why}; ask for a longer run with `--cycles` or `--for`")
    )]
    PastTheEnd {
        window: String,
        cycles: String,
        ended: String,
        /// What set the run's length.
        why: String,
    },
}

impl Window {
    /// Whether the window begins after a run that ended after `cycles` cycles at `clock_ns`.
    pub fn after(self, cycles: u64, clock_ns: u64) -> bool {
        match self {
            Window::Cycle(cycle) => cycle > cycles,
            Window::At(ns) => ns > clock_ns,
        }
    }

    /// "cycle 3", "250.000 ms": the window as the start of a sentence names it.
    pub fn name(self) -> String {
        match self {
            Window::Cycle(cycle) => format!("cycle {cycle}"),
            Window::At(ns) => crate::trace::format_ms(ns),
        }
    }

    /// "in cycle 3", "at or after 250.000 ms".
    pub fn describe(self) -> String {
        match self {
            Window::Cycle(cycle) => format!("in cycle {cycle}"),
            Window::At(0) => "in the run".to_string(),
            Window::At(ns) => format!("at or after {}", crate::trace::format_ms(ns)),
        }
    }
}
