//! A STEP 5 parse error on a line that holds a word only STEP 7 writes, said as such.

use crate::dialect;
use crate::mnemonics::MnemonicSet;

use super::ParseError;

/// The error said as a STEP 7 word where its line holds one (what STEP 5 writes instead, and
/// `--dialect s7` for a STEP 7 text). Other errors come back as they are.
pub fn explain_step7_word(source: &str, set: MnemonicSet, error: ParseError) -> ParseError {
    let explained = matches!(
        error,
        ParseError::UnexpectedCharacter { .. }
            | ParseError::UnknownOperation { .. }
            | ParseError::UnknownOperand { .. }
            | ParseError::MissingOperand { .. }
            | ParseError::UnexpectedToken { .. }
            | ParseError::BadAddress { .. }
            // `==I` reads in STEP 5 as `=` to a formal operand `=I`.
            | ParseError::FormalsFromUse { .. }
    );
    let span = error.span();
    if !explained {
        return error;
    }
    let Some(dialect::Step7Word { evidence, help }) =
        dialect::step7_word_on_line(source, set, span.start as usize)
    else {
        return error;
    };
    ParseError::Step7Word {
        word: source[evidence.start as usize..evidence.end as usize].to_string(),
        at: evidence.span(span.file),
        what: evidence.what,
        help,
    }
}
