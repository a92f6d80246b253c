//! The tally that decides a file's mnemonic set from the words only one set has.

use crate::mnemonics::MnemonicSet;
use crate::source::Span;

use super::token::Token;

/// Each set's count of words only it has, and its first such word.
#[derive(Debug, Default)]
pub struct Votes {
    votes: [(usize, Option<Span>); 2],
}

impl Votes {
    /// One word of `set` only.
    pub fn vote<K: Copy>(&mut self, set: MnemonicSet, token: Token<K>) {
        let slot = &mut self.votes[set as usize];
        slot.0 += 1;
        slot.1.get_or_insert(token.span(0));
    }

    /// The set with more such words (English on a tie), and the span of its first word in
    /// file 0; `None` without any.
    pub fn winner(self) -> Option<(MnemonicSet, Span)> {
        let [english, german] = self.votes;
        match (english, german) {
            ((0, _), (0, _)) => None,
            ((e, Some(span)), (g, _)) if e >= g => Some((MnemonicSet::English, span)),
            (_, (_, Some(span))) => Some((MnemonicSet::German, span)),
            _ => None,
        }
    }
}
