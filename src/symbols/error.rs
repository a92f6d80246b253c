//! The assignment list's diagnostics: in the symbol file, or where a program uses a symbol.

use miette::Diagnostic;
use thiserror::Error;

use crate::source::Span;

#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum SymbolError {
    #[error("unknown symbol `-{name}`")]
    #[diagnostic(code(awl::symbols::unknown))]
    Unknown {
        name: String,
        #[label("not in the assignment list")]
        at: Span,
        #[help]
        help: Option<String>,
    },

    #[error("symbol `{name}` is defined twice")]
    #[diagnostic(
        code(awl::symbols::duplicate),
        help(
            "a symbol names one operand: remove or rename one of them (the first is {first_place})"
        )
    )]
    Duplicate {
        name: String,
        #[label("defined again here")]
        at: Span,
        /// The first definition, when it is in the same file.
        #[label("first defined here")]
        first: Option<Span>,
        first_place: String,
    },

    #[error("`{operand}` is not an operand")]
    #[diagnostic(
        code(awl::symbols::bad_operand),
        help(
            "write the absolute operand first, as in the program: `E 1.0`/`I 1.0`, `MW 10`/`FW 10`, `T 1`, `PB 3`"
        )
    )]
    BadOperand {
        operand: String,
        #[label("{reason}")]
        at: Span,
        reason: String,
    },

    #[error("`{operand}` is out of range on the {cpu}")]
    #[diagnostic(
        code(awl::symbols::out_of_range),
        help("the {cpu} profile allows {range}")
    )]
    OutOfRange {
        operand: String,
        #[label("allowed: {range}")]
        at: Span,
        range: String,
        cpu: &'static str,
    },

    #[error("a line of the assignment list needs an operand and a symbol")]
    #[diagnostic(
        code(awl::symbols::bad_line),
        help(
            "write `E 1.0   START   Start button` (operand, symbol, comment) or the same as CSV; `;` or `#` start a comment line"
        )
    )]
    BadLine {
        #[label("no symbol after the operand")]
        at: Span,
    },

    #[error("`{name}` cannot be written as a symbol `-{name}`")]
    #[diagnostic(
        code(awl::symbols::bad_name),
        help("a symbol starts with a letter and has letters, digits and `_`")
    )]
    BadName {
        name: String,
        #[label("not a symbol name")]
        at: Span,
    },

    #[error("`-{name}` stands for {stands_for}, which `{op}` cannot take")]
    #[diagnostic(code(awl::symbols::wrong_kind))]
    WrongKind {
        name: String,
        stands_for: String,
        op: String,
        #[label("{stands_for} here")]
        at: Span,
        #[help]
        help: Option<String>,
    },
}

impl SymbolError {
    pub fn span(&self) -> Span {
        match self {
            SymbolError::Unknown { at, .. }
            | SymbolError::Duplicate { at, .. }
            | SymbolError::BadOperand { at, .. }
            | SymbolError::OutOfRange { at, .. }
            | SymbolError::BadLine { at }
            | SymbolError::BadName { at, .. }
            | SymbolError::WrongKind { at, .. } => *at,
        }
    }
}
