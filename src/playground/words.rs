//! The words the page's editor colours, taken from the tables the parser reads, so the colours
//! follow the language of both mnemonic sets.

use serde::Serialize;

use crate::mnemonics::{
    AREAS, BlockKind, CONSTANTS, DECLARATION_DE, DECLARATION_EN, NAME_WORD, OPERATIONS,
};

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
}

pub fn words() -> Words {
    let both = |pairs: &mut dyn Iterator<Item = (&'static str, &'static str)>| {
        let mut words: Vec<&'static str> = pairs.flat_map(|(en, de)| [en, de]).collect();
        words.sort_unstable();
        words.dedup();
        words
    };
    Words {
        operations: both(&mut OPERATIONS.iter().map(|info| (info.en, info.de))),
        areas: both(&mut AREAS.iter().map(|info| (info.en, info.de))),
        constants: both(&mut CONSTANTS.iter().map(|info| (info.en, info.de))),
        blocks: BlockKind::ALL.iter().map(|kind| kind.name()).collect(),
        keywords: vec![NAME_WORD, DECLARATION_EN, DECLARATION_DE],
    }
}
