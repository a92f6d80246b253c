//! The diagnostics `awl check` prints, as LSP diagnostics of the document: the primary
//! label's span is the range, the other labels are related information, the help ends the
//! message; the "compiles for …" note follows the errors when no CPU was chosen. A code links
//! to its page, the one `awl help error CODE` prints, written into awl's cache folder for the
//! editor to open.

use lsp_types::{
    CodeDescription, Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location,
    NumberOrString, Uri,
};
use miette::Report;

use super::position::LineIndex;
use super::workspace::{Analysis, uri_of};
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
        code_description: report.code().and_then(|code| page_link(&code.to_string())),
        source: Some(SOURCE.to_string()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

thread_local! {
    /// Each code's link, once its page is written (or could not be).
    static PAGE_LINKS: std::cell::RefCell<std::collections::HashMap<String, Option<CodeDescription>>> =
        Default::default();
}

fn page_link(code: &str) -> Option<CodeDescription> {
    PAGE_LINKS.with(|links| {
        links
            .borrow_mut()
            .entry(code.to_string())
            .or_insert_with(|| page_of(code))
            .clone()
    })
}

/// The page of a diagnostic code as a file the editor can open: written once into the cache
/// folder of this version of awl (`$XDG_CACHE_HOME`, `~/.cache`, or the temporary folder).
/// `None` when the code has no page or the folder cannot be written.
fn page_of(code: &str) -> Option<CodeDescription> {
    let page = crate::docs::error_page(code).ok()?;
    let cache = std::env::var_os("XDG_CACHE_HOME")
        .map(std::path::PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|home| std::path::Path::new(&home).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    let folder = cache
        .join("awl")
        .join(env!("CARGO_PKG_VERSION"))
        .join("errors");
    let name = code.trim_start_matches("awl::").replace("::", ".");
    let path = folder.join(format!("{name}.md"));
    if std::fs::read_to_string(&path).ok().as_deref() != Some(page.as_str()) {
        std::fs::create_dir_all(&folder).ok()?;
        std::fs::write(&path, &page).ok()?;
    }
    Some(CodeDescription {
        href: uri_of(&path)?,
    })
}
