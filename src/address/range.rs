//! The CPU's ranges of STEP 5 addresses: the compiler's operand checks, the symbol table's and
//! the scenario's, and the operands `DO` forms at run time.

use crate::ast::Address;
use crate::mnemonics::{Area, MnemonicSet, area_word};
use crate::profile::{Profile, Sizes};

/// An address past the CPU's range: what was written and the range allowed, in the program's
/// mnemonic set (`FW 300`, `FW 0…254`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutOfRange {
    pub what: String,
    pub range: String,
}

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

/// Whether `address` is within the CPU's ranges, and if not, what to say.
pub fn check(address: Address, set: MnemonicSet, profile: &Profile) -> Result<(), OutOfRange> {
    let word = area_word(set, address.area);
    let max = limit(address.area, profile);
    if address.index > max {
        return Err(OutOfRange {
            what: format!("{word} {}", address.index),
            range: format!("{word} 0…{max}"),
        });
    }
    let max_bit = if address.area == Area::DataBit { 15 } else { 7 };
    if address.area.is_bit() && address.bit > max_bit {
        return Err(OutOfRange {
            what: format!("bit {} of {word} {}", address.bit, address.index),
            range: format!("bits 0…{max_bit}"),
        });
    }
    Ok(())
}

/// Whether an address is within the CPU's ranges (for operands formed at run time by `DO`).
pub fn address_in_range(address: Address, profile: &Profile) -> bool {
    let max_bit = if address.area == Area::DataBit { 15 } else { 7 };
    address.index <= limit(address.area, profile)
        && (!address.area.is_bit() || address.bit <= max_bit)
}
