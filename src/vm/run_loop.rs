//! The execution loop. It runs ops of the current level until a block change or an operation
//! (in `operation` mode) finds `clock >= attention_at` — one comparison when nothing is due — or
//! the level ends, or a fault stops the CPU. It allocates nothing and does no string work
//! unless a trace is being written.
//!
//! The registers of the running level live in locals. Time and the operation count are kept as
//! bases against the position in the program's arena: the clock is `time_base + times[pc]` and
//! the count `count_base + pc`, so straight code pays nothing per op for either, and a jump or a
//! block change moves the bases once.

use std::sync::Arc;

use crate::compiler::bytecode::*;
use crate::compiler::fuse;
use crate::trace::Event;

use super::arith;
use super::native::NativeCode;
use super::probe::Flow;
use super::status::Status;
use super::stop::{StopCause, StopDetail};
use super::{
    BlockChanges, Change, Cpu, Exit, Frame, InstanceData, LastStretch, Point, StretchKind,
};

/// How the loop ended: small and `Copy`, so leaving it carries no STOP report.
#[derive(Clone, Copy)]
enum Leave {
    LevelEnd,
    Point(Point),
    /// A fault (or a halt) at op `pc`.
    Stop(StopCause, u32),
}

impl Cpu {
    /// Runs the current level; `operation_points` makes every operation an interrupt point.
    /// With a probe set, the stepping variant shows it every operation.
    pub fn execute(&mut self, operation_points: bool) -> Exit {
        if self.probe.is_some() || self.tracer.enabled {
            return self.execute_watched(operation_points);
        }
        // Code with native stretches runs in loops of its own: the others keep the loop they
        // had without the stretch's arm (callgrind, `programs/bench/calls`).
        let native = self.native_code().is_some();
        match (self.program.s7.step7, operation_points, native) {
            (true, true, false) => self.run_step7::<true, false>(),
            (true, true, true) => self.run_step7::<true, true>(),
            (true, false, false) => self.run_step7::<false, false>(),
            (true, false, true) => self.run_step7::<false, true>(),
            (false, true, false) => self.run_alone::<true, false>(),
            (false, true, true) => self.run_alone::<true, true>(),
            (false, false, false) => self.run_alone::<false, false>(),
            (false, false, true) => self.run_alone::<false, true>(),
        }
    }

    /// A STEP 5 program's loop, in a function of its own: sharing one with the STEP 7 loops
    /// costs a STEP 5 block call a dozen instructions more (callgrind, `programs/bench/calls`).
    #[inline(never)]
    fn run_alone<const OPERATION_POINTS: bool, const NATIVE: bool>(&mut self) -> Exit {
        self.run_loop::<OPERATION_POINTS, false, false, false, NATIVE>()
    }

    /// A STEP 7 program's loops, out of line: inlined into `execute` beside the others, they
    /// cost a STEP 7 block call a few instructions more (callgrind, `programs/bench/s7_calls`).
    #[inline(never)]
    fn run_step7<const OPERATION_POINTS: bool, const NATIVE: bool>(&mut self) -> Exit {
        self.run_loop::<OPERATION_POINTS, false, false, true, NATIVE>()
    }

    /// The variants that show a probe every operation or trace the block changes, kept out of
    /// line so the plain loops compile as they would alone (no call in their paths).
    #[cold]
    #[inline(never)]
    fn execute_watched(&mut self, operation_points: bool) -> Exit {
        match (
            operation_points,
            self.probe.is_some(),
            self.program.s7.step7,
        ) {
            (true, true, false) => self.run_loop::<true, true, true, false, false>(),
            (false, true, false) => self.run_loop::<false, true, true, false, false>(),
            (true, false, false) => self.run_loop::<true, false, true, false, true>(),
            (false, false, false) => self.run_loop::<false, false, true, false, true>(),
            (true, true, true) => self.run_loop::<true, true, true, true, false>(),
            (false, true, true) => self.run_loop::<false, true, true, true, false>(),
            (true, false, true) => self.run_loop::<true, false, true, true, true>(),
            (false, false, true) => self.run_loop::<false, false, true, true, true>(),
        }
    }

    /// The STOP report of a fault the loop left with (built once, after the loop).
    #[cold]
    #[inline(never)]
    fn stop_at(&self, cause: StopCause, pc: u32, detail: StopDetail) -> super::stop::Stop {
        self.stop(cause, pc, detail)
    }

    /// Marks a block change, an interrupt point with block points: the stretch since the last
    /// point ended with op `end_pc` of `block`.
    #[inline(always)]
    fn mark_point(&mut self, clock: u64, block: u16, end_pc: u32) {
        let kind = StretchKind::Block { block, end_pc };
        self.last_stretch = LastStretch {
            kind,
            start_ns: self.last_point_at,
            end_ns: clock,
        };
        self.longest_block.record(clock - self.last_point_at, kind);
        self.last_point_at = clock;
    }

    /// Marks the point after op `end_pc` of `block` with operation points, where the loop
    /// leaves at a block change: the stretch is that op alone, as at every other operation
    /// (so the loop keeps no stretch at the block changes it goes on after).
    #[cold]
    fn mark_operation(&mut self, clock: u64, block: u16, end_pc: u32) {
        let cost = self.program.blocks[usize::from(block)].cost(end_pc as usize);
        self.last_stretch = LastStretch {
            kind: StretchKind::Block { block, end_pc },
            start_ns: clock - cost,
            end_ns: clock,
        };
        self.last_point_at = clock;
    }

    /// Records where the loop stopped without a block change: the stretch from `start_ns`
    /// to `end_ns` ended with op `end_pc` of the running block.
    #[cold]
    fn note_stretch(&mut self, end_pc: u32, start_ns: u64, end_ns: u64) {
        self.last_op = (self.level.block, end_pc);
        self.last_stretch = LastStretch {
            kind: StretchKind::Block {
                block: self.level.block,
                end_pc,
            },
            start_ns,
            end_ns,
        };
    }

    /// Traces a block call at `self.clock`.
    #[cold]
    fn trace_call(&mut self, from: u16, to: u16) {
        let event = Event::BlockCall {
            from: self.block_name(from),
            to: self.block_name(to),
            depth: self.depth(),
        };
        self.trace_block_change(event);
    }

    /// Traces a block end at `self.clock`.
    #[cold]
    fn trace_end(&mut self, block: u16) {
        let event = Event::BlockEnd {
            block: self.block_name(block),
            depth: self.depth(),
        };
        self.trace_block_change(event);
    }

    /// The trace holds events back until the engine has taken in everything due by then;
    /// when nothing is due by now, they can be written at once.
    fn trace_block_change(&mut self, event: Event) {
        self.tracer.emit(self.clock, event);
        if self.clock < self.engine.next_due() {
            self.settle_trace();
        }
    }

    /// `TRACING`: block changes may be traced (the tracer is asked); without it the loop has
    /// no trace code at all — a run that traces nothing at its start traces nothing later.
    ///
    /// `STEP7`: the program is a STEP 7 program. Its operations run inline and its calls move
    /// the L stack; a STEP 5 program's loop has none of that code (it never meets those ops).
    fn run_loop<
        const OPERATION_POINTS: bool,
        const STEPPING: bool,
        const TRACING: bool,
        const STEP7: bool,
        const NATIVE: bool,
    >(
        &mut self,
    ) -> Exit {
        let program = Arc::clone(&self.program);
        let native_code = if NATIVE { self.native.clone() } else { None };
        let arena = &program.arena;
        // A STEP 7 program's calls also move the L stack and save the DB and DI registers.
        let step7 = STEP7;
        // Every body in one array: `pc` is a position in it, `start` where the running body
        // starts (so op `pc - start` of the block), `times` the op times as prefix sums.
        // The fused pairs run as one op, except in the stepping loop, which shows every op;
        // with operation points a pair runs as one only when no point falls between its ops.
        let plain = &arena.plain[..];
        // Straight-line stretches run as native code where there is any (see `native`).
        let native = native_code.as_deref();
        let code = match native {
            _ if STEPPING => plain,
            // Leaf calls run inside stretches only where a block change is no event.
            Some(native) => native.code(TRACING),
            None => &arena.ops[..],
        };
        let times = &arena.times[..];
        let mut start = arena.start(self.level.block, self.level.params);
        let mut pc = start + self.level.pc as usize;
        // Wrapping arithmetic: a base may stand "below zero" (a jump forward early in a run),
        // the clock and count it gives never do.
        let mut time_base = self.clock.wrapping_sub(times[pc]);
        // With operation points: the attention time on the scale of `times`, so the check after
        // each op is one comparison (`times[pc] >= deadline` is `clock >= attention_at`). Kept
        // current wherever `time_base` or `attention_at` can change.
        let mut deadline = u64::MAX;
        macro_rules! rebase {
            () => {
                if OPERATION_POINTS {
                    deadline = deadline_on(self.attention_at, time_base);
                }
            };
        }
        rebase!();
        let mut count_base = self.instructions.wrapping_sub(pc as u64);
        let mut status = self.level.status;
        let mut accu1 = self.level.accu1;
        let mut accu2 = self.level.accu2;
        // When the running pass of a loop began (where a request that came in it is placed).
        let mut pass_start = self.last_point_at;
        macro_rules! now {
            () => {
                time_base.wrapping_add(times[pc])
            };
        }
        // With operation points: a pair whose first op ends at a point runs as its first op.
        macro_rules! split_if_due {
            ($dispatch:lifetime, $op:ident) => {
                if OPERATION_POINTS && times[pc] >= deadline {
                    $op = &plain[pc - 1];
                    continue $dispatch;
                }
            };
        }
        // The position in the block of the op just fetched.
        macro_rules! at {
            () => {
                (pc - start) as u32 - 1
            };
        }
        // The registers live in locals; `sync!` hands them to `self` before anything else looks,
        // `reload!` takes them back.
        macro_rules! sync {
            () => {
                self.clock = now!();
                self.level.status = status;
                self.level.accu1 = accu1;
                self.level.accu2 = accu2;
            };
        }
        macro_rules! reload {
            () => {
                time_base = self.clock.wrapping_sub(times[pc]);
                rebase!();
                status = self.level.status;
                accu1 = self.level.accu1;
                accu2 = self.level.accu2;
            };
        }
        // The stepping variant shows the probe the op at `pc` before it runs, and op `$pc`
        // of `$block`, run as `$op`, after it ran.
        macro_rules! probe_before {
            ($run:lifetime) => {
                if STEPPING {
                    sync!();
                    self.level.pc = (pc - start) as u32;
                    if self.with_probe(Flow::Go, |probe, cpu| probe.before(cpu)) == Flow::Halt {
                        break $run Leave::Stop(StopCause::Halt, (pc - start) as u32);
                    }
                    reload!();
                }
            };
        }
        macro_rules! probe_after {
            ($run:lifetime, $pc:expr, $op:expr) => {
                if STEPPING {
                    sync!();
                    let (block, at, op) = (self.level.block, $pc, *$op);
                    let flow =
                        self.with_probe(Flow::Go, |probe, cpu| probe.after(cpu, block, at, op));
                    if flow == Flow::Halt {
                        break $run Leave::Stop(StopCause::Halt, at);
                    }
                }
            };
        }
        // Moves control to position `$to` of the body starting at `$start`, settling the bases.
        macro_rules! move_to {
            ($to:expr, $start:expr) => {
                let clock = now!();
                let to: usize = $to;
                count_base = count_base.wrapping_add(pc as u64).wrapping_sub(to as u64);
                start = $start;
                pc = to;
                time_base = clock.wrapping_sub(times[pc]);
                rebase!();
            };
        }
        // The point at a block change the loop leaves at, with operation points (with block
        // points it was marked at the change itself).
        macro_rules! leaving_point {
            ($clock:expr, $block:expr, $end_pc:expr) => {
                if OPERATION_POINTS {
                    self.mark_operation($clock, $block, $end_pc);
                }
            };
        }
        // The block end of the running block, after its status rule was applied.
        macro_rules! block_end {
            ($run:lifetime, $op:expr) => {{
                probe_after!($run, at!(), $op);
                let ended = self.level.block;
                let end_pc = at!();
                let clock = now!();
                let level_end = self.frames.len() == self.level.level_base;
                if TRACING && self.tracer.enabled {
                    self.clock = clock;
                    self.trace_end(ended);
                }
                if level_end && !self.levels.is_empty() {
                    // An interrupt OB's end is no point yet: its data cycle comes first.
                    self.note_stretch(end_pc, self.last_point_at, clock);
                    break $run Leave::LevelEnd;
                }
                if !OPERATION_POINTS {
                    self.mark_point(clock, ended, end_pc);
                }
                if level_end {
                    leaving_point!(clock, ended, end_pc);
                    self.last_op = (ended, end_pc);
                    break $run Leave::LevelEnd;
                }
                let Some(&frame) = self.frames.pop() else {
                    unreachable!("a frame above the level base");
                };
                self.level.block = frame.block;
                self.level.open_db = frame.open_db;
                self.level.params = frame.params;
                if step7 {
                    // A block end clears OS (STL manual, status word: OS).
                    status.set_os(false);
                    self.leave_s7_block();
                }
                let resume = frame.resume as usize;
                move_to!(resume, frame.start as usize);
                if clock >= self.attention_at {
                    leaving_point!(clock, ended, end_pc);
                    self.last_op = (ended, end_pc);
                    break $run Leave::Point(Point::BlockEnd);
                }
            }};
        }
        // Why the loop ended; a fault's detail waits in `detail` (the loop carries no report).
        let mut detail = StopDetail::None;
        // A block call (of op `$op` at `$op_pc`, for the probe): `$target` with actual-parameter
        // list `$params`, whose body starts at `$entry`.
        macro_rules! call {
            ($run:lifetime, $op_pc:expr, $op:expr,
             $target:expr, $conditional:expr, $params:expr, $entry:expr) => {{
                let (target, conditional, params, entry): (u16, bool, u16, usize) =
                    ($target, $conditional, $params, $entry);
                if conditional && !status.rlo() {
                    status.after_jump();
                    probe_after!($run, $op_pc, $op);
                    continue $run;
                }
                status.after_jump();
                if self.frames.len() >= self.level.frame_limit {
                    sync!();
                    break $run Leave::Stop(StopCause::Stueb, at!());
                }
                probe_after!($run, $op_pc, $op);
                let caller = self.level.block;
                let call_pc = at!();
                let pushed = self.frames.push(Frame {
                    block: caller,
                    open_db: self.level.open_db,
                    params: self.level.params,
                    start: start as u32,
                    resume: pc as u32,
                });
                if !pushed {
                    break $run Leave::Stop(StopCause::Stueb, call_pc);
                }
                if step7 {
                    // So does a block call.
                    status.set_os(false);
                }
                if step7 && !self.enter_s7_block(target) {
                    detail = StopDetail::LocalData {
                        block: target,
                        end: self.level.local_end,
                        call: true,
                    };
                    // The call did not happen: the caller stops at it, as at any other fault.
                    self.frames.pop();
                    self.leave_s7_block();
                    break $run Leave::Stop(StopCause::Lstack, call_pc);
                }
                self.level.block = target;
                self.level.params = params;
                // Every body's op times start at 0: its clock base is the clock.
                debug_assert_eq!(times[entry], 0, "a body's first op starts at 0");
                let clock = now!();
                count_base = count_base.wrapping_add(pc as u64).wrapping_sub(entry as u64);
                start = entry;
                pc = entry;
                time_base = clock;
                rebase!();
                if !OPERATION_POINTS {
                    self.mark_point(clock, caller, call_pc);
                }
                if TRACING && self.tracer.enabled {
                    self.clock = clock;
                    self.trace_call(caller, target);
                }
                if clock >= self.attention_at {
                    leaving_point!(clock, caller, call_pc);
                    self.last_op = (caller, call_pc);
                    break $run Leave::Point(Point::BlockCall);
                }
                continue $run;
            }};
        }
        // With operation points: the op that just ran ended at a point (the check of it is made
        // here, at the top, so every arm goes straight back to one place).
        let mut ended_op = false;
        let leave = 'run: loop {
            if OPERATION_POINTS && ended_op {
                ended_op = false;
                if times[pc] >= deadline {
                    self.last_op = (self.level.block, at!());
                    break 'run Leave::Point(Point::Operation);
                }
            }
            probe_before!('run);
            // Every body ends in `End`, so this finds an op; past the arena it stops all the same.
            let Some(fetched) = code.get(pc) else {
                detail = StopDetail::Text("the block has no BE".into());
                break 'run Leave::Stop(StopCause::Bcf, (pc - start) as u32);
            };
            pc += 1;
            // Matched through a reference, so each arm loads only the fields it uses and no
            // register carries an op's fields into every arm (`resolved` holds a formal
            // operand's or a `DO`'s op).
            let mut op = fetched;
            let mut resolved: Op;
            // The op's own position, for the probe: after a `DO`, the op it ran. Only the
            // stepping loop shows it; elsewhere it would cost a register at every dispatch.
            let mut op_pc = if STEPPING { at!() } else { 0 };
            // A formal operand or a `DO` is resolved, then its op dispatched again.
            'dispatch: loop {
                match *op {
                    Op::And(bit) => status.scanned(Logic::And, self.image_bit(bit)),
                    Op::AndNot(bit) => status.scanned(Logic::AndNot, self.image_bit(bit)),
                    Op::Or(bit) => status.scanned(Logic::Or, self.image_bit(bit)),
                    Op::OrNot(bit) => status.scanned(Logic::OrNot, self.image_bit(bit)),
                    Op::Assign(bit) => {
                        self.write_image_bit(bit, status.rlo());
                        status.end_string();
                    }
                    Op::Set(bit) => {
                        if status.rlo() {
                            self.write_image_bit(bit, true);
                        }
                        status.end_string();
                    }
                    Op::Reset(bit) => {
                        if status.rlo() {
                            self.write_image_bit(bit, false);
                        }
                        status.end_string();
                    }
                    Op::OrAlone => status.or_alone(),
                    Op::S7Scan(combination, bit) if STEP7 => {
                        status.scanned_step7(combination, self.image_bit(bit));
                    }
                    Op::S7Write(write, bit) if STEP7 => {
                        let rlo = status.rlo();
                        match write {
                            Write::Assign => self.write_image_bit(bit, rlo),
                            Write::Set if rlo => self.write_image_bit(bit, true),
                            Write::Reset if rlo => self.write_image_bit(bit, false),
                            _ => {}
                        }
                        super::s7::bit_logic::assigned(&mut status, rlo);
                    }
                    Op::LoadImageByte(byte) => {
                        accu2 = accu1;
                        accu1 = u32::from(self.image[usize::from(byte)]);
                    }
                    Op::LoadImageWord(byte) => {
                        accu2 = accu1;
                        accu1 = self.read_image(Width::Word, byte);
                    }
                    Op::LoadImageDouble(byte) => {
                        accu2 = accu1;
                        accu1 = self.read_image(Width::Double, byte);
                    }
                    Op::TransferImageByte(byte) => self.image[usize::from(byte)] = accu1 as u8,
                    Op::TransferImageWord(byte) => self.write_image(Width::Word, byte, accu1),
                    Op::TransferImageDouble(byte) => self.write_image(Width::Double, byte, accu1),
                    Op::LoadConstant(value) => {
                        accu2 = accu1;
                        accu1 = value;
                    }
                    Op::Arithmetic(kind) => arith::arithmetic(kind, &mut accu1, accu2, &mut status),
                    Op::ArithmeticStack(kind) => {
                        arith::arithmetic(kind, &mut accu1, accu2, &mut status);
                        // Four accumulators: ACCU 3 moves to ACCU 2, ACCU 4 to ACCU 3.
                        accu2 = self.level.accu3;
                        self.level.accu3 = self.level.accu4;
                    }
                    Op::Compare(kind) => arith::compare(kind, accu1, accu2, &mut status),
                    Op::Jump(condition, target) => {
                        if condition.taken(&mut status) {
                            let jump_pc = at!();
                            let to = start + target as usize;
                            let backward = to < pc;
                            move_to!(to, start);
                            if OPERATION_POINTS {
                                // The op that ended at this point is the jump, not the one
                                // before its target: the point is checked here.
                                probe_after!('run, op_pc, op);
                                if times[pc] >= deadline {
                                    self.last_op = (self.level.block, jump_pc);
                                    break 'run Leave::Point(Point::Operation);
                                }
                                continue 'run;
                            }
                            if backward {
                                let clock = now!();
                                if clock >= self.attention_at {
                                    let start = pass_start.max(self.last_point_at);
                                    self.note_stretch(jump_pc, start, clock);
                                    break 'run Leave::Point(Point::Loop);
                                }
                                pass_start = clock;
                            }
                        }
                    }
                    Op::Call {
                        block: target,
                        conditional,
                        params,
                    } => {
                        let entry = arena.start(target, params);
                        call!('run, op_pc, op, target, conditional, params, entry);
                    }
                    Op::CallAt {
                        block: target,
                        conditional,
                        entry,
                    } => call!('run, op_pc, op, target, conditional, NO_PARAMS, entry as usize),
                    Op::BlockEnd => {
                        status.end_string();
                        block_end!('run, op);
                        continue 'run;
                    }
                    Op::BlockEndUnconditional => {
                        status.after_jump();
                        block_end!('run, op);
                        continue 'run;
                    }
                    Op::BlockEndConditional => {
                        let taken = status.rlo();
                        status.after_jump();
                        if !taken {
                            probe_after!('run, op_pc, op);
                            continue 'run;
                        }
                        block_end!('run, op);
                        continue 'run;
                    }
                    Op::LogicPair {
                        first_op,
                        first,
                        second,
                        second_op,
                    } => {
                        split_if_due!('dispatch, op);
                        let (logic, bit) = fuse::unpack(first_op, first);
                        status.scanned(logic, self.image_bit(bit));
                        let (logic, bit) = fuse::unpack(second_op, second);
                        status.scanned(logic, self.image_bit(bit));
                        pc += 1;
                    }
                    Op::S7ScanPair {
                        first_op,
                        first,
                        second,
                        second_op,
                    } if STEP7 => {
                        split_if_due!('dispatch, op);
                        let (code, bit) = fuse::unpack_step7_code(first_op, first);
                        status.scanned_step7_code(code, self.image_bit(bit));
                        let (code, bit) = fuse::unpack_step7_code(second_op, second);
                        status.scanned_step7_code(code, self.image_bit(bit));
                        pc += 1;
                    }
                    Op::S7ScanWrite {
                        scan_op,
                        scanned,
                        written,
                        write_op,
                    } if STEP7 => {
                        split_if_due!('dispatch, op);
                        let (code, bit) = fuse::unpack_step7_code(scan_op, scanned);
                        status.scanned_step7_code(code, self.image_bit(bit));
                        let rlo = status.rlo();
                        let byte = &mut self.image[usize::from(written)];
                        *byte = fuse::apply_write(write_op, rlo, *byte);
                        super::s7::bit_logic::assigned(&mut status, rlo);
                        pc += 1;
                    }
                    Op::LogicWrite {
                        logic_op,
                        scanned,
                        written,
                        write_op,
                    } => {
                        split_if_due!('dispatch, op);
                        let (logic, bit) = fuse::unpack(logic_op, scanned);
                        status.scanned(logic, self.image_bit(bit));
                        let byte = &mut self.image[usize::from(written)];
                        *byte = fuse::apply_write(write_op, status.rlo(), *byte);
                        status.end_string();
                        pc += 1;
                    }
                    Op::LoadWordConstant { byte, value } => {
                        split_if_due!('dispatch, op);
                        accu2 = self.read_image(Width::Word, byte);
                        accu1 = u32::from(value);
                        pc += 1;
                    }
                    Op::LoadWords { first, second } => {
                        split_if_due!('dispatch, op);
                        accu2 = self.read_image(Width::Word, first);
                        accu1 = self.read_image(Width::Word, second);
                        pc += 1;
                    }
                    Op::ArithmeticTransferWord { kind, stack, byte } => {
                        split_if_due!('dispatch, op);
                        arith::arithmetic(kind, &mut accu1, accu2, &mut status);
                        if stack {
                            accu2 = self.level.accu3;
                            self.level.accu3 = self.level.accu4;
                        }
                        self.write_image(Width::Word, byte, accu1);
                        pc += 1;
                    }
                    Op::Native(index) if NATIVE => {
                        let first = pc - 1;
                        let registers = (status, accu1, accu2);
                        let from = (first, (first - start) as u32, deadline);
                        match self.run_stretch::<OPERATION_POINTS>(
                            native, index, time_base, from, registers,
                        ) {
                            Stretched::Ran(ran) => {
                                (status, accu1, accu2) = ran.registers;
                                if let Some(landed) = ran.landed {
                                    pass_start = landed;
                                }
                                if ran.shift_ns > 0 || ran.shift_ops > 0 {
                                    count_base = count_base.wrapping_add(ran.shift_ops);
                                    time_base = time_base.wrapping_add(ran.shift_ns);
                                    rebase!();
                                }
                                pc = ran.resume;
                            }
                            Stretched::OpByOp(first_op) => {
                                resolved = first_op;
                                op = &resolved;
                                continue 'dispatch;
                            }
                        }
                    }
                    Op::End => {
                        // Back onto the end, where a block without `BE` stops.
                        pc -= 1;
                        detail = StopDetail::Text("the block has no BE".into());
                        break 'run Leave::Stop(StopCause::Bcf, (pc - start) as u32);
                    }
                    Op::S7(code) if STEP7 => {
                        sync!();
                        let flow = self.execute_s7(code, at!());
                        reload!();
                        match flow {
                            Ok(super::s7::exec::Flow::Next) => {}
                            // A jump taken: the shared jump's arm moves there.
                            Ok(super::s7::exec::Flow::Jump(target)) => {
                                resolved = Op::Jump(JumpCondition::Always, target);
                                op = &resolved;
                                continue 'dispatch;
                            }
                            Err((cause, fault)) => {
                                detail = fault;
                                break 'run Leave::Stop(cause, at!());
                            }
                        }
                    }
                    Op::Formal { .. } | Op::Indirect { .. } => {
                        sync!();
                        match self.concrete(*op) {
                            Ok((concrete, consumes_next)) => {
                                if consumes_next {
                                    probe_after!('run, op_pc, op);
                                    if code.get(pc).is_some_and(|next| *next != Op::End) {
                                        pc += 1;
                                        op_pc += 1;
                                        self.clock = now!();
                                    }
                                }
                                reload!();
                                resolved = concrete;
                                op = &resolved;
                                continue 'dispatch;
                            }
                            Err((cause, fault)) => {
                                detail = fault;
                                break 'run Leave::Stop(cause, at!());
                            }
                        }
                    }
                    Op::LogicOther(..)
                    | Op::WriteData { .. }
                    | Op::AndBracket
                    | Op::OrBracket
                    | Op::CloseBracket
                    | Op::LoadData(..)
                    | Op::TransferData(..)
                    | Op::LoadPeripheral { .. }
                    | Op::TransferPeripheral { .. }
                    | timer_counter_ops!()
                    | Op::CallMissing { .. }
                    | Op::Builtin { .. }
                    | Op::OpenDb(_)
                    | Op::GenerateDb(_)
                    | Op::Nop
                    | Op::Stop
                    | Op::WordLogic(_)
                    | Op::ShiftLeft(_)
                    | Op::ShiftRight(_)
                    | Op::OnesComplement
                    | Op::TwosComplement
                    | Op::Swap
                    | Op::Enter
                    | Op::FloatArithmetic { .. }
                    | Op::FloatCompare(_)
                    | Op::Convert(_)
                    | Op::Increment(_)
                    | Op::Decrement(_)
                    | Op::SetUnconditional(_)
                    | Op::ResetUnconditional(_)
                    | Op::TestBit { .. }
                    | Op::AddConstant { .. }
                    | Op::NotSimulated { .. }
                    | Op::S7(_)
                    | Op::S7Scan(..)
                    | Op::S7Write(..)
                    | Op::S7ScanPair { .. }
                    | Op::S7ScanWrite { .. }
                    | Op::Native(_)
                    | Op::Interrupts { .. } => {
                        sync!();
                        let result = self.execute_other(*op, at!());
                        reload!();
                        if let Err((cause, fault)) = result {
                            detail = fault;
                            break 'run Leave::Stop(cause, at!());
                        }
                    }
                }
                break 'dispatch;
            }
            probe_after!('run, op_pc, op);
            ended_op = OPERATION_POINTS;
        };
        sync!();
        let exit = match leave {
            Leave::LevelEnd => Exit::LevelEnd,
            Leave::Point(point) => Exit::Point(point),
            Leave::Stop(cause, at) => Exit::Stop(self.stop_at(cause, at, detail)),
        };
        self.level.pc = (pc - start) as u32;
        self.instructions = count_base.wrapping_add(pc as u64);
        exit
    }
}

/// What became of a native stretch (see `Cpu::run_stretch`).
enum Stretched {
    Ran(StretchRan),
    /// A point falls due inside, or there is no native code: the stretch runs op by op, from
    /// this op (the arena's first).
    OpByOp(Op),
}

struct StretchRan {
    registers: (Status, u32, u32),
    /// What the count and the clock gained beyond the positions: whole passes of a loop, and the
    /// leaf blocks called.
    shift_ops: u64,
    shift_ns: u64,
    /// After whole passes of a loop, the clock where the last jump back landed.
    landed: Option<u64>,
    /// Where the loop goes on.
    resume: usize,
}

impl Cpu {
    /// The native code of the program's stretches, if it has any.
    fn native_code(&self) -> Option<&NativeCode> {
        self.native.as_deref()
    }

    /// Runs the native stretch `index` starting at `first`, op `first_pc` of the running block,
    /// for the loop's arm: a loop's whole passes while no point falls due in one or at its end,
    /// else the stretch once. `deadline` is the attention time on the scale of `times`
    /// (`u64::MAX` with block points). Out of line: it runs once a stretch, and inlined its
    /// loads of the CPU's fields went to every op's dispatch (callgrind, `programs/bench/fb_params`).
    #[inline(never)]
    fn run_stretch<const OPERATION_POINTS: bool>(
        &mut self,
        native: Option<&NativeCode>,
        index: u32,
        time_base: u64,
        (first, first_pc, deadline): (usize, u32, u64),
        (status, accu1, accu2): (Status, u32, u32),
    ) -> Stretched {
        let Some((native, stretch)) = native.and_then(|code| Some((code, code.stretch(index)?)))
        else {
            return Stretched::OpByOp(self.program.arena.ops[first]);
        };
        let times = &self.program.arena.times;
        let len = stretch.len as usize;
        if times[first].saturating_add(stretch.until_last) >= deadline {
            return Stretched::OpByOp(stretch.first);
        }
        // A leaf call that would find no room on the block stack stops the CPU, op by op.
        let depth = stretch.depth as usize;
        if depth > 0
            && (self.frames.len() + depth > self.level.frame_limit
                || !self.frames.has_room_for(depth))
        {
            return Stretched::OpByOp(stretch.first);
        }
        let clock = time_base.wrapping_add(times[first]);
        // With block points, its block changes are points: none may fall due.
        let changes = if OPERATION_POINTS {
            None
        } else {
            stretch.changes
        };
        if changes.is_some() && clock.saturating_add(stretch.span_ns) >= self.attention_at {
            return Stretched::OpByOp(stretch.first);
        }
        let most = if stretch.pass_ns == 0 {
            0
        } else {
            full_passes(self.attention_at, clock, stretch.pass_ns)
        };
        let mut status = status;
        let mut accus = [accu1, accu2, self.level.accu3, self.level.accu4];
        // The instance data, where it works on any: a missing or short instance DB, or AR2 on
        // a bit, stops the CPU or runs on, op by op.
        let (instance_db, start) = match stretch.instance {
            None => (None, 0),
            Some(InstanceData::Db(slot)) => (Some(slot), 0),
            Some(InstanceData::Running) => {
                let offset = self.level.ar2 & 0x0007_FFFF;
                if !offset.is_multiple_of(8) {
                    return Stretched::OpByOp(stretch.first);
                }
                (Some(self.level.di), (offset / 8) as usize)
            }
        };
        let data = match instance_db {
            None => &mut [][..],
            Some(slot) => match self.s7_data.get_mut(usize::from(slot)) {
                Some(Some(bytes)) if start <= bytes.len() => &mut bytes[start..],
                _ => return Stretched::OpByOp(stretch.first),
            },
        };
        let memories = (&mut self.image[..], data);
        let Some(ran) = native.run(index, most, &mut status, &mut accus, memories) else {
            return Stretched::OpByOp(stretch.first);
        };
        if let Some(slot) = instance_db.filter(|_| stretch.calls_fb) {
            self.level.db = slot;
        }
        [_, _, self.level.accu3, self.level.accu4] = accus;
        let registers = (status, accus[0], accus[1]);
        if let Some(changes) = changes {
            // The body ran once per pass, and once more where the loop's jump was not taken.
            let runs = ran.passes.max(1) + u32::from(ran.left_loop && ran.passes > 0);
            self.mark_changes(clock, first_pc, &changes, (runs, stretch.pass_ns));
        }
        if ran.passes == 0 && !ran.left_loop {
            return Stretched::Ran(StretchRan {
                registers,
                shift_ops: stretch.called_ops,
                shift_ns: stretch.called_ns,
                landed: None,
                resume: first + len,
            });
        }
        // Whole passes of a loop, and then, where its jump was not taken, the stretch once more
        // and the jump; else the passes ended at its start.
        let passes = u64::from(ran.passes);
        let pass_ops = len as u64 + 1 + stretch.called_ops;
        let passes_ns = passes * stretch.pass_ns;
        let (once_ops, once_ns, resume) = if ran.left_loop {
            (stretch.called_ops, stretch.called_ns, first + len + 1)
        } else {
            (0, 0, first)
        };
        Stretched::Ran(StretchRan {
            registers,
            shift_ops: passes * pass_ops + once_ops,
            shift_ns: passes_ns + once_ns,
            landed: (passes > 0).then(|| clock.wrapping_add(passes_ns)),
            resume,
        })
    }
}

impl Cpu {
    /// Marks the block changes of a stretch that started at `clock` with op `first_pc` of the
    /// running block and ran `runs` times, each `pass_ns` after the one before (a loop's
    /// passes), as marking each in turn would (see `mark_point`). Out of line: inlined, it
    /// costs the loop's other paths registers.
    #[inline(never)]
    fn mark_changes(
        &mut self,
        clock: u64,
        first_pc: u32,
        changes: &BlockChanges,
        (runs, pass_ns): (u32, u64),
    ) {
        let kind = |change: Change| StretchKind::Block {
            block: change.block.unwrap_or(self.level.block),
            end_pc: change.block.map_or(first_pc + change.pc, |_| change.pc),
        };
        let first_at = clock + changes.first_ns;
        self.longest_block
            .record(first_at - self.last_point_at, kind(changes.first));
        self.longest_block
            .record(changes.longest_ns, kind(changes.longest));
        if runs > 1 {
            // From a pass's last change to the next pass's first: after the first pass's own.
            let across = pass_ns - changes.last_ns + changes.first_ns;
            self.longest_block.record(across, kind(changes.first));
        }
        let last_run = clock + u64::from(runs - 1) * pass_ns;
        self.last_stretch = LastStretch {
            kind: kind(changes.last),
            start_ns: last_run + changes.before_last_ns,
            end_ns: last_run + changes.last_ns,
        };
        self.last_point_at = last_run + changes.last_ns;
    }
}

/// How many whole passes of `pass_ns` starting at `clock` end before `attention_at`.
fn full_passes(attention_at: u64, clock: u64, pass_ns: u64) -> u32 {
    let before = attention_at.saturating_sub(clock).saturating_sub(1);
    u32::try_from(before / pass_ns).unwrap_or(u32::MAX)
}

/// `attention_at` on the scale of the prefix times of a body whose clock is
/// `time_base + times[pc]`: the first time value at which the clock reaches it. `time_base` may
/// stand below zero (wrapped).
fn deadline_on(attention_at: u64, time_base: u64) -> u64 {
    if (time_base as i64) < 0 {
        attention_at.saturating_add(time_base.wrapping_neg())
    } else {
        attention_at.saturating_sub(time_base)
    }
}

#[cfg(test)]
mod tests {
    use super::{deadline_on, full_passes};

    #[test]
    fn whole_passes_are_those_that_end_before_the_attention_time() {
        // Passes of 10 ns from 100: the fourth ends at 140, not before an attention at 140.
        assert_eq!(full_passes(140, 100, 10), 3);
        assert_eq!(full_passes(141, 100, 10), 4);
        assert_eq!(full_passes(100, 100, 10), 0);
        assert_eq!(full_passes(50, 100, 10), 0);
        assert_eq!(full_passes(u64::MAX, 0, 1), u32::MAX);
    }

    #[test]
    fn the_deadline_is_the_attention_time_on_the_scale_of_the_body() {
        let bases: [i64; 7] = [-5_000_000, -1_000, -1, 0, 1, 999, 7_000_000];
        let attentions = [0, 1, 500, 1_000, 6_999_999, 7_000_000, 9_000_000, u64::MAX];
        for base in bases {
            for attention in attentions {
                let deadline = deadline_on(attention, base as u64);
                for time in [0u64, 1, 499, 500, 1_001, 2_000_000, 8_000_000, 12_000_000] {
                    let clock = i128::from(base) + i128::from(time);
                    if clock < 0 {
                        continue;
                    }
                    assert_eq!(
                        time >= deadline,
                        clock >= i128::from(attention),
                        "base {base} attention {attention} time {time}"
                    );
                }
            }
        }
    }
}
