//! FB bodies specialised per call: an FB called with a list of actual parameters that are all
//! known when the program is compiled (no parameter passed on from a calling FB) gets a copy
//! of its code with every operation on a formal operand replaced by the op it stands for, so
//! the VM runs it like any other op. Positions, times and spans stay those of the FB's own code;
//! an operation that cannot be substituted keeps its formal op and fails at run time as before.

use crate::mnemonics::{Area, OpCode};

use super::bytecode::{NO_PARAMS, Op};
use super::lower::{self, Resolved};
use crate::address::Layout;

/// The body of FB code `code` called with the actual parameters `list`, when all of them are
/// known (none is a formal operand of a calling FB).
pub fn body(code: &[Op], list: &[Resolved], layout: Layout) -> Option<Box<[Op]>> {
    if list
        .iter()
        .any(|actual| matches!(actual, Resolved::Formal(_)))
    {
        return None;
    }
    Some(substituted(code, list, layout))
}

fn substituted(code: &[Op], list: &[Resolved], layout: Layout) -> Box<[Op]> {
    code.iter()
        .map(|op| match *op {
            Op::Formal { op: code, param } => list
                .get(usize::from(param))
                .and_then(|actual| formal_op(code, *actual, layout))
                .unwrap_or(*op),
            other => other,
        })
        .collect()
}

/// The op an operation on a formal operand runs as with `actual`: what the VM substitutes at
/// run time too. `None` when the actual does not fit the operation.
pub fn formal_op(code: OpCode, actual: Resolved, layout: Layout) -> Option<Op> {
    let code = formal_meaning(code, actual)?;
    lower::lower(code, actual, layout, NO_PARAMS).filter(|op| !op.resolved_at_run_time())
}

/// The basic operation a formal-operand operation runs as with `actual`: `RB =` resets a bit,
/// `RD =` a timer or counter, `LW =` and `LD =` load a D parameter's constant, `DO =` (German
/// `B =`) opens the DB or calls the block the parameter names. `None` when the actual does not
/// fit the operation; every other operation runs as itself.
pub fn formal_meaning(code: OpCode, actual: Resolved) -> Option<OpCode> {
    let area = match actual {
        Resolved::Address(address) => Some(address.area),
        _ => None,
    };
    match code {
        OpCode::ResetBinary => area.filter(|area| area.is_bit()).map(|_| OpCode::Reset),
        OpCode::ResetDigital => area
            .filter(|area| matches!(area, Area::Timer | Area::Counter))
            .map(|_| OpCode::Reset),
        OpCode::LoadBitPattern | OpCode::LoadDecimal => {
            matches!(actual, Resolved::Constant(_)).then_some(OpCode::Load)
        }
        OpCode::Indirect => match actual {
            Resolved::Block { kind, .. } if kind.is_data() => Some(OpCode::OpenDb),
            Resolved::Block { .. } => Some(OpCode::JumpUnconditional),
            _ => None,
        },
        other => Some(other),
    }
}
