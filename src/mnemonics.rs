//! The two mnemonic sets (SIMATIC English and German) and the table that maps their words to the
//! language-independent operation codes, operand areas, constant formats and parameter kinds.
//!
//! `grammar/mnemonics.md` documents this table; a test keeps both in step.

use std::sync::OnceLock;

use crate::profile::Feature;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MnemonicSet {
    English,
    German,
}

impl MnemonicSet {
    pub fn other(self) -> Self {
        match self {
            MnemonicSet::English => MnemonicSet::German,
            MnemonicSet::German => MnemonicSet::English,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            MnemonicSet::English => "English (SIMATIC)",
            MnemonicSet::German => "German",
        }
    }

    /// The name with its article: "an English (SIMATIC)", "a German".
    pub fn with_article(self) -> &'static str {
        match self {
            MnemonicSet::English => "an English (SIMATIC)",
            MnemonicSet::German => "a German",
        }
    }
}

/// Language-independent operation codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OpCode {
    And,
    AndNot,
    Or,
    OrNot,
    AndBracket,
    OrBracket,
    CloseBracket,
    Assign,
    Set,
    Reset,
    Load,
    Transfer,
    LoadCoded,
    TimerPulse,
    TimerExtendedPulse,
    TimerOnDelay,
    TimerStoredOnDelay,
    TimerOffDelay,
    Enable,
    CountUp,
    CountDown,
    AddFixed,
    SubFixed,
    MulFixed,
    DivFixed,
    CmpEq,
    CmpNe,
    CmpGt,
    CmpGe,
    CmpLt,
    CmpLe,
    JumpUnconditional,
    JumpConditional,
    OpenDb,
    BlockEnd,
    BlockEndConditional,
    BlockEndUnconditional,
    Nop,
    Display,
    Stop,
    JumpZero,
    JumpNotZero,
    JumpPositive,
    JumpMinus,
    JumpOverflow,
    AndWord,
    OrWord,
    XorWord,
    ShiftLeft,
    ShiftRight,
    OnesComplement,
    TwosComplement,
    Swap,
    Enter,
    Increment,
    Decrement,
    Indirect,
    SetUnconditional,
    ResetUnconditional,
    TestBit,
    TestBitNot,
    DisableInterrupts,
    EnableInterrupts,
    GenerateDb,
    ResetBinary,
    ResetDigital,
    LoadBitPattern,
    LoadDecimal,
    AddConstant,
    TransferBytes,
    LoadIndirect,
    TransferIndirect,
    MoveBrToAccu,
    MoveAccuToBr,
    MoveSaToAccu,
    MoveAccuToSa,
    AddToBr,
    LoadRelativeBr,
    TransferRelativeBr,
    AddFloat,
    SubFloat,
    MulFloat,
    DivFloat,
    CmpEqFloat,
    CmpNeFloat,
    CmpGtFloat,
    CmpGeFloat,
    CmpLtFloat,
    CmpLeFloat,
    FixedToFloat,
    FloatToFixed,
    BcdToFixed,
    FixedToBcd,
    BcdToFixedDouble,
    FixedToBcdDouble,
}

/// One row of the operation table.
#[derive(Debug, Clone, Copy)]
pub struct OpInfo {
    pub op: OpCode,
    pub en: &'static str,
    pub de: &'static str,
    /// Supplementary operations are allowed in function blocks only.
    pub supplementary: bool,
    pub summary: &'static str,
    /// A typical operand in each set, empty when the operation takes none.
    pub example_en: &'static str,
    pub example_de: &'static str,
    /// The operation group only some CPUs have (`None`: every CPU has it).
    pub feature: Option<Feature>,
}

const fn basic(
    op: OpCode,
    en: &'static str,
    de: &'static str,
    summary: &'static str,
    example_en: &'static str,
    example_de: &'static str,
) -> OpInfo {
    OpInfo {
        op,
        en,
        de,
        supplementary: false,
        summary,
        example_en,
        example_de,
        feature: None,
    }
}

const fn supp(
    op: OpCode,
    en: &'static str,
    de: &'static str,
    summary: &'static str,
    example_en: &'static str,
    example_de: &'static str,
) -> OpInfo {
    OpInfo {
        supplementary: true,
        ..basic(op, en, de, summary, example_en, example_de)
    }
}

/// `info`, on the CPUs with `feature` only.
const fn needs(info: OpInfo, feature: Feature) -> OpInfo {
    OpInfo {
        feature: Some(feature),
        ..info
    }
}

/// An operation without operand of a group only some CPUs have; the same word in both sets.
const fn featured(
    op: OpCode,
    word: &'static str,
    supplementary: bool,
    summary: &'static str,
    feature: Feature,
) -> OpInfo {
    OpInfo {
        supplementary,
        feature: Some(feature),
        ..basic(op, word, word, summary, "", "")
    }
}

use Feature::{BcdConversions, DoubleBcd, FloatingPoint};
use OpCode::*;

pub static OPERATIONS: &[OpInfo] = &[
    basic(
        And,
        "A",
        "U",
        "AND the operand into the RLO",
        "I 0.0",
        "E 0.0",
    ),
    basic(
        AndNot,
        "AN",
        "UN",
        "AND NOT the operand into the RLO",
        "F 10.0",
        "M 10.0",
    ),
    basic(
        Or,
        "O",
        "O",
        "OR the operand into the RLO; alone: OR of AND functions",
        "Q 4.0",
        "A 4.0",
    ),
    basic(
        OrNot,
        "ON",
        "ON",
        "OR NOT the operand into the RLO",
        "T 1",
        "T 1",
    ),
    basic(AndBracket, "A(", "U(", "open an AND bracket", "", ""),
    basic(OrBracket, "O(", "O(", "open an OR bracket", "", ""),
    basic(
        CloseBracket,
        ")",
        ")",
        "close the bracket and combine",
        "",
        "",
    ),
    basic(
        Assign,
        "=",
        "=",
        "assign the RLO to the bit",
        "Q 4.1",
        "A 4.1",
    ),
    basic(
        Set,
        "S",
        "S",
        "set the bit (or load the counter) when the RLO is 1",
        "F 1.0",
        "M 1.0",
    ),
    basic(
        Reset,
        "R",
        "R",
        "reset the bit, timer or counter when the RLO is 1",
        "C 3",
        "Z 3",
    ),
    basic(
        Load,
        "L",
        "L",
        "load the operand into ACCU 1 (ACCU 1 moves to ACCU 2)",
        "FW 10",
        "MW 10",
    ),
    basic(
        Transfer,
        "T",
        "T",
        "transfer ACCU 1 to the operand",
        "QW 2",
        "AW 2",
    ),
    basic(
        LoadCoded,
        "LC",
        "LC",
        "load a timer or counter value in BCD",
        "T 5",
        "T 5",
    ),
    basic(TimerPulse, "SP", "SI", "start a pulse timer", "T 1", "T 1"),
    basic(
        TimerExtendedPulse,
        "SE",
        "SV",
        "start an extended pulse timer",
        "T 2",
        "T 2",
    ),
    basic(
        TimerOnDelay,
        "SD",
        "SE",
        "start an on-delay timer",
        "T 3",
        "T 3",
    ),
    basic(
        TimerStoredOnDelay,
        "SS",
        "SS",
        "start a stored on-delay timer",
        "T 4",
        "T 4",
    ),
    basic(
        TimerOffDelay,
        "SF",
        "SA",
        "start an off-delay timer",
        "T 5",
        "T 5",
    ),
    basic(
        Enable,
        "FR",
        "FR",
        "enable a timer or counter for a restart",
        "T 1",
        "T 1",
    ),
    basic(CountUp, "CU", "ZV", "count up", "C 1", "Z 1"),
    basic(CountDown, "CD", "ZR", "count down", "C 1", "Z 1"),
    basic(
        AddFixed,
        "+F",
        "+F",
        "fixed-point add: ACCU 2 + ACCU 1",
        "",
        "",
    ),
    basic(
        SubFixed,
        "-F",
        "-F",
        "fixed-point subtract: ACCU 2 - ACCU 1",
        "",
        "",
    ),
    basic(
        MulFixed,
        "X F",
        "X F",
        "fixed-point multiply: ACCU 2 * ACCU 1",
        "",
        "",
    ),
    basic(
        DivFixed,
        ":F",
        ":F",
        "fixed-point divide: ACCU 2 / ACCU 1",
        "",
        "",
    ),
    basic(CmpEq, "!=F", "!=F", "compare ACCU 2 = ACCU 1", "", ""),
    basic(CmpNe, "><F", "><F", "compare ACCU 2 <> ACCU 1", "", ""),
    basic(CmpGt, ">F", ">F", "compare ACCU 2 > ACCU 1", "", ""),
    basic(CmpGe, ">=F", ">=F", "compare ACCU 2 >= ACCU 1", "", ""),
    basic(CmpLt, "<F", "<F", "compare ACCU 2 < ACCU 1", "", ""),
    basic(CmpLe, "<=F", "<=F", "compare ACCU 2 <= ACCU 1", "", ""),
    basic(
        JumpUnconditional,
        "JU",
        "SPA",
        "call a block unconditionally",
        "PB 3",
        "PB 3",
    ),
    basic(
        JumpConditional,
        "JC",
        "SPB",
        "call a block when the RLO is 1",
        "FB 5",
        "FB 5",
    ),
    basic(OpenDb, "C", "A", "open a data block", "DB 10", "DB 10"),
    basic(BlockEnd, "BE", "BE", "block end", "", ""),
    basic(
        BlockEndConditional,
        "BEC",
        "BEB",
        "block end when the RLO is 1",
        "",
        "",
    ),
    basic(
        BlockEndUnconditional,
        "BEU",
        "BEA",
        "block end unconditionally",
        "",
        "",
    ),
    basic(Nop, "NOP", "NOP", "no operation (NOP 0 / NOP 1)", "0", "0"),
    basic(
        Display,
        "BLD",
        "BLD",
        "display construction for the programmer",
        "130",
        "130",
    ),
    basic(
        Stop,
        "STP",
        "STP",
        "go to STOP at the end of the cycle",
        "",
        "",
    ),
    supp(
        JumpZero,
        "JZ",
        "SPZ",
        "jump to the label when the result is zero",
        "=M001",
        "=M001",
    ),
    supp(
        JumpNotZero,
        "JN",
        "SPN",
        "jump to the label when the result is not zero",
        "=M001",
        "=M001",
    ),
    supp(
        JumpPositive,
        "JP",
        "SPP",
        "jump to the label when the result is positive",
        "=M001",
        "=M001",
    ),
    supp(
        JumpMinus,
        "JM",
        "SPM",
        "jump to the label when the result is negative",
        "=M001",
        "=M001",
    ),
    supp(
        JumpOverflow,
        "JO",
        "SPO",
        "jump to the label on overflow",
        "=M001",
        "=M001",
    ),
    supp(AndWord, "AW", "UW", "AND word: ACCU 1 and ACCU 2", "", ""),
    supp(OrWord, "OW", "OW", "OR word: ACCU 1 or ACCU 2", "", ""),
    supp(XorWord, "XOW", "XOW", "exclusive OR word", "", ""),
    supp(
        ShiftLeft,
        "SLW",
        "SLW",
        "shift ACCU 1 left by n bits",
        "3",
        "3",
    ),
    supp(
        ShiftRight,
        "SRW",
        "SRW",
        "shift ACCU 1 right by n bits",
        "3",
        "3",
    ),
    supp(
        OnesComplement,
        "CFW",
        "KEW",
        "one's complement of ACCU 1",
        "",
        "",
    ),
    supp(
        TwosComplement,
        "CSW",
        "KZW",
        "two's complement of ACCU 1",
        "",
        "",
    ),
    supp(Swap, "TAK", "TAK", "swap ACCU 1 and ACCU 2", "", ""),
    supp(
        Enter,
        "ENT",
        "ENT",
        "ACCU 3 to ACCU 4, ACCU 2 to ACCU 3 (CPUs with four accumulators)",
        "",
        "",
    ),
    supp(Increment, "I", "I", "increment ACCU 1 by n", "1", "1"),
    supp(Decrement, "D", "D", "decrement ACCU 1 by n", "1", "1"),
    supp(
        Indirect,
        "DO",
        "B",
        "process the next operation with the parameter in FW/DW",
        "FW 20",
        "MW 20",
    ),
    supp(
        SetUnconditional,
        "SU",
        "SU",
        "set the bit unconditionally",
        "D 1.0",
        "D 1.0",
    ),
    supp(
        ResetUnconditional,
        "RU",
        "RU",
        "reset the bit unconditionally",
        "D 1.0",
        "D 1.0",
    ),
    supp(
        TestBit,
        "TB",
        "P",
        "test the bit for 1 into the RLO",
        "D 1.0",
        "D 1.0",
    ),
    supp(
        TestBitNot,
        "TBN",
        "PN",
        "test the bit for 0 into the RLO",
        "D 1.0",
        "D 1.0",
    ),
    supp(
        DisableInterrupts,
        "IA",
        "AS",
        "disable interrupt servicing",
        "",
        "",
    ),
    supp(
        EnableInterrupts,
        "RA",
        "AF",
        "enable interrupt servicing",
        "",
        "",
    ),
    supp(
        GenerateDb,
        "G",
        "E",
        "generate a data block of ACCU 1 words",
        "DB 20",
        "DB 20",
    ),
    // The formal-operand operations: each takes `=NAME` only, and runs as the basic operation
    // its actual parameter decides (see `compiler::specialise::formal_meaning`).
    supp(
        ResetBinary,
        "RB",
        "RB",
        "reset a formal operand bit (I, Q parameter) when the RLO is 1",
        "=X",
        "=X",
    ),
    supp(
        ResetDigital,
        "RD",
        "RD",
        "reset a formal operand timer or counter when the RLO is 1",
        "=TIM",
        "=TIM",
    ),
    supp(
        LoadBitPattern,
        "LW",
        "LW",
        "load the constant of a D parameter into ACCU 1 as a bit pattern",
        "=KON",
        "=KON",
    ),
    supp(
        LoadDecimal,
        "LD",
        "LD",
        "load the constant of a D parameter into ACCU 1",
        "=KON",
        "=KON",
    ),
    needs(
        supp(
            AddConstant,
            "ADD",
            "ADD",
            "add a constant to ACCU 1 (KB, KF: low word; DH: 32 bits)",
            "KF +5",
            "KF +5",
        ),
        Feature::AddConstant,
    ),
    // System and register operations on absolute addresses: parsed and timed, but running one
    // stops the CPU (awl has no S5 memory map; `awl help language` says why).
    needs(
        supp(
            TransferBytes,
            "TNB",
            "TNB",
            "transfer a field of n bytes between absolute addresses (not simulated)",
            "10",
            "10",
        ),
        Feature::SystemOperations,
    ),
    needs(
        supp(
            LoadIndirect,
            "LIR",
            "LIR",
            "load register n from the absolute address in ACCU 1 (not simulated)",
            "2",
            "2",
        ),
        Feature::SystemOperations,
    ),
    needs(
        supp(
            TransferIndirect,
            "TIR",
            "TIR",
            "transfer register n to the absolute address in ACCU 1 (not simulated)",
            "2",
            "2",
        ),
        Feature::SystemOperations,
    ),
    needs(
        supp(
            MoveBrToAccu,
            "MBA",
            "MBA",
            "move the base address register BR to ACCU 1 (not simulated)",
            "",
            "",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            MoveAccuToBr,
            "MAB",
            "MAB",
            "move ACCU 1 to the base address register BR (not simulated)",
            "",
            "",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            MoveSaToAccu,
            "MSA",
            "MSA",
            "move the STEP address counter SA to ACCU 1 (not simulated)",
            "",
            "",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            MoveAccuToSa,
            "MAS",
            "MAS",
            "move ACCU 1 to the STEP address counter SA (not simulated)",
            "",
            "",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            AddToBr,
            "ABR",
            "ABR",
            "add n to the base address register BR (not simulated)",
            "4",
            "4",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            LoadRelativeBr,
            "LRB",
            "LRB",
            "load ACCU 1 from the word at BR + n (not simulated)",
            "4",
            "4",
        ),
        Feature::RegisterOperations,
    ),
    needs(
        supp(
            TransferRelativeBr,
            "TRB",
            "TRB",
            "transfer ACCU 1 to the word at BR + n (not simulated)",
            "4",
            "4",
        ),
        Feature::RegisterOperations,
    ),
    // CPU 928B programming guide, table 3-7 (arithmetic, basic operations) and table 3-21
    // (conversion operations, supplementary); the G comparisons sit with the F comparisons.
    featured(
        AddFloat,
        "+G",
        false,
        "floating-point add: ACCU 2 + ACCU 1",
        FloatingPoint,
    ),
    featured(
        SubFloat,
        "-G",
        false,
        "floating-point subtract: ACCU 2 - ACCU 1",
        FloatingPoint,
    ),
    featured(
        MulFloat,
        "X G",
        false,
        "floating-point multiply: ACCU 2 * ACCU 1",
        FloatingPoint,
    ),
    featured(
        DivFloat,
        ":G",
        false,
        "floating-point divide: ACCU 2 / ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpEqFloat,
        "!=G",
        false,
        "floating-point compare ACCU 2 = ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpNeFloat,
        "><G",
        false,
        "floating-point compare ACCU 2 <> ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpGtFloat,
        ">G",
        false,
        "floating-point compare ACCU 2 > ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpGeFloat,
        ">=G",
        false,
        "floating-point compare ACCU 2 >= ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpLtFloat,
        "<G",
        false,
        "floating-point compare ACCU 2 < ACCU 1",
        FloatingPoint,
    ),
    featured(
        CmpLeFloat,
        "<=G",
        false,
        "floating-point compare ACCU 2 <= ACCU 1",
        FloatingPoint,
    ),
    featured(
        FixedToFloat,
        "FDG",
        true,
        "ACCU 1: 32-bit fixed point to floating point",
        FloatingPoint,
    ),
    featured(
        FloatToFixed,
        "GFD",
        true,
        "ACCU 1: floating point to 32-bit fixed point",
        FloatingPoint,
    ),
    featured(
        BcdToFixed,
        "DEF",
        true,
        "ACCU 1-L: 16-bit BCD to fixed point",
        BcdConversions,
    ),
    featured(
        FixedToBcd,
        "DUF",
        true,
        "ACCU 1-L: 16-bit fixed point to BCD",
        BcdConversions,
    ),
    featured(
        BcdToFixedDouble,
        "DED",
        true,
        "ACCU 1: 32-bit BCD to fixed point",
        DoubleBcd,
    ),
    featured(
        FixedToBcdDouble,
        "DUD",
        true,
        "ACCU 1: 32-bit fixed point to BCD",
        DoubleBcd,
    ),
];

/// Operand areas.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Area {
    Input,
    Output,
    Flag,
    Timer,
    Counter,
    DataBit,
    InputByte,
    InputWord,
    OutputByte,
    OutputWord,
    FlagByte,
    FlagWord,
    FlagDouble,
    DataLeft,
    DataRight,
    DataWord,
    DataDouble,
    PeripheralByte,
    PeripheralWord,
    ExtendedByte,
    ExtendedWord,
}

impl Area {
    /// Areas addressed as `byte.bit`.
    pub fn is_bit(self) -> bool {
        matches!(
            self,
            Area::Input | Area::Output | Area::Flag | Area::DataBit
        )
    }
}

#[derive(Debug, Clone, Copy)]
pub struct AreaInfo {
    pub area: Area,
    pub en: &'static str,
    pub de: &'static str,
    pub summary: &'static str,
}

pub static AREAS: &[AreaInfo] = &[
    AreaInfo {
        area: Area::Input,
        en: "I",
        de: "E",
        summary: "input bit n.m (PII)",
    },
    AreaInfo {
        area: Area::Output,
        en: "Q",
        de: "A",
        summary: "output bit n.m (PIQ)",
    },
    AreaInfo {
        area: Area::Flag,
        en: "F",
        de: "M",
        summary: "flag bit n.m",
    },
    AreaInfo {
        area: Area::Timer,
        en: "T",
        de: "T",
        summary: "timer n",
    },
    AreaInfo {
        area: Area::Counter,
        en: "C",
        de: "Z",
        summary: "counter n",
    },
    AreaInfo {
        area: Area::DataBit,
        en: "D",
        de: "D",
        summary: "data bit n.m of the open DB",
    },
    AreaInfo {
        area: Area::InputByte,
        en: "IB",
        de: "EB",
        summary: "input byte",
    },
    AreaInfo {
        area: Area::InputWord,
        en: "IW",
        de: "EW",
        summary: "input word",
    },
    AreaInfo {
        area: Area::OutputByte,
        en: "QB",
        de: "AB",
        summary: "output byte",
    },
    AreaInfo {
        area: Area::OutputWord,
        en: "QW",
        de: "AW",
        summary: "output word",
    },
    AreaInfo {
        area: Area::FlagByte,
        en: "FY",
        de: "MB",
        summary: "flag byte",
    },
    AreaInfo {
        area: Area::FlagWord,
        en: "FW",
        de: "MW",
        summary: "flag word",
    },
    AreaInfo {
        area: Area::FlagDouble,
        en: "FD",
        de: "MD",
        summary: "flag double word",
    },
    AreaInfo {
        area: Area::DataLeft,
        en: "DL",
        de: "DL",
        summary: "data word, left (high) byte",
    },
    AreaInfo {
        area: Area::DataRight,
        en: "DR",
        de: "DR",
        summary: "data word, right (low) byte",
    },
    AreaInfo {
        area: Area::DataWord,
        en: "DW",
        de: "DW",
        summary: "data word",
    },
    AreaInfo {
        area: Area::DataDouble,
        en: "DD",
        de: "DD",
        summary: "data double word",
    },
    AreaInfo {
        area: Area::PeripheralByte,
        en: "PY",
        de: "PB",
        summary: "peripheral byte (direct)",
    },
    AreaInfo {
        area: Area::PeripheralWord,
        en: "PW",
        de: "PW",
        summary: "peripheral word (direct)",
    },
    AreaInfo {
        area: Area::ExtendedByte,
        en: "OY",
        de: "QB",
        summary: "extended peripheral byte",
    },
    AreaInfo {
        area: Area::ExtendedWord,
        en: "OW",
        de: "QW",
        summary: "extended peripheral word",
    },
];

/// Block types.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum BlockKind {
    Ob,
    Pb,
    Sb,
    Fb,
    Fx,
    Db,
    Dx,
    /// STEP 7's function (the dialect's own block; not in [`BlockKind::ALL`]).
    Fc,
}

impl BlockKind {
    pub const ALL: [BlockKind; 7] = [
        BlockKind::Ob,
        BlockKind::Pb,
        BlockKind::Sb,
        BlockKind::Fb,
        BlockKind::Fx,
        BlockKind::Db,
        BlockKind::Dx,
    ];

    pub fn name(self) -> &'static str {
        match self {
            BlockKind::Ob => "OB",
            BlockKind::Pb => "PB",
            BlockKind::Sb => "SB",
            BlockKind::Fb => "FB",
            BlockKind::Fx => "FX",
            BlockKind::Db => "DB",
            BlockKind::Dx => "DX",
            BlockKind::Fc => "FC",
        }
    }

    pub fn from_word(word: &str) -> Option<Self> {
        BlockKind::ALL
            .into_iter()
            .find(|kind| kind.name().eq_ignore_ascii_case(word))
    }

    pub fn is_data(self) -> bool {
        matches!(self, BlockKind::Db | BlockKind::Dx)
    }

    /// Function blocks may use the supplementary operation set.
    pub fn is_function(self) -> bool {
        matches!(self, BlockKind::Fb | BlockKind::Fx)
    }
}

/// Constant formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ConstFormat {
    Byte,
    Fixed,
    Hex,
    BitPattern,
    TwoBytes,
    Time,
    Count,
    Chars,
    Float,
    DoubleHex,
}

impl ConstFormat {
    /// The 16-bit words one value of the format fills: two for the 32-bit formats (`KG`, `DH`).
    pub fn words(self) -> u16 {
        match self {
            ConstFormat::Float | ConstFormat::DoubleHex => 2,
            _ => 1,
        }
    }
}

#[derive(Debug, Clone, Copy)]
pub struct ConstInfo {
    pub format: ConstFormat,
    pub en: &'static str,
    pub de: &'static str,
    pub summary: &'static str,
    pub example: &'static str,
}

pub static CONSTANTS: &[ConstInfo] = &[
    ConstInfo {
        format: ConstFormat::Byte,
        en: "KB",
        de: "KB",
        summary: "byte 0…255",
        example: "10",
    },
    ConstInfo {
        format: ConstFormat::Fixed,
        en: "KF",
        de: "KF",
        summary: "fixed-point −32768…+32767",
        example: "-100",
    },
    ConstInfo {
        format: ConstFormat::Hex,
        en: "KH",
        de: "KH",
        summary: "hex, 1…4 digits",
        example: "00FF",
    },
    ConstInfo {
        format: ConstFormat::BitPattern,
        en: "KM",
        de: "KM",
        summary: "bit pattern, up to 16 binary digits",
        example: "0000000011110000",
    },
    ConstInfo {
        format: ConstFormat::TwoBytes,
        en: "KY",
        de: "KY",
        summary: "two bytes 0…255",
        example: "12,34",
    },
    ConstInfo {
        format: ConstFormat::Time,
        en: "KT",
        de: "KT",
        summary: "time value 0…999 and base 0…3",
        example: "050.1",
    },
    ConstInfo {
        format: ConstFormat::Count,
        en: "KC",
        de: "KZ",
        summary: "count 0…999",
        example: "500",
    },
    ConstInfo {
        format: ConstFormat::Chars,
        en: "KS",
        de: "KS",
        summary: "characters",
        example: "'AB'",
    },
    ConstInfo {
        format: ConstFormat::Float,
        en: "KG",
        de: "KG",
        summary: "floating point ±mantissa(7)±exponent(2)",
        example: "+1234567+02",
    },
    ConstInfo {
        format: ConstFormat::DoubleHex,
        en: "DH",
        de: "DH",
        summary: "double word hex, 1…8 digits",
        example: "0000FFFF",
    },
];

/// Kinds of FB formal parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ParamKind {
    Input,
    Output,
    Data,
    Block,
    Timer,
    Counter,
}

#[derive(Debug, Clone, Copy)]
pub struct ParamKindInfo {
    pub kind: ParamKind,
    pub en: &'static str,
    pub de: &'static str,
}

pub static PARAM_KINDS: &[ParamKindInfo] = &[
    ParamKindInfo {
        kind: ParamKind::Input,
        en: "I",
        de: "E",
    },
    ParamKindInfo {
        kind: ParamKind::Output,
        en: "Q",
        de: "A",
    },
    ParamKindInfo {
        kind: ParamKind::Data,
        en: "D",
        de: "D",
    },
    ParamKindInfo {
        kind: ParamKind::Block,
        en: "B",
        de: "B",
    },
    ParamKindInfo {
        kind: ParamKind::Timer,
        en: "T",
        de: "T",
    },
    ParamKindInfo {
        kind: ParamKind::Counter,
        en: "C",
        de: "Z",
    },
];

/// Words of the FB header: the FB's name line and its declaration lines.
pub const NAME_WORD: &str = "NAME";
pub const DECLARATION_EN: &str = "DES";
pub const DECLARATION_DE: &str = "BEZ";

/// Packs up to 8 ASCII characters, upper-cased, into a lookup key.
pub fn key(word: &str) -> Option<u64> {
    if word.len() > 8 || !word.is_ascii() {
        return None;
    }
    let mut packed = [0u8; 8];
    for (slot, byte) in packed.iter_mut().zip(word.bytes()) {
        *slot = byte.to_ascii_uppercase();
    }
    Some(u64::from_le_bytes(packed))
}

/// Words of one kind: per set, an open-addressing hash table of packed words (the front end
/// looks up every word of every line, so this is on its hot path). Both dialects' mnemonic
/// tables are made of it.
pub(crate) struct Table<V> {
    english: Slots<V>,
    german: Slots<V>,
}

struct Slots<V> {
    slots: Box<[Option<(u64, V)>]>,
    mask: usize,
}

impl<V: Copy> Slots<V> {
    /// The table of `entries`; of two rows with one word, the first counts.
    fn new(entries: impl ExactSizeIterator<Item = (u64, V)>) -> Self {
        let size = (entries.len() * 4).next_power_of_two();
        let mut table = Slots {
            slots: vec![None; size].into_boxed_slice(),
            mask: size - 1,
        };
        for (key, value) in entries {
            let mut at = Self::home(key) & table.mask;
            loop {
                match table.slots[at] {
                    None => {
                        table.slots[at] = Some((key, value));
                        break;
                    }
                    Some((taken, _)) if taken == key => break,
                    Some(_) => at = (at + 1) & table.mask,
                }
            }
        }
        table
    }

    fn home(key: u64) -> usize {
        (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 40) as usize
    }

    fn get(&self, key: u64) -> Option<V> {
        let mut at = Self::home(key) & self.mask;
        loop {
            match self.slots.get(at)? {
                None => return None,
                Some((found, value)) if *found == key => return Some(*value),
                Some(_) => at = (at + 1) & self.mask,
            }
        }
    }
}

impl<V: Copy> Table<V> {
    pub(crate) fn new<T>(
        rows: &[T],
        words: impl Fn(&T) -> (&'static str, &'static str),
        value: impl Fn(&T) -> V,
    ) -> Self {
        let (words, value) = (&words, &value);
        let entries = |pick: fn((&'static str, &'static str)) -> &'static str| {
            rows.iter().map(move |row| {
                let word = pick(words(row));
                (key(word).expect("table words are short ASCII"), value(row))
            })
        };
        Table {
            english: Slots::new(entries(|(en, _)| en)),
            german: Slots::new(entries(|(_, de)| de)),
        }
    }

    pub(crate) fn get(&self, set: MnemonicSet, word: &str) -> Option<V> {
        let slots = match set {
            MnemonicSet::English => &self.english,
            MnemonicSet::German => &self.german,
        };
        slots.get(key(word)?)
    }
}

struct Tables {
    operations: Table<OpCode>,
    areas: Table<Area>,
    constants: Table<ConstFormat>,
    param_kinds: Table<ParamKind>,
}

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| Tables {
        operations: Table::new(OPERATIONS, |r| (r.en, r.de), |r| r.op),
        areas: Table::new(AREAS, |r| (r.en, r.de), |r| r.area),
        constants: Table::new(CONSTANTS, |r| (r.en, r.de), |r| r.format),
        param_kinds: Table::new(PARAM_KINDS, |r| (r.en, r.de), |r| r.kind),
    })
}

pub fn operation(set: MnemonicSet, word: &str) -> Option<OpInfo> {
    tables().operations.get(set, word).map(|op| *op_info(op))
}

pub fn area(set: MnemonicSet, word: &str) -> Option<Area> {
    tables().areas.get(set, word)
}

pub fn constant_format(set: MnemonicSet, word: &str) -> Option<ConstFormat> {
    tables().constants.get(set, word)
}

pub fn param_kind(set: MnemonicSet, word: &str) -> Option<ParamKind> {
    tables().param_kinds.get(set, word)
}

/// The table row of an operation; `OPERATIONS` is in `OpCode` order (a test checks it).
pub fn op_info(op: OpCode) -> &'static OpInfo {
    &OPERATIONS[op as usize]
}

pub fn op_word(set: MnemonicSet, op: OpCode) -> &'static str {
    let info = op_info(op);
    match set {
        MnemonicSet::English => info.en,
        MnemonicSet::German => info.de,
    }
}

pub fn area_word(set: MnemonicSet, area: Area) -> &'static str {
    let info = AREAS
        .iter()
        .find(|info| info.area == area)
        .expect("every area has a row");
    match set {
        MnemonicSet::English => info.en,
        MnemonicSet::German => info.de,
    }
}

/// Where a word stands on a statement line; the sets share many words, but seldom in one position.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Position {
    Operation,
    Operand,
}

/// The set a word in a position belongs to, when only one set knows it there.
pub fn evidence(position: Position, word: &str) -> Option<MnemonicSet> {
    let known = |set| match position {
        Position::Operation => operation(set, word).is_some(),
        Position::Operand => {
            area(set, word).is_some()
                || constant_format(set, word).is_some()
                || BlockKind::from_word(word).is_some()
        }
    };
    match (known(MnemonicSet::English), known(MnemonicSet::German)) {
        (true, false) => Some(MnemonicSet::English),
        (false, true) => Some(MnemonicSet::German),
        _ => None,
    }
}

/// Candidate words of one set for a "did you mean" help.
pub fn operation_words(set: MnemonicSet) -> impl Iterator<Item = &'static str> {
    OPERATIONS.iter().map(move |info| match set {
        MnemonicSet::English => info.en,
        MnemonicSet::German => info.de,
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn packed_words_are_upper_case_as_one_byte_at_a_time_makes_them() {
        for byte in 0u8..0x80 {
            let word = String::from_utf8(vec![byte; 8]).unwrap();
            let one_by_one = u64::from_le_bytes([byte.to_ascii_uppercase(); 8]);
            assert_eq!(super::key(&word), Some(one_by_one), "{byte:#x}");
        }
        assert_eq!(super::key("spa"), super::key("SPA"));
    }

    use super::*;

    #[test]
    fn operations_are_in_op_code_order() {
        for (index, info) in OPERATIONS.iter().enumerate() {
            assert_eq!(info.op as usize, index, "{:?}", info.op);
        }
    }

    #[test]
    fn every_word_of_the_tables_is_found_and_others_are_not() {
        for set in [MnemonicSet::English, MnemonicSet::German] {
            for info in OPERATIONS {
                let word = op_word(set, info.op);
                let found = operation(set, word).map(|found| op_word(set, found.op));
                assert_eq!(found, Some(word), "{set:?} {word}");
                assert!(operation(set, &word.to_ascii_lowercase()).is_some());
            }
            for info in AREAS {
                assert!(area(set, area_word(set, info.area)).is_some());
            }
            for word in ["", "XYZZY", "TOOLONGWORD", "Ä", "=F"] {
                assert!(operation(set, word).is_none(), "{set:?} {word}");
                assert!(area(set, word).is_none(), "{set:?} {word}");
            }
        }
    }

    #[test]
    fn sets_disagree_on_se() {
        assert_eq!(
            operation(MnemonicSet::English, "se").unwrap().op,
            TimerExtendedPulse
        );
        assert_eq!(
            operation(MnemonicSet::German, "SE").unwrap().op,
            TimerOnDelay
        );
    }

    #[test]
    fn evidence_depends_on_position() {
        assert_eq!(
            evidence(Position::Operation, "U"),
            Some(MnemonicSet::German)
        );
        assert_eq!(
            evidence(Position::Operation, "JU"),
            Some(MnemonicSet::English)
        );
        assert_eq!(evidence(Position::Operation, "A"), None);
        assert_eq!(evidence(Position::Operand, "A"), Some(MnemonicSet::German));
        assert_eq!(evidence(Position::Operand, "I"), Some(MnemonicSet::English));
        assert_eq!(evidence(Position::Operand, "PB"), None);
    }
}
