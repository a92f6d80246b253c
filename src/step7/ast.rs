//! The syntax tree of a STEP 7 STL source: blocks with their interfaces and statements, with
//! spans. Operations are named by [`S7Op`] whatever mnemonic set they were written in.

use crate::ast::Name;
use crate::mnemonics::MnemonicSet;
/// The six comparisons are the machine's rules ([`crate::rules`]), defined once.
pub use crate::rules::arith::Comparison as Cmp;
/// So are the status conditions (`==0`, `OV`, `BR` …).
pub use crate::rules::jump::Condition;
/// And the REAL functions of ACCU 1.
pub use crate::rules::real::Function;
/// And the ways a bit or a bracket combines with the RLO.
pub use crate::rules::status::Combination;
use crate::source::{FileId, Span};

/// One parsed STEP 7 source file.
#[derive(Debug, Clone)]
pub struct S7Unit {
    pub file: FileId,
    pub mnemonics: MnemonicSet,
    pub blocks: Vec<S7Block>,
}

impl S7Unit {
    /// The statements of the file's logic blocks, in file order.
    pub fn statements(&self) -> impl Iterator<Item = &S7Statement> {
        self.blocks
            .iter()
            .filter_map(|block| match &block.body {
                S7Body::Logic(statements) => Some(statements),
                _ => None,
            })
            .flatten()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum S7BlockKind {
    Ob,
    Fc,
    Fb,
    Db,
    Udt,
    Sfc,
    Sfb,
}

impl S7BlockKind {
    pub fn name(self) -> &'static str {
        match self {
            S7BlockKind::Ob => "OB",
            S7BlockKind::Fc => "FC",
            S7BlockKind::Fb => "FB",
            S7BlockKind::Db => "DB",
            S7BlockKind::Udt => "UDT",
            S7BlockKind::Sfc => "SFC",
            S7BlockKind::Sfb => "SFB",
        }
    }
}

/// `FC 1`, `DB 5`, or a symbol `"Motor"` that the symbol table turns into one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum S7BlockRef {
    Number { kind: S7BlockKind, number: u16 },
    Symbol(Name),
}

impl S7BlockRef {
    /// `FC 1`, or `"Valve"` when the source names the block by its symbol.
    pub fn written(&self) -> String {
        match self {
            S7BlockRef::Number { kind, number } => format!("{} {number}", kind.name()),
            S7BlockRef::Symbol(name) => format!("\"{}\"", name.text),
        }
    }
}

#[derive(Debug, Clone)]
pub struct S7Block {
    /// `ORGANIZATION_BLOCK` → Ob, `FUNCTION` → Fc, `FUNCTION_BLOCK` → Fb, `DATA_BLOCK` → Db,
    /// `TYPE` → Udt.
    pub kind: S7BlockKind,
    pub name: S7BlockRef,
    /// The header line (`FUNCTION FC 1 : INT`).
    pub header: Span,
    /// `FUNCTION FC 1 : INT`: the return type (`VOID` gives `None`).
    pub return_type: Option<DataType>,
    pub interface: Vec<VarSection>,
    pub body: S7Body,
    /// The `END_…` line; `None` when the file ended first (an error was reported).
    pub end: Option<Span>,
}

#[derive(Debug, Clone)]
pub enum S7Body {
    /// OB, FC, FB: the statements after `BEGIN` (or of a flat file).
    Logic(Vec<S7Statement>),
    /// `DATA_BLOCK`: a global DB with its `STRUCT`, or an instance DB of an FB/SFB; then the
    /// initial values after `BEGIN`.
    Data {
        instance_of: Option<S7BlockRef>,
        /// The `STRUCT … END_STRUCT` members of a global DB (empty for an instance DB).
        members: Vec<VarDecl>,
        initial: Vec<InitialValue>,
    },
    /// `TYPE UDT n`: the structure.
    Type(Vec<VarDecl>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarKind {
    Input,
    Output,
    InOut,
    /// `VAR`: static data of an FB (in its instance DB).
    Static,
    Temp,
}

#[derive(Debug, Clone)]
pub struct VarSection {
    pub kind: VarKind,
    pub vars: Vec<VarDecl>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub struct VarDecl {
    pub name: Name,
    pub ty: DataType,
    /// `:= value` (arrays: one value per element as written, `3 (0)` repeats are expanded).
    pub initial: Vec<S7Constant>,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum DataType {
    Bool,
    Byte,
    Word,
    Dword,
    Int,
    Dint,
    Real,
    S5Time,
    Time,
    Date,
    TimeOfDay,
    Char,
    DateAndTime,
    /// `STRING[n]` (254 when no length is given).
    String(u8),
    Array {
        /// `[1..10, 0..3]`
        dims: Vec<(i32, i32)>,
        element: Box<DataType>,
    },
    Struct(Vec<VarDecl>),
    Udt(u16),
    /// A multi-instance `name : FB 5` / `SFB 3`.
    Instance(S7BlockKind, u16),
    /// A UDT or FB written by its symbol, `"MotorData"`: the compiler replaces it by the
    /// [`DataType::Udt`] or [`DataType::Instance`] the name stands for.
    Named(Name),
    Timer,
    Counter,
    Pointer,
    Any,
    BlockDb,
    BlockFb,
    BlockFc,
}

/// `name := value;` after `BEGIN` in a data block; `path` is `a.b[1, 2]` as written.
#[derive(Debug, Clone)]
pub struct InitialValue {
    pub path: Vec<PathPart>,
    pub value: S7Constant,
    pub span: Span,
}

/// One step of a member path: `motor`, `speeds[3]`.
#[derive(Debug, Clone, PartialEq)]
pub enum PathPart {
    Member(Name),
    Index(Vec<i32>),
}

#[derive(Debug, Clone)]
pub struct S7Statement {
    pub label: Option<Name>,
    pub op: S7Op,
    pub op_span: Span,
    pub operand: S7Operand,
    pub operand_span: Span,
    /// `CALL FB 1, DB 1 (IN := …)`: what is called and with what.
    pub call: Option<CallSpec>,
    /// The `NETWORK` it is in, counted from 1; 0 before the first.
    pub network: u16,
    /// The whole statement, up to its `;`.
    pub span: Span,
}

#[derive(Debug, Clone)]
pub struct CallSpec {
    pub block: S7BlockRef,
    /// `CALL FB 1, DB 1`: the instance DB.
    pub instance: Option<S7BlockRef>,
    /// `CALL #motor`: a multi-instance of the calling FB.
    pub multi_instance: Option<Name>,
    pub params: Vec<CallParam>,
}

/// `IN1 := M 0.0` in a call's parameter list.
#[derive(Debug, Clone)]
pub struct CallParam {
    pub name: Name,
    pub actual: S7Operand,
    pub actual_span: Span,
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum S7Operand {
    None,
    Address(S7Address),
    /// `MW [MD 10]`, `DBX [AR1, P#2.0]`: the area and width, and where the pointer comes from.
    Indirect {
        area: S7Area,
        width: AccessWidth,
        pointer: IndirectPointer,
    },
    /// `#speed`, `#motor.on`, `#values[3]`: a block-local name with its member path.
    Local(Vec<PathPart>),
    /// `"Motor"`, or `"DB".member`: a symbol of the symbol table, with a member path.
    Symbol {
        name: Name,
        members: Vec<PathPart>,
    },
    Constant(S7Constant),
    /// A jump target.
    Label(Name),
    Block(S7BlockRef),
    /// `OPN DB [MW 2]`, `UC FC [MW 50]`: a block whose number is read from the word `word`.
    BlockFrom {
        kind: S7BlockKind,
        word: Box<S7Operand>,
    },
    /// A number where the operation takes one: `SLW 3`, `+AR1 P#…` is a constant instead.
    Number(i64),
    /// `L DBNO`, `L DBLG`, `L DINO`, `L DILG`.
    DbRegister(DbRegister),
    /// `LAR1 AR2`, `TAR1 AR2`: an address register as the operand.
    AddressRegister(u8),
    /// awlsim's test operands (`__STW VKE`, `__ACCU 1`, …); only with the test extensions.
    Extension(Extension),
    /// `__ASSERT== a, b`: two operands.
    Pair(Box<S7Operand>, Box<S7Operand>),
    /// `MW [#pointer]`, `DBX [#offset]`: memory-indirect through a block-local double word
    /// (a word for timers and counters).
    IndirectLocal {
        area: S7Area,
        width: AccessWidth,
        pointer: Vec<PathPart>,
    },
    /// `DB1.member`, `DB1.values[2].on`: a member of a global data block by name.
    DbMember {
        db: u16,
        path: Vec<PathPart>,
    },
    /// `P##local`, `P#DB1.member`, `P#"symbol"`: a pointer to what the operand names (an
    /// area pointer, or an ANY pointer where the parameter is one).
    PointerTo(Box<S7Operand>),
    /// `A ==0`, `O OV`, `A BR` (German `BIE`): a status condition read by bit logic.
    Condition(Condition),
    /// `L W [AR1, P#0.0]`, `A [AR2, P#2.0]`: register-indirect and area-crossing, the area is
    /// in the address register's pointer. `width` is `Bit` for the bit operations.
    AreaCrossing {
        width: AccessWidth,
        ar: u8,
        offset: u32,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DbRegister {
    /// `DBNO`: the number of the DB in the DB register.
    DbNumber,
    /// `DBLG`: its length in bytes.
    DbLength,
    DiNumber,
    DiLength,
}

/// The memory areas of STEP 7 addresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum S7Area {
    Input,
    Output,
    Flag,
    /// L: the running block's local data.
    Local,
    /// V: the calling block's local data.
    PreviousLocal,
    /// DBX/DBB/DBW/DBD: the open data block (or `DB5.DBW 4`, see [`S7Address::db`]).
    Data,
    /// DIX/DIB/DIW/DID: the open instance data block.
    Instance,
    PeripheralInput,
    PeripheralOutput,
    Timer,
    Counter,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum AccessWidth {
    Bit,
    Byte,
    Word,
    Double,
}

impl AccessWidth {
    /// The bytes an access of this width reads or writes (a bit's byte for a bit).
    pub const fn bytes(self) -> u32 {
        match self {
            AccessWidth::Bit | AccessWidth::Byte => 1,
            AccessWidth::Word => 2,
            AccessWidth::Double => 4,
        }
    }
}

/// `I 0.1`, `MW 10`, `DB5.DBW 4`, `L 2.0`, `PIW 256`, `T 5`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct S7Address {
    pub area: S7Area,
    pub width: AccessWidth,
    /// Byte number (timer or counter number for T and C).
    pub byte: u32,
    pub bit: u8,
    /// `DB5.DBW 4`: the data block it names (the access opens it).
    pub db: Option<u16>,
}

/// Where an indirect address takes its pointer from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IndirectPointer {
    /// Memory-indirect: `[MD 10]`, `[LD 2]`, `[DBD 0]`, `[DID 4]` (a double word, or a word for
    /// timers, counters and blocks: `T [MW 4]`).
    Memory(S7Address),
    /// Register-indirect, area-internal or area-crossing: `[AR1, P#2.0]`.
    Register { ar: u8, offset: u32 },
}

/// A typed constant: its type as written and its value as the CPU loads it into ACCU 1.
#[derive(Debug, Clone, PartialEq)]
pub struct S7Constant {
    pub kind: ConstKind,
    /// The 32-bit value loaded (REAL: the IEEE bits; a pointer: the area pointer).
    pub value: u32,
    /// Values wider than 32 bits (`DT#…`, `'long string'`, an ANY pointer): their bytes.
    pub bytes: Vec<u8>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConstKind {
    Bool,
    /// A decimal integer in −32768 … 32767 (16 bits).
    Int,
    /// `L#…`, or a decimal integer beyond 16 bits.
    Dint,
    Real,
    /// `B#16#`
    Byte,
    /// `W#16#`, `16#…` ≤ 4 digits, `2#…` ≤ 16 digits
    Word,
    /// `DW#16#`, longer `16#`/`2#`
    Dword,
    /// `B#(1, 2)` (two bytes) or `B#(1, 2, 3, 4)`
    ByteTuple,
    S5Time,
    Time,
    Date,
    TimeOfDay,
    DateAndTime,
    Char,
    String,
    /// `C#…` (three BCD digits)
    Counter,
    /// `P#M 1.0`, `P#DBX 2.0`, `P#2.0` (area pointer)
    Pointer,
    /// `P#DB1.DBX 0.0 BYTE 10`
    AnyPointer,
    /// A timer or counter as a parameter value (`T 5`, `Z 3`).
    TimerNumber,
    CounterNumber,
}

/// awlsim's test operands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extension {
    /// `__STW n` / `__STW VKE`: a status word bit, 0 (/FC) … 8 (BR).
    StatusBit(u8),
    /// `__STW` alone: the whole status word.
    StatusWord,
    Accu(u8),
    AddressRegister(u8),
    /// `__DBR 1` (DB register) / `__DBR 2` (DI register).
    DbRegister(u8),
    Pi,
    E,
    PositiveInfinity,
    NegativeInfinity,
    PositiveNan,
    NegativeNan,
}

/// The STEP 7 operations, by meaning. The mnemonic tables map both sets onto these.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum S7Op {
    // Bit logic
    /// `A AN O ON X XN` (`O` alone is [`S7Op::OrAlone`] once the operand is known).
    Logic(Combination),
    /// `A( AN( O( ON( X( XN(`.
    Bracket(Combination),
    CloseBracket,
    /// `O` without operand
    OrAlone,
    Assign,
    Set,
    Reset,
    /// `SET`
    SetRlo,
    /// `CLR`
    ClearRlo,
    Not,
    Save,
    EdgePositive,
    EdgeNegative,
    // Load and transfer
    Load,
    LoadCoded,
    Transfer,
    LoadStatusWord,
    TransferStatusWord,
    LoadAr1,
    LoadAr2,
    TransferAr1,
    TransferAr2,
    SwapAr,
    AddAr1,
    AddAr2,
    // Timers and counters
    TimerPulse,
    TimerExtendedPulse,
    TimerOnDelay,
    TimerRetentiveOnDelay,
    TimerOffDelay,
    /// `FR`
    Enable,
    CountUp,
    CountDown,
    // Arithmetic
    AddInt,
    SubInt,
    MulInt,
    DivInt,
    AddDint,
    SubDint,
    MulDint,
    DivDint,
    ModDint,
    AddReal,
    SubReal,
    MulReal,
    DivReal,
    /// `+ 5`, `+ L#5`
    AddConstant,
    Abs,
    /// `SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN`
    Real(Function),
    NegInt,
    NegDint,
    NegReal,
    InvInt,
    InvDint,
    // Comparisons
    CmpInt(Cmp),
    CmpDint(Cmp),
    CmpReal(Cmp),
    // Conversions
    IntToDint,
    IntToBcd,
    BcdToInt,
    BcdToDint,
    DintToBcd,
    DintToReal,
    Round,
    RoundUp,
    RoundDown,
    Truncate,
    /// `CAW`: swap the bytes of ACCU 1-L.
    SwapBytesWord,
    /// `CAD`: reverse the bytes of ACCU 1.
    SwapBytesDouble,
    // Shifts and rotates
    ShiftSignedInt,
    ShiftSignedDint,
    ShiftLeftWord,
    ShiftRightWord,
    ShiftLeftDouble,
    ShiftRightDouble,
    RotateLeftDouble,
    RotateRightDouble,
    RotateLeftViaCc1,
    RotateRightViaCc1,
    // Word logic
    AndWord,
    OrWord,
    XorWord,
    AndDouble,
    OrDouble,
    XorDouble,
    // Accumulators
    /// `TAK`
    SwapAccus,
    Push,
    Pop,
    Enter,
    Leave,
    Increment,
    Decrement,
    // Jumps
    JumpAlways,
    JumpIfRlo,
    JumpIfNotRlo,
    /// `JCB`: jump if RLO = 1, saving the RLO in BR.
    JumpIfRloSave,
    JumpIfNotRloSave,
    JumpIfBr,
    JumpIfNotBr,
    JumpIfOverflow,
    JumpIfStoredOverflow,
    JumpIfZero,
    JumpIfNotZero,
    JumpIfPositive,
    JumpIfMinus,
    JumpIfPositiveOrZero,
    JumpIfMinusOrZero,
    JumpIfUnordered,
    Loop,
    /// `JL`: the jump list.
    JumpList,
    // Blocks
    /// `OPN DB n`, `OPN [MW 2]`
    OpenDb,
    /// `OPN DI n`
    OpenInstanceDb,
    /// `CDB` (German `TDB`): exchange the DB and DI registers.
    ExchangeDbRegisters,
    Call,
    CallUnconditional,
    CallConditional,
    BlockEnd,
    BlockEndUnconditional,
    BlockEndConditional,
    // Master control relay
    McrActivate,
    McrDeactivate,
    McrOpen,
    McrClose,
    // Miscellaneous
    Nop,
    /// `BLD n`
    Display,
    // awlsim's test extensions
    Assert(Cmp),
    ResetStatusWord,
    Sleep,
    Feature,
}

impl S7Op {
    /// A shift or rotate that takes its count from its operand or from ACCU 2
    /// (`SSI SSD SLW SRW SLD SRD RLD RRD`).
    pub fn is_shift(self) -> bool {
        matches!(
            self,
            S7Op::ShiftSignedInt
                | S7Op::ShiftSignedDint
                | S7Op::ShiftLeftWord
                | S7Op::ShiftRightWord
                | S7Op::ShiftLeftDouble
                | S7Op::ShiftRightDouble
                | S7Op::RotateLeftDouble
                | S7Op::RotateRightDouble
        )
    }
}
