//! A diagnostic as the page shows it: the words, the code, the help, where it points (so the
//! editor can mark the line and a click can jump there), and miette's own rendering.

use miette::{Report, Severity};
use serde::Serialize;

use crate::diagnostics::render_plain;
use crate::vm::Cpu;

/// A line in one of the files.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Place {
    pub file: String,
    /// 1-based, as the editor numbers them.
    pub line: u32,
    pub column: u32,
}

impl Place {
    /// Where op `pc` of block `block` was written.
    pub fn of_op(cpu: &Cpu, block: u16, pc: u32) -> Option<Place> {
        let compiled = cpu.program.blocks.get(usize::from(block))?;
        let span = compiled
            .spans
            .get(pc as usize)
            .copied()
            .unwrap_or(compiled.header);
        Some(Place {
            file: cpu.sources.get(span.file).name.clone(),
            line: cpu.sources.line_of(span),
            column: 1,
        })
    }
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    /// `error`, `warning` or `advice`.
    pub severity: &'static str,
    pub code: Option<String>,
    pub message: String,
    pub help: Option<String>,
    /// Where its first label points, when it points into a file.
    pub at: Option<Place>,
    /// The whole report as `awl` prints it, without colours.
    pub rendered: String,
}

impl Diagnostic {
    pub fn of(report: &Report) -> Diagnostic {
        let severity = match report.severity().unwrap_or(Severity::Error) {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Advice => "advice",
        };
        Diagnostic {
            severity,
            code: report.code().map(|code| code.to_string()),
            message: report.to_string(),
            help: report.help().map(|help| help.to_string()),
            at: place(report),
            rendered: render_plain(report),
        }
    }
}

/// The place of the report's first label in its source.
fn place(report: &Report) -> Option<Place> {
    let label = report.labels()?.next()?;
    let contents = report.source_code()?.read_span(label.inner(), 0, 0).ok()?;
    Some(Place {
        file: contents.name().unwrap_or_default().to_string(),
        line: contents.line() as u32 + 1,
        column: contents.column() as u32 + 1,
    })
}
