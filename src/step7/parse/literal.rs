//! STEP 7 constants, as written, to the value the CPU loads ("Statement List (STL) for S7-300
//! and S7-400 Programming": data types and their constant formats).

use crate::step7::ast::{ConstKind, S7Constant};

fn constant(kind: ConstKind, value: u32) -> S7Constant {
    S7Constant {
        kind,
        value,
        bytes: Vec::new(),
    }
}

fn digits(text: &str, radix: u32) -> Option<u64> {
    let cleaned: String = text.chars().filter(|c| *c != '_').collect();
    // awlsim also reads a C-style `0x` after `16#`.
    let cleaned = match radix {
        16 => cleaned.trim_start_matches("0X").to_string(),
        _ => cleaned,
    };
    if cleaned.is_empty() {
        return None;
    }
    u64::from_str_radix(&cleaned, radix).ok()
}

/// Why a constant is not one.
pub type Problem = String;

/// A constant written in any STEP 7 format.
pub fn parse(text: &str) -> Result<S7Constant, Problem> {
    let upper = text.to_ascii_uppercase();
    if upper == "TRUE" || upper == "FALSE" {
        return Ok(constant(ConstKind::Bool, u32::from(upper == "TRUE")));
    }
    if let Some(inner) = text.strip_prefix('\'').and_then(|t| t.strip_suffix('\'')) {
        return Ok(string(inner));
    }
    if let Some(number) = timer_or_counter(&upper) {
        return Ok(number);
    }
    if let Some(hash) = upper.find('#') {
        let (prefix, rest) = (&upper[..hash], &upper[hash + 1..]);
        return typed(prefix, rest, text);
    }
    number(&upper)
}

/// `T 5`, `C 3` (German `Z 3`): a timer or counter as a parameter value.
fn timer_or_counter(upper: &str) -> Option<S7Constant> {
    let (kind, rest) = match upper.chars().next()? {
        'T' => (ConstKind::TimerNumber, &upper[1..]),
        'C' | 'Z' => (ConstKind::CounterNumber, &upper[1..]),
        _ => return None,
    };
    let number: u16 = rest.trim().parse().ok()?;
    Some(constant(kind, u32::from(number)))
}

fn string(inner: &str) -> S7Constant {
    let bytes: Vec<u8> = inner.chars().map(|c| c as u32 as u8).collect();
    let value = bytes
        .iter()
        .take(4)
        .fold(0u32, |v, b| v << 8 | u32::from(*b));
    let kind = if bytes.len() == 1 {
        ConstKind::Char
    } else {
        ConstKind::String
    };
    S7Constant { kind, value, bytes }
}

/// A decimal integer (INT when it fits 16 bits, else DINT) or a REAL.
fn number(text: &str) -> Result<S7Constant, Problem> {
    let is_real = text.contains('.') || (text.contains('E') && !text.starts_with("16"));
    if is_real {
        let value: f32 = text
            .parse()
            .map_err(|_| format!("`{text}` is not a number"))?;
        return Ok(constant(ConstKind::Real, value.to_bits()));
    }
    let value: i64 = text
        .trim_start_matches('+')
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if (-32768..=32767).contains(&value) {
        Ok(constant(ConstKind::Int, value as i16 as u16 as u32))
    } else if (i64::from(i32::MIN)..=i64::from(i32::MAX)).contains(&value) {
        Ok(constant(ConstKind::Dint, value as i32 as u32))
    } else {
        Err(format!("{value} does not fit 32 bits"))
    }
}

fn typed(prefix: &str, rest: &str, text: &str) -> Result<S7Constant, Problem> {
    let range = |kind, bits: u32, radix, digits_text: &str| -> Result<S7Constant, Problem> {
        let value = digits(digits_text, radix).ok_or_else(|| format!("`{text}`: bad digits"))?;
        if bits < 64 && value >= 1 << bits {
            return Err(format!("`{text}` does not fit {bits} bits"));
        }
        Ok(constant(kind, value as u32))
    };
    match prefix {
        "B" if rest.starts_with("16#") => range(ConstKind::Byte, 8, 16, &rest[3..]),
        "W" if rest.starts_with("16#") => range(ConstKind::Word, 16, 16, &rest[3..]),
        "W" if rest.starts_with("2#") => range(ConstKind::Word, 16, 2, &rest[2..]),
        "DW" if rest.starts_with("16#") => range(ConstKind::Dword, 32, 16, &rest[3..]),
        "DW" if rest.starts_with("2#") => range(ConstKind::Dword, 32, 2, &rest[2..]),
        "16" => {
            let count = rest.chars().filter(|c| *c != '_').count();
            let kind = if count <= 4 {
                ConstKind::Word
            } else {
                ConstKind::Dword
            };
            range(kind, 32, 16, rest)
        }
        "2" => {
            let count = rest.chars().filter(|c| *c != '_').count();
            let kind = if count <= 16 {
                ConstKind::Word
            } else {
                ConstKind::Dword
            };
            range(kind, 32, 2, rest)
        }
        "L" => {
            let value: i64 = rest
                .trim_start_matches('+')
                .parse()
                .map_err(|_| format!("`{text}` is not a double integer"))?;
            i32::try_from(value)
                .map(|v| constant(ConstKind::Dint, v as u32))
                .map_err(|_| format!("`{text}` does not fit 32 bits"))
        }
        "B" if rest.starts_with('(') => byte_tuple(rest, text),
        "S5T" | "S5TIME" => s5time(rest).map(|v| constant(ConstKind::S5Time, v)),
        "T" | "TIME" => duration_ms(rest).map(|v| constant(ConstKind::Time, v as u32)),
        "D" | "DATE" => date_days(rest).map(|d| constant(ConstKind::Date, d)),
        "TOD" | "TIME_OF_DAY" => time_of_day(rest).map(|ms| constant(ConstKind::TimeOfDay, ms)),
        "DT" | "DATE_AND_TIME" => date_and_time(rest),
        "C" => {
            let value: u32 = rest
                .parse()
                .map_err(|_| format!("`{text}`: a count 0 to 999"))?;
            if value > 999 {
                return Err(format!("`{text}`: a count 0 to 999"));
            }
            Ok(constant(ConstKind::Counter, bcd(value)))
        }
        "P" => pointer(rest, text),
        "CHAR" => Err(format!("`{text}`: write a character as 'A'")),
        _ => Err(format!("`{text}` is no STEP 7 constant")),
    }
}

fn bcd(mut value: u32) -> u32 {
    let mut out = 0;
    let mut shift = 0;
    while value > 0 {
        out |= (value % 10) << shift;
        value /= 10;
        shift += 4;
    }
    out
}

fn byte_tuple(rest: &str, text: &str) -> Result<S7Constant, Problem> {
    let inner = rest.trim_start_matches('(').trim_end_matches(')');
    let bytes: Result<Vec<u8>, _> = inner.split(',').map(|b| b.trim().parse::<u8>()).collect();
    let bytes = bytes.map_err(|_| format!("`{text}`: bytes 0 to 255"))?;
    if bytes.len() != 2 && bytes.len() != 4 {
        return Err(format!("`{text}`: two or four bytes"));
    }
    let value = bytes.iter().fold(0u32, |v, b| v << 8 | u32::from(*b));
    Ok(constant(ConstKind::ByteTuple, value))
}

/// `1D2H3M4S5MS` (also with `_` and a sign) in milliseconds.
fn duration_ms(text: &str) -> Result<i64, Problem> {
    let (negative, body) = match text.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, text.trim_start_matches('+')),
    };
    let body: String = body.chars().filter(|c| *c != '_').collect();
    let mut total = 0f64;
    let mut number = String::new();
    let mut chars = body.chars().peekable();
    let mut any = false;
    while let Some(c) = chars.next() {
        if c.is_ascii_digit() || c == '.' {
            number.push(c);
            continue;
        }
        let unit = match c {
            'D' => 86_400_000.0,
            'H' => 3_600_000.0,
            'M' if chars.peek() == Some(&'S') => {
                chars.next();
                1.0
            }
            'M' => 60_000.0,
            'S' => 1000.0,
            _ => return Err(format!("`{text}`: units are D H M S MS")),
        };
        let value: f64 = number
            .parse()
            .map_err(|_| format!("`{text}`: a number before each unit"))?;
        total += value * unit;
        number.clear();
        any = true;
    }
    if !number.is_empty() || !any {
        return Err(format!("`{text}`: each number needs a unit (D H M S MS)"));
    }
    let total = total.round() as i64;
    Ok(if negative { -total } else { total })
}

/// The S5TIME word: three BCD digits and the time base (10 ms, 100 ms, 1 s, 10 s) in bits
/// 12–13, the finest base that holds the value.
fn s5time(text: &str) -> Result<u32, Problem> {
    let ms = duration_ms(text)?;
    if !(0..=9_990_000).contains(&ms) {
        return Err(format!("S5T#{text}: S5TIME runs from 0 to 2H46M30S"));
    }
    let ms = ms as u32;
    let (base, unit) = [(0u32, 10u32), (1, 100), (2, 1000), (3, 10_000)]
        .into_iter()
        .find(|(_, unit)| ms / unit <= 999)
        .expect("9,990,000 ms fits the 10 s base");
    Ok(base << 12 | bcd(ms / unit))
}

fn days_from_civil(year: i64, month: i64, day: i64) -> i64 {
    let y = if month <= 2 { year - 1 } else { year };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (month + 9) % 12;
    let doy = (153 * mp + 2) / 5 + day - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

fn ymd(text: &str) -> Option<(i64, i64, i64)> {
    let mut parts = text.splitn(3, '-');
    let year = parts.next()?.parse().ok()?;
    let month = parts.next()?.parse().ok()?;
    let day = parts.next()?.parse().ok()?;
    ((1..=12).contains(&month) && (1..=31).contains(&day)).then_some((year, month, day))
}

/// Days since 1990-01-01.
fn date_days(text: &str) -> Result<u32, Problem> {
    let (year, month, day) = ymd(text).ok_or_else(|| format!("D#{text}: write D#yyyy-mm-dd"))?;
    let days = days_from_civil(year, month, day) - days_from_civil(1990, 1, 1);
    u16::try_from(days)
        .map(u32::from)
        .map_err(|_| format!("D#{text}: dates run from 1990-01-01 to 2168-12-31"))
}

/// `hh:mm:ss[.fff]` in milliseconds since midnight.
fn time_of_day(text: &str) -> Result<u32, Problem> {
    let bad = || format!("TOD#{text}: write TOD#hh:mm:ss.fff");
    let mut parts = text.split(':');
    let hours: u32 = parts.next().and_then(|p| p.parse().ok()).ok_or_else(bad)?;
    let minutes: u32 = parts.next().and_then(|p| p.parse().ok()).ok_or_else(bad)?;
    let seconds: f64 = parts
        .next()
        .map_or(Some(0.0), |p| p.parse().ok())
        .ok_or_else(bad)?;
    if hours > 23 || minutes > 59 || !(0.0..60.0).contains(&seconds) {
        return Err(bad());
    }
    Ok(hours * 3_600_000 + minutes * 60_000 + (seconds * 1000.0).round() as u32)
}

/// `yyyy-mm-dd-hh:mm:ss[.fff]` as the eight BCD bytes of DATE_AND_TIME.
fn date_and_time(text: &str) -> Result<S7Constant, Problem> {
    let bad = || format!("DT#{text}: write DT#yyyy-mm-dd-hh:mm:ss.fff");
    let (date, time) = text
        .match_indices('-')
        .nth(2)
        .map(|(at, _)| (&text[..at], &text[at + 1..]))
        .ok_or_else(bad)?;
    let (year, month, day) = ymd(date).ok_or_else(bad)?;
    if !(1990..=2089).contains(&year) {
        return Err(format!("DT#{text}: years 1990 to 2089"));
    }
    let ms = time_of_day(time).map_err(|_| bad())?;
    let weekday = (days_from_civil(year, month, day) + 4).rem_euclid(7) + 1;
    let (hours, minutes, seconds, millis) =
        (ms / 3_600_000, ms / 60_000 % 60, ms / 1000 % 60, ms % 1000);
    let bytes = vec![
        bcd((year % 100) as u32) as u8,
        bcd(month as u32) as u8,
        bcd(day as u32) as u8,
        bcd(hours) as u8,
        bcd(minutes) as u8,
        bcd(seconds) as u8,
        bcd(millis / 10) as u8,
        ((millis % 10) << 4 | weekday as u32) as u8,
    ];
    Ok(S7Constant {
        kind: ConstKind::DateAndTime,
        value: u32::from_be_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
        bytes,
    })
}

/// The area code of a pointer's area letters (`M`, `DBX`, `I`/`E`, …).
fn area_code(area: &str) -> Option<u32> {
    Some(match area {
        "P" => 0x80,
        "I" | "E" => 0x81,
        "Q" | "A" => 0x82,
        "M" => 0x83,
        "DBX" => 0x84,
        "DIX" => 0x85,
        "L" => 0x86,
        "V" => 0x87,
        _ => return None,
    })
}

fn byte_bit(text: &str) -> Option<u32> {
    let (byte, bit) = text.split_once('.')?;
    let byte: u32 = byte.trim().parse().ok()?;
    let bit: u32 = bit.trim().parse().ok()?;
    (bit <= 7 && byte <= 0xFFFF).then_some(byte << 3 | bit)
}

/// `P#M 1.0`, `P#DBX 2.0`, `P#2.0`, and the ANY pointer `P#DB1.DBX 0.0 BYTE 10`.
fn pointer(rest: &str, text: &str) -> Result<S7Constant, Problem> {
    let bad = || format!("`{text}`: write P#M 1.0, P#DBX 2.0 or P#2.0");
    let rest = rest.trim();
    if let Some(address) = byte_bit(rest) {
        return Ok(constant(ConstKind::Pointer, address));
    }
    let words: Vec<&str> = rest.split_whitespace().collect();
    let split_area = |word: &str| {
        let at = word
            .find(|c: char| c.is_ascii_digit())
            .unwrap_or(word.len());
        (word[..at].to_string(), word[at..].to_string())
    };
    match words.as_slice() {
        [area_and_address] | [area_and_address, ..] if words.len() <= 2 => {
            let (area, tail) = split_area(area_and_address);
            let address = if words.len() == 2 {
                words[1].to_string()
            } else {
                tail
            };
            let code = area_code(&area).ok_or_else(bad)?;
            let offset = byte_bit(&address).ok_or_else(bad)?;
            Ok(constant(ConstKind::Pointer, code << 24 | offset))
        }
        [db_area, address, ty, count] => any_pointer(db_area, address, ty, count).ok_or_else(bad),
        _ => Err(bad()),
    }
}

/// The ten bytes of an ANY pointer.
fn any_pointer(db_area: &str, address: &str, ty: &str, count: &str) -> Option<S7Constant> {
    let (db, area) = match db_area.split_once('.') {
        Some((db, area)) => (db.strip_prefix("DB")?.parse::<u16>().ok()?, area),
        None => (0, db_area),
    };
    let code = area_code(area)?;
    let offset = byte_bit(address)?;
    let type_code: u8 = match ty {
        "BOOL" => 1,
        "BYTE" => 2,
        "CHAR" => 3,
        "WORD" => 4,
        "INT" => 5,
        "DWORD" => 6,
        "DINT" => 7,
        "REAL" => 8,
        _ => return None,
    };
    let count: u16 = count.parse().ok()?;
    let pointer = (code << 24 | offset).to_be_bytes();
    let mut bytes = vec![0x10, type_code];
    bytes.extend(count.to_be_bytes());
    bytes.extend(db.to_be_bytes());
    bytes.extend(pointer);
    Some(S7Constant {
        kind: ConstKind::AnyPointer,
        value: u32::from_be_bytes(pointer),
        bytes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(text: &str) -> u32 {
        parse(text)
            .unwrap_or_else(|problem| panic!("{text}: {problem}"))
            .value
    }

    #[test]
    fn integers_reals_and_hex() {
        assert_eq!(value("-1"), 0xFFFF);
        assert_eq!(parse("40000").unwrap().kind, ConstKind::Dint);
        assert_eq!(value("L#-5"), (-5i32) as u32);
        assert_eq!(value("1.5"), 1.5f32.to_bits());
        assert_eq!(value("-0.0"), 0x8000_0000);
        assert_eq!(value("1.5e10"), 1.5e10f32.to_bits());
        assert_eq!(value("W#16#00FF"), 0xFF);
        assert_eq!(value("DW#16#DEAD_BEEF"), 0xDEAD_BEEF);
        assert_eq!(value("B#16#7f"), 0x7F);
        assert_eq!(value("2#0101_0101"), 0x55);
        assert_eq!(value("B#(1, 2)"), 0x0102);
        assert!(parse("B#16#100").is_err());
        assert_eq!(value("DW#16#0xFFED2979"), 0xFFED_2979);
        assert_eq!(parse("T 24").unwrap().kind, ConstKind::TimerNumber);
        assert_eq!(value("Z 3"), 3);
    }

    #[test]
    fn times_dates_and_counts() {
        assert_eq!(value("S5T#2S"), 0x0200);
        assert_eq!(value("S5T#7S"), 0x0700);
        assert_eq!(value("S5T#100MS"), 0x0010);
        assert_eq!(value("S5T#__1_M__2_S__100__MS__"), 0x1621);
        assert_eq!(value("T#1S"), 1000);
        assert_eq!(value("T#-1D"), (-86_400_000i32) as u32);
        assert_eq!(value("D#1990-01-02"), 1);
        assert_eq!(value("TOD#01:00:00.5"), 3_600_500);
        assert_eq!(value("C#999"), 0x999);
        let dt = parse("DT#1990-01-01-10:20:30.456").unwrap();
        assert_eq!(
            dt.bytes,
            vec![0x90, 0x01, 0x01, 0x10, 0x20, 0x30, 0x45, 0x62]
        );
    }

    #[test]
    fn pointers() {
        assert_eq!(value("P#M 1.0"), 0x8300_0008);
        assert_eq!(value("P#DBX 2.0"), 0x8400_0010);
        assert_eq!(value("P#2.1"), 0x11);
        let any = parse("P#DB1.DBX 0.0 BYTE 10").unwrap();
        assert_eq!(any.bytes, vec![0x10, 2, 0, 10, 0, 1, 0x84, 0, 0, 0]);
    }
}
