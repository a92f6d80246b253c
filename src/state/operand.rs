//! The value of an operation's operand, as program status shows it next to the statement:
//! bits 0/1, bytes `KH`, words `KF`, timers `KT`, counters `KZ`.

use crate::compiler::Op;
use crate::compiler::bytecode::{BitSource, BitTarget, DataPart, ImageBit, Width};
use crate::scenario::operand::Target;
use crate::vm::Cpu;

use super::watch::natural;

fn image_bit(cpu: &Cpu, bit: ImageBit) -> String {
    natural(
        cpu,
        Target::ImageBit {
            byte: bit.byte,
            bit: bit.bit,
        },
    )
}

fn image(cpu: &Cpu, width: Width, byte: u16) -> String {
    let bytes = width.bytes() as u8;
    natural(cpu, Target::Image { byte, bytes })
}

/// A data word of the open DB, or `-` when there is none.
fn data(cpu: &Cpu, part: DataPart, word: u16) -> String {
    let Some(value) = cpu.data_word(word) else {
        return "-".to_string();
    };
    match part {
        DataPart::Left => format!("KH {:02X}", value >> 8),
        DataPart::Right => format!("KH {:02X}", value & 0xFF),
        DataPart::Word => format!("KF {:+}", value as i16),
        DataPart::Double => match cpu.data_word(word + 1) {
            Some(low) => format!("KH {value:04X}{low:04X}"),
            None => "-".to_string(),
        },
    }
}

fn raw(value: u32, width: Width) -> String {
    match width {
        Width::Byte => format!("KH {:02X}", value as u8),
        Width::Word => format!("KF {:+}", value as u16 as i16),
        Width::Double => format!("KH {value:08X}"),
    }
}

fn data_bit(cpu: &Cpu, word: u16, bit: u8) -> String {
    cpu.data_word(word)
        .map_or("-".to_string(), |value| (value >> bit & 1).to_string())
}

fn bit_target(cpu: &Cpu, target: BitTarget) -> String {
    match target {
        BitTarget::Image(bit) => image_bit(cpu, bit),
        BitTarget::Data { word, bit } => data_bit(cpu, word, bit),
    }
}

/// The operand of `op` as it is now; `None` for operations without one that holds a value
/// (constants, jumps, block calls, accumulator operations).
pub fn value(cpu: &Cpu, op: Op) -> Option<String> {
    let timer = |n| natural(cpu, Target::TimerBit(n));
    let counter = |n| natural(cpu, Target::CounterValue(n));
    Some(match op {
        Op::And(bit)
        | Op::AndNot(bit)
        | Op::Or(bit)
        | Op::OrNot(bit)
        | Op::Assign(bit)
        | Op::Set(bit)
        | Op::Reset(bit) => image_bit(cpu, bit),
        Op::LogicOther(_, BitSource::Data { word, bit }) | Op::WriteData { word, bit, .. } => {
            data_bit(cpu, word, bit)
        }
        Op::LogicOther(_, BitSource::Timer(n))
        | Op::LoadTimer(n)
        | Op::LoadTimerCoded(n)
        | Op::StartTimer(_, n)
        | Op::EnableTimer(n)
        | Op::ResetTimer(n) => timer(n),
        Op::LogicOther(_, BitSource::Counter(n))
        | Op::LoadCounter(n)
        | Op::LoadCounterCoded(n)
        | Op::CountUp(n)
        | Op::CountDown(n)
        | Op::SetCounter(n)
        | Op::ResetCounter(n)
        | Op::EnableCounter(n) => counter(n),
        Op::LoadImageByte(byte) | Op::TransferImageByte(byte) => image(cpu, Width::Byte, byte),
        Op::LoadImageWord(byte) | Op::TransferImageWord(byte) => image(cpu, Width::Word, byte),
        Op::LoadImageDouble(byte) | Op::TransferImageDouble(byte) => {
            image(cpu, Width::Double, byte)
        }
        Op::LoadData(part, word) | Op::TransferData(part, word) => data(cpu, part, word),
        Op::SetUnconditional(target)
        | Op::ResetUnconditional(target)
        | Op::TestBit { target, .. } => bit_target(cpu, target),
        // What a load read from an input module is in ACCU 1 now.
        Op::LoadPeripheral { width, .. } => raw(cpu.level.accu1, width),
        Op::TransferPeripheral {
            width,
            byte,
            extended,
        } => natural(
            cpu,
            Target::Periphery {
                byte,
                bytes: width.bytes() as u8,
                extended,
            },
        ),
        Op::OrAlone
        | Op::AndBracket
        | Op::OrBracket
        | Op::CloseBracket
        | Op::LoadConstant(_)
        | Op::FloatArithmetic { .. }
        | Op::FloatCompare(_)
        | Op::Convert(_)
        | Op::Arithmetic(_)
        | Op::ArithmeticStack(_)
        | Op::Compare(_)
        | Op::Call { .. }
        | Op::CallAt { .. }
        | Op::CallMissing { .. }
        | Op::Builtin { .. }
        | Op::OpenDb(_)
        | Op::BlockEnd
        | Op::BlockEndConditional
        | Op::BlockEndUnconditional
        | Op::Nop
        | Op::Stop
        | Op::End
        | Op::LogicPair { .. }
        | Op::S7ScanPair { .. }
        | Op::S7ScanWrite { .. }
        | Op::LogicWrite { .. }
        | Op::LoadWordConstant { .. }
        | Op::LoadWords { .. }
        | Op::ArithmeticTransferWord { .. }
        | Op::Jump(..)
        | Op::WordLogic(_)
        | Op::ShiftLeft(_)
        | Op::ShiftRight(_)
        | Op::OnesComplement
        | Op::TwosComplement
        | Op::Swap
        | Op::Enter
        | Op::Increment(_)
        | Op::Decrement(_)
        | Op::DisableInterrupts
        | Op::EnableInterrupts
        | Op::GenerateDb(_)
        | Op::Indirect { .. }
        | Op::Formal { .. }
        | Op::AddConstant { .. }
        | Op::NotSimulated { .. }
        | Op::S7(_)
        | Op::S7Scan(..)
        | Op::S7Write(..) => return None,
    })
}
