//! `awl dump`: each block's bytecode with source line numbers, each op with what it does in the
//! user's terms (see `annotate`), each data word as written.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::ast::{Block, BlockBody, BlockId, DataWord, Statement};
use crate::compiler::DataBlockImage;
use crate::frontend::Frontend;
use crate::source::{SourceSet, Span};

pub mod annotate;
pub mod listing;
pub mod mc5;
pub mod step7;

pub use annotate::op_text;

/// `awl dump --listing` on a STEP 7 program: a PG listing (word addresses, `***`, `LEN=`) is
/// STEP 5's printout; a STEP 7 source has no such form.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("`--listing` prints a STEP 5 PG listing, and `{file}` is a STEP 7 program")]
#[diagnostic(
    code(awl::cli::listing_step7),
    help(
        "`awl dump` without `--listing` shows each STEP 7 statement with the operations it runs; the STEP 7 source is its own listing"
    )
)]
pub struct ListingOfStep7 {
    pub file: String,
}

/// The PG listing of a STEP 5 program (see [`listing::listing`]).
pub fn listing_of(built: &Frontend) -> Result<String, ListingOfStep7> {
    match built.s7_units.first() {
        Some(unit) => Err(ListingOfStep7 {
            file: built.sources.get(unit.file).name.clone(),
        }),
        None => Ok(listing::listing(built)),
    }
}

/// The parsed blocks of every program file, by block.
pub(crate) fn parsed_blocks(built: &Frontend) -> HashMap<BlockId, &Block> {
    built
        .units
        .iter()
        .flat_map(|unit| &unit.blocks)
        .map(|block| (block.id, block))
        .collect()
}

/// `PB 3  (file.awl:12, 4 ops)`
fn header(
    out: &mut String,
    sources: &SourceSet,
    id: impl std::fmt::Display,
    at: Span,
    count: usize,
    unit: &str,
) {
    let file = sources.get(at.file);
    let _ = writeln!(
        out,
        "{id}  ({}:{}, {count} {unit})",
        file.name,
        file.line_of(at.start)
    );
}

/// The whole dump: a header line per block, then one line per op or data word.
pub fn dump(built: &Frontend) -> String {
    if !built.s7_units.is_empty() {
        return step7::dump(built);
    }
    let program = &built.compiled.program;
    let sources = &built.sources;
    let parsed = parsed_blocks(built);
    let mut out = String::new();
    for block in &program.blocks {
        header(
            &mut out,
            sources,
            block.id,
            block.header,
            block.code.len(),
            "ops",
        );
        let statements: &[Statement] = match parsed.get(&block.id).map(|parsed| &parsed.body) {
            Some(BlockBody::Logic(body)) if body.statements.len() == block.code.len() => {
                &body.statements
            }
            _ => &[],
        };
        let context = annotate::Context {
            program,
            sources,
            set: block.mnemonics,
            params: &block.params,
            statements,
        };
        for (pc, (op, span)) in block.code.iter().zip(&block.spans).enumerate() {
            if let Some(&(_, segment)) = block
                .segments
                .iter()
                .find(|(first, _)| *first as usize == pc)
                && segment != 0
            {
                let _ = writeln!(out, "  segment {segment}");
            }
            let line = sources.line_of(*span);
            let text = sources.get(span.file).slice(*span);
            let _ = writeln!(
                out,
                "  {pc:>4}  line {line:>4}  {:<28} {}",
                text,
                op_text(*op, pc, context)
            );
        }
        out.push('\n');
    }
    for data in &program.data_blocks {
        header(
            &mut out,
            sources,
            data.id,
            data.header,
            data.words.len(),
            "words",
        );
        let words = match parsed.get(&data.id).map(|parsed| &parsed.body) {
            Some(BlockBody::Data(words)) => words.as_slice(),
            _ => &[],
        };
        data_words(&mut out, sources, data, words);
        out.push('\n');
    }
    out
}

/// One line per data word: the constant that starts there as written, or what covers it.
fn data_words(out: &mut String, sources: &SourceSet, data: &DataBlockImage, written: &[DataWord]) {
    // Data word → the line that wrote it and whether the word is that constant's first.
    let mut by_word: HashMap<usize, (&DataWord, bool)> = HashMap::new();
    for word in written {
        let first = usize::from(word.index);
        for at in first..first + data_words_of(word) {
            by_word.insert(at, (word, at == first));
        }
    }
    for index in 0..data.words.len() {
        let text = match by_word.get(&index) {
            Some((word, true)) => {
                let file = sources.get(word.span.file);
                format!(
                    "line {:>4}  {}",
                    file.line_of(word.span.start),
                    annotate::written_constant(data_constant_text(file.slice(word.span)))
                )
            }
            Some((word, false)) => format!("           (continues DW {})", word.index),
            None => "           (not written: 0)".to_string(),
        };
        let _ = writeln!(out, "  DW {index:>4}  {text}");
    }
}

/// The words one data line fills: 32-bit formats take two per value, a long `KS` string one per
/// two characters.
fn data_words_of(word: &DataWord) -> usize {
    let values = 1 + word.constant.extra_words.len();
    values * usize::from(word.constant.format.words())
}

/// A data line's constant without its word number: `3:  KF +5` → `KF +5`.
pub(crate) fn data_constant_text(line: &str) -> &str {
    let line = line.trim_start();
    let digits = line.len() - line.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    match line[digits..].trim_start().strip_prefix(':') {
        Some(rest) if digits > 0 => rest.trim_start(),
        _ => line,
    }
}
