//! Byte offsets of the front end's spans and the LSP's positions in the protocol's types:
//! [`text::LineIndex`] counts lines and UTF-16 columns; this turns its plain types into
//! `lsp_types`' and back.

use lsp_types::{Position, Range};

use super::text;

/// Where each line of a text starts, in the protocol's types.
pub struct LineIndex<'a>(text::LineIndex<'a>);

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        LineIndex(text::LineIndex::new(text))
    }

    pub fn range(&self, span: std::ops::Range<usize>) -> Range {
        let range = self.0.range(span.start, span.end);
        Range::new(protocol(range.start), protocol(range.end))
    }

    /// The byte offset of `position`; a position past a line's end is its end, past the
    /// text's end the text's end.
    pub fn offset(&self, position: Position) -> usize {
        self.0.offset(plain(position))
    }
}

pub fn plain(position: Position) -> text::Position {
    text::Position {
        line: position.line,
        character: position.character,
    }
}

pub fn protocol(position: text::Position) -> Position {
    Position::new(position.line, position.character)
}
