//! The token-slice input type for nom 8 (which has no `Input` impl for token slices) and the
//! primitive token parsers the line grammar is built from.

use nom::error::ErrorKind;
use nom::{IResult, Needed};

use crate::lexer::{Token, TokenKind};
use crate::source::{FileId, Span};

use super::error::ParseError;

/// A run of tokens as nom input (nom 8 has no `Input` for token slices): the tokens of a
/// STEP 5 line, or of a STEP 7 text with its own token type `T`.
#[derive(Debug, Clone, Copy)]
pub struct Tokens<'a, T = Token> {
    pub tokens: &'a [T],
}

impl<'a, T: Copy> Tokens<'a, T> {
    pub fn new(tokens: &'a [T]) -> Self {
        Tokens { tokens }
    }

    pub fn first(&self) -> Option<T> {
        self.tokens.first().copied()
    }

    pub fn is_empty(&self) -> bool {
        self.tokens.is_empty()
    }
}

impl<'a, T: Copy> nom::Input for Tokens<'a, T> {
    type Item = T;
    type Iter = std::iter::Copied<std::slice::Iter<'a, T>>;
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

/// A failed line parse: where it failed and, when known, the diagnostic to report.
#[derive(Debug, Clone, PartialEq)]
pub struct LineError {
    /// The token the parser stopped at; `None` at the end of the line.
    pub at: Option<Token>,
    pub expected: &'static str,
    pub diagnostic: Option<Box<ParseError>>,
}

impl LineError {
    pub fn diagnostic(diagnostic: ParseError) -> nom::Err<LineError> {
        nom::Err::Failure(LineError {
            at: None,
            expected: "",
            diagnostic: Some(Box::new(diagnostic)),
        })
    }
}

impl<'a> nom::error::ParseError<Tokens<'a>> for LineError {
    fn from_error_kind(input: Tokens<'a>, _kind: ErrorKind) -> Self {
        LineError {
            at: input.first(),
            expected: "",
            diagnostic: None,
        }
    }

    fn append(_input: Tokens<'a>, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

pub type LineResult<'a, T> = IResult<Tokens<'a>, T, LineError>;

/// What the line parsers need besides the tokens.
#[derive(Debug, Clone, Copy)]
pub struct Context<'a> {
    pub source: &'a str,
    pub file: FileId,
    pub set: crate::mnemonics::MnemonicSet,
}

impl<'a> Context<'a> {
    pub fn text(&self, token: Token) -> &'a str {
        token.text(self.source)
    }

    pub fn span(&self, token: Token) -> Span {
        Span {
            file: self.file,
            start: token.start,
            end: token.end,
        }
    }

    /// The span from `first` to `last`, inclusive.
    pub fn span_of(&self, first: Token, last: Token) -> Span {
        Span {
            file: self.file,
            start: first.start,
            end: last.end,
        }
    }
}

fn fail<'a>(input: Tokens<'a>, expected: &'static str) -> nom::Err<LineError> {
    nom::Err::Error(LineError {
        at: input.first(),
        expected,
        diagnostic: None,
    })
}

/// One token of the given kind.
pub fn kind<'a>(
    wanted: TokenKind,
    expected: &'static str,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, Token> {
    move |input: Tokens<'a>| match input.first() {
        Some(token) if token.kind == wanted => Ok((Tokens::new(&input.tokens[1..]), token)),
        _ => Err(fail(input, expected)),
    }
}

/// One token of the given kind that starts right where `previous` ends.
pub fn touching<'a>(
    previous: Token,
    wanted: TokenKind,
    expected: &'static str,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, Token> {
    move |input: Tokens<'a>| match input.first() {
        Some(token) if token.kind == wanted && previous.touches(token) => {
            Ok((Tokens::new(&input.tokens[1..]), token))
        }
        _ => Err(fail(input, expected)),
    }
}

/// A word equal (ignoring case) to one of `words`.
pub fn keyword<'a>(
    context: Context<'a>,
    words: &'static [&'static str],
    expected: &'static str,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, Token> {
    move |input: Tokens<'a>| match input.first() {
        Some(token)
            if token.kind == TokenKind::Word
                && words
                    .iter()
                    .any(|word| word.eq_ignore_ascii_case(context.text(token))) =>
        {
            Ok((Tokens::new(&input.tokens[1..]), token))
        }
        _ => Err(fail(input, expected)),
    }
}

/// Succeeds only at the end of the line.
pub fn end_of_line(input: Tokens<'_>) -> LineResult<'_, ()> {
    if input.is_empty() {
        Ok((input, ()))
    } else {
        Err(fail(input, "end of line"))
    }
}

/// A decimal number token that fits in `u16`.
pub fn decimal<'a>(
    context: Context<'a>,
    expected: &'static str,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, (u16, Token)> {
    move |input: Tokens<'a>| match input.first() {
        Some(token) if token.kind == TokenKind::Number => {
            match context.text(token).parse::<u16>() {
                Ok(value) => Ok((Tokens::new(&input.tokens[1..]), (value, token))),
                Err(_) => Err(fail(input, expected)),
            }
        }
        _ => Err(fail(input, expected)),
    }
}
