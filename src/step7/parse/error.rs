//! STEP 7 parse errors. Each has a stable code documented in `grammar/errors.md`.

use miette::Diagnostic;
use thiserror::Error;

use crate::source::Span;

#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum S7ParseError {
    #[error("unknown STEP 7 operation `{word}`")]
    #[diagnostic(code(awl::s7::unknown_operation))]
    UnknownOperation {
        word: String,
        #[label("not an operation of the {set} mnemonics")]
        at: Span,
        set: &'static str,
        #[help]
        help: Option<String>,
    },

    #[error("`{text}` is not an operand of `{op}`")]
    #[diagnostic(code(awl::s7::bad_operand))]
    BadOperand {
        text: String,
        op: String,
        #[label("{problem}")]
        at: Span,
        problem: String,
        #[help]
        help: Option<String>,
    },

    #[error("bad constant: {problem}")]
    #[diagnostic(code(awl::s7::bad_constant))]
    BadConstant {
        problem: String,
        #[label("here")]
        at: Span,
    },

    #[error("{what}")]
    #[diagnostic(code(awl::s7::syntax))]
    Syntax {
        what: String,
        #[label("{expected}")]
        at: Span,
        expected: String,
    },

    #[error("{block} has no `{end}`")]
    #[diagnostic(
        code(awl::s7::unclosed_block),
        help("end the block with `{end}` before the next block starts")
    )]
    UnclosedBlock {
        block: String,
        end: &'static str,
        #[label("this block is not closed")]
        at: Span,
    },

    #[error("`{word}` is STEP 5, not STEP 7")]
    #[diagnostic(code(awl::s7::step5_spelling))]
    Step5Spelling {
        word: String,
        #[label("a STEP 5 spelling")]
        at: Span,
        #[help]
        help: String,
    },

    #[error("`{word}` is {other} mnemonic in a file written in {set} mnemonics")]
    #[diagnostic(
        code(awl::s7::mixed_mnemonics),
        help(
            "a file uses one mnemonic set; write `{suggestion}` or choose the set with `--mnemonics`"
        )
    )]
    MixedMnemonics {
        word: String,
        other: &'static str,
        set: &'static str,
        suggestion: String,
        #[label("from the other set")]
        at: Span,
    },

    #[error("`{word}` is an awlsim test instruction")]
    #[diagnostic(
        code(awl::s7::extension_not_enabled),
        help("run the file with `awl conformance`, or pass `--extended`")
    )]
    ExtensionNotEnabled {
        word: String,
        #[label("only with the test extensions")]
        at: Span,
    },
}

impl S7ParseError {
    pub fn span(&self) -> Span {
        match self {
            S7ParseError::UnknownOperation { at, .. }
            | S7ParseError::BadOperand { at, .. }
            | S7ParseError::BadConstant { at, .. }
            | S7ParseError::Syntax { at, .. }
            | S7ParseError::UnclosedBlock { at, .. }
            | S7ParseError::Step5Spelling { at, .. }
            | S7ParseError::MixedMnemonics { at, .. }
            | S7ParseError::ExtensionNotEnabled { at, .. } => *at,
        }
    }
}
