//! Replaces every `-NAME` of the parsed program by the operand the assignment list gives it.

use crate::ast::{BlockBody, Operand, SourceUnit};
use crate::mnemonics::{self, OpCode};
use crate::source::{SourceSet, Span};

use super::{Entry, SymbolError, Symbols, operand_text};

/// Operations whose operand is a block.
fn takes_block(op: OpCode) -> bool {
    matches!(
        op,
        OpCode::JumpUnconditional | OpCode::JumpConditional | OpCode::OpenDb | OpCode::GenerateDb
    )
}

/// Resolves the symbols of `units`; the spans of those that could not be (their errors are
/// in the list), so that the compiler's own complaints about them can be left out.
pub fn resolve(
    units: &mut [SourceUnit],
    symbols: &Symbols,
    sources: &SourceSet,
    errors: &mut Vec<SymbolError>,
) -> Vec<Span> {
    let mut failed = Vec::new();
    for unit in units.iter_mut() {
        for block in &mut unit.blocks {
            let BlockBody::Logic(body) = &mut block.body else {
                continue;
            };
            for statement in &mut body.statements {
                let at = statement.operand_span;
                let op = statement.op;
                let set = unit.mnemonics;
                if let Err(error) =
                    replace(&mut statement.operand, Some(op), at, symbols, sources, set)
                {
                    errors.push(*error);
                    failed.push(at);
                }
                for param in &mut statement.call_params {
                    let at = param.actual_span;
                    if let Err(error) = replace(&mut param.actual, None, at, symbols, sources, set)
                    {
                        errors.push(*error);
                        failed.push(at);
                    }
                }
            }
        }
    }
    failed
}

fn replace(
    operand: &mut Operand,
    op: Option<OpCode>,
    at: Span,
    symbols: &Symbols,
    sources: &SourceSet,
    set: mnemonics::MnemonicSet,
) -> Result<(), Box<SymbolError>> {
    let Operand::Assigned(name) = operand else {
        return Ok(());
    };
    let Some(entry) = symbols.get(name) else {
        let help = symbols.suggest(name).or_else(|| {
            symbols.is_empty().then(|| {
                "give the assignment list with `--symbols FILE` or a scenario's `symbols = [...]`"
                    .to_string()
            })
        });
        return Err(Box::new(SymbolError::Unknown {
            name: name.clone(),
            at,
            help,
        }));
    };
    let wants_block = op.is_some_and(takes_block);
    let resolved = match (wants_block, entry.block, &entry.operand) {
        (true, Some(block), _) => Operand::Block(block),
        (true, None, Operand::Block(_)) | (false, _, Operand::Address(_)) => entry.operand.clone(),
        (false, Some(_), Operand::Block(_)) if op.is_none() => entry.operand.clone(),
        _ => return Err(Box::new(wrong_kind(entry, op, at, sources, set))),
    };
    *operand = resolved;
    Ok(())
}

fn wrong_kind(
    entry: &Entry,
    op: Option<OpCode>,
    at: Span,
    sources: &SourceSet,
    set: mnemonics::MnemonicSet,
) -> SymbolError {
    let stands_for = operand_text(&entry.operand, set).unwrap_or_default();
    let op = op.map_or_else(String::new, |op| mnemonics::op_word(set, op).to_string());
    let defined = entry.name_span;
    SymbolError::WrongKind {
        name: entry.name.clone(),
        help: Some(format!(
            "`-{}` is defined in {} line {}; use a symbol of the kind `{op}` takes",
            entry.name,
            sources.get(defined.file).name,
            sources.line_of(defined)
        )),
        stands_for,
        op,
        at,
    }
}
