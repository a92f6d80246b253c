//! The words the page's editor colours, taken from the tables the parser reads, so the colours
//! follow the language of both mnemonic sets.

use serde::Serialize;

use crate::dialect::STEP7_LINE_WORDS;
use crate::mnemonics::{
    AREAS, BlockKind, CONSTANTS, DECLARATION_DE, DECLARATION_EN, NAME_WORD, OPERATIONS,
};
use crate::step7::{mnemonics as s7, parser as s7_parser};

#[derive(Debug, Clone, Serialize)]
pub struct Words {
    /// Operations of both sets: `A`, `U`, `JU`, `SPA`, `BE`, …
    pub operations: Vec<&'static str>,
    /// Operand areas of both sets: `I`, `E`, `FW`, `MW`, …
    pub areas: Vec<&'static str>,
    /// Constant formats: `KF`, `KH`, …
    pub constants: Vec<&'static str>,
    /// Block kinds: `OB`, `PB`, …
    pub blocks: Vec<&'static str>,
    /// The words of an FB's header: `NAME`, `DES`, `BEZ`.
    pub keywords: Vec<&'static str>,
    pub step7: Step7Words,
}

/// STEP 7's words. A text is STEP 7 when a line opens with one of `line_words` or an `END_`
/// word, as awl's dialect detection has it; there `;` ends a statement and only `//` comments.
#[derive(Debug, Clone, Serialize)]
pub struct Step7Words {
    /// Operations of both sets: `A`, `U`, `JC`, `SPB`, `OPN`, `AUF`, …
    pub operations: Vec<&'static str>,
    /// Address areas of both sets: `I`, `E`, `DBW`, `PIW`, `PEW`, …
    pub areas: Vec<&'static str>,
    /// The source form's words and the data types: `FUNCTION`, `VAR_INPUT`, `BEGIN`, `INT`, …
    pub keywords: Vec<&'static str>,
    /// The words that open a line of a STEP 7 source only.
    pub line_words: Vec<&'static str>,
}

fn both(pairs: &mut dyn Iterator<Item = (&'static str, &'static str)>) -> Vec<&'static str> {
    let mut words: Vec<&'static str> = pairs.flat_map(|(en, de)| [en, de]).collect();
    words.sort_unstable();
    words.dedup();
    words
}

/// Words of the source form that neither open a line of their own nor are header words.
const STEP7_SECTION_WORDS: &[&str] = &["NETWORK", "TYPE", "OF", "VAR_IN_OUT", "RET_VAL"];

fn step7_words() -> Step7Words {
    let keywords = [
        STEP7_LINE_WORDS,
        s7_parser::HEADER_WORDS,
        s7_parser::TYPE_NAMES,
        STEP7_SECTION_WORDS,
    ];
    Step7Words {
        operations: both(&mut s7::OPERATIONS.iter().map(|info| (info.en, info.de))),
        areas: both(&mut s7::AREAS.iter().map(|info| (info.en, info.de))),
        keywords: keywords.concat(),
        line_words: STEP7_LINE_WORDS.to_vec(),
    }
}

pub fn words() -> Words {
    Words {
        operations: both(&mut OPERATIONS.iter().map(|info| (info.en, info.de))),
        areas: both(&mut AREAS.iter().map(|info| (info.en, info.de))),
        constants: both(&mut CONSTANTS.iter().map(|info| (info.en, info.de))),
        blocks: BlockKind::ALL.iter().map(|kind| kind.name()).collect(),
        keywords: vec![NAME_WORD, DECLARATION_EN, DECLARATION_DE],
        step7: step7_words(),
    }
}
