//! Lexer of STEP 7 STL text: tokens with byte spans (logos).
//!
//! Like the STEP 5 lexer it knows no mnemonics: words stay words and the parser gives them
//! meaning per mnemonic set. Typed constants (`W#16#FF`, `S5T#2S`, `DT#1990-01-01-00:00:00`)
//! are one token each; an area pointer's address (`P#M 1.0`) follows its `P#…` token. `//`
//! comments and blanks are skipped; line ends are tokens because a statement may end at one.

use logos::Logos;

#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\f\x0B\u{A0}]+")]
pub enum TokenKind {
    #[regex(r"//[^\n]*", logos::skip, allow_greedy = true)]
    Comment,
    #[regex(r"\r?\n|\r")]
    Newline,
    /// A keyword, mnemonic, area or name (ASCII and the ISO-8859-1 letters old exports write): `FUNCTION`, `A`, `JU`, `DBX`, `MW10`, `M001`.
    #[regex(r"[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    Word,
    /// awlsim's `__ASSERT==` and its other comparisons.
    #[regex(r"__[Aa][Ss][Ss][Ee][Rr][Tt](==|<>|>=|<=|>|<)")]
    Assert,
    /// Digits, with a fraction and exponent for a REAL: `10`, `0.1`, `1.5e10`, `1_000`.
    #[regex(r"[0-9][0-9_]*(\.[0-9]+)?([eE][+\-]?[0-9]+)?")]
    Number,
    /// A typed constant: `W#16#FF`, `L#-5`, `S5T#1M2S`, `T#-1D`, `16#FF`, `2#1010_0101`,
    /// `DT#1990-1-1-0:0:0.0`, `P#M` (its address follows), `B#` (before `(1, 2)`).
    #[regex(r"[A-Za-z0-9_]+#[A-Za-z0-9_.:+\-#]*")]
    Typed,
    /// `+I`, `-D`, `*R`, `/I`, `+AR1`: arithmetic written with its sign.
    #[regex(r"[+\-*/][A-Za-z][A-Za-z0-9]*")]
    SignedWord,
    /// A comparison with what it compares: `==I`, `>=D`, `<>R`, or a status condition `==0`,
    /// `>0`, `<>0`.
    #[regex(r"(==|<>|>=|<=|>|<)[A-Za-z0-9]")]
    Compare,
    /// `#speed`: a block-local name.
    #[regex(r"#[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    Local,
    /// `"Motor"`: a symbol of the symbol table.
    #[regex(r#""[^"\r\n]*""#)]
    Symbol,
    /// `'A'`, `'text'`: a character or string constant (`$'` is a quote inside it).
    #[regex(r"'([^'\r\n$]|\$[^\r\n])*'")]
    Quoted,
    #[token(":=")]
    Assign,
    #[token(":")]
    Colon,
    #[token(";")]
    Semicolon,
    #[token("..")]
    Range,
    #[token(".")]
    Dot,
    #[token(",")]
    Comma,
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
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("=")]
    Equals,
    /// A character no token starts with; reported where a statement holds it.
    Invalid,
}

crate::syntax::token::dialect_lexer!("STEP 7");

#[cfg(test)]
mod tests {
    use super::*;
    use TokenKind::*;

    #[test]
    fn statements_with_addresses_and_comments() {
        assert_eq!(
            kinds("  A I 0.1; // c\r\n"),
            [Word, Word, Number, Semicolon, Newline]
        );
        assert_eq!(kinds("L DB5.DBW 4"), [Word, Word, Dot, Word, Number]);
        assert_eq!(kinds("A I0.1"), [Word, Word, Dot, Number]);
    }

    #[test]
    fn typed_constants_are_one_token() {
        for text in [
            "W#16#FF",
            "L#-5",
            "S5T#__1_M__2_S__100__MS__",
            "T#-1D2H",
            "16#FF",
            "2#1010_0101",
            "DT#1990-01-01-12:30:00.000",
            "TOD#12:00:00.5",
            "P#M",
            "P#2.0",
            "B#",
        ] {
            assert_eq!(kinds(text), [Typed], "{text}");
        }
        assert_eq!(
            kinds("P#DB1.DBX 0.0 BYTE 10"),
            [Typed, Number, Word, Number]
        );
        assert_eq!(
            kinds("B#(1, 2)"),
            [Typed, LParen, Number, Comma, Number, RParen]
        );
    }

    #[test]
    fn operations_with_signs_and_comparisons() {
        assert_eq!(kinds("+I -D *R /I +AR1"), [SignedWord; 5]);
        assert_eq!(kinds("==I <>R >=0 <0"), [Compare; 4]);
        assert_eq!(
            kinds("__ASSERT== __ACCU 1, 5"),
            [Assert, Word, Number, Comma, Number]
        );
        assert_eq!(kinds("L -1.5e10"), [Word, Minus, Number]);
        assert_eq!(kinds("+ 5"), [Plus, Number]);
    }

    #[test]
    fn locals_symbols_strings_and_ranges() {
        assert_eq!(
            kinds("#a.b[1, 2]"),
            [Local, Dot, Word, LBracket, Number, Comma, Number, RBracket]
        );
        assert_eq!(kinds(r#""Motor".on"#), [Symbol, Dot, Word]);
        assert_eq!(kinds("'A' 'it$'s'"), [Quoted, Quoted]);
        assert_eq!(
            kinds("[1..10]"),
            [LBracket, Number, Range, Number, RBracket]
        );
        assert_eq!(kinds("x := 5;"), [Word, Assign, Number, Semicolon]);
    }

    #[test]
    fn any_byte_lexes() {
        assert_eq!(kinds("A § 1"), [Word, Invalid, Number]);
        assert_eq!(kinds("'open")[0], Invalid);
        assert_eq!(kinds("Größe"), [Word]);
    }
}
