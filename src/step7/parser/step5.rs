//! STEP 5 spellings in a STEP 7 file, named as such with the STEP 7 form in the help: constants
//! with a format word (`KF +5`, `KH 00FF`, `KT 50.1`), data words (`DW 4`, `D 0.1`), S5 flags
//! (`F 1.0`, `FW 2`), program and sequence blocks (`PB 3`), and the `DES`/`BEZ` declaration
//! lines of STEP 5 function blocks. The conversions follow the STEP 7 manual's appendix on
//! converting STEP 5 programs: S7 addresses bytes, so data word n is `DBW 2n`, and bit b of it
//! lies in its low byte (`DBX 2n+1.b`) for b < 8, in its high byte (`DBX 2n.b-8`) otherwise.

use crate::mnemonics::MnemonicSet;
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};

use super::tokens::{Ctx, Tokens, letters_and_digits};

/// The text of `tokens` joined as written (from the first's start to the last's end).
fn written(ctx: Ctx<'_>, tokens: &[Token]) -> String {
    match (tokens.first(), tokens.last()) {
        (Some(first), Some(last)) => ctx.source[first.start as usize..last.end as usize].into(),
        _ => String::new(),
    }
}

/// A STEP 5 operand at the start of `input`, with its STEP 7 form.
pub fn operand(ctx: Ctx<'_>, input: Tokens<'_>) -> Option<S7ParseError> {
    let first = input.first()?;
    let upper = ctx.word(first)?;
    // The word and its number: `DW 4` or `DW4`.
    let (word, number, value_tokens): (String, String, &[Token]) = match letters_and_digits(&upper)
    {
        Some((letters, digits)) => {
            let mut number = digits.to_string();
            let mut used = 1;
            if let (Some(dot), Some(bit)) = (input.tokens.get(1), input.tokens.get(2))
                && dot.kind == TokenKind::Dot
                && first.touches(*dot)
            {
                number = format!("{digits}.{}", ctx.text(*bit));
                used = 3;
            }
            (letters.to_string(), number, &input.tokens[..used])
        }
        None => {
            let value = &input.tokens[1..];
            (upper.clone(), written(ctx, value), input.tokens)
        }
    };
    let at = ctx.span_of(first, *value_tokens.last().unwrap_or(&first));
    let (what, help) = s7_form(ctx.set, &word, number.trim())?;
    Some(S7ParseError::Step5Spelling { what, at, help })
}

/// What the STEP 5 word is and how STEP 7 writes the operand.
fn s7_form(set: MnemonicSet, word: &str, value: &str) -> Option<(String, String)> {
    let english = set == MnemonicSet::English;
    let form =
        |s7: String, why: &str| Some((format!("`{word} {value}`"), format!("{why}: write `{s7}`")));
    match word {
        "KF" => form(
            value.trim_start_matches('+').to_string(),
            "STEP 7 writes a fixed-point constant as the number alone",
        ),
        "KH" => form(
            format!("W#16#{value}"),
            "STEP 7 writes a hexadecimal word as `W#16#…`",
        ),
        "KM" => form(
            format!("2#{}", value.replace(' ', "")),
            "STEP 7 writes a bit pattern as `2#…`",
        ),
        "KY" => form(
            format!("B#({value})"),
            "STEP 7 writes two bytes as `B#(…, …)`",
        ),
        "KC" | "KZ" => form(format!("C#{value}"), "STEP 7 writes a count as `C#…`"),
        "KS" => form(
            value.to_string(),
            "STEP 7 writes characters in quotes alone",
        ),
        "KG" => form(
            value.to_string(),
            "STEP 7 writes a REAL as a decimal number",
        ),
        "KT" => form(
            s5time_of_kt(value)?,
            "STEP 7 writes a time value as `S5T#…`",
        ),
        "DW" => data_bytes(value, "DW", "DBW", 0),
        "DD" => data_bytes(value, "DD", "DBD", 0),
        // `DL n` is the left (high) byte 2n, `DR n` the right (low) byte 2n+1.
        "DL" => data_bytes(value, "DL", "DBB", 0),
        "DR" => data_bytes(value, "DR", "DBB", 1),
        "D" => data_bit(value),
        "F" if english => Some(flag("M", value)),
        "FY" if english => Some(flag("MB", value)),
        "FW" if english => Some(flag("MW", value)),
        "FD" if english => Some(flag("MD", value)),
        "PY" => Some((
            format!("`PY {value}`"),
            format!(
                "STEP 7 names the periphery byte by direction: write `PIB {value}` or `PQB {value}`"
            ),
        )),
        "PB" | "SB" => Some((
            format!("`{word} {value}`"),
            format!(
                "S7 has no {word}: make it a function (`FUNCTION FC {value} : VOID`) and write `CALL FC {value}`"
            ),
        )),
        "FX" | "DX" => Some((
            format!("`{word} {value}`"),
            format!("STEP 7 has only data blocks `DB`: write `DB {value}`"),
        )),
        _ => None,
    }
}

fn flag(s7: &str, value: &str) -> (String, String) {
    let s5 = match s7 {
        "M" => "F",
        "MB" => "FY",
        "MW" => "FW",
        _ => "FD",
    };
    (
        format!("`{s5} {value}`"),
        format!("STEP 7 calls flags bit memory `M`: write `{s7} {value}`"),
    )
}

/// `DW n` → `DBW 2n`; `offset` is added for the right byte (`DR n` → `DBB 2n+1`).
fn data_bytes(value: &str, s5: &str, s7: &str, offset: u32) -> Option<(String, String)> {
    let number: u32 = value.parse().ok()?;
    let byte = number * 2 + offset;
    Some((
        format!("`{s5} {value}`"),
        format!(
            "STEP 7 addresses bytes: data word {number} is `DBW {}`; write `{s7} {byte}`",
            number * 2
        ),
    ))
}

/// `D n.b` → the byte and bit of data word n's bit b.
fn data_bit(value: &str) -> Option<(String, String)> {
    let (word, bit) = value.split_once('.')?;
    let (word, bit): (u32, u32) = (word.parse().ok()?, bit.parse().ok()?);
    let (byte, bit_in_byte) = if bit < 8 {
        (word * 2 + 1, bit)
    } else {
        (word * 2, bit - 8)
    };
    Some((
        format!("`D {value}`"),
        format!(
            "STEP 7 addresses bytes: bit {bit} of data word {word} is `DBX {byte}.{bit_in_byte}`"
        ),
    ))
}

/// `KT 50.1` (50 × 100 ms) as `S5T#5S`.
fn s5time_of_kt(value: &str) -> Option<String> {
    let (count, base) = value.split_once('.')?;
    let count: u64 = count.parse().ok()?;
    let unit_ms = match base {
        "0" => 10,
        "1" => 100,
        "2" => 1_000,
        "3" => 10_000,
        _ => return None,
    };
    let mut ms = count * unit_ms;
    let mut text = String::from("S5T#");
    for (unit, length) in [("H", 3_600_000), ("M", 60_000), ("S", 1_000), ("MS", 1)] {
        if ms >= length {
            text.push_str(&format!("{}{unit}", ms / length));
            ms %= length;
        }
    }
    if text.len() == 4 {
        text.push_str("0MS");
    }
    Some(text)
}

/// A STEP 5 operation or line in a STEP 7 body (`DES`, `BEZ`, a leading `:`), when it is one.
pub fn operation(ctx: Ctx<'_>, first: Token) -> Option<S7ParseError> {
    let at = ctx.span(first);
    if first.kind == TokenKind::Colon {
        return Some(S7ParseError::Step5Spelling {
            what: "a leading `:`".into(),
            at,
            help:
                "STEP 7 statements start with their operation (or a label `M001:`); remove the `:`"
                    .into(),
        });
    }
    match ctx.word(first)?.as_str() {
        "DES" | "BEZ" => Some(S7ParseError::Step5Spelling {
            what: format!("a `{}` parameter line", ctx.text(first)),
            at,
            help: "STEP 7 declares parameters between `VAR_INPUT` (`VAR_OUTPUT`, `VAR_IN_OUT`) and `END_VAR`, before `BEGIN`: `START : BOOL;`".into(),
        }),
        "DO" => Some(S7ParseError::Step5Spelling {
            what: "`DO`".into(),
            at,
            help: "STEP 7 has no `DO`: use memory-indirect addressing, `L DBW [MD 10]`".into(),
        }),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kt_values_become_s5time() {
        assert_eq!(s5time_of_kt("50.1").as_deref(), Some("S5T#5S"));
        assert_eq!(s5time_of_kt("999.3").as_deref(), Some("S5T#2H46M30S"));
        assert_eq!(s5time_of_kt("12.0").as_deref(), Some("S5T#120MS"));
        assert_eq!(s5time_of_kt("0.2").as_deref(), Some("S5T#0MS"));
    }

    #[test]
    fn data_words_become_bytes() {
        assert!(
            data_bytes("4", "DW", "DBW", 0)
                .unwrap()
                .1
                .ends_with("`DBW 8`")
        );
        assert!(
            data_bytes("4", "DR", "DBB", 1)
                .unwrap()
                .1
                .ends_with("`DBB 9`")
        );
        assert!(data_bit("0.1").unwrap().1.contains("`DBX 1.1`"));
        assert!(data_bit("3.9").unwrap().1.contains("`DBX 6.1`"));
    }
}
