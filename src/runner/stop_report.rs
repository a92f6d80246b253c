//! The STOP report: the cause as the PG names it, the source line, and the block stack.

use miette::Report;

use crate::diagnostics;
use crate::source::Span;
use crate::vm::Cpu;
use crate::vm::stop::{StackEntry, Stop, StopCause, StopDetail, StopError};

use super::Ran;

/// The shortest run of entries starting at `from` that repeats right after itself: its length
/// and how many times it stands there in a row.
fn repetition(stack: &[StackEntry], from: usize) -> Option<(usize, usize)> {
    let rest = &stack[from..];
    (1..=rest.len() / 2).find_map(|period| {
        let pattern = &rest[..period];
        let times = rest
            .chunks_exact(period)
            .take_while(|chunk| *chunk == pattern)
            .count();
        (times >= 2).then_some((period, times))
    })
}

fn stack_line(text: &mut String, entry: &StackEntry, role: &str, times: usize) {
    let count = if times > 1 {
        format!(" ×{times}")
    } else {
        String::new()
    };
    text.push_str(&format!(
        "\n  {:<6} {}line {:<5} {role}{count}",
        entry.block,
        crate::trace::segment_text(entry.segment),
        entry.line
    ));
}

/// The BSTACK, innermost first. Return points that repeat (a block calling itself, or blocks
/// calling each other) are shown once with their count.
fn stack_text(stop: &Stop) -> String {
    let Some((innermost, callers)) = stop.stack.split_first() else {
        return "BSTACK: empty, no block was running".to_string();
    };
    let mut text = String::from("BSTACK, innermost first:");
    stack_line(&mut text, innermost, "stopped here", 1);
    let mut at = 0;
    while at < callers.len() {
        match repetition(callers, at) {
            Some((1, times)) => {
                stack_line(&mut text, &callers[at], "return point", times);
                at += times;
            }
            Some((period, times)) => {
                for entry in &callers[at..at + period] {
                    stack_line(&mut text, entry, "return point", 1);
                }
                text.push_str(&format!("\n  (these {period} return points ×{times})"));
                at += period * times;
            }
            None => {
                stack_line(&mut text, &callers[at], "return point", 1);
                at += 1;
            }
        }
    }
    text
}

fn ms(ns: u64) -> String {
    format!("{:.3} ms", ns as f64 / 1e6)
}

/// What the watchdog saw: the cycle reached its time, or an operation carried it past.
fn watchdog_text(cycle_ns: u64, watchdog_ns: u64) -> String {
    if ms(cycle_ns) == ms(watchdog_ns) || cycle_ns < watchdog_ns {
        format!("the cycle reached the watchdog time of {}", ms(watchdog_ns))
    } else {
        format!(
            "the cycle ran {}, past the watchdog time of {}",
            ms(cycle_ns),
            ms(watchdog_ns)
        )
    }
}

/// The STOP as a miette report with the source line.
pub fn stop_report(ran: &Ran, stop: &Stop) -> Report {
    cpu_stop_report(&ran.cpu, stop)
}

/// The STOP of `cpu` (one still running on, as the playground's live mode keeps it).
pub fn cpu_stop_report(cpu: &Cpu, stop: &Stop) -> Report {
    let program = &cpu.program;
    // Between cycles in a program without OB 1 there is no block: the label goes to the start
    // of the first file.
    let (at, name) = match stop.block.map(|index| &program.blocks[usize::from(index)]) {
        Some(block) => {
            let at: Span = block
                .spans
                .get(stop.pc as usize)
                .copied()
                .unwrap_or(block.header);
            (at, block.id.to_string())
        }
        None => (
            Span::default(),
            "the operating system (between cycles)".to_string(),
        ),
    };
    let levels = crate::state::levels(cpu, stop);
    let stack = if levels.is_empty() {
        stack_text(stop)
    } else {
        format!(
            "{}\n{}",
            stack_text(stop),
            crate::state::istack_text(&levels)
        )
    };
    let detail = match &stop.detail {
        StopDetail::Text(text) => text.clone(),
        _ => String::new(),
    };
    let error = match (stop.cause, &stop.detail) {
        (
            StopCause::Zyk,
            StopDetail::Cycle {
                cycle_ns,
                watchdog_ns,
            },
        ) => StopError::CycleTime {
            how: watchdog_text(*cycle_ns, *watchdog_ns),
            block: name,
            at,
            stack,
        },
        (StopCause::Zyk, _) => StopError::CycleTime {
            how: "the cycle reached the watchdog time".into(),
            block: name,
            at,
            stack,
        },
        (StopCause::Lstack, &StopDetail::LocalData { block, end, call }) => {
            let entered = program.blocks[usize::from(block)].id.to_string();
            StopError::LocalOverflow {
                needed: end,
                size: cpu.local_bytes() as u32,
                at,
                place: if call {
                    format!("{entered} is called here")
                } else {
                    format!("{entered} starts here")
                },
                entered,
                stack,
            }
        }
        // The VM gives an L stack overflow its `LocalData`; without them it is told as the
        // block stack's.
        (StopCause::Stueb | StopCause::Lstack, _) => StopError::Nesting {
            limit: program.profile.nesting_limit,
            block: name,
            at,
            stack,
        },
        (StopCause::LzfBlock, _) => StopError::BlockNotLoaded {
            target: detail,
            at,
            stack,
        },
        (StopCause::LzfData, _) => StopError::DataAccess {
            problem: detail,
            fix: if program.s7.step7 {
                "open a data block long enough with `OPN DB n` (or call the FB with its instance DB) before using DBX/DBB/DBW/DBD"
            } else {
                "open a data block long enough with `C DB n` before using DW/DL/DR/DD/D"
            },
            at,
            stack,
        },
        (StopCause::Bcf, _) => StopError::Operation {
            problem: detail,
            at,
            stack,
        },
        (StopCause::Stp, _) => StopError::StopOperation { at, stack },
        (StopCause::Assert, _) => StopError::AssertionFailed {
            problem: detail,
            at,
            stack,
        },
        (StopCause::Weck, StopDetail::Ob(ob)) => StopError::WakeUp { ob: *ob, at, stack },
        (
            StopCause::Weck,
            StopDetail::Ob13Interval {
                interval_ns,
                max_delay_ns,
            },
        ) => StopError::IntervalNotAboveDelay {
            interval_ms: format!("{:.3}", *interval_ns as f64 / 1e6),
            max_delay_ms: format!("{:.3}", *max_delay_ns as f64 / 1e6),
            at,
        },
        (StopCause::Weck, _) => StopError::WakeUp { ob: 13, at, stack },
        (StopCause::Ob85, StopDetail::Module { module, ob }) => StopError::MissingOb85 {
            module: *module,
            ob: *ob,
            at,
            stack,
        },
        (StopCause::Ob85, _) => StopError::MissingOb85 {
            module: 0,
            ob: 40,
            at,
            stack,
        },
        (StopCause::Ob80, StopDetail::Ob(ob)) => StopError::TimeError { ob: *ob, at, stack },
        (StopCause::Ob80, _) => StopError::TimeError { ob: 35, at, stack },
        (StopCause::Ob86, &StopDetail::Station { station, failed }) => StopError::StationEvent {
            station,
            event: station_event(failed),
            at,
            stack,
        },
        (StopCause::Ob86, _) => StopError::StationEvent {
            station: 0,
            event: station_event(true),
            at,
            stack,
        },
        // A halt is reported as one, not as a STOP; should it reach here, it says what it was.
        (StopCause::Halt, _) => StopError::Operation {
            problem: "the run was halted here".into(),
            at,
            stack,
        },
    };
    diagnostics::with_source(&cpu.sources, error.span(), error)
}

/// What happened to a DP station, for a message.
fn station_event(failed: bool) -> &'static str {
    if failed { "failed" } else { "returned" }
}
