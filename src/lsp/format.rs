//! Formatting: STEP 5 statements in the columns of a PG printout (label, `:`, operation,
//! operand), STEP 7 statements indented as STEP 7 writes its source exports. Only statement
//! lines change; a line is rewritten only when its tokens stay the same, so the program
//! compiles to the same bytecode. A file with the comment `awl-format: off` is left alone.

use crate::ast::BlockBody;
use crate::dialect::Dialect;
use crate::lsp::text::{FileLanguage, LineIndex, TextEdit};
use crate::mnemonics::{self, MnemonicSet};
use crate::step7::ast::S7Body;

/// The comment that turns formatting off for a file.
pub const OFF_MARKER: &str = "awl-format: off";

/// The width of the label column of a PG printout (labels have at most 4 characters).
const LABEL_WIDTH: usize = 4;
/// The operation column's width after the `:`, as in `:U    E   1.0`.
const OPERATION_WIDTH: usize = 5;
/// The operand's area word column, as in `E   1.0`.
const AREA_WIDTH: usize = 4;
/// STEP 7 exports indent a statement by six columns and give its operation six.
const S7_INDENT: usize = 6;
const S7_OPERATION_WIDTH: usize = 6;
/// Where a comment after a statement starts, when the statement leaves room.
const COMMENT_COLUMN: usize = 32;

/// The edits that format `text`: one per statement line that changes.
pub fn format(text: &str, language: FileLanguage) -> Vec<TextEdit> {
    if text.contains(OFF_MARKER) {
        return Vec::new();
    }
    let lines = match language.dialect {
        Dialect::Step5 => step5_lines(text, language.mnemonics),
        Dialect::Step7 => step7_lines(text, language.mnemonics),
    };
    let index = LineIndex::new(text);
    lines
        .into_iter()
        .filter_map(|line| {
            let old = &text[line.start..line.end];
            (old != line.new_text && same_tokens(old, &line.new_text, language.dialect))
                .then(|| index.edit(line.start, line.end, line.new_text))
        })
        .collect()
}

/// `text` formatted.
pub fn formatted(text: &str, language: FileLanguage) -> String {
    crate::lsp::text::apply(text, &format(text, language))
}

/// A line's new text; `start..end` is the line without its line end.
struct Line {
    start: usize,
    end: usize,
    new_text: String,
}

/// The line around byte `at`, without its line end.
fn line_around(text: &str, at: usize) -> (usize, usize) {
    let start = text[..at].rfind('\n').map_or(0, |found| found + 1);
    let end = text[at..].find('\n').map_or(text.len(), |found| at + found);
    let end = if text[..end].ends_with('\r') {
        end - 1
    } else {
        end
    };
    (start, end)
}

/// The part of a line after its last token: its comment, or nothing.
fn comment_of(line: &str, dialect: Dialect) -> (usize, &str) {
    let code_end = match dialect {
        Dialect::Step5 => crate::lexer::lex(line).last().map_or(0, |t| t.end as usize),
        Dialect::Step7 => crate::step7::lexer::lex(line)
            .last()
            .map_or(0, |t| t.end as usize),
    };
    (code_end, line[code_end..].trim())
}

fn with_comment(mut code: String, comment: &str) -> String {
    if comment.is_empty() {
        return code.trim_end().to_string();
    }
    let width = code.chars().count();
    let pad = if width < COMMENT_COLUMN {
        COMMENT_COLUMN - width
    } else {
        1
    };
    code.extend(std::iter::repeat_n(' ', pad));
    code + comment
}

/// Whether two lines hold the same tokens: what the formatter may change is blanks only, and
/// in STEP 5 the `:` before the operation, which the PG always prints and the parser skips.
fn same_tokens(old: &str, new: &str, dialect: Dialect) -> bool {
    match dialect {
        Dialect::Step5 => {
            let without_colons = |line| {
                let mut tokens = texts(line, crate::lexer::lex(line));
                tokens.retain(|(kind, _)| *kind != crate::lexer::TokenKind::Colon);
                tokens
            };
            without_colons(old) == without_colons(new)
        }
        Dialect::Step7 => {
            texts(old, crate::step7::lexer::lex(old)) == texts(new, crate::step7::lexer::lex(new))
        }
    }
}

fn texts<K: Copy + PartialEq>(line: &str, tokens: Vec<crate::syntax::Token<K>>) -> Vec<(K, &str)> {
    tokens.into_iter().map(|t| (t.kind, t.text(line))).collect()
}

/// A PG listing's statement address before the `:` (`0004`), kept in its place.
fn listing_address(prefix: &str) -> Option<Option<&str>> {
    let prefix = prefix.trim().trim_end_matches(':').trim();
    if prefix.is_empty() {
        return Some(None);
    }
    (prefix.len() == 4 && prefix.chars().all(|c| c.is_ascii_hexdigit())).then_some(Some(prefix))
}

/// `E 1.0` → `E   1.0`: an address's area word in its column; constants, blocks and other
/// operands as written.
fn aligned_operand(operand: &str, set: MnemonicSet) -> String {
    let operand = operand.trim();
    match operand.split_once(char::is_whitespace) {
        Some((word, rest)) if mnemonics::area(set, word).is_some() && !rest.trim().is_empty() => {
            format!("{word:<AREA_WIDTH$}{}", rest.trim_start())
        }
        _ => operand.to_string(),
    }
}

/// `0004 M001 :U    E   1.0`
fn pg_line(address: Option<&str>, label: &str, statement: &str) -> String {
    let address = address.map_or(String::new(), |address| format!("{address} "));
    format!("{address}{label:<LABEL_WIDTH$} :{statement}")
}

fn step5_lines(text: &str, set: MnemonicSet) -> Vec<Line> {
    let parsed = crate::parser::parse_file(0, text, Some(set));
    let mut lines = Vec::new();
    for block in &parsed.unit.blocks {
        let BlockBody::Logic(body) = &block.body else {
            continue;
        };
        for statement in &body.statements {
            let op_start = statement.op_span.start as usize;
            let first = statement
                .label
                .as_ref()
                .map_or(op_start, |l| l.span.start as usize);
            lines.extend(step5_statement(text, set, statement, first, op_start));
            for param in &statement.call_params {
                let name_start = param.name.span.start as usize;
                let actual = param.actual_span.start as usize;
                lines.extend(step5_parameter(text, &param.name.text, name_start, actual));
            }
        }
    }
    lines
}

fn step5_statement(
    text: &str,
    set: MnemonicSet,
    statement: &crate::ast::Statement,
    first: usize,
    op_start: usize,
) -> Option<Line> {
    let (start, end) = line_around(text, op_start);
    let line = &text[start..end];
    let (code_end, comment) = comment_of(line, Dialect::Step5);
    let address = listing_address(text.get(start..first)?)?;
    let label = statement.label.as_ref().map_or("", |l| l.text.as_str());
    let operand_start = statement.operand_span.start as usize;
    let has_operand = statement.operand_span.end > statement.operand_span.start
        && operand_start >= statement.op_span.end as usize
        && operand_start < start + code_end;
    let (operation, operand) = if has_operand {
        (
            &text[op_start..operand_start],
            &text[operand_start..start + code_end],
        )
    } else {
        (&text[op_start..start + code_end], "")
    };
    let operation = operation.trim();
    let body = if operand.is_empty() {
        operation.to_string()
    } else {
        format!(
            "{operation:<OPERATION_WIDTH$}{}",
            aligned_operand(operand, set)
        )
    };
    Some(Line {
        start,
        end,
        new_text: with_comment(pg_line(address, label, &body), comment),
    })
}

/// `EIN  :I 0.0`: an FB call's parameter line.
fn step5_parameter(text: &str, name: &str, name_start: usize, actual: usize) -> Option<Line> {
    let (start, end) = line_around(text, name_start);
    let line = &text[start..end];
    let (code_end, comment) = comment_of(line, Dialect::Step5);
    let address = listing_address(text.get(start..name_start)?)?;
    let value = text.get(actual..start + code_end)?.trim();
    Some(Line {
        start,
        end,
        new_text: with_comment(pg_line(address, name, value), comment),
    })
}

fn step7_lines(text: &str, set: MnemonicSet) -> Vec<Line> {
    let options = crate::step7::parser::ParseOptions {
        mnemonics: Some(set),
        extensions: true,
    };
    let parsed = crate::step7::parser::parse(0, text, options);
    parsed
        .unit
        .blocks
        .iter()
        .filter_map(|block| match &block.body {
            S7Body::Logic(statements) => Some(statements),
            _ => None,
        })
        .flatten()
        .filter_map(|statement| step7_statement(text, statement))
        .collect()
}

/// `M1:   A     I 0.0;`: one statement alone on its line.
fn step7_statement(text: &str, statement: &crate::step7::ast::S7Statement) -> Option<Line> {
    let op_start = statement.op_span.start as usize;
    let first = statement
        .label
        .as_ref()
        .map_or(op_start, |l| l.span.start as usize);
    let (start, end) = line_around(text, first);
    if (statement.span.end as usize) > end || !text.get(start..first)?.trim().is_empty() {
        return None;
    }
    let line = &text[start..end];
    let (code_end, comment) = comment_of(line, Dialect::Step7);
    let code = &text[op_start..start + code_end];
    // Nothing but this statement on the line: it ends at its `;` and the line's code there.
    if !code.trim_end().ends_with(';') || code.matches(';').count() != 1 {
        return None;
    }
    let (operation, operand) = match code.split_once(char::is_whitespace) {
        Some((operation, operand)) if !operation.ends_with(';') => (operation, operand.trim()),
        _ => (code.trim(), ""),
    };
    let lead = statement
        .label
        .as_ref()
        .map_or(String::new(), |label| format!("{}: ", label.text));
    let statement_text = if operand.is_empty() || operand == ";" {
        format!("{operation}{}", if operand == ";" { ";" } else { "" })
    } else {
        format!("{operation:<S7_OPERATION_WIDTH$}{operand}")
    };
    Some(Line {
        start,
        end,
        new_text: with_comment(format!("{lead:<S7_INDENT$}{statement_text}"), comment),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step5(text: &str) -> String {
        formatted(text, FileLanguage::of_text(text))
    }

    #[test]
    fn step5_statements_take_the_pg_columns() {
        let text = "PB 1\nM001: U E 1.0 ; start\n  = A 4.0\n  SPA =M001\n BE\n";
        assert_eq!(
            step5(text),
            "PB 1\nM001 :U    E   1.0              ; start\n     :=    A   4.0\n     :SPA  =M001\n     :BE\n"
        );
    }

    #[test]
    fn listing_addresses_and_call_parameters_stay() {
        let text = "OB 1\n0000 :JU FB 1\n0001 NAME :X\n0002 :BE\nFB 1\nNAME :X\n0000 :BE\n";
        let formatted = step5(text);
        assert!(formatted.contains("0000      :JU   FB 1\n"), "{formatted}");
        assert!(formatted.contains("0001 NAME :X\n"), "{formatted}");
    }

    #[test]
    fn step7_statements_are_indented_as_an_export() {
        let text =
            "FUNCTION FC 1 : VOID\nBEGIN\nA I 0.0; // x\nM1: = Q 4.0;\n   BE;\nEND_FUNCTION\n";
        let formatted = formatted(text, FileLanguage::of_text(text));
        assert_eq!(
            formatted,
            "FUNCTION FC 1 : VOID\nBEGIN\n      A     I 0.0;              // x\nM1:   =     Q 4.0;\n      BE;\nEND_FUNCTION\n"
        );
    }

    #[test]
    fn a_label_on_its_own_line_stays_there() {
        let text = "FB 1\nNAME :X\nM001 :\n  A I 0.0\n      BE\n";
        let formatted = step5(text);
        assert!(
            formatted.contains("M001 :\n     :A    I   0.0\n"),
            "{formatted}"
        );
    }

    #[test]
    fn a_file_can_turn_formatting_off() {
        let text = "; awl-format: off\nPB 1\n  A I 0.0\n BE\n";
        assert!(format(text, FileLanguage::of_text(text)).is_empty());
    }
}
