//! `awl dump --listing`: the program as a STEP 5 PG listing. Every statement line gets its
//! statement number (the op's index in its block, in hex) before the `:`, a block without
//! segments gets a `SEGMENT 1` heading, and every other line (headers, declarations, FB call
//! parameters, data words, comments, segment headings and ends) is kept as written, so the
//! listing parses back to the same bytecode.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::frontend::Frontend;
use crate::source::SourceFile;

/// What a source line becomes in the listing.
enum Mark {
    /// A statement: its number in its block.
    Statement(usize),
    /// A logic block's header with no segment heading of its own: one is added after it.
    HeaderWithoutSegments,
}

pub fn listing(built: &Frontend) -> String {
    let program = &built.compiled.program;
    // (file, line) → what the line is.
    let mut marks: HashMap<(u16, u32), Mark> = HashMap::new();
    for block in &program.blocks {
        let file = built.sources.get(block.header.file);
        if block.segments.iter().all(|(_, segment)| *segment == 0) {
            let line = file.line_of(block.header.start);
            marks.insert((block.header.file, line), Mark::HeaderWithoutSegments);
        }
        for (pc, span) in block.spans.iter().enumerate() {
            marks.insert((span.file, file.line_of(span.start)), Mark::Statement(pc));
        }
    }
    let programs = built.mnemonics.len();
    let mut out = String::new();
    for (id, file) in built.sources.files.iter().enumerate().take(programs) {
        if programs > 1 {
            let _ = writeln!(out, "; {}", file.name);
        }
        write_file(&mut out, id as u16, file, &marks);
    }
    out
}

fn write_file(out: &mut String, id: u16, file: &SourceFile, marks: &HashMap<(u16, u32), Mark>) {
    let lines = file.text.lines().count() as u32;
    for number in 1..=lines {
        let text = file.line(number);
        match marks.get(&(id, number)) {
            Some(Mark::Statement(pc)) => {
                let statement = without_address(text);
                let colon = if statement.starts_with(':') || has_label(statement) {
                    ""
                } else {
                    ":"
                };
                let _ = writeln!(out, "{pc:04X}      {colon}{statement}");
            }
            Some(Mark::HeaderWithoutSegments) => {
                let _ = writeln!(out, "{}", text.trim_end());
                let _ = writeln!(out, "SEGMENT 1                             0000");
            }
            None => {
                let _ = writeln!(out, "{}", text.trim_end());
            }
        }
    }
}

/// The statement text without an old statement address and leading blanks.
fn without_address(text: &str) -> &str {
    let text = text.trim_start();
    let first = text.split_whitespace().next().unwrap_or("");
    let is_address = first.starts_with(|c: char| c.is_ascii_digit())
        && first.len() <= 4
        && first.chars().all(|c| c.is_ascii_hexdigit());
    if is_address && text.len() > first.len() {
        text[first.len()..].trim_start()
    } else {
        text
    }
}

/// `M001 :…`: the line starts with a jump label.
fn has_label(statement: &str) -> bool {
    let word: String = statement
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    !word.is_empty() && statement[word.len()..].trim_start().starts_with(':')
}
