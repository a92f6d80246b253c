//! The assignment list's diagnostics: in the symbol file, or where a program uses a symbol.

use miette::Diagnostic;
use thiserror::Error;

use crate::source::Span;

#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum SymbolError {
    /// `written` is the symbol as a program writes it: `-START`, `"Motor"`.
    #[error("unknown symbol `{written}`")]
    #[diagnostic(code(awl::symbols::unknown))]
    Unknown {
        written: String,
        /// `assignment list` (STEP 5) or `symbol table` (STEP 7).
        list: &'static str,
        #[label("not in the {list}")]
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
    #[diagnostic(code(awl::symbols::bad_operand))]
    BadOperand {
        operand: String,
        #[label("{reason}")]
        at: Span,
        reason: String,
        #[help]
        help: String,
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

    #[error("`{name}` cannot be written as a symbol `{written}`")]
    #[diagnostic(code(awl::symbols::bad_name))]
    BadName {
        name: String,
        written: String,
        #[label("not a symbol name")]
        at: Span,
        #[help]
        help: String,
    },

    #[error("not a line of a STEP 7 symbol table")]
    #[diagnostic(
        code(awl::symbols::bad_table_line),
        help(
            "a STEP 7 symbol table is the ASCII export (`126,` then the symbol in 24 columns, the address in 12, the data type in 10, the comment) or CSV `Symbol;Address;Data type;Comment`"
        )
    )]
    BadTableLine {
        reason: String,
        #[label("{reason}")]
        at: Span,
    },

    #[error("data type `{ty}` does not fit `{operand}`")]
    #[diagnostic(
        code(awl::symbols::type_mismatch),
        help("`{operand}` takes the data type {expected}")
    )]
    TypeMismatch {
        ty: String,
        operand: String,
        expected: String,
        #[label("not a type of `{operand}`")]
        at: Span,
    },

    #[error("a {found} symbol list for a {program} program")]
    #[diagnostic(code(awl::symbols::wrong_dialect), help("{help}"))]
    WrongDialect {
        found: &'static str,
        program: &'static str,
        help: &'static str,
        #[label("this file is read as a {found} list")]
        at: Span,
    },

    /// `written` as in [`SymbolError::Unknown`].
    #[error("`{written}` stands for {stands_for}, which `{op}` cannot take")]
    #[diagnostic(code(awl::symbols::wrong_kind))]
    WrongKind {
        written: String,
        stands_for: String,
        op: String,
        #[label("{stands_for} here")]
        at: Span,
        #[help]
        help: Option<String>,
    },
}

crate::source::error_span!(SymbolError {}
    Unknown, Duplicate, BadOperand, OutOfRange, BadLine, BadName, BadTableLine, TypeMismatch,
    WrongDialect, WrongKind,
);
