//! Replaces every `-NAME` of the parsed program by the operand the assignment list gives it.

use crate::ast::{BlockBody, Operand, SourceUnit};
use crate::mnemonics::{self, OpCode};
use crate::source::{SourceSet, Span};

use super::{Entry, SymbolError, Symbols};

/// Operations whose operand is a block.
fn takes_block(op: OpCode) -> bool {
    matches!(
        op,
        OpCode::JumpUnconditional | OpCode::JumpConditional | OpCode::OpenDb | OpCode::GenerateDb
    )
}

/// Where the program wrote symbols: those that could not be resolved (their errors are in
/// the list) and those that were, with their names.
#[derive(Debug, Default)]
pub struct Uses {
    pub failed: Vec<Span>,
    pub resolved: Vec<(Span, String)>,
}

/// Resolves the symbols of `units`.
pub fn resolve(
    units: &mut [SourceUnit],
    symbols: &Symbols,
    sources: &SourceSet,
    errors: &mut Vec<SymbolError>,
) -> Uses {
    let mut uses = Uses::default();
    for unit in units.iter_mut() {
        for block in &mut unit.blocks {
            let BlockBody::Logic(body) = &mut block.body else {
                continue;
            };
            for statement in &mut body.statements {
                let at = statement.operand_span;
                let op = statement.op;
                let set = unit.mnemonics;
                let operand = &mut statement.operand;
                uses.note(
                    replace(operand, Some(op), at, symbols, sources, set),
                    at,
                    errors,
                );
                for param in &mut statement.call_params {
                    let at = param.actual_span;
                    let result = replace(&mut param.actual, None, at, symbols, sources, set);
                    uses.note(result, at, errors);
                }
            }
        }
    }
    uses
}

impl Uses {
    fn note(
        &mut self,
        result: Result<Option<String>, Box<SymbolError>>,
        at: Span,
        errors: &mut Vec<SymbolError>,
    ) {
        match result {
            Ok(Some(name)) => self.resolved.push((at, name)),
            Ok(None) => {}
            Err(error) => {
                errors.push(*error);
                self.failed.push(at);
            }
        }
    }

    /// A compiler's "not an operand of `op`" at `at`, when a symbol was written there, said of
    /// the symbol.
    pub fn explain(
        &self,
        op: &str,
        at: Span,
        symbols: &Symbols,
        sources: &SourceSet,
        set: mnemonics::MnemonicSet,
    ) -> Option<SymbolError> {
        let (_, name) = self.resolved.iter().find(|(span, _)| *span == at)?;
        let entry = symbols.get(name)?;
        let mut explained = wrong_kind(entry, None, at, sources, set);
        if let SymbolError::WrongKind { op: slot, help, .. } = &mut explained {
            *slot = op.to_string();
            *help = Some(format!(
                "`{}` is defined in {} line {}; `{op}` takes another kind of operand",
                entry.written(),
                sources.get(entry.name_span.file).name,
                sources.line_of(entry.name_span)
            ));
        }
        Some(explained)
    }
}

/// Puts the symbol's operand in place of `-NAME`; the name, if there was one.
fn replace(
    operand: &mut Operand,
    op: Option<OpCode>,
    at: Span,
    symbols: &Symbols,
    sources: &SourceSet,
    set: mnemonics::MnemonicSet,
) -> Result<Option<String>, Box<SymbolError>> {
    let Operand::Assigned(name) = operand else {
        return Ok(None);
    };
    let Some(entry) = symbols.get(name) else {
        let help = symbols.suggest(name).or_else(|| {
            symbols.is_empty().then(|| {
                "give the assignment list with `--symbols FILE` or a scenario's `symbols = [...]`"
                    .to_string()
            })
        });
        return Err(Box::new(SymbolError::Unknown {
            written: format!("-{name}"),
            list: "assignment list",
            at,
            help,
        }));
    };
    let wants_block = op.is_some_and(takes_block);
    // The loader reads only STEP 5 lists for a STEP 5 program.
    let Some((stands, block)) = entry.step5() else {
        return Err(Box::new(wrong_kind(entry, op, at, sources, set)));
    };
    let resolved = match (wants_block, block, stands) {
        (true, Some(block), _) => Operand::Block(block),
        (true, None, Operand::Block(_)) | (false, _, Operand::Address(_)) => stands.clone(),
        (false, Some(_), Operand::Block(_)) if op.is_none() => stands.clone(),
        _ => return Err(Box::new(wrong_kind(entry, op, at, sources, set))),
    };
    let name = std::mem::replace(operand, resolved);
    match name {
        Operand::Assigned(name) => Ok(Some(name)),
        _ => Ok(None),
    }
}

fn wrong_kind(
    entry: &Entry,
    op: Option<OpCode>,
    at: Span,
    sources: &SourceSet,
    set: mnemonics::MnemonicSet,
) -> SymbolError {
    let stands_for = entry.operand_text(set).unwrap_or_default();
    let op = op.map_or_else(String::new, |op| mnemonics::op_word(set, op).to_string());
    let defined = entry.name_span;
    SymbolError::WrongKind {
        written: entry.written(),
        help: Some(format!(
            "`{}` is defined in {} line {}; use a symbol of the kind `{op}` takes",
            entry.written(),
            sources.get(defined.file).name,
            sources.line_of(defined)
        )),
        stands_for,
        op,
        at,
    }
}
