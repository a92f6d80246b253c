//! A STEP 7 data block as its declaration shows it, the way STEP 7's data view of a DB lists
//! it: every elementary value by name (`setpoint`, `motor.speed`, `table[2]`, `grid[1,2]`) in
//! its declared type, `1234` for an INT, `L#70000` for a DINT, `T#1S500MS` for a TIME. An
//! instance DB shows its FB's interface (inputs, outputs, in/outs, statics), a
//! multi-instance's members under its name. A data block without declarations keeps the byte
//! view.

use serde::Serialize;

use crate::step7::ast::{AccessWidth, DataType, S7BlockKind, VarDecl, VarKind};
use crate::step7::layout::{
    BitOffset, Home, Interface, Types, element_stride, is_complex, struct_layout,
};

use crate::address::notation;
use crate::rules::bcd;

/// What the compiler lays out for the state to show: the plain types live with its tables.
pub use crate::step7::bytecode::{BlockLocals, DeclaredParameter, DeclaredValue, Format};

impl Format {
    /// The type's name as STEP 7 writes it.
    pub(crate) fn type_name(self) -> String {
        match self {
            Format::Bool => "BOOL".into(),
            Format::Byte => "BYTE".into(),
            Format::Char => "CHAR".into(),
            Format::Word => "WORD".into(),
            Format::Int => "INT".into(),
            Format::S5Time => "S5TIME".into(),
            Format::Date => "DATE".into(),
            Format::Dword => "DWORD".into(),
            Format::Dint => "DINT".into(),
            Format::Real => "REAL".into(),
            Format::Time => "TIME".into(),
            Format::TimeOfDay => "TIME_OF_DAY".into(),
            Format::String(length) => format!("STRING[{length}]"),
            Format::Bytes(count) => format!("{count} bytes"),
        }
    }

    /// The bytes an operand reads a value of this type in: none for a BOOL (a bit), 1, 2 or
    /// 4; `None` for a STRING or a value of more bytes, which no single operand reads.
    pub(crate) fn operand_bytes(self) -> Option<u8> {
        match self {
            Format::Bool => Some(0),
            Format::String(_) | Format::Bytes(_) => None,
            other => u8::try_from(other.bytes()).ok(),
        }
    }

    /// The width of the operand that reads a value of this type whole; `None` where none does.
    pub(crate) fn access_width(self) -> Option<AccessWidth> {
        Some(match self.operand_bytes()? {
            0 => AccessWidth::Bit,
            1 => AccessWidth::Byte,
            2 => AccessWidth::Word,
            _ => AccessWidth::Double,
        })
    }

    pub(crate) fn bytes(self) -> usize {
        match self {
            Format::Bool | Format::Byte | Format::Char => 1,
            Format::Word | Format::Int | Format::S5Time | Format::Date => 2,
            Format::Dword | Format::Dint | Format::Real | Format::Time | Format::TimeOfDay => 4,
            Format::String(length) => usize::from(length) + 2,
            Format::Bytes(count) => usize::from(count),
        }
    }
}

/// One value of a data block as the state shows it (the JSON's `declared_data_blocks`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ValueView {
    pub name: String,
    /// The declared type: `INT`, `REAL`, `STRING[10]`.
    #[serde(rename = "type")]
    pub type_name: String,
    /// The address in the data block, `2.0`.
    pub address: String,
    /// The value in STEP 7 notation: `1234`, `L#70000`, `TRUE`, `T#1S500MS`.
    pub value: String,
}

/// The elementary values of a data block laid out as `interface` (a global DB's statics or
/// an instance DB's FB interface), in address order; empty when nothing is declared.
pub fn values(interface: &Interface, types: &Types) -> Vec<DeclaredValue> {
    homed(interface, types, |home| match home {
        Home::Instance(at) => Some(at),
        Home::Local(_) | Home::Parameter(_) => None,
    })
}

/// A logic block's parameters (an FC's, by their place in the call's list) and its temporaries
/// (by their offset from the block's local data), as the debugger lists them.
pub fn locals(interface: &Interface, types: &Types) -> BlockLocals {
    let parameters = interface
        .parameters
        .iter()
        .enumerate()
        .filter_map(|(place, upper)| {
            let variable = interface.variables.get(upper)?;
            Some(DeclaredParameter {
                name: variable.declaration.name.text.clone(),
                place: u8::try_from(place).ok()?,
                // A STRING, DATE_AND_TIME, POINTER or ANY reaches an FC as a pointer, too.
                format: elementary(&variable.ty).filter(|_| !is_complex(&variable.ty)),
            })
        })
        .collect();
    let temporaries = homed(interface, types, |home| match home {
        Home::Local(at) => Some(at),
        Home::Instance(_) | Home::Parameter(_) => None,
    });
    BlockLocals {
        parameters,
        temporaries,
    }
}

/// The elementary values of the variables `pick` places, in address order.
fn homed(
    interface: &Interface,
    types: &Types,
    pick: impl Fn(Home) -> Option<BitOffset>,
) -> Vec<DeclaredValue> {
    let mut variables: Vec<(BitOffset, &VarDecl, VarKind)> = interface
        .variables
        .values()
        .filter_map(|variable| Some((pick(variable.home)?, &variable.declaration, variable.kind)))
        .collect();
    variables.sort_by_key(|(at, _, _)| at.0);
    let mut out = Vec::new();
    for (at, declaration, kind) in variables {
        let name = declaration.name.text.clone();
        if kind == VarKind::InOut && is_complex(&declaration.ty) {
            // An in/out of a complex type: the instance DB holds a pointer to the actual.
            out.push(value_at(name, at, Format::Bytes(6)));
        } else {
            flatten(&mut out, name, at, &declaration.ty, types);
        }
    }
    out
}

fn value_at(name: String, at: BitOffset, format: Format) -> DeclaredValue {
    DeclaredValue {
        name,
        byte: at.byte(),
        bit: at.bit(),
        format,
    }
}

/// How a value of an elementary type (or a STRING, DATE_AND_TIME, POINTER or ANY) reads;
/// `None` for arrays, structures and instances, which hold several.
fn elementary(ty: &DataType) -> Option<Format> {
    Some(match ty {
        DataType::Bool => Format::Bool,
        DataType::Byte => Format::Byte,
        DataType::Char => Format::Char,
        DataType::Word
        | DataType::Timer
        | DataType::Counter
        | DataType::BlockDb
        | DataType::BlockFb
        | DataType::BlockFc => Format::Word,
        DataType::Int => Format::Int,
        DataType::S5Time => Format::S5Time,
        DataType::Date => Format::Date,
        DataType::Dword => Format::Dword,
        DataType::Dint => Format::Dint,
        DataType::Real => Format::Real,
        DataType::Time => Format::Time,
        DataType::TimeOfDay => Format::TimeOfDay,
        DataType::String(length) => Format::String(*length),
        DataType::DateAndTime => Format::Bytes(8),
        DataType::Pointer => Format::Bytes(6),
        DataType::Any => Format::Bytes(10),
        DataType::Array { .. }
        | DataType::Struct(_)
        | DataType::Udt(_)
        | DataType::Instance(..)
        | DataType::Named(_) => return None,
    })
}

/// `ty` at `at` named `name`, element by element.
fn flatten(
    out: &mut Vec<DeclaredValue>,
    name: String,
    at: BitOffset,
    ty: &DataType,
    types: &Types,
) {
    let format = match ty {
        DataType::Array { dims, element } => {
            let stride = element_stride(element, types);
            for (n, index) in indices(dims).into_iter().enumerate() {
                let element_at = BitOffset(at.0 + n as u32 * stride);
                flatten(out, format!("{name}[{index}]"), element_at, element, types);
            }
            return;
        }
        DataType::Struct(members) => return members_of(out, &name, at, members, types),
        DataType::Udt(number) => {
            if let Some(members) = types.udts.get(number) {
                members_of(out, &name, at, members, types);
            }
            return;
        }
        DataType::Instance(kind, number) => return instance(out, &name, at, *kind, *number, types),
        other => match elementary(other) {
            Some(format) => format,
            None => return,
        },
    };
    out.push(value_at(name, at, format));
}

fn members_of(
    out: &mut Vec<DeclaredValue>,
    name: &str,
    at: BitOffset,
    members: &[VarDecl],
    types: &Types,
) {
    let (offsets, _) = struct_layout(members, types);
    for (member, offset) in members.iter().zip(offsets) {
        let member_at = BitOffset(at.0 + offset.0);
        flatten(
            out,
            format!("{name}.{}", member.name.text),
            member_at,
            &member.ty,
            types,
        );
    }
}

/// A multi-instance: its FB's or SFB's instance data, section by section.
fn instance(
    out: &mut Vec<DeclaredValue>,
    name: &str,
    at: BitOffset,
    kind: S7BlockKind,
    number: u16,
    types: &Types,
) {
    let Some((sections, _)) = types.instance(kind, number) else {
        return;
    };
    for (section_at, members) in sections {
        members_of(out, name, BitOffset(at.0 + section_at), members, types);
    }
}

/// The indices of an array's elements in storage order, the last one fastest: `1`, `2` or
/// `1,0`, `1,1`.
fn indices(dims: &[(i32, i32)]) -> Vec<String> {
    dims.iter()
        .fold(vec![String::new()], |prefixes, &(low, high)| {
            prefixes
                .iter()
                .flat_map(|prefix| {
                    (low..=high).map(move |index| match prefix.as_str() {
                        "" => index.to_string(),
                        _ => format!("{prefix},{index}"),
                    })
                })
                .collect()
        })
}

/// Each declared value of a data block with its value in `bytes`.
pub fn view(values: &[DeclaredValue], bytes: &[u8]) -> Vec<ValueView> {
    values
        .iter()
        .map(|declared| ValueView {
            name: declared.name.clone(),
            type_name: declared.format.type_name(),
            address: format!("{}.{}", declared.byte, declared.bit),
            value: text(declared, bytes),
        })
        .collect()
}

/// The declared value an operand reads whole: the one at `byte`.`bit` of `bytes` bytes (0 for
/// a BOOL), when `values` (in address order) has one.
pub fn at(values: &[DeclaredValue], byte: u32, bit: u8, bytes: u8) -> Option<&DeclaredValue> {
    let first = values.partition_point(|value| value.byte < byte);
    values[first..]
        .iter()
        .take_while(|value| value.byte == byte)
        .find(|value| value.bit == bit && value.format.operand_bytes() == Some(bytes))
}

/// The value of `declared` in STEP 7 notation, from its data block's `bytes`.
pub fn text(declared: &DeclaredValue, bytes: &[u8]) -> String {
    let start = declared.byte as usize;
    let Some(raw) = bytes.get(start..start + declared.format.bytes()) else {
        return "(past the data block's end)".into();
    };
    let word = || u16::from_be_bytes([raw[0], raw[1]]);
    let double = || u32::from_be_bytes([raw[0], raw[1], raw[2], raw[3]]);
    match declared.format {
        Format::Bool => if raw[0] >> declared.bit & 1 == 1 {
            "TRUE"
        } else {
            "FALSE"
        }
        .into(),
        Format::Byte => notation::byte(raw[0]),
        Format::Char => char_text(raw[0]),
        Format::Word => format!("W#16#{:04X}", word()),
        Format::Int => (word() as i16).to_string(),
        Format::S5Time => {
            let word = word();
            notation::s5time(
                bcd::decode(u32::from(word & 0x0FFF), 3) as u16,
                (word >> 12 & 3) as u8,
            )
        }
        Format::Date => date(word()),
        Format::Dword => format!("DW#16#{:08X}", double()),
        Format::Dint => format!("L#{}", double() as i32),
        Format::Real => format!("{:?}", f32::from_bits(double())),
        Format::Time => time(double() as i32),
        Format::TimeOfDay => time_of_day(double()),
        Format::String(_) => {
            let length = usize::from(raw[1]).min(raw.len() - 2);
            let text: String = raw[2..2 + length].iter().map(|&b| char::from(b)).collect();
            format!("'{}'", text.replace('\'', "$'"))
        }
        Format::Bytes(_) => {
            let hex: Vec<String> = raw.iter().map(|b| format!("{b:02X}")).collect();
            format!("16#{}", hex.join("_"))
        }
    }
}

fn char_text(byte: u8) -> String {
    match byte {
        b'\'' => "'$''".into(),
        0x20..=0x7E => format!("'{}'", char::from(byte)),
        _ => format!("B#16#{byte:02X}"),
    }
}

/// `T#1D2H3M4S5MS`, `T#-1S`, `T#0MS`.
fn time(ms: i32) -> String {
    let sign = if ms < 0 { "-" } else { "" };
    let ms = i64::from(ms).unsigned_abs();
    let parts = [
        (ms / 86_400_000, "D"),
        (ms / 3_600_000 % 24, "H"),
        (ms / 60_000 % 60, "M"),
        (ms / 1000 % 60, "S"),
        (ms % 1000, "MS"),
    ];
    let text: String = parts
        .iter()
        .filter(|(count, _)| *count > 0)
        .map(|(count, unit)| format!("{count}{unit}"))
        .collect();
    if text.is_empty() {
        "T#0MS".into()
    } else {
        format!("T#{sign}{text}")
    }
}

/// `TOD#12:30:00.500` from the milliseconds since midnight.
fn time_of_day(ms: u32) -> String {
    format!(
        "TOD#{}:{:02}:{:02}.{:03}",
        ms / 3_600_000,
        ms / 60_000 % 60,
        ms / 1000 % 60,
        ms % 1000
    )
}

/// `D#1990-01-01` from the days since 1990-01-01.
fn date(days: u16) -> String {
    let mut year = 1990u32;
    let mut days = u32::from(days);
    let leap = |year: u32| {
        year.is_multiple_of(4) && (!year.is_multiple_of(100) || year.is_multiple_of(400))
    };
    loop {
        let in_year = if leap(year) { 366 } else { 365 };
        if days < in_year {
            break;
        }
        days -= in_year;
        year += 1;
    }
    let february = if leap(year) { 29 } else { 28 };
    let lengths = [31, february, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    let mut month = 1;
    for length in lengths {
        if days < length {
            break;
        }
        days -= length;
        month += 1;
    }
    format!("D#{year}-{month:02}-{:02}", days + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shown(format: Format, bytes: &[u8]) -> String {
        let declared = DeclaredValue {
            name: "x".into(),
            byte: 0,
            bit: 0,
            format,
        };
        text(&declared, bytes)
    }

    #[test]
    fn values_read_in_their_declared_types() {
        assert_eq!(shown(Format::Int, &[0x04, 0xD2]), "1234");
        assert_eq!(shown(Format::Int, &[0xFF, 0xFE]), "-2");
        assert_eq!(shown(Format::Dint, &70000i32.to_be_bytes()), "L#70000");
        assert_eq!(shown(Format::Real, &1.5f32.to_be_bytes()), "1.5");
        assert_eq!(shown(Format::Word, &[0x12, 0x34]), "W#16#1234");
        assert_eq!(shown(Format::Bool, &[1]), "TRUE");
        assert_eq!(shown(Format::Char, b"A"), "'A'");
        assert_eq!(shown(Format::Time, &1500i32.to_be_bytes()), "T#1S500MS");
        assert_eq!(shown(Format::Time, &(-1000i32).to_be_bytes()), "T#-1S");
        assert_eq!(shown(Format::S5Time, &[0x12, 0x50]), "S5T#25S");
        assert_eq!(shown(Format::Date, &[0, 0]), "D#1990-01-01");
        assert_eq!(shown(Format::Date, &59u16.to_be_bytes()), "D#1990-03-01");
        assert_eq!(
            shown(Format::TimeOfDay, &45_000_500u32.to_be_bytes()),
            "TOD#12:30:00.500"
        );
        assert_eq!(shown(Format::String(4), &[4, 2, b'o', b'k', 0, 0]), "'ok'");
        assert_eq!(shown(Format::Int, &[1]), "(past the data block's end)");
    }

    #[test]
    fn array_indices_run_the_last_dimension_fastest() {
        assert_eq!(indices(&[(1, 2)]), ["1", "2"]);
        assert_eq!(indices(&[(1, 2), (0, 1)]), ["1,0", "1,1", "2,0", "2,1"]);
    }
}
