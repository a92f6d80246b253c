//! The front-end toolkit both dialects' parsers are built on: the token with its span, the
//! lexer core over a dialect's logos token kind and the split into lines ([`token`]); the
//! token-slice input for nom, the failure a dialect's grammar reports and the primitive parsers
//! ([`input`]); the parse errors both dialects report alike ([`error`]); the tally that decides
//! a file's mnemonic set ([`votes`]); and the close spelling an unknown operation is offered
//! ([`close_spelling`]). Each dialect keeps only its token kinds, its own error variants and
//! its grammar.

pub mod error;
pub mod input;
pub mod token;
pub mod votes;

pub use input::{Failure, Grammar, Parsed, Tokens};
pub use token::{Context, Kind, Token};

/// The operation word of `words` closest to the unknown `upper` that starts with the same
/// letter (`JUU` → `JU`, but `XG` is no `G`): one edit away, two for a word of four letters
/// or more.
pub fn close_spelling(
    upper: &str,
    words: impl Iterator<Item = &'static str>,
) -> Option<&'static str> {
    words
        .filter(|candidate| candidate.chars().next() == upper.chars().next())
        .map(|candidate| (strsim::damerau_levenshtein(upper, candidate), candidate))
        .filter(|(distance, candidate)| *distance <= 1 + usize::from(candidate.len() > 3))
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, candidate)| candidate)
}
