//! The state as text, in STEP 5 notation: `FY 10 = KH 7B = 0111 1011`,
//! `DB 10 DW 3 = KF +123 = KH 007B`, `T 1 = KT 250.1`.

use std::fmt::Write;

use super::{LevelView, State, StatusBits};

fn bits(byte: u8) -> String {
    format!("{:04b} {:04b}", byte >> 4, byte & 0xF)
}

fn word(value: u16) -> String {
    format!("KF {:+} = KH {value:04X}", value as i16)
}

pub fn accu(value: u32) -> String {
    format!(
        "KH {:04X} {:04X}  (low word KF {:+})",
        value >> 16,
        value & 0xFFFF,
        value as u16 as i16
    )
}

pub fn status(status: &StatusBits) -> String {
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

fn open_db(open: Option<u8>) -> String {
    open.map_or("none".to_string(), |db| format!("DB {db}"))
}

const TIME_BASES: [&str; 4] = ["10 ms", "100 ms", "1 s", "10 s"];

/// `--state`: what a PG would show after the run.
pub fn render(state: &State) -> String {
    render_titled(state, "\nstate at the end")
}

/// The state under a title of its own (the debugger's `state`: "state at 12.5 ms").
pub fn render_titled(state: &State, title: &str) -> String {
    let mut out = format!("{title}: mode {}\n", state.mode);
    for (n, value) in state.accu.iter().enumerate() {
        let _ = writeln!(out, "  ACCU {}   {}", n + 1, accu(*value));
    }
    let _ = writeln!(out, "  status   {}", status(&state.status));
    let _ = writeln!(out, "  open DB  {}", open_db(state.open_db));
    for (area, prefix) in [("I", "IB"), ("Q", "QB"), ("F", "FY")] {
        for (byte, value) in &state.images[area] {
            let _ = writeln!(
                out,
                "  {prefix} {byte:<4} = KH {value:02X} = {}",
                bits(*value)
            );
        }
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
    for (db, words) in &state.data_blocks {
        for (n, value) in words {
            let _ = writeln!(out, "  {db} DW {n:<4} = {}", word(*value));
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
        let accus: Vec<String> = level.accu.iter().map(|a| format!("{a:08X}")).collect();
        let _ = write!(
            out,
            "\n  {} line {} ({role}), {open}\n    ACCU 1-{} KH {}\n    {}",
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
