//! `awl dump --listing`: the program as a STEP 5 PG prints it. Every statement gets its word
//! address in the block before the `:`, counted with the MC5 length of each statement (see
//! `mc5`), and so do an FB call's `NAME :` line (the jump over the parameters) and its parameter
//! lines, and the `***` that ends a segment. A block header carries the block's length in words
//! (`LAE=` in a German file, `LEN=` in an English one), a segment heading its start address, a
//! data line its word number. Statements, parameters and constants keep their text as written,
//! comments and every other line are kept, and the listing parses back to the same bytecode.

use std::collections::HashMap;
use std::fmt::Write as _;

use super::mc5;
use crate::ast::{Block, BlockBody, BlockId, DataWord, Statement};
use crate::frontend::Frontend;
use crate::mnemonics::{self, MnemonicSet};
use crate::parser::listing::SEGMENT_WORDS;
use crate::source::{SourceFile, Span};

/// The column where a header's length and a segment heading's address start, as on the PG.
const RIGHT_COLUMN: usize = 38;

/// What a source line is, as far as the parsed program knows.
enum Item<'a> {
    Header(&'a Block),
    Statement(&'a Block, usize),
    /// Parameter `usize` of the FB call that is statement `usize` of the block.
    Parameter(&'a Block, usize, usize),
    Data(&'a DataWord),
}

pub fn listing(built: &Frontend) -> String {
    let program = &built.compiled.program;
    let data_lengths: HashMap<BlockId, usize> = program
        .data_blocks
        .iter()
        .map(|data| (data.id, data.words.len()))
        .collect();
    let names: HashMap<BlockId, &str> = super::parsed_blocks(built)
        .into_iter()
        .filter_map(|(id, block)| match &block.body {
            BlockBody::Logic(body) => body.name.as_ref().map(|name| (id, name.text.as_str())),
            BlockBody::Data(_) => None,
        })
        .collect();
    let programs = built.mnemonics.len();
    let mut out = String::new();
    for unit in &built.units {
        let file = built.sources.get(unit.file);
        if programs > 1 {
            let _ = writeln!(out, "; {}", file.name);
        }
        let mut writer = Writer {
            out: &mut out,
            file,
            set: unit.mnemonics,
            data_lengths: &data_lengths,
            names: &names,
            block: None,
        };
        writer.write(&items(&unit.blocks, file));
    }
    out
}

/// Line number → what the line is.
fn items<'a>(blocks: &'a [Block], file: &SourceFile) -> HashMap<u32, Item<'a>> {
    let line = |span: Span| file.line_of(span.start);
    let mut items = HashMap::new();
    for block in blocks {
        items.insert(line(block.header), Item::Header(block));
        match &block.body {
            BlockBody::Logic(body) => {
                for (index, statement) in body.statements.iter().enumerate() {
                    items.insert(line(statement.span), Item::Statement(block, index));
                    for (param, actual) in statement.call_params.iter().enumerate() {
                        items.insert(line(actual.span), Item::Parameter(block, index, param));
                    }
                }
            }
            BlockBody::Data(words) => {
                for word in words {
                    items.insert(line(word.span), Item::Data(word));
                }
            }
        }
    }
    items
}

/// Where the walk through a logic block stands.
struct LogicState<'a> {
    statements: &'a [Statement],
    /// The statements written so far.
    written: usize,
    /// The address of the next word.
    address: u32,
    /// The address of the `NAME :` line of the FB call just written, until its line comes.
    name_at: Option<u32>,
}

struct Writer<'a, 'o> {
    out: &'o mut String,
    file: &'a SourceFile,
    set: MnemonicSet,
    data_lengths: &'a HashMap<BlockId, usize>,
    names: &'a HashMap<BlockId, &'a str>,
    block: Option<LogicState<'a>>,
}

impl<'a> Writer<'a, '_> {
    fn write(&mut self, items: &HashMap<u32, Item<'a>>) {
        let lines = self.file.text.lines().count() as u32;
        for number in 1..=lines {
            match items.get(&number) {
                Some(Item::Header(block)) => self.header(block),
                Some(Item::Statement(block, index)) => self.statement(block, *index, number),
                Some(Item::Parameter(block, index, param)) => {
                    self.parameter(block, *index, *param);
                }
                Some(Item::Data(word)) => self.data_word(word),
                None => self.other(self.file.line(number)),
            }
        }
    }

    /// `PB 3                                  LAE=9`, then `SEGMENT 1` when the block's first
    /// statements have no heading of their own.
    fn header(&mut self, block: &'a Block) {
        let word = match self.set {
            MnemonicSet::English => "LEN",
            MnemonicSet::German => "LAE",
        };
        let length = mc5::BLOCK_HEADER_WORDS + self.body_words(block);
        let id = block.id.to_string();
        let _ = writeln!(
            self.out,
            "{id:<RIGHT_COLUMN$}{word}={length}{}",
            comment(self.tail(block.header))
        );
        self.block = None;
        if let BlockBody::Logic(body) = &block.body {
            self.block = Some(LogicState {
                statements: &body.statements,
                written: 0,
                address: first_statement_address(block),
                name_at: None,
            });
            if body
                .statements
                .first()
                .is_none_or(|first| first.segment == 0)
            {
                self.segment_heading("SEGMENT", "1", 0, "");
            }
        }
    }

    /// The block's length in words after its header.
    fn body_words(&self, block: &Block) -> u32 {
        match &block.body {
            BlockBody::Logic(body) => {
                let statements: u32 = body.statements.iter().map(mc5::statement_words).sum();
                let segment_ends = body
                    .statements
                    .windows(2)
                    .filter(|pair| pair[0].segment != pair[1].segment)
                    .count() as u32;
                first_statement_address(block) + statements + segment_ends * mc5::SEGMENT_END_WORDS
            }
            BlockBody::Data(_) => self.data_lengths.get(&block.id).copied().unwrap_or(0) as u32,
        }
    }

    /// `0003 M001 :L  KF +20`
    fn statement(&mut self, block: &Block, index: usize, line: u32) {
        let BlockBody::Logic(body) = &block.body else {
            return;
        };
        let statement = &body.statements[index];
        let Some(state) = self.block.as_mut() else {
            return;
        };
        let address = state.address;
        let words = mc5::statement_words(statement);
        state.address += words;
        state.written = index + 1;
        let label = statement
            .label
            .as_ref()
            .map_or("", |label| label.text.as_str());
        let text = &self.file.text[statement.op_span.start as usize..statement.span.end as usize];
        let _ = writeln!(
            self.out,
            "{address:04X} {label:<4} :{text}{}",
            self.tail(statement.span)
        );
        if mc5::calls_function_block(statement) {
            let name_at = address + words - 1 - statement.call_params.len() as u32;
            self.call_name(statement, name_at, line);
        }
    }

    /// The `NAME :` line of an FB call: the source's own when it has one right after the call,
    /// else one written here with the called block's name.
    fn call_name(&mut self, call: &Statement, name_at: u32, line: u32) {
        let written = (line + 1..=self.file.text.lines().count() as u32)
            .map(|number| self.file.line(number).trim())
            .find(|text| !is_blank_or_comment(text))
            .is_some_and(|text| is_name_line(without_address(text)));
        if written {
            if let Some(state) = self.block.as_mut() {
                state.name_at = Some(name_at);
            }
            return;
        }
        let crate::ast::Operand::Block(callee) = call.operand else {
            return;
        };
        if let Some(name) = self.names.get(&callee) {
            let _ = writeln!(self.out, "{name_at:04X} {} :{name}", mnemonics::NAME_WORD);
        }
    }

    /// `0002 EIN  :I 0.0`
    fn parameter(&mut self, block: &Block, index: usize, param: usize) {
        let BlockBody::Logic(body) = &block.body else {
            return;
        };
        let call = &body.statements[index];
        let actual = &call.call_params[param];
        let next = self.block.as_ref().map_or(0, |state| state.address);
        let address = next - (call.call_params.len() - param) as u32;
        let text = self.file.slice(actual.actual_span);
        let _ = writeln!(
            self.out,
            "{address:04X} {:<4} :{text}{}",
            actual.name.text,
            self.tail(actual.span)
        );
    }

    /// `   3:  KF +5`
    fn data_word(&mut self, word: &DataWord) {
        let constant = super::data_constant_text(self.file.slice(word.span));
        let _ = writeln!(
            self.out,
            "{:>4}:  {constant}{}",
            word.index,
            self.tail(word.span)
        );
    }

    /// A line the parsed program does not keep: a segment heading or end, an FB call's
    /// `NAME :` line, a declaration, a comment.
    fn other(&mut self, line: &str) {
        let text = line.trim();
        if let Some(state) = &self.block {
            if let Some((word, number)) = segment_heading(text) {
                let word = word.to_ascii_uppercase();
                self.segment(&word, number, line_comment(text));
                return;
            }
            if is_segment_end(without_address(text)) {
                return;
            }
            if let Some(name_at) = state.name_at
                && is_name_line(without_address(text))
            {
                let _ = writeln!(self.out, "{name_at:04X} {}", without_address(text));
                if let Some(state) = self.block.as_mut() {
                    state.name_at = None;
                }
                return;
            }
        }
        let _ = writeln!(self.out, "{}", line.trim_end());
    }

    /// A segment heading in the source: the `***` that ends the segment before it (a word of
    /// its own), then the heading with the address where the new segment starts, and its
    /// comment.
    fn segment(&mut self, word: &str, number: &str, comment: &str) {
        let Some(state) = self.block.as_mut() else {
            return;
        };
        let written = state.written;
        let starts_new = written > 0
            && state
                .statements
                .get(written)
                .is_some_and(|next| next.segment != state.statements[written - 1].segment);
        if starts_new {
            let _ = writeln!(self.out, "{:04X}      :***", state.address);
            state.address += mc5::SEGMENT_END_WORDS;
        }
        let address = if written == 0 { 0 } else { state.address };
        self.segment_heading(word, number, address, comment);
    }

    fn segment_heading(&mut self, word: &str, number: &str, address: u32, comment: &str) {
        let heading = format!("{word} {number}");
        let _ = writeln!(
            self.out,
            "{heading:<RIGHT_COLUMN$}{address:04X}{}",
            self::comment(comment)
        );
    }

    /// What follows `span` on its line: the blanks and the comment, as written.
    fn tail(&self, span: Span) -> &'a str {
        let file: &'a SourceFile = self.file;
        let rest = &file.text[span.end as usize..];
        rest[..rest.find('\n').unwrap_or(rest.len())].trim_end()
    }
}

/// Where a block's statements start: a function block's parameter description comes first.
fn first_statement_address(block: &Block) -> u32 {
    match &block.body {
        BlockBody::Logic(body) if block.id.kind.is_function() => {
            mc5::function_block_description(body.params.len())
        }
        _ => 0,
    }
}

/// A line's comment after a part that was written anew: two blanks, then the comment.
fn comment(tail: &str) -> String {
    let comment = tail.trim_start();
    if comment.is_empty() {
        String::new()
    } else {
        format!("  {comment}")
    }
}

/// The comment of a line that holds no string constant: from `;` or `//` to the end.
fn line_comment(text: &str) -> &str {
    let start = [text.find(';'), text.find("//")]
        .into_iter()
        .flatten()
        .min();
    start.map_or("", |start| &text[start..])
}

fn is_blank_or_comment(text: &str) -> bool {
    text.is_empty() || text.starts_with(';') || text.starts_with("//")
}

/// `SEGMENT 2   0004` → (`SEGMENT`, `2`).
fn segment_heading(text: &str) -> Option<(&str, &str)> {
    let mut words = text.split_whitespace();
    let word = words.next()?;
    let number = words.next()?;
    let is_heading = SEGMENT_WORDS
        .iter()
        .any(|heading| heading.eq_ignore_ascii_case(word))
        && number.chars().all(|c| c.is_ascii_digit());
    is_heading.then_some((word, number))
}

/// `***` or `:***`.
fn is_segment_end(text: &str) -> bool {
    text.strip_prefix(':').unwrap_or(text).trim() == "***"
}

/// `NAME :MOTOR`
fn is_name_line(text: &str) -> bool {
    text.get(..mnemonics::NAME_WORD.len())
        .is_some_and(|word| word.eq_ignore_ascii_case(mnemonics::NAME_WORD))
        && text[mnemonics::NAME_WORD.len()..]
            .trim_start()
            .starts_with(':')
}

/// The text without an old statement address and the blanks after it.
fn without_address(text: &str) -> &str {
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
