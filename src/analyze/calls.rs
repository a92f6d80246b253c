//! The call graph: which blocks each block calls, the deepest call chain from each OB,
//! recursion, and the blocks no OB reaches.

use crate::compiler::{Program, Resolved};

use super::flow::{Callee, Step, step};

/// The blocks `block` may call: its calls, and for a call through a parameter every block
/// an FB call passes as an actual parameter.
pub fn callees(program: &Program, block: u16) -> Vec<u16> {
    let mut out: Vec<u16> = Vec::new();
    for op in &program.blocks[usize::from(block)].code {
        if let Step::Call { callee, .. } = step(*op) {
            match callee {
                Callee::Block(index) => out.push(index),
                Callee::Parameter => out.extend(parameter_blocks(program)),
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// Every logic block some FB call passes as a block parameter.
pub fn parameter_blocks(program: &Program) -> Vec<u16> {
    program
        .param_lists
        .iter()
        .flatten()
        .filter_map(|actual| match actual {
            Resolved::Block {
                index: Some(index), ..
            } => Some(*index),
            _ => None,
        })
        .collect()
}

/// The deepest chain of calls from `root` (blocks, the root included), or the cycle of a
/// recursion on the way.
pub fn deepest(program: &Program, root: u16) -> Result<Vec<u16>, Vec<u16>> {
    let mut memo: Vec<Option<Vec<u16>>> = vec![None; program.blocks.len()];
    let mut stack = Vec::new();
    chain(program, root, &mut memo, &mut stack)
}

fn chain(
    program: &Program,
    block: u16,
    memo: &mut Vec<Option<Vec<u16>>>,
    stack: &mut Vec<u16>,
) -> Result<Vec<u16>, Vec<u16>> {
    if let Some(at) = stack.iter().position(|on| *on == block) {
        let mut cycle = stack[at..].to_vec();
        cycle.push(block);
        return Err(cycle);
    }
    if let Some(known) = &memo[usize::from(block)] {
        return Ok(known.clone());
    }
    stack.push(block);
    let mut longest: Vec<u16> = Vec::new();
    for callee in callees(program, block) {
        let below = chain(program, callee, memo, stack)?;
        if below.len() > longest.len() {
            longest = below;
        }
    }
    stack.pop();
    let mut path = vec![block];
    path.extend(longest);
    memo[usize::from(block)] = Some(path.clone());
    Ok(path)
}

/// The blocks reachable from `roots`.
pub fn reachable(program: &Program, roots: &[u16]) -> Vec<bool> {
    let mut seen = vec![false; program.blocks.len()];
    let mut work: Vec<u16> = roots.to_vec();
    while let Some(block) = work.pop() {
        if std::mem::replace(&mut seen[usize::from(block)], true) {
            continue;
        }
        work.extend(callees(program, block));
    }
    seen
}
