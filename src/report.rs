//! Human-readable reports: the CPU profile list and the run summary.

use std::fmt::Write as _;

use crate::diagnostics::plural;
use crate::profile::{self, Family, InterruptPoints};
use crate::vm::bound::BoundCause;
use crate::vm::interrupts::Wait;
use crate::vm::{Cpu, IDLE, StretchKind};

fn micros(ns: u32) -> String {
    format!("{:.2} µs", f64::from(ns) / 1000.0)
}

/// The operation groups of a profile beyond the common set, then its aliases, integral FBs and
/// system OBs, for those that have any.
fn write_builtins(out: &mut String, p: &profile::Profile) {
    let groups: Vec<&str> = p.features.iter().map(|feature| feature.name()).collect();
    let groups = if groups.is_empty() {
        "none".to_string()
    } else {
        groups.join(", ")
    };
    let _ = writeln!(out, "  operation groups beyond the common set: {groups}");
    let aliases: Vec<&str> = profile::ALIASES
        .iter()
        .filter(|(_, target)| *target == p.name)
        .map(|(alias, _)| *alias)
        .collect();
    if !aliases.is_empty() {
        let _ = writeln!(out, "  also called: {}", aliases.join(", "));
    }
    if !p.integral_fbs.is_empty() {
        let fbs: Vec<String> = p
            .integral_fbs
            .iter()
            .map(|fb| format!("FB {fb} {}", crate::compiler::builtin::name(*fb)))
            .collect();
        let _ = writeln!(out, "  integral FBs: {}", fbs.join(", "));
    }
    if !p.system_obs.is_empty() {
        let obs: Vec<String> = p
            .system_obs
            .iter()
            .map(|ob| format!("OB {} ({})", ob.ob, ob.summary))
            .collect();
        let _ = writeln!(out, "  system OBs: {}", obs.join(", "));
    }
}

/// `awl cpus`: every profile with its rules, priorities, limits, timings and their sources.
pub fn cpus() -> String {
    let mut out = format!("the cycle, on every CPU: {}\n\n", profile::CYCLE_MODEL);
    for p in profile::PROFILES {
        let _ = writeln!(out, "{}  —  {}", p.name, p.title);
        let _ = writeln!(out, "  from: {}", p.manual);
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
        write_builtins(&mut out, p);
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
        let retentive = p.retentive();
        let flag = if p.runs_step7() { "M" } else { "F" };
        let _ = writeln!(
            out,
            "  retentive by default: {} (from: {}); the scenario's [retentive] sets others",
            retentive.ranges.describe(flag),
            retentive.source
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
        let _ = writeln!(out, "  times from: {}", t.source());
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

/// `PB 3 line 12`, `OB 1`, or the operating system's work a stretch stands for.
fn stretch_text(cpu: &Cpu, kind: StretchKind) -> String {
    match kind {
        StretchKind::Block { block, .. } if block == IDLE => "no block".to_string(),
        StretchKind::Block { block, .. } => cpu.block_id(block).to_string(),
        StretchKind::ProcessImageRead => "the process image read (PII) at the cycle start".into(),
        StretchKind::ProcessImageWrite => "the process image write (PIQ) after OB 1".into(),
        StretchKind::OsTime => "the operating-system time at the cycle end".into(),
        StretchKind::MinCycleWait => "the wait for the minimum cycle time".into(),
        StretchKind::InterruptEnd { block } => {
            format!("the end of {} with its data cycle", cpu.block_id(block))
        }
    }
}

fn bound_lines(out: &mut String, cpu: &Cpu) {
    match cpu.engine.config.points {
        InterruptPoints::Block => {
            let block = cpu.longest_block;
            if block.ns > 0 {
                let why = match cpu.profile.family {
                    Family::S5 => "the worst case with interrupt points at block boundaries",
                    _ => "the worst case in normal mode: SINUMERIK 840C PLC manual, 5.3.2",
                };
                let _ = writeln!(
                    out,
                    "longest block: {}, {:.3} ms ({why})",
                    stretch_text(cpu, block.kind),
                    block.ns as f64 / 1e6
                );
            }
        }
        InterruptPoints::Operation => {
            // The longest operation is the program's, not the run's: say it only when the
            // program ran at all.
            if let Some((block, pc, ns)) = cpu.longest_operation().filter(|_| cpu.instructions > 0)
            {
                let _ = writeln!(
                    out,
                    "longest operation in the program: {} line {}, {:.3} us",
                    cpu.block_id(block),
                    cpu.line_of(block, pc as u32),
                    ns as f64 / 1e3
                );
            }
        }
    }
    let bound = cpu.response_bound();
    if bound.ns == 0 {
        return;
    }
    let what = match bound.cause {
        BoundCause::Stretch(kind) => stretch_text(cpu, kind),
        BoundCause::Operation { block, pc } => format!(
            "an operation of {} (line {})",
            cpu.block_id(block),
            cpu.line_of(block, pc as u32)
        ),
    };
    let _ = writeln!(
        out,
        "response bound: {:.3} ms, the longest stretch without an interrupt point: {what}",
        bound.ns as f64 / 1e6
    );
}

/// The S5-95F's maximum response of time-controlled processing (S5-95F manual, 7.4.5).
fn time_controlled_response(out: &mut String, cpu: &Cpu) {
    let (Some(timing), Family::S5_95f) = (cpu.engine.config.ob13, cpu.profile.family) else {
        return;
    };
    let stats = cpu.engine.stats(13);
    if stats.run_max == 0 {
        // No OB 13 has ended yet: its execution time is not known.
        return;
    }
    let delay = timing.max_delay_ns.unwrap_or(timing.delay_ns);
    let data_cycles = 2 * u64::from(cpu.profile.timings.data_cycle);
    let input = u64::from(cpu.profile.timings.input_delay);
    let total = timing.interval_ns + delay + stats.run_max + data_cycles + input;
    let ms = |ns: u64| format!("{:.3}", ns as f64 / 1e6);
    let _ = writeln!(
        out,
        "time-controlled response ≤ {} ms: OB 13 interval {} + delay t {} + OB 13 {} (longest run) + data cycles {} + input module {} (estimate) (S5-95F manual, 7.4.5)",
        ms(total),
        ms(timing.interval_ns),
        ms(delay),
        ms(stats.run_max),
        ms(data_cycles),
        ms(input)
    );
}

/// The summary of `awl run`; it ends with the `cpu:` and `instructions:` lines scripts read.
/// `n thing` or `n things`.
/// One line per trace or timeline file: "trace: 1204 events written to run.jsonl (88.1 KiB)".
pub fn written(ran: &crate::runner::Ran) -> String {
    ran.written
        .iter()
        .map(|file| {
            format!(
                "{}: {} written to {} ({})\n",
                file.what,
                plural(file.events, "event"),
                file.path,
                size(file.bytes)
            )
        })
        .collect()
}

/// A file's size: bytes, KiB or MiB.
fn size(bytes: u64) -> String {
    const KIB: u64 = 1024;
    match bytes {
        0..KIB => plural(bytes, "byte"),
        KIB..1_048_576 => format!("{:.1} KiB", bytes as f64 / KIB as f64),
        _ => format!("{:.1} MiB", bytes as f64 / (KIB * KIB) as f64),
    }
}

/// One line per `[[check]]`: when it was verified and how many of its operands held, then
/// each one that did not.
fn checks(out: &mut String, ran: &crate::runner::Ran) {
    let symbols = &ran.cpu.program.symbols;
    for check in &ran.checks {
        let Some((at_ns, cycle)) = check.verified else {
            let _ = writeln!(
                out,
                "check at {}: not reached (the run ended at {})",
                check.at,
                crate::trace::format_ms(ran.outcome.clock_ns)
            );
            continue;
        };
        let _ = writeln!(
            out,
            "check at {}: verified at {} (cycle {cycle}): {} of {} met",
            check.at,
            crate::trace::format_ms(at_ns),
            check.operands - check.mismatches.len(),
            check.operands
        );
        for mismatch in &check.mismatches {
            let _ = writeln!(
                out,
                "  {}: expected {}, got {}",
                symbols.describe(&mismatch.name),
                mismatch.expected,
                mismatch.actual
            );
        }
    }
}

/// The summary `awl run` prints, ending with the instruction count, wall time and rate.
pub fn summary(ran: &crate::runner::Ran) -> String {
    let mut out = summary_of_the_run(ran);
    let outcome = &ran.outcome;
    let wall = outcome.wall.as_secs_f64();
    let rate = if wall > 0.0 {
        outcome.instructions as f64 / wall / 1e6
    } else {
        0.0
    };
    if let Some((start, path)) = &ran.retain_start {
        let _ = writeln!(out, "{}", start.describe(path));
    }
    let _ = writeln!(
        out,
        "instructions: {}   wall: {wall:.4} s   rate: {rate:.1} M instr/s",
        outcome.instructions
    );
    out
}

/// The summary with the instruction count alone on its last line: no wall time or rate,
/// which differ from machine to machine and run to run (the playground shows this one).
pub fn summary_on_simulated_time(ran: &crate::runner::Ran) -> String {
    let mut out = summary_of_the_run(ran);
    let _ = writeln!(out, "instructions: {}", ran.outcome.instructions);
    out
}

/// Every line of the summary but the last.
fn summary_of_the_run(ran: &crate::runner::Ran) -> String {
    let mut out = String::new();
    let outcome = &ran.outcome;
    let cpu = &ran.cpu;
    let expectations = ran.expectations;
    if expectations > 0 {
        for mismatch in &ran.mismatches {
            let _ = writeln!(
                out,
                "expect {}: expected {}, got {}",
                cpu.program.symbols.describe(&mismatch.name),
                mismatch.expected,
                mismatch.actual
            );
        }
        let _ = writeln!(
            out,
            "expectations: {} of {} met",
            expectations - ran.mismatches.len(),
            expectations
        );
    }
    checks(&mut out, ran);
    bound_lines(&mut out, cpu);
    time_controlled_response(&mut out, cpu);
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
        let waits: Vec<String> = Wait::ALL
            .iter()
            .zip(stats.waited)
            .filter(|(_, count)| *count > 0)
            .map(|(wait, count)| format!("{count} because {}", wait.explanation()))
            .collect();
        if !waits.is_empty() {
            let _ = writeln!(
                out,
                "  OB {ob}: waited beyond the response bound: {}",
                waits.join(", ")
            );
        }
    }
    if outcome.halted {
        let _ = writeln!(
            out,
            "halted: interrupted (Ctrl-C or SIGTERM) at the cycle boundary after cycle {}",
            outcome.cycles
        );
    }
    let times = cpu.cycle_times;
    if let Some(mean) = times.mean_ns() {
        let ms = |ns: u64| ns as f64 / 1e6;
        let _ = writeln!(
            out,
            "cycle time min/mean/max {:.3}/{:.3}/{:.3} ms over {}",
            ms(times.min_ns),
            ms(mean),
            ms(times.max_ns),
            plural(times.count, "completed cycle")
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
    out
}
