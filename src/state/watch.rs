//! The watch table (a PG's STATUS VAR): chosen operands read at every cycle boundary, a row
//! each time one of them changed, or one every `--watch-every` of simulated time.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::scenario::expect::actual;
use crate::scenario::operand::Target;
use crate::trace::Event;
use crate::vm::Cpu;

use crate::address::declared;
use crate::address::notation as s7;
use crate::dialect::Dialect;
use crate::vm::counters::decode_count;

/// One row: when, and every watched value in its natural notation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WatchRow {
    pub t_ns: u64,
    pub cycle: u64,
    pub values: Vec<String>,
}

#[derive(Debug, Default)]
pub struct WatchTable {
    names: Vec<String>,
    targets: Vec<Target>,
    formats: Vec<Option<Format>>,
    every_ns: Option<u64>,
    next_sample_ns: u64,
    last: Option<Vec<String>>,
    pub rows: Vec<WatchRow>,
}

/// A value as the PG shows it: bits 0/1, timers `KT value.base`, counters `KZ`, bytes `KH`,
/// words `KF`, double words `KH`; in a STEP 7 program as STEP 7 shows it: timers `S5T#…`,
/// counters `C#…`, bytes `B#16#…`, words the INT, double words `L#…` or the REAL they hold,
/// and a data block's declared value in its type, as `--state` shows it.
pub fn natural(cpu: &Cpu, target: Target) -> String {
    if let Some(text) = declared_value(cpu, target) {
        return text;
    }
    let step7 = cpu.program.s7.step7;
    match target {
        Target::TimerBit(n) => {
            let mut timer = cpu.timers[usize::from(n)];
            let bit = timer.bit(cpu.clock);
            let (value, base) = (timer.value(cpu.clock), timer.base());
            let time = if step7 {
                s7::s5time(value, base)
            } else {
                format!("KT {value:03}.{base}")
            };
            format!("{time} ({})", u8::from(bit))
        }
        Target::CounterValue(n) => {
            let counter = cpu.counters[usize::from(n)];
            let value = if step7 {
                format!("C#{}", counter.value)
            } else {
                format!("KZ {:03}", counter.value)
            };
            format!("{value} ({})", u8::from(counter.bit()))
        }
        _ => match (actual(cpu, target), target.bytes()) {
            (None, _) => "-".to_string(),
            (Some(raw), 0) => raw.to_string(),
            (Some(raw), 1) if step7 => s7::byte(raw as u8),
            (Some(raw), 1) => format!("KH {raw:02X}"),
            (Some(raw), 2) if step7 => (raw as u16 as i16).to_string(),
            (Some(raw), 2) => format!("KF {:+}", raw as u16 as i16),
            (Some(raw), _) if step7 => s7::double_value(raw),
            (Some(raw), _) => format!("KH {raw:08X}"),
        },
    }
}

/// A display format of a watch row, as STEP 7's variable table offers them (STATUS VAR's
/// `KM`, `KH`, `KF`, `KG`, `KT`, `KZ`, `KC` on a STEP 5 PG). Each is written in the program's
/// own notation; `S5TIME` and `KT` are one format, as the dialects name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Bool,
    Bin,
    Hex,
    Dec,
    Real,
    S5Time,
    Kz,
    Char,
}

impl Format {
    /// The names a watch row takes, and the format each stands for.
    pub const NAMES: [(&'static str, Format); 9] = [
        ("BOOL", Format::Bool),
        ("BIN", Format::Bin),
        ("HEX", Format::Hex),
        ("DEC", Format::Dec),
        ("REAL", Format::Real),
        ("S5TIME", Format::S5Time),
        ("KT", Format::S5Time),
        ("KZ", Format::Kz),
        ("CHAR", Format::Char),
    ];

    /// `HEX`, `hex`; `None` for a name that is no format.
    pub fn parse(name: &str) -> Option<Format> {
        let name = name.trim();
        Format::NAMES
            .iter()
            .find(|(known, _)| known.eq_ignore_ascii_case(name))
            .map(|(_, format)| *format)
    }

    /// The format's name in a program of `step7`'s dialect: `S5TIME` or `KT`.
    pub fn name(self, step7: bool) -> &'static str {
        match self {
            Format::S5Time if !step7 => "KT",
            _ => {
                let (name, _) = Format::NAMES
                    .iter()
                    .find(|(_, format)| *format == self)
                    .expect("every format has a name");
                name
            }
        }
    }

    /// The format [`natural`] writes `target` in, by the name a watch row shows: a bit's
    /// BOOL, a timer's time, a counter's count, a word's (and a STEP 7 double word's) DEC, a
    /// byte's (and a STEP 5 double word's) HEX.
    pub fn natural(target: Target, step7: bool) -> Format {
        match target {
            Target::TimerBit(_) => Format::S5Time,
            Target::CounterValue(_) => Format::Kz,
            _ => match (target.bytes(), step7) {
                (0, _) => Format::Bool,
                (2, _) | (4, true) => Format::Dec,
                _ => Format::Hex,
            },
        }
    }

    /// Why `target` cannot be shown in this format, if it cannot: a bit shows as BOOL or BIN,
    /// a REAL needs a double word, a time or a count a word.
    pub fn misfit(self, target: Target) -> Option<&'static str> {
        let bytes = target.bytes();
        let (timer, counter) = (
            matches!(target, Target::TimerBit(_)),
            matches!(target, Target::CounterValue(_)),
        );
        let fits = match self {
            Format::Bool => bytes == 0 || timer || counter,
            Format::Bin => true,
            Format::Hex | Format::Dec | Format::Char => bytes > 0 || timer,
            Format::Real => bytes == 4,
            Format::S5Time => bytes == 2 && !counter || timer,
            Format::Kz => bytes == 2,
        };
        (!fits).then_some(match self {
            Format::Bool => "BOOL shows a bit (or a timer's or counter's bit)",
            Format::Real => "REAL shows a double word (MD, ID, QD, DBD)",
            Format::S5Time => "a time (S5TIME, KT) is a word or a timer",
            Format::Kz => "a count (KZ) is a word or a counter",
            _ => "a bit shows as BOOL or BIN",
        })
    }
}

/// The bits a watch row shows of `target`, and how many: a timer's coded time word (as `LC T`
/// loads it), a counter's count.
fn shown_bits(cpu: &Cpu, target: Target) -> Option<(u32, u32)> {
    match target {
        Target::TimerBit(n) => {
            let mut timer = cpu.timers[usize::from(n)];
            Some((timer.coded(cpu.clock), 16))
        }
        Target::CounterValue(n) => Some((u32::from(cpu.counters[usize::from(n)].value), 16)),
        _ => actual(cpu, target).map(|raw| (raw, (u32::from(target.bytes()) * 8).max(1))),
    }
}

/// The bit a BOOL row shows: a timer's or counter's own bit, else the operand's lowest bit.
fn shown_bit(cpu: &Cpu, target: Target) -> bool {
    match target {
        Target::TimerBit(n) => {
            let mut timer = cpu.timers[usize::from(n)];
            timer.bit(cpu.clock)
        }
        Target::CounterValue(n) => cpu.counters[usize::from(n)].bit(),
        _ => actual(cpu, target).is_some_and(|raw| raw & 1 != 0),
    }
}

/// A watch row's value as a number: a bit's state, else the unsigned bit pattern (a timer's
/// coded time word, a counter's count).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(untagged)]
pub enum Raw {
    Bit(bool),
    Bits(u32),
}

/// The raw value of `target`; `None` when it is not there (a data block not loaded).
pub fn raw(cpu: &Cpu, target: Target) -> Option<Raw> {
    match target {
        Target::ImageBit { .. } | Target::S7Data { bytes: 0, .. } => {
            actual(cpu, target).map(|bit| Raw::Bit(bit != 0))
        }
        _ => shown_bits(cpu, target).map(|(bits, _)| Raw::Bits(bits)),
    }
}

/// `target`'s value in `format` (`None`: the dialect's own notation, as [`natural`]); the
/// format fits the target ([`Format::misfit`]).
pub fn formatted(cpu: &Cpu, target: Target, format: Option<Format>) -> String {
    let dialect = if cpu.program.s7.step7 {
        Dialect::Step7
    } else {
        Dialect::Step5
    };
    let Some(format) = format else {
        return natural(cpu, target);
    };
    match (format, shown_bits(cpu, target)) {
        (Format::Bool, _) => u8::from(shown_bit(cpu, target)).to_string(),
        (_, None) => "-".to_string(),
        (Format::Bin, Some((raw, bits))) => s7::binary(dialect, raw, bits),
        (Format::Hex, Some((raw, bits))) => s7::hex(dialect, raw, bits),
        (Format::Dec, Some((raw, bits))) => s7::decimal(dialect, raw, bits),
        (Format::Real, Some((raw, _))) => s7::real(dialect, raw),
        (Format::S5Time, Some((raw, _))) => s7::time_word(dialect, raw),
        (Format::Kz, Some((raw, _))) if matches!(target, Target::CounterValue(_)) => {
            s7::count(dialect, raw as u16)
        }
        (Format::Kz, Some((raw, _))) => s7::count(dialect, decode_count(raw)),
        (Format::Char, Some((raw, bits))) => s7::characters(dialect, raw, bits),
    }
}

/// The value a STEP 7 data block operand reads, in the type its declaration gives it
/// (`W#16#0200`, `T#1S500MS`, `TRUE`); `None` for an operand no declared value is.
fn declared_value(cpu: &Cpu, target: Target) -> Option<String> {
    let Target::S7Data {
        db,
        byte,
        bit,
        bytes,
    } = target
    else {
        return None;
    };
    let tables = &cpu.program.s7.declared_dbs;
    let (_, values) = tables.iter().find(|(number, _)| *number == db)?;
    let value = declared::at(values, byte, bit, bytes)?;
    Some(declared::text(value, cpu.s7_db(db)?))
}

/// A value as a number, for a counter track: timers and counters their value, words signed.
pub fn number(cpu: &Cpu, target: Target) -> i64 {
    match target {
        Target::TimerBit(n) => i64::from(cpu.timers[usize::from(n)].value(cpu.clock)),
        Target::CounterValue(n) => i64::from(cpu.counters[usize::from(n)].value),
        _ => match (actual(cpu, target), target.bytes()) {
            (None, _) => 0,
            (Some(raw), 2) => i64::from(raw as u16 as i16),
            (Some(raw), _) => i64::from(raw),
        },
    }
}

impl WatchTable {
    /// The table of `watched` operands by their column names, each with its display format
    /// (`None`: the dialect's own notation).
    pub fn new(watched: Vec<(String, Target, Option<Format>)>, every_ns: Option<u64>) -> Self {
        let mut table = WatchTable {
            every_ns,
            ..WatchTable::default()
        };
        for (name, target, format) in watched {
            table.names.push(name);
            table.targets.push(target);
            table.formats.push(format);
        }
        table
    }

    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }

    /// At a cycle boundary: records a row if a value changed (or the sampling time came), and
    /// traces it.
    pub fn observe(&mut self, cpu: &mut Cpu) {
        if self.is_empty() {
            return;
        }
        let values: Vec<String> = self
            .targets
            .iter()
            .zip(&self.formats)
            .map(|(target, format)| formatted(cpu, *target, *format))
            .collect();
        let due = match self.every_ns {
            Some(every) => {
                let due = cpu.clock >= self.next_sample_ns;
                while self.next_sample_ns <= cpu.clock {
                    self.next_sample_ns += every;
                }
                due
            }
            None => self.last.as_ref() != Some(&values),
        };
        if !due {
            return;
        }
        if cpu.tracer.enabled {
            let event = Event::Watch {
                cycle: cpu.cycle,
                values: self.names.iter().cloned().zip(values.clone()).collect(),
                numbers: self
                    .names
                    .iter()
                    .zip(&self.targets)
                    .map(|(name, target)| (name.clone(), number(cpu, *target)))
                    .collect(),
            };
            cpu.tracer.emit(cpu.clock, event);
        }
        self.rows.push(WatchRow {
            t_ns: cpu.clock,
            cycle: cpu.cycle,
            values: values.clone(),
        });
        self.last = Some(values);
    }

    /// The table as text: a header with the operands, one line per row.
    pub fn render(&self) -> String {
        let widths: Vec<usize> = self
            .names
            .iter()
            .enumerate()
            .map(|(n, name)| {
                let widest = self.rows.iter().map(|row| row.values[n].len()).max();
                widest.unwrap_or(0).max(name.len())
            })
            .collect();
        let mut out = format!("{:>14}  {:>6}", "time", "cycle");
        for (name, width) in self.names.iter().zip(&widths) {
            let _ = write!(out, "  {name:>width$}");
        }
        out.push('\n');
        for row in &self.rows {
            let _ = write!(
                out,
                "{:>14}  {:>6}",
                crate::trace::format_ms(row.t_ns),
                row.cycle
            );
            for (value, width) in row.values.iter().zip(&widths) {
                let _ = write!(out, "  {value:>width$}");
            }
            out.push('\n');
        }
        out
    }
}

/// The rows of a watch table file (the online page's Save and Load, `awl run --watch-file`):
/// one row a line, `OPERAND [FORMAT]` (`MW 10 HEX`, `DB 5 DW 3`, `"Motor"`), `//` starting a
/// comment, blank lines ignored. A last word that names a format is the row's format.
pub fn table_rows(text: &str) -> Vec<(String, Option<Format>)> {
    text.lines()
        .map(|line| line.split("//").next().unwrap_or("").trim())
        .filter(|line| !line.is_empty())
        .map(|line| {
            let format = line
                .rsplit_once(char::is_whitespace)
                .and_then(|(operand, last)| Some((operand.trim_end(), Format::parse(last)?)));
            match format {
                Some((operand, format)) => (operand.to_string(), Some(format)),
                None => (line.to_string(), None),
            }
        })
        .collect()
}

/// The values of a watch event, by operand.
pub type WatchValues = BTreeMap<String, String>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_watch_table_file_has_an_operand_and_a_format_a_line() {
        let text = "// the tank\nMW 10 HEX\n\n  DB 5 DW 3  // a data word\nQ 4.0 bool\n\"Motor\"\nT 1 KT\n";
        assert_eq!(
            table_rows(text),
            [
                ("MW 10".to_string(), Some(Format::Hex)),
                ("DB 5 DW 3".to_string(), None),
                ("Q 4.0".to_string(), Some(Format::Bool)),
                ("\"Motor\"".to_string(), None),
                ("T 1".to_string(), Some(Format::S5Time)),
            ]
        );
        assert!(table_rows("\n// nothing\n").is_empty());
    }
}
