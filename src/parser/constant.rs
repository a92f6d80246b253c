//! Constants: the text after a format word (`KF -100`, `KT 050.1`, `KS 'AB'`) to the value the CPU
//! loads. Range errors are reported here, with the range in the label.

use crate::ast::Constant;
use crate::lexer::{Token, TokenKind};
use crate::mnemonics::ConstFormat;

use super::error::ParseError;
use super::tokens::Context;

/// Parses all of `tokens` as a constant of `format`; `format_token` is the format word.
pub fn parse_constant(
    context: Context<'_>,
    format: ConstFormat,
    format_token: Token,
    tokens: &[Token],
) -> Result<Constant, ParseError> {
    let format_name = context.text(format_token).to_ascii_uppercase();
    let span = match (tokens.first(), tokens.last()) {
        (Some(first), Some(last)) => context.span_of(*first, *last),
        _ => context.span(format_token),
    };
    let bad = |expected: &str| ParseError::BadConstant {
        format: format_name.clone(),
        at: span,
        expected: expected.to_string(),
    };
    let out_of_range = |range: &str| ParseError::ConstantRange {
        format: format_name.clone(),
        at: span,
        range: range.to_string(),
    };
    let texts: Vec<&str> = tokens.iter().map(|token| context.text(*token)).collect();
    let kinds: Vec<TokenKind> = tokens.iter().map(|token| token.kind).collect();
    let word = |value: u32| {
        Ok(Constant {
            format,
            value,
            extra_words: Vec::new(),
        })
    };
    use TokenKind::{Comma, Dot, Minus, Number, Plus, Quoted, Word};
    match format {
        ConstFormat::Byte => match kinds.as_slice() {
            [Number] => match texts[0].parse::<u32>() {
                Ok(value) if value <= 255 => word(value),
                Ok(_) => Err(out_of_range("0…255")),
                Err(_) => Err(bad("a decimal number 0…255")),
            },
            _ => Err(bad("a decimal number 0…255")),
        },
        ConstFormat::Fixed => {
            let (negative, digits) = match kinds.as_slice() {
                [Number] => (false, texts[0]),
                [Plus, Number] => (false, texts[1]),
                [Minus, Number] => (true, texts[1]),
                _ => return Err(bad("a signed decimal number, e.g. +100 or -5")),
            };
            let magnitude: i64 = digits.parse().map_err(|_| bad("decimal digits"))?;
            let value = if negative { -magnitude } else { magnitude };
            if (-32768..=32767).contains(&value) {
                word(value as i16 as u16 as u32)
            } else {
                Err(out_of_range("−32768…+32767"))
            }
        }
        ConstFormat::Hex => {
            hex(&texts, &kinds, 4).map_or_else(|| Err(bad("1 to 4 hex digits")), word)
        }
        ConstFormat::DoubleHex => {
            hex(&texts, &kinds, 8).map_or_else(|| Err(bad("1 to 8 hex digits")), word)
        }
        ConstFormat::BitPattern => {
            let digits: String = texts.concat();
            let binary = kinds.iter().all(|kind| *kind == Number)
                && !digits.is_empty()
                && digits.bytes().all(|b| b == b'0' || b == b'1');
            if !binary {
                Err(bad("binary digits (0 and 1)"))
            } else if digits.len() > 16 {
                Err(out_of_range("up to 16 bits"))
            } else {
                word(u32::from_str_radix(&digits, 2).expect("checked binary digits"))
            }
        }
        ConstFormat::TwoBytes => match kinds.as_slice() {
            [Number, Comma, Number] => {
                let high = texts[0]
                    .parse::<u32>()
                    .map_err(|_| bad("two bytes, e.g. 12,34"))?;
                let low = texts[2]
                    .parse::<u32>()
                    .map_err(|_| bad("two bytes, e.g. 12,34"))?;
                if high > 255 || low > 255 {
                    Err(out_of_range("0…255 for each byte"))
                } else {
                    word(high << 8 | low)
                }
            }
            _ => Err(bad("two bytes separated by a comma, e.g. 12,34")),
        },
        ConstFormat::Time => match kinds.as_slice() {
            [Number, Dot, Number] => {
                let value = texts[0]
                    .parse::<u32>()
                    .map_err(|_| bad("value.base, e.g. 050.1"))?;
                let base = texts[2]
                    .parse::<u32>()
                    .map_err(|_| bad("value.base, e.g. 050.1"))?;
                if value > 999 {
                    Err(out_of_range("time value 0…999"))
                } else if base > 3 {
                    Err(out_of_range("time base 0…3 (0.01 s, 0.1 s, 1 s, 10 s)"))
                } else {
                    word(base << 12 | bcd(value))
                }
            }
            _ => Err(bad("time value and base, e.g. 050.1 (50 × 0.1 s)")),
        },
        ConstFormat::Count => match kinds.as_slice() {
            [Number] => match texts[0].parse::<u32>() {
                Ok(value) if value <= 999 => word(bcd(value)),
                Ok(_) => Err(out_of_range("0…999")),
                Err(_) => Err(bad("a count 0…999")),
            },
            _ => Err(bad("a count 0…999")),
        },
        ConstFormat::Chars => {
            let text: String = match kinds.as_slice() {
                [Quoted] => texts[0][1..texts[0].len() - 1].to_string(),
                [] => return Err(bad("characters, e.g. 'AB'")),
                _ if kinds.iter().all(|kind| matches!(kind, Word | Number)) => texts.concat(),
                _ => return Err(bad("characters in quotes, e.g. 'AB'")),
            };
            chars(&text).ok_or_else(|| bad("ISO-8859-1 characters"))
        }
        ConstFormat::Float => float(&texts, &kinds)
            .ok_or_else(|| bad("±mantissa±exponent, e.g. +1234567+02 (0.1234567 × 10²)"))
            .map(|value| Constant {
                format,
                value,
                extra_words: Vec::new(),
            }),
    }
}

fn hex(texts: &[&str], kinds: &[TokenKind], max_digits: usize) -> Option<u32> {
    match kinds {
        [TokenKind::Number | TokenKind::Word] if (1..=max_digits).contains(&texts[0].len()) => {
            u32::from_str_radix(texts[0], 16).ok()
        }
        _ => None,
    }
}

/// Binary-coded decimal of a value 0…999.
pub fn bcd(value: u32) -> u32 {
    ((value / 100) << 8) | ((value / 10 % 10) << 4) | (value % 10)
}

/// Packs characters two to a data word; the first word is the constant's value.
fn chars(text: &str) -> Option<Constant> {
    let bytes: Vec<u8> = text
        .chars()
        .map(|c| u8::try_from(u32::from(c)).ok())
        .collect::<Option<_>>()?;
    if bytes.is_empty() {
        return None;
    }
    let mut words = bytes
        .chunks(2)
        .map(|pair| u16::from(pair[0]) << 8 | u16::from(*pair.get(1).unwrap_or(&b' ')));
    let first = words.next()?;
    Some(Constant {
        format: ConstFormat::Chars,
        value: u32::from(first),
        extra_words: words.collect(),
    })
}

/// `+1234567+02` means 0.1234567 × 10^2. The S5 format holds an 8-bit two's-complement exponent
/// in bits 31–24 and a 24-bit two's-complement mantissa, value = mantissa / 2^23 × 2^exponent.
fn float(texts: &[&str], kinds: &[TokenKind]) -> Option<u32> {
    use TokenKind::{Minus, Number, Plus};
    let sign = |kind: TokenKind| if kind == Minus { -1.0 } else { 1.0 };
    let (mantissa_sign, mantissa, exponent_sign, exponent) = match kinds {
        [s1 @ (Plus | Minus), Number, s2 @ (Plus | Minus), Number] => {
            (sign(*s1), texts[1], sign(*s2), texts[3])
        }
        _ => return None,
    };
    if mantissa.len() > 7 || exponent.len() > 2 {
        return None;
    }
    let fraction: f64 = format!("0.{mantissa}").parse().ok()?;
    let decimal_exponent: i32 = exponent.parse().ok()?;
    let value = mantissa_sign * fraction * 10f64.powi(exponent_sign as i32 * decimal_exponent);
    Some(to_s5_float(value))
}

pub fn to_s5_float(value: f64) -> u32 {
    if value == 0.0 {
        return 0x8000_0000;
    }
    let mut exponent = value.abs().log2().floor() as i32 + 1;
    let mut mantissa = (value / 2f64.powi(exponent) * f64::from(1 << 23)).round() as i64;
    if mantissa.abs() >= 1 << 23 {
        mantissa /= 2;
        exponent += 1;
    }
    let exponent = exponent.clamp(-128, 127) as i8 as u8 as u32;
    exponent << 24 | (mantissa as u32 & 0x00FF_FFFF)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bcd_packs_digits() {
        assert_eq!(bcd(503), 0x503);
        assert_eq!(bcd(0), 0);
    }

    #[test]
    fn float_of_twelve_point_three_four() {
        let packed = to_s5_float(12.34567);
        assert_eq!(packed >> 24, 4);
        let mantissa = (packed & 0xFF_FFFF) as f64 / f64::from(1 << 23);
        assert!((mantissa * 16.0 - 12.34567).abs() < 1e-5);
    }
}
