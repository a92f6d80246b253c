//! The state as text, in the program's dialect. STEP 5: `FY 10 = KH 7B = 0111 1011`,
//! `DB 10 DW 3 = KF +123 = KH 007B`, `T 1 = KT 250.1`. STEP 7: `MW 10 = 22 = W#16#0016`,
//! `MD 20 = DW#16#3FC00000 = 1.5`, `DB5.DBW 2 = 12 = W#16#000C`, `T 1 = S5T#2S500MS`,
//! `C 3 = C#5`, and the registers: the status word with BR, AR1, AR2, the DB and DI registers.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::address::declared::ValueView;
use crate::address::notation;
use crate::dialect::Dialect;

use super::{LevelView, Registers, State, StatusBits};

/// A map keyed by numbers written as text (`"10"`, `"DB 10"`), keyed by the numbers.
pub(super) fn numeric<'a, V>(map: &'a BTreeMap<String, V>, prefix: &str) -> BTreeMap<u16, &'a V> {
    map.iter()
        .filter_map(|(key, value)| Some((key.strip_prefix(prefix)?.parse().ok()?, value)))
        .collect()
}

/// The image areas and the names of their bytes, words and double words.
fn image_names(dialect: Dialect) -> [(&'static str, [&'static str; 3]); 3] {
    let flags = match dialect {
        Dialect::Step5 => ("F", ["FY", "FW", "FD"]),
        Dialect::Step7 => ("M", ["MB", "MW", "MD"]),
    };
    [("I", ["IB", "IW", "ID"]), ("Q", ["QB", "QW", "QD"]), flags]
}

/// One address in the width the program used: `FY 10 = KH 7B = 0111 1011`,
/// `MW 10 = 22 = W#16#0016`, `MD 20 = DW#16#3FC00000 = 1.5`.
fn line(dialect: Dialect, names: [&str; 3], at: u16, width: u16, value: u32) -> String {
    match width {
        1 => format!(
            "{} {at:<4} = {}",
            names[0],
            notation::byte_and_bits(dialect, value as u8)
        ),
        2 => format!(
            "{} {at:<4} = {}",
            names[1],
            notation::integer_word(dialect, value as u16)
        ),
        _ => format!(
            "{} {at:<4} = {}",
            names[2],
            notation::hex_double(dialect, value)
        ),
    }
}

/// `width` units from `at`, big-endian, from a map of the non-zero ones.
fn value_at<V: Copy + Into<u32>>(
    units: &BTreeMap<u16, &V>,
    at: u16,
    width: u16,
    unit_bits: u32,
) -> u32 {
    (at..at.saturating_add(width)).fold(0u32, |value, at| {
        value << unit_bits | units.get(&at).map_or(0, |unit| (**unit).into())
    })
}

/// The non-zero bytes of an image area in address order, each in the width the program used
/// it in.
fn image_area(
    out: &mut String,
    state: &State,
    dialect: Dialect,
    area: &'static str,
    names: [&str; 3],
) {
    let bytes = numeric(&state.images[area], "");
    for (at, width) in state.widths.image_ranges(area, bytes.keys().copied()) {
        let value = value_at(&bytes, at, width, 8);
        let _ = writeln!(out, "  {}", line(dialect, names, at, width, value));
    }
}

/// The non-zero words of STEP 5 data block `db` in address order; double words where the
/// program transferred one: `DB 10 DW 3 = KF +123 = KH 007B`, `DB 10 DD 4 = DH 00010002 = +65538`.
fn word_data_block(out: &mut String, state: &State, db: u16, words: &BTreeMap<String, u16>) {
    let words = numeric(words, "");
    for (at, width) in state.widths.data_ranges(words.keys().copied()) {
        let value = value_at(&words, at, width, 16);
        let line = line(Dialect::Step5, ["DL", "DW", "DD"], at, width * 2, value);
        let _ = writeln!(out, "  DB {db} {line}");
    }
}

/// The non-zero bytes of STEP 7 data block `db`: `DB5.DBW 2 = 12 = W#16#000C`.
fn byte_data_block(out: &mut String, state: &State, db: u16, bytes: &BTreeMap<String, u16>) {
    let bytes = numeric(bytes, "");
    for (at, width) in state.widths.s7_data_ranges(bytes.keys().copied()) {
        let text = line(
            Dialect::Step7,
            ["DBB", "DBW", "DBD"],
            at,
            width,
            value_at(&bytes, at, width, 8),
        );
        let _ = writeln!(out, "  DB{db}.{text}");
    }
}

/// A data block by its declaration, as STEP 7's data view lists it: `DB5.setpoint = 1234`,
/// the names aligned.
fn declared_block(out: &mut String, db: u16, values: &[ValueView]) {
    let width = values
        .iter()
        .map(|value| value.name.len())
        .max()
        .unwrap_or(0);
    for value in values {
        let _ = writeln!(out, "  DB{db}.{:<width$} = {}", value.name, value.value);
    }
}

fn registers(out: &mut String, registers: &Registers) {
    let register = |db: u16| match db {
        0 => "none".to_string(),
        db => format!("DB {db}"),
    };
    for (name, value) in [("AR1", registers.ar1), ("AR2", registers.ar2)] {
        let _ = writeln!(
            out,
            "  {name}      DW#16#{value:08X} = {}",
            notation::pointer(value)
        );
    }
    let _ = writeln!(
        out,
        "  DB       {}   DI  {}",
        register(registers.db),
        register(registers.di)
    );
}

pub fn accu(value: u32) -> String {
    format!(
        "KH {:04X} {:04X}  (low word KF {:+})",
        value >> 16,
        value & 0xFFFF,
        value as u16 as i16
    )
}

/// A STEP 7 accumulator as a double word, and its low word as an INT unless it holds a REAL.
fn step7_accu(value: u32) -> String {
    let double = notation::double(value);
    match notation::as_real(value) {
        Some(_) => double,
        None => format!("{double}  (low word {})", value as u16 as i16),
    }
}

/// The status bits; a STEP 7 program's (with BR) as its status word.
pub fn status(status: &StatusBits) -> String {
    if status.br.is_some() {
        return format!("STW {}", notation::status_word(status.word()));
    }
    let bit = |set: bool| u8::from(set);
    format!(
        "first check {}  RLO {}  STA {}  OR {}  OS {}  OV {}  CC 1 {}  CC 0 {}",
        bit(status.first_check),
        bit(status.rlo),
        bit(status.sta),
        bit(status.or),
        bit(status.os),
        bit(status.ov),
        bit(status.cc1),
        bit(status.cc0)
    )
}

fn open_db(open: Option<u16>) -> String {
    open.map_or("none".to_string(), |db| format!("DB {db}"))
}

const TIME_BASES: [&str; 4] = ["10 ms", "100 ms", "1 s", "10 s"];

/// `--state`: what a PG would show after the run.
pub fn render(state: &State) -> String {
    render_titled(state, "\nstate at the end")
}

/// The state under a title of its own (the debugger's `state`: "state at 12.5 ms").
pub fn render_titled(state: &State, title: &str) -> String {
    let dialect = if state.step7 {
        Dialect::Step7
    } else {
        Dialect::Step5
    };
    let mut out = format!("{title}: mode {}\n", state.mode);
    for (n, value) in state.accu.iter().enumerate() {
        let text = match dialect {
            Dialect::Step5 => accu(*value),
            Dialect::Step7 => step7_accu(*value),
        };
        let _ = writeln!(out, "  ACCU {}   {text}", n + 1);
    }
    match dialect {
        Dialect::Step5 => {
            let _ = writeln!(out, "  status   {}", status(&state.status));
            let _ = writeln!(out, "  open DB  {}", open_db(state.open_db));
        }
        Dialect::Step7 => {
            let stw = notation::status_word(state.status.word());
            let _ = writeln!(out, "  STW      {stw}");
            if let Some(registers_now) = &state.registers {
                registers(&mut out, registers_now);
            }
        }
    }
    for (area, names) in image_names(dialect) {
        image_area(&mut out, state, dialect, area, names);
    }
    for timer in &state.timers {
        let value = match dialect {
            Dialect::Step5 => format!("KT {:03}.{}", timer.value, timer.base),
            Dialect::Step7 => notation::s5time(timer.value, timer.base),
        };
        let _ = writeln!(
            out,
            "  T {:<5} = {value}  ({} × {}), {}, bit {}",
            timer.number,
            timer.value,
            TIME_BASES[usize::from(timer.base)],
            if timer.running { "running" } else { "stopped" },
            u8::from(timer.bit)
        );
    }
    for counter in &state.counters {
        let value = match dialect {
            Dialect::Step5 => format!("KZ {:03}", counter.value),
            Dialect::Step7 => format!("C#{}", counter.value),
        };
        let _ = writeln!(
            out,
            "  C {:<5} = {value}, bit {}",
            counter.number,
            u8::from(counter.bit)
        );
    }
    for (db, units) in numeric(&state.data_blocks, "DB ") {
        match dialect {
            Dialect::Step5 => word_data_block(&mut out, state, db, units),
            Dialect::Step7 => match state.declared_data_blocks.get(&format!("DB {db}")) {
                Some(values) => declared_block(&mut out, db, values),
                None => byte_data_block(&mut out, state, db, units),
            },
        }
    }
    if let Some(levels) = &state.levels {
        out.push_str(&istack_text(levels));
        out.push('\n');
    }
    out
}
/// The ISTACK, compactly: each level with its accumulators, status word and open DB, the
/// running one first. Return points are the BSTACK's; an interrupted level lists its own.
pub fn istack_text(levels: &[LevelView]) -> String {
    let mut out = String::from("ISTACK, the running level first:");
    for (n, level) in levels.iter().enumerate() {
        let role = if n == 0 { "running" } else { "interrupted" };
        let open = level
            .open_db
            .map_or("no DB open".to_string(), |db| format!("DB {db} open"));
        // A STEP 7 level (its status has BR) in STEP 7 notation.
        let hex = if level.status.br.is_some() {
            "DW#16#"
        } else {
            "KH "
        };
        let accus: Vec<String> = level.accu.iter().map(|a| format!("{a:08X}")).collect();
        let _ = write!(
            out,
            "\n  {} line {} ({role}), {open}\n    ACCU 1-{} {hex}{}\n    {}",
            level.block,
            level.line,
            accus.len(),
            accus.join(" "),
            status(&level.status)
        );
        if n > 0 {
            for point in &level.return_points {
                let _ = write!(out, "\n    return to {} line {}", point.block, point.line);
            }
        }
    }
    out
}
