//! Operand range checks against the CPU profile.

use crate::ast::Address;
use crate::mnemonics::{Area, MnemonicSet, OpCode, area_word};
use crate::profile::Profile;
use crate::source::Span;

use super::error::CheckError;

/// The highest index an area allows on this CPU, and the range text for the diagnostic.
fn limit(area: Area, profile: &Profile) -> u16 {
    let sizes = &profile.sizes;
    match area {
        Area::Input | Area::Output | Area::InputByte | Area::OutputByte => sizes.image_bytes - 1,
        Area::InputWord | Area::OutputWord => sizes.image_bytes - 2,
        Area::Flag | Area::FlagByte => sizes.flag_bytes - 1,
        Area::FlagWord => sizes.flag_bytes - 2,
        Area::FlagDouble => sizes.flag_bytes - 4,
        Area::Timer => sizes.timers - 1,
        Area::Counter => sizes.counters - 1,
        Area::DataBit | Area::DataLeft | Area::DataRight | Area::DataWord => sizes.data_words - 1,
        Area::DataDouble => sizes.data_words - 2,
        Area::PeripheralByte | Area::ExtendedByte => sizes.peripheral_bytes - 1,
        Area::PeripheralWord | Area::ExtendedWord => sizes.peripheral_bytes - 2,
    }
}

pub fn check_address(
    address: Address,
    set: MnemonicSet,
    profile: &'static Profile,
    at: Span,
) -> Result<(), CheckError> {
    let word = area_word(set, address.area);
    let max = limit(address.area, profile);
    if address.index > max {
        return Err(CheckError::OperandRange {
            what: format!("{word} {}", address.index),
            at,
            range: format!("{word} 0…{max}"),
            cpu: profile.name,
        });
    }
    let max_bit = if address.area == Area::DataBit { 15 } else { 7 };
    if address.area.is_bit() && address.bit > max_bit {
        return Err(CheckError::OperandRange {
            what: format!("bit {} of {word} {}", address.bit, address.index),
            at,
            range: format!("bits 0…{max_bit}"),
            cpu: profile.name,
        });
    }
    Ok(())
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

/// Whether an address is within the CPU's ranges (for operands formed at run time by `DO`).
pub fn address_in_range(address: Address, profile: &Profile) -> bool {
    let max_bit = if address.area == Area::DataBit { 15 } else { 7 };
    address.index <= limit(address.area, profile)
        && (!address.area.is_bit() || address.bit <= max_bit)
}
