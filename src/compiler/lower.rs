//! Lowering: one operation with a resolved operand to one op. Used by the compiler for every
//! statement and by the VM for operations on formal operands, once the actual is known.

use crate::address::Layout;
use crate::ast::Address;
use crate::mnemonics::{Area, BlockKind, OpCode};

use super::bytecode::*;

/// An operand after name resolution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resolved {
    None,
    Address(Address),
    Constant(u32),
    /// A block; `index` is its place in the program when it is loaded (logic blocks).
    Block {
        kind: BlockKind,
        number: u16,
        index: Option<u16>,
    },
    Label(u32),
    Number(u16),
    /// The n-th formal parameter of the running FB.
    Formal(u8),
    /// A STEP 7 actual parameter: its place in the program's S7 tables, in the caller.
    S7(u16),
}

/// `+G -G XG :G`; the compiler sets `stack` on CPUs with four accumulators.
fn float_arithmetic(kind: Arith) -> Op {
    Op::FloatArithmetic { kind, stack: false }
}

fn image_bit(layout: Layout, address: Address) -> Option<ImageBit> {
    matches!(address.area, Area::Input | Area::Output | Area::Flag).then(|| ImageBit {
        byte: layout.image_byte(address.area, address.index).unwrap_or(0),
        bit: address.bit,
    })
}

fn bit_target(layout: Layout, address: Address) -> Option<BitTarget> {
    match address.area {
        Area::DataBit => Some(BitTarget::Data {
            word: address.index,
            bit: address.bit,
        }),
        _ => image_bit(layout, address).map(BitTarget::Image),
    }
}

fn image_width(area: Area) -> Option<Width> {
    match area {
        Area::InputByte | Area::OutputByte | Area::FlagByte => Some(Width::Byte),
        Area::InputWord | Area::OutputWord | Area::FlagWord => Some(Width::Word),
        Area::FlagDouble => Some(Width::Double),
        _ => None,
    }
}

fn data_part(area: Area) -> Option<DataPart> {
    match area {
        Area::DataLeft => Some(DataPart::Left),
        Area::DataRight => Some(DataPart::Right),
        Area::DataWord => Some(DataPart::Word),
        Area::DataDouble => Some(DataPart::Double),
        _ => None,
    }
}

fn peripheral(area: Area) -> Option<(Width, bool)> {
    match area {
        Area::PeripheralByte => Some((Width::Byte, false)),
        Area::PeripheralWord => Some((Width::Word, false)),
        Area::ExtendedByte => Some((Width::Byte, true)),
        Area::ExtendedWord => Some((Width::Word, true)),
        _ => None,
    }
}

fn logic(op: OpCode) -> Option<Logic> {
    match op {
        OpCode::And => Some(Logic::And),
        OpCode::AndNot => Some(Logic::AndNot),
        OpCode::Or => Some(Logic::Or),
        OpCode::OrNot => Some(Logic::OrNot),
        _ => None,
    }
}

fn timer_kind(op: OpCode) -> Option<TimerKind> {
    match op {
        OpCode::TimerPulse => Some(TimerKind::Pulse),
        OpCode::TimerExtendedPulse => Some(TimerKind::ExtendedPulse),
        OpCode::TimerOnDelay => Some(TimerKind::OnDelay),
        OpCode::TimerStoredOnDelay => Some(TimerKind::StoredOnDelay),
        OpCode::TimerOffDelay => Some(TimerKind::OffDelay),
        _ => None,
    }
}

fn label_condition(op: OpCode) -> Option<JumpCondition> {
    match op {
        OpCode::JumpUnconditional => Some(JumpCondition::Always),
        OpCode::JumpConditional => Some(JumpCondition::Rlo),
        OpCode::JumpZero => Some(JumpCondition::Zero),
        OpCode::JumpNotZero => Some(JumpCondition::NotZero),
        OpCode::JumpPositive => Some(JumpCondition::Positive),
        OpCode::JumpMinus => Some(JumpCondition::Minus),
        OpCode::JumpOverflow => Some(JumpCondition::Overflow),
        _ => None,
    }
}

/// The op for an operation and its operand, or `None` when the operand does not fit.
/// `params` is the actual-parameter list of an FB call.
/// A STEP 5 data block's number: the STEP 5 parser takes none above 255, so the op keeps a
/// byte (STEP 7's `OPN DB n` is an S7 op with the whole number).
fn s5_db(number: u16) -> Option<u8> {
    u8::try_from(number).ok()
}

pub fn lower(op: OpCode, operand: Resolved, layout: Layout, params: u16) -> Option<Op> {
    use OpCode::*;
    use Resolved as R;
    if let R::Formal(param) = operand {
        return formal_allowed(op).then_some(Op::Formal { op, param });
    }
    let address = match operand {
        R::Address(address) => Some(address),
        _ => None,
    };
    let area = address.map(|address| address.area);
    let index = address.map_or(0, |address| address.index);
    Some(match (op, operand) {
        (And | AndNot | Or | OrNot, R::Address(address)) => {
            if let Some(bit) = image_bit(layout, address) {
                match op {
                    And => Op::And(bit),
                    AndNot => Op::AndNot(bit),
                    Or => Op::Or(bit),
                    _ => Op::OrNot(bit),
                }
            } else {
                let source = match address.area {
                    Area::DataBit => BitSource::Data {
                        word: address.index,
                        bit: address.bit,
                    },
                    Area::Timer => BitSource::Timer(address.index),
                    Area::Counter => BitSource::Counter(address.index),
                    _ => return None,
                };
                Op::LogicOther(logic(op)?, source)
            }
        }
        (Or, R::None) => Op::OrAlone,
        (AndBracket, R::None) => Op::AndBracket,
        (OrBracket, R::None) => Op::OrBracket,
        (CloseBracket, R::None) => Op::CloseBracket,
        (Assign | Set | Reset, R::Address(address)) => match (op, address.area) {
            (Set, Area::Counter) => Op::SetCounter(address.index),
            (Reset, Area::Counter) => Op::ResetCounter(address.index),
            (Reset, Area::Timer) => Op::ResetTimer(address.index),
            (_, Area::DataBit) => {
                let write = match op {
                    Assign => Write::Assign,
                    Set => Write::Set,
                    _ => Write::Reset,
                };
                Op::WriteData {
                    write,
                    word: address.index,
                    bit: address.bit,
                }
            }
            _ => {
                let bit = image_bit(layout, address)?;
                match op {
                    Assign => Op::Assign(bit),
                    Set => Op::Set(bit),
                    _ => Op::Reset(bit),
                }
            }
        },
        (Load, R::Constant(value)) => Op::LoadConstant(value),
        (Load | Transfer, R::Address(_)) => {
            let area = area?;
            let load = op == Load;
            if let Some(width) = image_width(area) {
                let byte = layout.image_byte(area, index)?;
                if load {
                    Op::load_image(width, byte)
                } else {
                    Op::transfer_image(width, byte)
                }
            } else if let Some(part) = data_part(area) {
                if load {
                    Op::LoadData(part, index)
                } else {
                    Op::TransferData(part, index)
                }
            } else if let Some((width, extended)) = peripheral(area) {
                if load {
                    Op::LoadPeripheral {
                        width,
                        byte: index,
                        extended,
                    }
                } else {
                    Op::TransferPeripheral {
                        width,
                        byte: index,
                        extended,
                    }
                }
            } else {
                match (load, area) {
                    (true, Area::Timer) => Op::LoadTimer(index),
                    (true, Area::Counter) => Op::LoadCounter(index),
                    _ => return None,
                }
            }
        }
        (LoadCoded, R::Address(_)) => match area? {
            Area::Timer => Op::LoadTimerCoded(index),
            Area::Counter => Op::LoadCounterCoded(index),
            _ => return None,
        },
        (
            TimerPulse | TimerExtendedPulse | TimerOnDelay | TimerStoredOnDelay | TimerOffDelay,
            R::Address(_),
        ) if area == Some(Area::Timer) => Op::StartTimer(timer_kind(op)?, index),
        (Enable, R::Address(_)) => match area? {
            Area::Timer => Op::EnableTimer(index),
            Area::Counter => Op::EnableCounter(index),
            _ => return None,
        },
        (CountUp, R::Address(_)) if area == Some(Area::Counter) => Op::CountUp(index),
        (CountDown, R::Address(_)) if area == Some(Area::Counter) => Op::CountDown(index),
        (AddFixed, R::None) => Op::Arithmetic(Arith::Add),
        (SubFixed, R::None) => Op::Arithmetic(Arith::Sub),
        (MulFixed, R::None) => Op::Arithmetic(Arith::Mul),
        (DivFixed, R::None) => Op::Arithmetic(Arith::Div),
        (CmpEq, R::None) => Op::Compare(Comparison::Eq),
        (CmpNe, R::None) => Op::Compare(Comparison::Ne),
        (CmpGt, R::None) => Op::Compare(Comparison::Gt),
        (CmpGe, R::None) => Op::Compare(Comparison::Ge),
        (CmpLt, R::None) => Op::Compare(Comparison::Lt),
        (CmpLe, R::None) => Op::Compare(Comparison::Le),
        (AddFloat, R::None) => float_arithmetic(Arith::Add),
        (SubFloat, R::None) => float_arithmetic(Arith::Sub),
        (MulFloat, R::None) => float_arithmetic(Arith::Mul),
        (DivFloat, R::None) => float_arithmetic(Arith::Div),
        (CmpEqFloat, R::None) => Op::FloatCompare(Comparison::Eq),
        (CmpNeFloat, R::None) => Op::FloatCompare(Comparison::Ne),
        (CmpGtFloat, R::None) => Op::FloatCompare(Comparison::Gt),
        (CmpGeFloat, R::None) => Op::FloatCompare(Comparison::Ge),
        (CmpLtFloat, R::None) => Op::FloatCompare(Comparison::Lt),
        (CmpLeFloat, R::None) => Op::FloatCompare(Comparison::Le),
        (FixedToFloat, R::None) => Op::Convert(Conversion::FixedToFloat),
        (FloatToFixed, R::None) => Op::Convert(Conversion::FloatToFixed),
        (BcdToFixed, R::None) => Op::Convert(Conversion::BcdToFixed),
        (FixedToBcd, R::None) => Op::Convert(Conversion::FixedToBcd),
        (BcdToFixedDouble, R::None) => Op::Convert(Conversion::BcdToFixedDouble),
        (FixedToBcdDouble, R::None) => Op::Convert(Conversion::FixedToBcdDouble),
        (
            JumpUnconditional | JumpConditional,
            R::Block {
                kind,
                number,
                index,
            },
        ) if !kind.is_data() => {
            let conditional = op == JumpConditional;
            match index {
                Some(block) => Op::Call {
                    block,
                    conditional,
                    params,
                },
                None => Op::CallMissing {
                    kind,
                    number,
                    conditional,
                },
            }
        }
        (
            OpenDb,
            R::Block {
                kind: BlockKind::Db,
                number,
                ..
            },
        ) => Op::OpenDb(s5_db(number)?),
        (
            GenerateDb,
            R::Block {
                kind: BlockKind::Db,
                number,
                ..
            },
        ) => Op::GenerateDb(s5_db(number)?),
        (BlockEnd, R::None) => Op::BlockEnd,
        (BlockEndConditional, R::None) => Op::BlockEndConditional,
        (BlockEndUnconditional, R::None) => Op::BlockEndUnconditional,
        (Nop, R::Number(0 | 1)) => Op::Nop,
        (Display, R::Number(n)) if n <= 255 => Op::Nop,
        (Stop, R::None) => Op::Stop,
        (_, R::Label(target)) => Op::Jump(label_condition(op)?, target),
        (AndWord, R::None) => Op::WordLogic(WordLogic::And),
        (OrWord, R::None) => Op::WordLogic(WordLogic::Or),
        (XorWord, R::None) => Op::WordLogic(WordLogic::Xor),
        (ShiftLeft, R::Number(n)) if n <= 15 => Op::ShiftLeft(n as u8),
        (ShiftRight, R::Number(n)) if n <= 15 => Op::ShiftRight(n as u8),
        (OnesComplement, R::None) => Op::OnesComplement,
        (TwosComplement, R::None) => Op::TwosComplement,
        (Swap, R::None) => Op::Swap,
        (Enter, R::None) => Op::Enter,
        (Increment, R::Number(n)) if n <= 255 => Op::Increment(n as u8),
        (Decrement, R::Number(n)) if n <= 255 => Op::Decrement(n as u8),
        (Indirect, R::Address(_)) => match area? {
            Area::FlagWord => Op::Indirect {
                source: IndirectSource::FlagWord(layout.image_byte(Area::FlagWord, index)?),
                template: 0,
            },
            Area::DataWord => Op::Indirect {
                source: IndirectSource::DataWord(index),
                template: 0,
            },
            _ => return None,
        },
        (SetUnconditional, R::Address(address)) => {
            Op::SetUnconditional(bit_target(layout, address)?)
        }
        (ResetUnconditional, R::Address(address)) => {
            Op::ResetUnconditional(bit_target(layout, address)?)
        }
        (TestBit, R::Address(address)) => Op::TestBit {
            negate: false,
            target: bit_target(layout, address)?,
        },
        (TestBitNot, R::Address(address)) => Op::TestBit {
            negate: true,
            target: bit_target(layout, address)?,
        },
        (DisableInterrupts, R::None) => Op::Interrupts { enabled: false },
        (EnableInterrupts, R::None) => Op::Interrupts { enabled: true },
        (TransferBytes, R::Number(operand)) if (1..=255).contains(&operand) => {
            Op::NotSimulated { op, operand }
        }
        (LoadIndirect | TransferIndirect, R::Number(operand)) if operand <= 15 => {
            Op::NotSimulated { op, operand }
        }
        (AddToBr | LoadRelativeBr | TransferRelativeBr, R::Number(operand)) => {
            Op::NotSimulated { op, operand }
        }
        (MoveBrToAccu | MoveAccuToBr | MoveSaToAccu | MoveAccuToSa, R::None) => {
            Op::NotSimulated { op, operand: 0 }
        }
        _ => return None,
    })
}

/// Operations that may take a formal operand (`A =EIN`, `L =WERT`, `JU =BLK`).
fn formal_allowed(op: OpCode) -> bool {
    use OpCode::*;
    matches!(
        op,
        And | AndNot
            | Or
            | OrNot
            | Assign
            | Set
            | Reset
            | Load
            | Transfer
            | LoadCoded
            | TimerPulse
            | TimerExtendedPulse
            | TimerOnDelay
            | TimerStoredOnDelay
            | TimerOffDelay
            | Enable
            | CountUp
            | CountDown
            | JumpUnconditional
            | JumpConditional
            | OpenDb
            | SetUnconditional
            | ResetUnconditional
            | TestBit
            | TestBitNot
            | ResetBinary
            | ResetDigital
            | LoadBitPattern
            | LoadDecimal
            | Indirect
    )
}
