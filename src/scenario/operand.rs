//! Operands in `set` and `[expect]`: an absolute operand of the address model
//! ([`crate::address::operand`]) or a symbol of the program's assignment list.

use miette::SourceSpan;

pub use crate::address::Target;
use crate::address::operand::{self, Places};
use crate::compiler::Program;
use crate::mnemonics::MnemonicSet;

use super::error::ScenarioError;

pub fn parse_target(
    text: &str,
    at: SourceSpan,
    set: MnemonicSet,
    program: &Program,
) -> Result<Target, ScenarioError> {
    let places = Places::of(program);
    let absolute = |text: &str| {
        operand::parse(text, set, &places).map_err(|refusal| ScenarioError::UnknownOperand {
            operand: text.to_string(),
            at,
            reason: refusal.reason,
            help: refusal.help,
        })
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
