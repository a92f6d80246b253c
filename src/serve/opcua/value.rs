//! The OPC UA types of the CPU's values: a data block member's from its declaration (BOOL
//! Boolean, INT Int16, REAL Float, TIME Int32 milliseconds, S5TIME UInt16, STRING String), an
//! operand's by its width where nothing is declared; the value a client writes checked against
//! it, and turned into the writes an S7 client's would be (so an input write reaches the
//! input modules and their interrupts).

use opcua_server::address_space::AccessLevel;
use opcua_types::{
    Array, DataTypeId, DateTime, StatusCode, UAString, Variant, VariantScalarTypeId,
};

use crate::address::Target;
use crate::address::declared::Format;
use crate::address::{ImageArea, Layout};
use crate::rules::bcd;
use crate::state::watch::Raw;

use super::super::request::{Area, Item, ItemError, Range};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Boolean,
    Byte,
    UInt16,
    Int16,
    UInt32,
    Int32,
    Float,
    /// A TIME: signed milliseconds.
    Time,
    /// An S5TIME or a timer: the coded time word.
    S5Time,
    Char,
    String,
}

impl Kind {
    pub fn declared(format: Format) -> Kind {
        match format {
            Format::Bool => Kind::Boolean,
            Format::Byte => Kind::Byte,
            Format::Char => Kind::Char,
            Format::Word | Format::Date => Kind::UInt16,
            Format::Int => Kind::Int16,
            Format::S5Time => Kind::S5Time,
            Format::Dword | Format::TimeOfDay => Kind::UInt32,
            Format::Dint => Kind::Int32,
            Format::Real => Kind::Float,
            Format::Time => Kind::Time,
            Format::String(_) => Kind::String,
            Format::Bytes(count) => Kind::by_width(count.min(4)),
        }
    }

    /// A bit Boolean, a byte Byte, a word UInt16, a double word UInt32.
    pub fn by_width(bytes: u8) -> Kind {
        match bytes {
            0 => Kind::Boolean,
            1 => Kind::Byte,
            2 => Kind::UInt16,
            _ => Kind::UInt32,
        }
    }

    pub fn data_type(self) -> DataTypeId {
        match self {
            Kind::Boolean => DataTypeId::Boolean,
            Kind::Byte => DataTypeId::Byte,
            Kind::UInt16 | Kind::S5Time => DataTypeId::UInt16,
            Kind::Int16 => DataTypeId::Int16,
            Kind::UInt32 => DataTypeId::UInt32,
            Kind::Int32 | Kind::Time => DataTypeId::Int32,
            Kind::Float => DataTypeId::Float,
            Kind::Char | Kind::String => DataTypeId::String,
        }
    }

    fn scalar_type(self) -> VariantScalarTypeId {
        match self {
            Kind::Boolean => VariantScalarTypeId::Boolean,
            Kind::Byte => VariantScalarTypeId::Byte,
            Kind::UInt16 | Kind::S5Time => VariantScalarTypeId::UInt16,
            Kind::Int16 => VariantScalarTypeId::Int16,
            Kind::UInt32 => VariantScalarTypeId::UInt32,
            Kind::Int32 | Kind::Time => VariantScalarTypeId::Int32,
            Kind::Float => VariantScalarTypeId::Float,
            Kind::Char | Kind::String => VariantScalarTypeId::String,
        }
    }

    /// The value of an operand read `raw`.
    pub fn variant(self, raw: Raw) -> Variant {
        let bits = match raw {
            Raw::Bit(bit) => u32::from(bit),
            Raw::Bits(bits) => bits,
        };
        match self {
            Kind::Boolean => Variant::Boolean(bits & 1 != 0),
            Kind::Byte => Variant::Byte(bits as u8),
            Kind::UInt16 | Kind::S5Time => Variant::UInt16(bits as u16),
            Kind::Int16 => Variant::Int16(bits as u16 as i16),
            Kind::UInt32 => Variant::UInt32(bits),
            Kind::Int32 | Kind::Time => Variant::Int32(bits as i32),
            Kind::Float => Variant::Float(f32::from_bits(bits)),
            Kind::Char | Kind::String => {
                Variant::String(UAString::from(char::from(bits as u8).to_string()))
            }
        }
    }

    /// The raw bits of a value written; `BadTypeMismatch` for a value of another type.
    pub fn raw(self, value: &Variant) -> Result<u32, StatusCode> {
        Ok(match (self, value) {
            (Kind::Boolean, Variant::Boolean(bit)) => u32::from(*bit),
            (Kind::Byte, Variant::Byte(byte)) => u32::from(*byte),
            (Kind::UInt16 | Kind::S5Time, Variant::UInt16(word)) => u32::from(*word),
            (Kind::Int16, Variant::Int16(word)) => u32::from(*word as u16),
            (Kind::UInt32, Variant::UInt32(double)) => *double,
            (Kind::Int32 | Kind::Time, Variant::Int32(double)) => *double as u32,
            (Kind::Float, Variant::Float(real)) => real.to_bits(),
            (Kind::Char, Variant::String(text)) => match latin1(text.as_ref())?.as_slice() {
                [byte] => u32::from(*byte),
                _ => return Err(StatusCode::BadOutOfRange),
            },
            _ => return Err(StatusCode::BadTypeMismatch),
        })
    }

    /// An array of this type's values.
    pub fn array(self, values: Vec<Variant>) -> Variant {
        Array::new(self.scalar_type(), values)
            .map(Variant::from)
            .unwrap_or(Variant::Empty)
    }
}

/// A STRING's value from its bytes: the maximum length, the current one, the characters.
pub fn text(bytes: &[u8]) -> Variant {
    let length = bytes.get(1).map_or(0, |&length| usize::from(length));
    let characters = bytes.get(2..).unwrap_or_default();
    let text: String = characters[..length.min(characters.len())]
        .iter()
        .map(|&byte| char::from(byte))
        .collect();
    Variant::String(UAString::from(text))
}

/// The bytes a STRING of `range` (its two length bytes and its characters) is written with:
/// the current length and the characters, from the range's second byte.
pub fn text_write(range: Range, value: &Variant) -> Result<Item, StatusCode> {
    let Variant::String(text) = value else {
        return Err(StatusCode::BadTypeMismatch);
    };
    let characters = latin1(text.as_ref())?;
    let maximum = range.length.saturating_sub(2) as usize;
    if characters.len() > maximum {
        return Err(StatusCode::BadOutOfRange);
    }
    let mut bytes = vec![characters.len() as u8];
    bytes.extend(characters);
    Ok(Item::Write {
        range: Range::new(range.area, range.start + 1, bytes.len() as u32),
        bytes,
    })
}

/// The characters of a STRING or CHAR: Latin-1, one byte each.
fn latin1(text: &str) -> Result<Vec<u8>, StatusCode> {
    text.chars()
        .map(|character| u8::try_from(u32::from(character)).map_err(|_| StatusCode::BadOutOfRange))
        .collect()
}

/// The write an S7 client would send for `raw` into `target`.
pub fn write_item(target: Target, raw: u32, layout: Layout) -> Result<Item, StatusCode> {
    let bytes = |count: u8| raw.to_be_bytes()[4 - usize::from(count)..].to_vec();
    let write = |area, start: u32, count: u8| Item::Write {
        range: Range::new(area, start, u32::from(count)),
        bytes: bytes(count),
    };
    Ok(match target {
        Target::ImageBit { byte, bit } => {
            let (area, start) = image_area(layout, byte)?;
            Item::WriteBit {
                area,
                byte: start,
                bit,
                value: raw & 1 != 0,
            }
        }
        Target::Image { byte, bytes } => {
            let (area, start) = image_area(layout, byte)?;
            write(area, start, bytes)
        }
        Target::Periphery {
            byte,
            bytes,
            extended: false,
        } => write(Area::Inputs, u32::from(byte), bytes),
        Target::Periphery { .. } => return Err(StatusCode::BadNotWritable),
        Target::TimerBit(number) => write(Area::Timers, u32::from(number), 2),
        Target::CounterValue(number) => {
            if raw > 999 {
                return Err(StatusCode::BadOutOfRange);
            }
            Item::Write {
                range: Range::new(Area::Counters, u32::from(number), 1),
                bytes: (bcd::encode(raw, 3) as u16).to_be_bytes().to_vec(),
            }
        }
        Target::DataWord { db, word } => {
            write(Area::DataBlock(u16::from(db)), u32::from(word) * 2, 2)
        }
        Target::DataDouble { db, word } => {
            write(Area::DataBlock(u16::from(db)), u32::from(word) * 2, 4)
        }
        Target::S7Data {
            db,
            byte,
            bit,
            bytes: 0,
        } => Item::WriteBit {
            area: Area::DataBlock(db),
            byte,
            bit,
            value: raw & 1 != 0,
        },
        Target::S7Data {
            db, byte, bytes, ..
        } => write(Area::DataBlock(db), byte, bytes),
    })
}

/// The area and byte of an image byte.
fn image_area(layout: Layout, byte: u16) -> Result<(Area, u32), StatusCode> {
    match layout.image_area_of(byte) {
        Some((ImageArea::Input, at)) => Ok((Area::Inputs, u32::from(at))),
        Some((ImageArea::Output, at)) => Ok((Area::Outputs, u32::from(at))),
        Some((ImageArea::Flag, at)) => Ok((Area::Flags, u32::from(at))),
        None => Err(StatusCode::BadNotWritable),
    }
}

/// A failed item as the status a client gets.
pub fn status_of(error: ItemError) -> StatusCode {
    match error {
        ItemError::NoSuchBlock => StatusCode::BadNodeIdUnknown,
        ItemError::OutOfRange => StatusCode::BadOutOfRange,
        ItemError::ReadOnly => StatusCode::BadUserAccessDenied,
        ItemError::NotSupported => StatusCode::BadNotWritable,
    }
}

/// The simulated date and time (milliseconds since 1990-01-01, as READ_CLK reads it) as an
/// OPC UA timestamp.
pub fn timestamp(clock_ms: i64) -> DateTime {
    const TICKS_PER_MS: i64 = 10_000;
    let epoch = DateTime::ymd_hms(1990, 1, 1, 0, 0, 0).ticks();
    DateTime::from(epoch.saturating_add(clock_ms.saturating_mul(TICKS_PER_MS)))
}

/// What a client may do with a variable: read it, and write it unless the server is read-only.
pub fn access(read_only: bool) -> AccessLevel {
    match read_only {
        true => AccessLevel::CURRENT_READ,
        false => AccessLevel::CURRENT_READ | AccessLevel::CURRENT_WRITE,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_written_must_have_the_variable_s_type() {
        assert_eq!(Kind::Int16.raw(&Variant::Int16(-2)), Ok(0xFFFE));
        assert_eq!(
            Kind::Int16.raw(&Variant::Int32(5)),
            Err(StatusCode::BadTypeMismatch)
        );
        assert_eq!(Kind::Float.raw(&Variant::Float(1.5)), Ok(0x3FC0_0000));
        assert_eq!(Kind::Int16.variant(Raw::Bits(0xFFFE)), Variant::Int16(-2));
    }

    #[test]
    fn strings_keep_to_their_declared_length() {
        let range = Range::new(Area::DataBlock(5), 10, 6);
        let written = text_write(range, &Variant::String("abc".into()));
        assert_eq!(
            written,
            Ok(Item::Write {
                range: Range::new(Area::DataBlock(5), 11, 4),
                bytes: vec![3, b'a', b'b', b'c'],
            })
        );
        let too_long = text_write(range, &Variant::String("abcde".into()));
        assert_eq!(too_long, Err(StatusCode::BadOutOfRange));
        assert_eq!(
            text(&[4, 2, b'h', b'i', 0, 0]),
            Variant::String("hi".into())
        );
    }

    #[test]
    fn the_simulated_clock_is_the_source_timestamp() {
        assert_eq!(timestamp(0), DateTime::ymd_hms(1990, 1, 1, 0, 0, 0));
        assert_eq!(
            timestamp(1500),
            DateTime::ymd_hms_nano(1990, 1, 1, 0, 0, 1, 500_000_000)
        );
    }
}
