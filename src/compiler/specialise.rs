//! FB bodies specialised per call: an FB called with a list of actual parameters that are all
//! known when the program is compiled (no parameter passed on from a calling FB) gets a copy
//! of its code with every operation on a formal operand replaced by the op it stands for, so
//! the VM runs it like any other op. Positions, times and spans stay those of the FB's own code;
//! an operation that cannot be substituted keeps its formal op and fails at run time as before.
//!
//! So is a STEP 7 FC: an operation on an elementary parameter whose actual is an I, Q or M
//! address reaches that address through the pointer the call passes ("Programming with STEP 7",
//! parameter passing), so it runs as the inline op on the address itself.

use crate::mnemonics::{Area, OpCode};
use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{MemOp, Place, S7Code, Target};

use super::bytecode::{ImageBit, NO_PARAMS, Op, Write};
use super::lower::{self, Resolved};
use crate::address::Layout;

/// The body of FB code `code` called with the actual parameters `list`, when all of them are
/// known (none is a formal operand of a calling FB); `places`: the STEP 7 places the ops name.
pub fn body(code: &[Op], list: &[Resolved], layout: Layout, places: &[Place]) -> Option<Box<[Op]>> {
    if list
        .iter()
        .any(|actual| matches!(actual, Resolved::Formal(_)))
    {
        return None;
    }
    Some(substituted(code, list, layout, places))
}

fn substituted(code: &[Op], list: &[Resolved], layout: Layout, places: &[Place]) -> Box<[Op]> {
    code.iter()
        .map(|op| match *op {
            Op::Formal { op: code, param } => list
                .get(usize::from(param))
                .and_then(|actual| formal_op(code, *actual, layout))
                .unwrap_or(*op),
            Op::S7(S7Code::Mem { op: mem, place }) => {
                parameter_op(mem, place, list, places).unwrap_or(*op)
            }
            other => other,
        })
        .collect()
}

/// A STEP 7 operation `mem` on place `place` when that is an FC parameter whose actual in
/// `list` is an I, Q or M address of the parameter's width: the inline op on that address.
fn parameter_op(mem: MemOp, place: u16, list: &[Resolved], places: &[Place]) -> Option<Op> {
    let formal = places.get(usize::from(place))?;
    let Target::Parameter {
        param,
        byte: 0,
        bit: 0,
    } = formal.target
    else {
        return None;
    };
    let Some(Resolved::S7(actual)) = list.get(usize::from(param)) else {
        return None;
    };
    let actual = places.get(usize::from(*actual))?;
    let Target::Image { byte, bit } = actual.target else {
        return None;
    };
    if actual.width != formal.width {
        return None;
    }
    if formal.width == AccessWidth::Bit {
        let bit = ImageBit { byte, bit };
        return Some(match mem {
            MemOp::Scan(combination) => Op::S7Scan(combination, bit),
            MemOp::Assign => Op::S7Write(Write::Assign, bit),
            MemOp::Set => Op::S7Write(Write::Set, bit),
            MemOp::Reset => Op::S7Write(Write::Reset, bit),
            _ => return None,
        });
    }
    let width = super::step7::lower::width_of(formal.width);
    match mem {
        MemOp::Load => Some(Op::load_image(width, byte)),
        MemOp::Transfer => Some(Op::transfer_image(width, byte)),
        _ => None,
    }
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
