//! The STEP 7 lexer (logos): words, numbers, typed literals (`W#16#00FF`, `S5T#2S`), locals
//! (`#speed`), symbols (`"Motor"`), strings and punctuation, with byte spans. `//` comments are
//! skipped; line ends and `;` are tokens because a statement ends at either.

use logos::Logos;

#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\f\x0B\r]+")]
pub enum Tok {
    #[regex(r"//[^\n]*", logos::skip, allow_greedy = true)]
    Comment,
    #[token("\n")]
    Newline,
    #[token(";")]
    Semicolon,
    #[regex(r#""[^"\n]*""#)]
    Symbol,
    #[regex(r"'[^'\n]*'")]
    Quoted,
    #[regex(r"#[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    Local,
    /// `B#16#FF`, `S5T#2S`, `L#-5`, `DT#1990-01-01-00:00:00.000`, `P#M`, `B#` (before `(`).
    #[regex(r"[A-Za-z0-9_]+#[A-Za-z0-9_:.+\-#]*", priority = 5)]
    Typed,
    #[regex(r"[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    Word,
    #[regex(r"[0-9]+(\.[0-9]+)?([eE][+\-]?[0-9]+)?")]
    Number,
    #[token(":=")]
    Assign,
    #[token(":")]
    Colon,
    #[token(",")]
    Comma,
    #[token("..")]
    Range,
    #[token(".")]
    Dot,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[regex(r"==|<>|>=|<=|[<>=+\-*/]")]
    Operator,
    Invalid,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Token {
    pub kind: Tok,
    pub start: u32,
    pub end: u32,
}

impl Token {
    pub fn text(self, source: &str) -> &str {
        &source[self.start as usize..self.end as usize]
    }

    pub fn touches(self, next: Token) -> bool {
        self.end == next.start
    }

    pub fn is(self, source: &str, word: &str) -> bool {
        matches!(self.kind, Tok::Word) && self.text(source).eq_ignore_ascii_case(word)
    }
}

/// The tokens of a text; what no token matches is an `Invalid` token.
pub fn lex(source: &str) -> Vec<Token> {
    let mut lexer = Tok::lexer(source);
    let mut tokens = Vec::new();
    while let Some(kind) = lexer.next() {
        let span = lexer.span();
        tokens.push(Token {
            kind: kind.unwrap_or(Tok::Invalid),
            start: span.start as u32,
            end: span.end as u32,
        });
    }
    tokens
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(text: &str) -> Vec<(Tok, &str)> {
        lex(text)
            .into_iter()
            .map(|t| (t.kind, t.text(text)))
            .collect()
    }

    #[test]
    fn typed_literals_locals_and_symbols_are_single_tokens() {
        assert_eq!(
            kinds("L W#16#00FF; T #speed // note\n"),
            vec![
                (Tok::Word, "L"),
                (Tok::Typed, "W#16#00FF"),
                (Tok::Semicolon, ";"),
                (Tok::Word, "T"),
                (Tok::Local, "#speed"),
                (Tok::Newline, "\n"),
            ]
        );
        assert_eq!(
            kinds("CALL \"Motor\" L DT#1990-01-01-00:00:00.000 ==I"),
            vec![
                (Tok::Word, "CALL"),
                (Tok::Symbol, "\"Motor\""),
                (Tok::Word, "L"),
                (Tok::Typed, "DT#1990-01-01-00:00:00.000"),
                (Tok::Operator, "=="),
                (Tok::Word, "I"),
            ]
        );
    }
}
