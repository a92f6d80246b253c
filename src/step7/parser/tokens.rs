//! The token-slice input for nom 8 over STEP 7 tokens (the STEP 5 parser's wrapper,
//! `crate::parser::tokens::Tokens`), and the primitive parsers the statement, operand and
//! declaration grammars are built from.

use std::cell::Cell;

use nom::IResult;
use nom::error::ErrorKind;

use crate::mnemonics::MnemonicSet;
use crate::source::{FileId, Span};
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};

/// A run of STEP 7 tokens, as nom input: the STEP 5 parser's wrapper over this lexer's tokens.
pub type Tokens<'a> = crate::parser::tokens::Tokens<'a, Token>;

impl<'a> Tokens<'a> {
    pub fn second(&self) -> Option<Token> {
        self.tokens.get(1).copied()
    }

    pub fn skip(&self, count: usize) -> Self {
        Tokens {
            tokens: &self.tokens[count.min(self.tokens.len())..],
        }
    }
}

/// A failed parse: where it failed and, when known, the diagnostic to report.
#[derive(Debug, Clone, PartialEq)]
pub struct Fail {
    /// The token the parser stopped at; `None` at the end of the input.
    pub at: Option<Token>,
    pub expected: &'static str,
    pub diagnostic: Option<Box<S7ParseError>>,
}

impl Fail {
    /// A failure that carries its diagnostic (no alternative is tried after it).
    pub fn with(diagnostic: S7ParseError) -> nom::Err<Fail> {
        nom::Err::Failure(Fail {
            at: None,
            expected: "",
            diagnostic: Some(Box::new(diagnostic)),
        })
    }
}

impl<'a> nom::error::ParseError<Tokens<'a>> for Fail {
    fn from_error_kind(input: Tokens<'a>, _kind: ErrorKind) -> Self {
        Fail {
            at: input.first(),
            expected: "",
            diagnostic: None,
        }
    }

    fn append(_input: Tokens<'a>, _kind: ErrorKind, other: Self) -> Self {
        other
    }
}

pub type PResult<'a, T> = IResult<Tokens<'a>, T, Fail>;

/// What the parsers need besides the tokens.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    pub source: &'a str,
    pub file: FileId,
    pub set: MnemonicSet,
    /// awlsim's test extensions are allowed.
    pub extensions: bool,
    /// The first word of the other mnemonic set met so far, and whether it stood in an
    /// operation's place.
    pub foreign: &'a Cell<Option<(Token, bool)>>,
}

impl<'a> Ctx<'a> {
    pub fn text(&self, token: Token) -> &'a str {
        token.text(self.source)
    }

    pub fn upper(&self, token: Token) -> String {
        self.text(token).to_ascii_uppercase()
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
            end: last.end.max(first.end),
        }
    }

    /// The span of the tokens consumed between `before` and `after`.
    pub fn consumed(&self, before: Tokens<'_>, after: Tokens<'_>) -> Span {
        let used = before.tokens.len() - after.tokens.len();
        match (before.tokens.first(), before.tokens.get(used.max(1) - 1)) {
            (Some(first), Some(last)) if used > 0 => self.span_of(*first, *last),
            (Some(first), _) => Span {
                file: self.file,
                start: first.start,
                end: first.start,
            },
            _ => Span {
                file: self.file,
                start: 0,
                end: 0,
            },
        }
    }

    /// Notes a word of the other mnemonic set (the first one is reported).
    pub fn foreign_word(&self, token: Token, operation: bool) {
        if self.foreign.get().is_none() {
            self.foreign.set(Some((token, operation)));
        }
    }

    /// The word of a token, when it is one, in upper case.
    pub fn word(&self, token: Token) -> Option<String> {
        (token.kind == TokenKind::Word).then(|| self.upper(token))
    }
}

pub fn fail(input: Tokens<'_>, expected: &'static str) -> nom::Err<Fail> {
    nom::Err::Error(Fail {
        at: input.first(),
        expected,
        diagnostic: None,
    })
}

/// One token of the given kind.
pub fn kind<'a>(
    wanted: TokenKind,
    expected: &'static str,
) -> impl Fn(Tokens<'a>) -> PResult<'a, Token> {
    move |input: Tokens<'a>| match input.first() {
        Some(token) if token.kind == wanted => Ok((input.skip(1), token)),
        _ => Err(fail(input, expected)),
    }
}

/// A decimal number without fraction, as `i64`.
pub fn integer<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, (i64, Token)> {
    move |input: Tokens<'a>| match input.first() {
        Some(token) if token.kind == TokenKind::Number => {
            let digits: String = ctx.text(token).chars().filter(|c| *c != '_').collect();
            match digits.parse::<i64>() {
                Ok(value) => Ok((input.skip(1), (value, token))),
                Err(_) => Err(fail(input, "a whole number")),
            }
        }
        _ => Err(fail(input, "a number")),
    }
}

/// An integer with an optional sign before it.
pub fn signed_integer<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, (i64, Token)> {
    move |input: Tokens<'a>| {
        let (rest, negative) = match input.first().map(|t| t.kind) {
            Some(TokenKind::Minus) => (input.skip(1), true),
            Some(TokenKind::Plus) => (input.skip(1), false),
            _ => (input, false),
        };
        let (rest, (value, token)) = integer(ctx)(rest)?;
        Ok((rest, (if negative { -value } else { value }, token)))
    }
}

/// Succeeds only at the end of the input.
pub fn end(input: Tokens<'_>) -> PResult<'_, ()> {
    if input.is_empty() {
        Ok((input, ()))
    } else {
        Err(fail(input, "the end of the statement"))
    }
}

/// A word split into its letters and the digits after them: `MW10` → (`MW`, `10`),
/// `DB5` → (`DB`, `5`); `None` when the word holds no digits after letters.
pub fn letters_and_digits(upper: &str) -> Option<(&str, &str)> {
    let split = upper.find(|c: char| c.is_ascii_digit())?;
    let (letters, digits) = upper.split_at(split);
    (split > 0 && digits.chars().all(|c| c.is_ascii_digit())).then_some((letters, digits))
}
