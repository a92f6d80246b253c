//! Errors in scenario files: each names the key, operand or OB, and points at its line.

use miette::{Diagnostic, SourceSpan};
use thiserror::Error;

use crate::diagnostics::Finding;

#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum ScenarioError {
    #[error("cannot read scenario `{path}`: {reason}")]
    #[diagnostic(code(awl::scenario::read), help("check the path of the scenario file"))]
    Read { path: String, reason: String },

    #[error("{message}")]
    #[diagnostic(
        code(awl::scenario::syntax),
        help(
            "a scenario is TOML: `key = value` lines, text and durations in quotes (`watchdog = \"300ms\"`), tables under `[expect]` or `[[event]]`; `awl help scenario` describes the keys"
        )
    )]
    Syntax {
        message: String,
        #[label("here")]
        at: Option<SourceSpan>,
    },

    #[error("unknown key `{key}`")]
    #[diagnostic(code(awl::scenario::unknown_key))]
    UnknownKey {
        key: String,
        /// "not a scenario key", "not a key of [[event]]".
        #[label("{label}")]
        at: SourceSpan,
        label: String,
        #[help]
        help: Option<String>,
    },

    /// `key`: how the key is named, "`run`" or "`at` in [[event]]".
    #[error("{key} takes {takes}")]
    #[diagnostic(code(awl::scenario::wrong_type), help("e.g. {example}"))]
    WrongType {
        key: String,
        takes: &'static str,
        example: &'static str,
        /// What the value is instead: "a string", "a whole number", …
        #[label("{found}")]
        at: SourceSpan,
        found: String,
    },

    #[error("unknown operand `{operand}`")]
    #[diagnostic(code(awl::scenario::unknown_operand))]
    UnknownOperand {
        operand: String,
        #[label("{reason}")]
        at: SourceSpan,
        reason: String,
        #[help]
        help: Option<String>,
    },

    /// `written`: the symbol as the scenario wrote it (`-START`, `"Motor"`).
    #[error("unknown symbol `{written}`")]
    #[diagnostic(code(awl::scenario::unknown_symbol))]
    UnknownSymbol {
        written: String,
        #[label("not in the assignment list")]
        at: SourceSpan,
        #[help]
        help: Option<String>,
    },

    #[error("`{value}` does not fit `{operand}`")]
    #[diagnostic(code(awl::scenario::bad_value))]
    BadValue {
        operand: String,
        value: String,
        #[label("allowed: {range}")]
        at: SourceSpan,
        range: String,
    },

    #[error("unknown OB `{ob}` for the {cpu} CPU")]
    #[diagnostic(code(awl::scenario::unknown_ob))]
    UnknownOb {
        ob: String,
        cpu: &'static str,
        #[label("not an interrupt OB of this CPU")]
        at: SourceSpan,
        #[help]
        help: Option<String>,
    },

    #[error("bad duration `{text}`")]
    #[diagnostic(
        code(awl::scenario::bad_duration),
        help("write a number and a unit: ns, us, ms or s, e.g. \"2.5ms\"")
    )]
    BadDuration {
        text: String,
        #[label("not a duration")]
        at: SourceSpan,
    },

    #[error("the event at {when} never happened: the run ended at {end}")]
    #[diagnostic(
        code(awl::scenario::event_after_end),
        severity(Warning),
        help("lengthen the run (`run = {{ for = \"...\" }}` or `--for`), or move the event")
    )]
    EventAfterEnd {
        when: String,
        end: String,
        #[label("after the end of the run")]
        at: SourceSpan,
    },

    /// `key`: the `[modbus]` key; `takes`: "a bit" or "a word"; `found`: what the operand is.
    #[error("`{key}` in [modbus] starts at {takes}, not at `{operand}`")]
    #[diagnostic(code(awl::scenario::modbus_table))]
    ModbusTable {
        key: &'static str,
        takes: &'static str,
        operand: String,
        #[label("{found}")]
        at: SourceSpan,
        found: &'static str,
        #[help]
        help: &'static str,
    },

    #[error(transparent)]
    #[diagnostic(code(awl::scenario::invalid), forward(0))]
    Invalid(Finding),
}

impl ScenarioError {
    /// Why an operand was refused, for messages outside a scenario file (the command line).
    pub fn reason(&self) -> String {
        match self {
            ScenarioError::UnknownSymbol {
                help: Some(help), ..
            } => {
                format!("not in the assignment list; {help}")
            }
            ScenarioError::UnknownOperand { reason, help, .. } => match help {
                Some(help) => format!("{reason}; {help}"),
                None => reason.clone(),
            },
            other => other.to_string(),
        }
    }
}

impl ScenarioError {
    /// Where the error stands in the file, to report errors in file order.
    pub fn offset(&self) -> usize {
        match self {
            ScenarioError::Read { .. } => 0,
            ScenarioError::Syntax { at, .. } => at.map_or(0, |at| at.offset()),
            ScenarioError::UnknownKey { at, .. }
            | ScenarioError::WrongType { at, .. }
            | ScenarioError::UnknownOperand { at, .. }
            | ScenarioError::UnknownSymbol { at, .. }
            | ScenarioError::BadValue { at, .. }
            | ScenarioError::UnknownOb { at, .. }
            | ScenarioError::BadDuration { at, .. }
            | ScenarioError::EventAfterEnd { at, .. }
            | ScenarioError::ModbusTable { at, .. }
            | ScenarioError::Invalid(Finding { at, .. }) => at.offset(),
        }
    }
}
