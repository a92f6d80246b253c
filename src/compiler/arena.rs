//! The program's code as the VM runs it: every block's ops, and every FB body specialised for
//! its actual parameters, in one array, each body followed by an [`Op::End`] guard. Positions
//! into it are global, so a block change moves one index and the loop keeps one code pointer;
//! the times are prefix sums per body at the same positions (the guard's is the body's total).
//! The same code is there twice at the same positions: as compiled (`plain`, for the stepping
//! loop and operation points) and with pairs fused (`ops`, for block points; see `fuse`).

use super::CompiledBlock;
use super::bytecode::{NO_PARAMS, Op};
use super::lower::Resolved;
use super::{fuse, specialise};
use crate::address::Layout;

#[derive(Debug, Clone, Default)]
pub struct Arena {
    pub ops: Box<[Op]>,
    pub plain: Box<[Op]>,
    /// `times[i]`: the time in ns of the ops of i's body before i.
    pub times: Box<[u64]>,
    /// Where each block's own body starts.
    block_start: Box<[u32]>,
    /// Where the body an FB runs with each actual-parameter list starts: its specialised body,
    /// or its own.
    list_start: Box<[u32]>,
    /// Whether the VM may run straight-line stretches of `ops` as native code (see
    /// `vm::native`): an optimised arena, unless the program asks to be interpreted.
    pub native: bool,
}

impl Arena {
    /// Lays out `blocks`, whose STEP 7 ops name `places`; `optimised`: with the specialised FB
    /// and FC bodies and the fused pairs (else the ops run as compiled, which tests compare with).
    pub fn build(
        blocks: &[CompiledBlock],
        param_lists: &[Vec<Resolved>],
        (layout, places): (Layout, &[crate::step7::bytecode::Place]),
        optimised: bool,
    ) -> Self {
        let specialised = optimised;
        let mut arena = Arena::default();
        let mut ops = Vec::new();
        let mut plain = Vec::new();
        let mut times = Vec::new();
        let mut place = |code: &[Op], elapsed: &[u64]| {
            let start = ops.len() as u32;
            if optimised {
                ops.extend(fuse::fuse(code));
            } else {
                ops.extend_from_slice(code);
            }
            ops.push(Op::End);
            plain.extend_from_slice(code);
            plain.push(Op::End);
            times.extend_from_slice(&elapsed[..=code.len()]);
            start
        };
        arena.block_start = blocks
            .iter()
            .map(|block| place(&block.code, &block.elapsed))
            .collect();
        // The FB each list is given to (every list belongs to one call).
        let mut callee = vec![None; param_lists.len()];
        for op in blocks.iter().flat_map(|block| &block.code) {
            if let Op::Call { block, params, .. } = *op
                && let Some(slot) = callee.get_mut(usize::from(params))
            {
                *slot = Some(usize::from(block));
            }
        }
        arena.list_start = param_lists
            .iter()
            .zip(&callee)
            .map(|(list, callee)| {
                // A list no call uses: nothing runs with it.
                let Some(block) = *callee else {
                    return 0;
                };
                let fb = &blocks[block];
                match specialised
                    .then(|| specialise::body(&fb.code, list, layout, places))
                    .flatten()
                {
                    Some(body) => place(&body, &fb.elapsed),
                    None => arena.block_start[block],
                }
            })
            .collect();
        if optimised {
            for op in &mut ops {
                *op = arena.located(*op);
            }
        }
        arena.native = optimised;
        arena.ops = ops.into_boxed_slice();
        arena.plain = plain.into_boxed_slice();
        arena.times = times.into_boxed_slice();
        arena
    }

    /// A call without actual parameters as the call that knows where its callee starts.
    fn located(&self, op: Op) -> Op {
        match op {
            Op::Call {
                block,
                conditional,
                params: NO_PARAMS,
            } => Op::CallAt {
                block,
                conditional,
                entry: self.start(block, NO_PARAMS) as u32,
            },
            other => other,
        }
    }

    /// Where the body block `block` runs with actual-parameter list `params` starts (both
    /// resolved by the compiler, so always known).
    #[inline(always)]
    pub fn start(&self, block: u16, params: u16) -> usize {
        let start = if params == NO_PARAMS {
            self.block_start.get(usize::from(block))
        } else {
            self.list_start.get(usize::from(params))
        };
        start.map_or(0, |start| *start as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_call_without_parameters_knows_where_its_callee_starts() {
        let source = "OB 1\n JU PB 1\n JC PB 1\n JU FB 2\nNAME :F\nX    :I 0.0\n BE\n\
                      PB 1\n NOP 0\n BE\n\
                      FB 2\nNAME :F\nDES  :X    I BI\n A  =X\n BE\n";
        let profile = crate::profile::find("sinumerik-840c").expect("a profile");
        let built = crate::frontend::build_text("calls.awl", source, profile);
        assert!(!built.has_errors(), "{:#?}", built.diagnostics);
        let program = built.compiled.program;
        let id = crate::ast::BlockId {
            kind: crate::mnemonics::BlockKind::Pb,
            number: 1,
        };
        let pb = program.block_index(id).expect("PB 1");
        let entry = program.arena.start(pb, NO_PARAMS) as u32;
        let located = |conditional| Op::CallAt {
            block: pb,
            conditional,
            entry,
        };
        assert_eq!(program.arena.ops[0], located(false));
        assert_eq!(program.arena.ops[1], located(true));
        // A call with actual parameters finds its body by its list; the stepping loop and the
        // program as compiled show the calls as written.
        assert!(matches!(program.arena.ops[2], Op::Call { params: 0, .. }));
        assert!(matches!(program.arena.plain[0], Op::Call { .. }));
        let as_compiled = program.unoptimised();
        assert!(matches!(as_compiled.arena.ops[0], Op::Call { .. }));
    }
}
