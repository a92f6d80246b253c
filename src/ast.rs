//! The syntax tree: blocks of statements with spans, in language-independent terms.

use crate::mnemonics::{Area, BlockKind, ConstFormat, MnemonicSet, OpCode, ParamKind};
use crate::source::{FileId, Span};

/// A block's type and number, written `PB 3`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BlockId {
    pub kind: BlockKind,
    pub number: u16,
}

impl BlockId {
    /// `PB 3`, `pb3`, `OB 1`, STEP 7's `FC 1`: a block as the command line names it.
    pub fn parse(text: &str) -> Option<BlockId> {
        let text = text.trim();
        let split = text.find(|c: char| !c.is_ascii_alphabetic())?;
        let (kind, number) = text.split_at(split);
        let kind = BlockKind::ALL
            .into_iter()
            .chain([BlockKind::Fc])
            .find(|k| k.name().eq_ignore_ascii_case(kind))?;
        Some(BlockId {
            kind,
            number: number.trim().parse().ok()?,
        })
    }
}

impl std::fmt::Display for BlockId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}", self.kind.name(), self.number)
    }
}

/// A name with where it was written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Name {
    pub text: String,
    pub span: Span,
}

/// One parsed source file.
#[derive(Debug, Clone)]
pub struct SourceUnit {
    pub file: FileId,
    pub mnemonics: MnemonicSet,
    pub blocks: Vec<Block>,
}

#[derive(Debug, Clone)]
pub struct Block {
    pub id: BlockId,
    /// The header line `PB 3`.
    pub header: Span,
    pub body: BlockBody,
}

#[derive(Debug, Clone)]
pub enum BlockBody {
    Logic(LogicBody),
    Data(Vec<DataWord>),
}

#[derive(Debug, Clone, Default)]
pub struct LogicBody {
    /// `NAME :MOTOR` of a function block.
    pub name: Option<Name>,
    pub params: Vec<ParamDecl>,
    pub statements: Vec<Statement>,
    /// Where the final `BE` stands; `None` when the block has none.
    pub end: Option<Span>,
}

/// `DES :EIN I BI` — a formal parameter of a function block.
#[derive(Debug, Clone)]
pub struct ParamDecl {
    pub name: Name,
    pub kind: ParamKind,
    pub format: Option<ParamFormat>,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamFormat {
    Bit,
    Byte,
    Word,
    Constant(ConstFormat),
}

#[derive(Debug, Clone)]
pub struct Statement {
    pub label: Option<Name>,
    pub op: OpCode,
    pub op_span: Span,
    pub operand: Operand,
    pub operand_span: Span,
    /// The parameter lines after `JU FB n` / `JC FB n`.
    pub call_params: Vec<CallParam>,
    /// The segment of a PG listing it is in (`SEGMENT 2`); 0 outside segments.
    pub segment: u16,
    /// The whole line.
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Operand {
    None,
    Address(Address),
    Constant(Constant),
    Block(BlockId),
    /// `=NAME`: a formal operand, or a jump label inside a function block.
    Symbol(String),
    /// A plain number: `NOP 0`, `BLD 130`, `I 1`, `SLW 3`.
    Number(u16),
    /// `-NAME`: a symbol of the assignment list; replaced by its operand before compiling.
    Assigned(String),
}

/// `I 0.0`, `FW 10`, `T 5`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Address {
    pub area: Area,
    /// Byte, word, timer or counter number.
    pub index: u16,
    /// The bit of a bit address.
    pub bit: u8,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Constant {
    pub format: ConstFormat,
    /// The constant as the CPU loads it; 32-bit formats fill all bits.
    pub value: u32,
    /// Data words of a character string longer than two characters (DB bodies).
    pub extra_words: Vec<u16>,
}

/// `EIN :I 0.0` — one actual parameter of an FB call.
#[derive(Debug, Clone)]
pub struct CallParam {
    pub name: Name,
    pub actual: Operand,
    pub actual_span: Span,
    pub span: Span,
}

/// `0: KF +100` — a data word of a data block.
#[derive(Debug, Clone)]
pub struct DataWord {
    pub index: u16,
    pub constant: Constant,
    pub span: Span,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_line_blocks_include_step7_functions() {
        let fc = BlockId::parse("fc 12").unwrap();
        assert_eq!((fc.kind, fc.number), (BlockKind::Fc, 12));
        assert_eq!(BlockId::parse("PB3").unwrap().kind, BlockKind::Pb);
        assert!(BlockId::parse("XY 1").is_none());
    }
}
