//! Program status as text: the block's source lines, and beside each line that ran its RLO,
//! STA, ACCU 1, ACCU 2 and operand; lines that did not run are marked.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::compiler::CompiledBlock;
use crate::source::{SourceFile, SourceSet};

use super::{OpStatus, Recording};

/// The accumulator columns: `KH 0001 0000`, and STEP 7's `DW#16#00010000`.
const ACCU_WIDTH: usize = 12;
const ACCU_WIDTH_S7: usize = 14;

/// An accumulator as the PG shows a 16-bit one, with the high word only when it is used:
/// `KH 0005`, `KH 0001 0000`; STEP 7's `W#16#0005`, `DW#16#00010000`.
pub fn accu(value: u32, step7: bool) -> String {
    match (step7, value >> 16 == 0) {
        (false, true) => format!("KH {value:04X}"),
        (false, false) => format!("KH {:04X} {:04X}", value >> 16, value & 0xFFFF),
        (true, true) => format!("W#16#{value:04X}"),
        (true, false) => format!("DW#16#{value:08X}"),
    }
}

fn columns(status: &OpStatus, step7: bool) -> String {
    let wide = if step7 { ACCU_WIDTH_S7 } else { ACCU_WIDTH };
    let mut out = format!(
        "{:>3} {:>3}  {:<wide$} {:<wide$} {:<14}",
        u8::from(status.rlo),
        u8::from(status.sta),
        accu(status.accu1, step7),
        accu(status.accu2, step7),
        status.operand.as_deref().unwrap_or("")
    );
    if status.runs > 1 {
        let _ = write!(out, " ×{}", status.runs);
    }
    out.trim_end().to_string()
}

/// Each line of `block` that holds an op, with what its last op left behind (`None`: it did
/// not run).
fn by_line<'a>(
    block: &CompiledBlock,
    file: &SourceFile,
    recording: &'a Recording,
) -> BTreeMap<u32, Option<&'a OpStatus>> {
    block
        .spans
        .iter()
        .zip(&recording.ops)
        .map(|(span, status)| (file.line_of(span.start), status.as_ref()))
        .collect()
}

/// The statement on `line`, without its comment.
fn statement_on(file: &SourceFile, line: u32) -> String {
    let text = file.line(line).replace('\t', "    ");
    text.split(';').next().unwrap_or("").trim_end().to_string()
}

/// The block's statements in line order: each line, its statement (without indentation and
/// comment) and what it left behind (`None`: it did not run). The online page shows these.
pub fn statements<'a>(
    block: &CompiledBlock,
    sources: &SourceSet,
    recording: &'a Recording,
) -> Vec<(u32, String, Option<&'a OpStatus>)> {
    let file = sources.get(block.header.file);
    by_line(block, file, recording)
        .into_iter()
        .map(|(line, status)| (line, statement_on(file, line).trim().to_string(), status))
        .collect()
}

/// The recording of `block` beside its source.
pub fn render(block: &CompiledBlock, sources: &SourceSet, recording: &Recording) -> String {
    let file = sources.get(block.header.file);
    let mut out = match &recording.invocation {
        Some(invocation) => format!(
            "program status of {} in cycle {}, from {}, level {}{}\n",
            block.id,
            invocation.cycle,
            crate::trace::format_ms(invocation.t_ns),
            invocation.level,
            if recording.complete {
                ""
            } else {
                " (the run ended before its block end)"
            }
        ),
        None => format!("program status of {}: it did not run\n", block.id),
    };
    let by_line = by_line(block, file, recording);
    let first = file.line_of(block.header.start);
    let last = by_line.keys().next_back().copied().unwrap_or(first);
    // Beside a statement its comment would push the columns away; comment lines stay whole.
    let statement = |line: u32| match by_line.contains_key(&line) {
        true => statement_on(file, line),
        false => file.line(line).replace('\t', "    ").trim_end().to_string(),
    };
    let width = by_line
        .keys()
        .map(|line| statement(*line).chars().count())
        .max()
        .unwrap_or(0)
        .max("statement".len());
    let wide = if recording.step7 {
        ACCU_WIDTH_S7
    } else {
        ACCU_WIDTH
    };
    let _ = writeln!(
        out,
        "{:>5}  {:<width$}  {:>3} {:>3}  {:<wide$} {:<wide$} operand",
        "line", "statement", "RLO", "STA", "ACCU 1", "ACCU 2"
    );
    let interrupted_after = |line: u32| {
        recording.interruptions.iter().filter(move |interruption| {
            let after = interruption
                .after_pc
                .and_then(|pc| block.spans.get(pc as usize))
                .map_or(first, |span| file.line_of(span.start));
            after == line
        })
    };
    for line in first..=last {
        let beside = match by_line.get(&line) {
            Some(Some(status)) => columns(status, recording.step7),
            Some(None) => "  -   -  not executed".to_string(),
            None => String::new(),
        };
        let row = format!("{line:>5}  {:<width$}  {beside}", statement(line));
        let _ = writeln!(out, "{}", row.trim_end());
        for interruption in interrupted_after(line) {
            let _ = writeln!(
                out,
                "{:>5}  {:<width$}  OB {} ran here: serviced at {}",
                "",
                "↳ interrupt",
                interruption.ob,
                crate::trace::format_ms(interruption.t_ns)
            );
        }
    }
    if recording.ops.iter().flatten().any(|status| status.runs > 1) {
        out.push_str("×n: the line ran n times (a loop); its values are those of the last pass\n");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accumulators_as_words_or_double_words() {
        assert_eq!(accu(5, false), "KH 0005");
        assert_eq!(accu(0x0001_0000, false), "KH 0001 0000");
        assert_eq!(accu(5, true), "W#16#0005");
        assert_eq!(accu(0x0001_0000, true), "DW#16#00010000");
    }
}
