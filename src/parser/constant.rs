//! Constants: the text after a format word (`KF -100`, `KT 050.1`, `KS 'AB'`) to the value the CPU
//! loads. Range errors are reported here, with the range in the label.

use crate::ast::Constant;
use crate::lexer::{Token, TokenKind};
use crate::mnemonics::ConstFormat;
use crate::rules::bcd;
use crate::s5_float;
use crate::source::FileId;

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
    // The two numbers of `12,34` or `050.1`.
    let number_pair = |expected: &str| {
        let number = |text: &str| text.parse::<u32>().map_err(|_| bad(expected));
        Ok::<_, ParseError>((number(texts[0])?, number(texts[2])?))
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
                let (high, low) = number_pair("two bytes, e.g. 12,34")?;
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
                let (value, base) = number_pair("value.base, e.g. 050.1")?;
                if value > 999 {
                    Err(out_of_range("time value 0…999"))
                } else if base > 3 {
                    Err(out_of_range("time base 0…3 (0.01 s, 0.1 s, 1 s, 10 s)"))
                } else {
                    word(base << 12 | bcd::encode(value, 3))
                }
            }
            _ => Err(bad("time value and base, e.g. 050.1 (50 × 0.1 s)")),
        },
        ConstFormat::Count => match kinds.as_slice() {
            [Number] => match texts[0].parse::<u32>() {
                Ok(value) if value <= 999 => word(bcd::encode(value, 3)),
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
        ConstFormat::Float => match float(&texts, &kinds) {
            Some(Ok(value)) => word(value),
            Some(Err(_)) => Err(out_of_range("±0.1469368 × 10⁻³⁸ … ±0.1701412 × 10³⁹, or 0")),
            None => Err(bad(
                "±mantissa±exponent, e.g. +1234567+02 (0.1234567 × 10²)",
            )),
        },
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

/// The constant a bare number after `L` stands for, with the format STEP 5 needs (`1` →
/// `KF +1`, `-5` → `KF -5`, `40000` → `KH 9C40`, `0FFH` or `1A` → `KH 00FF`, `KH 001A`, a
/// number past 16 bits → `DH`); `None` when `text` is no number.
pub fn format_for_bare(negative: bool, text: &str) -> Option<String> {
    if let Ok(value) = text.parse::<i64>() {
        let value = if negative { -value } else { value };
        return Some(match value {
            -32768..=32767 => format!("KF {value:+}"),
            32768..=65535 => format!("KH {value:04X}"),
            _ => format!("DH {:08X}", i32::try_from(value).ok()? as u32),
        });
    }
    let digits = text.strip_suffix(['H', 'h']).unwrap_or(text);
    let value = u32::from_str_radix(digits, 16).ok().filter(|_| !negative)?;
    Some(if value <= 0xFFFF {
        format!("KH {value:04X}")
    } else {
        format!("DH {value:08X}")
    })
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

/// A `KG` constant as the PG writes it, `±mantissa±exponent` (`+1234567+02` is 0.1234567 × 10²;
/// a shorter mantissa is filled with zeros on the right: `-5-2` is −0.5 × 10⁻², CPU 928B
/// programming guide, 2.2), or as a plain decimal (`2457.6`, which [`decimal_float_warnings`]
/// reports). `None` when it is neither; `Err` with the value when it is out of range.
fn float(texts: &[&str], kinds: &[TokenKind]) -> Option<Result<u32, f64>> {
    use TokenKind::{Dot, Minus, Number, Plus};
    let sign = |kind: &TokenKind| if *kind == Minus { "-" } else { "+" };
    let text = match kinds {
        [s1 @ (Plus | Minus), Number, s2 @ (Plus | Minus), Number] => {
            pg_float_text(sign(s1), texts[1], sign(s2), texts[3])?
        }
        [Number, s2 @ (Plus | Minus), Number] => pg_float_text("+", texts[0], sign(s2), texts[2])?,
        [Number] | [Number, Dot, Number] => texts.concat(),
        [s1 @ (Plus | Minus), Number] | [s1 @ (Plus | Minus), Number, Dot, Number] => {
            format!("{}{}", sign(s1), texts[1..].concat())
        }
        _ => return None,
    };
    let value: f64 = text.parse().ok()?;
    match s5_float::encode_nearest(value) {
        (bits, s5_float::Outcome::Exact) => Some(Ok(bits)),
        _ => Some(Err(value)),
    }
}

/// `+`, `1234567`, `-`, `02` as the decimal text `+0.1234567e-02`.
fn pg_float_text(
    sign: &str,
    mantissa: &str,
    exponent_sign: &str,
    exponent: &str,
) -> Option<String> {
    let digits = |text: &str, max: usize| {
        (1..=max).contains(&text.len()) && text.bytes().all(|b| b.is_ascii_digit())
    };
    (digits(mantissa, 7) && digits(exponent, 2))
        .then(|| format!("{sign}0.{mantissa}e{exponent_sign}{exponent}"))
}

/// The PG's form of a decimal number: `2457.6` is `+2457600+04` (0.2457600 × 10⁴); digits after
/// the seventh significant one are cut off, as the PG keeps seven.
pub fn pg_float_form(negative: bool, integer: &str, fraction: &str) -> String {
    let integer = integer.trim_start_matches('0');
    let (digits, exponent) = if integer.is_empty() {
        let significant = fraction.trim_start_matches('0');
        let zeros = fraction.len() - significant.len();
        (significant.to_string(), -(zeros as i64))
    } else {
        (format!("{integer}{fraction}"), integer.len() as i64)
    };
    let sign = if negative { '-' } else { '+' };
    if digits.trim_end_matches('0').is_empty() {
        return format!("{sign}0000000+00");
    }
    let mantissa: String = digits
        .chars()
        .chain(std::iter::repeat('0'))
        .take(7)
        .collect();
    let exponent_sign = if exponent < 0 { '-' } else { '+' };
    format!("{sign}{mantissa}{exponent_sign}{:02}", exponent.abs())
}

/// A warning for each `KG` written as a plain decimal (`KG 2457.6`): awl reads it, the PG
/// writes `KG +2457600+04`.
pub fn decimal_float_warnings(file: FileId, source: &str, tokens: &[Token]) -> Vec<ParseError> {
    use TokenKind::{Dot, Equals, Minus, Number, Plus, Word};
    let mut warnings = Vec::new();
    for (at, token) in tokens.iter().enumerate() {
        if token.kind != Word || !token.text(source).eq_ignore_ascii_case("KG") {
            continue;
        }
        let mut rest = &tokens[at + 1..];
        if rest.first().is_some_and(|next| next.kind == Equals) {
            rest = &rest[1..];
        }
        let negative = rest.first().is_some_and(|next| next.kind == Minus);
        if rest
            .first()
            .is_some_and(|next| matches!(next.kind, Plus | Minus))
        {
            rest = &rest[1..];
        }
        if let [integer, dot, fraction, ..] = rest {
            let decimal = integer.kind == Number && dot.kind == Dot && fraction.kind == Number;
            let digits = |token: &Token| token.text(source).bytes().all(|b| b.is_ascii_digit());
            if decimal && digits(integer) && digits(fraction) {
                warnings.push(ParseError::DecimalFloat {
                    at: token.span_to(*fraction, file),
                    pg_form: pg_float_form(negative, integer.text(source), fraction.text(source)),
                });
            }
        }
    }
    warnings
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_bare_number_gets_the_format_its_value_needs() {
        assert_eq!(super::format_for_bare(false, "1").unwrap(), "KF +1");
        assert_eq!(super::format_for_bare(true, "5").unwrap(), "KF -5");
        assert_eq!(super::format_for_bare(false, "40000").unwrap(), "KH 9C40");
        assert_eq!(
            super::format_for_bare(false, "70000").unwrap(),
            "DH 00011170"
        );
        assert_eq!(super::format_for_bare(false, "0FFH").unwrap(), "KH 00FF");
        assert_eq!(super::format_for_bare(false, "1A").unwrap(), "KH 001A");
        assert_eq!(super::format_for_bare(false, "1Z"), None);
    }
    use super::*;

    fn kg(texts: &[&str], kinds: &[TokenKind]) -> f64 {
        s5_float::decode(float(texts, kinds).unwrap().unwrap())
    }

    /// The CPU 928B programming guide's examples (2.2): `+1234567+02` is 12.34567, `-5-2` is
    /// −0.005; a plain decimal reads as its value.
    #[test]
    fn kg_forms() {
        use TokenKind::{Dot, Minus, Number, Plus};
        let twelve = kg(&["+", "1234567", "+", "02"], &[Plus, Number, Plus, Number]);
        assert!((twelve - 12.34567).abs() < 1e-5);
        let small = kg(&["-", "5", "-", "2"], &[Minus, Number, Minus, Number]);
        assert!((small + 0.005).abs() < 1e-9);
        let unsigned = kg(&["1234567", "+", "3"], &[Number, Plus, Number]);
        assert!((unsigned - 123.4567).abs() < 1e-4);
        // Rounded to the nearest number of the format: just above 2457.6.
        assert_eq!(
            kg(&["2457", ".", "6"], &[Number, Dot, Number]),
            2457.60009765625
        );
        assert_eq!(kg(&["-", "2"], &[Minus, Number]), -2.0);
        assert_eq!(
            float(&["12345678", "+", "1"], &[Number, Plus, Number]),
            None
        );
        assert_eq!(
            float(&["+", "9", "+", "99"], &[Plus, Number, Plus, Number]),
            Some(Err(0.9e99))
        );
    }

    #[test]
    fn the_pg_form_of_a_decimal() {
        assert_eq!(pg_float_form(false, "2457", "6"), "+2457600+04");
        assert_eq!(pg_float_form(true, "0", "005"), "-5000000-02");
        assert_eq!(pg_float_form(false, "12", "345678"), "+1234567+02");
        assert_eq!(pg_float_form(false, "0", "0"), "+0000000+00");
    }
}
