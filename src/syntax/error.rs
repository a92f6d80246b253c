//! The parse errors both dialects report alike: one message, label and fields for each,
//! declared once by [`parse_errors`]; each dialect names their codes (STEP 5's `awl::parse::…`,
//! STEP 7's `awl::s7::…`, which users see and must not change) and adds its own variants.

/// Declares a dialect's parse error enum: the shared variants, each given as its
/// `#[diagnostic(…)]` (code, and help where the dialects word it apart) and its name in this
/// order, then the dialect's own variants; every variant has its span in `at`.
macro_rules! parse_errors {
    (
        $(#[$attr:meta])*
        pub enum $name:ident {
            #[diagnostic($($unexpected_character:tt)*)] UnexpectedCharacter,
            #[diagnostic($($unknown_operation:tt)*)] UnknownOperation,
            #[diagnostic($($mixed_mnemonics:tt)*)] MixedMnemonics,
            #[diagnostic($($unknown_operand:tt)*)] UnknownOperand,
            #[diagnostic($($missing_operand:tt)*)] MissingOperand,
            #[diagnostic($($unexpected_token:tt)*)] UnexpectedToken,
            #[diagnostic($($constant_range:tt)*)] ConstantRange,
            $($(#[$($own_attr:tt)*])* $own:ident { $($own_field:tt)* },)*
        }
    ) => {
        $(#[$attr])*
        #[derive(Debug, Clone, ::thiserror::Error, ::miette::Diagnostic, PartialEq)]
        pub enum $name {
            #[error("unexpected character `{found}`")]
            #[diagnostic($($unexpected_character)*)]
            UnexpectedCharacter {
                found: String,
                #[label("no token starts with this character")]
                at: $crate::source::Span,
            },

            #[error("unknown operation `{word}`")]
            #[diagnostic($($unknown_operation)*)]
            UnknownOperation {
                word: String,
                #[label("not an operation of the {set} set")]
                at: $crate::source::Span,
                set: &'static str,
                #[help]
                help: Option<String>,
            },

            #[error("`{word}` is {word_set} mnemonic, but this file uses {file_set} mnemonics")]
            #[diagnostic($($mixed_mnemonics)*)]
            MixedMnemonics {
                word: String,
                word_set: &'static str,
                file_set: &'static str,
                #[label("{word_set} word")]
                at: $crate::source::Span,
                #[label("the file's set was decided by this word")]
                decided_by: Option<$crate::source::Span>,
                #[help]
                help: Option<String>,
            },

            #[error("unknown operand `{word}`")]
            #[diagnostic($($unknown_operand)*)]
            UnknownOperand {
                word: String,
                #[label("not an operand of the {set} set")]
                at: $crate::source::Span,
                set: &'static str,
                #[help]
                help: Option<String>,
            },

            #[error("`{op}` needs an operand")]
            #[diagnostic($($missing_operand)*)]
            MissingOperand {
                op: String,
                #[label("operand expected after this")]
                at: $crate::source::Span,
                #[help]
                help: Option<String>,
            },

            #[error("unexpected {found}")]
            #[diagnostic($($unexpected_token)*)]
            UnexpectedToken {
                found: String,
                #[label("expected {expected}")]
                at: $crate::source::Span,
                expected: String,
            },

            #[error("{format} constant out of range")]
            #[diagnostic($($constant_range)*)]
            ConstantRange {
                format: String,
                #[label("allowed: {range}")]
                at: $crate::source::Span,
                range: String,
            },

            $($(#[$($own_attr)*])* $own { $($own_field)* },)*
        }

        $crate::source::error_span!($name {}
            UnexpectedCharacter, UnknownOperation, MixedMnemonics, UnknownOperand,
            MissingOperand, UnexpectedToken, ConstantRange, $($own),*
        );
    };
}
pub(crate) use parse_errors;

/// The help a diagnostic offers, for the front end's tests.
#[cfg(test)]
pub(crate) fn help_text(diagnostic: &dyn miette::Diagnostic) -> String {
    diagnostic.help().expect("a help").to_string()
}
