//! The token-slice input for nom 8 (which has no `Input` impl for token slices), the failure
//! both dialects' parsers return, and the primitive parsers their grammars are built from.

use nom::error::ErrorKind;
use nom::{IResult, Needed};

use super::token::{Kind, Token};

/// A token kind a dialect's grammar parses, with the error that grammar reports.
pub trait Grammar: Kind {
    type Error: Clone + PartialEq + std::fmt::Debug;
}

/// A run of tokens as nom input: the tokens of a STEP 5 line or of a STEP 7 statement.
#[derive(Debug, Clone, Copy)]
pub struct Tokens<'a, K> {
    pub tokens: &'a [Token<K>],
}

impl<'a, K: Copy> Tokens<'a, K> {
    pub fn new(tokens: &'a [Token<K>]) -> Self {
        Tokens { tokens }
    }

    pub fn first(&self) -> Option<Token<K>> {
        self.tokens.first().copied()
    }

    pub fn second(&self) -> Option<Token<K>> {
        self.tokens.get(1).copied()
    }

    pub fn is_empty(&self) -> bool {
        self.tokens.is_empty()
    }

    pub fn skip(&self, count: usize) -> Self {
        Tokens {
            tokens: &self.tokens[count.min(self.tokens.len())..],
        }
    }
}

impl<'a, K: Copy> nom::Input for Tokens<'a, K> {
    type Item = Token<K>;
    type Iter = std::iter::Copied<std::slice::Iter<'a, Token<K>>>;
    type IterIndices = std::iter::Enumerate<Self::Iter>;

    fn input_len(&self) -> usize {
        self.tokens.len()
    }

    fn take(&self, index: usize) -> Self {
        Tokens {
            tokens: &self.tokens[..index],
        }
    }

    fn take_from(&self, index: usize) -> Self {
        Tokens {
            tokens: &self.tokens[index..],
        }
    }

    fn take_split(&self, index: usize) -> (Self, Self) {
        let (prefix, suffix) = self.tokens.split_at(index);
        (Tokens { tokens: suffix }, Tokens { tokens: prefix })
    }

    fn position<P>(&self, predicate: P) -> Option<usize>
    where
        P: Fn(Self::Item) -> bool,
    {
        self.tokens.iter().position(|token| predicate(*token))
    }

    fn iter_elements(&self) -> Self::Iter {
        self.tokens.iter().copied()
    }

    fn iter_indices(&self) -> Self::IterIndices {
        self.iter_elements().enumerate()
    }

    fn slice_index(&self, count: usize) -> Result<usize, Needed> {
        if self.tokens.len() >= count {
            Ok(count)
        } else {
            Err(Needed::new(count - self.tokens.len()))
        }
    }
}

/// A failed parse: where it failed and, when known, the dialect's diagnostic to report.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure<K: Grammar> {
    /// The token the parser stopped at; `None` at the end of the input.
    pub at: Option<Token<K>>,
    pub expected: &'static str,
    pub diagnostic: Option<Box<K::Error>>,
}

impl<K: Grammar> Failure<K> {
    /// A failure that carries its diagnostic (no alternative is tried after it).
    pub fn with(diagnostic: K::Error) -> nom::Err<Self> {
        nom::Err::Failure(Failure {
            at: None,
            expected: "",
            diagnostic: Some(Box::new(diagnostic)),
        })
    }

    /// The failure of a nom error, whichever kind; running out of input expects "more".
    pub fn of(error: nom::Err<Self>) -> Self {
        match error {
            nom::Err::Error(failure) | nom::Err::Failure(failure) => failure,
            nom::Err::Incomplete(_) => Failure {
                at: None,
                expected: "more",
                diagnostic: None,
            },
        }
    }
}

impl<'a, K: Grammar> nom::error::ParseError<Tokens<'a, K>> for Failure<K> {
    fn from_error_kind(input: Tokens<'a, K>, _kind: ErrorKind) -> Self {
        Failure {
            at: input.first(),
            expected: "",
            diagnostic: None,
        }
    }

    fn append(_input: Tokens<'a, K>, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

/// What a parser over tokens of kind `K` returns.
pub type Parsed<'a, K, T> = IResult<Tokens<'a, K>, T, Failure<K>>;

/// A failure at the input's first token, saying what was expected there.
pub fn fail<K: Grammar>(input: Tokens<'_, K>, expected: &'static str) -> nom::Err<Failure<K>> {
    nom::Err::Error(Failure {
        at: input.first(),
        expected,
        diagnostic: None,
    })
}

/// One token of the given kind.
pub fn kind<'a, K: Grammar>(
    wanted: K,
    expected: &'static str,
) -> impl Fn(Tokens<'a, K>) -> Parsed<'a, K, Token<K>> {
    move |input: Tokens<'a, K>| match input.first() {
        Some(token) if token.kind == wanted => Ok((input.skip(1), token)),
        _ => Err(fail(input, expected)),
    }
}

/// Succeeds only at the end of the input; `expected` names that end.
pub fn at_end<'a, K: Grammar>(input: Tokens<'a, K>, expected: &'static str) -> Parsed<'a, K, ()> {
    if input.is_empty() {
        Ok((input, ()))
    } else {
        Err(fail(input, expected))
    }
}

/// The names a dialect's parsers use for the toolkit over its `TokenKind`: the token input
/// `Tokens`, the failure and the parse result (named as given), and the primitive parsers.
macro_rules! dialect_grammar {
    ($dialect:literal, $error:ty, $failure:ident, $result:ident) => {
        pub use $crate::syntax::input::{fail, kind};

        impl $crate::syntax::Grammar for TokenKind {
            type Error = $error;
        }

        #[doc = concat!("A run of ", $dialect, " tokens as nom input.")]
        pub type Tokens<'a> = $crate::syntax::Tokens<'a, TokenKind>;

        /// A failed parse: where it failed and, when known, the diagnostic to report.
        pub type $failure = $crate::syntax::Failure<TokenKind>;

        pub type $result<'a, T> = $crate::syntax::Parsed<'a, TokenKind, T>;
    };
}
pub(crate) use dialect_grammar;
