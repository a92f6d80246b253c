//! The checks of every diagnostic. The cheap ones run for every input: the message, the code,
//! the help, and every label inside its text and on character boundaries. Reading the labels'
//! lines through miette and rendering in full (layout, wrapping) cost far more than building
//! and checking the program (miette finds a label's lines by scanning the text from its
//! start), so they run for a sample of inputs.

use std::sync::Once;

use awl::diagnostics::{self, render_plain};
use awl::frontend::Frontend;
use miette::{Diagnostic, GraphicalReportHandler, GraphicalTheme, Report, SourceCode};

/// The lines around a label miette shows (its default), so the same lines are read.
const CONTEXT_LINES: usize = 1;

/// Makes building a [`Report`] cheap: miette's default hook asks the terminal and the
/// environment how to print every time a report is made; the fuzz targets never print one.
pub fn quiet_reports() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // Set before any report is made, so it cannot have been set already.
        let _ = miette::set_hook(Box::new(|_| {
            Box::new(GraphicalReportHandler::new_themed(
                GraphicalTheme::unicode_nocolor(),
            ))
        }));
    });
}

/// Every diagnostic of the front end passes the cheap checks; with `render`, it renders too.
pub fn check_diagnostics(built: &Frontend, render: bool) {
    for diagnostic in &built.diagnostics {
        let span = diagnostic.span();
        let file = built.sources.get(span.file);
        assert!(span.start <= span.end, "{diagnostic:?}");
        let text = &file.text;
        assert!(
            text.is_char_boundary(span.start as usize) && text.is_char_boundary(span.end as usize),
            "{diagnostic:?} splits a character or leaves the text"
        );
        check_labels(diagnostic, text);
        if render {
            check_readable(diagnostic, &file.named_source());
            assert!(!render_plain(&diagnostics::report(&built.sources, diagnostic)).is_empty());
        }
    }
}

/// A report about `text` (a scenario's errors, a STOP report) passes the cheap checks; with
/// `render`, it renders too.
pub fn check_report(report: &Report, text: &str, render: bool) {
    let diagnostic: &dyn Diagnostic = report.as_ref();
    check_labels(diagnostic, text);
    if diagnostic.labels().is_some() {
        let source = diagnostic
            .source_code()
            .unwrap_or_else(|| panic!("{report:?}: labels without the text they point into"));
        if render {
            check_readable(diagnostic, source);
        }
    }
    if render {
        assert!(!render_plain(report).is_empty());
    }
}

/// The message, code and help, and every label inside `text` on character boundaries.
fn check_labels(diagnostic: &dyn Diagnostic, text: &str) {
    check_text(diagnostic);
    for label in diagnostic.labels().into_iter().flatten() {
        let (start, end) = (label.offset(), label.offset() + label.len());
        assert!(end <= text.len(), "{diagnostic:?}: label past the end");
        assert!(
            text.is_char_boundary(start) && text.is_char_boundary(end),
            "{diagnostic:?}: a label splits a character"
        );
    }
}

/// Every label's lines read through the source miette reads, with the lines around it it shows.
fn check_readable(diagnostic: &dyn Diagnostic, source: &dyn SourceCode) {
    for label in diagnostic.labels().into_iter().flatten() {
        let read = source.read_span(label.inner(), CONTEXT_LINES, CONTEXT_LINES);
        assert!(read.is_ok(), "{diagnostic:?}: label unreadable");
    }
}

/// The message, a stable `awl::` code, and the help if there is one.
fn check_text(diagnostic: &dyn Diagnostic) {
    assert!(
        !diagnostic.to_string().is_empty(),
        "{diagnostic:?}: no message"
    );
    let code = diagnostic
        .code()
        .unwrap_or_else(|| panic!("{diagnostic:?}: no code"))
        .to_string();
    assert!(code.starts_with("awl::"), "{diagnostic:?}: code `{code}`");
    if let Some(help) = diagnostic.help() {
        assert!(!help.to_string().is_empty(), "{diagnostic:?}: empty help");
    }
}
