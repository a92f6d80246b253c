//! Tokens with byte spans, and the lexer core both dialects' lexers run (logos).

use logos::Logos;

use crate::source::{FileId, Span};

/// A dialect's token kind, with the one its characters no token starts with become.
pub trait Kind: Copy + PartialEq + std::fmt::Debug {
    const INVALID: Self;
}

/// One token: its kind (a STEP 5 or a STEP 7 one) and where it stands in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Token<K> {
    pub kind: K,
    pub start: u32,
    pub end: u32,
}

impl<K: Copy> Token<K> {
    pub fn text(self, source: &str) -> &str {
        &source[self.start as usize..self.end as usize]
    }

    /// True when `next` starts right where this token ends (`A(`, `:F`, `I0.1`).
    pub fn touches(self, next: Token<K>) -> bool {
        self.end == next.start
    }

    /// Where the token stands in `file`.
    pub fn span(self, file: FileId) -> Span {
        Span {
            file,
            start: self.start,
            end: self.end,
        }
    }

    /// The span from this token to `last`, inclusive.
    pub fn span_to(self, last: Token<K>, file: FileId) -> Span {
        Span {
            file,
            start: self.start,
            end: last.end.max(self.end),
        }
    }
}

/// What a dialect's parsers read their tokens against besides the tokens: the file's text and
/// number, and its mnemonic set.
#[derive(Debug, Clone, Copy)]
pub struct Context<'a> {
    pub source: &'a str,
    pub file: FileId,
    pub set: crate::mnemonics::MnemonicSet,
}

impl<'a> Context<'a> {
    pub fn text<K: Copy>(&self, token: Token<K>) -> &'a str {
        token.text(self.source)
    }

    pub fn span<K: Copy>(&self, token: Token<K>) -> Span {
        token.span(self.file)
    }

    /// The span from `first` to `last`, inclusive.
    pub fn span_of<K: Copy>(&self, first: Token<K>, last: Token<K>) -> Span {
        first.span_to(last, self.file)
    }
}

/// The runs of tokens between those whose kind `ends` a line or a statement; empty runs are
/// left out.
pub fn runs<K: Copy>(
    tokens: &[Token<K>],
    ends: impl Fn(K) -> bool,
) -> impl Iterator<Item = &[Token<K>]> {
    tokens
        .split(move |token| ends(token.kind))
        .filter(|run| !run.is_empty())
}

/// Splits a whole file into tokens. Characters that start no token become [`Kind::INVALID`].
pub fn lex<'s, K>(source: &'s str) -> Vec<Token<K>>
where
    K: Kind + Logos<'s, Source = str>,
    K::Extras: Default,
{
    let mut lexer = K::lexer(source);
    let mut tokens = Vec::with_capacity(source.len() / 3);
    while let Some(result) = lexer.next() {
        let span = lexer.span();
        tokens.push(Token {
            kind: result.unwrap_or(K::INVALID),
            start: span.start as u32,
            end: span.end as u32,
        });
    }
    tokens
}

/// The glue of a dialect's lexer module around its `TokenKind` (which has an `Invalid`
/// variant): its `Token`, the kind characters no token starts with become, its `lex` and,
/// for its tests, `kinds`.
macro_rules! dialect_lexer {
    ($dialect:literal) => {
        #[doc = concat!("One ", $dialect, " token: its kind and where it stands in the file.")]
        pub type Token = $crate::syntax::Token<TokenKind>;

        impl $crate::syntax::Kind for TokenKind {
            const INVALID: Self = TokenKind::Invalid;
        }

        /// Splits a whole file into tokens. Characters that start no token become
        /// [`TokenKind::Invalid`].
        pub fn lex(source: &str) -> Vec<Token> {
            $crate::syntax::token::lex(source)
        }

        /// The kinds of the tokens of `source`.
        #[cfg(test)]
        fn kinds(source: &str) -> Vec<TokenKind> {
            lex(source).into_iter().map(|token| token.kind).collect()
        }
    };
}
pub(crate) use dialect_lexer;
