//! STEP 7 operands of a scenario for a STEP 7 program: `I 0.0`, `MW 12`, `PIW 256`, `T 5`,
//! `C 3`, `DB5.DBW 4` — in either mnemonic set, whose area letters do not collide (`E`/`A`/`Z`
//! are German only, `I`/`Q`/`C` English only) — checked against the CPU's ranges and the
//! program's data blocks.

use miette::SourceSpan;

use crate::compiler::Program;
use crate::step7::ast::AccessWidth;

use super::error::ScenarioError;
use super::operand::Target;

/// The S7 operand forms, for the help of an operand that is none.
pub const FORMS: &str = "use I, Q, M bits (`I 0.0`, German `E 0.0`, `A 4.0`), IB IW ID, QB QW QD (German EB EW ED, AB AW AD), MB MW MD, PIB PIW PID, PQB PQW PQD (German PEB PEW PED, PAB PAW PAD), T 5, C 3 (German Z 3), or data block operands `DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4`, `DB5.DBD 6`";

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Area {
    Input,
    Output,
    Flag,
    PeripheralInput,
    PeripheralOutput,
    Timer,
    Counter,
}

/// An area word of either set: the area and the access width.
fn area(word: &str) -> Option<(Area, AccessWidth)> {
    use AccessWidth::*;
    use Area::*;
    Some(match word {
        "I" | "E" => (Input, Bit),
        "IB" | "EB" => (Input, Byte),
        "IW" | "EW" => (Input, Word),
        "ID" | "ED" => (Input, Double),
        "Q" | "A" => (Output, Bit),
        "QB" | "AB" => (Output, Byte),
        "QW" | "AW" => (Output, Word),
        "QD" | "AD" => (Output, Double),
        "M" => (Flag, Bit),
        "MB" => (Flag, Byte),
        "MW" => (Flag, Word),
        "MD" => (Flag, Double),
        "PIB" | "PEB" => (PeripheralInput, Byte),
        "PIW" | "PEW" => (PeripheralInput, Word),
        "PID" | "PED" => (PeripheralInput, Double),
        "PQB" | "PAB" => (PeripheralOutput, Byte),
        "PQW" | "PAW" => (PeripheralOutput, Word),
        "PQD" | "PAD" => (PeripheralOutput, Double),
        "T" => (Timer, Word),
        "C" | "Z" => (Counter, Word),
        _ => return None,
    })
}

/// The data block area words after `DBn.`.
fn data_width(word: &str) -> Option<AccessWidth> {
    Some(match word {
        "DBX" => AccessWidth::Bit,
        "DBB" => AccessWidth::Byte,
        "DBW" => AccessWidth::Word,
        "DBD" => AccessWidth::Double,
        _ => return None,
    })
}

fn byte_count(width: AccessWidth) -> u8 {
    match width {
        AccessWidth::Bit => 0,
        AccessWidth::Byte => 1,
        AccessWidth::Word => 2,
        AccessWidth::Double => 4,
    }
}

/// Why an operand was refused, and the help that goes with it.
struct Refusal {
    reason: String,
    help: Option<String>,
}

fn refuse(reason: impl Into<String>, help: Option<&str>) -> Refusal {
    Refusal {
        reason: reason.into(),
        help: help.map(str::to_string),
    }
}

/// Splits `MW12` into `MW` and `12`.
fn split_letters(text: &str) -> (&str, &str) {
    let at = text
        .find(|c: char| !c.is_ascii_alphabetic())
        .unwrap_or(text.len());
    text.split_at(at)
}

/// `12` for a byte, word or double word; `0.1` for a bit.
fn address(text: &str, width: AccessWidth) -> Result<(u32, u8), Refusal> {
    let bit_form = || {
        refuse(
            "a bit address is byte.bit with bits 0 to 7, e.g. `I 0.0`",
            None,
        )
    };
    match (width, text.split_once('.')) {
        (AccessWidth::Bit, Some((byte, bit))) => match (byte.parse(), bit.parse::<u8>()) {
            (Ok(byte), Ok(bit)) if bit <= 7 => Ok((byte, bit)),
            _ => Err(bit_form()),
        },
        (AccessWidth::Bit, None) => Err(bit_form()),
        (_, None) => text
            .parse()
            .map(|byte| (byte, 0))
            .map_err(|_| refuse("a number must follow the area, e.g. `MW 10`", None)),
        (_, Some(_)) => Err(refuse(
            "only bit addresses have a `.bit`: `MW 10`, `M 10.1`",
            None,
        )),
    }
}

/// A STEP 7 operand of a scenario for `program`.
pub fn parse(text: &str, at: SourceSpan, program: &Program) -> Result<Target, ScenarioError> {
    let compact: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    target(&compact, program).map_err(|refusal| ScenarioError::UnknownOperand {
        operand: text.to_string(),
        at,
        reason: refusal.reason,
        help: refusal.help,
    })
}

fn target(text: &str, program: &Program) -> Result<Target, Refusal> {
    if text.is_empty() {
        return Err(refuse("empty operand", None));
    }
    if let Some(rest) = text.strip_prefix("DB")
        && rest.starts_with(|c: char| c.is_ascii_digit())
    {
        return data_target(rest, program);
    }
    let (letters, rest) = split_letters(text);
    let Some((area, width)) = area(letters) else {
        return Err(not_an_area(letters));
    };
    let (byte, bit) = address(rest, width)?;
    let profile = program.profile;
    let sizes = &profile.sizes;
    let layout = program.layout;
    let bytes = byte_count(width);
    let out_of_range = |range: String| {
        refuse(
            format!("out of range for the {} CPU: {range}", profile.name),
            None,
        )
    };
    let within = |size: u16| byte + u32::from(bytes.max(1)) <= u32::from(size);
    let image = |base: u16, size: u16, name: &str| {
        if !within(size) {
            return Err(out_of_range(format!(
                "{name} bytes 0 to {}",
                size.saturating_sub(1)
            )));
        }
        let byte = base + byte as u16;
        Ok(if width == AccessWidth::Bit {
            Target::ImageBit { byte, bit }
        } else {
            Target::Image { byte, bytes }
        })
    };
    let periphery = |name: &str| {
        if !within(sizes.peripheral_bytes) {
            return Err(out_of_range(format!(
                "{name} bytes 0 to {}",
                sizes.peripheral_bytes.saturating_sub(1)
            )));
        }
        Ok(Target::Periphery {
            byte: byte as u16,
            bytes,
            extended: false,
        })
    };
    let numbered = |count: u16, name: &str| {
        if byte >= u32::from(count) {
            return Err(out_of_range(format!(
                "{name} 0 to {}",
                count.saturating_sub(1)
            )));
        }
        Ok(byte as u16)
    };
    match area {
        Area::Input => image(layout.input_base(), layout.image_bytes, "I"),
        Area::Output => image(layout.output_base(), layout.image_bytes, "Q"),
        Area::Flag => image(layout.flag_base(), layout.flag_bytes, "M"),
        Area::PeripheralInput => periphery("PI"),
        Area::PeripheralOutput => periphery("PQ"),
        Area::Timer => numbered(sizes.timers, "T").map(Target::TimerBit),
        Area::Counter => numbered(sizes.counters, "C").map(Target::CounterValue),
    }
}

/// Why an area word is none, with the help that fits it.
fn not_an_area(letters: &str) -> Refusal {
    match letters {
        "L" | "LB" | "LW" | "LD" | "V" | "VB" | "VW" | "VD" => refuse(
            "local data exist only while their block runs",
            Some("copy the value to a flag or a data block in the program and name that"),
        ),
        "DIX" | "DIB" | "DIW" | "DID" => refuse(
            "the instance DB register changes with every call",
            Some("name the data block: `DB2.DBW 2` for a word of instance DB 2"),
        ),
        "DBX" | "DBB" | "DBW" | "DBD" => refuse(
            "a data block operand names its data block",
            Some("`DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4`, `DB5.DBD 6`"),
        ),
        "F" | "FY" | "FW" | "FD" => refuse(
            "STEP 7 has no F area",
            Some("the flags are M in STEP 7: `M 1.0`, `MB 1`, `MW 10`, `MD 20`"),
        ),
        _ => refuse("not a STEP 7 operand", Some(FORMS)),
    }
}

/// `5.DBW4` (after `DB`): a byte, word, double word or bit of a data block of the program.
fn data_target(text: &str, program: &Program) -> Result<Target, Refusal> {
    let form = || {
        refuse(
            "write a data block operand as `DB5.DBW 4`",
            Some("`DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4`, `DB5.DBD 6`"),
        )
    };
    let (number, inner) = text.split_once('.').ok_or_else(form)?;
    let db: u16 = number.parse().map_err(|_| form())?;
    let (letters, rest) = split_letters(inner);
    let width = data_width(letters).ok_or_else(form)?;
    let (byte, bit) = address(rest, width)?;
    let blocks = &program.s7.data_blocks;
    let Some((_, bytes)) = blocks.iter().find(|(number, _)| *number == db) else {
        let known: Vec<String> = blocks.iter().map(|(n, _)| format!("DB {n}")).collect();
        let help = if known.is_empty() {
            "the program has no data blocks".to_string()
        } else {
            format!("the program's data blocks: {}", known.join(", "))
        };
        return Err(Refusal {
            reason: format!("DB {db} is not in the program"),
            help: Some(help),
        });
    };
    let count = byte_count(width);
    if byte + u32::from(count.max(1)) > bytes.len() as u32 {
        let range = match bytes.len() {
            0 => "it has no bytes".to_string(),
            length => format!("it has {length} bytes, 0 to {}", length - 1),
        };
        return Err(refuse(format!("past the end of DB {db}: {range}"), None));
    }
    Ok(Target::S7Data {
        db,
        byte,
        bit,
        bytes: count,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend;
    use crate::profile;

    const PROGRAM: &str = "DATA_BLOCK DB 5
  STRUCT
    flags : WORD;
    batches : BYTE;
    spare : BYTE;
    level : INT;
    volume : REAL;
  END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB5.DBW 4;
      T     MW 10;
END_ORGANIZATION_BLOCK
";

    fn program() -> Program {
        let profile = profile::find("speed7").expect("the speed7 profile");
        let built = frontend::build_text("tank.awl", PROGRAM, profile);
        assert!(!built.has_errors(), "the test program compiles");
        assert!(built.compiled.program.s7.step7);
        built.compiled.program.clone()
    }

    fn parsed(program: &Program, text: &str) -> Result<Target, (String, Option<String>)> {
        parse(text, (0, 0).into(), program).map_err(|error| match error {
            ScenarioError::UnknownOperand { reason, help, .. } => (reason, help),
            other => panic!("not an unknown operand: {other:?}"),
        })
    }

    #[test]
    fn image_operands_in_both_sets() {
        let program = program();
        let layout = program.layout;
        let (inputs, outputs, flags) = (
            layout.input_base(),
            layout.output_base(),
            layout.flag_base(),
        );
        let bit = |byte, bit| Ok(Target::ImageBit { byte, bit });
        let bytes = |byte, bytes| Ok(Target::Image { byte, bytes });
        for (english, german, target) in [
            ("I 0.1", "E 0.1", bit(inputs, 1)),
            ("IB 1", "EB 1", bytes(inputs + 1, 1)),
            ("IW 2", "EW 2", bytes(inputs + 2, 2)),
            ("ID 4", "ED 4", bytes(inputs + 4, 4)),
            ("Q 4.0", "A 4.0", bit(outputs + 4, 0)),
            ("QB 4", "AB 4", bytes(outputs + 4, 1)),
            ("QW 4", "AW 4", bytes(outputs + 4, 2)),
            ("QD 4", "AD 4", bytes(outputs + 4, 4)),
            ("M 1.7", "M 1.7", bit(flags + 1, 7)),
            ("MB 1", "MB 1", bytes(flags + 1, 1)),
            ("MW 12", "MW 12", bytes(flags + 12, 2)),
            ("MD 20", "MD 20", bytes(flags + 20, 4)),
        ] {
            assert_eq!(parsed(&program, english), target, "{english}");
            assert_eq!(parsed(&program, german), target, "{german}");
        }
        assert_eq!(parsed(&program, "mw12"), bytes(flags + 12, 2), "any case");
    }

    #[test]
    fn periphery_timers_and_counters_in_both_sets() {
        let program = program();
        let periphery = |byte, bytes| {
            Ok(Target::Periphery {
                byte,
                bytes,
                extended: false,
            })
        };
        for (english, german, target) in [
            ("PIB 3", "PEB 3", periphery(3, 1)),
            ("PIW 128", "PEW 128", periphery(128, 2)),
            ("PID 8", "PED 8", periphery(8, 4)),
            ("PQB 3", "PAB 3", periphery(3, 1)),
            ("PQW 6", "PAW 6", periphery(6, 2)),
            ("PQD 8", "PAD 8", periphery(8, 4)),
            ("T 5", "T 5", Ok(Target::TimerBit(5))),
            ("C 3", "Z 3", Ok(Target::CounterValue(3))),
        ] {
            assert_eq!(parsed(&program, english), target, "{english}");
            assert_eq!(parsed(&program, german), target, "{german}");
        }
    }

    #[test]
    fn data_block_operands() {
        let program = program();
        let data = |byte, bit, bytes| {
            Ok(Target::S7Data {
                db: 5,
                byte,
                bit,
                bytes,
            })
        };
        assert_eq!(parsed(&program, "DB5.DBX 0.1"), data(0, 1, 0));
        assert_eq!(parsed(&program, "DB5.DBB 2"), data(2, 0, 1));
        assert_eq!(parsed(&program, "DB5.DBW 4"), data(4, 0, 2));
        assert_eq!(parsed(&program, "DB5.DBD 6"), data(6, 0, 4));
        assert_eq!(
            parsed(&program, "DB 5.DBD6"),
            data(6, 0, 4),
            "blanks anywhere"
        );
        assert_eq!(parsed(&program, "db5.dbx0.1"), data(0, 1, 0), "any case");
    }

    #[test]
    fn refusals_say_why_and_how() {
        let program = program();
        let reason = |text| parsed(&program, text).expect_err(text).0;
        let help = |text| {
            parsed(&program, text)
                .expect_err(text)
                .1
                .unwrap_or_default()
        };
        assert_eq!(reason("XW 2"), "not a STEP 7 operand");
        assert!(help("XW 2").contains("`DB5.DBW 4`"), "{}", help("XW 2"));
        assert!(help("XW 2").contains("PEW"), "both sets in the help");
        assert_eq!(reason("FW 10"), "STEP 7 has no F area");
        assert!(help("FW 10").contains("MW 10"));
        assert!(reason("LW 2").contains("local data"));
        assert!(help("DIW 2").contains("DB2.DBW 2"));
        assert!(reason("I 0.8").contains("byte.bit"));
        assert!(reason("I 0").contains("byte.bit"));
        assert!(reason("MW 1.0").contains("only bit addresses"));
        assert!(reason("MW").contains("a number"));
        assert_eq!(reason(""), "empty operand");
        assert_eq!(
            reason("MW 8191"),
            "out of range for the speed7 CPU: M bytes 0 to 8191"
        );
        assert!(reason("Q 256.0").contains("Q bytes 0 to 255"));
        assert!(reason("PIW 8192").contains("PI bytes 0 to 8191"));
        assert!(reason("T 512").contains("T 0 to 511"));
        assert!(reason("Z 512").contains("C 0 to 511"));
        assert_eq!(reason("DB9.DBW 0"), "DB 9 is not in the program");
        assert_eq!(help("DB9.DBW 0"), "the program's data blocks: DB 5");
        assert_eq!(
            reason("DB5.DBD 8"),
            "past the end of DB 5: it has 10 bytes, 0 to 9"
        );
        assert!(reason("DB5.DW 2").contains("`DB5.DBW 4`"));
        assert!(reason("DB 5 DW 2").contains("`DB5.DBW 4`"));
        assert!(reason("DBW 2").contains("names its data block"));
    }
}
