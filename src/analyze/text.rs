//! The analysis as a table a person reads, ending with the bound.

use std::fmt::Write as _;

use super::Analysis;

fn ms(ns: Option<u64>) -> String {
    match ns {
        Some(ns) => format!("{:.3} ms", ns as f64 / 1_000_000.0),
        None => "unbounded".to_string(),
    }
}

fn us(ns: Option<u64>) -> String {
    match ns {
        Some(ns) => format!("{}.{:03} µs", ns / 1000, ns % 1000),
        None => "unbounded".to_string(),
    }
}

/// Microseconds below a millisecond, milliseconds above.
fn time(ns: u64) -> String {
    if ns < 1_000_000 {
        us(Some(ns))
    } else {
        ms(Some(ns))
    }
}

fn margin(margin: Option<i64>) -> String {
    match margin {
        Some(margin) if margin < 0 => format!("short by {}", time(margin.unsigned_abs())),
        Some(margin) => format!("margin {}", time(margin as u64)),
        None => "no margin known (a figure is unbounded)".to_string(),
    }
}

/// Lines as runs: `20–23, 27, 30–33`.
fn runs(lines: &[u32]) -> String {
    let mut runs: Vec<(u32, u32)> = Vec::new();
    for &line in lines {
        match runs.last_mut() {
            Some(run) if run.1 + 1 == line || run.1 == line => run.1 = line,
            _ => runs.push((line, line)),
        }
    }
    runs.iter()
        .map(|&(first, last)| {
            if first == last {
                first.to_string()
            } else {
                format!("{first}–{last}")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

pub fn render(analysis: &Analysis) -> String {
    let mut out = String::new();
    let mode = analysis
        .mode
        .map_or(String::new(), |mode| format!(", {mode} mode"));
    let _ = writeln!(
        out,
        "static analysis on the {}{mode}, {} points\n",
        analysis.cpu, analysis.interrupt_points
    );
    let _ = writeln!(
        out,
        "{:<8} {:>14} {:>14}  {:<16} {:<14} calls",
        "block", "wcet", "stretch", "stretch lines", "loops"
    );
    for block in &analysis.blocks {
        let lines = block.stretch_path.as_deref().map_or("-".to_string(), runs);
        let loops: Vec<String> = block
            .loops
            .iter()
            .map(|l| match l.bound {
                Some(bound) => format!("{} ×{bound}", l.line),
                None => format!("{} ×?", l.line),
            })
            .collect();
        let _ = writeln!(
            out,
            "{:<8} {:>14} {:>14}  {:<16} {:<14} {}",
            block.block,
            us(block.wcet_ns),
            us(block.stretch_ns),
            lines,
            if loops.is_empty() {
                "-".to_string()
            } else {
                loops.join(", ")
            },
            block.calls.join(", ")
        );
        if let Some(reason) = &block.unbounded {
            let _ = writeln!(out, "         unbounded: {reason}");
        }
    }
    if !analysis.obs.is_empty() {
        out.push('\n');
    }
    for ob in &analysis.obs {
        let _ = writeln!(
            out,
            "OB {:<3} priority {:>2}: run {}, response ≤ {} (the bound and one run each of {})",
            ob.ob,
            ob.priority,
            us(ob.wcet_ns),
            us(ob.response_bound_ns),
            ob.waits_for.join(", ")
        );
    }
    let nesting = &analysis.nesting;
    out.push('\n');
    match &nesting.recursion {
        Some(cycle) => {
            let _ = writeln!(
                out,
                "nesting: recursion {} (STOP STUEB unless it ends itself; limit {})",
                cycle.join(" → "),
                nesting.limit
            );
        }
        None => {
            let _ = writeln!(
                out,
                "nesting: {} of {} blocks deep{}: {}",
                nesting.max_depth.unwrap_or(0),
                nesting.limit,
                if nesting.exceeds {
                    ", EXCEEDS the limit: STOP STUEB"
                } else {
                    ""
                },
                nesting.path.join(" → ")
            );
        }
    }
    if let Some(weck) = &analysis.weck {
        let verdict = match weck.interval_ns {
            None => "no interval to compare with (a scenario's `[ob13] interval`)".to_string(),
            Some(interval) => format!(
                "interval {}: {}{}",
                ms(Some(interval)),
                margin(weck.margin_ns),
                if weck.risk == Some(true) {
                    " — RISK of STOP WECK (S5-95F manual, 7.4.4)"
                } else {
                    ""
                }
            ),
        };
        let _ = writeln!(
            out,
            "OB 13 wake-up: {} from request to end, {verdict}",
            ms(weck.ob13_ns)
        );
    }
    let watchdog = &analysis.watchdog;
    let _ = writeln!(
        out,
        "cycle: {} worst case, watchdog {}: {}{}",
        ms(watchdog.cycle_ns),
        ms(Some(watchdog.watchdog_ns)),
        margin(watchdog.margin_ns),
        if watchdog.risk == Some(true) {
            " — RISK of STOP ZYK"
        } else {
            ""
        }
    );
    let unused = &analysis.unused;
    if !unused.blocks.is_empty() {
        let _ = writeln!(out, "never called: {}", unused.blocks.join(", "));
    }
    for code in &unused.code {
        let _ = writeln!(
            out,
            "never reached: {} lines {}–{}",
            code.block, code.lines[0], code.lines[1]
        );
    }
    let _ = writeln!(
        out,
        "response bound: {}, {}",
        ms(analysis.response_bound_ns),
        analysis.response_bound_by
    );
    out
}
