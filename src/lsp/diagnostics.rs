//! The diagnostics `awl check` prints, as LSP diagnostics of the document: the primary
//! label's span is the range, the other labels are related information, the help ends the
//! message; the "compiles for …" note follows the errors when no CPU was chosen.

use lsp_types::{
    Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString, Uri,
};
use miette::Report;

use super::position::LineIndex;
use super::workspace::Analysis;
use crate::diagnostics;

const SOURCE: &str = "awl";

/// The diagnostics of each file of the document's program (the document is file 0): the
/// other program files and the assignment lists have theirs too, as `awl check` prints them.
pub fn of_program(analysis: &Analysis) -> Vec<(Option<Uri>, Vec<Diagnostic>)> {
    (0..analysis.built.sources.files.len() as u16)
        .map(|file| (analysis.uri(file), of_file(analysis, file)))
        .collect()
}

fn of_file(analysis: &Analysis, file: u16) -> Vec<Diagnostic> {
    let text = analysis.text(file);
    let index = LineIndex::new(text);
    let mut found: Vec<Diagnostic> = analysis
        .built
        .diagnostics
        .iter()
        .filter(|diagnostic| diagnostic.span().file == file)
        .map(|diagnostic| {
            let report = diagnostics::report(&analysis.built.sources, diagnostic);
            convert(&report, analysis.uri(file), &index)
        })
        .collect();
    if file == 0 {
        // A file named by the scenario or the settings that is missing: at the document's top.
        found.extend(
            analysis
                .unread
                .iter()
                .map(|report| convert(report, None, &index)),
        );
    }
    if let Some(note) = runs_on_note(analysis).filter(|_| file == 0) {
        let first_error = found
            .iter()
            .find(|diagnostic| diagnostic.severity == Some(DiagnosticSeverity::ERROR))
            .map(|diagnostic| diagnostic.range);
        found.push(Diagnostic {
            range: first_error.unwrap_or_default(),
            severity: Some(DiagnosticSeverity::INFORMATION),
            source: Some(SOURCE.to_string()),
            message: note,
            ..Diagnostic::default()
        });
    }
    found
}

/// "compiles without errors for --cpu …", as `awl check` says it, where a CPU would help.
fn runs_on_note(analysis: &Analysis) -> Option<String> {
    if crate::frontend::cpu_cannot_help(&analysis.built) {
        return None;
    }
    let note = crate::frontend::runs_on_note(&analysis.runs_on()?);
    Some(note.trim_end().trim_start_matches("note: ").to_string())
}

fn severity(report: &Report) -> DiagnosticSeverity {
    match report.severity() {
        Some(miette::Severity::Warning) => DiagnosticSeverity::WARNING,
        Some(miette::Severity::Advice) => DiagnosticSeverity::INFORMATION,
        Some(miette::Severity::Error) | None => DiagnosticSeverity::ERROR,
    }
}

/// One report as an LSP diagnostic of the file `uri` whose lines `index` holds.
fn convert(report: &Report, uri: Option<Uri>, index: &LineIndex) -> Diagnostic {
    let labels: Vec<miette::LabeledSpan> = report.labels().into_iter().flatten().collect();
    let primary = labels.iter().position(|label| label.primary()).unwrap_or(0);
    let range_of =
        |label: &miette::LabeledSpan| index.range(label.offset()..label.offset() + label.len());
    let range = labels.get(primary).map(range_of).unwrap_or_default();
    let mut message = report.to_string();
    if let Some(text) = labels.get(primary).and_then(|label| label.label()) {
        message.push_str(&format!(" ({text})"));
    }
    if let Some(help) = report.help() {
        message.push_str(&format!("\nhelp: {help}"));
    }
    let related: Vec<DiagnosticRelatedInformation> = uri
        .map(|uri| {
            labels
                .iter()
                .enumerate()
                .filter(|(at, _)| *at != primary)
                .map(|(_, label)| DiagnosticRelatedInformation {
                    location: Location::new(uri.clone(), range_of(label)),
                    message: label.label().unwrap_or("here").to_string(),
                })
                .collect()
        })
        .unwrap_or_default();
    Diagnostic {
        range,
        severity: Some(severity(report)),
        code: report
            .code()
            .map(|code| NumberOrString::String(code.to_string())),
        source: Some(SOURCE.to_string()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}
