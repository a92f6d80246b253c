//! `ADD KB n`, `ADD KF n`, `ADD DH n`: the constant's format decides the width of the addition,
//! so the op is formed from the statement's constant rather than from its resolved value.

use crate::ast::Operand;
use crate::mnemonics::ConstFormat;

use super::bytecode::Op;

/// The op of an `ADD`, or `None` when its operand is not a KB, KF or DH constant.
pub fn lower(operand: &Operand) -> Option<Op> {
    let Operand::Constant(constant) = operand else {
        return None;
    };
    let double = match constant.format {
        ConstFormat::Byte | ConstFormat::Fixed => false,
        ConstFormat::DoubleHex => true,
        _ => return None,
    };
    Some(Op::AddConstant {
        value: constant.value,
        double,
    })
}
