//! Semantic tokens: each token of a document as an operation, operand, label, constant or
//! comment, read with the lexer of the document's dialect and encoded as the Language Server
//! Protocol sends them (each token relative to the one before).

use crate::dialect::Dialect;
use crate::lexer::{self, TokenKind};
use crate::lsp::text::{FileLanguage, LineIndex};
use crate::mnemonics::{self, BlockKind, MnemonicSet};
use crate::step7::lexer::{self as s7, TokenKind as S7Kind};
use crate::step7::mnemonics as s7_mnemonics;
use crate::syntax::Token;

/// What a token is; the order is the legend's ([`LEGEND`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TokenType {
    Operation,
    Operand,
    Label,
    Constant,
    Comment,
}

/// The token type names the server announces, in [`TokenType`] order: standard names where
/// the protocol has one, `label` declared by the VS Code extension.
pub const LEGEND: &[&str] = &["keyword", "variable", "label", "number", "comment"];

/// One token before encoding: byte offsets into the text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Classified {
    pub start: usize,
    pub end: usize,
    pub kind: TokenType,
}

/// One encoded token: the five numbers of the protocol's delta encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SemanticToken {
    pub delta_line: u32,
    pub delta_start: u32,
    pub length: u32,
    pub token_type: u32,
    pub modifiers: u32,
}

/// The semantic tokens of a document, delta-encoded.
pub fn semantic_tokens(text: &str, language: FileLanguage) -> Vec<SemanticToken> {
    encode(text, &classify(text, language))
}

/// Every token of `text` with its type, in text order.
pub fn classify(text: &str, language: FileLanguage) -> Vec<Classified> {
    let mut found = match language.dialect {
        Dialect::Step5 => step5_tokens(text, language.mnemonics),
        Dialect::Step7 => step7_tokens(text, language.mnemonics),
    };
    found.sort_by_key(|token| token.start);
    found
}

/// The protocol's encoding; a token over several lines (none of ours) would be cut at the
/// line end by clients, so tokens are kept to one line.
pub fn encode(text: &str, tokens: &[Classified]) -> Vec<SemanticToken> {
    let index = LineIndex::new(text);
    let mut previous = crate::lsp::text::Position::default();
    tokens
        .iter()
        .map(|token| {
            let start = index.position(token.start);
            let end = index.position(token.end);
            let length = if end.line == start.line {
                end.character - start.character
            } else {
                0
            };
            let delta_line = start.line - previous.line;
            let delta_start = if delta_line == 0 {
                start.character - previous.character
            } else {
                start.character
            };
            previous = start;
            SemanticToken {
                delta_line,
                delta_start,
                length,
                token_type: token.kind as u32,
                modifiers: 0,
            }
        })
        .collect()
}

/// The comments between the tokens: both lexers skip them, so they are the text of a gap
/// from its first comment start to the line end.
fn comments<K: Copy>(text: &str, tokens: &[Token<K>], starts: &[&str]) -> Vec<Classified> {
    let mut gaps: Vec<(usize, usize)> = Vec::new();
    let mut at = 0;
    for token in tokens {
        gaps.push((at, token.start as usize));
        at = token.end as usize;
    }
    gaps.push((at, text.len()));
    gaps.into_iter()
        .filter_map(|(from, to)| {
            let gap = &text[from..to];
            let start = starts.iter().filter_map(|mark| gap.find(mark)).min()?;
            let comment = &gap[start..];
            let end = comment.find(['\r', '\n']).unwrap_or(comment.len());
            Some(Classified {
                start: from + start,
                end: from + start + end,
                kind: TokenType::Comment,
            })
        })
        .collect()
}

fn classified<K: Copy>(token: Token<K>, kind: TokenType) -> Classified {
    Classified {
        start: token.start as usize,
        end: token.end as usize,
        kind,
    }
}

fn step5_tokens(text: &str, set: MnemonicSet) -> Vec<Classified> {
    let tokens = lexer::lex(text);
    let mut found = comments(text, &tokens, &[";", "//"]);
    for line in crate::syntax::token::runs(&tokens, |kind| kind == TokenKind::Newline) {
        step5_line(text, set, line, &mut found);
    }
    found
}

/// `[address] [label :] [:] operation operand`, a block header, a declaration or a data word.
fn step5_line(text: &str, set: MnemonicSet, line: &[lexer::Token], found: &mut Vec<Classified>) {
    let mut rest = line;
    let is = |token: Option<&lexer::Token>, kind| token.is_some_and(|t| t.kind == kind);
    // A listing's address, or a data word's number.
    if rest.len() > 1 && is_listing_address(text, rest[0]) {
        rest = &rest[1..];
    } else if rest.len() > 1
        && rest[0].kind == TokenKind::Number
        && is(rest.get(1), TokenKind::Colon)
    {
        found.push(classified(rest[0], TokenType::Label));
        rest = &rest[2..];
    }
    if rest.len() > 1
        && matches!(rest[0].kind, TokenKind::Word | TokenKind::Number)
        && is(rest.get(1), TokenKind::Colon)
    {
        found.push(classified(rest[0], TokenType::Label));
        rest = &rest[2..];
    }
    if is(rest.first(), TokenKind::Colon) {
        rest = &rest[1..];
    }
    let Some((&first, operand)) = rest.split_first() else {
        return;
    };
    let word = first.text(text);
    let operation = match first.kind {
        TokenKind::Word => {
            mnemonics::operation(set, word).is_some()
                || BlockKind::from_word(word).is_some()
                || is_header_word(word)
        }
        TokenKind::Compare
        | TokenKind::AddSub
        | TokenKind::Equals
        | TokenKind::RParen
        | TokenKind::SegmentEnd => true,
        _ => false,
    };
    if operation {
        found.push(classified(first, TokenType::Operation));
        if let Some(open) = operand.first().filter(|t| t.kind == TokenKind::LParen) {
            found.push(classified(*open, TokenType::Operation));
        }
    }
    let operand = if operation { operand } else { rest };
    let constant = operand
        .first()
        .is_some_and(|t| mnemonics::constant_format(set, t.text(text)).is_some());
    for token in operand {
        let kind = match token.kind {
            TokenKind::Quoted => TokenType::Constant,
            TokenKind::Word | TokenKind::Number | TokenKind::FormalRef | TokenKind::SymbolRef
                if constant =>
            {
                TokenType::Constant
            }
            TokenKind::Word | TokenKind::Number | TokenKind::FormalRef | TokenKind::SymbolRef => {
                TokenType::Operand
            }
            _ => continue,
        };
        found.push(classified(*token, kind));
    }
}

/// `0004` before a statement's `:` in a PG listing.
fn is_listing_address(text: &str, token: lexer::Token) -> bool {
    let word = token.text(text);
    matches!(token.kind, TokenKind::Number | TokenKind::Word)
        && word.len() == 4
        && word.chars().all(|c| c.is_ascii_hexdigit())
}

/// Words that open a line that is no statement: `NAME`, `DES`/`BEZ`, segment headings.
fn is_header_word(word: &str) -> bool {
    let upper = word.to_ascii_uppercase();
    [
        mnemonics::NAME_WORD,
        mnemonics::DECLARATION_EN,
        mnemonics::DECLARATION_DE,
    ]
    .contains(&upper.as_str())
        || crate::parser::listing::SEGMENT_WORDS.contains(&upper.as_str())
}

fn step7_tokens(text: &str, set: MnemonicSet) -> Vec<Classified> {
    let tokens = s7::lex(text);
    let mut found = comments(text, &tokens, &["//"]);
    let ends = |kind| matches!(kind, S7Kind::Newline | S7Kind::Semicolon);
    for statement in crate::syntax::token::runs(&tokens, ends) {
        step7_statement(text, set, statement, &mut found);
    }
    found
}

/// `[label:] operation operand`, or a line of a block's frame (`FUNCTION FC 1 : VOID`,
/// `VAR_INPUT`, `speed : INT := 5`).
fn step7_statement(
    text: &str,
    set: MnemonicSet,
    tokens: &[s7::Token],
    found: &mut Vec<Classified>,
) {
    let mut rest = tokens;
    if rest.len() > 1 && rest[0].kind == S7Kind::Word && rest[1].kind == S7Kind::Colon {
        let operation_follows = rest.get(2).is_some_and(|next| {
            s7_mnemonics::operation(set, &next.text(text).to_ascii_uppercase()).is_some()
        });
        if operation_follows || rest.len() == 2 {
            found.push(classified(rest[0], TokenType::Label));
            rest = &rest[2..];
        } else {
            // A declaration `name : TYPE`: the name is an operand, the type a keyword.
            found.push(classified(rest[0], TokenType::Operand));
            if let Some(ty) = rest.get(2).filter(|t| t.kind == S7Kind::Word) {
                found.push(classified(*ty, TokenType::Operation));
            }
            rest = &rest[rest.len().min(3)..];
        }
    }
    let Some((&first, operand)) = rest.split_first() else {
        return;
    };
    let upper = first.text(text).to_ascii_uppercase();
    let operation = match first.kind {
        S7Kind::Word => {
            s7_mnemonics::operation(set, &upper).is_some()
                || crate::step7::parser::block_keyword(&upper).is_some()
                || crate::dialect::STEP7_LINE_WORDS.contains(&upper.as_str())
                || upper.starts_with("END_")
                || matches!(upper.as_str(), "NETWORK" | "TITLE" | "STRUCT" | "CALL")
        }
        S7Kind::SignedWord | S7Kind::Compare | S7Kind::Assert | S7Kind::Equals => true,
        _ => false,
    };
    if operation {
        found.push(classified(first, TokenType::Operation));
    }
    let operand = if operation { operand } else { rest };
    for token in operand {
        let kind = match token.kind {
            S7Kind::Typed | S7Kind::Number | S7Kind::Quoted => TokenType::Constant,
            S7Kind::Word | S7Kind::Local | S7Kind::Symbol => TokenType::Operand,
            _ => continue,
        };
        found.push(classified(*token, kind));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step5(set: MnemonicSet) -> FileLanguage {
        FileLanguage {
            dialect: Dialect::Step5,
            mnemonics: set,
        }
    }

    fn kinds(text: &str, language: FileLanguage) -> Vec<(&str, TokenType)> {
        classify(text, language)
            .into_iter()
            .map(|token| (&text[token.start..token.end], token.kind))
            .collect()
    }

    #[test]
    fn step5_statement_with_label_constant_and_comment() {
        use TokenType::*;
        let text = "PB 1\nM001 : L KF +5 ; five\n       U E 0.0\n       SPA =M001\n";
        assert_eq!(
            kinds(text, step5(MnemonicSet::German)),
            [
                ("PB", Operation),
                ("1", Operand),
                ("M001", Label),
                ("L", Operation),
                ("KF", Constant),
                ("5", Constant),
                ("; five", Comment),
                ("U", Operation),
                ("E", Operand),
                ("0", Operand),
                ("0", Operand),
                ("SPA", Operation),
                ("=M001", Operand),
            ]
        );
    }

    #[test]
    fn step5_listing_addresses_and_brackets() {
        use TokenType::*;
        let text = "0004      :A(\n0005 M001 :=    Q   4.0\n";
        assert_eq!(
            kinds(text, step5(MnemonicSet::English)),
            [
                ("A", Operation),
                ("(", Operation),
                ("M001", Label),
                ("=", Operation),
                ("Q", Operand),
                ("4", Operand),
                ("0", Operand),
            ]
        );
    }

    #[test]
    fn step7_source() {
        use TokenType::*;
        let text = "FUNCTION FC 1 : VOID\nVAR_TEMP\n  t : INT;\nEND_VAR\nBEGIN\nM1: L W#16#FF; // x\n      T #t;\nEND_FUNCTION\n";
        let language = FileLanguage {
            dialect: Dialect::Step7,
            mnemonics: MnemonicSet::English,
        };
        let found = kinds(text, language);
        for expected in [
            ("FUNCTION", Operation),
            ("t", Operand),
            ("INT", Operation),
            ("M1", Label),
            ("L", Operation),
            ("W#16#FF", Constant),
            ("// x", Comment),
            ("T", Operation),
            ("#t", Operand),
            ("END_FUNCTION", Operation),
        ] {
            assert!(found.contains(&expected), "{expected:?} in {found:?}");
        }
    }

    #[test]
    fn delta_encoding_is_relative_to_the_previous_token() {
        let text = "A I 0.0\n  Ä; ü\n";
        let tokens = [
            Classified {
                start: 0,
                end: 1,
                kind: TokenType::Operation,
            },
            Classified {
                start: 2,
                end: 3,
                kind: TokenType::Operand,
            },
            Classified {
                start: text.find(';').unwrap(),
                end: text.len() - 1,
                kind: TokenType::Comment,
            },
        ];
        let encoded: Vec<[u32; 4]> = encode(text, &tokens)
            .into_iter()
            .map(|t| [t.delta_line, t.delta_start, t.length, t.token_type])
            .collect();
        assert_eq!(encoded, [[0, 0, 1, 0], [0, 2, 1, 1], [1, 3, 3, 4]]);
    }
}
