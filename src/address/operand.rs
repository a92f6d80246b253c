//! Operands as a scenario, a watch or the debugger names them, checked against the CPU's
//! ranges and the program's data blocks: every name `--state` shows. A STEP 5 program's in its
//! mnemonic set or English (`I 0.0`, `FW 10`, `T 1`, `DB 10 DW 3`, `DB 10 DD 4`), a STEP 7
//! program's in STEP 7 spelling of either set, whose area letters do not collide (`E`/`A`/`Z`
//! are German only, `I`/`Q`/`C` English only): `I 0.0`, `MW 12`, `PIW 256`, `T 5`, `C 3`,
//! `DB5.DBW 4`, and a declared data block's values by name (`DB5.level`, `DB5.motor.speed`,
//! `DB5.table[2]`, an instance DB's `DB6.start`).

use crate::ast::Address;
use crate::dialect::Dialect;
use crate::mnemonics::{self, Area, MnemonicSet};
use crate::profile::Profile;
use crate::step7::ast::{AccessWidth, S7Area};
use crate::step7::mnemonics::AREAS;

use super::Layout;
use super::declared::DeclaredValue;
use super::range::address_in_range;

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
    /// `DB 10 DD 4`: data words 4 and 5 of a STEP 5 data block.
    DataDouble {
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
            Target::DataDouble { .. } => 4,
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

/// The operands of a list as a user writes it, `Q 4.0, MW 10, DB5.grid[1,2]`: separated by
/// commas, but for those of an array's indices.
pub fn list(text: &str) -> Vec<String> {
    let mut operands = Vec::new();
    let (mut depth, mut start) = (0usize, 0);
    for (at, c) in text.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => {
                operands.push(&text[start..at]);
                start = at + 1;
            }
            _ => {}
        }
    }
    operands.push(&text[start..]);
    operands
        .into_iter()
        .map(str::trim)
        .filter(|operand| !operand.is_empty())
        .map(str::to_string)
        .collect()
}

/// What an operand is checked against and placed by: the program's dialect, the CPU's ranges,
/// where the image areas lie, and a STEP 7 program's data blocks.
pub struct Places<'a> {
    pub dialect: Dialect,
    pub profile: &'static Profile,
    pub layout: Layout,
    pub data_blocks: &'a [(u16, Vec<u8>)],
    /// A STEP 7 program's data blocks with declarations: their values by name.
    pub declared: &'a [(u16, Vec<DeclaredValue>)],
}

/// Why an operand was refused, and the help that goes with it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    pub reason: String,
    pub help: Option<String>,
}

/// An absolute operand in the dialect of `places`; `set` is a STEP 5 program's mnemonic set
/// (English is read too), a STEP 7 operand is read in either set.
pub fn parse(text: &str, set: MnemonicSet, places: &Places) -> Result<Target, Refusal> {
    match places.dialect {
        Dialect::Step5 => step5_target(text, set, places),
        Dialect::Step7 => {
            let compact: String = text.chars().filter(|c| !c.is_whitespace()).collect();
            step7_target(&compact, places)
        }
    }
}

/// An absolute operand: `I 0.0`, `FW 10`, `T 1`, `DB 10 DW 3`.
fn step5_target(text: &str, set: MnemonicSet, places: &Places) -> Result<Target, Refusal> {
    let (profile, layout) = (places.profile, places.layout);
    let unknown = |reason: &str, help: Option<String>| Refusal {
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
        let width = parts.get(2).map(|p| p.to_ascii_uppercase());
        let word = number(parts.get(3));
        let words = profile.sizes.data_words;
        return match (db, width.as_deref(), word, parts.len()) {
            (Some(db), Some("DW"), Some(word), 4) if word < words => {
                Ok(Target::DataWord { db: db as u8, word })
            }
            (Some(db), Some("DD"), Some(word), 4) if word < words.saturating_sub(1) => {
                Ok(Target::DataDouble { db: db as u8, word })
            }
            _ => Err(unknown(
                "write a data word as `DB 10 DW 3`, a double word as `DB 10 DD 4`",
                None,
            )),
        };
    }
    let area = mnemonics::area(set, first).or_else(|| mnemonics::area(MnemonicSet::English, first));
    let Some(area) = area else {
        return Err(unknown(
            "not an operand area",
            Some("use I, Q, F bits (`I 0.0`), IB IW QB QW FY FW FD, PY PW, T n, C n, or `DB 10 DW 3`, `DB 10 DD 4`".into()),
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

/// The S7 operand forms, for the help of an operand that is none.
pub const FORMS: &str = "use I, Q, M bits (`I 0.0`, German `E 0.0`, `A 4.0`), IB IW ID, QB QW QD (German EB EW ED, AB AW AD), MB MW MD, PIB PIW PID, PQB PQW PQD (German PEB PEW PED, PAB PAW PAD), T 5, C 3 (German Z 3), data block operands `DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4`, `DB5.DBD 6`, or a data block's values by name as `--state` shows them (`DB5.level`)";

/// An area word of either set that a scenario may name: the area and the access width. Local
/// data and the DB registers' data blocks change while the program runs.
fn s7_area(word: &str) -> Option<(S7Area, AccessWidth)> {
    use S7Area::*;
    AREAS
        .iter()
        .filter(|words| !matches!(words.area, Local | PreviousLocal | Data | Instance))
        .find(|words| words.en == word || words.de == word)
        .map(|words| (words.area, words.width))
}

/// The data block area words after `DBn.`: `DBX`, `DBB`, `DBW`, `DBD`.
fn data_width(word: &str) -> Option<AccessWidth> {
    AREAS
        .iter()
        .find(|words| words.area == S7Area::Data && words.en == word)
        .map(|words| words.width)
}

fn byte_count(width: AccessWidth) -> u8 {
    match width {
        AccessWidth::Bit => 0,
        AccessWidth::Byte => 1,
        AccessWidth::Word => 2,
        AccessWidth::Double => 4,
    }
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

/// A STEP 7 operand, `text` without blanks; a data block's value names keep their case for
/// the messages.
fn step7_target(text: &str, places: &Places) -> Result<Target, Refusal> {
    if text.is_empty() {
        return Err(refuse("empty operand", None));
    }
    if let Some(rest) = text.get(2..)
        && text[..2].eq_ignore_ascii_case("DB")
        && rest.starts_with(|c: char| c.is_ascii_digit())
    {
        return data_target(rest, places);
    }
    let text = text.to_ascii_uppercase();
    let (letters, rest) = split_letters(&text);
    let Some((area, width)) = s7_area(letters) else {
        return Err(not_an_area(letters));
    };
    let (byte, bit) = address(rest, width)?;
    let profile = places.profile;
    let sizes = &profile.sizes;
    let layout = places.layout;
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
        S7Area::Input => image(layout.input_base(), layout.image_bytes, "I"),
        S7Area::Output => image(layout.output_base(), layout.image_bytes, "Q"),
        S7Area::Flag => image(layout.flag_base(), layout.flag_bytes, "M"),
        S7Area::PeripheralInput => periphery("PI"),
        S7Area::PeripheralOutput => periphery("PQ"),
        S7Area::Timer => numbered(sizes.timers, "T").map(Target::TimerBit),
        S7Area::Counter => numbered(sizes.counters, "C").map(Target::CounterValue),
        _ => Err(not_an_area(letters)),
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

/// `5.DBW4` or `5.level` (after `DB`): a bit, byte, word or double word of a data block of the
/// program, or one of its declared values by name.
fn data_target(text: &str, places: &Places) -> Result<Target, Refusal> {
    let form = || {
        refuse(
            "write a data block operand as `DB5.DBW 4`",
            Some("`DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4`, `DB5.DBD 6`"),
        )
    };
    let (number, inner) = text.split_once('.').ok_or_else(form)?;
    let db: u16 = number.parse().map_err(|_| form())?;
    let blocks = places.data_blocks;
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
    let declared = places
        .declared
        .iter()
        .find(|(number, _)| *number == db)
        .map(|(_, values)| values.as_slice());
    if let Some(value) = declared
        .into_iter()
        .flatten()
        .find(|value| value.name.eq_ignore_ascii_case(inner))
    {
        return declared_target(db, value);
    }
    let upper = inner.to_ascii_uppercase();
    let (letters, rest) = split_letters(&upper);
    let Some(width) = data_width(letters) else {
        // `DW2`, `DBW` without its DB: an address in another form; else a name.
        let an_address = letters.len() <= 3 && rest.starts_with(|c: char| c.is_ascii_digit());
        return Err(match declared {
            Some(values) if !an_address => no_such_value(db, inner, values),
            _ => form(),
        });
    };
    let (byte, bit) = address(rest, width)?;
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

/// A declared value of data block `db` as the operand that reads it whole.
fn declared_target(db: u16, value: &DeclaredValue) -> Result<Target, Refusal> {
    let Some(bytes) = value.format.operand_bytes() else {
        return Err(refuse(
            format!(
                "a {}: an operand is a BOOL or a value of 1, 2 or 4 bytes",
                value.format.type_name()
            ),
            Some(&format!(
                "name its bytes from `DB{db}.DBB {}` on",
                value.byte
            )),
        ));
    };
    Ok(Target::S7Data {
        db,
        byte: value.byte,
        bit: value.bit,
        bytes,
    })
}

/// The most names of a data block's values a help lists.
const NAMES_LISTED: usize = 8;

/// A name that is none of data block `db`'s values: the close one, else those it has.
fn no_such_value(db: u16, written: &str, values: &[DeclaredValue]) -> Refusal {
    let names = values.iter().map(|value| value.name.as_str());
    let help = match crate::suggest::one_edit_from(written, names.clone()) {
        Some(close) => format!("did you mean `DB{db}.{close}`?"),
        None => {
            let listed: Vec<String> = names
                .take(NAMES_LISTED)
                .map(|name| format!("DB{db}.{name}"))
                .collect();
            let more = match values.len() {
                count if count > NAMES_LISTED => format!(", … ({count} in all)"),
                _ => String::new(),
            };
            format!(
                "its values by name, as `--state` shows them: {}{more}; or its bytes: `DB{db}.DBW 4`",
                listed.join(", ")
            )
        }
    };
    Refusal {
        reason: format!("DB {db} declares no `{written}`"),
        help: Some(help),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compiler::Program;
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
        parse(text, MnemonicSet::English, &Places::of(program))
            .map_err(|refusal| (refusal.reason, refusal.help))
    }

    #[test]
    fn splits_operand_text() {
        assert_eq!(words("IW 2"), ["IW", "2"]);
        assert_eq!(words("I0.0"), ["I", "0.0"]);
        assert_eq!(words("DB10.DW3"), ["DB", "10", "DW", "3"]);
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

    /// A bit (`bytes` 0), byte, word or double word of DB 5 of [`PROGRAM`].
    fn data(byte: u32, bit: u8, bytes: u8) -> Result<Target, (String, Option<String>)> {
        Ok(Target::S7Data {
            db: 5,
            byte,
            bit,
            bytes,
        })
    }

    #[test]
    fn data_block_operands() {
        let program = program();
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
    fn declared_values_by_the_names_the_state_shows() {
        let program = program();
        assert_eq!(parsed(&program, "DB5.flags"), data(0, 0, 2));
        assert_eq!(parsed(&program, "DB5.batches"), data(2, 0, 1));
        assert_eq!(parsed(&program, "DB5.level"), data(4, 0, 2));
        assert_eq!(parsed(&program, "db5 . VOLUME"), data(6, 0, 4), "any case");
        let refused = parsed(&program, "DB5.levle").unwrap_err();
        assert_eq!(refused.0, "DB 5 declares no `levle`");
        assert_eq!(refused.1.as_deref(), Some("did you mean `DB5.level`?"));
        let listed = parsed(&program, "DB5.pressure").unwrap_err().1.unwrap();
        assert!(
            listed.contains("DB5.flags, DB5.batches, DB5.spare, DB5.level, DB5.volume"),
            "{listed}"
        );
        let form = parsed(&program, "DB5.DW 2").unwrap_err().0;
        assert!(form.contains("`DB5.DBW 4`"), "{form}");
    }

    #[test]
    fn step5_data_words_and_double_words() {
        let profile = profile::find("sinumerik-840c").expect("the default S5 profile");
        let built = frontend::build_text("db.awl", "DB 10\n 0: KF +1\n 1: KF +2\n", profile);
        let places = Places::of(&built.compiled.program);
        let parsed = |text| parse(text, MnemonicSet::English, &places).map_err(|r| r.reason);
        assert_eq!(
            parsed("DB 10 DW 3"),
            Ok(Target::DataWord { db: 10, word: 3 })
        );
        assert_eq!(
            parsed("DB 10 DD 4"),
            Ok(Target::DataDouble { db: 10, word: 4 })
        );
        assert_eq!(Target::DataDouble { db: 10, word: 4 }.bytes(), 4);
        assert!(
            parsed("DB 10 DD 2047").is_err(),
            "its second word is past the end"
        );
    }

    #[test]
    fn operand_lists_split_at_commas_outside_indices() {
        assert_eq!(
            list("Q 4.0, DB5.grid[1,2] ,MW 10,"),
            ["Q 4.0", "DB5.grid[1,2]", "MW 10"]
        );
        assert!(list(" , ").is_empty());
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
        assert_eq!(reason(""), "empty operand");
        assert_eq!(
            reason("MW 8191"),
            "out of range for the speed7 CPU: M bytes 0 to 8191"
        );
        assert_eq!(reason("DB9.DBW 0"), "DB 9 is not in the program");
        assert_eq!(help("DB9.DBW 0"), "the program's data blocks: DB 5");
        assert_eq!(
            reason("DB5.DBD 8"),
            "past the end of DB 5: it has 10 bytes, 0 to 9"
        );
        // What the reason or the help says, in part.
        let refusals: [(&str, &str, &str); 14] = [
            ("FW 10", "help", "MW 10"),
            ("LW 2", "reason", "local data"),
            ("DIW 2", "help", "DB2.DBW 2"),
            ("I 0.8", "reason", "byte.bit"),
            ("I 0", "reason", "byte.bit"),
            ("MW 1.0", "reason", "only bit addresses"),
            ("MW", "reason", "a number"),
            ("Q 256.0", "reason", "Q bytes 0 to 255"),
            ("PIW 8192", "reason", "PI bytes 0 to 8191"),
            ("T 512", "reason", "T 0 to 511"),
            ("Z 512", "reason", "C 0 to 511"),
            ("DB5.DW 2", "reason", "`DB5.DBW 4`"),
            ("DB 5 DW 2", "reason", "`DB5.DBW 4`"),
            ("DBW 2", "reason", "names its data block"),
        ];
        for (text, part, says) in refusals {
            let said = if part == "reason" {
                reason(text)
            } else {
                help(text)
            };
            assert!(said.contains(says), "{text}: {said}");
        }
    }
}
