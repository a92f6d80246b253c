//! Straight-line stretches as native code. A stretch is a run of ops in one body without a
//! jump, call, block end or anything else that can fault or leave: bit logic on I, Q and F,
//! loads and transfers of the image and of constants, 16-bit addition, subtraction and
//! comparison. Its simulated time is already one difference of the body's prefix times, and no
//! op in it can stop the CPU, so the loop runs it as one call into code the `awl-jit` crate
//! compiled, whenever no interrupt point can fall due inside it (with operation points, the
//! loop checks the stretch's end time once; with block points a stretch holds no point at all).
//! Otherwise, and where no native code could be made, the ops run one by one as before.
//!
//! A stretch may also call leaf blocks (blocks whose bodies are such stretches, calling leaf
//! blocks in turn, and their block end): without a trace, a block change shows only as an
//! interrupt point with block points, and the stretch runs only when no request is pending and
//! nothing falls due before it ends, so no point inside it is taken; it marks the points it
//! crossed as the loop would have (see [`BlockChanges`]).
//!
//! The stretches are marked in copies of the arena's code: [`Op::Native`] at a stretch's first
//! position; every other position keeps its op, so a jump into a stretch runs on from there.

use std::sync::OnceLock;

use awl_jit::{BitAction, Compiler, LoopBack, Registers, Step};

use super::status::Status;
use super::{BlockChanges, Change, IMAGE_MEMORY, NativeRun, NativeStretch};
use crate::compiler::Program;
use crate::compiler::bytecode::{
    Arith, Comparison, ImageBit, JumpCondition, Logic, Op, Width, Write,
};
use crate::step7::bytecode::S7Code;

/// The shortest stretch that runs as native code: the call into it costs about what the
/// interpreter spends on eight ops, so `programs/bench/fb_params`' FB body of eight gains a
/// little (callgrind: 29.80 host instructions per operation op by op, 29.60 native) and a
/// shorter one would run no faster…
const SHORTEST: usize = 8;
/// …but for a loop's stretch, whose passes run in one call, and one that calls a leaf block,
/// whose call and end cost more than that.
const SHORTEST_LOOP: usize = 3;

/// How deep leaf calls nest inside a stretch at most.
const DEEPEST: u32 = 4;

/// The native code of a program's stretches.
#[derive(Debug)]
pub struct NativeCode {
    /// The arena's code with [`Op::Native`] at each stretch's start: for traced runs, where a
    /// block change is an event.
    traced_code: Box<[Op]>,
    /// The same where a stretch may also run calls of leaf blocks (see [`leaf`]): for untraced
    /// runs with operation points, where a block change is no point…
    operation_code: Box<[Op]>,
    /// …and with block points, where the stretch marks the points it crosses; a loop's stretch
    /// that calls runs op by op there (each pass would cross points of its own).
    block_code: Box<[Op]>,
    /// Whether `operation_code` and `block_code` hold any stretch (else the plain loops run).
    in_operation_code: bool,
    in_block_code: bool,
    stretches: Box<[NativeStretch]>,
    jit: awl_jit::Code,
}

impl NativeCode {
    /// Whether the code for these points (`operation_points`) holds any stretch.
    /// Whether the untraced code for these points holds any stretch.
    pub fn holds_stretches(&self, operation_points: bool) -> bool {
        if operation_points {
            self.in_operation_code
        } else {
            self.in_block_code
        }
    }

    /// The code with the stretches marked for these points, traced or not.
    pub fn code(&self, operation_points: bool, traced: bool) -> &[Op] {
        match (traced, operation_points) {
            (true, _) => &self.traced_code,
            (false, true) => &self.operation_code,
            (false, false) => &self.block_code,
        }
    }

    pub fn stretch(&self, index: u32) -> Option<&NativeStretch> {
        self.stretches.get(index as usize)
    }

    /// Runs stretch `index` on the registers and the image: up to `most` passes of a loop, or
    /// the stretch once (see [`awl_jit::Code::run`]); `None` if it could not run.
    #[inline(always)]
    pub fn run(
        &self,
        index: u32,
        most: u32,
        status: &mut Status,
        accus: &mut [u32; 4],
        image: &mut [u8],
    ) -> Option<NativeRun> {
        let [accu1, accu2, accu3, accu4] = *accus;
        let mut registers = Registers {
            accu1,
            accu2,
            accu3,
            accu4,
            status: u32::from(status.bits()),
        };
        let passes = self.jit.run(index as usize, &mut registers, image, most)?;
        *accus = [
            registers.accu1,
            registers.accu2,
            registers.accu3,
            registers.accu4,
        ];
        *status = Status::from_bits(registers.status as u8);
        Some(NativeRun {
            passes: passes.done,
            left_loop: passes.left_loop,
        })
    }
}

/// The native code of `program`'s stretches; `None` when the program has none, runs op by op
/// as compiled, or Cranelift cannot write code for this host.
pub fn compile(program: &Program) -> Option<NativeCode> {
    if !program.arena.native {
        return None;
    }
    let plain = &program.arena.plain;
    let mut compiler = Compiler::new(status_bits(), IMAGE_MEMORY).ok()?;
    let mut traced_code = program.arena.ops.to_vec();
    let mut operation_code = traced_code.clone();
    let mut block_code = traced_code.clone();
    let mut stretches = Vec::new();
    let call_free = find(plain, &|_| None);
    let leaves = Leaves::new(program);
    let with_calls = find(plain, &|op| leaves.leaf(op));
    let mut compiled = std::collections::HashMap::new();
    for (found, calls) in chosen(call_free, with_calls) {
        let range = found.start..found.start + found.len;
        let calls = calls && plain[range].iter().any(|op| step(*op).is_none());
        let key = (found.start, found.len, calls);
        let index = match compiled.get(&key) {
            Some(index) => *index,
            None => {
                let index = stretches.len();
                let flat = flatten(program, &leaves, &found, calls);
                compiler
                    .add(&flat.steps, found.loop_back.map(loop_back))
                    .ok()?;
                let times = &program.arena.times;
                let jump = found.start + found.len;
                let pass = |ns: u64| times[jump + 1] - times[found.start] + ns;
                stretches.push(NativeStretch {
                    len: found.len as u32,
                    first: traced_code[found.start],
                    pass_ns: found.loop_back.map_or(0, |_| pass(flat.called_ns)),
                    until_last: flat.until_last,
                    called_ops: flat.called_ops,
                    called_ns: flat.called_ns,
                    depth: flat.depth,
                    span_ns: flat.span_ns,
                    changes: block_changes(&flat.changes),
                });
                compiled.insert(key, index);
                index
            }
        };
        let marker = Op::Native(index as u32);
        operation_code[found.start] = marker;
        if !calls {
            traced_code[found.start] = marker;
        }
        if !calls || found.loop_back.is_none() {
            block_code[found.start] = marker;
        }
    }
    if stretches.is_empty() {
        return None;
    }
    let holds_stretch = |code: &[Op]| code.iter().any(|op| matches!(op, Op::Native(_)));
    Some(NativeCode {
        in_operation_code: holds_stretch(&operation_code),
        in_block_code: holds_stretch(&block_code),
        traced_code: traced_code.into_boxed_slice(),
        operation_code: operation_code.into_boxed_slice(),
        block_code: block_code.into_boxed_slice(),
        stretches: stretches.into_boxed_slice(),
        jit: compiler.finish().ok()?,
    })
}

/// A call of a leaf block: a block without local data whose body is native steps and calls
/// of leaf blocks (nested at most [`DEEPEST`] deep), then its block end. Run inside a stretch,
/// it is its status rules (the call's, the body's, the end's), its time and its block changes;
/// without a trace nothing else of a block change shows.
#[derive(Debug, Clone, Copy)]
struct Leaf {
    block: u16,
    /// Where its body starts in the arena, and its ops with the block end.
    entry: usize,
    ops: usize,
    end: Op,
    /// The ops it runs with those of the leaf blocks it calls, and the frames they need.
    runs: usize,
    depth: u32,
}

/// The leaf blocks of a program, each found once.
struct Leaves<'a> {
    program: &'a Program,
    /// By (block, actual-parameter list, nesting left).
    found: std::cell::RefCell<std::collections::HashMap<(u16, u16, u32), Option<Leaf>>>,
}

impl<'a> Leaves<'a> {
    fn new(program: &'a Program) -> Self {
        Leaves {
            program,
            found: Default::default(),
        }
    }

    /// The leaf block `op` calls, if it calls one.
    fn leaf(&self, op: Op) -> Option<Leaf> {
        self.within(op, DEEPEST)
    }

    fn within(&self, op: Op, depth_left: u32) -> Option<Leaf> {
        let Op::Call {
            block,
            conditional: false,
            params,
        } = op
        else {
            return None;
        };
        if depth_left == 0 || self.program.local_bytes(block) != 0 {
            return None;
        }
        let key = (block, params, depth_left);
        if let Some(known) = self.found.borrow().get(&key) {
            return *known;
        }
        let leaf = self.body(block, params, depth_left);
        self.found.borrow_mut().insert(key, leaf);
        leaf
    }

    fn body(&self, block: u16, params: u16, depth_left: u32) -> Option<Leaf> {
        let entry = self.program.arena.start(block, params);
        let body = self.program.arena.plain.get(entry..)?;
        let (mut runs, mut depth) = (0, 1);
        for (at, op) in body.iter().enumerate() {
            runs += 1;
            if step(*op).is_some() {
                continue;
            }
            if let Some(inner) = self.within(*op, depth_left - 1) {
                runs += inner.runs;
                depth = depth.max(inner.depth + 1);
                continue;
            }
            let ends = matches!(op, Op::BlockEnd | Op::BlockEndUnconditional);
            return (ends && body.get(at + 1) == Some(&Op::End)).then_some(Leaf {
                block,
                entry,
                ops: at + 1,
                end: *op,
                runs,
                depth,
            });
        }
        None
    }
}

/// A stretch as the steps it runs, with the leaf blocks it calls laid in.
struct Flat {
    steps: Vec<Step>,
    /// The time of the op it runs last.
    last_ns: u64,
    until_last: u64,
    called_ops: u64,
    called_ns: u64,
    depth: u32,
    span_ns: u64,
    /// Its block changes: the time from its start, and where.
    changes: Vec<(u64, Change)>,
}

fn flatten(program: &Program, leaves: &Leaves, found: &Found, calls: bool) -> Flat {
    let plain = &program.arena.plain;
    let times = &program.arena.times;
    let mut flat = Flat {
        steps: Vec::new(),
        last_ns: 0,
        until_last: 0,
        called_ops: 0,
        called_ns: 0,
        depth: 0,
        span_ns: 0,
        changes: Vec::new(),
    };
    for at in found.start..found.start + found.len {
        let pc = (at - found.start) as u32;
        flat.op(
            program,
            leaves,
            plain[at],
            times[at + 1] - times[at],
            calls,
            None,
            pc,
        );
    }
    flat.until_last = flat.span_ns - flat.last_ns;
    flat
}

impl Flat {
    /// The next op it runs takes `cost`.
    fn spend(&mut self, cost: u64) {
        self.last_ns = cost;
        self.span_ns += cost;
    }

    /// Lays in op `pc` of `block` (`None`: of the stretch), which takes `cost`: its step, or the
    /// leaf block it calls.
    #[allow(clippy::too_many_arguments)]
    fn op(
        &mut self,
        program: &Program,
        leaves: &Leaves,
        op: Op,
        cost: u64,
        calls: bool,
        block: Option<u16>,
        pc: u32,
    ) {
        self.spend(cost);
        if let Some(step) = step(op) {
            self.steps.push(step);
            return;
        }
        let Some(leaf) = leaves.leaf(op).filter(|_| calls) else {
            return;
        };
        self.depth = self.depth.max(leaf.depth);
        self.changes.push((self.span_ns, Change { block, pc }));
        let step7 = program.s7.step7;
        let times = &program.arena.times;
        self.steps.push(Step::Status(called(step7)));
        for body_at in leaf.entry..leaf.entry + leaf.ops {
            let cost = times[body_at + 1] - times[body_at];
            let body_pc = (body_at - leaf.entry) as u32;
            let op = program.arena.plain[body_at];
            if body_at + 1 == leaf.entry + leaf.ops {
                self.spend(cost);
                self.steps.push(Step::Status(ended(step7, leaf.end)));
                let end = Change {
                    block: Some(leaf.block),
                    pc: body_pc,
                };
                self.changes.push((self.span_ns, end));
            } else {
                self.op(program, leaves, op, cost, true, Some(leaf.block), body_pc);
            }
        }
        self.called_ops += leaf.ops as u64;
        self.called_ns += times[leaf.entry + leaf.ops] - times[leaf.entry];
    }
}

/// What marking `changes` in turn leaves behind; `None` for a stretch without any.
fn block_changes(changes: &[(u64, Change)]) -> Option<BlockChanges> {
    let (&(first_ns, first), rest) = changes.split_first()?;
    let (mut longest_ns, mut longest) = (0, first);
    let mut before = (first_ns, first);
    let mut before_last_ns = first_ns;
    for &(ns, change) in rest {
        if ns - before.0 > longest_ns {
            (longest_ns, longest) = (ns - before.0, change);
        }
        before_last_ns = before.0;
        before = (ns, change);
    }
    Some(BlockChanges {
        first_ns,
        first,
        longest_ns,
        longest,
        before_last_ns,
        last_ns: before.0,
        last: before.1,
    })
}

/// How many operations (a leaf call's counted) of stretches outside loops are compiled at
/// most. Cranelift takes some 100,000 host instructions per operation (callgrind, a
/// 97,000-operation program: 9.6 G in `awl run`, 1.4 s of CPU), and a stretch that runs once a
/// cycle gains a few instructions per operation, so a large program's start would cost more
/// than its runs gain.
const STRAIGHT_BUDGET: usize = 4_000;

/// The stretches worth their compilation, each with whether it runs leaf calls: every loop's,
/// then the others that run the most ops within [`STRAIGHT_BUDGET`], in the arena's order. A
/// stretch that calls leaf blocks comes beside the call-free ones it covers (block points and
/// traces run those).
fn chosen(call_free: Vec<Found>, with_calls: Vec<Found>) -> Vec<(Found, bool)> {
    let mut found: Vec<(Found, bool)> = call_free
        .into_iter()
        .map(|found| (found, false))
        .chain(with_calls.into_iter().map(|found| (found, true)))
        .collect();
    found.sort_by_key(|(stretch, _)| {
        (
            stretch.loop_back.is_none(),
            std::cmp::Reverse(stretch.weight),
        )
    });
    let mut budget = STRAIGHT_BUDGET;
    found.retain(|(stretch, _)| {
        let fits = stretch.loop_back.is_some() || stretch.weight <= budget;
        if fits && stretch.loop_back.is_none() {
            budget -= stretch.weight;
        }
        fits
    });
    found.sort_by_key(|(stretch, calls)| (stretch.start, *calls));
    found
}

/// A stretch of the arena's code.
#[derive(Debug, PartialEq, Eq)]
struct Found {
    start: usize,
    len: usize,
    /// The ops it runs: `len`, and the ops of the leaf blocks it calls.
    weight: usize,
    /// The condition of the jump right after it, when that jump goes back to its start.
    loop_back: Option<JumpCondition>,
}

/// The stretches of the arena's code: maximal runs of ops with a native step, broken where a
/// jump lands (so a loop's body starts one), at least [`SHORTEST`] long.
fn find(plain: &[Op], leaf: &dyn Fn(Op) -> Option<Leaf>) -> Vec<Found> {
    let mut landings = vec![false; plain.len()];
    let mut body_starts = vec![0; plain.len()];
    let mut body_start = 0;
    for (at, op) in plain.iter().enumerate() {
        body_starts[at] = body_start;
        if let Some(target) = jump_target(*op)
            && let Some(landing) = landings.get_mut(body_start + target)
        {
            *landing = true;
        }
        if *op == Op::End {
            body_start = at + 1;
        }
    }
    let mut found = Vec::new();
    let mut run_start = 0;
    // A leaf call weighs as the ops it runs.
    let weight = |range: std::ops::Range<usize>| -> usize {
        plain[range]
            .iter()
            .map(|op| leaf(*op).map_or(1, |leaf| 1 + leaf.runs))
            .sum()
    };
    let mut close = |start: usize, end: usize| {
        let loop_back = match plain.get(end) {
            Some(Op::Jump(condition, target)) if body_starts[end] + *target as usize == start => {
                Some(*condition)
            }
            _ => None,
        };
        let weight = weight(start..end);
        let shortest = if loop_back.is_some() || weight > end - start {
            SHORTEST_LOOP
        } else {
            SHORTEST
        };
        if weight < shortest {
            return;
        }
        found.push(Found {
            start,
            len: end - start,
            weight,
            loop_back,
        });
    };
    for (at, op) in plain.iter().enumerate() {
        // `DO` runs the op after it with its own operand: that op never starts a stretch.
        let after_indirect = at > 0 && matches!(plain[at - 1], Op::Indirect { .. });
        if (step(*op).is_none() && leaf(*op).is_none()) || after_indirect {
            close(run_start, at);
            run_start = at + 1;
        } else if landings[at] {
            close(run_start, at);
            run_start = at;
        }
    }
    close(run_start, plain.len());
    found
}

/// Where in its body a jump op goes.
fn jump_target(op: Op) -> Option<usize> {
    let target = match op {
        Op::Jump(_, target) => target,
        Op::S7(S7Code::Jump { target, .. } | S7Code::Loop { target }) => u32::from(target),
        Op::S7(S7Code::JumpList { target, .. }) => u32::from(target),
        _ => return None,
    };
    Some(target as usize)
}

/// The native step of an op, where it has one.
fn step(op: Op) -> Option<Step> {
    Some(match op {
        Op::And(bit) => scan(bit, Status::scan_table(Logic::And)),
        Op::AndNot(bit) => scan(bit, Status::scan_table(Logic::AndNot)),
        Op::Or(bit) => scan(bit, Status::scan_table(Logic::Or)),
        Op::OrNot(bit) => scan(bit, Status::scan_table(Logic::OrNot)),
        Op::S7Scan(combination, bit) => scan(bit, Status::step7_scan_table(combination)),
        Op::Assign(bit) => write(Write::Assign, bit, string_ended()),
        Op::Set(bit) => write(Write::Set, bit, string_ended()),
        Op::Reset(bit) => write(Write::Reset, bit, string_ended()),
        Op::S7Write(kind, bit) => write(kind, bit, step7_assigned()),
        Op::OrAlone => Step::Status(or_alone()),
        Op::LoadImageByte(byte) => load(Width::Byte, byte),
        Op::LoadImageWord(byte) => load(Width::Word, byte),
        Op::LoadImageDouble(byte) => load(Width::Double, byte),
        Op::TransferImageByte(byte) => transfer(Width::Byte, byte),
        Op::TransferImageWord(byte) => transfer(Width::Word, byte),
        Op::TransferImageDouble(byte) => transfer(Width::Double, byte),
        Op::LoadConstant(value) => Step::LoadConstant(value),
        Op::Arithmetic(kind) => add_sub(kind, false)?,
        Op::ArithmeticStack(kind) => add_sub(kind, true)?,
        Op::Compare(kind) => Step::Compare(comparison(kind)),
        Op::Nop => Step::Nop,
        _ => return None,
    })
}

fn scan(bit: ImageBit, table: &'static [u8; 512]) -> Step {
    Step::Scan {
        byte: bit.byte,
        bit: bit.bit,
        table,
    }
}

fn write(kind: Write, bit: ImageBit, after: &'static [u8; 256]) -> Step {
    let (rlo_0, rlo_1) = match kind {
        Write::Assign => (BitAction::Clear, BitAction::Set),
        Write::Set => (BitAction::Keep, BitAction::Set),
        Write::Reset => (BitAction::Keep, BitAction::Clear),
    };
    Step::Write {
        byte: bit.byte,
        bit: bit.bit,
        rlo_0,
        rlo_1,
        after,
    }
}

fn load(width: Width, byte: u16) -> Step {
    Step::Load {
        width: native_width(width),
        byte,
    }
}

fn transfer(width: Width, byte: u16) -> Step {
    Step::Transfer {
        width: native_width(width),
        byte,
    }
}

fn native_width(width: Width) -> awl_jit::Width {
    match width {
        Width::Byte => awl_jit::Width::Byte,
        Width::Word => awl_jit::Width::Word,
        Width::Double => awl_jit::Width::Double,
    }
}

/// `+F -F` (`+I -I`); multiplication and division stay in the loop.
fn add_sub(kind: Arith, stack: bool) -> Option<Step> {
    let subtract = match kind {
        Arith::Add => false,
        Arith::Sub => true,
        Arith::Mul | Arith::Div => return None,
    };
    Some(Step::AddSub { subtract, stack })
}

fn comparison(kind: Comparison) -> awl_jit::Comparison {
    match kind {
        Comparison::Eq => awl_jit::Comparison::Equal,
        Comparison::Ne => awl_jit::Comparison::NotEqual,
        Comparison::Gt => awl_jit::Comparison::Greater,
        Comparison::Ge => awl_jit::Comparison::GreaterOrEqual,
        Comparison::Lt => awl_jit::Comparison::Less,
        Comparison::Le => awl_jit::Comparison::LessOrEqual,
    }
}

/// Where the status keeps each bit, asked of the status itself.
fn status_bits() -> awl_jit::StatusBits {
    let with = |set: fn(&mut Status)| {
        let mut status = Status::default();
        set(&mut status);
        status.bits()
    };
    awl_jit::StatusBits {
        rlo: with(|status| status.set_rlo(true)),
        first_check: with(|status| status.set_first_check(true)),
        or: with(|status| status.set_or_bit(true)),
        cc1: with(|status| status.set_condition(true, false)),
        cc0: with(|status| status.set_condition(false, true)),
        ov: with(|status| status.set_ov(true)),
        os: with(|status| status.set_os(true)),
    }
}

/// A status rule as a table over every status byte, made once from the rule itself.
fn table_of(cell: &'static OnceLock<[u8; 256]>, rule: fn(&mut Status)) -> &'static [u8; 256] {
    cell.get_or_init(|| {
        std::array::from_fn(|bits| {
            let mut status = Status::from_bits(bits as u8);
            rule(&mut status);
            status.bits()
        })
    })
}

/// STEP 5's `= S R`: the string ends.
fn string_ended() -> &'static [u8; 256] {
    static TABLE: OnceLock<[u8; 256]> = OnceLock::new();
    table_of(&TABLE, Status::end_string)
}

/// STEP 7's `= S R`: STA takes the RLO, the string ends.
fn step7_assigned() -> &'static [u8; 256] {
    static TABLE: OnceLock<[u8; 256]> = OnceLock::new();
    table_of(&TABLE, |status| {
        let rlo = status.rlo();
        super::s7::bit_logic::assigned(status, rlo);
    })
}

/// A loop's jump back as tables: whether it is taken, and the status after it.
fn loop_back(condition: JumpCondition) -> LoopBack {
    const CONDITIONS: usize = 7;
    static TAKEN: [OnceLock<[u8; 256]>; CONDITIONS] = [const { OnceLock::new() }; CONDITIONS];
    static AFTER: [OnceLock<[u8; 256]>; CONDITIONS] = [const { OnceLock::new() }; CONDITIONS];
    let slot = condition as usize;
    let over_statuses = |rule: &dyn Fn(Status) -> u8| -> [u8; 256] {
        std::array::from_fn(|bits| rule(Status::from_bits(bits as u8)))
    };
    LoopBack {
        taken: TAKEN[slot]
            .get_or_init(|| over_statuses(&|mut status| u8::from(condition.taken(&mut status)))),
        after: AFTER[slot].get_or_init(|| {
            over_statuses(&|mut status| {
                condition.taken(&mut status);
                status.bits()
            })
        }),
    }
}

/// A call's status rules: a new string with RLO 1; STEP 7 clears OS.
fn called(step7: bool) -> &'static [u8; 256] {
    static STEP5: OnceLock<[u8; 256]> = OnceLock::new();
    static STEP7: OnceLock<[u8; 256]> = OnceLock::new();
    if step7 {
        table_of(&STEP7, |status| {
            status.after_jump();
            status.set_os(false);
        })
    } else {
        table_of(&STEP5, Status::after_jump)
    }
}

/// A block end's status rules (`BE` ends the string, `BEU` as a jump); STEP 7 clears OS.
fn ended(step7: bool, end: Op) -> &'static [u8; 256] {
    static TABLES: [OnceLock<[u8; 256]>; 4] = [const { OnceLock::new() }; 4];
    let unconditional = end == Op::BlockEndUnconditional;
    let cell = &TABLES[usize::from(step7) << 1 | usize::from(unconditional)];
    let rule: fn(&mut Status) = match (step7, unconditional) {
        (false, false) => Status::end_string,
        (false, true) => Status::after_jump,
        (true, false) => |status| {
            status.end_string();
            status.set_os(false);
        },
        (true, true) => |status| {
            status.after_jump();
            status.set_os(false);
        },
    };
    table_of(cell, rule)
}

/// `O` alone.
fn or_alone() -> &'static [u8; 256] {
    static TABLE: OnceLock<[u8; 256]> = OnceLock::new();
    table_of(&TABLE, Status::or_alone)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rules::status::Combination;

    /// A stretch without leaf calls.
    fn found(start: usize, len: usize, loop_back: Option<JumpCondition>) -> Found {
        Found {
            start,
            len,
            weight: len,
            loop_back,
        }
    }

    #[test]
    fn stretches_break_at_ops_without_a_step_and_where_jumps_land() {
        let bit = ImageBit { byte: 1, bit: 0 };
        let code = [
            Op::And(bit),
            Op::Or(bit),
            Op::Assign(bit),
            Op::LoadConstant(1),
            Op::Nop,
            Op::Nop,
            Op::Nop,
            Op::Nop,
            Op::Nop,
            // A jump lands here: a stretch starts, a loop's.
            Op::LoadConstant(2),
            Op::Arithmetic(Arith::Add),
            Op::TransferImageWord(4),
            Op::Jump(crate::compiler::bytecode::JumpCondition::Rlo, 9),
            // Too short for a stretch outside a loop.
            Op::Nop,
            Op::Nop,
            Op::End,
        ];
        let jump_back = Some(crate::compiler::bytecode::JumpCondition::Rlo);
        assert_eq!(
            find(&code, &|_| None),
            [found(0, 9, None), found(9, 3, jump_back)]
        );
    }

    #[test]
    fn loops_are_always_chosen_and_other_stretches_longest_first_within_the_budget() {
        let jump_back = Some(crate::compiler::bytecode::JumpCondition::Always);
        let found = vec![
            found(0, STRAIGHT_BUDGET / 2, None),
            found(10_000, 3, jump_back),
            found(20_000, STRAIGHT_BUDGET / 2 + 1, None),
            found(30_000, STRAIGHT_BUDGET / 2, None),
            found(40_000, 2 * STRAIGHT_BUDGET, jump_back),
        ];
        let starts: Vec<usize> = chosen(found, Vec::new())
            .iter()
            .map(|(found, _)| found.start)
            .collect();
        assert_eq!(starts, [10_000, 20_000, 40_000]);
    }

    #[test]
    fn block_changes_leave_what_marking_each_in_turn_leaves() {
        let at = |pc| Change { block: Some(7), pc };
        let changes = [
            (5, at(0)),
            (12, at(1)),
            (20, at(2)),
            (27, at(3)),
            (30, at(4)),
        ];
        let marked = block_changes(&changes).expect("changes");
        assert_eq!((marked.first_ns, marked.first), (5, at(0)));
        // 7, 8, 7, 3 ns between them: the first of the longest.
        assert_eq!((marked.longest_ns, marked.longest), (8, at(2)));
        assert_eq!(
            (marked.before_last_ns, marked.last_ns, marked.last),
            (27, 30, at(4))
        );
        assert!(block_changes(&[]).is_none());
    }

    #[test]
    fn multiplication_and_data_blocks_end_a_stretch() {
        assert!(step(Op::Arithmetic(Arith::Mul)).is_none());
        let data = Op::LoadData(crate::compiler::bytecode::DataPart::Word, 3);
        assert!(step(data).is_none());
        assert!(step(Op::S7Scan(Combination::Xor, ImageBit { byte: 0, bit: 7 })).is_some());
    }
}
