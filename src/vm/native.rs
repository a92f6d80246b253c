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
//! So may a STEP 7 call of a leaf block with parameters, its three ops run whole: `CALL FC`
//! whose actuals the FC reaches itself (nothing copied), and `CALL FB n, DB m` whose actuals
//! are image addresses or constants, copied into and out of the instance DB as moves the call
//! prepared when compiled; the FB's body works on DB m's bytes, which the stretch is run on
//! ("Programming with STEP 7", calling an FB: the instance DB opened as DI, its data at AR2's
//! offset, 0 for an instance DB of its own). In an FB's own code a stretch works on the running
//! FB's instance data (DI's DB from AR2's offset), and runs the calls of its multi-instances,
//! whose data lie there at offsets known when compiled.
//!
//! The stretches are marked in copies of the arena's code: [`Op::Native`] at a stretch's first
//! position; every other position keeps its op, so a jump into a stretch runs on from there.

use std::sync::OnceLock;

use awl_jit::{BitAction, Compiler, LoopBack, Memory, Registers, Spot, Step};

use super::status::Status;
use super::{BlockChanges, Change, IMAGE_MEMORY, InstanceData, NativeRun, NativeStretch};
use crate::compiler::Program;
use crate::compiler::bytecode::{
    Arith, Comparison, ImageBit, JumpCondition, Logic, Op, Width, Write,
};
use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{MemOp, ParamCopy, Place, S7Code, Target};

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
    /// The same where a stretch may also run calls of leaf blocks (see [`Leaf`]): for untraced
    /// runs, where a block change is no event (with block points, the stretch marks the points
    /// it crosses, a loop's in each pass).
    untraced_code: Box<[Op]>,
    stretches: Box<[NativeStretch]>,
    jit: awl_jit::Code,
}

impl NativeCode {
    /// The code with the stretches marked, for a traced run or an untraced one.
    pub fn code(&self, traced: bool) -> &[Op] {
        if traced {
            &self.traced_code
        } else {
            &self.untraced_code
        }
    }

    pub fn stretch(&self, index: u32) -> Option<&NativeStretch> {
        self.stretches.get(index as usize)
    }

    /// Runs stretch `index` on the registers, the image and the instance data its FB calls
    /// work on (empty for a stretch without any): up to `most` passes of a loop, or the
    /// stretch once (see [`awl_jit::Code::run`]); `None` if it could not run.
    #[inline(always)]
    pub fn run(
        &self,
        index: u32,
        most: u32,
        status: &mut Status,
        accus: &mut [u32; 4],
        memories: (&mut [u8], &mut [u8]),
    ) -> Option<NativeRun> {
        let [accu1, accu2, accu3, accu4] = *accus;
        let mut registers = Registers {
            accu1,
            accu2,
            accu3,
            accu4,
            status: u32::from(status.bits()),
        };
        let passes = self
            .jit
            .run(index as usize, &mut registers, memories, most)?;
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
    let mut untraced_code = traced_code.clone();
    let mut stretches = Vec::new();
    let leaves = Leaves::new(program);
    let call_free = find(plain, &|at| leaves.own(plain[at]));
    let with_calls = find(plain, &|at| leaves.unit(at));
    let mut compiled = std::collections::HashMap::new();
    for (found, calls) in chosen(call_free, with_calls) {
        let range = found.start..found.start + found.len;
        let calls = calls && plain[range].iter().any(|op| leaves.own(*op).is_none());
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
                    instance: found.instance,
                    calls_fb: flat.calls_fb,
                });
                compiled.insert(key, index);
                index
            }
        };
        let marker = Op::Native(index as u32);
        untraced_code[found.start] = marker;
        if !calls {
            traced_code[found.start] = marker;
        }
    }
    if stretches.is_empty() {
        return None;
    }
    Some(NativeCode {
        traced_code: traced_code.into_boxed_slice(),
        untraced_code: untraced_code.into_boxed_slice(),
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

/// A STEP 7 call a stretch runs whole: `FbEnter`/`FcEnter`, the call of a leaf block, then
/// `FbLeave`/`FcLeave`.
struct S7Call {
    leaf: Leaf,
    /// An FB's instance data, which the stretch is run on, and where the FB's lie in them.
    instance: Option<(InstanceData, u32)>,
    /// The parameter copies before and after the call.
    enter: Vec<Step>,
    leave: Vec<Step>,
}

/// What a stretch runs at one place of the arena: how many ops, how many with those of the
/// leaf blocks they call, and the instance data they work on.
#[derive(Debug, Clone, Copy)]
struct Unit {
    len: usize,
    weight: usize,
    instance: Option<InstanceData>,
}

impl Unit {
    /// An op that runs `weight` ops: its own step, or a call of a leaf block.
    fn op(weight: usize) -> Self {
        Unit {
            len: 1,
            weight,
            instance: None,
        }
    }
}

/// The leaf blocks of a program, each found once.
struct Leaves<'a> {
    program: &'a Program,
    /// By (block, actual-parameter list, nesting left, where its instance data lie).
    found: std::cell::RefCell<LeafMap>,
}

type LeafMap = std::collections::HashMap<(u16, u16, u32, Option<u32>), Option<Leaf>>;

impl<'a> Leaves<'a> {
    fn new(program: &'a Program) -> Self {
        Leaves {
            program,
            found: Default::default(),
        }
    }

    /// The leaf block `op` calls, if it calls one (`instance`: an FB whose instance data lie
    /// this many bytes into the data the stretch is run on).
    fn leaf(&self, op: Op, instance: Option<u32>) -> Option<Leaf> {
        self.within(op, DEEPEST, instance)
    }

    /// The native step of an op of a block's own code: on the running FB's instance data, if
    /// it works on them.
    fn own_step(&self, op: Op) -> Option<Step> {
        step(op, Some((&self.program.s7.places, 0)))
    }

    /// What an op of a block's own code is in a stretch, if it has a step.
    fn own(&self, op: Op) -> Option<Unit> {
        let step = self.own_step(op)?;
        let on_data = match step {
            Step::Scan { memory, .. }
            | Step::Write { memory, .. }
            | Step::Load { memory, .. }
            | Step::Transfer { memory, .. } => memory == Memory::Data,
            _ => false,
        };
        Some(Unit {
            instance: on_data.then_some(InstanceData::Running),
            ..Unit::op(1)
        })
    }

    /// What a stretch with calls runs at `at`: the op's step, a leaf call, or a STEP 7 call.
    fn unit(&self, at: usize) -> Option<Unit> {
        let op = self.program.arena.plain[at];
        if let Some(own) = self.own(op) {
            return Some(own);
        }
        if let Some(leaf) = self.leaf(op, None) {
            return Some(Unit::op(1 + leaf.runs));
        }
        let call = self.s7_call(at)?;
        Some(Unit {
            len: 3,
            weight: 3 + call.leaf.runs,
            instance: call.instance.map(|(data, _)| data),
        })
    }

    /// The STEP 7 call starting at `at` that a stretch runs whole: a `CALL FC` that copies
    /// nothing, or a `CALL FB n, DB m` or of a multi-instance whose actuals are image addresses
    /// or constants.
    fn s7_call(&self, at: usize) -> Option<S7Call> {
        let plain = &self.program.arena.plain;
        let s7 = &self.program.s7;
        let [Op::S7(enter), call, Op::S7(leave)] = *plain.get(at..at + 3)? else {
            return None;
        };
        match (enter, leave) {
            (S7Code::FcEnter { call: entered }, S7Code::FcLeave { call: left })
                if entered == left =>
            {
                let fc = s7.fc_calls.get(usize::from(entered))?;
                let copies = fc.inputs.len() + fc.outputs.len();
                if copies + fc.constants.len() + fc.pointers.len() > 0 {
                    return None;
                }
                Some(S7Call {
                    leaf: self.leaf(call, None)?,
                    instance: None,
                    enter: Vec::new(),
                    leave: Vec::new(),
                })
            }
            (S7Code::FbEnter { call: entered }, S7Code::FbLeave { call: left })
                if entered == left =>
            {
                let fb = s7.fb_calls.get(usize::from(entered))?;
                let moved_whole = fb.blocks_in.len() + fb.blocks_out.len() + fb.pointers.len();
                if fb.system.is_some() || moved_whole > 0 {
                    return None;
                }
                // A multi-instance's data lie in the running FB's, whole bytes after its start.
                let instance = match fb.multi_instance {
                    None => (InstanceData::Db(fb.instance_slot), 0),
                    Some(bits) if bits.is_multiple_of(8) => (InstanceData::Running, bits / 8),
                    Some(_) => return None,
                };
                let places = &s7.places[..];
                let copies = |copies: &[ParamCopy], into: bool| -> Option<Vec<Step>> {
                    copies
                        .iter()
                        .map(|copy| parameter_copy(copy, places, into, instance.1))
                        .collect()
                };
                Some(S7Call {
                    enter: copies(&fb.inputs, true)?,
                    leave: copies(&fb.outputs, false)?,
                    leaf: self.leaf(call, Some(instance.1))?,
                    instance: Some(instance),
                })
            }
            _ => None,
        }
    }

    fn within(&self, op: Op, depth_left: u32, instance: Option<u32>) -> Option<Leaf> {
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
        let key = (block, params, depth_left, instance);
        if let Some(known) = self.found.borrow().get(&key) {
            return *known;
        }
        let leaf = self.body(block, params, depth_left, instance);
        self.found.borrow_mut().insert(key, leaf);
        leaf
    }

    fn body(
        &self,
        block: u16,
        params: u16,
        depth_left: u32,
        instance: Option<u32>,
    ) -> Option<Leaf> {
        let entry = self.program.arena.start(block, params);
        let body = self.program.arena.plain.get(entry..)?;
        let places = instance.map(|shift| (&self.program.s7.places[..], shift));
        let (mut runs, mut depth) = (0, 1);
        for (at, op) in body.iter().enumerate() {
            runs += 1;
            if step(*op, places).is_some() {
                continue;
            }
            if let Some(inner) = self.within(*op, depth_left - 1, instance) {
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
struct Flat<'a> {
    program: &'a Program,
    leaves: &'a Leaves<'a>,
    steps: Vec<Step>,
    /// Whether it runs an FB's call, which leaves the instance DB in the DB register.
    calls_fb: bool,
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

fn flatten<'a>(program: &'a Program, leaves: &'a Leaves, found: &Found, calls: bool) -> Flat<'a> {
    let plain = &program.arena.plain;
    let times = &program.arena.times;
    let mut flat = Flat {
        program,
        leaves,
        steps: Vec::new(),
        calls_fb: false,
        last_ns: 0,
        until_last: 0,
        called_ops: 0,
        called_ns: 0,
        depth: 0,
        span_ns: 0,
        changes: Vec::new(),
    };
    let cost = |at: usize| times[at + 1] - times[at];
    let mut at = found.start;
    while at < found.start + found.len {
        let pc = (at - found.start) as u32;
        if let Some(call) = leaves.s7_call(at).filter(|_| calls) {
            let shift = call.instance.map(|(_, shift)| shift);
            flat.calls_fb |= shift.is_some();
            flat.spend(cost(at));
            flat.steps.extend(call.enter);
            flat.call(call.leaf, cost(at + 1), None, pc + 1, shift);
            flat.spend(cost(at + 2));
            flat.steps.extend(call.leave);
            at += 3;
            continue;
        }
        match leaves.own_step(plain[at]) {
            Some(step) => {
                flat.spend(cost(at));
                flat.steps.push(step);
            }
            None => flat.op(plain[at], cost(at), calls, None, pc, None),
        }
        at += 1;
    }
    flat.until_last = flat.span_ns - flat.last_ns;
    flat
}

impl Flat<'_> {
    /// The next op it runs takes `cost`.
    fn spend(&mut self, cost: u64) {
        self.last_ns = cost;
        self.span_ns += cost;
    }

    /// Lays in op `pc` of `block` (`None`: of the stretch), which takes `cost`: its step, or the
    /// leaf block it calls (`instance`: where its instance data lie in the stretch's data).
    fn op(
        &mut self,
        op: Op,
        cost: u64,
        calls: bool,
        block: Option<u16>,
        pc: u32,
        instance: Option<u32>,
    ) {
        let places = instance.map(|shift| (&self.program.s7.places[..], shift));
        if let Some(step) = step(op, places) {
            self.spend(cost);
            self.steps.push(step);
            return;
        }
        match self.leaves.leaf(op, instance).filter(|_| calls) {
            Some(leaf) => self.call(leaf, cost, block, pc, instance),
            None => self.spend(cost),
        }
    }

    /// Lays in the call of `leaf` by op `pc` of `block`, which takes `cost`, and its body.
    fn call(&mut self, leaf: Leaf, cost: u64, block: Option<u16>, pc: u32, instance: Option<u32>) {
        let program = self.program;
        self.spend(cost);
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
                self.op(op, cost, true, Some(leaf.block), body_pc, instance);
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
    /// The instance data it works on.
    instance: Option<InstanceData>,
}

/// The stretches of the arena's code: maximal runs of the units `unit` finds at a place
/// (ops with a native step, leaf calls, STEP 7 calls), broken where a jump lands (so a loop's
/// body starts one) and where the instance data change, at least [`SHORTEST`] long.
fn find(plain: &[Op], unit: &dyn Fn(usize) -> Option<Unit>) -> Vec<Found> {
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
    let mut close = |start: usize, end: usize, weight: usize, instance: Option<InstanceData>| {
        let loop_back = match plain.get(end) {
            Some(Op::Jump(condition, target)) if body_starts[end] + *target as usize == start => {
                Some(*condition)
            }
            _ => None,
        };
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
            instance,
        });
    };
    // The run being gathered: its start, weight and instance data.
    let (mut run_start, mut weight, mut instance) = (0, 0, None);
    let mut at = 0;
    while at < plain.len() {
        // `DO` runs the op after it with its own operand: that op never starts a stretch.
        let after_indirect = at > 0 && matches!(plain[at - 1], Op::Indirect { .. });
        let Some(next) = unit(at).filter(|_| !after_indirect) else {
            close(run_start, at, weight, instance);
            (run_start, weight, instance) = (at + 1, 0, None);
            at += 1;
            continue;
        };
        let other_instance =
            next.instance.is_some() && instance.is_some_and(|data| Some(data) != next.instance);
        if landings[at] || other_instance {
            close(run_start, at, weight, instance);
            (run_start, weight, instance) = (at, 0, None);
        }
        weight += next.weight;
        instance = instance.or(next.instance);
        at += next.len;
    }
    close(run_start, plain.len(), weight, instance);
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

/// The native step of an op, where it has one; `instance`: the places of a STEP 7 program and
/// how many bytes into the data the stretch is run on the running FB's instance data lie.
fn step(op: Op, instance: Option<(&[Place], u32)>) -> Option<Step> {
    const IMAGE: Memory = Memory::Image;
    Some(match op {
        Op::And(bit) => scan(IMAGE, bit, Status::scan_table(Logic::And)),
        Op::AndNot(bit) => scan(IMAGE, bit, Status::scan_table(Logic::AndNot)),
        Op::Or(bit) => scan(IMAGE, bit, Status::scan_table(Logic::Or)),
        Op::OrNot(bit) => scan(IMAGE, bit, Status::scan_table(Logic::OrNot)),
        Op::S7Scan(combination, bit) => scan(IMAGE, bit, Status::step7_scan_table(combination)),
        Op::Assign(bit) => write(Write::Assign, IMAGE, bit, string_ended()),
        Op::Set(bit) => write(Write::Set, IMAGE, bit, string_ended()),
        Op::Reset(bit) => write(Write::Reset, IMAGE, bit, string_ended()),
        Op::S7Write(kind, bit) => write(kind, IMAGE, bit, step7_assigned()),
        Op::S7(S7Code::Mem { op, place }) => {
            let (places, shift) = instance?;
            instance_step(op, place, places, shift)?
        }
        Op::OrAlone => Step::Status(or_alone()),
        Op::LoadImageByte(byte) => load(IMAGE, Width::Byte, byte),
        Op::LoadImageWord(byte) => load(IMAGE, Width::Word, byte),
        Op::LoadImageDouble(byte) => load(IMAGE, Width::Double, byte),
        Op::TransferImageByte(byte) => transfer(IMAGE, Width::Byte, byte),
        Op::TransferImageWord(byte) => transfer(IMAGE, Width::Word, byte),
        Op::TransferImageDouble(byte) => transfer(IMAGE, Width::Double, byte),
        Op::LoadConstant(value) => Step::LoadConstant(value),
        Op::Arithmetic(kind) => add_sub(kind, false)?,
        Op::ArithmeticStack(kind) => add_sub(kind, true)?,
        Op::Compare(kind) => Step::Compare(comparison(kind)),
        Op::Nop => Step::Nop,
        _ => return None,
    })
}

/// A STEP 7 operation `op` on place `place` of `places`, where that is the running FB's
/// instance data, `shift` bytes into the data the stretch is run on: the step on them. The bit
/// logic and loads and transfers the inline ops on the image run, with their rules.
fn instance_step(op: MemOp, place: u16, places: &[Place], shift: u32) -> Option<Step> {
    let place = places.get(usize::from(place))?;
    let Target::Instance { byte, bit } = place.target else {
        return None;
    };
    let bit = ImageBit {
        byte: u16::try_from(byte.checked_add(shift)?).ok()?,
        bit,
    };
    const DATA: Memory = Memory::Data;
    match (native_access(place.width), op) {
        (None, MemOp::Scan(combination)) => {
            Some(scan(DATA, bit, Status::step7_scan_table(combination)))
        }
        (None, MemOp::Assign) => Some(write(Write::Assign, DATA, bit, step7_assigned())),
        (None, MemOp::Set) => Some(write(Write::Set, DATA, bit, step7_assigned())),
        (None, MemOp::Reset) => Some(write(Write::Reset, DATA, bit, step7_assigned())),
        (Some(width), MemOp::Load) => Some(Step::Load {
            memory: DATA,
            width,
            byte: bit.byte,
        }),
        (Some(width), MemOp::Transfer) => Some(Step::Transfer {
            memory: DATA,
            width,
            byte: bit.byte,
        }),
        _ => None,
    }
}

/// A STEP 7 access width as the native code's: `None` for a bit.
fn native_access(width: AccessWidth) -> Option<awl_jit::Width> {
    match width {
        AccessWidth::Bit => None,
        AccessWidth::Byte => Some(awl_jit::Width::Byte),
        AccessWidth::Word => Some(awl_jit::Width::Word),
        AccessWidth::Double => Some(awl_jit::Width::Double),
    }
}

/// An FB call's parameter copy as a move between its actual, an image address or (`into`
/// the instance data) a constant, and its instance data, `shift` bytes into the data the
/// stretch is run on.
fn parameter_copy(copy: &ParamCopy, places: &[Place], into: bool, shift: u32) -> Option<Step> {
    let actual = places.get(usize::from(copy.actual))?;
    let width = native_access(copy.width);
    let instance = Spot {
        memory: Memory::Data,
        byte: u16::try_from(copy.byte.checked_add(shift)?).ok()?,
        bit: copy.bit,
    };
    match actual.target {
        Target::Image { byte, bit } => {
            let image = Spot {
                memory: Memory::Image,
                byte,
                bit,
            };
            let (from, to) = if into {
                (image, instance)
            } else {
                (instance, image)
            };
            Some(Step::Copy { width, from, to })
        }
        Target::Constant(value) if into => Some(Step::Put {
            width,
            to: instance,
            value,
        }),
        _ => None,
    }
}

fn scan(memory: Memory, bit: ImageBit, table: &'static [u8; 512]) -> Step {
    Step::Scan {
        memory,
        byte: bit.byte,
        bit: bit.bit,
        table,
    }
}

fn write(kind: Write, memory: Memory, bit: ImageBit, after: &'static [u8; 256]) -> Step {
    let (rlo_0, rlo_1) = match kind {
        Write::Assign => (BitAction::Clear, BitAction::Set),
        Write::Set => (BitAction::Keep, BitAction::Set),
        Write::Reset => (BitAction::Keep, BitAction::Clear),
    };
    Step::Write {
        memory,
        byte: bit.byte,
        bit: bit.bit,
        rlo_0,
        rlo_1,
        after,
    }
}

fn load(memory: Memory, width: Width, byte: u16) -> Step {
    Step::Load {
        memory,
        width: native_width(width),
        byte,
    }
}

fn transfer(memory: Memory, width: Width, byte: u16) -> Step {
    Step::Transfer {
        memory,
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
            instance: None,
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
            find(&code, &|at| step(code[at], None).map(|_| Unit::op(1))),
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

    /// The native code of a STEP 7 program for the SPEED7.
    fn compiled_step7(source: &str) -> NativeCode {
        let profile = crate::profile::find("speed7").expect("the SPEED7");
        let built = crate::frontend::build_text("calls.awl", source, profile);
        assert!(!built.has_errors(), "{:#?}", built.diagnostics);
        compile(&built.compiled.program).expect("stretches")
    }

    #[test]
    fn calls_with_parameters_run_whole_in_stretches() {
        let source = "FUNCTION_BLOCK FB 1\nVAR_INPUT\n  start : BOOL;\n  speed : INT;\nEND_VAR\n\
            VAR_OUTPUT\n  level : INT;\nEND_VAR\nVAR\n  passes : INT;\nEND_VAR\nBEGIN\n\
            L #speed;\nL #passes;\n+I;\nT #level;\nA #start;\n= M 1.0;\nEND_FUNCTION_BLOCK\n\
            FUNCTION FC 2 : VOID\nVAR_INPUT\n  on : BOOL;\nEND_VAR\nBEGIN\nA #on;\n= M 2.0;\n\
            END_FUNCTION\n\
            DATA_BLOCK DB 1\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\
            DATA_BLOCK DB 2\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\
            ORGANIZATION_BLOCK OB 1\nBEGIN\n\
            CALL FB 1, DB 1 (start := I 0.0, speed := 7, level := MW 10);\n\
            CALL FB 1, DB 1 (start := I 0.1, speed := MW 2, level := MW 12);\n\
            CALL FB 1, DB 2 (start := I 0.0, speed := MW 4, level := MW 14);\n\
            CALL FC 2 (on := I 0.2);\nCALL FC 2 (on := M 3.0);\nEND_ORGANIZATION_BLOCK\n";
        let native = compiled_step7(source);
        let instances: Vec<Option<InstanceData>> = native
            .stretches
            .iter()
            .filter(|stretch| stretch.called_ops > 0)
            .map(|stretch| stretch.instance)
            .collect();
        // The two calls on DB 1 in one stretch, then DB 2's with the FC calls after it.
        assert_eq!(instances.len(), 2, "{instances:?}");
        assert!(instances.iter().all(Option::is_some));
        assert_ne!(instances[0], instances[1]);
        assert_eq!(native.stretches[1].len, 3 + 3 + 3);
    }

    #[test]
    fn an_fb_runs_its_own_operations_and_its_multi_instances_calls_on_its_instance_data() {
        let source = "FUNCTION_BLOCK FB 1\nVAR_INPUT\n  speed : INT;\nEND_VAR\n\
            VAR_OUTPUT\n  level : INT;\nEND_VAR\nBEGIN\nL #speed;\nT #level;\n\
            END_FUNCTION_BLOCK\n\
            FUNCTION_BLOCK FB 2\nVAR\n  passes : INT;\n  inner : FB 1;\nEND_VAR\nBEGIN\n\
            L #passes;\nL 1;\n+I;\nT #passes;\n\
            CALL #inner (speed := MW 2, level := MW 4);\nL #passes;\nT MW 6;\n\
            END_FUNCTION_BLOCK\n\
            DATA_BLOCK DB 2\nFB 2\nBEGIN\nEND_DATA_BLOCK\n\
            ORGANIZATION_BLOCK OB 1\nBEGIN\nCALL FB 2, DB 2;\nEND_ORGANIZATION_BLOCK\n";
        let native = compiled_step7(source);
        let running: Vec<(u32, bool)> = native
            .stretches
            .iter()
            .filter(|stretch| stretch.instance == Some(InstanceData::Running))
            .map(|stretch| (stretch.len, stretch.calls_fb))
            .collect();
        // FB 2's body whole (4 ops, the call's 3, 2), and the part without the call (4 ops).
        assert!(running.contains(&(9, true)), "{running:?}");
    }

    #[test]
    fn multiplication_and_data_blocks_end_a_stretch() {
        assert!(step(Op::Arithmetic(Arith::Mul), None).is_none());
        let data = Op::LoadData(crate::compiler::bytecode::DataPart::Word, 3);
        assert!(step(data, None).is_none());
        let xor = Op::S7Scan(Combination::Xor, ImageBit { byte: 0, bit: 7 });
        assert!(step(xor, None).is_some());
    }

    #[test]
    fn instance_data_are_steps_only_on_the_data_a_stretch_is_run_on() {
        let places = [
            Place {
                target: Target::Instance { byte: 4, bit: 0 },
                width: AccessWidth::Word,
            },
            Place {
                target: Target::Data {
                    instance: true,
                    byte: 4,
                    bit: 0,
                },
                width: AccessWidth::Word,
            },
        ];
        let load = |place| {
            Op::S7(S7Code::Mem {
                op: MemOp::Load,
                place,
            })
        };
        assert!(step(load(0), None).is_none());
        assert!(matches!(
            step(load(0), Some((&places, 6))),
            Some(Step::Load {
                memory: Memory::Data,
                byte: 10,
                ..
            })
        ));
        // `L DIW 4` reads whatever DI holds: no step.
        assert!(step(load(1), Some((&places, 0))).is_none());
    }
}
