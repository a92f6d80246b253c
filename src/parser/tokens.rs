//! The STEP 5 names of the front-end toolkit's token input and failure, and the primitive token
//! parsers the line grammar is built from.

use crate::lexer::{Token, TokenKind};

use super::error::ParseError;

crate::syntax::input::dialect_grammar!("STEP 5", ParseError, LineError, LineResult);

/// What the line parsers need besides the tokens.
pub type Context<'a> = crate::syntax::Context<'a>;

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
    crate::syntax::input::at_end(input, "end of line")
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
