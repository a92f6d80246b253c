//! Rendering: diagnostics carry spans only; the source is attached here, when they are printed.

use miette::{Diagnostic, GraphicalReportHandler, GraphicalTheme, Report, SourceSpan};
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

/// What is wrong at one place of a file, for the errors that say it in their own words (a
/// project's, a test's `.conf`, a scenario's): the message, the place with its label, the help
/// where a fix is known. The error's variant gives the code (`forward(0)` for the rest).
#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
#[error("{message}")]
pub struct Finding {
    pub message: String,
    #[label("{label}")]
    pub at: SourceSpan,
    pub label: String,
    #[help]
    pub help: Option<String>,
}

impl Finding {
    pub fn new(
        message: impl Into<String>,
        at: SourceSpan,
        label: impl Into<String>,
        help: Option<String>,
    ) -> Self {
        let (message, label) = (message.into(), label.into());
        Finding {
            message,
            at,
            label,
            help,
        }
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

/// The counts of a front end's diagnostics, as a command's totals line says them: "3 errors,
/// 1 warning, 2 notes in 1 file".
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Totals {
    pub errors: usize,
    pub warnings: usize,
    pub notes: usize,
    /// The files read: the programs and the symbol tables.
    pub files: usize,
}

impl Totals {
    /// The counts of `diagnostics`, from `files` files.
    pub fn of(diagnostics: &[SourceDiagnostic], files: usize) -> Self {
        let errors = diagnostics.iter().filter(|d| !d.is_warning()).count();
        let notes = diagnostics.iter().filter(|d| d.is_note()).count();
        Totals {
            errors,
            warnings: diagnostics.len() - errors - notes,
            notes,
            files,
        }
    }

    /// With `more` warnings found beyond the front end's (the program's warnings).
    pub fn with_warnings(self, more: usize) -> Self {
        Totals {
            warnings: self.warnings + more,
            ..self
        }
    }
}

impl std::fmt::Display for Totals {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}, {}",
            plural(self.errors as u64, "error"),
            plural(self.warnings as u64, "warning")
        )?;
        if self.notes > 0 {
            write!(f, ", {}", plural(self.notes as u64, "note"))?;
        }
        write!(f, " in {}", plural(self.files as u64, "file"))
    }
}

/// How many reports of one code and message are printed before the rest of them are counted
/// in one line.
pub const SHOWN_ALIKE: usize = 3;

/// What to print of a list of reports: each report, or the count of those left out.
#[derive(Debug)]
pub enum Shown<'a> {
    Report(&'a Report),
    /// "and 673 more like this": after the last report of a group of one code and message.
    MoreLikeThis {
        count: usize,
        code: String,
        message: String,
    },
}

/// A report's group: its code and its message.
fn group_of(report: &Report) -> (String, String) {
    let code = report
        .code()
        .map(|code| code.to_string())
        .unwrap_or_default();
    (code, report.to_string())
}

/// The reports to print: the first [`SHOWN_ALIKE`] of each code and message, then, where the
/// group's last report stood, how many more there were.
pub fn without_floods<'a>(reports: &[&'a Report]) -> Vec<Shown<'a>> {
    use std::collections::HashMap;
    let groups: Vec<(String, String)> = reports.iter().map(|report| group_of(report)).collect();
    // Per group: how many, and the position of its last report.
    let mut sizes: HashMap<&(String, String), (usize, usize)> = HashMap::new();
    for (at, group) in groups.iter().enumerate() {
        let entry = sizes.entry(group).or_insert((0, at));
        *entry = (entry.0 + 1, at);
    }
    let mut seen: HashMap<&(String, String), usize> = HashMap::new();
    let mut shown = Vec::with_capacity(reports.len());
    for (at, (report, group)) in reports.iter().zip(&groups).enumerate() {
        let count = seen.entry(group).or_insert(0);
        *count += 1;
        if *count <= SHOWN_ALIKE {
            shown.push(Shown::Report(report));
        }
        let (size, last) = sizes[group];
        if at == last && size > SHOWN_ALIKE {
            shown.push(Shown::MoreLikeThis {
                count: size - SHOWN_ALIKE,
                code: group.0.clone(),
                message: group.1.clone(),
            });
        }
    }
    shown
}

/// A place in a source file, 1-based; the column counts characters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Place {
    line: usize,
    column: usize,
}

/// A source text with where its lines start, to tell places quickly.
#[derive(Debug)]
struct Lines {
    text: String,
    starts: Vec<usize>,
}

impl Lines {
    fn new(text: String) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(at, _)| at + 1))
            .collect();
        Lines { text, starts }
    }

    /// The place of byte `offset`.
    fn place(&self, offset: usize) -> Place {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|start| *start <= offset);
        let start = self.starts[line - 1];
        let column = self
            .text
            .get(start..offset)
            .map_or(offset - start, |before| before.chars().count());
        Place {
            line,
            column: column + 1,
        }
    }
}

/// One label of a JSON diagnostic.
#[derive(Debug, serde::Serialize)]
struct JsonLabel {
    line: usize,
    column: usize,
    end_line: usize,
    end_column: usize,
    text: Option<String>,
}

/// A diagnostic as one JSON object (`--format json`).
#[derive(Debug, serde::Serialize)]
struct JsonDiagnostic {
    code: Option<String>,
    severity: &'static str,
    file: Option<String>,
    line: Option<usize>,
    column: Option<usize>,
    message: String,
    labels: Vec<JsonLabel>,
    help: Option<String>,
}

/// Writes reports as JSON lines (`--format json`), keeping each source file's lines so many
/// diagnostics of one big file stay quick.
#[derive(Debug, Default)]
pub struct JsonWriter {
    files: std::collections::HashMap<String, Lines>,
}

impl JsonWriter {
    /// The lines of a report's source and its name, read once per file.
    fn source_of(&mut self, report: &Report) -> Option<(&Lines, Option<String>)> {
        let source = report.source_code()?;
        // A span at the start with no context reads one byte, and gives the file's name.
        let name = source
            .read_span(&(0, 0).into(), 0, 0)
            .ok()?
            .name()
            .map(str::to_string);
        let key = name.clone().unwrap_or_default();
        if !self.files.contains_key(&key) || name.is_none() {
            // As many lines after the start as a file can have: the whole text.
            let all_lines = u32::MAX as usize;
            let whole = source.read_span(&(0, 0).into(), 0, all_lines).ok()?;
            let text = String::from_utf8_lossy(whole.data()).into_owned();
            self.files.insert(key.clone(), Lines::new(text));
        }
        Some((&self.files[&key], name))
    }

    /// A report as one line of JSON: `code`, `severity`, `file`, `line`, `column` (1-based, of
    /// the primary label), `message`, `labels` (each with its start, its end, exclusive, and
    /// its text) and `help`.
    pub fn line(&mut self, report: &Report) -> String {
        let severity = match report.severity() {
            Some(miette::Severity::Warning) => "warning",
            Some(miette::Severity::Advice) => "advice",
            Some(miette::Severity::Error) | None => "error",
        };
        let labels: Vec<miette::LabeledSpan> = report.labels().into_iter().flatten().collect();
        let primary = labels
            .iter()
            .find(|label| label.primary())
            .or(labels.first())
            .map(|label| label.offset());
        let (file, start, labels) = match self.source_of(report) {
            Some((lines, name)) => {
                let labels = labels
                    .iter()
                    .map(|label| {
                        let start = lines.place(label.offset());
                        let end = lines.place(label.offset() + label.len());
                        JsonLabel {
                            line: start.line,
                            column: start.column,
                            end_line: end.line,
                            end_column: end.column,
                            text: label.label().map(str::to_string),
                        }
                    })
                    .collect();
                (name, primary.map(|offset| lines.place(offset)), labels)
            }
            None => (None, None, Vec::new()),
        };
        let json = JsonDiagnostic {
            code: report.code().map(|code| code.to_string()),
            severity,
            file,
            line: start.map(|start| start.line),
            column: start.map(|start| start.column),
            message: report.to_string(),
            labels,
            help: report.help().map(|help| help.to_string()),
        };
        let mut line = serde_json::to_string(&json).expect("a diagnostic is plain data");
        line.push('\n');
        line
    }
}

/// `1 error`, `3 errors`: a count with its word, as every summary and totals line writes it.
pub fn plural(n: impl Into<u64>, word: &str) -> String {
    let n = n.into();
    format!("{n} {word}{}", if n == 1 { "" } else { "s" })
}

#[cfg(test)]
mod tests {
    use super::*;
    use miette::{LabeledSpan, NamedSource, miette};

    fn report(code: &str, message: &str) -> Report {
        miette!(code = code.to_string(), "{message}")
    }

    fn texts(shown: &[Shown<'_>]) -> Vec<String> {
        shown
            .iter()
            .map(|shown| match shown {
                Shown::Report(report) => report.to_string(),
                Shown::MoreLikeThis { count, .. } => format!("+{count}"),
            })
            .collect()
    }

    #[test]
    fn a_flood_shows_three_then_counts_the_rest_where_it_ends() {
        let mut reports: Vec<Report> = (0..6).map(|_| report("awl::a", "same")).collect();
        reports.insert(2, report("awl::b", "other"));
        reports.push(report("awl::c", "last"));
        let reports: Vec<&Report> = reports.iter().collect();
        assert_eq!(
            texts(&without_floods(&reports)),
            ["same", "same", "other", "same", "+3", "last"]
        );
    }

    #[test]
    fn one_code_with_other_messages_is_another_group() {
        let reports: Vec<Report> = (0..4)
            .map(|n| report("awl::a", &format!("message {}", n % 2)))
            .collect();
        let reports: Vec<&Report> = reports.iter().collect();
        assert_eq!(without_floods(&reports).len(), 4);
    }

    #[test]
    fn places_count_lines_and_characters_from_one() {
        let lines = Lines::new("ab\näx = 1\n".to_string());
        assert_eq!(lines.place(0), Place { line: 1, column: 1 });
        assert_eq!(lines.place(3), Place { line: 2, column: 1 });
        // `ä` is two bytes and one character.
        assert_eq!(lines.place(5), Place { line: 2, column: 2 });
        assert_eq!(lines.place(100), Place { line: 3, column: 1 });
    }

    #[test]
    fn a_json_line_has_the_place_labels_and_help() {
        let source = NamedSource::new("p.awl", "OB 1\n  A  I 200.0\n".to_string());
        let with_label = miette!(
            code = "awl::check::operand_range",
            labels = vec![LabeledSpan::at(10..17, "out of range")],
            help = "I 0…127",
            "I 200 is out of range"
        )
        .with_source_code(source);
        let mut writer = JsonWriter::default();
        let json: serde_json::Value = serde_json::from_str(&writer.line(&with_label)).unwrap();
        assert_eq!(
            json,
            serde_json::json!({
                "code": "awl::check::operand_range",
                "severity": "error",
                "file": "p.awl",
                "line": 2,
                "column": 6,
                "message": "I 200 is out of range",
                "labels": [{
                    "line": 2, "column": 6, "end_line": 2, "end_column": 13,
                    "text": "out of range"
                }],
                "help": "I 0…127"
            })
        );
        let plain = miette!("no source");
        let json: serde_json::Value = serde_json::from_str(&writer.line(&plain)).unwrap();
        assert_eq!(json["file"], serde_json::Value::Null);
        assert_eq!(json["labels"], serde_json::json!([]));
        assert_eq!(json["help"], serde_json::Value::Null);
    }

    #[test]
    fn totals_say_notes_only_when_there_are_some() {
        let totals = Totals {
            errors: 1,
            warnings: 2,
            notes: 0,
            files: 1,
        };
        assert_eq!(totals.to_string(), "1 error, 2 warnings in 1 file");
        let more = Totals { notes: 2, ..totals }.with_warnings(1);
        assert_eq!(more.to_string(), "1 error, 3 warnings, 2 notes in 1 file");
    }
}
