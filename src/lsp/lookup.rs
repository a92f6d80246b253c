//! What stands at a place of a document, for hover and navigation: the statements and blocks
//! of both dialects' syntax trees in one shape, and the word under the cursor.

use crate::ast::{BlockBody, Name};
use crate::mnemonics::MnemonicSet;
use crate::source::Span;
use crate::step7::ast::S7Body;

use super::workspace::Analysis;

/// One statement, of either dialect.
#[derive(Debug, Clone, Copy)]
pub struct Statement<'a> {
    pub label: Option<&'a Name>,
    pub op: Span,
    pub operand: Span,
    pub whole: Span,
    /// The index of its block in [`blocks`].
    pub block: usize,
}

/// One block, of either dialect.
#[derive(Debug, Clone)]
pub struct Block {
    /// `PB 3`, `FC 1`, or the symbol of a STEP 7 block written by name (`"Valve"`).
    pub name: String,
    pub header: Span,
    /// The whole block, header to end.
    pub whole: Span,
    /// The spans of its interface: the `VAR` sections of a STEP 7 block, the `DES` lines of
    /// a STEP 5 function block.
    pub interface: Vec<Span>,
    /// The networks (STEP 7) or segments (STEP 5 listings): number and first statement.
    pub parts: Vec<(u16, Span)>,
}

fn cover(first: Span, last: Option<Span>) -> Span {
    match last {
        Some(last) if last.file == first.file && last.end >= first.start => {
            Span::new(first.file, first.start as usize..last.end as usize)
        }
        _ => first,
    }
}

/// Starts of the numbered parts (networks, segments) of a block's statements.
fn parts(numbers: impl Iterator<Item = (u16, Span)>) -> Vec<(u16, Span)> {
    let mut found: Vec<(u16, Span)> = Vec::new();
    for (number, span) in numbers {
        if number != 0 && found.last().is_none_or(|(last, _)| *last != number) {
            found.push((number, span));
        }
    }
    found
}

/// The blocks and the statements of file `file`, in file order.
pub fn outline(analysis: &Analysis, file: u16) -> (Vec<Block>, Vec<Statement<'_>>) {
    let mut blocks = Vec::new();
    let mut statements = Vec::new();
    for unit in analysis.built.units.iter().filter(|unit| unit.file == file) {
        for block in &unit.blocks {
            let index = blocks.len();
            let (interface, last, numbered) = match &block.body {
                BlockBody::Logic(body) => {
                    statements.extend(body.statements.iter().map(|statement| Statement {
                        label: statement.label.as_ref(),
                        op: statement.op_span,
                        operand: statement.operand_span,
                        whole: statement.span,
                        block: index,
                    }));
                    (
                        body.params.iter().map(|param| param.span).collect(),
                        body.end.or(body.statements.last().map(|last| last.span)),
                        parts(body.statements.iter().map(|s| (s.segment, s.span))),
                    )
                }
                BlockBody::Data(_) => (Vec::new(), None, Vec::new()),
            };
            blocks.push(Block {
                name: block.id.to_string(),
                header: block.header,
                whole: cover(block.header, last),
                interface,
                parts: numbered,
            });
        }
    }
    for unit in analysis
        .built
        .s7_units
        .iter()
        .filter(|unit| unit.file == file)
    {
        for block in &unit.blocks {
            let index = blocks.len();
            let numbered = match &block.body {
                S7Body::Logic(body) => {
                    statements.extend(body.iter().map(|statement| Statement {
                        label: statement.label.as_ref(),
                        op: statement.op_span,
                        operand: statement.operand_span,
                        whole: statement.span,
                        block: index,
                    }));
                    parts(body.iter().map(|s| (s.network, s.span)))
                }
                _ => Vec::new(),
            };
            blocks.push(Block {
                name: block.name.written(),
                header: block.header,
                whole: cover(block.header, block.end),
                interface: block.interface.iter().map(|section| section.span).collect(),
                parts: numbered,
            });
        }
    }
    (blocks, statements)
}

/// The mnemonic set file `file` is written in.
pub fn mnemonics_of(analysis: &Analysis, file: u16) -> MnemonicSet {
    analysis
        .built
        .mnemonics
        .get(usize::from(file))
        .copied()
        .unwrap_or(MnemonicSet::English)
}

fn is_word(character: char) -> bool {
    character.is_alphanumeric() || matches!(character, '_' | '#' | '.' | '-' | '=' | '"')
}

/// The word at byte `offset` of `text` (`-START`, `"Motor"`, `M_1`, `I`), and its range.
pub fn word_at(text: &str, offset: usize) -> Option<(&str, std::ops::Range<usize>)> {
    let offset = offset.min(text.len());
    let start = text[..offset]
        .char_indices()
        .rev()
        .take_while(|(_, character)| is_word(*character))
        .last()
        .map_or(offset, |(at, _)| at);
    let end = text[offset..]
        .char_indices()
        .find(|(_, character)| !is_word(*character))
        .map_or(text.len(), |(at, _)| offset + at);
    (start < end).then(|| (&text[start..end], start..end))
}

/// A block named by the text around `offset`: `PB 3`, `FC 1`, `DB 5` (the kind word and its
/// number, the cursor on either), as the blocks' names write it.
pub fn block_name_at(text: &str, offset: usize) -> Option<String> {
    let line_start = text[..offset.min(text.len())]
        .rfind('\n')
        .map_or(0, |at| at + 1);
    let line_end = text[line_start..]
        .find('\n')
        .map_or(text.len(), |at| line_start + at);
    let line = &text[line_start..line_end];
    let at = offset - line_start;
    let words: Vec<(usize, &str)> = line
        .split(|character: char| character.is_whitespace() || character == ',' || character == ';')
        .scan(0, |position, word| {
            let start = *position;
            *position += word.len() + 1;
            Some((start, word))
        })
        .filter(|(_, word)| !word.is_empty())
        .collect();
    words.windows(2).find_map(|pair| {
        let ((kind_at, kind), (number_at, number)) = (pair[0], pair[1]);
        let covers = at >= kind_at && at <= number_at + number.len();
        let kind = kind.to_uppercase();
        let is_block = crate::mnemonics::BlockKind::from_word(&kind).is_some()
            || matches!(
                kind.as_str(),
                "OB" | "FC" | "FB" | "DB" | "SFC" | "SFB" | "UDT"
            );
        (covers && is_block && number.chars().all(|c| c.is_ascii_digit()))
            .then(|| format!("{kind} {number}"))
    })
}

/// The text a span covers, in its file of the analysis.
pub fn slice(analysis: &Analysis, span: Span) -> &str {
    analysis.built.sources.get(span.file).slice(span)
}

/// Whether `span` covers `offset` of its file (its end included, where a cursor may stand).
pub fn covers(span: Span, offset: usize) -> bool {
    span.start as usize <= offset && offset <= span.end as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_word_keeps_its_symbol_marks() {
        let text = "      U -START\n      CALL \"Valve\"";
        assert_eq!(word_at(text, 10).map(|(word, _)| word), Some("-START"));
        assert_eq!(word_at(text, 28).map(|(word, _)| word), Some("\"Valve\""));
        assert_eq!(word_at(text, 5), None);
    }

    #[test]
    fn a_block_is_its_kind_and_number() {
        let text = "  SPA PB 3\n  CALL FC 12, DB 1";
        assert_eq!(block_name_at(text, 7).as_deref(), Some("PB 3"));
        assert_eq!(block_name_at(text, 9).as_deref(), Some("PB 3"));
        assert_eq!(block_name_at(text, 20).as_deref(), Some("FC 12"));
        assert_eq!(block_name_at(text, 28).as_deref(), Some("DB 1"));
        assert_eq!(block_name_at(text, 3), None);
    }
}
