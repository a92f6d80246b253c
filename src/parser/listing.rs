//! The elements of a STEP 5 PG listing (the printout and its text export): trailing block
//! information (`PB 3   LAE=12`), segment headings (`SEGMENT 2   0004`, `NETZWERK 2`,
//! `NETWORK 2`), the statement address before the `:` (`0004  :U E 1.0`) and the segment end
//! `***`. A file may mix them with the plain form.

use crate::lexer::{Token, TokenKind};

use super::tokens::{Context, LineResult, Tokens, decimal, end_of_line, keyword, kind};

/// The words that open a segment heading, in both mnemonic sets.
pub const SEGMENT_WORDS: &[&str] = &["SEGMENT", "NETZWERK", "NETWORK"];

/// `LAE=12`, `LEN=12`: block information after a header, as many as there are.
pub fn header_information(input: Tokens<'_>) -> LineResult<'_, ()> {
    let mut rest = input;
    while let Some(first) = rest.first() {
        let pair = (first.kind == TokenKind::Word)
            .then(|| rest.tokens.get(1..3))
            .flatten()
            .filter(|pair| {
                pair[0].kind == TokenKind::Equals
                    && matches!(pair[1].kind, TokenKind::Number | TokenKind::Word)
            });
        if pair.is_none() {
            break;
        }
        rest = Tokens::new(&rest.tokens[3..]);
    }
    end_of_line(rest)
}

/// `SEGMENT 2` with the segment's optional start address; the segment's number.
pub fn segment_heading<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, u16> {
    move |input: Tokens<'a>| {
        let (rest, _) = keyword(context, SEGMENT_WORDS, "SEGMENT")(input)?;
        let (rest, (number, _)) = decimal(context, "the segment's number")(rest)?;
        let rest = match rest.first() {
            Some(address) if is_address(context, address) => Tokens::new(&rest.tokens[1..]),
            _ => rest,
        };
        let (rest, _) = end_of_line(rest)?;
        Ok((rest, number))
    }
}

/// `***` or `:***`, with the address before it already taken off.
pub fn segment_end(input: Tokens<'_>) -> LineResult<'_, ()> {
    let rest = match input.first() {
        Some(colon) if colon.kind == TokenKind::Colon => Tokens::new(&input.tokens[1..]),
        _ => input,
    };
    let (rest, _) = kind(TokenKind::SegmentEnd, "`***`")(rest)?;
    end_of_line(rest)
}

/// A lone `:`: an empty statement line of a PG printout.
pub fn empty_statement(line: &[Token]) -> bool {
    matches!(line, [colon] if colon.kind == TokenKind::Colon)
}

/// A hexadecimal statement address: `0000`, `001A` (a word of hex digits only when `words`).
fn is_hex_address(text: &str) -> bool {
    (1..=4).contains(&text.len()) && text.chars().all(|c| c.is_ascii_hexdigit())
}

fn is_address(context: Context<'_>, token: Token) -> bool {
    matches!(token.kind, TokenKind::Number | TokenKind::Word) && is_hex_address(context.text(token))
}

/// The line without its leading statement address. A number always is one (no statement
/// starts with a number); a word of hex digits (`A01F`) only in a file that has shown
/// addresses already, and only before a `:` or a label, since it could be a label itself.
pub fn without_address<'a>(context: Context<'a>, line: &'a [Token], listing: bool) -> &'a [Token] {
    let Some((first, rest)) = line.split_first() else {
        return line;
    };
    if !is_address(context, *first) || rest.is_empty() {
        return line;
    }
    let before_colon = |tokens: &[Token]| match tokens {
        [colon, ..] => colon.kind == TokenKind::Colon,
        _ => false,
    };
    let label_then_colon = |tokens: &[Token]| match tokens {
        [label, colon, ..] => label.kind == TokenKind::Word && colon.kind == TokenKind::Colon,
        _ => false,
    };
    match first.kind {
        TokenKind::Number => rest,
        _ if listing && (before_colon(rest) || label_then_colon(rest)) => rest,
        _ => line,
    }
}
