//! The state as text, in STEP 5 notation: `FY 10 = KH 7B = 0111 1011`,
//! `DB 10 DW 3 = KF +123 = KH 007B`, `T 1 = KT 250.1`.

use std::collections::BTreeMap;
use std::fmt::Write;

use super::{LevelView, State, StatusBits};

fn bits(byte: u8) -> String {
    format!("{:04b} {:04b}", byte >> 4, byte & 0xF)
}

fn word(value: u16) -> String {
    format!("KF {:+} = KH {value:04X}", value as i16)
}

fn double(value: u32) -> String {
    format!("DH {value:08X} = {:+}", value as i32)
}

/// A map keyed by numbers written as text (`"10"`, `"DB 10"`), keyed by the numbers.
pub(super) fn numeric<'a, V>(map: &'a BTreeMap<String, V>, prefix: &str) -> BTreeMap<u16, &'a V> {
    map.iter()
        .filter_map(|(key, value)| Some((key.strip_prefix(prefix)?.parse().ok()?, value)))
        .collect()
}

/// The non-zero bytes of an image area in address order, each in the width the program used
/// it in: `FW 0 = KF +750 = KH 02EE`, `FY 10 = KH 7B = 0111 1011`.
fn image_area(out: &mut String, state: &State, area: &'static str, names: [&str; 3]) {
    let bytes = numeric(&state.images[area], "");
    let byte = |at: u16| bytes.get(&at).map_or(0, |value| **value);
    for (at, width) in state.widths.image_ranges(area, bytes.keys().copied()) {
        let value =
            (at..at.saturating_add(width)).fold(0u32, |value, at| value << 8 | u32::from(byte(at)));
        let line = match width {
            1 => format!(
                "{} {at:<4} = KH {value:02X} = {}",
                names[0],
                bits(value as u8)
            ),
            2 => format!("{} {at:<4} = {}", names[1], word(value as u16)),
            _ => format!("{} {at:<4} = {}", names[2], double(value)),
        };
        let _ = writeln!(out, "  {line}");
    }
}

/// The non-zero words of data block `db` in address order; double words where the program
/// transferred one: `DB 10 DW 3 = KF +123 = KH 007B`, `DB 10 DD 4 = DH 00010002 = +65538`.
fn data_block(out: &mut String, state: &State, db: u16, words: &BTreeMap<String, u16>) {
    let words = numeric(words, "");
    let word_at = |at: u16| words.get(&at).map_or(0, |value| **value);
    for (at, width) in state.widths.data_ranges(words.keys().copied()) {
        let line = if width == 2 {
            let value = u32::from(word_at(at)) << 16 | u32::from(word_at(at.saturating_add(1)));
            format!("DD {at:<4} = {}", double(value))
        } else {
            format!("DW {at:<4} = {}", word(word_at(at)))
        };
        let _ = writeln!(out, "  DB {db} {line}");
    }
}

pub fn accu(value: u32) -> String {
    format!(
        "KH {:04X} {:04X}  (low word KF {:+})",
        value >> 16,
        value & 0xFFFF,
        value as u16 as i16
    )
}

/// The status bits; a STEP 7 program's (with BR) as its status word.
pub fn status(status: &StatusBits) -> String {
    if status.br.is_some() {
        return format!("STW {}", super::s7::status_word(status.word()));
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

pub(super) const TIME_BASES: [&str; 4] = ["10 ms", "100 ms", "1 s", "10 s"];

/// `--state`: what a PG would show after the run.
pub fn render(state: &State) -> String {
    render_titled(state, "\nstate at the end")
}

/// The state under a title of its own (the debugger's `state`: "state at 12.5 ms").
pub fn render_titled(state: &State, title: &str) -> String {
    if state.step7 {
        return super::s7_text::render_titled(state, title);
    }
    let mut out = format!("{title}: mode {}\n", state.mode);
    for (n, value) in state.accu.iter().enumerate() {
        let _ = writeln!(out, "  ACCU {}   {}", n + 1, accu(*value));
    }
    let _ = writeln!(out, "  status   {}", status(&state.status));
    let _ = writeln!(out, "  open DB  {}", open_db(state.open_db));
    for (area, names) in [
        ("I", ["IB", "IW", "ID"]),
        ("Q", ["QB", "QW", "QD"]),
        ("F", ["FY", "FW", "FD"]),
    ] {
        image_area(&mut out, state, area, names);
    }
    for timer in &state.timers {
        let _ = writeln!(
            out,
            "  T {:<5} = KT {:03}.{}  ({} × {}), {}, bit {}",
            timer.number,
            timer.value,
            timer.base,
            timer.value,
            TIME_BASES[usize::from(timer.base)],
            if timer.running { "running" } else { "stopped" },
            u8::from(timer.bit)
        );
    }
    for counter in &state.counters {
        let _ = writeln!(
            out,
            "  C {:<5} = KZ {:03}, bit {}",
            counter.number,
            counter.value,
            u8::from(counter.bit)
        );
    }
    for (db, words) in numeric(&state.data_blocks, "DB ") {
        data_block(&mut out, state, db, words);
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
