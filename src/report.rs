//! Human-readable reports: the CPU profile list and the run summary.

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
            if p.default_points == InterruptPoints::Block {
                " (block calls, block ends, cycle boundary)"
            } else {
                " (after every operation)"
            }
        );
        let obs: Vec<String> = p
            .interrupt_obs
            .iter()
            .map(|ob| format!("OB {} (priority {}, {})", ob.ob, ob.priority, ob.summary))
            .collect();
        let _ = writeln!(
            out,
            "  interrupt OBs, highest priority first: {}; cyclic OB 1 lowest",
            obs.join(", ")
        );
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

/// `12.0` for 12 000 ns: microseconds with one decimal.
fn us(ns: u64) -> String {
    format!("{:.1}", ns as f64 / 1000.0)
}

/// The program's longest single operation: with operation points, the bound on the response.
fn longest_operation(ran: &crate::runner::Ran) -> Option<(String, u32, u64)> {
    let program = &ran.cpu.program;
    let (block, pc, ns) = program
        .blocks
        .iter()
        .enumerate()
        .flat_map(|(index, block)| (0..block.code.len()).map(move |pc| (index, pc, block.cost(pc))))
        .max_by_key(|(_, _, ns)| *ns)?;
    let block = &program.blocks[block];
    Some((
        block.id.to_string(),
        ran.frontend.sources.line_of(block.spans[pc]),
        ns,
    ))
}

/// The summary of `awl run`; it ends with the `cpu:` and `instructions:` lines of SPEC §2.
pub fn summary(ran: &crate::runner::Ran) -> String {
    let mut out = String::new();
    let outcome = &ran.outcome;
    let cpu = &ran.cpu;
    let expectations = ran.expectations;
    if expectations > 0 {
        for mismatch in &ran.mismatches {
            let _ = writeln!(
                out,
                "expect {}: expected {}, got {}",
                mismatch.name, mismatch.expected, mismatch.actual
            );
        }
        let _ = writeln!(
            out,
            "expectations: {} of {} met",
            expectations - ran.mismatches.len(),
            expectations
        );
    }
    match ran.points {
        InterruptPoints::Block => {
            let stretch = cpu.longest_stretch;
            if stretch.ns > 0 {
                let _ = writeln!(
                    out,
                    "longest block: {}, {:.3} ms (worst-case response in normal mode)",
                    cpu.block_id(stretch.block),
                    stretch.ns as f64 / 1e6
                );
            }
        }
        InterruptPoints::Operation => {
            if let Some((block, line, ns)) = longest_operation(ran) {
                let _ = writeln!(
                    out,
                    "longest operation: {block} line {line}, {:.3} us (worst-case response with operation points)",
                    ns as f64 / 1e3
                );
            }
        }
    }
    for (ob, stats) in cpu.engine.requested_obs() {
        let latency = match stats.latency_sum.checked_div(stats.serviced) {
            Some(mean) => format!(
                "{}/{}/{} us",
                us(stats.latency_min),
                us(mean),
                us(stats.latency_max)
            ),
            None => "-/-/- us".to_string(),
        };
        let _ = writeln!(
            out,
            "OB {ob}: requested {}, serviced {}, lost {}, ignored {}, latency min/mean/max {latency}",
            stats.requested, stats.serviced, stats.lost, stats.ignored
        );
    }
    let simulated = outcome.clock_ns as f64 / 1e6;
    let _ = writeln!(
        out,
        "cpu: {}   mode at end: {}   simulated: {simulated:.3} ms   cycles: {}",
        cpu.profile.name,
        outcome.mode.name(),
        outcome.cycles
    );
    let wall = outcome.wall.as_secs_f64();
    let rate = if wall > 0.0 {
        outcome.instructions as f64 / wall / 1e6
    } else {
        0.0
    };
    let _ = writeln!(
        out,
        "instructions: {}   wall: {wall:.4} s   rate: {rate:.1} M instr/s",
        outcome.instructions
    );
    out
}
