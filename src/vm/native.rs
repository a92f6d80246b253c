//! Straight-line stretches as native code. A stretch is a run of ops in one body without a
//! jump, call, block end or anything else that can fault or leave: bit logic on I, Q and F,
//! loads and transfers of the image and of constants, 16-bit addition, subtraction and
//! comparison. Its simulated time is already one difference of the body's prefix times, and no
//! op in it can stop the CPU, so the loop runs it as one call into code the `awl-jit` crate
//! compiled, whenever no interrupt point can fall due inside it (with operation points, the
//! loop checks the stretch's end time once; with block points a stretch holds no point at all).
//! Otherwise, and where no native code could be made, the ops run one by one as before.
//!
//! The stretches are marked in a copy of the arena's code: [`Op::Native`] at a stretch's first
//! position; every other position keeps its op, so a jump into a stretch runs on from there.

use std::sync::OnceLock;

use awl_jit::{BitAction, Compiler, LoopBack, Registers, Step};

use super::status::Status;
use super::{IMAGE_MEMORY, NativeRun, NativeStretch};
use crate::compiler::Program;
use crate::compiler::bytecode::{
    Arith, Comparison, ImageBit, JumpCondition, Logic, NO_PARAMS, Op, Width, Write,
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

/// The native code of a program's stretches.
#[derive(Debug)]
pub struct NativeCode {
    /// The arena's code with [`Op::Native`] at each stretch's start: for block points and traced
    /// runs, where a block change is a point or an event.
    code: Box<[Op]>,
    /// The same where a stretch may also run a call of a leaf block (see [`leaf`]): for untraced
    /// runs with operation points, where a block change is neither.
    operation_code: Box<[Op]>,
    /// Whether `code` and `operation_code` hold any stretch (else the plain loops run).
    in_code: bool,
    in_operation_code: bool,
    stretches: Box<[NativeStretch]>,
    jit: awl_jit::Code,
}

impl NativeCode {
    /// Whether the code for these points (`operation_points`) holds any stretch.
    pub fn holds_stretches(&self, operation_points: bool) -> bool {
        if operation_points {
            self.in_operation_code
        } else {
            self.in_code
        }
    }

    /// The code with the stretches marked; `leaf_calls`: those that run leaf calls too.
    pub fn code(&self, leaf_calls: bool) -> &[Op] {
        if leaf_calls {
            &self.operation_code
        } else {
            &self.code
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
    let mut code = program.arena.ops.to_vec();
    let mut operation_code = code.clone();
    let mut stretches = Vec::new();
    let call_free = find(plain, &|_| None);
    let with_calls = find(plain, &|op| leaf(program, op));
    let mut compiled = std::collections::HashMap::new();
    for (found, calls) in chosen(call_free, with_calls) {
        let range = found.start..found.start + found.len;
        let calls = calls && plain[range].iter().any(|op| step(*op).is_none());
        let key = (found.start, found.len, calls);
        let index = match compiled.get(&key) {
            Some(index) => *index,
            None => {
                let index = stretches.len();
                let flat = flatten(program, &found, calls);
                compiler
                    .add(&flat.steps, found.loop_back.map(loop_back))
                    .ok()?;
                let times = &program.arena.times;
                let jump = found.start + found.len;
                let pass = |ns: u64| times[jump + 1] - times[found.start] + ns;
                stretches.push(NativeStretch {
                    len: found.len as u32,
                    first: code[found.start],
                    pass_ns: found.loop_back.map_or(0, |_| pass(flat.called_ns)),
                    until_last: flat.until_last,
                    called_ops: flat.called_ops,
                    called_ns: flat.called_ns,
                });
                compiled.insert(key, index);
                index
            }
        };
        let marker = Op::Native(index as u32);
        operation_code[found.start] = marker;
        if !calls {
            code[found.start] = marker;
        }
    }
    if stretches.is_empty() {
        return None;
    }
    let holds_stretch = |code: &[Op]| code.iter().any(|op| matches!(op, Op::Native(_)));
    Some(NativeCode {
        in_code: holds_stretch(&code),
        in_operation_code: holds_stretch(&operation_code),
        code: code.into_boxed_slice(),
        operation_code: operation_code.into_boxed_slice(),
        stretches: stretches.into_boxed_slice(),
        jit: compiler.finish().ok()?,
    })
}

/// A call of a leaf block: a block whose body is native steps and its block end, without
/// local data, called without parameters. Run inside a stretch, it is its status rules (the
/// call's, the body's, the end's) and its time; with operation points and no trace nothing else
/// of a block change shows.
#[derive(Debug, Clone, Copy)]
struct Leaf {
    /// Where its body starts in the arena, and its ops with the block end.
    entry: usize,
    ops: usize,
    end: Op,
}

fn leaf(program: &Program, op: Op) -> Option<Leaf> {
    let Op::Call {
        block,
        conditional: false,
        params: NO_PARAMS,
    } = op
    else {
        return None;
    };
    if program.local_bytes(block) != 0 {
        return None;
    }
    let entry = program.arena.start(block, NO_PARAMS);
    let body = program.arena.plain.get(entry..)?;
    let end = body.iter().position(|op| step(*op).is_none())?;
    let ends = matches!(body[end], Op::BlockEnd | Op::BlockEndUnconditional);
    (ends && body.get(end + 1) == Some(&Op::End)).then_some(Leaf {
        entry,
        ops: end + 1,
        end: body[end],
    })
}

/// A stretch as the steps it runs, with the leaf blocks it calls laid in.
struct Flat {
    steps: Vec<Step>,
    until_last: u64,
    called_ops: u64,
    called_ns: u64,
}

fn flatten(program: &Program, found: &Found, calls: bool) -> Flat {
    let plain = &program.arena.plain;
    let times = &program.arena.times;
    let step7 = program.s7.step7;
    let mut flat = Flat {
        steps: Vec::new(),
        until_last: 0,
        called_ops: 0,
        called_ns: 0,
    };
    // Each op's time, in the order they run.
    let mut costs = Vec::new();
    for at in found.start..found.start + found.len {
        costs.push(times[at + 1] - times[at]);
        if let Some(step) = step(plain[at]) {
            flat.steps.push(step);
            continue;
        }
        let Some(leaf) = leaf(program, plain[at]).filter(|_| calls) else {
            continue;
        };
        flat.steps.push(Step::Status(called(step7)));
        for body_at in leaf.entry..leaf.entry + leaf.ops {
            costs.push(times[body_at + 1] - times[body_at]);
            flat.steps.extend(step(plain[body_at]));
        }
        flat.steps.push(Step::Status(ended(step7, leaf.end)));
        flat.called_ops += leaf.ops as u64;
        flat.called_ns += times[leaf.entry + leaf.ops] - times[leaf.entry];
    }
    flat.until_last = costs[..costs.len() - 1].iter().sum();
    flat
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
            .map(|op| leaf(*op).map_or(1, |leaf| 1 + leaf.ops))
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
    fn multiplication_and_data_blocks_end_a_stretch() {
        assert!(step(Op::Arithmetic(Arith::Mul)).is_none());
        let data = Op::LoadData(crate::compiler::bytecode::DataPart::Word, 3);
        assert!(step(data).is_none());
        assert!(step(Op::S7Scan(Combination::Xor, ImageBit { byte: 0, bit: 7 })).is_some());
    }
}
