//! The state of a STEP 7 program in STEP 7 notation: `MB 1 = B#16#16`, `MW 10 = 22`,
//! `MD 20 = DW#16#3FC00000 = 1.5`, `S5T#2S500MS`, `C#5`, pointers `P#DBX 2.0`, and the registers
//! a STEP 7 PG shows beside the accumulators: the status word with BR, AR1, AR2, and the DB and
//! DI registers.

use std::collections::BTreeMap;

use serde::Serialize;

use super::s7_declared::{self, ValueView};
use crate::vm::Cpu;

/// The registers of a STEP 7 program's running level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Registers {
    /// The status word as `L STW` loads it.
    pub stw: u16,
    pub ar1: u32,
    pub ar2: u32,
    /// The DB register's data block; 0 when none is open.
    pub db: u16,
    /// The DI register's (instance) data block; 0 when none is open.
    pub di: u16,
}

impl Registers {
    pub fn of(cpu: &Cpu) -> Registers {
        let level = &cpu.level;
        Registers {
            stw: level.status.to_word(level.br),
            ar1: level.ar1,
            ar2: level.ar2,
            db: cpu.program.s7.db_number(level.db),
            di: cpu.program.s7.db_number(level.di),
        }
    }
}

/// A double word is shown as a REAL too when its bits are a normal REAL between 1e-6 and 1e10
/// in magnitude: what process values and computed REALs are. A DINT would need to lie above
/// 8.0e8 (or be negative in a narrow band) to pass, so counters and integers stay integers.
pub fn as_real(value: u32) -> Option<f32> {
    let real = f32::from_bits(value);
    (real.is_normal() && (1e-6..1e10).contains(&real.abs())).then_some(real)
}

/// `B#16#7B`
pub fn byte(value: u8) -> String {
    format!("B#16#{value:02X}")
}

/// `2#0111_1011`
pub fn bits(value: u8) -> String {
    format!("2#{:04b}_{:04b}", value >> 4, value & 0xF)
}

/// `22 = W#16#0016`: the INT, then the hex.
pub fn word(value: u16) -> String {
    format!("{} = W#16#{value:04X}", value as i16)
}

/// `DW#16#3FC00000 = 1.5`, or `DW#16#00000016 = L#22` when it is no REAL.
pub fn double(value: u32) -> String {
    format!("DW#16#{value:08X} = {}", double_value(value))
}

/// `1.5` for a REAL, else `L#22`.
pub fn double_value(value: u32) -> String {
    match as_real(value) {
        Some(real) => format!("{real:?}"),
        None => format!("L#{}", value as i32),
    }
}

/// A timer's time as STEP 7 writes an S5TIME: `S5T#1M30S`, `S5T#250MS`, `S5T#0MS`.
pub fn s5time(value: u16, base: u8) -> String {
    const BASE_MS: [u64; 4] = [10, 100, 1000, 10_000];
    let mut ms = u64::from(value) * BASE_MS[usize::from(base & 3)];
    let mut text = String::from("S5T#");
    for (unit_ms, unit) in [(3_600_000, "H"), (60_000, "M"), (1000, "S")] {
        if ms >= unit_ms {
            text.push_str(&format!("{}{unit}", ms / unit_ms));
            ms %= unit_ms;
        }
    }
    if ms > 0 || text.len() == 4 {
        text.push_str(&format!("{ms}MS"));
    }
    text
}

/// A pointer as STEP 7 writes it: `P#2.0`, or with the area of an area-crossing pointer
/// (bit 31 set) `P#DBX 2.0`.
pub fn pointer(value: u32) -> String {
    const AREAS: [&str; 8] = ["P", "I", "Q", "M", "DBX", "DIX", "L", "V"];
    let (byte, bit) = (value >> 3 & 0xFFFF, value & 7);
    if value & 0x8000_0000 == 0 {
        format!("P#{byte}.{bit}")
    } else {
        format!("P#{} {byte}.{bit}", AREAS[(value >> 24 & 7) as usize])
    }
}

/// The status word's bits as `L STW` orders them, bit 0 first.
pub fn status_word(stw: u16) -> String {
    const NAMES: [&str; 9] = ["/FC", "RLO", "STA", "OR", "OS", "OV", "CC0", "CC1", "BR"];
    let bits: Vec<String> = NAMES
        .iter()
        .enumerate()
        .map(|(n, name)| format!("{name} {}", stw >> n & 1))
        .collect();
    format!("W#16#{stw:04X}  {}", bits.join("  "))
}

/// The STEP 7 data blocks: `"DB 5"` → byte offset → value, the bytes that are not 0.
pub fn data_blocks(cpu: &Cpu) -> BTreeMap<String, BTreeMap<String, u16>> {
    cpu.s7_data
        .iter()
        .enumerate()
        .filter_map(|(slot, bytes)| Some((cpu.program.s7.db_number(slot as u16), bytes.as_ref()?)))
        .map(|(number, bytes)| {
            let non_zero = bytes
                .iter()
                .enumerate()
                .filter(|(_, byte)| **byte != 0)
                .map(|(n, byte)| (n.to_string(), u16::from(*byte)))
                .collect();
            (format!("DB {number}"), non_zero)
        })
        .collect()
}

/// The STEP 7 data blocks with declarations: `"DB 5"` → its values by name, in their types.
pub fn declared_data_blocks(cpu: &Cpu) -> BTreeMap<String, Vec<ValueView>> {
    let tables = &cpu.program.s7;
    tables
        .declared_dbs
        .iter()
        .filter_map(|(number, values)| {
            let slot = tables.db_slot(*number)?;
            let bytes = cpu.s7_data.get(usize::from(slot))?.as_ref()?;
            Some((format!("DB {number}"), s7_declared::view(values, bytes)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_are_shown_where_they_are_plausible() {
        assert_eq!(double(0x3FC0_0000), "DW#16#3FC00000 = 1.5");
        assert_eq!(double(22), "DW#16#00000016 = L#22");
        assert_eq!(double(0xFFFF_FFFF), "DW#16#FFFFFFFF = L#-1");
        assert_eq!(double(0), "DW#16#00000000 = L#0");
        assert_eq!(double_value((-4.25f32).to_bits()), "-4.25");
    }

    #[test]
    fn s5_times_name_their_units() {
        assert_eq!(s5time(250, 0), "S5T#2S500MS");
        assert_eq!(s5time(90, 2), "S5T#1M30S");
        assert_eq!(s5time(0, 1), "S5T#0MS");
        assert_eq!(s5time(999, 3), "S5T#2H46M30S");
    }

    #[test]
    fn pointers_show_their_area_when_crossing() {
        assert_eq!(pointer(0x10), "P#2.0");
        assert_eq!(pointer(0x8400_0011), "P#DBX 2.1");
        assert_eq!(pointer(0x8300_0050), "P#M 10.0");
    }

    #[test]
    fn the_status_word_lists_br_last() {
        assert_eq!(
            status_word(0x0106),
            "W#16#0106  /FC 0  RLO 1  STA 1  OR 0  OS 0  OV 0  CC0 0  CC1 0  BR 1"
        );
    }
}
