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

/// A watch row's value in BIN: the `bits` lowest bits of `value` in groups of four, STEP 7's
/// `2#0000_0000_0010_1010`, STEP 5's `KM 0000 0000 0010 1010`; a bit alone `2#1`, `1`.
pub fn binary(dialect: Dialect, value: u32, bits: u32) -> String {
    let digits = format!("{value:0width$b}", width = bits as usize);
    let groups: Vec<&str> = digits
        .as_bytes()
        .rchunks(4)
        .rev()
        .map(|group| std::str::from_utf8(group).unwrap_or_default())
        .collect();
    match dialect {
        Dialect::Step7 => format!("2#{}", groups.join("_")),
        Dialect::Step5 if bits == 1 => digits,
        Dialect::Step5 => format!("KM {}", groups.join(" ")),
    }
}

/// A byte, word or double word in HEX: `B#16#2A`, `W#16#002A`, `DW#16#0000002A`; STEP 5's
/// `KH 2A`, `KH 002A`, `DH 0000002A`.
pub fn hex(dialect: Dialect, value: u32, bits: u32) -> String {
    match (dialect, bits) {
        (Dialect::Step7, ..=8) => byte(value as u8),
        (Dialect::Step7, ..=16) => format!("W#16#{value:04X}"),
        (Dialect::Step7, _) => format!("DW#16#{value:08X}"),
        (Dialect::Step5, ..=8) => format!("KH {value:02X}"),
        (Dialect::Step5, ..=16) => format!("KH {value:04X}"),
        (Dialect::Step5, _) => format!("DH {value:08X}"),
    }
}

/// A byte, word or double word in DEC: a byte unsigned, a word an INT, a double word a DINT
/// (`42`, `-1`, `L#70000`); STEP 5's `KF +42`, and a double word `+70000`.
pub fn decimal(dialect: Dialect, value: u32, bits: u32) -> String {
    match (dialect, bits) {
        (Dialect::Step7, ..=8) => value.to_string(),
        (Dialect::Step7, ..=16) => (value as u16 as i16).to_string(),
        (Dialect::Step7, _) => format!("L#{}", value as i32),
        (Dialect::Step5, ..=8) => format!("KF {value:+}"),
        (Dialect::Step5, ..=16) => format!("KF {:+}", value as u16 as i16),
        (Dialect::Step5, _) => format!("{:+}", value as i32),
    }
}

/// A double word as a REAL: STEP 7's IEEE 754 `1.5`, STEP 5's own floating-point format as
/// the PG writes a `KG` constant, `KG +1500000+01`.
pub fn real(dialect: Dialect, value: u32) -> String {
    match dialect {
        Dialect::Step7 => format!("{:?}", f32::from_bits(value)),
        Dialect::Step5 => {
            let number = crate::s5_float::decode(value);
            let decimal = number.abs().to_string();
            let (integer, fraction) = decimal.split_once('.').unwrap_or((&decimal, ""));
            let form = crate::parser::pg_float_form(number < 0.0, integer, fraction);
            format!("KG {form}")
        }
    }
}

/// A time word (a timer's, or a word holding a time value and base): `S5T#2S500MS`,
/// STEP 5's `KT 250.1`.
pub fn time_word(dialect: Dialect, word: u32) -> String {
    let (value, base) = crate::vm::timers::decode_time(word);
    match dialect {
        Dialect::Step7 => s5time(value, base),
        Dialect::Step5 => format!("KT {value:03}.{base}"),
    }
}

/// A count: `C#42`, STEP 5's `KZ 042`.
pub fn count(dialect: Dialect, count: u16) -> String {
    match dialect {
        Dialect::Step7 => format!("C#{count}"),
        Dialect::Step5 => format!("KZ {count:03}"),
    }
}

/// The bytes of a value as characters, high byte first: `'AB'`, STEP 5's `KC AB`; a byte that
/// is no printable ASCII character is written `$hh`, as STEP 7 escapes it in a string.
pub fn characters(dialect: Dialect, value: u32, bits: u32) -> String {
    let bytes = (bits / 8).max(1) as usize;
    let text: String = value.to_be_bytes()[4 - bytes..]
        .iter()
        .map(|&byte| match byte {
            b' '..=b'~' if byte != b'$' && byte != b'\'' => char::from(byte).to_string(),
            _ => format!("${byte:02X}"),
        })
        .collect();
    match dialect {
        Dialect::Step7 => format!("'{text}'"),
        Dialect::Step5 => format!("KC {text}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn watch_formats_write_each_dialect_s_notation() {
        let (s5, s7) = (Dialect::Step5, Dialect::Step7);
        assert_eq!(binary(s7, 42, 16), "2#0000_0000_0010_1010");
        assert_eq!(binary(s5, 42, 8), "KM 0010 1010");
        assert_eq!(binary(s5, 1, 1), "1");
        assert_eq!(hex(s7, 42, 16), "W#16#002A");
        assert_eq!(hex(s5, 42, 32), "DH 0000002A");
        assert_eq!(decimal(s7, 0xFFFF, 16), "-1");
        assert_eq!(decimal(s7, 70000, 32), "L#70000");
        assert_eq!(decimal(s5, 42, 16), "KF +42");
        assert_eq!(real(s7, 1.5f32.to_bits()), "1.5");
        assert_eq!(
            real(s5, crate::s5_float::encode_nearest(15.0).0),
            "KG +1500000+02"
        );
        assert_eq!(time_word(s7, 0x1250), "S5T#25S");
        assert_eq!(time_word(s5, 0x1250), "KT 250.1");
        assert_eq!(count(s5, 42), "KZ 042");
        assert_eq!(characters(s7, 0x4142, 16), "'AB'");
        assert_eq!(characters(s5, 0x4100, 16), "KC A$00");
    }

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
