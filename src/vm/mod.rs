//! The virtual CPU: process images, flags, timers, counters, data blocks, accumulators, status
//! and the block stack, executing the compiled program on simulated time.
//!
//! [`exec`] is the execution loop; [`cycle`] drives the modes and the cycle; [`interrupts`] is
//! the engine that decides, at the interrupt points the loop reports, which OB runs.

pub mod block_stack;
pub mod bound;
pub mod bytes;
pub mod counters;
pub mod cycle;
pub mod exec;
pub mod float;
pub mod force;
mod integral;
pub mod interrupts;
mod io_trace;
#[cfg(all(feature = "jit", not(target_arch = "wasm32")))]
pub mod native;
pub mod place;
pub mod probe;
pub mod pulse;
mod restart;
mod run_loop;
pub mod s7;
pub mod saved;
pub mod start_info;
pub mod stop;
pub mod system_ops;
pub mod timers;

pub use crate::rules::{arith, status};

/// What a native stretch ran: `passes` of its loop (each the stretch and the jump back), and
/// whether it ended on the jump not taken (see [`native`]).
#[derive(Debug, Clone, Copy)]
pub struct NativeRun {
    pub passes: u32,
    pub left_loop: bool,
}

/// A native stretch as the loop runs it (see [`native`]).
#[derive(Debug, Clone, Copy)]
pub struct NativeStretch {
    /// How many ops it runs.
    pub len: u32,
    /// The arena's op at its start: what runs when the stretch cannot run as a whole.
    pub first: crate::compiler::Op,
    /// A loop's stretch, which a jump right after it takes back to its start: the simulated
    /// time of one pass (the stretch and the jump); 0 for any other stretch.
    pub pass_ns: u64,
    /// The simulated time from the stretch's start to the start of its last operation.
    pub until_last: u64,
    /// The operations and time of the leaf blocks it calls, beyond the calls' own places.
    pub called_ops: u64,
    pub called_ns: u64,
    /// How deep its leaf calls nest: the frames they need on the block stack (0: no call).
    pub depth: u32,
    /// The simulated time of the whole stretch, with the leaf blocks it calls.
    pub span_ns: u64,
    /// Its block changes, where it has any: the interrupt points it crosses with block points.
    pub changes: Option<BlockChanges>,
    /// The instance data it works on: the data it is run on.
    pub instance: Option<InstanceData>,
    /// Whether it calls STEP 7 FBs, which leave their instance DB in the DB register.
    pub calls_fb: bool,
}

/// The STEP 7 instance data a native stretch works on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InstanceData {
    /// `CALL FB n, DB m`'s instance DB (its slot), from its start.
    Db(u16),
    /// The running FB's: DI's data block from AR2's offset, where its multi-instances' lie too.
    Running,
}

/// The block changes inside a stretch that calls leaf blocks, which are interrupt points with
/// block points: what marking each in turn leaves behind (see `Cpu::mark_point`), made when
/// the stretch is compiled. Times are from the stretch's start.
#[derive(Debug, Clone, Copy)]
pub struct BlockChanges {
    /// The first change, which ends the stretch that began at the last point before.
    pub first_ns: u64,
    pub first: Change,
    /// The longest stretch between two of its changes (the first of equal ones).
    pub longest_ns: u64,
    pub longest: Change,
    /// The last change, and the one before it (where the last stretch began).
    pub before_last_ns: u64,
    pub last_ns: u64,
    pub last: Change,
}

/// A block change inside a stretch: the point after op `pc` of `block`, or, where `block` is
/// `None`, after op `pc` of the stretch (its first is 0) in the block that runs it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Change {
    pub block: Option<u16>,
    pub pc: u32,
}

/// Without the `jit` feature, and on wasm32, there is no native code: every op is interpreted.
#[cfg(not(all(feature = "jit", not(target_arch = "wasm32"))))]
pub mod native {
    use super::status::Status;
    use super::{NativeRun, NativeStretch};
    use crate::compiler::{Op, Program};

    /// Never made.
    #[derive(Debug)]
    pub enum NativeCode {}

    impl NativeCode {
        pub fn code(&self, _: bool) -> &[Op] {
            match *self {}
        }

        pub fn stretch(&self, _: u32) -> Option<&NativeStretch> {
            match *self {}
        }

        pub fn run(
            &self,
            _: u32,
            _: u32,
            _: &mut Status,
            _: &mut [u32; 4],
            _: (&mut [u8], &mut [u8]),
        ) -> Option<NativeRun> {
            match *self {}
        }
    }

    pub fn compile(_: &Program) -> Option<NativeCode> {
        None
    }
}

use std::sync::Arc;

use crate::ast::BlockId;
use crate::compiler::bytecode::NO_PARAMS;
use crate::compiler::{Program, Resolved};
use crate::profile::{Nesting, Profile};
use crate::source::SourceSet;
use crate::trace::{BlockName, Tracer};

use block_stack::BlockStack;
use counters::Counter;
use interrupts::{Engine, EngineConfig};
use status::{Brackets, Status};
use stop::{StackEntry, Stop, StopCause, StopDetail};
use timers::Timer;

/// A return point on the block stack.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frame {
    pub block: u16,
    pub open_db: Option<u8>,
    pub params: u16,
    /// Where the calling block's body starts in the program's arena, and where the loop resumes
    /// in it: kept so a block end needs no lookup.
    pub start: u32,
    pub resume: u32,
}

impl Default for Frame {
    fn default() -> Self {
        Frame {
            block: IDLE,
            start: 0,
            open_db: None,
            params: crate::compiler::bytecode::NO_PARAMS,
            resume: 0,
        }
    }
}

impl Frame {
    /// The op of the calling block the loop resumes at.
    pub fn pc(&self) -> u32 {
        self.resume - self.start
    }
}

/// What a STEP 7 block call saves beside its [`Frame`] (on a stack of its own, parallel to the
/// block stack, so STEP 5 calls carry none of it): the calling block's DB and DI registers
/// (slots, as in [`LevelState`]) and where its local data start.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct S7Frame {
    pub db: u16,
    pub di: u16,
    pub local_base: u32,
}

/// The registers and position of a processing level: what an interrupt OB saves and restores.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelState {
    pub accu1: u32,
    pub accu2: u32,
    /// ACCU 3 and 4 of the CPUs that have four accumulators (the CPU 928B).
    pub accu3: u32,
    pub accu4: u32,
    pub status: Status,
    /// STEP 7's binary result BR, beside the status so the status stays one byte for the
    /// STEP 5 loop (see [`status`]).
    pub br: bool,
    pub brackets: Brackets,
    pub open_db: Option<u8>,
    pub block: u16,
    pub pc: u32,
    pub params: u16,
    /// Where this level's frames begin on the block stack.
    pub level_base: usize,
    /// A block call with this many frames on the block stack exceeds the nesting limit.
    pub frame_limit: usize,
    pub interrupts_enabled: bool,
    /// STEP 7: the SFC 41 DIS_AIRT calls of this level's OB still in force; they end with the
    /// OB (System Software for S7-300/400 System and Standard Functions, 12.4).
    pub airt_delays: u16,
    /// S5-95F: this level is OB 13, so `L PY`/`T PY` reach the interrupt process images.
    pub interrupt_images: bool,
    /// STEP 7: the address registers, the DB and DI registers and where the running block's
    /// local data start on the L stack. The DB and DI registers hold the open data blocks'
    /// slots (see [`S7Tables::db_numbers`]; 0: none open), `L DBNO` their numbers.
    ///
    /// [`S7Tables::db_numbers`]: crate::step7::bytecode::S7Tables::db_numbers
    pub ar1: u32,
    pub ar2: u32,
    pub db: u16,
    pub di: u16,
    pub local_base: u32,
    /// STEP 7: where the running block's local data end (its base plus its size), where a
    /// block it calls has its own: kept so a call looks up only the called block's size.
    pub local_end: u32,
    /// STEP 7: the master control relay.
    pub mcr: s7::mcr::Mcr,
}

/// The operating mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum Mode {
    Stop,
    Startup,
    Run,
}

impl Mode {
    pub fn name(self) -> &'static str {
        match self {
            Mode::Stop => "STOP",
            Mode::Startup => "STARTUP",
            Mode::Run => "RUN",
        }
    }
}

/// Why the execution loop handed control back.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Point {
    BlockCall,
    BlockEnd,
    Operation,
    Cycle,
    /// A backward jump: no interrupt point, but the watchdog is checked.
    Loop,
}

impl Point {
    pub fn name(self) -> &'static str {
        match self {
            Point::BlockCall => "block_call",
            Point::BlockEnd => "block_end",
            Point::Operation => "operation",
            Point::Cycle => "cycle",
            Point::Loop => "loop",
        }
    }
}

pub enum Exit {
    /// The level's bottom block executed its block end.
    LevelEnd,
    Point(Point),
    Stop(Stop),
}

/// What ran in a stretch between two interrupt points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StretchKind {
    /// Operations of a block, ending with op `end_pc`.
    Block { block: u16, end_pc: u32 },
    /// The PII read at the cycle start.
    ProcessImageRead,
    /// The PIQ write after OB 1.
    ProcessImageWrite,
    /// The operating-system time at the cycle end.
    OsTime,
    /// S7: a stretch of the wait for the minimum cycle time, up to the next thing due.
    MinCycleWait,
    /// An interrupt OB's last operations with its end (S5-95F OB 13: and its interrupt output
    /// data cycle).
    InterruptEnd { block: u16 },
}

impl Default for StretchKind {
    fn default() -> Self {
        StretchKind::Block {
            block: IDLE,
            end_pc: 0,
        }
    }
}

/// The last stretch between interrupt points: what ran, from when to when.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LastStretch {
    pub kind: StretchKind,
    pub start_ns: u64,
    pub end_ns: u64,
}

/// The longest stretch of a kind seen in the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Stretch {
    pub ns: u64,
    pub kind: StretchKind,
}

impl Stretch {
    pub fn record(&mut self, ns: u64, kind: StretchKind) {
        if ns > self.ns {
            *self = Stretch { ns, kind };
        }
    }
}

/// Image memory for every `u16` offset plus a double word: ops address it with `u16` offsets,
/// so the compiler can prove every access in bounds. A program uses only the profile's part
/// (PII, PIQ and flags, see `Layout`); its addresses are range-checked when it is compiled.
pub const IMAGE_MEMORY: usize = 1 << 16 | 4;

pub type ImageMemory = [u8; IMAGE_MEMORY];

/// The block index that stands for "no block runs" (between cycles).
pub const IDLE: u16 = u16::MAX;

pub struct Cpu {
    pub program: Arc<Program>,
    /// For line numbers in traces and STOP reports.
    pub sources: Arc<SourceSet>,
    pub profile: &'static Profile,
    /// PII, then PIQ, then the flags (see [`crate::address::Layout`]).
    pub image: Box<ImageMemory>,
    /// The process inputs at the input modules.
    pub inputs: Vec<u8>,
    /// The process outputs at the output modules.
    pub outputs: Vec<u8>,
    /// A direct read of an input (`L PIB`) gives the PII's byte, as on awlsim's dummy
    /// hardware, whose input modules hand back the process image (`awl conformance`).
    pub inputs_echo_pii: bool,
    /// The S7 clock memory byte's place in the image (the scenario's `clock_memory`).
    pub clock_memory: Option<u16>,
    /// The simulated time the clock memory and SFC 64 (TIME_TCK) count from: the start of
    /// the run, or the last `CALL SFC -4` (awlsim's `__CLKRST`, which restarts both).
    pub clock_origin_ns: u64,
    /// How far SFC 0 (SET_CLK) set the CPU's clock from [`start_info::START_DATE`] plus the
    /// simulated time, in milliseconds.
    pub clock_set_ms: i64,
    /// The operating system writes each OB's start information into its local data; awlsim's
    /// project files may switch that off (`ob_startinfo_enable="0"`, `awl conformance`).
    pub writes_start_info: bool,
    pub extended_inputs: Vec<u8>,
    pub extended_outputs: Vec<u8>,
    pub timers: Vec<Timer>,
    pub counters: Vec<Counter>,
    /// STEP 5 data blocks by number (0–255).
    pub data_blocks: Vec<Option<Vec<u16>>>,
    /// STEP 7 data blocks by slot (see [`crate::step7::bytecode::S7Tables::db_numbers`]),
    /// byte-addressed.
    pub s7_data: Vec<Option<Vec<u8>>>,
    /// STEP 7: the L stack.
    pub local: Vec<u8>,
    /// STEP 7: the DB, DI and AR2 registers each `CALL FB` saved.
    pub fb_saves: Vec<(u16, u16, u32)>,
    /// STEP 7: what each frame of the block stack saved besides (see [`S7Frame`]), at the
    /// frame's index: the block stack's length says how many are in use.
    pub s7_frames: Box<[S7Frame]>,
    /// The running level's registers and position.
    pub level: LevelState,
    pub frames: BlockStack<Frame>,
    /// The interrupted levels, innermost last.
    pub levels: Vec<LevelState>,
    pub mode: Mode,
    /// Simulated time in ns.
    pub clock: u64,
    /// The loop hands control to the engine at an interrupt point once `clock` reaches this.
    pub attention_at: u64,
    /// When the engine itself has to look; `attention_at` is earlier when the pulse looks first.
    pub engine_attention_at: u64,
    pub instructions: u64,
    pub cycle: u64,
    pub cycle_started_at: u64,
    pub stop_requested: Option<(u16, u32)>,
    /// The last moment an interrupt could have been serviced.
    pub last_point_at: u64,
    /// The last stretch between interrupt points: what ran, and when it began and ended.
    pub last_stretch: LastStretch,
    /// The op that led to the last interrupt point (block, pc), where STOPs found there are
    /// reported.
    pub last_op: (u16, u32),
    /// The longest stretch between two block changes, on any level.
    pub longest_block: Stretch,
    /// The longest stretch of the operating system's work: a part of the cycle-end work, or an
    /// interrupt OB's end with its data cycle.
    pub longest_system: Stretch,
    pub engine: Engine,
    pub tracer: Tracer,
    pub cycle_times: cycle::CycleTimes,
    /// An observer of single operations (program status, the debugger); see [`probe`].
    pub probe: Option<Box<dyn probe::Probe>>,
    /// A listener told how far a long run has come; see [`pulse`].
    pub pulse: Option<pulse::Pulse>,
    /// The inputs and outputs held at values (the online page's force); see [`force`].
    pub forces: force::Forces,
    /// The native code of the program's straight-line stretches (see [`native`]): made with
    /// the CPU, kept by its restarts.
    native: Option<Arc<native::NativeCode>>,
}

impl Cpu {
    pub fn new(program: Arc<Program>, sources: Arc<SourceSet>) -> Self {
        let native = native::compile(&program).map(Arc::new);
        Self::with_native(program, sources, native)
    }

    /// A CPU for `program` whose stretches run as `native` (made for this program).
    fn with_native(
        program: Arc<Program>,
        sources: Arc<SourceSet>,
        native: Option<Arc<native::NativeCode>>,
    ) -> Self {
        let profile = program.profile;
        let sizes = profile.sizes;
        let periphery = usize::from(sizes.peripheral_bytes);
        let mut data_blocks = vec![None; 256];
        for block in &program.data_blocks {
            if block.id.kind == crate::mnemonics::BlockKind::Db {
                data_blocks[usize::from(block.id.number)] = Some(block.words.clone());
            }
        }
        let levels_capacity = profile.interrupt_obs.len() + 2;
        Cpu {
            image: vec![0u8; IMAGE_MEMORY]
                .into_boxed_slice()
                .try_into()
                .expect("the length is IMAGE_MEMORY"),
            inputs: vec![0; periphery],
            outputs: vec![0; periphery],
            inputs_echo_pii: false,
            clock_memory: None,
            clock_origin_ns: 0,
            clock_set_ms: 0,
            writes_start_info: true,
            extended_inputs: vec![0; periphery],
            extended_outputs: vec![0; periphery],
            timers: vec![Timer::default(); usize::from(sizes.timers)],
            counters: vec![Counter::default(); usize::from(sizes.counters)],
            data_blocks,
            s7_data: s7::initial_data(&program),
            local: if program.s7.is_empty() {
                Vec::new()
            } else {
                vec![0; s7::memory::LOCAL_BYTES]
            },
            // As deep as the block stack, so a call never allocates.
            fb_saves: Vec::with_capacity(usize::from(profile.nesting_limit) * levels_capacity + 1),
            s7_frames: vec![
                S7Frame::default();
                usize::from(profile.nesting_limit) * levels_capacity + 1
            ]
            .into_boxed_slice(),
            level: LevelState {
                accu1: 0,
                accu2: 0,
                accu3: 0,
                accu4: 0,
                status: Status::default(),
                br: false,
                brackets: Brackets::default(),
                open_db: None,
                // No block runs before the first cycle; a STOP then names none.
                block: IDLE,
                pc: 0,
                params: NO_PARAMS,
                level_base: 0,
                frame_limit: usize::from(profile.nesting_limit).saturating_sub(1),
                interrupts_enabled: true,
                airt_delays: 0,
                interrupt_images: false,
                ar1: 0,
                ar2: 0,
                db: 0,
                di: 0,
                local_base: 0,
                local_end: 0,
                mcr: s7::mcr::Mcr::default(),
            },
            frames: BlockStack::with_room(usize::from(profile.nesting_limit) * levels_capacity + 1),
            levels: Vec::with_capacity(levels_capacity),
            mode: Mode::Stop,
            clock: 0,
            attention_at: u64::MAX,
            engine_attention_at: u64::MAX,
            instructions: 0,
            cycle: 0,
            cycle_started_at: 0,
            stop_requested: None,
            last_point_at: 0,
            last_stretch: LastStretch::default(),
            last_op: (0, 0),
            longest_block: Stretch::default(),
            longest_system: Stretch::default(),
            engine: Engine::new(profile, EngineConfig::default(), Vec::new()),
            tracer: Tracer::off(),
            cycle_times: cycle::CycleTimes::default(),
            probe: None,
            pulse: None,
            forces: force::Forces::default(),
            native,
            profile,
            program,
            sources,
        }
    }

    pub fn block_id(&self, index: u16) -> BlockId {
        self.program.blocks[usize::from(index)].id
    }

    /// The name of block `index` for a trace event.
    pub fn block_name(&self, index: u16) -> BlockName {
        BlockName::clone(&self.program.names[usize::from(index)])
    }

    /// Source line of an op.
    pub fn line_of(&self, block: u16, pc: u32) -> u32 {
        let block = &self.program.blocks[usize::from(block)];
        self.sources.line_of(
            block
                .spans
                .get(pc as usize)
                .copied()
                .unwrap_or(block.header),
        )
    }

    /// The PG listing's segment of op `pc` of `block`, in a listing.
    #[cold]
    #[inline(never)]
    pub fn segment_of(&self, block: u16, pc: u32) -> Option<u16> {
        self.program
            .blocks
            .get(usize::from(block))?
            .segment_of(pc as usize)
    }

    /// A BSTACK entry: the block, the line (and segment) of op `pc`.
    #[cold]
    #[inline(never)]
    pub fn stack_entry(&self, block: u16, pc: u32) -> StackEntry {
        StackEntry {
            block: self.block_id(block).to_string(),
            line: self.line_of(block, pc),
            segment: self.segment_of(block, pc),
        }
    }

    /// The block at the bottom of the running level: OB 1, a startup OB, or an interrupt OB.
    pub fn level_block(&self) -> u16 {
        self.frames
            .get(self.level.level_base)
            .map_or(self.level.block, |frame| frame.block)
    }

    /// Nesting depth of the running level (1 = its bottom block).
    pub fn depth(&self) -> usize {
        self.frames.len() - self.level.level_base + 1
    }

    /// Starts a level at a block (OB 1, a startup OB, an interrupt OB); a STOP when the
    /// block's local data do not fit the L stack.
    pub fn enter_level(&mut self, block: u16) -> Result<(), Stop> {
        self.level.level_base = self.frames.len();
        self.level.block = block;
        self.level.pc = 0;
        self.level.params = NO_PARAMS;
        self.level.open_db = None;
        self.level.status = Status::default();
        self.level.br = false;
        self.level.brackets = Brackets::default();
        self.level.interrupt_images = false;
        self.level.airt_delays = 0;
        self.level.db = 0;
        self.level.di = 0;
        self.level.mcr = s7::mcr::Mcr::default();
        self.level.local_base = self.levels.last().map_or(0, |outer| {
            if outer.block == IDLE {
                0
            } else {
                outer.local_end
            }
        });
        self.level.local_end = self.level.local_base + self.program.local_bytes(block);
        let limit = usize::from(self.profile.nesting_limit);
        self.level.frame_limit = match self.profile.nesting {
            Nesting::PerLevel => self.level.level_base + limit - 1,
            Nesting::WholeCpu => {
                let outer = self.levels.iter().filter(|level| level.block != IDLE);
                (limit - 1).saturating_sub(outer.count())
            }
        };
        if self.level.local_end as usize > self.local.len() {
            let detail = StopDetail::LocalData {
                block,
                end: self.level.local_end,
                call: false,
            };
            return Err(self.stop(StopCause::Lstack, stop::BEFORE_FIRST_OP, detail));
        }
        Ok(())
    }

    /// The L stack's size in bytes: a STEP 7 program's blocks share it.
    pub fn local_bytes(&self) -> usize {
        self.local.len()
    }

    /// Gives a STEP 7 program an L stack of `bytes` (an awlsim project's `nr_localbytes`),
    /// before the run.
    pub fn set_local_bytes(&mut self, bytes: usize) {
        if !self.local.is_empty() {
            self.local = vec![0; bytes];
        }
    }

    /// The return points (block, op of the call) of the block stack's frames `frames`,
    /// innermost first.
    pub fn return_points(
        &self,
        frames: std::ops::Range<usize>,
    ) -> impl Iterator<Item = (u16, u32)> + '_ {
        self.frames[frames]
            .iter()
            .rev()
            .map(|frame| (frame.block, frame.pc().saturating_sub(1)))
    }

    /// The block stack, innermost first: the running block, then each return point.
    /// Interrupted levels follow, each with its own return points.
    pub fn block_stack(&self, pc: u32) -> Vec<(u16, u32)> {
        self.level_stacks(pc)
            .into_iter()
            .flat_map(|(_, stack)| stack)
            .collect()
    }

    /// Each level's registers and block stack, innermost first: the running level (at `pc`),
    /// then the levels it interrupted (the ISTACK).
    pub fn level_stacks(&self, pc: u32) -> Vec<(&LevelState, Vec<(u16, u32)>)> {
        let mut stack = vec![(self.level.block, pc)];
        let (mut base, mut top) = (self.level.level_base, self.frames.len());
        stack.extend(self.return_points(base..top));
        let mut levels = vec![(&self.level, stack)];
        for level in self.levels.iter().rev() {
            if level.block == IDLE {
                break;
            }
            let mut stack = vec![(level.block, level.pc)];
            top = base;
            base = level.level_base;
            stack.extend(self.return_points(base..top));
            levels.push((level, stack));
        }
        levels
    }

    /// A STOP at the running block's op `pc`, with the block stack. Between cycles it is placed
    /// at the end of OB 1, where the cycle ended. Out of line: the loop only reaches it on the
    /// way out.
    #[cold]
    #[inline(never)]
    pub fn stop(&self, cause: StopCause, pc: u32, detail: StopDetail) -> Stop {
        let (block, pc) = if self.level.block == IDLE {
            // Between cycles: at the end of OB 1, where the cycle ended, if there is one and
            // it has run.
            match self.program.ob(1).filter(|_| self.instructions > 0) {
                Some(ob1) => {
                    let last = self.program.blocks[usize::from(ob1)]
                        .code
                        .len()
                        .saturating_sub(1);
                    (Some(ob1), last as u32)
                }
                None => (None, 0),
            }
        } else {
            (Some(self.level.block), pc)
        };
        let stack = match block {
            None => Vec::new(),
            Some(block) if self.level.block == IDLE => vec![(block, pc)],
            Some(_) => self.block_stack(pc),
        };
        let stack = stack
            .into_iter()
            .map(|(block, pc)| self.stack_entry(block, pc))
            .collect();
        Stop {
            cause,
            block,
            pc,
            detail,
            stack,
        }
    }

    /// What a call passed for parameter `param`, from its parameter list `list`.
    pub fn passed(&self, list: u16, param: u8) -> Option<Resolved> {
        let actuals = self.program.param_lists.get(usize::from(list))?;
        actuals.get(usize::from(param)).copied()
    }

    /// Resolves an actual parameter of the running FB, following parameters passed on from the
    /// calling FBs.
    pub fn actual(&self, param: u8) -> Option<Resolved> {
        let mut list = self.level.params;
        let mut frames = self.frames[self.level.level_base..].iter().rev();
        let mut index = param;
        loop {
            match self.passed(list, index)? {
                Resolved::Formal(outer) => {
                    list = frames.next()?.params;
                    index = outer;
                }
                other => return Some(other),
            }
        }
    }
}
