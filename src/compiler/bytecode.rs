//! The bytecode: one small `Copy` op per statement, operands decoded, jump targets resolved.
//! Spans and execution times live in arrays parallel to the code, so ops stay at 8 bytes.

use crate::mnemonics::{BlockKind, OpCode};
/// The kinds of arithmetic, comparison and word logic live with their rules.
pub use crate::rules::arith::{Arith, Comparison, WordLogic};
/// The STEP 5 bit logic is a status rule: it lives with the status word.
pub use crate::rules::status::Logic;

/// A bit in the VM's flat image memory (PII, then PIQ, then flags).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageBit {
    pub byte: u16,
    pub bit: u8,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Write {
    Assign,
    Set,
    Reset,
}

/// Bits that are not in the image memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BitSource {
    Data { word: u16, bit: u8 },
    Timer(u16),
    Counter(u16),
}

/// A bit for the unconditional set/reset and test operations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BitTarget {
    Image(ImageBit),
    Data { word: u16, bit: u8 },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Width {
    Byte,
    Word,
    Double,
}

impl Width {
    pub fn bytes(self) -> usize {
        match self {
            Width::Byte => 1,
            Width::Word => 2,
            Width::Double => 4,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataPart {
    Left,
    Right,
    Word,
    Double,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum TimerKind {
    Pulse,
    ExtendedPulse,
    OnDelay,
    StoredOnDelay,
    OffDelay,
}

/// The conversions of ACCU 1 (CPU 928B programming guide, table 3-21).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Conversion {
    /// `FDG`
    FixedToFloat,
    /// `GFD`
    FloatToFixed,
    /// `DEF`
    BcdToFixed,
    /// `DUF`
    FixedToBcd,
    /// `DED`
    BcdToFixedDouble,
    /// `DUD`
    FixedToBcdDouble,
}

impl Conversion {
    pub fn op_code(self) -> OpCode {
        match self {
            Conversion::FixedToFloat => OpCode::FixedToFloat,
            Conversion::FloatToFixed => OpCode::FloatToFixed,
            Conversion::BcdToFixed => OpCode::BcdToFixed,
            Conversion::FixedToBcd => OpCode::FixedToBcd,
            Conversion::BcdToFixedDouble => OpCode::BcdToFixedDouble,
            Conversion::FixedToBcdDouble => OpCode::FixedToBcdDouble,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JumpCondition {
    Always,
    Rlo,
    Zero,
    NotZero,
    Positive,
    Minus,
    Overflow,
}

impl JumpCondition {
    /// Whether the jump is taken with `status`, which the jump then changes as it does.
    #[inline(always)]
    pub fn taken(self, status: &mut crate::rules::status::Status) -> bool {
        use crate::rules::jump::Condition;
        let taken = match self {
            JumpCondition::Always => true,
            JumpCondition::Rlo => status.rlo(),
            // The conditions on CC1, CC0 and OV, one rule for both dialects.
            JumpCondition::Zero => Condition::Zero.holds(*status, false),
            // `JN` jumps on CC1 ≠ CC0 only, unlike the condition `<>0`.
            JumpCondition::NotZero => status.cc1() != status.cc0(),
            JumpCondition::Positive => Condition::Positive.holds(*status, false),
            JumpCondition::Minus => Condition::Negative.holds(*status, false),
            JumpCondition::Overflow => Condition::Overflow.holds(*status, false),
        };
        if self == JumpCondition::Rlo {
            status.after_jump();
        }
        taken
    }
}

/// Where `DO` takes the parameter of the next operation from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IndirectSource {
    /// A flag word, as an image byte offset.
    FlagWord(u16),
    DataWord(u16),
    /// STEP 7 `UC FC [MW 50]`, `CC FB [MW 50]`: the block number is the word at this place of
    /// the S7 tables; the op's `template` holds [`CALL_FROM_FB`] and [`CALL_FROM_CONDITIONAL`]
    /// instead of a template.
    S7Block(u16),
}

/// [`IndirectSource::S7Block`]: an FB is called (an FC otherwise).
pub const CALL_FROM_FB: u16 = 1;
/// [`IndirectSource::S7Block`]: `CC`, called when the RLO is 1.
pub const CALL_FROM_CONDITIONAL: u16 = 2;

/// No actual-parameter list.
pub const NO_PARAMS: u16 = u16::MAX;

/// One op of the VM. How LLVM lays out the run loop's call and block-end paths depends on the
/// number of variants (one more cost `programs/bench/calls` a host instruction per block call):
/// run `benches/callgrind.py` after adding one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    And(ImageBit),
    AndNot(ImageBit),
    Or(ImageBit),
    OrNot(ImageBit),
    Assign(ImageBit),
    Set(ImageBit),
    Reset(ImageBit),
    LogicOther(Logic, BitSource),
    WriteData {
        write: Write,
        word: u16,
        bit: u8,
    },
    OrAlone,
    AndBracket,
    OrBracket,
    CloseBracket,
    /// Loads and transfers of the image memory, one variant per width so the loop dispatches once.
    LoadImageByte(u16),
    LoadImageWord(u16),
    LoadImageDouble(u16),
    TransferImageByte(u16),
    TransferImageWord(u16),
    TransferImageDouble(u16),
    LoadData(DataPart, u16),
    TransferData(DataPart, u16),
    LoadPeripheral {
        width: Width,
        byte: u16,
        extended: bool,
    },
    TransferPeripheral {
        width: Width,
        byte: u16,
        extended: bool,
    },
    LoadConstant(u32),
    LoadTimer(u16),
    LoadTimerCoded(u16),
    LoadCounter(u16),
    LoadCounterCoded(u16),
    StartTimer(TimerKind, u16),
    EnableTimer(u16),
    ResetTimer(u16),
    CountUp(u16),
    CountDown(u16),
    SetCounter(u16),
    ResetCounter(u16),
    EnableCounter(u16),
    /// Fixed-point arithmetic on CPUs with two accumulators.
    Arithmetic(Arith),
    /// Fixed-point arithmetic on CPUs with four accumulators: ACCU 3 and 4 move up after it.
    ArithmeticStack(Arith),
    Compare(Comparison),
    /// S5 floating-point arithmetic `+G -G XG :G` (`stack`: on four accumulators, ACCU 3 and 4
    /// move up after it).
    FloatArithmetic {
        kind: Arith,
        stack: bool,
    },
    FloatCompare(Comparison),
    Convert(Conversion),
    /// `JU`/`JC` to a block: its index in the program, and its actual-parameter list.
    Call {
        block: u16,
        conditional: bool,
        params: u16,
    },
    /// A `Call` without actual parameters, with where the callee's body starts in the arena, so
    /// the call finds it without a lookup. Only in the arena's fused code (see `arena`).
    CallAt {
        block: u16,
        conditional: bool,
        entry: u32,
    },
    /// `JU`/`JC` to a block the CPU has built in (an integral FB, a system OB), with its
    /// actual-parameter list.
    Builtin {
        block: super::builtin::Builtin,
        conditional: bool,
        params: u16,
    },
    /// A call of a block that is not loaded: STOP when taken.
    CallMissing {
        kind: BlockKind,
        number: u16,
        conditional: bool,
    },
    OpenDb(u8),
    BlockEnd,
    BlockEndConditional,
    BlockEndUnconditional,
    Nop,
    Stop,
    Jump(JumpCondition, u32),
    WordLogic(WordLogic),
    ShiftLeft(u8),
    ShiftRight(u8),
    OnesComplement,
    TwosComplement,
    Swap,
    /// `ENT`: ACCU 3 to ACCU 4, ACCU 2 to ACCU 3.
    Enter,
    Increment(u8),
    Decrement(u8),
    SetUnconditional(BitTarget),
    ResetUnconditional(BitTarget),
    TestBit {
        negate: bool,
        target: BitTarget,
    },
    /// `RA` (`enabled`) and `IA`: interrupt servicing enabled or disabled.
    Interrupts {
        enabled: bool,
    },
    GenerateDb(u8),
    /// The end of a block's code in the VM's arena: reached only by running past the last op
    /// of a block without `BE`. The compiler never emits it.
    End,
    // Pairs of ops the VM's arena runs as one (see `compiler::fuse`); the compiler never emits
    // them, and the second op of a pair keeps its own place.
    /// Two of `A AN O ON` on image bits; each `u8` packs the logic (bits 3–4) and the bit.
    LogicPair {
        first_op: u8,
        first: u16,
        second: u16,
        second_op: u8,
    },
    /// One of `A AN O ON` on an image bit, then `=`, `S` or `R` of an image bit; the first
    /// `u8` packs the logic and the bit as in `LogicPair`, the second the bit and what the
    /// write does to it for each RLO (see `fuse::apply_write`).
    LogicWrite {
        logic_op: u8,
        scanned: u16,
        written: u16,
        write_op: u8,
    },
    /// STEP 7's `LogicPair`: two of `A AN O ON X XN` on image bits, each `u8` packing the
    /// combination (bits 3–5) and the bit.
    S7ScanPair {
        first_op: u8,
        first: u16,
        second: u16,
        second_op: u8,
    },
    /// STEP 7's `LogicWrite`: a scan packed as in `S7ScanPair`, then `=`, `S` or `R` packed as
    /// in `LogicWrite`.
    S7ScanWrite {
        scan_op: u8,
        scanned: u16,
        written: u16,
        write_op: u8,
    },
    /// `L` of an image word, then `L` of a 16-bit constant.
    LoadWordConstant {
        byte: u16,
        value: u16,
    },
    /// `L` of two image words.
    LoadWords {
        first: u16,
        second: u16,
    },
    /// Fixed-point arithmetic (`stack`: on four accumulators), then `T` of an image word.
    ArithmeticTransferWord {
        kind: Arith,
        stack: bool,
        byte: u16,
    },
    /// `DO`: run the next op with its parameter taken from the source; `template` indexes the
    /// program's indirect templates.
    Indirect {
        source: IndirectSource,
        template: u16,
    },
    /// An operation on a formal operand, resolved against the running FB's actual parameters.
    Formal {
        op: OpCode,
        param: u8,
    },
    /// `ADD KB/KF n` (`double` false: the low word of ACCU 1) or `ADD DH n` (all 32 bits).
    AddConstant {
        value: u32,
        double: bool,
    },
    /// A STEP 7 operation STEP 5 does not have, run out of line.
    S7(crate::step7::bytecode::S7Code),
    /// STEP 7's `A AN O ON X XN` on an image bit (their status rules differ from STEP 5's).
    S7Scan(crate::rules::status::Combination, ImageBit),
    /// STEP 7's `=`, `S`, `R` on an image bit (STA takes the RLO).
    S7Write(Write, ImageBit),
    /// A system or register operation on absolute addresses: running it stops the CPU.
    NotSimulated {
        op: OpCode,
        operand: u16,
    },
    /// A straight-line stretch run as native code, in the VM's code only (see `vm::native`):
    /// the stretch's index there.
    Native(u32),
}

// Groups of ops as patterns (with `Op` in scope where they are used), for the matches that
// must name every op: each group is listed here once, and a match that names it stays exhaustive.

/// STEP 5's bit scans and writes on I, Q and F (`A AN O ON = S R`), binding the bit to `$bit`.
macro_rules! image_bit_ops {
    ($bit:pat) => {
        Op::And($bit)
            | Op::AndNot($bit)
            | Op::Or($bit)
            | Op::OrNot($bit)
            | Op::Assign($bit)
            | Op::Set($bit)
            | Op::Reset($bit)
    };
}
pub(crate) use image_bit_ops;

/// The loads, starts and resets of timers and counters.
macro_rules! timer_counter_ops {
    () => {
        Op::LoadTimer(_)
            | Op::LoadTimerCoded(_)
            | Op::LoadCounter(_)
            | Op::LoadCounterCoded(_)
            | Op::StartTimer(..)
            | Op::EnableTimer(_)
            | Op::ResetTimer(_)
            | Op::CountUp(_)
            | Op::CountDown(_)
            | Op::SetCounter(_)
            | Op::ResetCounter(_)
            | Op::EnableCounter(_)
    };
}
pub(crate) use timer_counter_ops;

/// The pairs of ops the VM's arena runs as one (see `compiler::fuse`).
#[rustfmt::skip] // one line per kind of pair: STEP 5 bit logic, STEP 7 bit logic, words
macro_rules! fused_pairs {
    () => {
        Op::LogicPair { .. } | Op::LogicWrite { .. }
            | Op::S7ScanPair { .. } | Op::S7ScanWrite { .. }
            | Op::LoadWordConstant { .. } | Op::LoadWords { .. } | Op::ArithmeticTransferWord { .. }
    };
}
pub(crate) use fused_pairs;

impl Op {
    pub fn load_image(width: Width, byte: u16) -> Op {
        match width {
            Width::Byte => Op::LoadImageByte(byte),
            Width::Word => Op::LoadImageWord(byte),
            Width::Double => Op::LoadImageDouble(byte),
        }
    }

    /// The image bit of STEP 5's bit scans and writes on I, Q and F (`A AN O ON`, `= S R`).
    pub fn image_bit(self) -> Option<ImageBit> {
        match self {
            image_bit_ops!(bit) => Some(bit),
            _ => None,
        }
    }

    /// A formal operand or a `DO`: the op it runs as is known only at run time.
    pub fn resolved_at_run_time(self) -> bool {
        matches!(self, Op::Formal { .. } | Op::Indirect { .. })
    }

    pub fn transfer_image(width: Width, byte: u16) -> Op {
        match width {
            Width::Byte => Op::TransferImageByte(byte),
            Width::Word => Op::TransferImageWord(byte),
            Width::Double => Op::TransferImageDouble(byte),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ops_stay_small() {
        assert_eq!(std::mem::size_of::<Op>(), 8);
    }
}
