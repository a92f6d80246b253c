//! Errors of the STEP 7 lexer and parser. Each variant has a stable code documented in
//! `grammar/errors.md`; spans only, the source is attached when they are printed.

use miette::Diagnostic;

use crate::source::Span;

crate::syntax::error::parse_errors! {
    pub enum S7ParseError {
        #[diagnostic(
            code(awl::s7::unexpected_character),
            help(
                "STEP 7 statements hold an optional label, an operation and an operand, and end with `;`; comments start with `//`"
            )
        )]
        UnexpectedCharacter,
        #[diagnostic(code(awl::s7::unknown_operation))]
        UnknownOperation,
        #[diagnostic(code(awl::s7::mixed_mnemonics))]
        MixedMnemonics,
        #[diagnostic(code(awl::s7::unknown_operand))]
        UnknownOperand,
        #[diagnostic(code(awl::s7::missing_operand))]
        MissingOperand,
        #[diagnostic(code(awl::s7::unexpected_token))]
        UnexpectedToken,
        #[diagnostic(code(awl::s7::constant_range))]
        ConstantRange,

        #[error("bad address `{text}`")]
        #[diagnostic(code(awl::s7::bad_address))]
        BadAddress {
            text: String,
            #[label("{expected}")]
            at: Span,
            expected: String,
        },

        #[error("bad {format} constant")]
        #[diagnostic(code(awl::s7::bad_constant))]
        BadConstant {
            format: String,
            #[label("expected {expected}")]
            at: Span,
            expected: String,
        },

        #[error("bad declaration")]
        #[diagnostic(
            code(awl::s7::bad_declaration),
            help(
                "declarations look like `speed : INT;` or `speed : INT := 5;`, one per line between `VAR_INPUT` (`VAR_OUTPUT`, `VAR_IN_OUT`, `VAR`, `VAR_TEMP`) and `END_VAR`"
            )
        )]
        BadDeclaration {
            #[label("{reason}")]
            at: Span,
            reason: String,
        },

        #[error("unknown data type `{word}`")]
        #[diagnostic(code(awl::s7::unknown_type))]
        UnknownType {
            word: String,
            #[label("not a STEP 7 data type")]
            at: Span,
            #[help]
            help: Option<String>,
        },

        #[error("`{keyword}` has no `{end}`")]
        #[diagnostic(code(awl::s7::unclosed_block))]
        UnclosedBlock {
            keyword: String,
            end: String,
            #[label("opened here")]
            at: Span,
            #[help]
            help: String,
        },

        #[error("`{found}` ends a block that `{opened}` did not open")]
        #[diagnostic(code(awl::s7::mismatched_end))]
        MismatchedEnd {
            found: String,
            opened: String,
            #[label("expected `{expected}`")]
            at: Span,
            expected: String,
        },

        #[error("text outside a block")]
        #[diagnostic(
            code(awl::s7::outside_block),
            help(
                "a STEP 7 source holds blocks: `ORGANIZATION_BLOCK`, `FUNCTION`, `FUNCTION_BLOCK`, `DATA_BLOCK` or `TYPE`, each up to its `END_…`"
            )
        )]
        OutsideBlock {
            #[label("this belongs to no block")]
            at: Span,
        },

        #[error("block number {number} is out of range")]
        #[diagnostic(code(awl::s7::block_number), help("block numbers run from 0 to 65535"))]
        BlockNumber {
            number: String,
            #[label("0…65535 expected")]
            at: Span,
        },

        #[error("label `{label}` is longer than 4 characters")]
        #[diagnostic(
            code(awl::s7::bad_label),
            help(
                "STEP 7 labels have at most 4 characters (letters, digits, `_`), the first not a digit, such as `M001` or `LOOP`"
            )
        )]
        BadLabel {
            label: String,
            #[label("too long")]
            at: Span,
        },

        #[error("{what} is STEP 5, not STEP 7")]
        #[diagnostic(code(awl::s7::step5_spelling))]
        Step5Spelling {
            what: String,
            #[label("STEP 5 spelling")]
            at: Span,
            #[help]
            help: String,
        },

        #[error("read as STEP 7 STL, not STEP 5")]
        #[diagnostic(code(awl::dialect::read_as_step7), severity(Advice))]
        ReadAsStep7 {
            #[label("{reason}")]
            at: Span,
            reason: String,
            #[help]
            help: String,
        },

        #[error("`{word}` is an awlsim test extension")]
        #[diagnostic(
            code(awl::s7::extension_not_enabled),
            help("awlsim test extension: run it with `awl conformance` or `--extended`")
        )]
        ExtensionNotEnabled {
            word: String,
            #[label("only with the test extensions")]
            at: Span,
        },
    }
}

impl S7ParseError {
    /// The code, for tests and tools.
    pub fn stable_code(&self) -> String {
        Diagnostic::code(self).map_or_else(String::new, |code| code.to_string())
    }
}
