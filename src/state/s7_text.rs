//! The state of a STEP 7 program as text, in STEP 7 notation: `MW 10 = 22 = W#16#0016`,
//! `MD 20 = DW#16#3FC00000 = 1.5`, `DB5.DBW 2 = 12 = W#16#000C`, `T 1 = S5T#2S500MS`,
//! `C 3 = C#5`, and the registers: the status word with BR, AR1, AR2, the DB and DI registers.

use std::collections::BTreeMap;
use std::fmt::Write;

use super::State;
use super::s7::{self, Registers};
use super::s7_declared::ValueView;
use super::text::{TIME_BASES, istack_text, numeric};

/// One address in the width the program used: `MB 1 = B#16#16 = 2#0001_0110`,
/// `MW 10 = 22 = W#16#0016`, `MD 20 = DW#16#3FC00000 = 1.5`.
fn line(names: [&str; 3], at: u16, width: u16, value: u32) -> String {
    match width {
        1 => format!(
            "{} {at:<4} = {} = {}",
            names[0],
            s7::byte(value as u8),
            s7::bits(value as u8)
        ),
        2 => format!("{} {at:<4} = {}", names[1], s7::word(value as u16)),
        _ => format!("{} {at:<4} = {}", names[2], s7::double(value)),
    }
}

/// `width` bytes from `at`, big-endian, from a map of the non-zero ones.
fn value_at<V: Copy + Into<u32>>(bytes: &BTreeMap<u16, &V>, at: u16, width: u16) -> u32 {
    (at..at.saturating_add(width)).fold(0u32, |value, at| {
        value << 8 | bytes.get(&at).map_or(0, |byte| (**byte).into())
    })
}

fn image_area(out: &mut String, state: &State, area: &'static str, names: [&str; 3]) {
    let bytes = numeric(&state.images[area], "");
    for (at, width) in state.widths.image_ranges(area, bytes.keys().copied()) {
        let _ = writeln!(
            out,
            "  {}",
            line(names, at, width, value_at(&bytes, at, width))
        );
    }
}

fn data_block(out: &mut String, state: &State, db: u16, bytes: &BTreeMap<String, u16>) {
    let bytes = numeric(bytes, "");
    let names = ["DBB", "DBW", "DBD"];
    for (at, width) in state.widths.s7_data_ranges(bytes.keys().copied()) {
        let text = line(names, at, width, value_at(&bytes, at, width));
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
            s7::pointer(value)
        );
    }
    let _ = writeln!(
        out,
        "  DB       {}   DI  {}",
        register(registers.db),
        register(registers.di)
    );
}

/// The accumulator as a double word, and its low word as an INT unless it holds a REAL.
fn accu(value: u32) -> String {
    let double = s7::double(value);
    match s7::as_real(value) {
        Some(_) => double,
        None => format!("{double}  (low word {})", value as u16 as i16),
    }
}

/// `--state` of a STEP 7 program.
pub fn render_titled(state: &State, title: &str) -> String {
    let mut out = format!("{title}: mode {}\n", state.mode);
    for (n, value) in state.accu.iter().enumerate() {
        let _ = writeln!(out, "  ACCU {}   {}", n + 1, accu(*value));
    }
    let _ = writeln!(out, "  STW      {}", s7::status_word(state.status.word()));
    if let Some(registers_now) = &state.registers {
        registers(&mut out, registers_now);
    }
    for (area, names) in [
        ("I", ["IB", "IW", "ID"]),
        ("Q", ["QB", "QW", "QD"]),
        ("M", ["MB", "MW", "MD"]),
    ] {
        image_area(&mut out, state, area, names);
    }
    for timer in &state.timers {
        let _ = writeln!(
            out,
            "  T {:<5} = {}  ({} × {}), {}, bit {}",
            timer.number,
            s7::s5time(timer.value, timer.base),
            timer.value,
            TIME_BASES[usize::from(timer.base)],
            if timer.running { "running" } else { "stopped" },
            u8::from(timer.bit)
        );
    }
    for counter in &state.counters {
        let _ = writeln!(
            out,
            "  C {:<5} = C#{}, bit {}",
            counter.number,
            counter.value,
            u8::from(counter.bit)
        );
    }
    for (db, bytes) in numeric(&state.data_blocks, "DB ") {
        match state.declared_data_blocks.get(&format!("DB {db}")) {
            Some(values) => declared_block(&mut out, db, values),
            None => data_block(&mut out, state, db, bytes),
        }
    }
    if let Some(levels) = &state.levels {
        out.push_str(&istack_text(levels));
        out.push('\n');
    }
    out
}
