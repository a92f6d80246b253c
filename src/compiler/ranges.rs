//! Operand range checks against the CPU profile.

use crate::ast::Address;
use crate::mnemonics::{Area, MnemonicSet, OpCode, area_word};
use crate::profile::{Profile, Sizes};
use crate::source::Span;

use super::error::CheckError;

/// Which of a profile's sizes an area lies in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SizeOf {
    Image,
    Flags,
    Peripheral,
    Timers,
    Counters,
    DataWords,
}

impl SizeOf {
    pub const ALL: [SizeOf; 6] = [
        SizeOf::Image,
        SizeOf::Flags,
        SizeOf::Peripheral,
        SizeOf::Timers,
        SizeOf::Counters,
        SizeOf::DataWords,
    ];

    pub fn of(self, sizes: &Sizes) -> u16 {
        match self {
            SizeOf::Image => sizes.image_bytes,
            SizeOf::Flags => sizes.flag_bytes,
            SizeOf::Peripheral => sizes.peripheral_bytes,
            SizeOf::Timers => sizes.timers,
            SizeOf::Counters => sizes.counters,
            SizeOf::DataWords => sizes.data_words,
        }
    }
}

/// The size an area's addresses are counted in, and how many units of it one address spans
/// (a word two bytes, a double word four).
pub fn extent(area: Area) -> (SizeOf, u16) {
    match area {
        Area::Input | Area::Output | Area::InputByte | Area::OutputByte => (SizeOf::Image, 1),
        Area::InputWord | Area::OutputWord => (SizeOf::Image, 2),
        Area::Flag | Area::FlagByte => (SizeOf::Flags, 1),
        Area::FlagWord => (SizeOf::Flags, 2),
        Area::FlagDouble => (SizeOf::Flags, 4),
        Area::Timer => (SizeOf::Timers, 1),
        Area::Counter => (SizeOf::Counters, 1),
        Area::DataBit | Area::DataLeft | Area::DataRight | Area::DataWord => (SizeOf::DataWords, 1),
        Area::DataDouble => (SizeOf::DataWords, 2),
        Area::PeripheralByte | Area::ExtendedByte => (SizeOf::Peripheral, 1),
        Area::PeripheralWord | Area::ExtendedWord => (SizeOf::Peripheral, 2),
    }
}

/// The highest index an area allows on this CPU.
fn limit(area: Area, profile: &Profile) -> u16 {
    let (size, span) = extent(area);
    size.of(&profile.sizes) - span
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
