//! STEP 7 operands, from the text written after the operation: addresses (`I 0.1`, `MW10`,
//! `DB5.DBW 4`), indirect addresses (`MW [MD 10]`, `DBX [AR1, P#2.0]`), locals (`#a.b[1]`),
//! symbols, blocks, constants, labels, status conditions and awlsim's test operands.

use crate::ast::Name;
use crate::mnemonics::MnemonicSet;
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, DbRegister, Extension, IndirectPointer, PathPart, S7Address, S7Area, S7BlockKind,
    S7BlockRef, S7Op, S7Operand, StatusCondition,
};

use super::literal;

/// Where the operand text stands, for the names inside it.
pub struct Written<'t> {
    pub text: &'t str,
    pub span: Span,
    pub set: MnemonicSet,
    pub extensions: bool,
}

impl Written<'_> {
    fn name(&self, text: &str) -> Name {
        Name {
            text: text.to_string(),
            span: self.span,
        }
    }
}

/// An area prefix: the area and its width.
fn area(prefix: &str, set: MnemonicSet) -> Option<(S7Area, AccessWidth)> {
    use AccessWidth::*;
    use S7Area::*;
    let german = set == MnemonicSet::German;
    Some(match prefix {
        "I" if !german => (Input, Bit),
        "IB" if !german => (Input, Byte),
        "IW" if !german => (Input, Word),
        "ID" if !german => (Input, Double),
        "E" if german => (Input, Bit),
        "EB" if german => (Input, Byte),
        "EW" if german => (Input, Word),
        "ED" if german => (Input, Double),
        "Q" if !german => (Output, Bit),
        "QB" if !german => (Output, Byte),
        "QW" if !german => (Output, Word),
        "QD" if !german => (Output, Double),
        "A" if german => (Output, Bit),
        "AB" if german => (Output, Byte),
        "AW" if german => (Output, Word),
        "AD" if german => (Output, Double),
        "M" => (Flag, Bit),
        "MB" => (Flag, Byte),
        "MW" => (Flag, Word),
        "MD" => (Flag, Double),
        "L" => (Local, Bit),
        "LB" => (Local, Byte),
        "LW" => (Local, Word),
        "LD" => (Local, Double),
        "V" => (PreviousLocal, Bit),
        "VB" => (PreviousLocal, Byte),
        "VW" => (PreviousLocal, Word),
        "VD" => (PreviousLocal, Double),
        "DBX" => (Data, Bit),
        "DBB" => (Data, Byte),
        "DBW" => (Data, Word),
        "DBD" => (Data, Double),
        "DIX" => (Instance, Bit),
        "DIB" => (Instance, Byte),
        "DIW" => (Instance, Word),
        "DID" => (Instance, Double),
        "PIB" if !german => (PeripheralInput, Byte),
        "PIW" if !german => (PeripheralInput, Word),
        "PID" if !german => (PeripheralInput, Double),
        "PQB" if !german => (PeripheralOutput, Byte),
        "PQW" if !german => (PeripheralOutput, Word),
        "PQD" if !german => (PeripheralOutput, Double),
        "PEB" if german => (PeripheralInput, Byte),
        "PEW" if german => (PeripheralInput, Word),
        "PED" if german => (PeripheralInput, Double),
        "PAB" if german => (PeripheralOutput, Byte),
        "PAW" if german => (PeripheralOutput, Word),
        "PAD" if german => (PeripheralOutput, Double),
        "T" => (Timer, Word),
        "C" if !german => (Counter, Word),
        "Z" if german => (Counter, Word),
        _ => return None,
    })
}

fn block_kind(word: &str) -> Option<S7BlockKind> {
    Some(match word {
        "OB" => S7BlockKind::Ob,
        "FC" => S7BlockKind::Fc,
        "FB" => S7BlockKind::Fb,
        "DB" => S7BlockKind::Db,
        "SFC" => S7BlockKind::Sfc,
        "SFB" => S7BlockKind::Sfb,
        "UDT" => S7BlockKind::Udt,
        _ => return None,
    })
}

/// Splits `MW10` / `MW 10` / `DBX0.0` into the letters and the rest.
fn split_letters(text: &str) -> (&str, &str) {
    let at = text
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(text.len());
    (&text[..at], text[at..].trim())
}

fn byte_and_bit(text: &str, width: AccessWidth) -> Result<(u32, u8), String> {
    let bad = || format!("`{text}` is no address: write a byte number (and `.bit` for a bit)");
    match (width, text.split_once('.')) {
        (AccessWidth::Bit, Some((byte, bit))) => {
            let byte: u32 = byte.trim().parse().map_err(|_| bad())?;
            let bit: u8 = bit.trim().parse().map_err(|_| bad())?;
            if bit > 7 {
                return Err(format!("bit {bit}: bits are numbered 0 to 7"));
            }
            Ok((byte, bit))
        }
        (AccessWidth::Bit, None) => Err(format!("`{text}` needs a bit: write `{text}.0`")),
        (_, None) => Ok((text.trim().parse().map_err(|_| bad())?, 0)),
        (_, Some(_)) => Err(format!("`{text}`: only bit addresses have a `.bit`")),
    }
}

/// A member path after a local or a symbol: `.b[1, 2].c`.
fn path(text: &str, written: &Written<'_>) -> Result<Vec<PathPart>, String> {
    let mut parts = Vec::new();
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix('.') {
            let end = after.find(['.', '[']).unwrap_or(after.len());
            let name = after[..end].trim().trim_matches('"');
            if name.is_empty() {
                return Err("a member name after `.`".into());
            }
            parts.push(PathPart::Member(written.name(name)));
            rest = &after[end..];
        } else if let Some(after) = rest.strip_prefix('[') {
            let end = after.find(']').ok_or("a `]` after the index")?;
            let indexes: Result<Vec<i32>, _> = after[..end]
                .split(',')
                .map(|i| i.trim().parse::<i32>())
                .collect();
            parts.push(PathPart::Index(
                indexes.map_err(|_| "constant indexes only")?,
            ));
            rest = &after[end + 1..];
        } else {
            return Err(format!("`{rest}` after the name"));
        }
        rest = rest.trim_start();
    }
    Ok(parts)
}

fn extension(text: &str, written: &Written<'_>) -> Result<Option<S7Operand>, String> {
    let upper = text.to_ascii_uppercase();
    if !upper.starts_with("__") {
        return Ok(None);
    }
    if !written.extensions {
        return Err("awlsim test operand: run it with `awl conformance` or `--extended`".into());
    }
    let (word, argument) = upper
        .split_once(char::is_whitespace)
        .unwrap_or((&upper, ""));
    let argument = argument.trim();
    let number = || {
        argument
            .parse::<u8>()
            .map_err(|_| format!("`{text}` needs a number"))
    };
    let extension = match word {
        "__STW" if argument.is_empty() => Extension::StatusWord,
        "__STW" => {
            let bit = match argument {
                "/ER" | "/FC" => 0,
                "VKE" | "RLO" => 1,
                "STA" => 2,
                "OR" => 3,
                "OS" => 4,
                "OV" => 5,
                "A0" | "CC0" => 6,
                "A1" | "CC1" => 7,
                "BIE" | "BR" => 8,
                other => other
                    .parse::<u8>()
                    .ok()
                    .filter(|bit| *bit <= 8)
                    .ok_or_else(|| format!("`{other}` is no status bit"))?,
            };
            Extension::StatusBit(bit)
        }
        "__ACCU" => Extension::Accu(number()?),
        "__AR" => Extension::AddressRegister(number()?),
        "__DBR" => Extension::DbRegister(number()?),
        "__CNST_PI" => Extension::Pi,
        "__CNST_E" => Extension::E,
        "__CNST_PINF" => Extension::PositiveInfinity,
        "__CNST_NINF" => Extension::NegativeInfinity,
        "__CNST_PNAN" => Extension::PositiveNan,
        "__CNST_NNAN" => Extension::NegativeNan,
        _ => return Err(format!("`{text}` is no awlsim test operand")),
    };
    Ok(Some(S7Operand::Extension(extension)))
}

fn condition(upper: &str, set: MnemonicSet) -> Option<StatusCondition> {
    Some(match upper {
        "==0" => StatusCondition::Zero,
        "<>0" => StatusCondition::NotZero,
        ">0" => StatusCondition::Positive,
        "<0" => StatusCondition::Negative,
        ">=0" => StatusCondition::PositiveOrZero,
        "<=0" => StatusCondition::NegativeOrZero,
        "UO" => StatusCondition::Unordered,
        "OV" => StatusCondition::Overflow,
        "OS" => StatusCondition::StoredOverflow,
        "BR" if set == MnemonicSet::English => StatusCondition::BinaryResult,
        "BIE" if set == MnemonicSet::German => StatusCondition::BinaryResult,
        _ => return None,
    })
}

fn is_jump(op: S7Op) -> bool {
    use S7Op::*;
    matches!(
        op,
        JumpAlways
            | JumpIfRlo
            | JumpIfNotRlo
            | JumpIfRloSave
            | JumpIfNotRloSave
            | JumpIfBr
            | JumpIfNotBr
            | JumpIfOverflow
            | JumpIfStoredOverflow
            | JumpIfZero
            | JumpIfNotZero
            | JumpIfPositive
            | JumpIfMinus
            | JumpIfPositiveOrZero
            | JumpIfMinusOrZero
            | JumpIfUnordered
            | Loop
            | JumpList
    )
}

fn is_bit_logic(op: S7Op) -> bool {
    matches!(
        op,
        S7Op::And | S7Op::AndNot | S7Op::Or | S7Op::OrNot | S7Op::Xor | S7Op::XorNot
    )
}

/// The operand `written.text` of `op`.
pub fn parse(op: S7Op, written: &Written<'_>) -> Result<S7Operand, String> {
    let text = written.text.trim();
    if text.is_empty() {
        return Ok(S7Operand::None);
    }
    if let S7Op::Assert(_) | S7Op::Feature = op
        && let Some((left, right)) = split_pair(text)
    {
        // An operand of `__ASSERT` may also be a status condition (`UO`, `==0`).
        let part = |t: &str| {
            parse(
                S7Op::And,
                &Written {
                    text: t,
                    span: written.span,
                    set: written.set,
                    extensions: written.extensions,
                },
            )
        };
        return Ok(S7Operand::Pair(
            Box::new(part(left)?),
            Box::new(part(right)?),
        ));
    }
    if let Some(extension) = extension(text, written)? {
        return Ok(extension);
    }
    let upper = text.to_ascii_uppercase();
    if is_jump(op) {
        let valid = text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        return if valid {
            Ok(S7Operand::Label(written.name(text)))
        } else {
            Err(format!("`{text}` is no label"))
        };
    }
    if is_bit_logic(op)
        && let Some(condition) = condition(&upper, written.set)
    {
        return Ok(S7Operand::Status(condition));
    }
    if let Some(local) = text.strip_prefix('#') {
        let end = local.find(['.', '[']).unwrap_or(local.len());
        let mut parts = vec![PathPart::Member(written.name(local[..end].trim()))];
        parts.extend(path(&local[end..], written)?);
        return Ok(S7Operand::Local(parts));
    }
    if let Some(symbol) = text.strip_prefix('"') {
        let end = symbol.find('"').ok_or("a closing `\"`")?;
        return Ok(S7Operand::Symbol {
            name: written.name(&symbol[..end]),
            members: path(symbol[end + 1..].trim(), written)?,
        });
    }
    match upper.as_str() {
        "DBNO" => return Ok(S7Operand::DbRegister(DbRegister::DbNumber)),
        "DBLG" => return Ok(S7Operand::DbRegister(DbRegister::DbLength)),
        "DINO" => return Ok(S7Operand::DbRegister(DbRegister::DiNumber)),
        "DILG" => return Ok(S7Operand::DbRegister(DbRegister::DiLength)),
        "AR1" => return Ok(S7Operand::AddressRegister(1)),
        "AR2" => return Ok(S7Operand::AddressRegister(2)),
        _ => {}
    }
    if looks_constant(&upper) {
        if matches!(
            op,
            S7Op::ShiftLeftWord
                | S7Op::ShiftRightWord
                | S7Op::ShiftLeftDouble
                | S7Op::ShiftRightDouble
                | S7Op::ShiftSignedInt
                | S7Op::ShiftSignedDint
                | S7Op::RotateLeftDouble
                | S7Op::RotateRightDouble
                | S7Op::Increment
                | S7Op::Decrement
                | S7Op::Sleep
                | S7Op::Display
                | S7Op::Nop
        ) && let Ok(number) = upper.parse::<i64>()
        {
            return Ok(S7Operand::Number(number));
        }
        return literal::parse(text).map(S7Operand::Constant);
    }
    address(&upper, written)
}

/// Whether an operand is written as a constant (a typed literal, a number, a string).
pub fn looks_constant(upper: &str) -> bool {
    upper.contains('#')
        || upper.starts_with('\'')
        || upper == "TRUE"
        || upper == "FALSE"
        || upper.starts_with(|c: char| c.is_ascii_digit() || c == '+' || c == '-')
}

/// `a, b` at the top level (not inside brackets or parentheses).
fn split_pair(text: &str) -> Option<(&str, &str)> {
    let mut depth = 0i32;
    for (at, c) in text.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' if depth == 0 => return Some((text[..at].trim(), text[at + 1..].trim())),
            _ => {}
        }
    }
    None
}

/// An absolute, indirect or block address.
fn address(upper: &str, written: &Written<'_>) -> Result<S7Operand, String> {
    // `DB5.DBW 4`
    if let Some(rest) = upper.strip_prefix("DB")
        && let Some((number, inner)) = rest.split_once('.')
        && let Ok(db) = number.trim().parse::<u16>()
    {
        let (letters, tail) = split_letters(inner.trim());
        let Some((S7Area::Data, width)) = area(letters, written.set) else {
            return Err(format!(
                "`{upper}`: after `DB{db}.` comes DBX, DBB, DBW or DBD"
            ));
        };
        let (byte, bit) = byte_and_bit(tail, width)?;
        return Ok(S7Operand::Address(S7Address {
            area: S7Area::Data,
            width,
            byte,
            bit,
            db: Some(db),
        }));
    }
    // Area-crossing register-indirect: `[AR1, P#0.0]` after a width letter.
    let (letters, tail) = split_letters(upper);
    if let Some(kind) = block_kind(letters) {
        if let Ok(number) = tail.parse::<u16>() {
            return Ok(S7Operand::Block(S7BlockRef::Number { kind, number }));
        }
        if tail.starts_with('[') && matches!(kind, S7BlockKind::Db) {
            let pointer = indirect(tail, written)?;
            return Ok(S7Operand::Indirect {
                area: S7Area::Data,
                width: AccessWidth::Word,
                pointer,
            });
        }
    }
    if letters == "DI"
        && let Ok(number) = tail.parse::<u16>()
    {
        return Ok(S7Operand::Block(S7BlockRef::Number {
            kind: S7BlockKind::Db,
            number,
        }));
    }
    let Some((area_found, width)) = area(letters, written.set) else {
        if let ("B" | "W" | "D" | "X", true) = (letters, tail.starts_with('[')) {
            let width = match letters {
                "B" => AccessWidth::Byte,
                "W" => AccessWidth::Word,
                "D" => AccessWidth::Double,
                _ => AccessWidth::Bit,
            };
            let pointer = indirect(tail, written)?;
            // The area comes from the address register (area-crossing).
            return Ok(S7Operand::Indirect {
                area: S7Area::Flag,
                width,
                pointer: match pointer {
                    IndirectPointer::Register { ar, offset } => IndirectPointer::Register {
                        ar: ar | 0x80,
                        offset,
                    },
                    other => other,
                },
            });
        }
        return Err(format!("`{upper}` is no STEP 7 operand"));
    };
    if tail.starts_with('[') {
        let pointer = indirect(tail, written)?;
        return Ok(S7Operand::Indirect {
            area: area_found,
            width,
            pointer,
        });
    }
    let (byte, bit) = byte_and_bit(tail, width)?;
    Ok(S7Operand::Address(S7Address {
        area: area_found,
        width,
        byte,
        bit,
        db: None,
    }))
}

/// `[MD 10]` or `[AR1, P#2.0]`.
fn indirect(text: &str, written: &Written<'_>) -> Result<IndirectPointer, String> {
    let inner = text
        .strip_prefix('[')
        .and_then(|t| t.strip_suffix(']'))
        .ok_or("write the pointer in brackets: `[MD 10]`")?
        .trim();
    if let Some((register, offset)) = inner.split_once(',') {
        let ar = match register.trim() {
            "AR1" => 1,
            "AR2" => 2,
            other => return Err(format!("`{other}`: AR1 or AR2")),
        };
        let offset = literal::parse(offset.trim())?;
        return Ok(IndirectPointer::Register {
            ar,
            offset: offset.value & 0x00FF_FFFF,
        });
    }
    match address(inner, written)? {
        S7Operand::Address(address) if address.width != AccessWidth::Bit => {
            Ok(IndirectPointer::Memory(address))
        }
        _ => Err(format!(
            "`{inner}`: the pointer is a word or double word (MD, LD, DBD, DID)"
        )),
    }
}
