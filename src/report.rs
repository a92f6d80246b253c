//! Human-readable reports: the CPU profile list.

use std::fmt::Write as _;

use crate::profile::{self, InterruptPoints};

fn micros(ns: u32) -> String {
    format!("{:.2} µs", f64::from(ns) / 1000.0)
}

/// `awl cpus`: every profile with its rules, priorities, limits, timings and their sources.
pub fn cpus() -> String {
    let mut out = String::new();
    for p in profile::PROFILES {
        let _ = writeln!(out, "{}  —  {}", p.name, p.title);
        let _ = writeln!(out, "  from: {}", p.seed);
        let _ = writeln!(
            out,
            "  interrupt points: {} by default{}",
            p.default_points.name(),
            if p.default_points == InterruptPoints::Block { " (block calls, block ends, cycle boundary)" } else { " (after every operation)" }
        );
        let obs: Vec<String> = p.interrupt_obs.iter().map(|ob| format!("OB {} (priority {}, {})", ob.ob, ob.priority, ob.summary)).collect();
        let _ = writeln!(out, "  interrupt OBs, highest priority first: {}; cyclic OB 1 lowest", obs.join(", "));
        let startup: Vec<String> = p.startup_obs.iter().map(|ob| format!("OB {ob}")).collect();
        let _ = writeln!(out, "  startup OB: {}", startup.join(" / "));
        let s = &p.sizes;
        let _ = writeln!(
            out,
            "  limits: I/Q bytes 0…{}, F bytes 0…{}, peripheral bytes 0…{}, T 0…{}, C 0…{}, DW 0…{}, nesting depth {}, brackets {}, cycle watchdog {} ms",
            s.image_bytes - 1,
            s.flag_bytes - 1,
            s.peripheral_bytes - 1,
            s.timers - 1,
            s.counters - 1,
            s.data_words - 1,
            p.nesting_limit,
            p.bracket_depth,
            p.watchdog_ns / 1_000_000
        );
        let t = &p.timings;
        let _ = writeln!(
            out,
            "  times: bit I/Q/F {}, bit D {}, L FY {}, L FW {}, L FD {}, +F/-F {}, X F {}, :F {}, block call {}, block end {}, cycle overhead {}",
            micros(t.bit_image),
            micros(t.bit_data),
            micros(t.load_byte),
            micros(t.load_word),
            micros(t.load_double),
            micros(t.add_sub),
            micros(t.multiply),
            micros(t.divide),
            micros(t.block_call),
            micros(t.block_end),
            micros(t.cycle_overhead)
        );
        let _ = writeln!(out, "  times from: {}", t.source);
        let _ = writeln!(out, "  rules:");
        for rule in p.rules {
            let _ = writeln!(out, "    - {rule}");
        }
        out.push('\n');
    }
    out
}
