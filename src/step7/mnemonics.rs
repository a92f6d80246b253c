//! The STEP 7 mnemonic table: the English (SIMATIC international) and German (SIMATIC) words of
//! every operation, operand area and status condition, mapped to [`S7Op`], [`S7Area`] and
//! [`Condition`]. Words are compared without case. The sets are those of the "Statement List
//! (STL) for S7-300 and S7-400 Programming" reference manual (appendix A, "All STL
//! Instructions").

use std::sync::OnceLock;

use crate::mnemonics::{MnemonicSet, Table};

use super::ast::{AccessWidth, Cmp, Combination, Condition, Function, S7Area, S7Op};

/// One operation: its meaning and its word in each set.
#[derive(Debug, Clone, Copy)]
pub struct OpWords {
    pub op: S7Op,
    pub en: &'static str,
    pub de: &'static str,
}

const fn op(op: S7Op, en: &'static str, de: &'static str) -> OpWords {
    OpWords { op, en, de }
}

use S7Op::*;

/// Every operation word. Statement-level words with an operand of their own (`L STW`) are the
/// parser's; `CALL`, `UC`, `CC` take blocks.
pub const OPERATIONS: &[OpWords] = &[
    op(Logic(Combination::And), "A", "U"),
    op(Logic(Combination::AndNot), "AN", "UN"),
    op(Logic(Combination::Or), "O", "O"),
    op(Logic(Combination::OrNot), "ON", "ON"),
    op(Logic(Combination::Xor), "X", "X"),
    op(Logic(Combination::XorNot), "XN", "XN"),
    op(Bracket(Combination::And), "A(", "U("),
    op(Bracket(Combination::AndNot), "AN(", "UN("),
    op(Bracket(Combination::Or), "O(", "O("),
    op(Bracket(Combination::OrNot), "ON(", "ON("),
    op(Bracket(Combination::Xor), "X(", "X("),
    op(Bracket(Combination::XorNot), "XN(", "XN("),
    op(CloseBracket, ")", ")"),
    op(Assign, "=", "="),
    op(Set, "S", "S"),
    op(Reset, "R", "R"),
    op(SetRlo, "SET", "SET"),
    op(ClearRlo, "CLR", "CLR"),
    op(Not, "NOT", "NOT"),
    op(Save, "SAVE", "SAVE"),
    op(EdgePositive, "FP", "FP"),
    op(EdgeNegative, "FN", "FN"),
    op(Load, "L", "L"),
    op(LoadCoded, "LC", "LC"),
    op(Transfer, "T", "T"),
    op(LoadAr1, "LAR1", "LAR1"),
    op(LoadAr2, "LAR2", "LAR2"),
    op(TransferAr1, "TAR1", "TAR1"),
    op(TransferAr2, "TAR2", "TAR2"),
    op(SwapAr, "CAR", "TAR"),
    op(AddAr1, "+AR1", "+AR1"),
    op(AddAr2, "+AR2", "+AR2"),
    op(TimerPulse, "SP", "SI"),
    op(TimerExtendedPulse, "SE", "SV"),
    op(TimerOnDelay, "SD", "SE"),
    op(TimerRetentiveOnDelay, "SS", "SS"),
    op(TimerOffDelay, "SF", "SA"),
    op(Enable, "FR", "FR"),
    op(CountUp, "CU", "ZV"),
    op(CountDown, "CD", "ZR"),
    op(AddInt, "+I", "+I"),
    op(SubInt, "-I", "-I"),
    op(MulInt, "*I", "*I"),
    op(DivInt, "/I", "/I"),
    op(AddDint, "+D", "+D"),
    op(SubDint, "-D", "-D"),
    op(MulDint, "*D", "*D"),
    op(DivDint, "/D", "/D"),
    op(ModDint, "MOD", "MOD"),
    op(AddReal, "+R", "+R"),
    op(SubReal, "-R", "-R"),
    op(MulReal, "*R", "*R"),
    op(DivReal, "/R", "/R"),
    op(AddConstant, "+", "+"),
    op(Abs, "ABS", "ABS"),
    op(Real(Function::Sqr), "SQR", "SQR"),
    op(Real(Function::Sqrt), "SQRT", "SQRT"),
    op(Real(Function::Exp), "EXP", "EXP"),
    op(Real(Function::Ln), "LN", "LN"),
    op(Real(Function::Sin), "SIN", "SIN"),
    op(Real(Function::Cos), "COS", "COS"),
    op(Real(Function::Tan), "TAN", "TAN"),
    op(Real(Function::Asin), "ASIN", "ASIN"),
    op(Real(Function::Acos), "ACOS", "ACOS"),
    op(Real(Function::Atan), "ATAN", "ATAN"),
    op(NegInt, "NEGI", "NEGI"),
    op(NegDint, "NEGD", "NEGD"),
    op(NegReal, "NEGR", "NEGR"),
    op(InvInt, "INVI", "INVI"),
    op(InvDint, "INVD", "INVD"),
    op(CmpInt(Cmp::Eq), "==I", "==I"),
    op(CmpInt(Cmp::Ne), "<>I", "<>I"),
    op(CmpInt(Cmp::Gt), ">I", ">I"),
    op(CmpInt(Cmp::Lt), "<I", "<I"),
    op(CmpInt(Cmp::Ge), ">=I", ">=I"),
    op(CmpInt(Cmp::Le), "<=I", "<=I"),
    op(CmpDint(Cmp::Eq), "==D", "==D"),
    op(CmpDint(Cmp::Ne), "<>D", "<>D"),
    op(CmpDint(Cmp::Gt), ">D", ">D"),
    op(CmpDint(Cmp::Lt), "<D", "<D"),
    op(CmpDint(Cmp::Ge), ">=D", ">=D"),
    op(CmpDint(Cmp::Le), "<=D", "<=D"),
    op(CmpReal(Cmp::Eq), "==R", "==R"),
    op(CmpReal(Cmp::Ne), "<>R", "<>R"),
    op(CmpReal(Cmp::Gt), ">R", ">R"),
    op(CmpReal(Cmp::Lt), "<R", "<R"),
    op(CmpReal(Cmp::Ge), ">=R", ">=R"),
    op(CmpReal(Cmp::Le), "<=R", "<=R"),
    op(IntToDint, "ITD", "ITD"),
    op(IntToBcd, "ITB", "ITB"),
    op(BcdToInt, "BTI", "BTI"),
    op(BcdToDint, "BTD", "BTD"),
    op(DintToBcd, "DTB", "DTB"),
    op(DintToReal, "DTR", "DTR"),
    op(Round, "RND", "RND"),
    op(RoundUp, "RND+", "RND+"),
    op(RoundDown, "RND-", "RND-"),
    op(Truncate, "TRUNC", "TRUNC"),
    op(SwapBytesWord, "CAW", "TAW"),
    op(SwapBytesDouble, "CAD", "TAD"),
    op(ShiftSignedInt, "SSI", "SSI"),
    op(ShiftSignedDint, "SSD", "SSD"),
    op(ShiftLeftWord, "SLW", "SLW"),
    op(ShiftRightWord, "SRW", "SRW"),
    op(ShiftLeftDouble, "SLD", "SLD"),
    op(ShiftRightDouble, "SRD", "SRD"),
    op(RotateLeftDouble, "RLD", "RLD"),
    op(RotateRightDouble, "RRD", "RRD"),
    op(RotateLeftViaCc1, "RLDA", "RLDA"),
    op(RotateRightViaCc1, "RRDA", "RRDA"),
    op(AndWord, "AW", "UW"),
    op(OrWord, "OW", "OW"),
    op(XorWord, "XOW", "XOW"),
    op(AndDouble, "AD", "UD"),
    op(OrDouble, "OD", "OD"),
    op(XorDouble, "XOD", "XOD"),
    op(SwapAccus, "TAK", "TAK"),
    op(Push, "PUSH", "PUSH"),
    op(Pop, "POP", "POP"),
    op(Enter, "ENT", "ENT"),
    op(Leave, "LEAVE", "LEAVE"),
    op(Increment, "INC", "INC"),
    op(Decrement, "DEC", "DEC"),
    op(JumpAlways, "JU", "SPA"),
    op(JumpIfRlo, "JC", "SPB"),
    op(JumpIfNotRlo, "JCN", "SPBN"),
    op(JumpIfRloSave, "JCB", "SPBB"),
    op(JumpIfNotRloSave, "JNB", "SPBNB"),
    op(JumpIfBr, "JBI", "SPBI"),
    op(JumpIfNotBr, "JNBI", "SPBIN"),
    op(JumpIfOverflow, "JO", "SPO"),
    op(JumpIfStoredOverflow, "JOS", "SPS"),
    op(JumpIfZero, "JZ", "SPZ"),
    op(JumpIfNotZero, "JN", "SPN"),
    op(JumpIfPositive, "JP", "SPP"),
    op(JumpIfMinus, "JM", "SPM"),
    op(JumpIfPositiveOrZero, "JPZ", "SPPZ"),
    op(JumpIfMinusOrZero, "JMZ", "SPMZ"),
    op(JumpIfUnordered, "JUO", "SPU"),
    op(Loop, "LOOP", "LOOP"),
    op(JumpList, "JL", "SPL"),
    op(OpenDb, "OPN", "AUF"),
    op(ExchangeDbRegisters, "CDB", "TDB"),
    op(Call, "CALL", "CALL"),
    op(CallUnconditional, "UC", "UC"),
    op(CallConditional, "CC", "CC"),
    op(BlockEnd, "BE", "BE"),
    op(BlockEndUnconditional, "BEU", "BEA"),
    op(BlockEndConditional, "BEC", "BEB"),
    op(McrActivate, "MCRA", "MCRA"),
    op(McrDeactivate, "MCRD", "MCRD"),
    op(McrOpen, "MCR(", "MCR("),
    op(McrClose, ")MCR", ")MCR"),
    op(Nop, "NOP", "NOP"),
    op(Display, "BLD", "BLD"),
];

/// awlsim's test operations (only with the test extensions); `__ASSERT==` and its siblings are
/// lexed apart.
pub const EXTENSION_OPERATIONS: &[OpWords] = &[
    op(ResetStatusWord, "__STWRST", "__STWRST"),
    op(Sleep, "__SLEEP", "__SLEEP"),
    op(Feature, "__FEATURE", "__FEATURE"),
];

/// One operand area word: the area, the access width and the word in each set.
#[derive(Debug, Clone, Copy)]
pub struct AreaWords {
    pub area: S7Area,
    pub width: AccessWidth,
    pub en: &'static str,
    pub de: &'static str,
}

const fn area_words(
    area: S7Area,
    width: AccessWidth,
    en: &'static str,
    de: &'static str,
) -> AreaWords {
    AreaWords {
        area,
        width,
        en,
        de,
    }
}

use AccessWidth::{Bit, Byte, Double, Word};
use S7Area::*;

pub const AREAS: &[AreaWords] = &[
    area_words(Input, Bit, "I", "E"),
    area_words(Input, Byte, "IB", "EB"),
    area_words(Input, Word, "IW", "EW"),
    area_words(Input, Double, "ID", "ED"),
    area_words(Output, Bit, "Q", "A"),
    area_words(Output, Byte, "QB", "AB"),
    area_words(Output, Word, "QW", "AW"),
    area_words(Output, Double, "QD", "AD"),
    area_words(Flag, Bit, "M", "M"),
    area_words(Flag, Byte, "MB", "MB"),
    area_words(Flag, Word, "MW", "MW"),
    area_words(Flag, Double, "MD", "MD"),
    area_words(Local, Bit, "L", "L"),
    area_words(Local, Byte, "LB", "LB"),
    area_words(Local, Word, "LW", "LW"),
    area_words(Local, Double, "LD", "LD"),
    area_words(PreviousLocal, Bit, "V", "V"),
    area_words(PreviousLocal, Byte, "VB", "VB"),
    area_words(PreviousLocal, Word, "VW", "VW"),
    area_words(PreviousLocal, Double, "VD", "VD"),
    area_words(Data, Bit, "DBX", "DBX"),
    area_words(Data, Byte, "DBB", "DBB"),
    area_words(Data, Word, "DBW", "DBW"),
    area_words(Data, Double, "DBD", "DBD"),
    area_words(Instance, Bit, "DIX", "DIX"),
    area_words(Instance, Byte, "DIB", "DIB"),
    area_words(Instance, Word, "DIW", "DIW"),
    area_words(Instance, Double, "DID", "DID"),
    area_words(PeripheralInput, Byte, "PIB", "PEB"),
    area_words(PeripheralInput, Word, "PIW", "PEW"),
    area_words(PeripheralInput, Double, "PID", "PED"),
    area_words(PeripheralOutput, Byte, "PQB", "PAB"),
    area_words(PeripheralOutput, Word, "PQW", "PAW"),
    area_words(PeripheralOutput, Double, "PQD", "PAD"),
    area_words(Timer, Word, "T", "T"),
    area_words(Counter, Word, "C", "Z"),
];

/// The status conditions bit logic reads (`A ==0`, `A OV`, `A BR`).
pub const CONDITIONS: &[(Condition, &str, &str)] = &[
    (Condition::Zero, "==0", "==0"),
    (Condition::NotZero, "<>0", "<>0"),
    (Condition::Positive, ">0", ">0"),
    (Condition::Negative, "<0", "<0"),
    (Condition::PositiveOrZero, ">=0", ">=0"),
    (Condition::NegativeOrZero, "<=0", "<=0"),
    (Condition::Overflow, "OV", "OV"),
    (Condition::StoredOverflow, "OS", "OS"),
    (Condition::Unordered, "UO", "UO"),
    (Condition::BinaryResult, "BR", "BIE"),
];

/// The status word bits by number (0 … 8), as `__STW` names them in each set.
pub const STATUS_BITS: &[(&str, &str)] = &[
    ("/FC", "/ER"),
    ("RLO", "VKE"),
    ("STA", "STA"),
    ("OR", "OR"),
    ("OS", "OS"),
    ("OV", "OV"),
    ("CC0", "A0"),
    ("CC1", "A1"),
    ("BR", "BIE"),
];

fn word(set: MnemonicSet, en: &'static str, de: &'static str) -> &'static str {
    match set {
        MnemonicSet::English => en,
        MnemonicSet::German => de,
    }
}

fn operation_table() -> &'static Table<S7Op> {
    static TABLE: OnceLock<Table<S7Op>> = OnceLock::new();
    TABLE.get_or_init(|| Table::new(OPERATIONS, |words| (words.en, words.de), |words| words.op))
}

fn area_table() -> &'static Table<(S7Area, AccessWidth)> {
    static TABLE: OnceLock<Table<(S7Area, AccessWidth)>> = OnceLock::new();
    TABLE.get_or_init(|| {
        Table::new(
            AREAS,
            |words| (words.en, words.de),
            |words| (words.area, words.width),
        )
    })
}

/// The operation a word (already upper case) names in `set`.
pub fn operation(set: MnemonicSet, upper: &str) -> Option<S7Op> {
    operation_table().get(set, upper)
}

/// The area and width an area word (upper case) names in `set`.
pub fn area(set: MnemonicSet, upper: &str) -> Option<(S7Area, AccessWidth)> {
    area_table().get(set, upper)
}

pub fn condition(set: MnemonicSet, upper: &str) -> Option<Condition> {
    CONDITIONS
        .iter()
        .find(|(_, en, de)| word(set, en, de) == upper)
        .map(|(condition, ..)| *condition)
}

/// `__STW` bit names: their number.
pub fn status_bit(set: MnemonicSet, upper: &str) -> Option<u8> {
    STATUS_BITS
        .iter()
        .position(|(en, de)| word(set, en, de) == upper)
        .map(|bit| bit as u8)
}

/// The word of `op` in `set`.
pub fn op_word(set: MnemonicSet, op: S7Op) -> &'static str {
    OPERATIONS
        .iter()
        .chain(EXTENSION_OPERATIONS)
        .find(|words| words.op == op)
        .map_or("", |words| word(set, words.en, words.de))
}

/// The word of an area in `set`.
pub fn area_word(set: MnemonicSet, area: S7Area, width: AccessWidth) -> &'static str {
    AREAS
        .iter()
        .find(|words| words.area == area && words.width == width)
        .map_or("", |words| word(set, words.en, words.de))
}

pub fn operation_words(set: MnemonicSet) -> impl Iterator<Item = &'static str> {
    OPERATIONS
        .iter()
        .map(move |words| word(set, words.en, words.de))
}

/// The set an operation word belongs to when only one set has it (`U`, `SPA` German; `A`,
/// `JU` English); `None` for words of both sets (`L`, `SE`) or of neither.
pub fn operation_evidence(upper: &str) -> Option<MnemonicSet> {
    evidence(
        operation(MnemonicSet::English, upper).is_some(),
        operation(MnemonicSet::German, upper).is_some(),
    )
}

/// The same for an operand word: an area (`E`, `PEW`, `Z` German; `I`, `PIW`, `C` English) or
/// a condition (`BIE`, `BR`).
pub fn operand_evidence(upper: &str) -> Option<MnemonicSet> {
    let known = |set| area(set, upper).is_some() || condition(set, upper).is_some();
    evidence(known(MnemonicSet::English), known(MnemonicSet::German))
}

fn evidence(english: bool, german: bool) -> Option<MnemonicSet> {
    match (english, german) {
        (true, false) => Some(MnemonicSet::English),
        (false, true) => Some(MnemonicSet::German),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use MnemonicSet::{English, German};

    #[test]
    fn both_sets_name_the_same_operations() {
        assert_eq!(operation(English, "A"), Some(Logic(Combination::And)));
        assert_eq!(operation(German, "U"), Some(Logic(Combination::And)));
        assert_eq!(operation(English, "JU"), operation(German, "SPA"));
        assert_eq!(operation(English, "BEC"), operation(German, "BEB"));
        assert_eq!(operation(German, "A"), None);
        assert_eq!(operation(English, "U"), None);
    }

    #[test]
    fn timer_words_differ_in_meaning_between_the_sets() {
        assert_eq!(operation(English, "SE"), Some(TimerExtendedPulse));
        assert_eq!(operation(German, "SE"), Some(TimerOnDelay));
        assert_eq!(operation(English, "SD"), operation(German, "SE"));
        assert_eq!(operation(English, "SF"), operation(German, "SA"));
        assert_eq!(operation(English, "SP"), operation(German, "SI"));
    }

    #[test]
    fn areas_of_both_sets() {
        assert_eq!(area(English, "PIW"), Some((PeripheralInput, Word)));
        assert_eq!(area(German, "PEW"), Some((PeripheralInput, Word)));
        assert_eq!(area(German, "A"), Some((Output, Bit)));
        assert_eq!(area(German, "Z"), Some((Counter, Word)));
        assert_eq!(area(English, "DBX"), area(German, "DBX"));
    }

    #[test]
    fn evidence_is_a_word_of_one_set_only() {
        assert_eq!(operation_evidence("U"), Some(German));
        assert_eq!(operation_evidence("A"), Some(English));
        assert_eq!(operation_evidence("SE"), None);
        assert_eq!(operation_evidence("L"), None);
        assert_eq!(operand_evidence("E"), Some(German));
        assert_eq!(operand_evidence("Q"), Some(English));
        assert_eq!(operand_evidence("BIE"), Some(German));
        assert_eq!(operand_evidence("MW"), None);
    }

    #[test]
    fn every_word_is_unique_in_its_set() {
        for set in [English, German] {
            let mut words: Vec<&str> = operation_words(set).collect();
            words.sort_unstable();
            let count = words.len();
            words.dedup();
            assert_eq!(words.len(), count, "{set:?}");
        }
    }

    #[test]
    fn status_bits_by_name() {
        assert_eq!(status_bit(English, "RLO"), Some(1));
        assert_eq!(status_bit(German, "VKE"), Some(1));
        assert_eq!(status_bit(German, "BIE"), Some(8));
        assert_eq!(status_bit(English, "/FC"), Some(0));
    }
}
