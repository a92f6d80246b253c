//! The block program status shows, as the command line and the online page name it:
//! absolute (`PB 3`, `FC 1`) or by its symbol as a program writes it (`-FILL`, `"Valve"`).

use crate::ast::BlockId;
use crate::compiler::Program;
use crate::mnemonics::BlockKind;

use super::StatusError;

/// A block as it is named.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BlockRef {
    Id(BlockId),
    Symbol(String),
}

impl BlockRef {
    /// `PB 3`, `-FILL`, `"Valve"`; the error says how to write a block.
    pub fn parse(text: &str) -> Result<BlockRef, String> {
        let text = text.trim();
        if crate::symbols::symbol_written(text).is_some() {
            return Ok(BlockRef::Symbol(text.to_string()));
        }
        BlockId::parse(text).map(BlockRef::Id).ok_or_else(|| {
            format!("`{text}` is not a block; write e.g. \"PB 3\", -FILL or '\"Valve\"'")
        })
    }

    /// As it was written.
    pub fn written(&self) -> String {
        match self {
            BlockRef::Id(id) => id.to_string(),
            BlockRef::Symbol(written) => written.clone(),
        }
    }
}

/// The index of the logic block `block` names in `program`, or why it names none: a symbol or
/// a block the program does not have, or a data block.
pub fn find(program: &Program, block: &BlockRef) -> Result<u16, StatusError> {
    let id = match block {
        BlockRef::Id(id) => *id,
        BlockRef::Symbol(written) => {
            program
                .symbols
                .block_of(written)
                .ok_or_else(|| StatusError::UnknownBlock {
                    block: written.clone(),
                    hint: program
                        .symbols
                        .suggest_block(written)
                        .map(|hint| format!("{hint} "))
                        .unwrap_or_default(),
                    known: known(program, |id| program.symbols.decorate(&id.to_string())),
                })?
        }
    };
    if matches!(id.kind, BlockKind::Db | BlockKind::Dx) {
        return Err(StatusError::DataBlock {
            block: id.to_string(),
        });
    }
    program
        .block_index(id)
        .ok_or_else(|| StatusError::UnknownBlock {
            block: id.to_string(),
            hint: String::new(),
            known: known(program, |id| id.to_string()),
        })
}

/// The program's blocks, as `name` writes each.
fn known(program: &Program, name: impl Fn(BlockId) -> String) -> String {
    program
        .blocks
        .iter()
        .map(|block| name(block.id))
        .collect::<Vec<_>>()
        .join(", ")
}
