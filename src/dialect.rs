//! Which STL a text is written in. awl reads STEP 5 STL; a STEP 7 source (`ORGANIZATION_BLOCK`
//! … `BEGIN` … `END_ORGANIZATION_BLOCK`, `S5T#2S`, `DBX 0.1`, `#local`, `"symbol"`) is told
//! apart here, on words STEP 5 never writes, so the parser reports it once instead of failing
//! on every line. A trailing `;` is no evidence: it starts a comment in STEP 5. Nor is
//! `NETWORK n`, the heading of a STEP 5 listing's segment.

use crate::lexer::{Token, TokenKind};

/// The STL dialects awl tells apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    Step5,
    Step7,
}

/// The first place in a text that shows its dialect is not STEP 5.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Evidence {
    pub dialect: Dialect,
    /// Byte offsets of the evidence in the text.
    pub start: u32,
    pub end: u32,
    /// What the evidence is, for the diagnostic's label.
    pub what: &'static str,
}

/// Words that open a line of a STEP 7 source and never one of STEP 5.
pub const STEP7_LINE_WORDS: &[&str] = &[
    "ORGANIZATION_BLOCK",
    "FUNCTION_BLOCK",
    "FUNCTION",
    "DATA_BLOCK",
    "BEGIN",
    "VAR",
    "VAR_INPUT",
    "VAR_OUTPUT",
    "VAR_IN_OUT",
    "VAR_TEMP",
    "VERSION",
    "KNOW_HOW_PROTECT",
];

/// Addresses of STEP 7's data blocks (`DBX 0.1`, `DBW 4`); STEP 5 writes `D 0.1`, `DW 4`.
const STEP7_DATA_AREAS: &[&str] = &["DBX", "DBB", "DBW", "DBD", "DIX", "DIB", "DIW", "DID"];

/// The text's tokens split into lines, as the lexer gives them.
fn lines(tokens: &[Token]) -> impl Iterator<Item = &[Token]> {
    tokens
        .split(|token| token.kind == TokenKind::Newline)
        .filter(|line| !line.is_empty())
}

/// The first STEP 7 evidence in the text, if any: the text is STEP 5 otherwise.
pub fn detect(source: &str, tokens: &[Token]) -> Option<Evidence> {
    lines(tokens).find_map(|line| step7_in_line(source, line))
}

fn step7_in_line(source: &str, line: &[Token]) -> Option<Evidence> {
    let evidence = |first: Token, last: Token, what| Evidence {
        dialect: Dialect::Step7,
        start: first.start,
        end: last.end,
        what,
    };
    let first = line[0];
    let word = |token: Token| (token.kind == TokenKind::Word).then(|| token.text(source));
    if let Some(text) = word(first) {
        let upper = text.to_ascii_uppercase();
        if STEP7_LINE_WORDS.contains(&upper.as_str()) || upper.starts_with("END_") {
            return Some(evidence(first, first, "a STEP 7 block keyword"));
        }
        if upper == "TITLE" && line.get(1).is_some_and(|t| t.kind == TokenKind::Equals) {
            return Some(evidence(first, line[1], "a STEP 7 title line"));
        }
    }
    line.windows(2).find_map(|pair| {
        let (a, b) = (pair[0], pair[1]);
        let hash = |token: Token| token.kind == TokenKind::Invalid && token.text(source) == "#";
        if hash(b) && a.touches(b) && a.kind == TokenKind::Word {
            return Some(evidence(
                a,
                b,
                "a STEP 7 constant such as `S5T#2S` or `W#16#FF`",
            ));
        }
        if hash(a) && a.touches(b) && b.kind == TokenKind::Word {
            return Some(evidence(a, b, "a STEP 7 local variable (`#name`)"));
        }
        if a.kind == TokenKind::Invalid && a.text(source) == "\"" {
            return Some(evidence(a, a, "a STEP 7 symbol in quotes"));
        }
        let data_area = word(a).is_some_and(|text| {
            STEP7_DATA_AREAS
                .iter()
                .any(|area| area.eq_ignore_ascii_case(text))
        });
        (data_area && b.kind == TokenKind::Number)
            .then(|| evidence(a, b, "a STEP 7 data block address"))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::lex;

    fn what(source: &str) -> Option<&'static str> {
        detect(source, &lex(source)).map(|evidence| evidence.what)
    }

    #[test]
    fn step7_sources_are_recognised_by_their_first_evidence() {
        assert_eq!(
            what("ORGANIZATION_BLOCK OB 1\nBEGIN\n"),
            Some("a STEP 7 block keyword")
        );
        assert_eq!(what("TITLE = Motor\n"), Some("a STEP 7 title line"));
        assert_eq!(
            what("      L S5T#2S;\n"),
            Some("a STEP 7 constant such as `S5T#2S` or `W#16#FF`")
        );
        assert_eq!(
            what("      A #START;\n"),
            Some("a STEP 7 local variable (`#name`)")
        );
        assert_eq!(
            what("      A \"Motor\";\n"),
            Some("a STEP 7 symbol in quotes")
        );
        assert_eq!(
            what("      A DBX 0.1;\n"),
            Some("a STEP 7 data block address")
        );
    }

    #[test]
    fn step5_texts_show_no_evidence() {
        assert_eq!(what("OB 1\nNETWORK 1\n      A I 0.0;\n      BE\n"), None);
        assert_eq!(what("FB 1\nNAME :RAD:GP\nDES :EIN I BI\n      BE\n"), None);
        assert_eq!(what("PB 1\n      A § 1\n      BE\n"), None);
    }
}
