//! Places and edits in a document as the Language Server Protocol counts them: lines from 0
//! and columns in UTF-16 code units. The server converts these plain types to its protocol
//! types; the modules here work on byte offsets and convert at their edge.

use crate::dialect::Dialect;
use crate::frontend::Frontend;
use crate::mnemonics::MnemonicSet;
use crate::source::FileId;

/// A place in a document: line from 0, column in UTF-16 code units.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
pub struct Position {
    pub line: u32,
    pub character: u32,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Range {
    pub start: Position,
    pub end: Position,
}

/// Replace `range` by `new_text`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextEdit {
    pub range: Range,
    pub new_text: String,
}

/// The dialect and mnemonic set a document is read in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FileLanguage {
    pub dialect: Dialect,
    pub mnemonics: MnemonicSet,
}

impl FileLanguage {
    /// As the front end read file `file`: STEP 7 when it built STEP 7 units.
    pub fn of(frontend: &Frontend, file: FileId) -> FileLanguage {
        let dialect = if frontend.s7_units.is_empty() {
            Dialect::Step5
        } else {
            Dialect::Step7
        };
        FileLanguage {
            dialect,
            mnemonics: frontend
                .mnemonics
                .get(file as usize)
                .copied()
                .unwrap_or(MnemonicSet::English),
        }
    }

    /// As the front end reads `text` alone.
    pub fn of_text(text: &str) -> FileLanguage {
        let language = crate::frontend::Language::default();
        let mut sources = crate::source::SourceSet::default();
        sources
            .add(crate::source::SourceFile::new("document", text))
            .expect("one file fits");
        let profile = crate::frontend::default_profile(&sources, language);
        FileLanguage::of(&crate::frontend::build(sources, language, profile), 0)
    }
}

/// Converts between byte offsets and positions of one text.
pub struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of each line's start.
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    pub fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(at, _)| at + 1))
            .collect();
        LineIndex { text, starts }
    }

    pub fn position(&self, offset: usize) -> Position {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|start| *start <= offset) - 1;
        let start = self.starts[line];
        let character = self.text[start..floor_char(self.text, offset)]
            .encode_utf16()
            .count();
        Position {
            line: line as u32,
            character: character as u32,
        }
    }

    pub fn offset(&self, position: Position) -> usize {
        let Some(&start) = self.starts.get(position.line as usize) else {
            return self.text.len();
        };
        let line_end = self.text[start..]
            .find('\n')
            .map_or(self.text.len(), |at| start + at);
        let mut units = 0;
        for (at, c) in self.text[start..line_end].char_indices() {
            if units >= position.character as usize {
                return start + at;
            }
            units += c.len_utf16();
        }
        line_end
    }

    pub fn range(&self, start: usize, end: usize) -> Range {
        Range {
            start: self.position(start),
            end: self.position(end),
        }
    }

    pub fn edit(&self, start: usize, end: usize, new_text: impl Into<String>) -> TextEdit {
        TextEdit {
            range: self.range(start, end),
            new_text: new_text.into(),
        }
    }
}

fn floor_char(text: &str, mut offset: usize) -> usize {
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    offset
}

/// Applies edits that do not overlap (tests and the formatter's own checks).
pub fn apply(text: &str, edits: &[TextEdit]) -> String {
    let index = LineIndex::new(text);
    let mut spans: Vec<(usize, usize, &str)> = edits
        .iter()
        .map(|edit| {
            (
                index.offset(edit.range.start),
                index.offset(edit.range.end),
                edit.new_text.as_str(),
            )
        })
        .collect();
    spans.sort_by_key(|(start, end, _)| (*start, *end));
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (start, end, new_text) in spans {
        out.push_str(&text[at..start]);
        out.push_str(new_text);
        at = end;
    }
    out.push_str(&text[at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_utf16_units() {
        let text = "A I 0.0\n; Ä𝄞x\nBE";
        let index = LineIndex::new(text);
        let x = text.find('x').unwrap();
        assert_eq!(
            index.position(x),
            Position {
                line: 1,
                character: 5
            }
        );
        assert_eq!(index.offset(index.position(x)), x);
        assert_eq!(index.position(text.len()).line, 2);
        assert_eq!(
            index.offset(Position {
                line: 9,
                character: 0
            }),
            text.len()
        );
        let past_the_end = Position {
            line: 0,
            character: 99,
        };
        assert_eq!(index.offset(past_the_end), 7);
    }

    #[test]
    fn edits_apply_in_place() {
        let text = "A T1\nBE\n";
        let index = LineIndex::new(text);
        let edit = index.edit(2, 4, "T 1");
        assert_eq!(apply(text, &[edit]), "A T 1\nBE\n");
    }

    #[test]
    fn language_of_text_follows_the_front_end() {
        let step5 = FileLanguage::of_text("PB 1\nU E 0.0\n= A 4.0\nBE\n");
        assert_eq!(step5.dialect, Dialect::Step5);
        assert_eq!(step5.mnemonics, MnemonicSet::German);
        let step7 = FileLanguage::of_text("FUNCTION FC 1 : VOID\nBEGIN\nA I 0.0;\nEND_FUNCTION\n");
        assert_eq!(step7.dialect, Dialect::Step7);
    }
}
