//! Hover: on an operation what it does, its spelling in the other mnemonic set and its
//! execution time on the CPU; on an operand its symbol and comment; on a block call the
//! block's interface; on a jump label its line; on a STEP 7 variable its declaration.

use lsp_types::{Hover, HoverContents, MarkupContent, MarkupKind};

use super::lookup::{self, Statement, covers};
use super::navigate::{self, Target};
use super::text::LineIndex;
use super::workspace::Analysis;
use crate::mnemonics::{self, MnemonicSet};
use crate::rules::effects;
use crate::source::Span;

/// The hover text at byte `offset` of the document, as Markdown.
pub fn hover_text(analysis: &Analysis, offset: usize) -> Option<String> {
    let (_, statements) = lookup::outline(analysis, 0);
    let statement = statements
        .iter()
        .find(|statement| covers(statement.whole, offset));
    if let Some(statement) = statement
        && covers(statement.op, offset)
        && !statement.op.is_empty()
    {
        return operation(analysis, statement);
    }
    if let Some(target) = navigate::target_at(analysis, offset) {
        return Some(match &target {
            Target::Label { name, .. } => label(analysis, &target, name)?,
            Target::Block(name) => block(analysis, name)?,
            Target::Symbol(name) => symbol(analysis, name)?,
            Target::Variable(declared) => {
                format!("```awl\n{}\n```", lookup::slice(analysis, *declared).trim())
            }
        });
    }
    let statement = statement.filter(|statement| covers(statement.operand, offset))?;
    operand(analysis, lookup::slice(analysis, statement.operand))
}

pub fn hover(analysis: &Analysis, offset: usize) -> Option<Hover> {
    let text = hover_text(analysis, offset)?;
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: text,
        }),
        range: None,
    })
}

/// `A` — "AND with the bit", `U` in German, 0.24 µs on the CPU.
fn operation(analysis: &Analysis, statement: &Statement) -> Option<String> {
    let word = lookup::slice(analysis, statement.op).trim();
    let set = lookup::mnemonics_of(analysis, 0);
    let upper = word.to_uppercase();
    let step7 = !analysis.built.s7_units.is_empty();
    let (summary, other, english) = if step7 {
        let op = crate::step7::mnemonics::operation(set, &upper)?;
        let summary = mnemonics::operation(set, &upper).map(|info| info.summary);
        let word_in = |set| crate::step7::mnemonics::op_word(set, op);
        (summary, word_in(set.other()), word_in(MnemonicSet::English))
    } else {
        let info = mnemonics::operation(set, &upper)?;
        let other = match set.other() {
            MnemonicSet::English => info.en,
            MnemonicSet::German => info.de,
        };
        (Some(info.summary), other, info.en)
    };
    let mut text = format!("**`{word}`**");
    if let Some(summary) = summary {
        text.push_str(&format!(" — {summary}"));
    }
    text.push_str(&format!(
        "\n\nIn {} mnemonics: `{other}`.",
        set.other().name()
    ));
    if let Some(table) = status_table(analysis, statement, english, step7) {
        text.push_str(&format!("\n\nStatus word:\n\n{table}"));
    }
    for note in crate::docs::status_notes(english, step7) {
        text.push_str(&format!("\n\n{note}"));
    }
    if let Some(ns) = execution_time(analysis, statement.whole) {
        text.push_str(&format!(
            "\n\nExecution time on {}: {:.2} µs.",
            analysis.profile.name,
            ns as f64 / 1000.0
        ));
    }
    Some(text)
}

/// Which status bits the operation reads and writes, on the bits the dialect's CPUs have.
/// A STEP 5 `JU`/`JC` with a block is a call, not the jump the table describes.
fn status_table(
    analysis: &Analysis,
    statement: &Statement,
    english: &str,
    step7: bool,
) -> Option<String> {
    let operand = lookup::slice(analysis, statement.operand).trim_start();
    if step7 {
        let effect = effects::of_statement(english, operand)?;
        return Some(effect.markdown(&effects::STEP7_BITS));
    }
    let kind: String = operand
        .chars()
        .take_while(char::is_ascii_alphabetic)
        .collect();
    if mnemonics::BlockKind::from_word(&kind).is_some() {
        return None;
    }
    Some(effects::of_step5(english)?.markdown(&effects::STEP5_BITS))
}

/// The time of the ops compiled from the statement written at `whole`, on the analysis' CPU.
fn execution_time(analysis: &Analysis, whole: Span) -> Option<u64> {
    let mut total = None;
    for block in &analysis.built.compiled.program.blocks {
        for (pc, span) in block.spans.iter().enumerate() {
            if *span == whole {
                *total.get_or_insert(0) += block.cost(pc);
            }
        }
    }
    total
}

fn line_of(analysis: &Analysis, span: Span) -> u32 {
    let text = analysis.text(span.file);
    LineIndex::new(text).position(span.start as usize).line + 1
}

fn label(analysis: &Analysis, target: &Target, name: &str) -> Option<String> {
    let at = navigate::definition(analysis, target)?;
    Some(format!(
        "jump label `{name}`, line {}",
        at.range.start.line + 1
    ))
}

/// The block's header and interface as written.
fn block(analysis: &Analysis, name: &str) -> Option<String> {
    for file in 0..analysis.built.sources.files.len() as u16 {
        let (blocks, _) = lookup::outline(analysis, file);
        let Some(found) = blocks
            .iter()
            .find(|block| block.name.eq_ignore_ascii_case(name))
        else {
            continue;
        };
        let mut text = format!(
            "```awl\n{}\n",
            lookup::slice(analysis, found.header).trim_end()
        );
        for span in &found.interface {
            text.push_str(lookup::slice(analysis, *span).trim_end());
            text.push('\n');
        }
        text.push_str(&format!(
            "```\n\n{} line {}",
            analysis.built.sources.get(file).name,
            line_of(analysis, found.header)
        ));
        return Some(text);
    }
    None
}

/// `-START`: its operand and comment from the assignment list.
fn symbol(analysis: &Analysis, name: &str) -> Option<String> {
    let entry = analysis.built.compiled.program.symbols.get(name)?;
    let mut text = format!("`{}`", entry.written());
    if let Some(operand) = entry.operand_text(lookup::mnemonics_of(analysis, 0)) {
        text.push_str(&format!(" = `{operand}`"));
    }
    if !entry.comment.trim().is_empty() {
        text.push_str(&format!(" — {}", entry.comment.trim()));
    }
    if let Some(id) = analysis.built.compiled.program.symbols.block_of(name)
        && let Some(interface) = block(analysis, &id.to_string())
    {
        text.push_str(&format!("\n\n{interface}"));
    }
    Some(text)
}

/// An absolute operand (`E 1.0`): its symbol and comment, when the list has one.
fn operand(analysis: &Analysis, written: &str) -> Option<String> {
    let written = written.split_whitespace().collect::<Vec<_>>().join(" ");
    let entry = analysis.built.compiled.program.symbols.entry_of(&written)?;
    let mut text = format!("`{written}` = `{}`", entry.written());
    if !entry.comment.trim().is_empty() {
        text.push_str(&format!(" — {}", entry.comment.trim()));
    }
    Some(text)
}
