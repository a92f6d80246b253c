//! Operand range checks of the compiler: the address model's ranges as check errors, and the
//! numbers of operations that take a plain number.

use crate::address::range;
use crate::ast::Address;
use crate::mnemonics::{MnemonicSet, OpCode};
use crate::profile::Profile;
use crate::source::Span;

use super::error::CheckError;

pub fn check_address(
    address: Address,
    set: MnemonicSet,
    profile: &'static Profile,
    at: Span,
) -> Result<(), CheckError> {
    range::check(address, set, profile).map_err(|out| CheckError::OperandRange {
        what: out.what,
        at,
        range: out.range,
        cpu: profile.name,
    })
}

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
