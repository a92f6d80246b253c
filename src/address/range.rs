//! The CPU's ranges of STEP 5 addresses: the compiler's operand checks, the symbol table's and
//! the scenario's, and the operands `DO` forms at run time.

use crate::ast::Address;
use crate::mnemonics::{Area, MnemonicSet, area_word};
use crate::profile::Profile;

/// An address past the CPU's range: what was written and the range allowed, in the program's
/// mnemonic set (`FW 300`, `FW 0…254`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutOfRange {
    pub what: String,
    pub range: String,
}

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
