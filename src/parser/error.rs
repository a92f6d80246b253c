//! Errors of the lexer and parser. Each variant has a stable code documented in `grammar/errors.md`.

use crate::source::Span;

crate::syntax::error::parse_errors! {
    pub enum ParseError {
        #[diagnostic(
            code(awl::lex::unexpected_character),
            help(
                "STL lines hold an optional label, an operation and an operand; comments start with `;` or `//`"
            )
        )]
        UnexpectedCharacter,
        #[diagnostic(code(awl::parse::unknown_operation))]
        UnknownOperation,
        #[diagnostic(code(awl::parse::mixed_mnemonics))]
        MixedMnemonics,
        #[diagnostic(code(awl::parse::unknown_operand))]
        UnknownOperand,
        #[diagnostic(code(awl::parse::missing_operand))]
        MissingOperand,
        #[diagnostic(code(awl::parse::unexpected_token))]
        UnexpectedToken,
        #[diagnostic(code(awl::check::constant_range))]
        ConstantRange,

        #[error("bad address for `{area}`")]
        #[diagnostic(code(awl::parse::bad_address))]
        BadAddress {
            area: String,
            #[label("{expected}")]
            at: Span,
            expected: String,
        },

        #[error("statement outside a block")]
        #[diagnostic(
            code(awl::parse::outside_block),
            help("start a block with a header line such as `PB 3`, or remove what follows `BE`")
        )]
        OutsideBlock {
            #[label("this line belongs to no block")]
            at: Span,
        },

        #[error("block number {number} is out of range")]
        #[diagnostic(
            code(awl::parse::block_number),
            help("block numbers run from 0 to 255")
        )]
        BlockNumber {
            number: String,
            #[label("0…255 expected")]
            at: Span,
        },

        #[error("bad {format} constant")]
        #[diagnostic(code(awl::parse::bad_constant))]
        BadConstant {
            format: String,
            #[label("{expected}")]
            at: Span,
            expected: String,
        },

        #[error("a constant needs its format: `{op} {constant}`")]
        #[diagnostic(code(awl::parse::bare_constant))]
        BareConstant {
            op: String,
            constant: String,
            #[label("a number without a constant format")]
            at: Span,
            #[help]
            help: String,
        },

        #[error("bad parameter declaration")]
        #[diagnostic(
            code(awl::parse::bad_declaration),
            help(
                "write `DES :NAME KIND FORMAT`, e.g. `DES :EIN I BI`; kinds I Q D B T C, formats BI BY W or a constant format for D"
            )
        )]
        BadDeclaration {
            #[label("{reason}")]
            at: Span,
            reason: String,
        },

        #[error("bad data word")]
        #[diagnostic(
            code(awl::parse::bad_data_word),
            help("data block lines look like `0: KF +100` (word number, colon, constant)")
        )]
        BadDataWord {
            #[label("{reason}")]
            at: Span,
            reason: String,
        },

        #[error("this is STEP 7 STL (S7), not STEP 5")]
        #[diagnostic(
            code(awl::parse::step7_source),
            help(
                "the text was read as STEP 5 because the dialect was given as STEP 5: read it with `--dialect s7` (a scenario's `dialect = \"s7\"`), or leave the dialect out and awl tells STEP 7 sources by their words; nothing else in this file was checked"
            )
        )]
        Step7Source {
            #[label("{what}")]
            at: Span,
            what: &'static str,
        },

        #[error("`{word}` is STEP 7, not STEP 5")]
        #[diagnostic(code(awl::parse::step7_word))]
        Step7Word {
            word: String,
            #[label("{what}")]
            at: Span,
            what: &'static str,
            #[help]
            help: String,
        },

        #[error("statements before any block header are taken as {block}")]
        #[diagnostic(code(awl::parse::fragment), severity(Advice))]
        Fragment {
            block: String,
            #[label("{block} starts here")]
            at: Span,
            #[help]
            help: String,
        },

        #[error("`KG` as a plain decimal: the PG writes it `KG {pg_form}`")]
        #[diagnostic(
            code(awl::parse::decimal_float),
            severity(Warning),
            help(
                "awl reads the decimal as its value; the PG's form is ±mantissa±exponent, seven \
                 mantissa digits read as 0.ddddddd times ten to the exponent (CPU 928B programming \
                 guide, 2.2)"
            )
        )]
        DecimalFloat {
            #[label("the PG writes `{pg_form}`")]
            at: Span,
            pg_form: String,
        },

        #[error("formal operands declared from their use: {list}")]
        #[diagnostic(code(awl::parse::formals_from_use), severity(Advice))]
        FormalsFromUse {
            list: String,
            first: String,
            #[label("`={first}` first used here")]
            at: Span,
            #[help]
            help: String,
        },
    }
}
