//! The paths through one block's bytecode: the longest time from its start to an end
//! (`wcet`), and the longest time between two interrupt points (`stretch`), on the same op
//! times the VM counts. Conditional jumps take the worse branch; `BEB` ends a path; a
//! backward jump is a loop, bounded by a `; @bound N` comment on its first line (N passes at
//! most) or unbounded. With `Delayed`, the longest SFC 41 DIS_AIRT section: from a DIS_AIRT
//! call to the next SFC 42 EN_AIRT call or the block's end, with the blocks it calls.

use crate::compiler::builtin::Builtin;
use crate::compiler::bytecode::JumpCondition;
use crate::compiler::{CompiledBlock, Op};
use crate::mnemonics::OpCode;
use crate::step7::bytecode::{MemOp, S7Code};

/// How an op goes on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    Plain,
    Jump {
        target: usize,
        conditional: bool,
    },
    /// STEP 7's `JL`: on to one of the next `entries` ops (the list's jumps) or past them to
    /// `target`.
    JumpList {
        entries: usize,
        target: usize,
    },
    /// A block call: an interrupt point when taken.
    Call {
        callee: Callee,
        conditional: bool,
    },
    /// A block end: `BE`, `BEA`; `BEB` is conditional.
    End {
        conditional: bool,
    },
    /// A call of a block that is not loaded: STOP when taken.
    Stop {
        conditional: bool,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Callee {
    Block(u16),
    /// A block given as an FB's parameter (`JU =BLK`).
    Parameter,
}

pub fn step(op: Op) -> Step {
    match op {
        Op::Jump(condition, target) => Step::Jump {
            target: target as usize,
            conditional: condition != JumpCondition::Always,
        },
        // STEP 7's own conditional jumps; `LOOP` is one backward (a loop to bound).
        Op::S7(S7Code::Jump { target, .. } | S7Code::Loop { target }) => Step::Jump {
            target: usize::from(target),
            conditional: true,
        },
        Op::S7(S7Code::JumpList { entries, target }) => Step::JumpList {
            entries: usize::from(entries),
            target: usize::from(target),
        },
        Op::S7(S7Code::Mem {
            op: MemOp::CallFrom,
            ..
        }) => Step::Call {
            callee: Callee::Parameter,
            conditional: false,
        },
        Op::Call {
            block, conditional, ..
        } => Step::Call {
            callee: Callee::Block(block),
            conditional,
        },
        Op::CallMissing { conditional, .. }
        | Op::Builtin {
            block: Builtin::SystemOb(_),
            conditional,
            ..
        } => Step::Stop { conditional },
        Op::BlockEnd | Op::BlockEndUnconditional => Step::End { conditional: false },
        Op::BlockEndConditional => Step::End { conditional: true },
        Op::Formal {
            // `DO =BLK` (German `B =BLK`) calls the block the parameter names, or opens a DB.
            op: op @ (OpCode::JumpUnconditional | OpCode::JumpConditional | OpCode::Indirect),
            ..
        } => Step::Call {
            callee: Callee::Parameter,
            conditional: op == OpCode::JumpConditional,
        },
        _ => Step::Plain,
    }
}

/// A loop: the ops `head..=tail`, entered at `head`, and the most passes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Loop {
    pub head: usize,
    pub tail: usize,
    pub bound: Option<u32>,
}

/// The loops of a block from its backward jumps; loops that overlap without nesting are joined
/// (and bounded only when both are, by the product of their bounds).
pub fn loops(block: &CompiledBlock, bound_at: &dyn Fn(usize) -> Option<u32>) -> Vec<Loop> {
    let mut loops: Vec<Loop> = Vec::new();
    for (pc, op) in block.code.iter().enumerate() {
        if let Step::Jump { target, .. } = step(*op)
            && target <= pc
        {
            loops.push(Loop {
                head: target,
                tail: pc,
                bound: bound_at(target),
            });
        }
    }
    loops.sort_by_key(|l| (l.head, std::cmp::Reverse(l.tail)));
    let mut joined: Vec<Loop> = Vec::new();
    for next in loops {
        match joined.iter_mut().find(|l| {
            l.head == next.head || (l.head < next.head && next.head <= l.tail && l.tail < next.tail)
        }) {
            Some(same) if same.head == next.head => same.tail = same.tail.max(next.tail),
            Some(crossing) => {
                crossing.tail = next.tail;
                crossing.bound = crossing
                    .bound
                    .zip(next.bound)
                    .map(|(a, b)| a.saturating_mul(b));
            }
            None => joined.push(next),
        }
    }
    joined
}

/// What is measured along the paths.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// From the block's start to an end, with the called blocks' times.
    Wcet,
    /// Between two interrupt points: a taken call and a block end are points.
    Stretch,
    /// From an SFC 41 DIS_AIRT call to the next SFC 42 EN_AIRT call or the block's end, with
    /// the called blocks' times: the interrupts DIS_AIRT delays wait that long ("System Software
    /// for S7-300/400 System and Standard Functions", 12.4). A nested DIS_AIRT goes on with the
    /// section; the first EN_AIRT after it ends it.
    Delayed,
}

/// An op that opens or closes a DIS_AIRT section.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Airt {
    /// SFC 41 DIS_AIRT.
    Disable,
    /// SFC 42 EN_AIRT.
    Enable,
}

/// Where a path leaves a range of ops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Exit {
    Pc(usize),
    /// A block end or a STOP.
    End,
}

/// The result over a range of ops entered at its first op with time 0.
#[derive(Debug, Default)]
struct Range {
    exits: Vec<(Exit, u64, usize)>,
    /// The longest time to the range's last op, through it: one pass of a loop.
    body: Option<u64>,
    /// The longest stretch seen inside: (ns, its ops).
    best: Option<(u64, Vec<usize>)>,
}

/// How the best path reached an op: (time, first op of its stretch, the op before).
type Reach = Option<(u64, usize, usize)>;

/// The figures of one block.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Paths {
    /// `Err(reason)` when unbounded.
    pub value: Result<u64, String>,
    /// The ops the longest stretch runs through (stretch only).
    pub path: Vec<usize>,
}

pub struct Walker<'a> {
    pub block: &'a CompiledBlock,
    pub loops: &'a [Loop],
    /// The time of a called block (Wcet), or why it is unbounded.
    pub callee: &'a dyn Fn(Callee) -> Result<u64, String>,
    pub measure: Measure,
    /// The line of an op, for reasons.
    pub line: &'a dyn Fn(usize) -> u32,
    /// Whether an op is a DIS_AIRT or EN_AIRT call (read with `Delayed` only).
    pub airt: &'a dyn Fn(usize) -> Option<Airt>,
}

impl Walker<'_> {
    /// Whether a path whose stretch starts at op `start` is inside a DIS_AIRT section.
    fn opens(&self, start: usize) -> bool {
        self.measure == Measure::Delayed
            && start < self.block.code.len()
            && (self.airt)(start) == Some(Airt::Disable)
    }

    pub fn run(&self) -> Paths {
        let last = self.block.code.len().saturating_sub(1);
        match self.range(0, last, None) {
            Err(reason) => Paths {
                value: Err(reason),
                path: Vec::new(),
            },
            Ok(range) => match self.measure {
                Measure::Wcet => Paths {
                    value: Ok(range.exits.iter().map(|(_, ns, _)| *ns).max().unwrap_or(0)),
                    path: Vec::new(),
                },
                Measure::Stretch | Measure::Delayed => {
                    let (ns, path) = range.best.unwrap_or_default();
                    Paths {
                        value: Ok(ns),
                        path,
                    }
                }
            },
        }
    }

    /// The paths through `lo..=hi` entered at `lo`; `own` is the loop the range is the body
    /// of (its backward jumps to `lo` continue the loop).
    fn range(&self, lo: usize, hi: usize, own: Option<Loop>) -> Result<Range, String> {
        let mut pass = Pass {
            lo,
            hi,
            own,
            reach: vec![None; hi - lo + 2],
            out: Range::default(),
            line: self.line,
            opens: &|start| self.opens(start),
        };
        pass.reach[0] = Some((0, lo, lo));
        let mut pc = lo;
        while pc <= hi {
            let Some((value, start, _)) = pass.reach[pc - lo] else {
                pc += 1;
                continue;
            };
            if let Some(inner) = self
                .loops
                .iter()
                .find(|l| l.head == pc && Some(**l) != own && l.tail <= hi)
            {
                for (exit, ns, from) in self.through_loop(*inner, value, start, &mut pass.out)? {
                    pass.arrive(inner.tail, exit, ns, from)?;
                }
                pc = inner.tail + 1;
                continue;
            }
            let at = value + self.block.cost(pc);
            let next = Exit::Pc(pc + 1);
            match step(self.block.code[pc]) {
                Step::Plain if self.measure == Measure::Delayed => match (self.airt)(pc) {
                    // A section starts with the DIS_AIRT call, or goes on when one is open.
                    Some(Airt::Disable) if !self.opens(start) => {
                        pass.arrive(pc, next, self.block.cost(pc), pc)?;
                    }
                    Some(Airt::Enable) => {
                        if self.opens(start) {
                            let path = self.path_to(lo, pc, start, &pass.reach);
                            note(&mut pass.out.best, at, path);
                        }
                        pass.arrive(pc, next, 0, pc + 1)?;
                    }
                    _ => pass.arrive(pc, next, at, start)?,
                },
                Step::Plain => pass.arrive(pc, next, at, start)?,
                Step::JumpList { entries, target } => {
                    for entry in pc + 1..=pc + entries {
                        pass.arrive(pc, Exit::Pc(entry), at, start)?;
                    }
                    pass.arrive(pc, Exit::Pc(target), at, start)?;
                }
                Step::Jump {
                    target,
                    conditional,
                } => {
                    pass.arrive(pc, Exit::Pc(target), at, start)?;
                    if conditional {
                        pass.arrive(pc, next, at, start)?;
                    }
                }
                Step::Call {
                    callee,
                    conditional,
                } => match self.measure {
                    // Interrupts stay delayed while the called block runs.
                    Measure::Wcet | Measure::Delayed => {
                        pass.arrive(pc, next, at + (self.callee)(callee)?, start)?;
                    }
                    Measure::Stretch => {
                        // Taken, the call is a point: a new stretch starts after the callee.
                        let path = self.path_to(lo, pc, start, &pass.reach);
                        note(&mut pass.out.best, at, path);
                        pass.arrive(pc, next, 0, pc + 1)?;
                        if conditional {
                            pass.arrive(pc, next, at, start)?;
                        }
                    }
                },
                Step::End { conditional } | Step::Stop { conditional } => {
                    let counts = match self.measure {
                        Measure::Delayed => self.opens(start),
                        _ => true,
                    };
                    if counts && matches!(step(self.block.code[pc]), Step::End { .. }) {
                        let path = self.path_to(lo, pc, start, &pass.reach);
                        note(&mut pass.out.best, at, path);
                    }
                    pass.out.exits.push((Exit::End, at, start));
                    if conditional {
                        pass.arrive(pc, next, at, start)?;
                    }
                }
            }
            pc += 1;
        }
        Ok(pass.out)
    }

    /// The ops of the best path from `start` to `pc` in a range starting at `lo`; a loop on
    /// the way is shown whole.
    fn path_to(&self, lo: usize, pc: usize, start: usize, reach: &[Reach]) -> Vec<usize> {
        let mut path = vec![pc];
        let mut at = pc;
        while at > start {
            let Some((_, _, before)) = reach[at - lo] else {
                break;
            };
            if before >= at {
                break;
            }
            match self.loops.iter().find(|l| l.tail == before && l.head >= lo) {
                Some(inner) => {
                    path.extend((inner.head..=inner.tail).rev());
                    at = inner.head;
                }
                None => {
                    path.push(before);
                    at = before;
                }
            }
        }
        path.reverse();
        path.dedup();
        path
    }

    /// A loop entered with `value`: where its paths leave it, with their times.
    fn through_loop(
        &self,
        inner: Loop,
        value: u64,
        start: usize,
        out: &mut Range,
    ) -> Result<Vec<(Exit, u64, usize)>, String> {
        let body = self.range(inner.head, inner.tail, Some(inner))?;
        let pass = body.body.unwrap_or(0);
        let has_point = body.best.is_some() && self.measure == Measure::Stretch;
        // Outside a section, and opening none, a loop's length does not matter.
        let outside = self.measure == Measure::Delayed
            && !self.opens(start)
            && !(inner.head..=inner.tail).any(|pc| (self.airt)(pc) == Some(Airt::Disable));
        let passes = match (inner.bound, has_point || outside) {
            (Some(bound), _) => u64::from(bound.max(1)),
            // A point in every pass breaks the stretch: two passes bound it.
            (None, true) => 2,
            (None, false) => {
                return Err(format!(
                    "the loop at line {} has no bound (write `; @bound N` on that line)",
                    (self.line)(inner.head)
                ));
            }
        };
        let repeated = pass.saturating_mul(passes - 1);
        if let Some((ns, path)) = body.best {
            note(&mut out.best, value + repeated + ns, path);
        }
        Ok(body
            .exits
            .into_iter()
            .map(|(exit, ns, from)| {
                // A section open before the loop, or opened in it, goes on after it.
                let from = if self.opens(start) || !self.opens(from) {
                    from.min(start)
                } else {
                    from
                };
                (exit, value + repeated + ns, from)
            })
            .collect())
    }
}

/// One walk through a range of ops: where paths got to, and what left the range.
struct Pass<'a> {
    lo: usize,
    hi: usize,
    own: Option<Loop>,
    reach: Vec<Reach>,
    out: Range,
    line: &'a dyn Fn(usize) -> u32,
    /// Whether a stretch starting at an op is a DIS_AIRT section: such a path wins over one
    /// outside, whatever their times, so the section is never lost where they join.
    opens: &'a dyn Fn(usize) -> bool,
}

impl Pass<'_> {
    /// A path from op `current` arrives at `exit` with `ns`: inside the range it joins the
    /// op's best, to the range's head it is a loop pass, beyond the range it leaves it.
    fn arrive(&mut self, current: usize, exit: Exit, ns: u64, start: usize) -> Result<(), String> {
        let Exit::Pc(target) = exit else {
            self.out.exits.push((exit, ns, start));
            return Ok(());
        };
        if self.own.is_some() && target == self.lo {
            self.out.body = Some(self.out.body.map_or(ns, |body| body.max(ns)));
            return Ok(());
        }
        if target > current && target <= self.hi {
            let opens = self.opens;
            let slot = &mut self.reach[target - self.lo];
            if slot.is_none_or(|(best, from, _)| (opens(start), ns) > (opens(from), best)) {
                *slot = Some((ns, start, current));
            }
            return Ok(());
        }
        if target > self.hi || target < self.lo {
            self.out.exits.push((exit, ns, start));
            return Ok(());
        }
        Err(format!(
            "a jump back to line {} that is no loop awl can bound",
            (self.line)(target)
        ))
    }
}

fn note(best: &mut Option<(u64, Vec<usize>)>, ns: u64, path: Vec<usize>) {
    if best.as_ref().is_none_or(|(seen, _)| ns > *seen) {
        *best = Some((ns, path));
    }
}

/// The ops no path from the block's start reaches: (first, last) of each run.
pub fn unreachable(block: &CompiledBlock) -> Vec<(usize, usize)> {
    let n = block.code.len();
    let mut seen = vec![false; n];
    let mut work = vec![0usize];
    while let Some(pc) = work.pop() {
        if pc >= n || std::mem::replace(&mut seen[pc], true) {
            continue;
        }
        match step(block.code[pc]) {
            Step::Plain | Step::Call { .. } => work.push(pc + 1),
            Step::JumpList { entries, target } => {
                work.extend(pc + 1..=pc + entries);
                work.push(target);
            }
            Step::Jump {
                target,
                conditional,
            } => {
                work.push(target);
                if conditional {
                    work.push(pc + 1);
                }
            }
            Step::End { conditional } | Step::Stop { conditional } => {
                if conditional {
                    work.push(pc + 1);
                }
            }
        }
    }
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for pc in (0..n).filter(|pc| !seen[*pc]) {
        match runs.last_mut() {
            Some(run) if run.1 + 1 == pc => run.1 = pc,
            _ => runs.push((pc, pc)),
        }
    }
    runs
}
