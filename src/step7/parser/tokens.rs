//! The STEP 7 names of the front-end toolkit's token input and failure, and the primitive
//! parsers the statement, operand and declaration grammars are built from.

use std::cell::Cell;

use crate::source::Span;
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};

crate::syntax::input::dialect_grammar!("STEP 7", S7ParseError, Fail, PResult);

/// What the parsers need besides the tokens: the front end's [`crate::syntax::Context`] (its
/// fields and methods are the `Ctx`'s) and what only STEP 7 reads.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    pub context: crate::syntax::Context<'a>,
    /// awlsim's test extensions are allowed.
    pub extensions: bool,
    /// The first word of the other mnemonic set met so far, and whether it stood in an
    /// operation's place.
    pub foreign: &'a Cell<Option<(Token, bool)>>,
}

impl<'a> std::ops::Deref for Ctx<'a> {
    type Target = crate::syntax::Context<'a>;

    fn deref(&self) -> &Self::Target {
        &self.context
    }
}

impl<'a> Ctx<'a> {
    pub fn upper(&self, token: Token) -> String {
        self.text(token).to_ascii_uppercase()
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
    crate::syntax::input::at_end(input, "the end of the statement")
}

/// A word split into its letters and the digits after them: `MW10` → (`MW`, `10`),
/// `DB5` → (`DB`, `5`); `None` when the word holds no digits after letters.
pub fn letters_and_digits(upper: &str) -> Option<(&str, &str)> {
    let split = upper.find(|c: char| c.is_ascii_digit())?;
    let (letters, digits) = upper.split_at(split);
    (split > 0 && digits.chars().all(|c| c.is_ascii_digit())).then_some((letters, digits))
}
