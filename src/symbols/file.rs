//! Reading an assignment list: one symbol per line, the absolute operand, the symbol and an
//! optional comment, separated by whitespace (the PG's export: `E 1.0   START   Start
//! button`) or by commas (CSV, fields may be quoted). Lines starting with `;` or `#` are
//! comments.

use crate::ast::Operand;
use crate::lexer::{Token, lex};
use crate::mnemonics::{self, MnemonicSet, OpCode, Position};
use crate::parser::line::operand;
use crate::parser::tokens::{Context, Tokens};
use crate::profile::Profile;
use crate::source::{FileId, Span};

use super::{Stands, SymbolError};

/// A field of a line: its text and where it starts in the file.
#[derive(Debug, Clone, Copy)]
struct Field<'a> {
    text: &'a str,
    start: usize,
}

impl Field<'_> {
    fn span(self, file: FileId) -> Span {
        Span {
            file,
            start: self.start as u32,
            end: (self.start + self.text.len()) as u32,
        }
    }
}

/// One line of the list, read but not yet checked.
#[derive(Debug)]
pub struct Line<'a> {
    operand: Field<'a>,
    symbol: Option<Field<'a>>,
    comment: &'a str,
}

/// A symbol as the list defines it.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Without the leading `-` (STEP 5) or the quotes (STEP 7).
    pub name: String,
    pub stands: Stands,
    pub comment: String,
    /// The mnemonic set the list is written in.
    pub set: MnemonicSet,
    pub name_span: Span,
    pub operand_span: Span,
}

/// The lines of `text` that define symbols.
fn lines(text: &str) -> Vec<Line<'_>> {
    let mut lines = Vec::new();
    let mut start = 0;
    for raw in text.split_inclusive('\n') {
        let line = raw.trim_end_matches(['\n', '\r']);
        let at = start;
        start += raw.len();
        let trimmed = line.trim_start();
        if trimmed.is_empty() || trimmed.starts_with(';') || trimmed.starts_with('#') {
            continue;
        }
        let fields = if line.contains(',') {
            csv_fields(line, at)
        } else {
            blank_fields(line, at)
        };
        lines.push(split(line, at, &fields, line.contains(',')));
    }
    lines
}

fn blank_fields(line: &str, at: usize) -> Vec<Field<'_>> {
    let mut fields = Vec::new();
    let mut rest = line;
    let mut offset = at;
    loop {
        let skipped = rest.len() - rest.trim_start().len();
        rest = &rest[skipped..];
        offset += skipped;
        if rest.is_empty() {
            return fields;
        }
        let length = rest.find(char::is_whitespace).unwrap_or(rest.len());
        fields.push(Field {
            text: &rest[..length],
            start: offset,
        });
        rest = &rest[length..];
        offset += length;
    }
}

/// CSV fields: split at commas outside quotes; a quoted field loses its quotes (`""` inside
/// stays as written).
fn csv_fields(line: &str, at: usize) -> Vec<Field<'_>> {
    let mut fields = Vec::new();
    let mut start = 0;
    let mut quoted = false;
    for (index, c) in line.char_indices().chain([(line.len(), ',')]) {
        match c {
            '"' => quoted = !quoted,
            ',' if !quoted => {
                fields.push(csv_field(&line[start..index], at + start));
                start = index + 1;
            }
            _ => {}
        }
    }
    fields
}

fn csv_field(raw: &str, at: usize) -> Field<'_> {
    let leading = raw.len() - raw.trim_start().len();
    let text = raw.trim();
    match text
        .strip_prefix('"')
        .and_then(|inner| inner.strip_suffix('"'))
    {
        Some(inner) => Field {
            text: inner,
            start: at + leading + 1,
        },
        None => Field {
            text,
            start: at + leading,
        },
    }
}

/// Operand, symbol and comment. Blank-separated, the operand takes two fields when the second
/// is its number (`E 1.0`, `MW 10`, `PB 3`).
fn split<'a>(line: &'a str, at: usize, fields: &[Field<'a>], csv: bool) -> Line<'a> {
    let two = !csv && fields.len() >= 2 && fields[1].text.starts_with(|c: char| c.is_ascii_digit());
    let operand = if two {
        let end = fields[1].start + fields[1].text.len() - at;
        Field {
            text: &line[fields[0].start - at..end],
            start: fields[0].start,
        }
    } else {
        fields[0]
    };
    let next = if two { 2 } else { 1 };
    let symbol = fields
        .get(next)
        .copied()
        .filter(|field| !field.text.is_empty());
    let comment = match fields.get(next + 1) {
        Some(field) if csv => field.text,
        Some(field) => line[field.start - at..].trim_end(),
        None => "",
    };
    Line {
        operand,
        symbol,
        comment,
    }
}

/// The mnemonic set the list's operands are written in: the set more of its area words belong
/// to, else `default`.
fn detect(lines: &[Line<'_>], default: MnemonicSet) -> MnemonicSet {
    let mut votes = [0usize; 2];
    for line in lines {
        let word = line.operand.text.split_whitespace().next().unwrap_or("");
        let word = word.trim_end_matches(|c: char| c.is_ascii_digit() || c == '.');
        if let Some(set) = mnemonics::evidence(Position::Operand, word) {
            votes[set as usize] += 1;
        }
    }
    match votes {
        [english, german] if english > german => MnemonicSet::English,
        [english, german] if german > english => MnemonicSet::German,
        _ => default,
    }
}

/// Reads the list in `text` (file `file`): its entries and every error in it.
pub fn read(
    file: FileId,
    text: &str,
    default: MnemonicSet,
    profile: &'static Profile,
) -> (Vec<Entry>, MnemonicSet, Vec<SymbolError>) {
    let lines = lines(text);
    let set = detect(&lines, default);
    let context = Context {
        source: text,
        file,
        set,
    };
    let mut entries = Vec::new();
    let mut errors = Vec::new();
    for line in &lines {
        match entry(context, line, profile) {
            Ok(entry) => entries.push(entry),
            Err(error) => errors.push(error),
        }
    }
    (entries, set, errors)
}

fn entry(
    context: Context<'_>,
    line: &Line<'_>,
    profile: &'static Profile,
) -> Result<Entry, SymbolError> {
    let operand_span = line.operand.span(context.file);
    let Some(symbol) = line.symbol else {
        return Err(SymbolError::BadLine { at: operand_span });
    };
    let name = symbol.text.strip_prefix('-').unwrap_or(symbol.text);
    let name_span = symbol.span(context.file);
    let valid = name.starts_with(|c: char| c.is_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_alphanumeric() || c == '_');
    if !valid {
        return Err(SymbolError::BadName {
            name: name.to_string(),
            written: format!("-{name}"),
            at: name_span,
            help: "a symbol starts with a letter and has letters, digits and `_`".into(),
        });
    }
    let tokens: Vec<Token> = lex(line.operand.text)
        .into_iter()
        .map(|token| Token {
            start: token.start + line.operand.start as u32,
            end: token.end + line.operand.start as u32,
            ..token
        })
        .collect();
    let bad = |reason: &str| {
        SymbolError::BadOperand {
        operand: line.operand.text.to_string(),
        at: operand_span,
        reason: reason.to_string(),
        help: "write the absolute operand first, as in the program: `E 1.0`/`I 1.0`, `MW 10`/`FW 10`, `T 1`, `PB 3`".into(),
    }
    };
    let parsed = operand(context, None)(Tokens::new(&tokens));
    let value = match parsed {
        Ok((rest, (value, _))) if rest.is_empty() => value,
        _ => return Err(bad("not an operand of this CPU's mnemonics")),
    };
    let block = match operand(context, Some(OpCode::JumpUnconditional))(Tokens::new(&tokens)) {
        Ok((rest, (Operand::Block(id), _))) if rest.is_empty() => Some(id),
        _ => None,
    };
    match &value {
        Operand::Address(address) => {
            crate::address::range::check(*address, context.set, profile).map_err(|out| {
                SymbolError::OutOfRange {
                    operand: line.operand.text.to_string(),
                    at: operand_span,
                    range: out.range,
                    cpu: profile.name,
                }
            })?;
        }
        Operand::Block(_) => {}
        _ => return Err(bad("a symbol stands for an address or a block")),
    }
    Ok(Entry {
        name: name.to_string(),
        stands: Stands::Step5 {
            operand: value,
            block,
        },
        comment: line.comment.to_string(),
        set: context.set,
        name_span,
        operand_span,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_text(text: &str) -> (Vec<Entry>, MnemonicSet, Vec<SymbolError>) {
        let profile = crate::profile::find("sinumerik-840c").unwrap();
        read(0, text, MnemonicSet::English, profile)
    }

    #[test]
    fn blank_separated_lines_with_comments() {
        let (entries, set, errors) =
            read_text("; plant\nE 1.0   START   Start button\nMW 10 SETPOINT\nPB 3  FILL\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(set, MnemonicSet::German);
        assert_eq!(entries.len(), 3);
        assert_eq!(entries[0].name, "START");
        assert_eq!(entries[0].comment, "Start button");
        assert_eq!(
            entries[2]
                .step5()
                .and_then(|(_, block)| block)
                .map(|id| id.to_string())
                .as_deref(),
            Some("PB 3")
        );
    }

    #[test]
    fn csv_lines_and_quoted_fields() {
        let (entries, set, errors) = read_text("I 1.0,START,\"Start, green\"\nQ 4.0,-MOTOR,\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(set, MnemonicSet::English);
        assert_eq!(entries[0].comment, "Start, green");
        assert_eq!(entries[1].name, "MOTOR");
    }

    #[test]
    fn every_bad_line_is_reported() {
        let (entries, _, errors) =
            read_text("I 1.0 START\nX 1.0 NOPE\nI 900.0 FAR\nQ 4.0\nF 1.0 1ST\n");
        assert_eq!(entries.len(), 1);
        let codes: Vec<&str> = errors
            .iter()
            .map(|error| match error {
                SymbolError::BadOperand { .. } => "operand",
                SymbolError::OutOfRange { .. } => "range",
                SymbolError::BadLine { .. } => "line",
                SymbolError::BadName { .. } => "name",
                _ => "other",
            })
            .collect();
        assert_eq!(codes, ["operand", "range", "line", "name"]);
    }
}
