//! How many 16-bit words each statement takes in MC5, the STEP 5 machine code, so a listing
//! numbers its statements by word address as the PG does (`0000 :L KF +20` takes two words, the
//! next statement is `0002`). `grammar/README.md` ("Statement addresses") has the table and
//! where each length comes from.

use crate::ast::{Operand, Statement};
use crate::mnemonics::{Area, BlockKind, ConstFormat, OpCode};

/// Every block starts with a five-word header; the fifth word is the block's length in words,
/// the header included (CPU 928B Programming Guide, 8.3.1).
pub const BLOCK_HEADER_WORDS: u32 = 5;

/// The `BLD 255` that separates two segments: the PG shows it as `***`.
pub const SEGMENT_END_WORDS: u32 = 1;

/// The words before a function block's first statement: the jump over the description (one
/// word; CPU 928B Programming Guide, 8.3.2), the block's name (four words: eight characters)
/// and three words per formal parameter (kind and format, then the four-character name).
pub fn function_block_description(params: usize) -> u32 {
    5 + 3 * params as u32
}

/// The words of one statement, the parameter lines of an FB call included: the call, one jump
/// word over the parameters (the PG shows it as the `NAME :` line) and one word per parameter.
pub fn statement_words(statement: &Statement) -> u32 {
    let own = operation_words(statement.op, &statement.operand);
    if calls_function_block(statement) {
        own + 1 + statement.call_params.len() as u32
    } else {
        own
    }
}

/// `JU FB 5` / `JC FX 2`: a call that carries actual parameters (and their jump word).
pub fn calls_function_block(statement: &Statement) -> bool {
    matches!(
        statement.op,
        OpCode::JumpUnconditional | OpCode::JumpConditional
    ) && matches!(statement.operand, Operand::Block(target) if target.kind.is_function())
}

fn operation_words(op: OpCode, operand: &Operand) -> u32 {
    match (op, operand) {
        // `L KB`: the byte rides in the operation word; every other constant follows it in
        // words of its own.
        (OpCode::Load | OpCode::AddConstant, Operand::Constant(constant)) => {
            match constant.format {
                ConstFormat::Byte => 1,
                format => 1 + u32::from(format.words()),
            }
        }
        (
            OpCode::SetUnconditional
            | OpCode::ResetUnconditional
            | OpCode::TestBit
            | OpCode::TestBitNot,
            _,
        ) => 2,
        // A 16-bit displacement does not fit beside the operation code.
        (OpCode::AddToBr | OpCode::LoadRelativeBr | OpCode::TransferRelativeBr, _) => 2,
        // Bit operations on data bits have no one-word form.
        (_, Operand::Address(address)) if address.area == Area::DataBit => 2,
        // The extended blocks: `JU FX`, `C DX`, `G DX`.
        (_, Operand::Block(block)) if matches!(block.kind, BlockKind::Fx | BlockKind::Dx) => 2,
        _ => 1,
    }
}
