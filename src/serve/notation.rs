//! How the trace names what a client wrote: the operand in the program's dialect (English
//! mnemonics), as the scenario's own input changes are named.

use super::request::{Area, Range};

/// `MW 10`, `DB1.DBX 0.1`, `DB 10 DW 3`, `T 4`; a longer run names its first byte and its
/// length (`MB 10, 16 bytes`).
pub fn operand(step7: bool, range: Range, bit: Option<u8>) -> String {
    let (start, length) = (range.start, range.length);
    match range.area {
        Area::Timers | Area::Counters => {
            let letter = if range.area == Area::Timers { "T" } else { "C" };
            match length {
                1 => format!("{letter} {start}"),
                _ => format!("{letter} {start} to {letter} {}", start + length - 1),
            }
        }
        Area::DataBlock(number) if !step7 => step5_data(number, start, length),
        Area::DataBlock(number) => byte_area(&format!("DB{number}.DB"), "X", range, bit),
        Area::Inputs => byte_area("I", "", range, bit),
        Area::Outputs => byte_area("Q", "", range, bit),
        Area::Flags if step7 => byte_area("M", "", range, bit),
        Area::Flags => byte_area("F", "", range, bit),
    }
}

/// A byte area's bit (`I 1.3`, `DB1.DBX 0.1`), byte, word or double word (`MW 10`), or a
/// longer run (`MB 10, 16 bytes`).
fn byte_area(letters: &str, bit_letter: &str, range: Range, bit: Option<u8>) -> String {
    let (start, length) = (range.start, range.length);
    if let Some(bit) = bit {
        return format!("{letters}{bit_letter} {start}.{bit}");
    }
    let width = match length {
        1 if letters == "F" => "Y",
        1 => "B",
        2 => "W",
        4 => "D",
        _ => return format!("{letters}B {start}, {length} bytes"),
    };
    format!("{letters}{width} {start}")
}

/// A STEP 5 data block's bytes as data words: `DB 10 DW 3`, `DL 3` (its high byte), `DR 3`.
fn step5_data(number: u16, start: u32, length: u32) -> String {
    let word = start / 2;
    match (start % 2, length) {
        (0, 2) => format!("DB {number} DW {word}"),
        (0, 1) => format!("DB {number} DL {word}"),
        (1, 1) => format!("DB {number} DR {word}"),
        _ => format!("DB {number} byte {start}, {length} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operands_are_named_as_each_dialect_writes_them() {
        assert_eq!(operand(true, Range::new(Area::Flags, 10, 2), None), "MW 10");
        assert_eq!(
            operand(false, Range::new(Area::Flags, 10, 1), None),
            "FY 10"
        );
        assert_eq!(
            operand(true, Range::new(Area::Inputs, 1, 1), Some(3)),
            "I 1.3"
        );
        assert_eq!(
            operand(true, Range::new(Area::DataBlock(1), 0, 1), Some(1)),
            "DB1.DBX 0.1"
        );
        assert_eq!(
            operand(true, Range::new(Area::DataBlock(1), 4, 4), None),
            "DB1.DBD 4"
        );
        assert_eq!(
            operand(false, Range::new(Area::DataBlock(10), 6, 2), None),
            "DB 10 DW 3"
        );
        assert_eq!(
            operand(false, Range::new(Area::DataBlock(10), 7, 1), None),
            "DB 10 DR 3"
        );
        assert_eq!(
            operand(true, Range::new(Area::Outputs, 0, 16), None),
            "QB 0, 16 bytes"
        );
        assert_eq!(operand(true, Range::new(Area::Timers, 4, 1), None), "T 4");
        assert_eq!(
            operand(true, Range::new(Area::Counters, 1, 3), None),
            "C 1 to C 3"
        );
    }
}
