//! How each dialect writes the values an address holds. STEP 5: `KH 7B = 0111 1011`,
//! `KF +123 = KH 007B`, `DH 00010002 = +65538`. STEP 7: `B#16#7B`, `2#0111_1011`,
//! `22 = W#16#0016`, `DW#16#3FC00000 = 1.5`, `S5T#2S500MS`, pointers `P#DBX 2.0`, and the
//! status word with BR.

use crate::dialect::Dialect;

/// A byte with its bits: `KH 7B = 0111 1011`, `B#16#7B = 2#0111_1011`.
pub fn byte_and_bits(dialect: Dialect, value: u8) -> String {
    match dialect {
        Dialect::Step5 => format!("KH {value:02X} = {:04b} {:04b}", value >> 4, value & 0xF),
        Dialect::Step7 => format!("{} = {}", byte(value), bits(value)),
    }
}

/// A word as an integer and in hex: `KF +123 = KH 007B`, `123 = W#16#007B`.
pub fn integer_word(dialect: Dialect, value: u16) -> String {
    match dialect {
        Dialect::Step5 => format!("KF {:+} = KH {value:04X}", value as i16),
        Dialect::Step7 => word(value),
    }
}

/// A double word in hex and as a number: `DH 00010002 = +65538`, `DW#16#3FC00000 = 1.5`.
pub fn hex_double(dialect: Dialect, value: u32) -> String {
    match dialect {
        Dialect::Step5 => format!("DH {value:08X} = {:+}", value as i32),
        Dialect::Step7 => double(value),
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
