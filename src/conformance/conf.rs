//! The `.conf` file beside an awlsim test (`insn_CALL.awl.conf`): lines `key=value`, `#`
//! comments. awlsim's harness (`tests/run.sh` in awlsim 0.77.1) reads the keys below; awl
//! reads the same, ignores those about Python and awlsim's own runs, and rejects any other
//! key, so a typo does not pass unnoticed.

use std::path::Path;
use std::sync::Arc;

use miette::{Diagnostic, NamedSource, Report, SourceSpan};
use thiserror::Error;

use crate::diagnostics::Finding;

/// The longest cycle awlsim's harness allows unless the `.conf` says otherwise: 60 s.
pub const DEFAULT_CYCLE_LIMIT_NS: u64 = 60_000_000_000;

/// What a test's `.conf` asks for; without a `.conf`, awlsim's defaults.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Conf {
    /// The exit code awlsim must end with: 0 (ran cleanly) or 30 (the simulator reported an
    /// error: a source error, a STOP other than by `CALL SFC 46`).
    pub exit_code: u8,
    /// `cycle_limit`: a cycle longer than this is an error (the CPU's cycle watchdog).
    pub cycle_limit_ns: u64,
    /// `max_runtime`: the CPU stops cleanly after this much simulated time; `None` (awlsim's
    /// −1): it runs until the program stops it.
    pub max_runtime_ns: Option<u64>,
    /// `accus`: the number of accumulators the test needs (2 or 4), when it says.
    pub accus: Option<u8>,
    /// `disabled`: why the test is not run, when it is not.
    pub disabled: Option<String>,
}

impl Default for Conf {
    fn default() -> Self {
        Conf {
            exit_code: 0,
            cycle_limit_ns: DEFAULT_CYCLE_LIMIT_NS,
            max_runtime_ns: None,
            accus: None,
            disabled: None,
        }
    }
}

/// Keys awlsim's harness reads that concern Python or awlsim's own runs, not the program.
const IGNORED_KEYS: &[&str] = &["optimizer_runs", "tries", "loglevel", "env", "PYTHONPATH"];

/// The keys awl acts on.
const KEYS: &[&str] = &[
    "exit_code",
    "cycle_limit",
    "max_runtime",
    "accus",
    "disabled",
];

/// The largest number of seconds that still fits simulated time in nanoseconds, with room.
const MAX_SECONDS: f64 = 1e9;

#[derive(Debug, Error, Diagnostic)]
pub enum ConfError {
    #[error(transparent)]
    #[diagnostic(code(awl::conformance::bad_conf), forward(0))]
    Line(Finding),

    #[error("cannot read `{path}`: {reason}")]
    #[diagnostic(
        code(awl::conformance::read_conf),
        help("a test's .conf is a text file of `key=value` lines beside it")
    )]
    Read { path: String, reason: String },
}

/// The `.conf` beside `test` (`test` with `.conf` appended), or the defaults when there is
/// none; every error in it, each at its line.
pub fn read_conf(test: &Path) -> Result<Conf, Vec<Report>> {
    let mut name = test.as_os_str().to_owned();
    name.push(".conf");
    let path = Path::new(&name);
    if !path.exists() {
        return Ok(Conf::default());
    }
    let read = |reason: String| {
        vec![Report::new(ConfError::Read {
            path: path.display().to_string(),
            reason,
        })]
    };
    let bytes = std::fs::read(path).map_err(|error| read(error.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|error| read(error.to_string()))?;
    parse_conf(&text).map_err(|errors| {
        let text: Arc<str> = Arc::from(text);
        let source = NamedSource::new(path.display().to_string(), text);
        errors
            .into_iter()
            .map(|error| Report::new(error).with_source_code(source.clone()))
            .collect()
    })
}

/// Reads `.conf` text: the settings, or every error found.
pub fn parse_conf(text: &str) -> Result<Conf, Vec<ConfError>> {
    let mut conf = Conf::default();
    let mut errors = Vec::new();
    let mut seen: Vec<&str> = Vec::new();
    for (start, line) in lines(text) {
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let offset = start + (line.len() - line.trim_start().len());
        let whole: SourceSpan = (offset, trimmed.len()).into();
        let Some((key, value)) = trimmed.split_once('=') else {
            errors.push(bad(
                "a line that is not `key=value`",
                whole,
                "no `=`",
                Some("write e.g. `exit_code=30`; a `#` starts a comment line".into()),
            ));
            continue;
        };
        let (key, value) = (key.trim(), value.trim());
        let key_span: SourceSpan = (offset, key.len()).into();
        let value_span: SourceSpan = (offset + trimmed.len() - value.len(), value.len()).into();
        if seen.contains(&key) {
            errors.push(bad(
                format!("`{key}` given twice"),
                key_span,
                "again",
                Some("give each key once".into()),
            ));
            continue;
        }
        seen.push(key);
        let result = match key {
            "exit_code" => exit_code(value).map(|code| conf.exit_code = code),
            "cycle_limit" => seconds(value, false).map(|ns| conf.cycle_limit_ns = ns),
            "max_runtime" => runtime(value).map(|limit| conf.max_runtime_ns = limit),
            "accus" => accus(value).map(|count| conf.accus = Some(count)),
            "disabled" => {
                conf.disabled = (!value.is_empty()).then(|| value.to_string());
                Ok(())
            }
            ignored if IGNORED_KEYS.contains(&ignored) => Ok(()),
            unknown => {
                errors.push(unknown_key(unknown, key_span));
                continue;
            }
        };
        if let Err((message, help)) = result {
            errors.push(bad(message, value_span, "this value", Some(help)));
        }
    }
    if errors.is_empty() {
        Ok(conf)
    } else {
        Err(errors)
    }
}

/// Each line with its byte offset; `\r\n` and `\n` end lines, a byte order mark is skipped.
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let bom = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let mut start = bom;
    text[bom..].split_inclusive('\n').map(move |piece| {
        let at = start;
        start += piece.len();
        (at, piece.trim_end_matches(['\n', '\r']))
    })
}

fn bad(message: impl Into<String>, at: SourceSpan, label: &str, help: Option<String>) -> ConfError {
    ConfError::Line(Finding::new(message, at, label, help))
}

fn unknown_key(key: &str, at: SourceSpan) -> ConfError {
    let known = KEYS.iter().chain(IGNORED_KEYS).copied();
    let help = match crate::suggest::did_you_mean(key, known) {
        Some(near) => format!("did you mean `{near}`?"),
        None => format!(
            "the keys: {}; awlsim's {} are accepted and ignored",
            KEYS.join(", "),
            IGNORED_KEYS.join(", ")
        ),
    };
    bad(
        format!("unknown key `{key}`"),
        at,
        "not a test key",
        Some(help),
    )
}

type ValueError = (String, String);

fn exit_code(value: &str) -> Result<u8, ValueError> {
    match value {
        "0" => Ok(0),
        "30" => Ok(30),
        _ => Err((
            format!("unknown exit code `{value}`"),
            "0 (the test runs cleanly) or 30 (the simulator must report an error)".into(),
        )),
    }
}

/// A number of seconds (decimals allowed) in nanoseconds; above 0 unless `zero_too`.
fn seconds(value: &str, zero_too: bool) -> Result<u64, ValueError> {
    let lowest = if zero_too { "0 or more" } else { "above 0" };
    let error = || {
        (
            format!("`{value}` is not a time in seconds"),
            format!("a number of seconds, {lowest}, e.g. `1` or `0.5`"),
        )
    };
    let seconds: f64 = value.parse().map_err(|_| error())?;
    let in_range = seconds.is_finite()
        && seconds <= MAX_SECONDS
        && (seconds > 0.0 || (zero_too && seconds == 0.0));
    if !in_range {
        return Err(error());
    }
    Ok((seconds * 1e9).round() as u64)
}

/// `max_runtime`: seconds, or a negative number (awlsim's −1) for no limit.
fn runtime(value: &str) -> Result<Option<u64>, ValueError> {
    if value.starts_with('-') && value.parse::<f64>().is_ok_and(|n| n < 0.0) {
        return Ok(None);
    }
    seconds(value, true).map(Some).map_err(|(message, _)| {
        (
            message,
            "a number of seconds, e.g. `1`; -1: no limit".into(),
        )
    })
}

fn accus(value: &str) -> Result<u8, ValueError> {
    match value {
        "2" => Ok(2),
        "4" => Ok(4),
        _ => Err((
            format!("unknown number of accumulators `{value}`"),
            "2 (as an S7-300) or 4 (as an S7-400)".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn errors(text: &str) -> Vec<String> {
        let errors = parse_conf(text).expect_err("errors");
        errors
            .into_iter()
            .map(|error| {
                let ConfError::Line(Finding {
                    message, at, help, ..
                }) = error
                else {
                    panic!("a line error");
                };
                let shown = &text[at.offset()..at.offset() + at.len()];
                format!("{message} @ `{shown}` | {}", help.unwrap_or_default())
            })
            .collect()
    }

    #[test]
    fn no_keys_are_awlsim_s_defaults() {
        let conf = parse_conf("").unwrap();
        assert_eq!(conf, Conf::default());
        assert_eq!(conf.exit_code, 0);
        assert_eq!(conf.cycle_limit_ns, 60_000_000_000);
        assert_eq!(conf.max_runtime_ns, None);
        assert_eq!(conf.accus, None);
        assert_eq!(conf.disabled, None);
    }

    #[test]
    fn every_key_is_read() {
        let text = "exit_code=30\ncycle_limit=0.5\nmax_runtime=1\naccus=4\ndisabled=no GUI here\n";
        let conf = parse_conf(text).unwrap();
        assert_eq!(
            conf,
            Conf {
                exit_code: 30,
                cycle_limit_ns: 500_000_000,
                max_runtime_ns: Some(1_000_000_000),
                accus: Some(4),
                disabled: Some("no GUI here".into()),
            }
        );
    }

    #[test]
    fn awlsim_s_own_keys_are_ignored() {
        let text = "optimizer_runs=off all\ntries=3\nloglevel=1\nenv=A=1\nPYTHONPATH=libs:more\n";
        assert_eq!(parse_conf(text).unwrap(), Conf::default());
    }

    #[test]
    fn comments_blank_lines_crlf_and_a_byte_order_mark_are_read() {
        let text =
            "\u{feff}# a comment\r\n\r\n  exit_code = 30 \r\n\t# another\r\nmax_runtime=2\r\n";
        let conf = parse_conf(text).unwrap();
        assert_eq!(conf.exit_code, 30);
        assert_eq!(conf.max_runtime_ns, Some(2_000_000_000));
        let errors = errors("# comment\r\naccus=3\r\n");
        assert_eq!(
            errors,
            ["unknown number of accumulators `3` @ `3` | 2 (as an S7-300) or 4 (as an S7-400)"]
        );
    }

    #[test]
    fn max_runtime_below_zero_is_no_limit() {
        for text in ["max_runtime=-1", "max_runtime=-1.0", "max_runtime=-5"] {
            assert_eq!(parse_conf(text).unwrap().max_runtime_ns, None, "{text}");
        }
        let zero = parse_conf("max_runtime=0").unwrap();
        assert_eq!(zero.max_runtime_ns, Some(0));
        let decimal = parse_conf("max_runtime=0.25").unwrap();
        assert_eq!(decimal.max_runtime_ns, Some(250_000_000));
    }

    #[test]
    fn an_empty_disabled_runs_the_test() {
        assert_eq!(parse_conf("disabled=").unwrap().disabled, None);
        assert_eq!(parse_conf("disabled=  ").unwrap().disabled, None);
    }

    #[test]
    fn bad_values_are_errors_at_the_value() {
        assert_eq!(
            errors("exit_code=1\n"),
            [
                "unknown exit code `1` @ `1` | 0 (the test runs cleanly) or 30 (the simulator must report an error)"
            ]
        );
        assert_eq!(
            errors("cycle_limit=0\n"),
            [
                "`0` is not a time in seconds @ `0` | a number of seconds, above 0, e.g. `1` or `0.5`"
            ]
        );
        assert_eq!(
            errors("cycle_limit=1s\n"),
            [
                "`1s` is not a time in seconds @ `1s` | a number of seconds, above 0, e.g. `1` or `0.5`"
            ]
        );
        assert_eq!(
            errors("max_runtime=soon\n"),
            [
                "`soon` is not a time in seconds @ `soon` | a number of seconds, e.g. `1`; -1: no limit"
            ]
        );
        assert_eq!(
            errors("max_runtime=1e30\n"),
            [
                "`1e30` is not a time in seconds @ `1e30` | a number of seconds, e.g. `1`; -1: no limit"
            ]
        );
        assert_eq!(errors("accus=\n").len(), 1);
    }

    #[test]
    fn every_bad_line_is_reported() {
        assert_eq!(
            errors("exit_cod=30\nnothing here\nexit_code=30\nexit_code=0\nfoo=1\n"),
            [
                "unknown key `exit_cod` @ `exit_cod` | did you mean `exit_code`?",
                "a line that is not `key=value` @ `nothing here` | write e.g. `exit_code=30`; a `#` starts a comment line",
                "`exit_code` given twice @ `exit_code` | give each key once",
                "unknown key `foo` @ `foo` | the keys: exit_code, cycle_limit, max_runtime, accus, disabled; awlsim's optimizer_runs, tries, loglevel, env, PYTHONPATH are accepted and ignored",
            ]
        );
    }
}
