//! The numbers of operations that take a plain number (the address ranges are the address
//! model's, [`crate::address::range`]).

use crate::mnemonics::OpCode;

/// The allowed numbers of operations that take a plain number.
pub fn number_range(op: OpCode) -> Option<&'static str> {
    match op {
        OpCode::Nop => Some("NOP 0 or NOP 1"),
        OpCode::Display | OpCode::Increment | OpCode::Decrement => Some("0…255"),
        OpCode::ShiftLeft | OpCode::ShiftRight => Some("0…15"),
        OpCode::TransferBytes => Some("1…255"),
        OpCode::LoadIndirect | OpCode::TransferIndirect => Some("0…15"),
        _ => None,
    }
}
