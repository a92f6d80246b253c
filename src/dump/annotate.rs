//! What `awl dump` says about each op, in the user's terms: the verb in plain English, the
//! operand with its area in the block's mnemonic set (`count up Z 1` in a German file), a
//! constant as it was written (`load constant KF +20`), jump targets by their label.

use crate::address::Layout;
use crate::ast::{CallParam, ParamDecl, Statement};
use crate::compiler::Program;
use crate::compiler::builtin::Builtin;
use crate::compiler::bytecode::{
    Arith, BitSource, BitTarget, Comparison, DataPart, ImageBit, IndirectSource, JumpCondition,
    Logic, Op, TimerKind, Width, WordLogic, Write, fused_pairs,
};
use crate::mnemonics::{self, Area, MnemonicSet, OpCode};
use crate::source::SourceSet;

/// Everything an op's text needs beyond the op itself.
#[derive(Clone, Copy)]
pub struct Context<'a> {
    pub program: &'a Program,
    pub sources: &'a SourceSet,
    pub set: MnemonicSet,
    /// The formal parameters of the block the op is in.
    pub params: &'a [ParamDecl],
    /// The block's statements as parsed, parallel to its code.
    pub statements: &'a [Statement],
}

impl Context<'_> {
    fn word(self, area: Area) -> &'static str {
        mnemonics::area_word(self.set, area)
    }

    /// `text` with its symbol, if it has one: `E 1.0 (-START)`.
    fn named(self, text: String) -> String {
        match self.program.symbols.written_of(&text) {
            Some(name) => format!("{text} ({name})"),
            None => text,
        }
    }

    /// The bit area of an image byte offset and the byte's number in it.
    fn image(self, byte: u16) -> (Area, u16) {
        let layout: Layout = self.program.layout;
        if byte >= layout.flag_base() {
            (Area::Flag, byte - layout.flag_base())
        } else if byte >= layout.output_base() {
            (Area::Output, byte - layout.output_base())
        } else {
            (Area::Input, byte)
        }
    }

    /// `IW 2`, `MB 10`, `FD 4` for a sized image access.
    fn sized(self, width: Width, byte: u16) -> String {
        let (area, number) = self.image(byte);
        let sized = match (area, width) {
            (Area::Input, Width::Byte) => Area::InputByte,
            (Area::Input, _) => Area::InputWord,
            (Area::Output, Width::Byte) => Area::OutputByte,
            (Area::Output, _) => Area::OutputWord,
            (_, Width::Byte) => Area::FlagByte,
            (_, Width::Word) => Area::FlagWord,
            (_, Width::Double) => Area::FlagDouble,
        };
        self.named(format!("{} {number}", self.word(sized)))
    }

    fn bit(self, bit: ImageBit) -> String {
        let (area, number) = self.image(bit.byte);
        self.named(format!("{} {number}.{}", self.word(area), bit.bit))
    }

    fn data_bit(self, word: u16, bit: u8) -> String {
        format!("{} {word}.{bit}", self.word(Area::DataBit))
    }

    fn bit_target(self, target: BitTarget) -> String {
        match target {
            BitTarget::Image(bit) => self.bit(bit),
            BitTarget::Data { word, bit } => self.data_bit(word, bit),
        }
    }

    /// `T 5`, `Z 1`, `PW 128`: an area and a number.
    fn numbered(self, area: Area, number: impl std::fmt::Display) -> String {
        self.named(format!("{} {number}", self.word(area)))
    }

    fn block(self, index: u16) -> String {
        self.named(self.program.blocks[usize::from(index)].id.to_string())
    }

    /// The statement's constant as written: `KF +20`, `KT 050.1`, `KY 1,2`.
    fn constant(self, statement: Option<&Statement>) -> Option<String> {
        let statement = statement?;
        let file = self.sources.get(statement.operand_span.file);
        Some(written_constant(file.slice(statement.operand_span)))
    }

    /// `M001 (op 4)`: a jump target by its label, and where it is in the dump.
    fn target(self, pc: u32) -> String {
        match self
            .statements
            .get(pc as usize)
            .and_then(|statement| statement.label.as_ref())
        {
            Some(label) => format!("{} (op {pc})", label.text.to_uppercase()),
            None => format!("op {pc}"),
        }
    }

    /// `EIN I 0.0, AUS Q 4.0 (-LAMP)`: an FB call's actual parameters.
    fn actuals(self, params: &[CallParam]) -> String {
        let actual = |param: &CallParam| {
            let written = self
                .sources
                .get(param.actual_span.file)
                .slice(param.actual_span);
            let text = crate::symbols::operand_text(&param.actual, self.set)
                .map_or_else(|| written.to_string(), |text| self.named(text));
            format!("{} = {text}", param.name.text)
        };
        params.iter().map(actual).collect::<Vec<_>>().join(", ")
    }
}

/// A constant's text as the user wrote it, made regular: the format word in capitals, one blank,
/// no `=` (`KT050.0` → `KT 050.0`, `kh = 00ff` → `KH 00ff`).
pub fn written_constant(text: &str) -> String {
    let text = text.trim();
    let split = text
        .char_indices()
        .find(|(_, c)| !c.is_ascii_alphabetic())
        .map_or(text.len(), |(at, _)| at)
        .min(2);
    let (format, value) = text.split_at(split);
    let value = value.trim_start();
    let value = value.strip_prefix('=').unwrap_or(value).trim_start();
    format!("{} {value}", format.to_ascii_uppercase())
}

/// What an operation does, as the annotation's verb.
pub fn verb(op: OpCode) -> &'static str {
    use OpCode::*;
    match op {
        And => "and",
        AndNot => "and not",
        Or => "or",
        OrNot => "or not",
        AndBracket => "open AND bracket",
        OrBracket => "open OR bracket",
        CloseBracket => "close bracket",
        Assign => "assign",
        Set => "set",
        Reset => "reset",
        Load => "load",
        Transfer => "transfer",
        LoadCoded => "load BCD-coded",
        TimerPulse => "start pulse timer",
        TimerExtendedPulse => "start extended pulse timer",
        TimerOnDelay => "start on-delay timer",
        TimerStoredOnDelay => "start stored on-delay timer",
        TimerOffDelay => "start off-delay timer",
        Enable => "enable",
        CountUp => "count up",
        CountDown => "count down",
        AddFixed => "fixed-point add",
        SubFixed => "fixed-point subtract",
        MulFixed => "fixed-point multiply",
        DivFixed => "fixed-point divide",
        CmpEq => "compare ACCU 2 = ACCU 1",
        CmpNe => "compare ACCU 2 <> ACCU 1",
        CmpGt => "compare ACCU 2 > ACCU 1",
        CmpGe => "compare ACCU 2 >= ACCU 1",
        CmpLt => "compare ACCU 2 < ACCU 1",
        CmpLe => "compare ACCU 2 <= ACCU 1",
        JumpUnconditional => "call",
        JumpConditional => "call if RLO 1",
        OpenDb => "open",
        BlockEnd => "block end",
        BlockEndConditional => "block end if RLO 1",
        BlockEndUnconditional => "block end unconditionally",
        Nop => "no operation",
        Display => "display construction for the PG, no operation",
        Stop => "stop at the end of the cycle",
        JumpZero => "jump if zero to",
        JumpNotZero => "jump if not zero to",
        JumpPositive => "jump if positive to",
        JumpMinus => "jump if negative to",
        JumpOverflow => "jump on overflow to",
        AndWord => "AND word",
        OrWord => "OR word",
        XorWord => "exclusive OR word",
        ShiftLeft => "shift ACCU 1 left by",
        ShiftRight => "shift ACCU 1 right by",
        OnesComplement => "one's complement of ACCU 1",
        TwosComplement => "two's complement of ACCU 1",
        Swap => "swap ACCU 1 and ACCU 2",
        Enter => "enter: ACCU 3 to ACCU 4, ACCU 2 to ACCU 3",
        Increment => "increment ACCU 1 by",
        Decrement => "decrement ACCU 1 by",
        Indirect => "do the next operation with the parameter in",
        SetUnconditional => "set unconditionally",
        ResetUnconditional => "reset unconditionally",
        TestBit => "test bit for 1",
        TestBitNot => "test bit for 0",
        DisableInterrupts => "disable interrupts",
        EnableInterrupts => "enable interrupts",
        GenerateDb => "generate",
        ResetBinary => "reset the formal operand bit",
        ResetDigital => "reset the formal operand timer or counter",
        LoadBitPattern => "load the bit pattern of",
        LoadDecimal => "load the constant of",
        AddConstant => "add to ACCU 1",
        TransferBytes => "transfer bytes between absolute addresses (not simulated), count",
        LoadIndirect => "load indirectly from an absolute address (not simulated), register",
        TransferIndirect => "transfer indirectly to an absolute address (not simulated), register",
        MoveBrToAccu => "move BR to ACCU 1 (not simulated)",
        MoveAccuToBr => "move ACCU 1 to BR (not simulated)",
        MoveSaToAccu => "move the STEP address counter to ACCU 1 (not simulated)",
        MoveAccuToSa => "move ACCU 1 to the STEP address counter (not simulated)",
        AddToBr => "add to BR (not simulated)",
        LoadRelativeBr => "load relative to BR (not simulated), offset",
        TransferRelativeBr => "transfer relative to BR (not simulated), offset",
        AddFloat => "floating-point add",
        SubFloat => "floating-point subtract",
        MulFloat => "floating-point multiply",
        DivFloat => "floating-point divide",
        CmpEqFloat => "compare ACCU 2 = ACCU 1 (floating point)",
        CmpNeFloat => "compare ACCU 2 <> ACCU 1 (floating point)",
        CmpGtFloat => "compare ACCU 2 > ACCU 1 (floating point)",
        CmpGeFloat => "compare ACCU 2 >= ACCU 1 (floating point)",
        CmpLtFloat => "compare ACCU 2 < ACCU 1 (floating point)",
        CmpLeFloat => "compare ACCU 2 <= ACCU 1 (floating point)",
        FixedToFloat => "convert ACCU 1 from 32-bit fixed point to floating point",
        FloatToFixed => "convert ACCU 1 from floating point to 32-bit fixed point",
        BcdToFixed => "convert ACCU 1-L from BCD to fixed point",
        FixedToBcd => "convert ACCU 1-L from fixed point to BCD",
        BcdToFixedDouble => "convert ACCU 1 from 32-bit BCD to fixed point",
        FixedToBcdDouble => "convert ACCU 1 from 32-bit fixed point to BCD",
    }
}

fn logic_verb(logic: Logic) -> &'static str {
    verb(match logic {
        Logic::And => OpCode::And,
        Logic::AndNot => OpCode::AndNot,
        Logic::Or => OpCode::Or,
        Logic::OrNot => OpCode::OrNot,
    })
}

fn write_verb(write: Write) -> &'static str {
    verb(match write {
        Write::Assign => OpCode::Assign,
        Write::Set => OpCode::Set,
        Write::Reset => OpCode::Reset,
    })
}

fn timer_verb(kind: TimerKind) -> &'static str {
    verb(match kind {
        TimerKind::Pulse => OpCode::TimerPulse,
        TimerKind::ExtendedPulse => OpCode::TimerExtendedPulse,
        TimerKind::OnDelay => OpCode::TimerOnDelay,
        TimerKind::StoredOnDelay => OpCode::TimerStoredOnDelay,
        TimerKind::OffDelay => OpCode::TimerOffDelay,
    })
}

fn arithmetic_verb(kind: Arith) -> &'static str {
    verb(match kind {
        Arith::Add => OpCode::AddFixed,
        Arith::Sub => OpCode::SubFixed,
        Arith::Mul => OpCode::MulFixed,
        Arith::Div => OpCode::DivFixed,
    })
}

fn comparison_verb(comparison: Comparison) -> &'static str {
    verb(match comparison {
        Comparison::Eq => OpCode::CmpEq,
        Comparison::Ne => OpCode::CmpNe,
        Comparison::Gt => OpCode::CmpGt,
        Comparison::Ge => OpCode::CmpGe,
        Comparison::Lt => OpCode::CmpLt,
        Comparison::Le => OpCode::CmpLe,
    })
}

fn word_logic_verb(logic: WordLogic) -> &'static str {
    verb(match logic {
        WordLogic::And => OpCode::AndWord,
        WordLogic::Or => OpCode::OrWord,
        WordLogic::Xor => OpCode::XorWord,
    })
}

fn jump_verb(condition: JumpCondition) -> &'static str {
    match condition {
        JumpCondition::Always => "jump to",
        JumpCondition::Rlo => "jump if RLO 1 to",
        JumpCondition::Zero => verb(OpCode::JumpZero),
        JumpCondition::NotZero => verb(OpCode::JumpNotZero),
        JumpCondition::Positive => verb(OpCode::JumpPositive),
        JumpCondition::Minus => verb(OpCode::JumpMinus),
        JumpCondition::Overflow => verb(OpCode::JumpOverflow),
    }
}

fn data_area(part: DataPart) -> Area {
    match part {
        DataPart::Left => Area::DataLeft,
        DataPart::Right => Area::DataRight,
        DataPart::Word => Area::DataWord,
        DataPart::Double => Area::DataDouble,
    }
}

fn peripheral_area(width: Width, extended: bool) -> Area {
    match (extended, width) {
        (false, Width::Byte) => Area::PeripheralByte,
        (false, _) => Area::PeripheralWord,
        (true, Width::Byte) => Area::ExtendedByte,
        (true, _) => Area::ExtendedWord,
    }
}

/// The text of op `pc` of a block.
pub fn op_text(op: Op, pc: usize, context: Context<'_>) -> String {
    let statement = context.statements.get(pc);
    match op {
        Op::And(bit) => format!("{} {}", verb(OpCode::And), context.bit(bit)),
        Op::AndNot(bit) => format!("{} {}", verb(OpCode::AndNot), context.bit(bit)),
        Op::Or(bit) => format!("{} {}", verb(OpCode::Or), context.bit(bit)),
        Op::OrNot(bit) => format!("{} {}", verb(OpCode::OrNot), context.bit(bit)),
        Op::Assign(bit) => format!("{} {}", verb(OpCode::Assign), context.bit(bit)),
        Op::Set(bit) => format!("{} {}", verb(OpCode::Set), context.bit(bit)),
        Op::Reset(bit) => format!("{} {}", verb(OpCode::Reset), context.bit(bit)),
        Op::LogicOther(logic, source) => {
            let operand = match source {
                BitSource::Data { word, bit } => context.data_bit(word, bit),
                BitSource::Timer(n) => context.numbered(Area::Timer, n),
                BitSource::Counter(n) => context.numbered(Area::Counter, n),
            };
            format!("{} {operand}", logic_verb(logic))
        }
        Op::WriteData { write, word, bit } => {
            format!("{} {}", write_verb(write), context.data_bit(word, bit))
        }
        Op::OrAlone => "or: the AND strings before and after".to_string(),
        Op::AndBracket => verb(OpCode::AndBracket).to_string(),
        Op::OrBracket => verb(OpCode::OrBracket).to_string(),
        Op::CloseBracket => verb(OpCode::CloseBracket).to_string(),
        Op::LoadImageByte(byte) => format!("load {}", context.sized(Width::Byte, byte)),
        Op::LoadImageWord(byte) => format!("load {}", context.sized(Width::Word, byte)),
        Op::LoadImageDouble(byte) => format!("load {}", context.sized(Width::Double, byte)),
        Op::TransferImageByte(byte) => format!("transfer {}", context.sized(Width::Byte, byte)),
        Op::TransferImageWord(byte) => format!("transfer {}", context.sized(Width::Word, byte)),
        Op::TransferImageDouble(byte) => {
            format!("transfer {}", context.sized(Width::Double, byte))
        }
        Op::LoadData(part, word) => format!("load {}", context.numbered(data_area(part), word)),
        Op::TransferData(part, word) => {
            format!("transfer {}", context.numbered(data_area(part), word))
        }
        Op::LoadPeripheral {
            width,
            byte,
            extended,
        } => format!(
            "load {}",
            context.numbered(peripheral_area(width, extended), byte)
        ),
        Op::TransferPeripheral {
            width,
            byte,
            extended,
        } => format!(
            "transfer {}",
            context.numbered(peripheral_area(width, extended), byte)
        ),
        Op::LoadConstant(value) => match context.constant(statement) {
            Some(written) => format!("load constant {written}"),
            None => format!("load constant {value}"),
        },
        Op::LoadTimer(n) => format!("load {}", context.numbered(Area::Timer, n)),
        Op::LoadTimerCoded(n) => format!(
            "{} {}",
            verb(OpCode::LoadCoded),
            context.numbered(Area::Timer, n)
        ),
        Op::LoadCounter(n) => format!("load {}", context.numbered(Area::Counter, n)),
        Op::LoadCounterCoded(n) => format!(
            "{} {}",
            verb(OpCode::LoadCoded),
            context.numbered(Area::Counter, n)
        ),
        Op::StartTimer(kind, n) => {
            format!("{} {}", timer_verb(kind), context.numbered(Area::Timer, n))
        }
        Op::EnableTimer(n) => format!("enable {}", context.numbered(Area::Timer, n)),
        Op::ResetTimer(n) => format!("reset {}", context.numbered(Area::Timer, n)),
        Op::CountUp(n) => format!("count up {}", context.numbered(Area::Counter, n)),
        Op::CountDown(n) => format!("count down {}", context.numbered(Area::Counter, n)),
        Op::SetCounter(n) => format!("set {}", context.numbered(Area::Counter, n)),
        Op::ResetCounter(n) => format!("reset {}", context.numbered(Area::Counter, n)),
        Op::EnableCounter(n) => format!("enable {}", context.numbered(Area::Counter, n)),
        Op::Arithmetic(kind) => arithmetic_verb(kind).to_string(),
        Op::ArithmeticStack(kind) => {
            format!("{}, ACCU 3 and 4 move up", arithmetic_verb(kind))
        }
        Op::Compare(comparison) => format!("{} (fixed-point)", comparison_verb(comparison)),
        Op::FloatArithmetic { kind, stack } => {
            let verb = verb(match kind {
                Arith::Add => OpCode::AddFloat,
                Arith::Sub => OpCode::SubFloat,
                Arith::Mul => OpCode::MulFloat,
                Arith::Div => OpCode::DivFloat,
            });
            if stack {
                format!("{verb}, ACCU 3 and 4 move up")
            } else {
                verb.to_string()
            }
        }
        Op::FloatCompare(comparison) => {
            format!("{} (floating point)", comparison_verb(comparison))
        }
        Op::Convert(conversion) => verb(conversion.op_code()).to_string(),
        Op::Call {
            block, conditional, ..
        } => {
            let verb = if conditional { "call if RLO 1" } else { "call" };
            let callee = context.block(block);
            match statement {
                Some(statement) if !statement.call_params.is_empty() => format!(
                    "{verb} {callee} with {}",
                    context.actuals(&statement.call_params)
                ),
                _ => format!("{verb} {callee}"),
            }
        }
        Op::CallMissing {
            kind,
            number,
            conditional,
        } => {
            let verb = if conditional { "call if RLO 1" } else { "call" };
            format!("{verb} {} {number}, which is not loaded: STOP", kind.name())
        }
        Op::Builtin {
            block, conditional, ..
        } => {
            let verb = if conditional { "call if RLO 1" } else { "call" };
            match block {
                Builtin::Integral(fb) => format!("{verb} the CPU's integral {}", fb.name()),
                Builtin::SystemOb(ob) => {
                    format!("{verb} system OB {ob}, which awl does not simulate: STOP")
                }
            }
        }
        Op::OpenDb(number) => format!("open {}", context.named(format!("DB {number}"))),
        Op::GenerateDb(number) => format!("generate {}", context.named(format!("DB {number}"))),
        Op::BlockEnd => verb(OpCode::BlockEnd).to_string(),
        Op::BlockEndConditional => verb(OpCode::BlockEndConditional).to_string(),
        Op::BlockEndUnconditional => verb(OpCode::BlockEndUnconditional).to_string(),
        Op::Nop => match statement {
            Some(statement) if statement.op == OpCode::Display => verb(OpCode::Display),
            _ => verb(OpCode::Nop),
        }
        .to_string(),
        Op::Stop => verb(OpCode::Stop).to_string(),
        Op::Jump(condition, target) => {
            format!("{} {}", jump_verb(condition), context.target(target))
        }
        Op::WordLogic(logic) => word_logic_verb(logic).to_string(),
        Op::ShiftLeft(n) => format!("{} {n} bits", verb(OpCode::ShiftLeft)),
        Op::ShiftRight(n) => format!("{} {n} bits", verb(OpCode::ShiftRight)),
        Op::OnesComplement => verb(OpCode::OnesComplement).to_string(),
        Op::TwosComplement => verb(OpCode::TwosComplement).to_string(),
        Op::Swap => verb(OpCode::Swap).to_string(),
        Op::Enter => verb(OpCode::Enter).to_string(),
        Op::Increment(n) => format!("{} {n}", verb(OpCode::Increment)),
        Op::Decrement(n) => format!("{} {n}", verb(OpCode::Decrement)),
        Op::SetUnconditional(target) => format!(
            "{} {}",
            verb(OpCode::SetUnconditional),
            context.bit_target(target)
        ),
        Op::ResetUnconditional(target) => format!(
            "{} {}",
            verb(OpCode::ResetUnconditional),
            context.bit_target(target)
        ),
        Op::TestBit { negate, target } => {
            let op = if negate {
                OpCode::TestBitNot
            } else {
                OpCode::TestBit
            };
            format!("{} {}", verb(op), context.bit_target(target))
        }
        Op::AddConstant { value, double } => {
            let shown = if double {
                format!("DH {value:08X}")
            } else {
                format!("{}", value as u16 as i16)
            };
            format!("{} {shown}", verb(OpCode::AddConstant))
        }
        Op::S7(code) => format!("{code:?}"),
        Op::S7Scan(..) | Op::S7Write(..) => format!("{op:?}"),
        Op::NotSimulated { op, operand } => {
            let takes_none = matches!(
                op,
                OpCode::MoveBrToAccu
                    | OpCode::MoveAccuToBr
                    | OpCode::MoveSaToAccu
                    | OpCode::MoveAccuToSa
            );
            if takes_none {
                format!("{}: STOP when run", verb(op))
            } else {
                format!("{} {operand}: STOP when run", verb(op))
            }
        }
        Op::Interrupts { enabled: true } => verb(OpCode::EnableInterrupts).to_string(),
        Op::Interrupts { enabled: false } => verb(OpCode::DisableInterrupts).to_string(),
        Op::Indirect { source, .. } => {
            let operand = match source {
                IndirectSource::FlagWord(byte) => context.sized(Width::Word, byte),
                IndirectSource::DataWord(word) => context.numbered(Area::DataWord, word),
                // STEP 7's `UC FC [MW 50]`: its own dump (`dump::step7`) shows the statement.
                IndirectSource::S7Block(_) => return "call the block numbered in the word".into(),
            };
            format!("{} {operand}", verb(OpCode::Indirect))
        }
        Op::Formal { op, param } => {
            let name = context
                .params
                .get(usize::from(param))
                .map_or("?", |decl| decl.name.text.as_str());
            let verb = match op {
                OpCode::Indirect => "process (open the DB or call the block in)",
                other => verb(other),
            };
            format!("{verb} ={name} (parameter {})", param + 1)
        }
        // Only in the VM's code (fused pairs, direct calls, native stretches, the end marker): never in a
        // compiled block, which is what the dump shows.
        Op::End | Op::CallAt { .. } | Op::Native(_) | fused_pairs!() => format!("{op:?}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_keep_their_written_value_in_a_regular_form() {
        assert_eq!(written_constant("KF +20"), "KF +20");
        assert_eq!(written_constant("KT050.0"), "KT 050.0");
        assert_eq!(written_constant("kh = 00ff"), "KH 00ff");
        assert_eq!(written_constant("KY 1,2"), "KY 1,2");
        assert_eq!(written_constant("KS 'AB'"), "KS 'AB'");
    }
}
