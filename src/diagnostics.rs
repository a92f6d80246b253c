//! Rendering: diagnostics carry spans only; the source is attached here, when they are printed.

use miette::{Diagnostic, GraphicalReportHandler, GraphicalTheme, Report};
use thiserror::Error;

use crate::compiler::CheckError;
use crate::parser::ParseError;
use crate::source::{SourceSet, Span};
use crate::step7::error::S7ParseError;
use crate::symbols::SymbolError;

/// A diagnostic of the front end, about one source file.
#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum SourceDiagnostic {
    #[error(transparent)]
    #[diagnostic(transparent)]
    Parse(#[from] ParseError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Check(#[from] CheckError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Symbol(#[from] SymbolError),
    #[error(transparent)]
    #[diagnostic(transparent)]
    Step7(#[from] S7ParseError),
}

impl SourceDiagnostic {
    pub fn span(&self) -> Span {
        match self {
            SourceDiagnostic::Parse(error) => error.span(),
            SourceDiagnostic::Check(error) => error.span(),
            SourceDiagnostic::Symbol(error) => error.span(),
            SourceDiagnostic::Step7(error) => error.span(),
        }
    }

    /// A warning or a note: printed, and `check` still passes.
    pub fn is_warning(&self) -> bool {
        matches!(
            self.severity(),
            Some(miette::Severity::Warning | miette::Severity::Advice)
        )
    }

    /// A note (miette's advice): says how the text was read.
    pub fn is_note(&self) -> bool {
        self.severity() == Some(miette::Severity::Advice)
    }
}

/// A report with the diagnostic's source file attached.
pub fn with_source<D>(sources: &SourceSet, span: Span, diagnostic: D) -> Report
where
    D: Diagnostic + Send + Sync + 'static,
{
    let file = sources.get(span.file);
    Report::new(diagnostic).with_source_code(file.named_source())
}

pub fn report(sources: &SourceSet, diagnostic: &SourceDiagnostic) -> Report {
    with_source(sources, diagnostic.span(), diagnostic.clone())
}

/// Renders a report without colours, as tests and files want it.
pub fn render_plain(report: &Report) -> String {
    let mut out = String::new();
    GraphicalReportHandler::new_themed(GraphicalTheme::unicode_nocolor())
        .with_width(100)
        .render_report(&mut out, report.as_ref())
        .expect("rendering into a String cannot fail");
    out
}
