//! The STRING functions of the IEC library: FC 2 CONCAT, FC 4 DELETE, FC 11 FIND, FC 17
//! INSERT, FC 20 LEFT, FC 21 LEN, FC 26 MID, FC 31 REPLACE, FC 32 RIGHT, the comparisons FC 10,
//! 13, 15, 19, 24, 29 (EQ_STRNG … NE_STRNG) and the conversions FC 5 DI_STRNG, FC 16 I_STRNG,
//! FC 30 R_STRNG, FC 37 STRNG_DI, FC 38 STRNG_I, FC 39 STRNG_R.
//!
//! A STRING in memory is its maximum length, its current length, then the characters. A
//! result is put together in a buffer on the stack (the result may be written over an input)
//! and then written: cut to the destination's maximum length, which is an error.

use std::cmp::Ordering;

use crate::step7::ast::AccessWidth;
use crate::step7::library::LibraryCall;
use crate::vm::Cpu;

use super::super::memory::{Fault, Located};

/// The longest STRING.
const LONGEST: usize = 254;

/// A STRING parameter: where it is and its current length (at most its maximum).
#[derive(Clone, Copy)]
struct Text {
    at: Located,
    len: usize,
}

/// A result being put together; `overflow` once more than a STRING holds was added.
struct Buffer {
    bytes: [u8; LONGEST],
    len: usize,
    overflow: bool,
}

impl Buffer {
    fn new() -> Buffer {
        Buffer {
            bytes: [0; LONGEST],
            len: 0,
            overflow: false,
        }
    }

    fn push(&mut self, byte: u8) {
        if self.len == LONGEST {
            self.overflow = true;
        } else {
            self.bytes[self.len] = byte;
            self.len += 1;
        }
    }

    fn chars(&self) -> &[u8] {
        &self.bytes[..self.len]
    }
}

/// The characters of an INT or DINT: its sign (`+` or `-`) and its digits.
fn integer_text(value: i32, out: &mut Buffer) {
    out.push(if value < 0 { b'-' } else { b'+' });
    let mut digits = [0u8; 10];
    let mut count = 0;
    let mut rest = value.unsigned_abs();
    loop {
        digits[count] = b'0' + (rest % 10) as u8;
        count += 1;
        rest /= 10;
        if rest == 0 {
            break;
        }
    }
    for &digit in digits[..count].iter().rev() {
        out.push(digit);
    }
}

/// A REAL as `±v.nnnnnnnE±xx`: eight significant digits and a two-digit exponent.
fn real_text(value: f32, out: &mut Buffer) {
    let value = f64::from(value);
    out.push(if value.is_sign_negative() { b'-' } else { b'+' });
    let magnitude = value.abs();
    let (mut mantissa, mut exponent) = (0u64, 0i32);
    if magnitude != 0.0 {
        exponent = magnitude.log10().floor() as i32;
        mantissa = (magnitude / 10f64.powi(exponent) * 1e7).round() as u64;
        // Rounding may carry into a ninth digit, and log10 may be one off either way.
        if mantissa >= 100_000_000 {
            mantissa = (mantissa as f64 / 10.0).round() as u64;
            exponent += 1;
        } else if mantissa < 10_000_000 {
            mantissa = (magnitude / 10f64.powi(exponent - 1) * 1e7).round() as u64;
            exponent -= 1;
        }
    }
    let mut digits = [0u8; 8];
    for digit in digits.iter_mut().rev() {
        *digit = b'0' + (mantissa % 10) as u8;
        mantissa /= 10;
    }
    out.push(digits[0]);
    out.push(b'.');
    for &digit in &digits[1..] {
        out.push(digit);
    }
    out.push(b'E');
    out.push(if exponent < 0 { b'-' } else { b'+' });
    let exponent = exponent.unsigned_abs();
    out.push(b'0' + (exponent / 10 % 10) as u8);
    out.push(b'0' + (exponent % 10) as u8);
}

/// The integer `±digits` spell, at most `longest` characters long (sign included); `None` when
/// they spell none. Too large a value is given as it is, for the caller to limit.
fn parse_integer(chars: &[u8], longest: usize) -> Option<i64> {
    let (negative, digits) = match chars.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, chars),
    };
    if digits.is_empty() || chars.len() > longest || !digits.iter().all(u8::is_ascii_digit) {
        return None;
    }
    let magnitude = digits
        .iter()
        .fold(0i64, |value, digit| value * 10 + i64::from(digit - b'0'));
    Some(if negative { -magnitude } else { magnitude })
}

/// The REAL `±v.nnnnnnnE±xx` spells (its first 14 characters), not yet limited to a REAL.
fn parse_real(chars: &[u8]) -> Option<f64> {
    let chars = chars.get(..14)?;
    let sign = |byte: u8| match byte {
        b'+' => Some(1.0),
        b'-' => Some(-1.0),
        _ => None,
    };
    let digit = |at: usize| {
        chars[at]
            .is_ascii_digit()
            .then(|| f64::from(chars[at] - b'0'))
    };
    let negative = sign(chars[0])?;
    if chars[2] != b'.' || chars[10] != b'E' {
        return None;
    }
    let mut mantissa = digit(1)?;
    for at in 3..10 {
        mantissa = mantissa * 10.0 + digit(at)?;
    }
    let exponent = sign(chars[11])? * (digit(12)? * 10.0 + digit(13)?);
    Some(negative * mantissa * 10f64.powf(exponent - 7.0))
}

impl Cpu {
    fn text(&mut self, call: &LibraryCall, index: usize) -> Result<Text, Fault> {
        let (at, _) = self.arg(call, index)?;
        let max = self.fetch(at, AccessWidth::Byte)? as usize;
        let len = self.fetch(at.offset(1, 0), AccessWidth::Byte)? as usize;
        Ok(Text {
            at,
            len: len.min(max),
        })
    }

    fn char_at(&mut self, text: Text, index: usize) -> Result<u8, Fault> {
        Ok(self.fetch(text.at.offset(2 + index as u32, 0), AccessWidth::Byte)? as u8)
    }

    /// Characters `from` up to `to` (exclusive) of `text` onto `out`.
    fn append(
        &mut self,
        out: &mut Buffer,
        text: Text,
        from: usize,
        to: usize,
    ) -> Result<(), Fault> {
        for index in from..to.min(text.len) {
            out.push(self.char_at(text, index)?);
        }
        Ok(())
    }

    /// The characters of `text`.
    fn read_text(&mut self, text: Text) -> Result<Buffer, Fault> {
        let mut out = Buffer::new();
        self.append(&mut out, text, 0, text.len)?;
        Ok(out)
    }

    /// The STRING output `index` set to `result`, cut to its maximum length; whether it fit.
    fn write_text(
        &mut self,
        call: &LibraryCall,
        index: usize,
        result: &Buffer,
    ) -> Result<bool, Fault> {
        let (at, _) = self.arg(call, index)?;
        let max = self.fetch(at, AccessWidth::Byte)? as usize;
        let len = result.len.min(max);
        for (offset, &byte) in result.chars()[..len].iter().enumerate() {
            self.store(
                at.offset(2 + offset as u32, 0),
                AccessWidth::Byte,
                u32::from(byte),
            )?;
        }
        self.store(at.offset(1, 0), AccessWidth::Byte, len as u32)?;
        Ok(!result.overflow && result.len <= max)
    }

    /// An empty STRING into output `index`: the result of an invalid length or position.
    fn write_empty(&mut self, call: &LibraryCall, index: usize) -> Result<bool, Fault> {
        self.write_text(call, index, &Buffer::new())?;
        Ok(false)
    }

    /// The maximum length of the STRING output `index`.
    fn text_room(&mut self, call: &LibraryCall, index: usize) -> Result<usize, Fault> {
        let (at, _) = self.arg(call, index)?;
        Ok(self.fetch(at, AccessWidth::Byte)? as usize)
    }

    pub(super) fn string_fc(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        match call.number {
            2 => {
                let (first, second) = (self.text(call, 0)?, self.text(call, 1)?);
                let mut out = self.read_text(first)?;
                self.append(&mut out, second, 0, second.len)?;
                self.write_text(call, 2, &out)
            }
            4 => self.delete(call),
            5 | 16 | 30 => self.number_to_text(call),
            11 => self.find(call),
            17 => self.insert(call),
            20 | 32 => self.side(call),
            // The current-length byte as it is, even past the maximum (the other functions
            // read no further than the maximum).
            21 => {
                let (at, _) = self.arg(call, 0)?;
                let len = self.fetch(at.offset(1, 0), AccessWidth::Byte)?;
                self.write_arg(call, 1, len)?;
                Ok(true)
            }
            26 => self.mid(call),
            31 => self.replace(call),
            37..=39 => self.text_to_number(call),
            _ => self.compare_texts(call),
        }
    }

    /// LEFT and RIGHT (IN, L): the first or last L characters; a negative L gives an empty
    /// STRING and an error.
    fn side(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let text = self.text(call, 0)?;
        let Ok(count) = usize::try_from(self.read_int(call, 1)?) else {
            return self.write_empty(call, 2);
        };
        let count = count.min(text.len);
        let from = if call.number == 20 {
            0
        } else {
            text.len - count
        };
        let mut out = Buffer::new();
        self.append(&mut out, text, from, from + count)?;
        self.write_text(call, 2, &out)
    }

    /// MID (IN, L, P): L characters from position P (1 the first); an L or P of 0 or below
    /// gives an empty STRING and an error, a P past the end an empty STRING.
    fn mid(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let text = self.text(call, 0)?;
        let (count, position) = (self.read_int(call, 1)?, self.read_int(call, 2)?);
        if count <= 0 || position <= 0 {
            return self.write_empty(call, 3);
        }
        let from = position as usize - 1;
        let mut out = Buffer::new();
        self.append(&mut out, text, from, from + count as usize)?;
        self.write_text(call, 3, &out)
    }

    /// DELETE (IN, L, P): IN without L characters from position P; an L or P of 0, or a P
    /// past the end, leaves IN as it is; a negative one gives an empty STRING and an error,
    /// the only error the manual gives DELETE: a result longer than RET_VAL is cut to it.
    fn delete(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let text = self.text(call, 0)?;
        let (count, position) = (self.read_int(call, 1)?, self.read_int(call, 2)?);
        if count < 0 || position < 0 {
            return self.write_empty(call, 3);
        }
        let mut out = Buffer::new();
        if count == 0 || position == 0 || position as usize > text.len {
            self.append(&mut out, text, 0, text.len)?;
        } else {
            let from = position as usize - 1;
            self.append(&mut out, text, 0, from)?;
            self.append(&mut out, text, from + count as usize, text.len)?;
        }
        self.write_text(call, 3, &out)?;
        Ok(true)
    }

    /// INSERT (IN1, IN2, P): IN2 after character P of IN1 (0: before the first; past the end:
    /// appended); a negative P gives an empty STRING and an error.
    fn insert(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let (first, second) = (self.text(call, 0)?, self.text(call, 1)?);
        let Ok(position) = usize::try_from(self.read_int(call, 2)?) else {
            return self.write_empty(call, 3);
        };
        let mut out = Buffer::new();
        self.append(&mut out, first, 0, position)?;
        self.append(&mut out, second, 0, second.len)?;
        self.append(&mut out, first, position, first.len)?;
        self.write_text(call, 3, &out)
    }

    /// REPLACE (IN1, IN2, L, P): L characters of IN1 from position P replaced by IN2 (L 0:
    /// IN2 inserted before P; P past the end: appended); a negative L or a P of 0 or below
    /// gives an empty STRING and an error.
    fn replace(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let (first, second) = (self.text(call, 0)?, self.text(call, 1)?);
        let (count, position) = (self.read_int(call, 2)?, self.read_int(call, 3)?);
        if count < 0 || position <= 0 {
            return self.write_empty(call, 4);
        }
        let from = (position as usize - 1).min(first.len);
        let mut out = Buffer::new();
        self.append(&mut out, first, 0, from)?;
        self.append(&mut out, second, 0, second.len)?;
        self.append(&mut out, first, from + count as usize, first.len)?;
        self.write_text(call, 4, &out)
    }

    /// FIND (IN1, IN2): the position of the first IN2 in IN1, 0 when there is none.
    fn find(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let (first, second) = (self.text(call, 0)?, self.text(call, 1)?);
        let haystack = self.read_text(first)?;
        let needle = self.read_text(second)?;
        let position = if needle.len == 0 {
            0
        } else {
            haystack
                .chars()
                .windows(needle.len)
                .position(|window| window == needle.chars())
                .map_or(0, |index| index + 1)
        };
        self.write_arg(call, 2, position as u32)?;
        Ok(true)
    }

    /// EQ_STRNG … NE_STRNG (S1, S2): by the characters' codes from the left, a STRING that
    /// ends first being the smaller.
    fn compare_texts(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let (first, second) = (self.text(call, 0)?, self.text(call, 1)?);
        let first = self.read_text(first)?;
        let second = self.read_text(second)?;
        let order = first.chars().cmp(second.chars());
        let result = match call.number {
            10 => order == Ordering::Equal,
            13 => order != Ordering::Less,
            15 => order == Ordering::Greater,
            19 => order != Ordering::Greater,
            24 => order == Ordering::Less,
            _ => order != Ordering::Equal,
        };
        self.write_arg(call, 2, u32::from(result))?;
        Ok(true)
    }

    /// DI_STRNG, I_STRNG, R_STRNG: the value's characters, when the output can hold the
    /// longest (11, 6, 14 characters) and a REAL is a number; else an error and the output
    /// as it was.
    fn number_to_text(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let raw = self.read_arg(call, 0)?;
        let mut out = Buffer::new();
        let longest = match call.number {
            5 => {
                integer_text(raw as i32, &mut out);
                11
            }
            16 => {
                integer_text(i32::from(raw as u16 as i16), &mut out);
                6
            }
            _ => {
                let value = f32::from_bits(raw);
                if !value.is_finite() {
                    return Ok(false);
                }
                real_text(value, &mut out);
                14
            }
        };
        if self.text_room(call, 1)? < longest {
            return Ok(false);
        }
        self.write_text(call, 1, &out)
    }

    /// STRNG_DI, STRNG_I, STRNG_R: the value the characters spell; characters that spell none
    /// are an error and leave the output as it was, a value beyond the type is limited and an
    /// error.
    fn text_to_number(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let text = self.text(call, 0)?;
        let text = self.read_text(text)?;
        let chars = text.chars();
        let (raw, fits) = match call.number {
            37 | 38 => {
                let (longest, low, high) = if call.number == 37 {
                    (11, i64::from(i32::MIN), i64::from(i32::MAX))
                } else {
                    (6, i64::from(i16::MIN), i64::from(i16::MAX))
                };
                let Some(value) = parse_integer(chars, longest) else {
                    return Ok(false);
                };
                let limited = value.clamp(low, high);
                (limited as i32 as u32, limited == value)
            }
            _ => {
                let Some(value) = parse_real(chars) else {
                    return Ok(false);
                };
                let limited = value.clamp(f64::from(-f32::MAX), f64::from(f32::MAX));
                ((limited as f32).to_bits(), limited == value)
            }
        };
        self.write_arg(call, 1, raw)?;
        Ok(fits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn real(value: f32) -> String {
        let mut out = Buffer::new();
        real_text(value, &mut out);
        String::from_utf8(out.chars().to_vec()).unwrap()
    }

    #[test]
    fn reals_are_written_with_eight_digits_and_a_two_digit_exponent() {
        assert_eq!(real(0.0), "+0.0000000E+00");
        assert_eq!(real(1.0), "+1.0000000E+00");
        assert_eq!(real(-1234.5), "-1.2345000E+03");
        assert_eq!(real(0.001), "+1.0000000E-03");
        assert_eq!(real(3.4028235e38), "+3.4028235E+38");
        assert_eq!(real(9.9999999), "+1.0000000E+01");
    }

    #[test]
    fn reals_are_read_back() {
        assert_eq!(parse_real(b"+1.2345000E+03"), Some(1234.5));
        assert_eq!(parse_real(b"-5.0000000E-01"), Some(-0.5));
        assert_eq!(parse_real(b"+1.2345000E+0"), None);
        assert_eq!(parse_real(b"1.23450000E+03"), None);
    }

    #[test]
    fn integers_take_a_sign_and_at_most_their_length() {
        assert_eq!(parse_integer(b"+123", 6), Some(123));
        assert_eq!(parse_integer(b"-32768", 6), Some(-32768));
        assert_eq!(parse_integer(b"1234567", 6), None);
        assert_eq!(parse_integer(b"12a", 6), None);
        assert_eq!(parse_integer(b"-", 6), None);
    }
}
