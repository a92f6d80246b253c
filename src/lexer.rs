//! Lexer: STL source text to tokens with byte spans (logos).
//!
//! The lexer knows no mnemonics: words and numbers stay words and numbers, the parser gives them
//! meaning per mnemonic set. Comments (`;` and `//`) and blanks are skipped; line ends are tokens
//! because STL is line oriented.

use logos::Logos;

#[derive(Logos, Debug, Clone, Copy, PartialEq, Eq)]
#[logos(skip r"[ \t\f\x0B]+")]
pub enum TokenKind {
    /// `; …` and `// …` to the end of the line.
    #[regex(r";[^\n]*", logos::skip, allow_greedy = true)]
    #[regex(r"//[^\n]*", logos::skip, allow_greedy = true)]
    Comment,
    #[regex(r"\r?\n")]
    Newline,
    /// A name or mnemonic: `A`, `JU`, `PB`, `MOTOR`, `M001`.
    #[regex(r"[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    Word,
    /// Digits, possibly followed by hex digits or letters (`00FF`, `050`).
    #[regex(r"[0-9][0-9A-Za-z_]*")]
    Number,
    /// `=NAME`: a formal operand or a jump label inside an FB.
    #[regex(r"=[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    FormalRef,
    /// A fixed-point or floating-point comparison: `!=F`, `><F`, `>F`, `>=F`, `<F`, `<=F`,
    /// and the same with `G`.
    #[regex(r"(!=|><|>=|<=|>|<)[FfGg]")]
    Compare,
    /// Fixed- or floating-point addition or subtraction: `+F`, `-F`, `+G`, `-G` (before a
    /// symbol of the same length).
    #[regex(r"[+\-][FfGg]", priority = 10)]
    AddSub,
    /// `-NAME`: a symbol of the assignment list standing for an operand.
    #[regex(r"-[A-Za-z_\u{C0}-\u{FF}][A-Za-z0-9_\u{C0}-\u{FF}]*")]
    SymbolRef,
    /// `***`: a segment's end in a PG listing.
    #[token("***")]
    SegmentEnd,
    /// A character string in quotes (`KS 'TEXT'`).
    #[regex(r"'[^'\r\n]*'")]
    Quoted,
    #[token(":")]
    Colon,
    #[token(".")]
    Dot,
    #[token(",")]
    Comma,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("=")]
    Equals,
    /// A character no token starts with; reported by the lexer, skipped by the parser.
    Invalid,
}

crate::syntax::token::dialect_lexer!("STEP 5");

#[cfg(test)]
mod tests {
    use super::*;
    use TokenKind::*;

    #[test]
    fn statement_with_bit_address_and_comment() {
        assert_eq!(
            kinds("  :A  I 0.0 ; c\r\n"),
            [Colon, Word, Word, Number, Dot, Number, Newline]
        );
    }

    #[test]
    fn formal_operands_comparisons_and_arithmetic() {
        assert_eq!(kinds("JC =M001 // x"), [Word, FormalRef]);
        assert_eq!(
            kinds("!=F >=F <F +F -F"),
            [Compare, Compare, Compare, AddSub, AddSub]
        );
        assert_eq!(kinds("KF -100"), [Word, Minus, Number]);
    }

    #[test]
    fn symbols_and_segment_ends() {
        assert_eq!(kinds("U -START"), [Word, SymbolRef]);
        assert_eq!(kinds("SPA -FILL"), [Word, SymbolRef]);
        assert_eq!(kinds("-F +F"), [AddSub, AddSub]);
        assert_eq!(kinds("-G +g >=G"), [AddSub, AddSub, Compare]);
        assert_eq!(kinds("0003 :***"), [Number, Colon, SegmentEnd]);
    }

    #[test]
    fn invalid_characters_become_tokens() {
        assert_eq!(kinds("A § 1"), [Word, Invalid, Number]);
    }
}
