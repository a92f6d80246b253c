//! Execution time of each op, from the CPU profile's timing table.

use crate::profile::Timings;

use super::bytecode::*;

pub fn cost(op: Op, t: &Timings) -> u32 {
    match op {
        image_bit_ops!(_) | Op::OrAlone | Op::AndBracket | Op::OrBracket | Op::CloseBracket => {
            t.bit_image
        }
        Op::LogicOther(_, BitSource::Data { .. }) | Op::WriteData { .. } => t.bit_data,
        Op::LogicOther(_, _) => t.bit_timer_counter,
        Op::SetUnconditional(target)
        | Op::ResetUnconditional(target)
        | Op::TestBit { target, .. } => match target {
            BitTarget::Image(_) => t.bit_image,
            BitTarget::Data { .. } => t.bit_data,
        },
        Op::LoadImageByte(_) | Op::TransferImageByte(_) => t.load_byte,
        Op::LoadImageWord(_) | Op::TransferImageWord(_) => t.load_word,
        Op::LoadImageDouble(_) | Op::TransferImageDouble(_) => t.load_double,
        Op::LoadData(..) | Op::TransferData(..) => t.load_data,
        Op::LoadPeripheral { .. } | Op::TransferPeripheral { .. } => t.load_peripheral,
        Op::LoadConstant(_) => t.load_constant,
        timer_counter_ops!() => t.timer_counter,
        Op::Arithmetic(Arith::Add | Arith::Sub) | Op::ArithmeticStack(Arith::Add | Arith::Sub) => {
            t.add_sub
        }
        Op::Arithmetic(Arith::Mul) | Op::ArithmeticStack(Arith::Mul) => t.multiply,
        Op::Arithmetic(Arith::Div) | Op::ArithmeticStack(Arith::Div) => t.divide,
        Op::Compare(_) | Op::FloatCompare(_) => t.compare,
        // The profiles time floating point in their fixed-point classes.
        Op::FloatArithmetic {
            kind: Arith::Add | Arith::Sub,
            ..
        } => t.add_sub,
        Op::FloatArithmetic {
            kind: Arith::Mul, ..
        } => t.multiply,
        Op::FloatArithmetic {
            kind: Arith::Div, ..
        } => t.divide,
        Op::Convert(_) => t.add_sub,
        Op::Call { .. } | Op::CallAt { .. } | Op::CallMissing { .. } => t.block_call,
        // An estimate: the call, its end, and about forty operations of the block's body.
        Op::Builtin { .. } => t.block_call + t.block_end + 40 * t.load_word,
        Op::BlockEnd | Op::BlockEndConditional | Op::BlockEndUnconditional => t.block_end,
        Op::OpenDb(_) | Op::GenerateDb(_) => t.open_db,
        Op::Jump(..) => t.jump,
        Op::WordLogic(_) => t.word_logic,
        Op::ShiftLeft(_)
        | Op::ShiftRight(_)
        | Op::OnesComplement
        | Op::TwosComplement
        | Op::Swap
        | Op::Enter
        | Op::Increment(_)
        | Op::Decrement(_) => t.accumulator,
        Op::Indirect { .. } => t.load_word + t.other,
        Op::AddConstant { .. } => t.accumulator,
        Op::NotSimulated { .. } => t.other,
        Op::S7(code) => crate::step7::bytecode::cost(code, t),
        Op::S7Scan(..) | Op::S7Write(..) => t.bit_image,
        Op::Nop | Op::Stop | Op::Interrupts { .. } | Op::Formal { .. } => t.other,
        // Never compiled: their ops are timed one by one.
        Op::End | Op::Native(_) | fused_pairs!() => 0,
    }
}
