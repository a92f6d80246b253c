//! Standard output and standard error that never panic. A closed pipe (`awl dump … | head`)
//! silences the stream, as `cargo` and `grep` do; any other write error (a full disk) is
//! reported once, in one line, and turns the exit code to 1. Diagnostics beyond
//! [`MAX_SHOWN`] are counted, not printed, and so are those of one code and message beyond the
//! first few of a list. With `--format json` each diagnostic is one JSON line on standard
//! output; with `--quiet` only errors are printed.

use std::io::{self, Write};
use std::process::ExitCode;

use miette::Report;

use crate::diagnostics::{JsonWriter, Shown, without_floods};

/// The most diagnostics one command prints; the rest are counted in one line.
pub const MAX_SHOWN: usize = 1000;

/// The exit code for an output that cannot be written.
const EXIT_OUTPUT_FAILED: u8 = 1;

#[derive(Debug, Default)]
struct Stream {
    closed: bool,
}

impl Stream {
    fn write(&mut self, out: &mut dyn Write, text: &str) -> Option<io::Error> {
        if self.closed {
            return None;
        }
        let result = out.write_all(text.as_bytes()).and_then(|()| out.flush());
        match result {
            Ok(()) => None,
            Err(error) => {
                self.closed = true;
                (error.kind() != io::ErrorKind::BrokenPipe).then_some(error)
            }
        }
    }
}

#[derive(Debug, Default)]
pub struct Console {
    stdout: Stream,
    stderr: Stream,
    shown: usize,
    hidden: usize,
    /// `--format json`: diagnostics as JSON lines on standard output.
    json: Option<JsonWriter>,
    /// `--quiet`: no warnings and no notes.
    quiet: bool,
    /// The first write error that was not a closed pipe: (stream, error).
    failure: Option<(&'static str, io::Error)>,
}

impl Console {
    /// Diagnostics as JSON lines on standard output (`--format json`) or as text on standard
    /// error; with `quiet`, errors only.
    pub fn set_output(&mut self, json: bool, quiet: bool) {
        self.json = json.then(JsonWriter::default);
        self.quiet = quiet;
    }

    /// Whether diagnostics go to standard output as JSON: the rest then goes to standard error.
    pub fn is_json(&self) -> bool {
        self.json.is_some()
    }

    /// Whether `--quiet` asked for errors only.
    pub fn is_quiet(&self) -> bool {
        self.quiet
    }

    /// Prints text that is not a diagnostic: to standard output, or to standard error when
    /// standard output holds JSON diagnostics.
    pub fn out_text(&mut self, text: &str) {
        if self.is_json() {
            self.err(text);
        } else {
            self.out(text);
        }
    }

    /// Prints a command's totals line, `awl run: 3 errors, 0 warnings in 1 file`, unless quiet.
    pub fn totals(&mut self, command: &str, totals: crate::diagnostics::Totals) {
        if !self.quiet {
            self.err(&format!("awl {command}: {totals}\n"));
        }
    }

    /// Whether `--quiet` leaves this report out.
    fn left_out(&self, report: &Report) -> bool {
        self.quiet
            && matches!(
                report.severity(),
                Some(miette::Severity::Warning | miette::Severity::Advice)
            )
    }
    /// Prints to standard output.
    pub fn out(&mut self, text: &str) {
        if let Some(error) = self.stdout.write(&mut io::stdout().lock(), text) {
            self.failure.get_or_insert(("standard output", error));
        }
    }

    /// Prints to standard error, after the count of diagnostics not shown, if any.
    pub fn err(&mut self, text: &str) {
        self.note_hidden();
        self.write_err(text);
    }

    fn write_err(&mut self, text: &str) {
        if let Some(error) = self.stderr.write(&mut io::stderr().lock(), text) {
            self.failure.get_or_insert(("standard error", error));
        }
    }

    /// Whether standard output was closed: there is no point producing more of it.
    pub fn out_closed(&self) -> bool {
        self.stdout.closed
    }

    /// Marks standard output closed (a trace to `-` found the pipe closed).
    pub fn close_out(&mut self) {
        self.stdout.closed = true;
    }

    /// Prints a diagnostic: as JSON on standard output, or to standard error, up to
    /// [`MAX_SHOWN`] of them.
    pub fn report(&mut self, report: &Report) {
        if self.left_out(report) {
            return;
        }
        if let Some(json) = &mut self.json {
            let line = json.line(report);
            self.out(&line);
            return;
        }
        if self.shown == MAX_SHOWN {
            self.hidden += 1;
            return;
        }
        self.shown += 1;
        self.write_err(&format!("{report:?}\n"));
    }

    /// Prints a list of diagnostics; as text, those of one code and message beyond the first
    /// few are counted in one line where the last of them stood.
    pub fn reports<'a>(&mut self, reports: impl IntoIterator<Item = &'a Report>) {
        let reports: Vec<&Report> = reports
            .into_iter()
            .filter(|report| !self.left_out(report))
            .collect();
        if self.is_json() {
            for report in reports {
                self.report(report);
            }
            return;
        }
        for shown in without_floods(&reports) {
            match shown {
                Shown::Report(report) => self.report(report),
                Shown::MoreLikeThis {
                    count,
                    code,
                    message,
                } => {
                    let code = if code.is_empty() {
                        String::new()
                    } else {
                        format!("{code}: ")
                    };
                    self.write_err(&format!(
                        "… and {count} more like this ({code}{message})\n\n"
                    ));
                }
            }
        }
    }

    /// Says how many diagnostics were not shown since the last time it said so.
    fn note_hidden(&mut self) {
        let hidden = std::mem::take(&mut self.hidden);
        if hidden > 0 {
            self.write_err(&format!(
                "awl: {} not shown (the first {MAX_SHOWN} are above)\n",
                super::plural(hidden as u64, "more diagnostic")
            ));
        }
    }

    /// Ends the command: the count of diagnostics not shown, the output failure if any, and
    /// the exit code (`code`, or 1 when output failed).
    pub fn finish(mut self, code: u8) -> ExitCode {
        self.note_hidden();
        match self.failure.take() {
            Some((stream, error)) => {
                // Standard error may be the stream that failed: then there is nowhere to say it.
                let _ = writeln!(io::stderr(), "awl: cannot write to {stream}: {error}");
                ExitCode::from(EXIT_OUTPUT_FAILED)
            }
            None => ExitCode::from(code),
        }
    }
}
