//! Operands in `set` and `[expect]`: the program's mnemonic set or English, checked against the
//! CPU's ranges; a STEP 7 program's operands in STEP 7 spelling ([`super::s7_operand`]).

use miette::SourceSpan;

use crate::ast::Address;
use crate::compiler::{Layout, Program, address_in_range};
use crate::mnemonics::{self, Area, MnemonicSet};
use crate::profile::Profile;

use super::error::ScenarioError;
use super::s7_operand;

/// What an operand of a scenario reads or writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A bit of the image memory (I, Q, F).
    ImageBit {
        byte: u16,
        bit: u8,
    },
    /// Bytes of the image memory (IB…FD).
    Image {
        byte: u16,
        bytes: u8,
    },
    /// Process input or output modules (PY/PW) and the extended periphery (OY/OW).
    Periphery {
        byte: u16,
        bytes: u8,
        extended: bool,
    },
    TimerBit(u16),
    CounterValue(u16),
    /// `DB 10 DW 3` (or `DB10.DW3`).
    DataWord {
        db: u8,
        word: u16,
    },
    /// A STEP 7 data block's bit (`bytes` 0), byte, word or double word: `DB5.DBW 4`.
    S7Data {
        db: u16,
        byte: u32,
        bit: u8,
        bytes: u8,
    },
}

impl Target {
    pub fn bytes(self) -> u8 {
        match self {
            Target::ImageBit { .. } | Target::TimerBit(_) => 0,
            Target::Image { bytes, .. }
            | Target::Periphery { bytes, .. }
            | Target::S7Data { bytes, .. } => bytes,
            Target::CounterValue(_) | Target::DataWord { .. } => 2,
        }
    }
}

fn area_bytes(area: Area) -> u8 {
    match area {
        Area::InputByte
        | Area::OutputByte
        | Area::FlagByte
        | Area::PeripheralByte
        | Area::ExtendedByte => 1,
        Area::FlagDouble => 4,
        _ => 2,
    }
}

/// Splits `"IW 2"`, `"I 0.0"`, `"DB 10 DW 3"`, `"DB10.DW3"` into words.
fn words(text: &str) -> Vec<String> {
    let mut spaced = String::new();
    let mut previous: Option<char> = None;
    for c in text.chars() {
        if let Some(p) = previous
            && p.is_ascii_alphabetic() != c.is_ascii_alphabetic()
            && c != '.'
            && p != '.'
        {
            spaced.push(' ');
        }
        spaced.push(c);
        previous = Some(c);
    }
    spaced
        .replace(".D", " D")
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

pub fn parse_target(
    text: &str,
    at: SourceSpan,
    set: MnemonicSet,
    program: &Program,
) -> Result<Target, ScenarioError> {
    let absolute = |text: &str| {
        if program.s7.step7 {
            s7_operand::parse(text, at, program)
        } else {
            parse_absolute(text, at, set, program.profile, program.layout)
        }
    };
    // `-START`, or a STEP 7 symbol in its quotes: `"Motor"`.
    let Some(name) = crate::symbols::symbol_written(text) else {
        return absolute(text);
    };
    let symbols = &program.symbols;
    match symbols.operand_in(name, set) {
        Some(operand) => absolute(&operand),
        None => Err(ScenarioError::UnknownSymbol {
            written: text.trim().to_string(),
            at,
            help: symbols.suggest(name).or_else(|| {
                symbols.is_empty().then(|| {
                    "name the assignment list with `symbols = [...]` or `--symbols FILE`"
                        .to_string()
                })
            }),
        }),
    }
}

/// An absolute operand: `I 0.0`, `FW 10`, `T 1`, `DB 10 DW 3`.
fn parse_absolute(
    text: &str,
    at: SourceSpan,
    set: MnemonicSet,
    profile: &'static Profile,
    layout: Layout,
) -> Result<Target, ScenarioError> {
    let unknown = |reason: &str, help: Option<String>| ScenarioError::UnknownOperand {
        operand: text.to_string(),
        at,
        reason: reason.to_string(),
        help,
    };
    let parts = words(text);
    let number = |part: Option<&String>| part.and_then(|p| p.parse::<u16>().ok());
    let Some(first) = parts.first() else {
        return Err(unknown("empty operand", None));
    };
    if first.eq_ignore_ascii_case("DB") {
        let db = number(parts.get(1)).filter(|db| *db <= 255);
        let is_dw = parts.get(2).is_some_and(|p| p.eq_ignore_ascii_case("DW"));
        let word = number(parts.get(3));
        return match (db, is_dw, word, parts.len()) {
            (Some(db), true, Some(word), 4) if word < profile.sizes.data_words => {
                Ok(Target::DataWord { db: db as u8, word })
            }
            _ => Err(unknown("write a data word as `DB 10 DW 3`", None)),
        };
    }
    let area = mnemonics::area(set, first).or_else(|| mnemonics::area(MnemonicSet::English, first));
    let Some(area) = area else {
        return Err(unknown(
            "not an operand area",
            Some("use I, Q, F bits (`I 0.0`), IB IW QB QW FY FW FD, PY PW, T n, C n, or `DB 10 DW 3`".into()),
        ));
    };
    let (index, bit) = match (area.is_bit(), parts.as_slice()) {
        (true, [_, address]) => match address.split_once('.') {
            Some((byte, bit)) => match (byte.parse::<u16>(), bit.parse::<u8>()) {
                (Ok(byte), Ok(bit)) => (byte, bit),
                _ => return Err(unknown("a bit address is byte.bit, e.g. `I 0.0`", None)),
            },
            None => return Err(unknown("a bit address is byte.bit, e.g. `I 0.0`", None)),
        },
        (false, [_, index]) => match index.parse::<u16>() {
            Ok(index) => (index, 0),
            Err(_) => return Err(unknown("a number must follow the area", None)),
        },
        _ => {
            return Err(unknown(
                "an area and an address, e.g. `Q 4.0` or `FW 10`",
                None,
            ));
        }
    };
    let address = Address { area, index, bit };
    if !address_in_range(address, profile) {
        return Err(unknown(
            &format!("out of range for the {} CPU", profile.name),
            None,
        ));
    }
    let image = |area, index| {
        layout
            .image_byte(area, index)
            .expect("image areas have a place")
    };
    Ok(match area {
        Area::Input | Area::Output | Area::Flag => Target::ImageBit {
            byte: image(area, index),
            bit,
        },
        Area::Timer => Target::TimerBit(index),
        Area::Counter => Target::CounterValue(index),
        Area::DataBit | Area::DataLeft | Area::DataRight | Area::DataWord | Area::DataDouble => {
            return Err(unknown("data operands need their DB: `DB 10 DW 3`", None));
        }
        Area::PeripheralByte | Area::PeripheralWord => Target::Periphery {
            byte: index,
            bytes: area_bytes(area),
            extended: false,
        },
        Area::ExtendedByte | Area::ExtendedWord => Target::Periphery {
            byte: index,
            bytes: area_bytes(area),
            extended: true,
        },
        _ => Target::Image {
            byte: image(area, index),
            bytes: area_bytes(area),
        },
    })
}

/// What a scenario wants an operand to hold, or writes into it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wanted {
    /// An integer (or `true`/`false`) as the raw bits it stands for: matched exactly.
    Raw(u32),
    /// A REAL given to a STEP 7 double word, as its IEEE 754 bits: matched by [`reals_match`].
    Real(u32),
}

impl Wanted {
    /// The bits written into the operand.
    pub fn raw(self) -> u32 {
        match self {
            Wanted::Raw(raw) | Wanted::Real(raw) => raw,
        }
    }

    /// Whether the operand's raw value `actual` is what is wanted.
    pub fn matches(self, actual: u32) -> bool {
        match self {
            Wanted::Raw(raw) => raw == actual,
            Wanted::Real(bits) => reals_match(f32::from_bits(bits), f32::from_bits(actual)),
        }
    }
}

/// Two REALs match when they are equal or differ by at most 1e-6 of the larger magnitude (a few
/// steps of a REAL's 24-bit mantissa), so a decimal written in the scenario matches the REAL a
/// computation rounded differently. NaN matches nothing.
pub fn reals_match(wanted: f32, actual: f32) -> bool {
    wanted == actual || (wanted - actual).abs() <= 1e-6 * wanted.abs().max(actual.abs())
}

/// The REAL a float stands for in a double word; only double words hold REALs.
pub fn real_value(target: Target, value: f64) -> Result<u32, String> {
    if target.bytes() != 4 {
        return Err("an integer (a REAL only for a double word: MD, ID, QD, PID, DBD)".into());
    }
    let real = value as f32;
    if value.is_nan() || (value.is_finite() && !real.is_finite()) {
        return Err("a REAL: a number up to ±3.402823e38".into());
    }
    Ok(real.to_bits())
}

/// The allowed values of a target and the raw value of an integer: bits 0 or 1; bytes, words
/// and double words unsigned or signed.
pub fn raw_value(target: Target, value: i64) -> Result<u32, String> {
    let bits = match target.bytes() {
        0 => {
            return if value == 0 || value == 1 {
                Ok(value as u32)
            } else {
                Err("0 or 1".into())
            };
        }
        bytes => u32::from(bytes) * 8,
    };
    let unsigned_max = (1i64 << bits) - 1;
    let signed_min = -(1i64 << (bits - 1));
    if (signed_min..=unsigned_max).contains(&value) {
        Ok((value & unsigned_max) as u32)
    } else {
        Err(format!("{signed_min}…{unsigned_max}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_operand_text() {
        assert_eq!(words("IW 2"), ["IW", "2"]);
        assert_eq!(words("I0.0"), ["I", "0.0"]);
        assert_eq!(words("DB10.DW3"), ["DB", "10", "DW", "3"]);
    }

    #[test]
    fn reals_match_within_a_relative_millionth() {
        assert!(Wanted::Real(1.5f32.to_bits()).matches(0x3FC0_0000));
        assert!(reals_match(0.3, 0.1 + 0.2));
        assert!(reals_match(4.0, 4.000_003));
        assert!(!reals_match(4.0, 4.000_01));
        assert!(reals_match(0.0, -0.0));
        assert!(!reals_match(f32::NAN, f32::NAN));
        assert!(!Wanted::Raw(4).matches(5));
    }

    #[test]
    fn reals_go_to_double_words_only() {
        let double = Target::S7Data {
            db: 5,
            byte: 6,
            bit: 0,
            bytes: 4,
        };
        assert_eq!(real_value(double, -1.5), Ok(0xBFC0_0000));
        assert!(real_value(double, f64::NAN).is_err());
        assert!(real_value(double, 1e39).is_err());
        assert!(real_value(Target::Image { byte: 0, bytes: 2 }, 1.5).is_err());
    }

    #[test]
    fn raw_values_accept_signed_and_unsigned() {
        let word = Target::Image { byte: 0, bytes: 2 };
        assert_eq!(raw_value(word, -32768), Ok(0x8000));
        assert_eq!(raw_value(word, 65535), Ok(0xFFFF));
        assert!(raw_value(word, 65536).is_err());
        assert!(raw_value(Target::ImageBit { byte: 0, bit: 0 }, 2).is_err());
    }
}
