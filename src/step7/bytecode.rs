//! The STEP 7 operations the VM runs out of line, as one `Copy` op inside [`Op::S7`], and the
//! tables they index: the places (addresses, parameters, pointers) and the FB calls.
//!
//! STEP 7 operations that mean the same as a STEP 5 one (`A I 0.0`, `L MW 10`, `JU`, `JC`,
//! timers, counters, `+I` on two accumulators …) compile to the shared ops and run inline; what
//! only STEP 7 has — the L stack, byte-addressed data blocks, parameters passed as pointers,
//! address registers, REAL arithmetic — is here.
//!
//! [`Op::S7`]: crate::compiler::Op::S7

use super::ast::{AccessWidth, Cmp, DbRegister, Extension, S7Area, S7Op};
use crate::rules::jump::Jump;
use crate::rules::status::Combination;

/// A STEP 7 operation with its operand decoded: small and `Copy`, so [`crate::compiler::Op`]
/// stays at 8 bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum S7Code {
    /// A bit, load, transfer, timer or counter operation on a place of [`S7Tables::places`].
    Mem {
        op: MemOp,
        place: u16,
    },
    /// An operation on the accumulators and the status word alone (`+R`, `ITD`, `TAK`, `NOT` …).
    Accu(S7Op),
    /// A shift or rotate by a count written with it (`SLW 3`); without one the count is in
    /// ACCU 2 and the op is an [`S7Code::Accu`].
    Shift {
        op: S7Op,
        count: u8,
    },
    /// Word logic with a constant (`AW W#16#00FF`): the constant's index in
    /// [`S7Tables::constants`].
    WordConstant {
        op: S7Op,
        constant: u16,
    },
    /// `+ L#100000` and other 32-bit additions (16-bit ones are [`crate::compiler::Op::AddConstant`]).
    AddDouble {
        constant: u16,
    },
    /// A conditional jump STEP 5 does not have, to op `target` of the block.
    Jump {
        jump: Jump,
        target: u16,
    },
    /// `LOOP label`
    Loop {
        target: u16,
    },
    /// `JL label`: the next `entries` ops are the list's `JU`s; past them, `target`.
    JumpList {
        entries: u16,
        target: u16,
    },
    /// `A(` … `XN(` that STEP 5 does not have: how the bracket's result will combine.
    Bracket(Combination),
    /// `)` closing any bracket (S7 brackets keep BR).
    CloseBracket,
    /// `A ==0`, `O OV`, `AN BR`: a status condition as a bit operand.
    Condition {
        combination: Combination,
        condition: Condition,
    },
    /// `OPN DB n` / `OPN DI n`: the DB's slot (see [`S7Tables::db_numbers`]).
    OpenDb {
        instance: bool,
        slot: u16,
    },
    /// `OPN DB [MW 2]`, `OPN #db_param`: the number from a place.
    OpenDbFrom {
        instance: bool,
        place: u16,
    },
    ExchangeDbRegisters,
    /// `L DBNO` …
    LoadDbRegister(DbRegister),
    /// `LAR1`/`LAR2` from ACCU 1 (`ar` 1 or 2).
    LoadAr(u8),
    /// `LAR1 P#…`: from a constant.
    LoadArConstant {
        ar: u8,
        constant: u16,
    },
    /// `LAR1 AR2`
    LoadAr1FromAr2,
    /// `TAR1`/`TAR2` to ACCU 1.
    TransferAr(u8),
    /// `TAR1 AR2`
    TransferAr1ToAr2,
    /// `CAR` (German `TAR`): exchange AR1 and AR2.
    SwapAr,
    /// `+AR1`/`+AR2`: add ACCU 1-L (a byte.bit offset), or a `P#` constant.
    AddAr {
        ar: u8,
        constant: Option<u16>,
    },
    /// `CALL FB n, DB m`, before the call: copy the inputs into the instance DB, save the DB
    /// and DI registers and AR2, open the instance DB. Indexes [`S7Tables::fb_calls`].
    FbEnter {
        call: u16,
    },
    /// After the call: copy the outputs back, restore the registers.
    FbLeave {
        call: u16,
    },
    /// `CALL FC n (…)`, before the call: the actuals STEP 7 passes as copies on the caller's L
    /// stack copied there, AR2 saved. Indexes [`S7Tables::fc_calls`].
    FcEnter {
        call: u16,
    },
    /// After the FC: AR2 back, the copies of the outputs and in/outs copied to their actuals.
    FcLeave {
        call: u16,
    },
    /// `L P##param` in an FC: the pointer to the actual its caller passed.
    LoadParamPointer {
        param: u8,
    },
    /// `CALL SFC n` (with its parameter places in [`S7Tables::sfc_calls`]).
    Sfc {
        call: u16,
    },
    /// `CALL FC n (…)` of a library FC the program does not define (see
    /// [`crate::step7::library`]), with its parameters in [`S7Tables::library_calls`].
    Library {
        call: u16,
    },
    /// `__ASSERT== a, b`: the two places' indexes are `left` and `left + 1`.
    Assert {
        cmp: Cmp,
        left: u16,
    },
    /// The master control relay (see [`crate::vm::s7::mcr`]).
    Mcr(McrCode),
    /// `__STWRST`
    ResetStatusWord,
    /// `__SLEEP ms`: simulated time passes.
    Sleep {
        ms: u16,
    },
    /// `__FEATURE target[, value]`
    Feature {
        target: u8,
        value: Option<u8>,
    },
}

/// An [`S7Code::Mcr`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum McrCode {
    /// `MCRA`, and `MCRD` or the start of a block with `MCRA` (false).
    Activate(bool),
    /// `MCR(`
    Open,
    /// `)MCR`
    Close,
    /// Around a call in a block with `MCRA`: its dependency saved and cleared (true), then
    /// back (false).
    Call(bool),
}

/// What an [`S7Code::Mem`] does with its place.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemOp {
    /// `A AN O ON X XN`: how the bit combines with the RLO.
    Scan(Combination),
    Assign,
    Set,
    Reset,
    EdgePositive,
    EdgeNegative,
    Load,
    /// `LC T`/`LC C`: the BCD value.
    LoadCoded,
    Transfer,
    /// `=`, `S`, `R` on a bit and `T` in a block with `MCRA`: under the master control relay.
    McrAssign,
    McrSet,
    McrReset,
    McrTransfer,
    TimerPulse,
    TimerExtendedPulse,
    TimerOnDelay,
    TimerRetentiveOnDelay,
    TimerOffDelay,
    Enable,
    CountUp,
    CountDown,
    /// `S C n`: preset a counter from ACCU 1.
    SetCounter,
    /// `R T n`/`R C n`.
    ResetTimerCounter,
    /// `LAR1 MD 10`: load AR1/AR2 from the place.
    LoadAr1,
    LoadAr2,
    TransferAr1,
    TransferAr2,
    /// `UC FC [MW 4]`, a `BLOCK_FC` parameter: not in part 1.
    CallFrom,
}

pub use super::ast::Condition;

/// Where an S7 operation reads or writes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Place {
    pub target: Target,
    pub width: AccessWidth,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Target {
    /// PII, PIQ, flags at their offset in the image memory.
    Image {
        byte: u16,
        bit: u8,
    },
    /// Peripheral inputs (`PIW`) or outputs (`PQW`).
    Peripheral {
        output: bool,
        byte: u16,
    },
    Local {
        byte: u32,
        bit: u8,
    },
    PreviousLocal {
        byte: u32,
        bit: u8,
    },
    /// The open DB (DB register) or instance DB (DI register).
    Data {
        instance: bool,
        byte: u32,
        bit: u8,
    },
    /// A variable of the running FB's interface: in the instance DB (DI register) at AR2's
    /// offset plus `byte`.`bit`, as STEP 7 addresses it (`DIX [AR2, P#byte.bit]`), so a
    /// multi-instance finds its data inside the caller's instance DB.
    Instance {
        byte: u32,
        bit: u8,
    },
    /// `DB5.DBW 4`: opens DB 5 (the DB register) and accesses it; `slot` is DB 5's slot (see
    /// [`S7Tables::db_numbers`]).
    NumberedData {
        db: u16,
        slot: u16,
        byte: u32,
        bit: u8,
    },
    /// FC parameter `param` (a pointer to the caller's actual), `offset` bytes/bits into it
    /// for a member of a structure.
    Parameter {
        param: u8,
        byte: u32,
        bit: u8,
    },
    /// FC parameter `param` of a complex type (ARRAY, STRUCT, UDT, STRING, DATE_AND_TIME):
    /// its actual is the 6-byte DB pointer the caller wrote to its L stack, `byte`.`bit` into
    /// what that points to.
    Through {
        param: u8,
        byte: u32,
        bit: u8,
    },
    /// An FB's in/out of a complex type: the 6-byte DB pointer to the actual lies in the
    /// instance data at byte `pointer` (after AR2's offset), `byte`.`bit` into what it points
    /// to.
    InstanceThrough {
        pointer: u32,
        byte: u32,
        bit: u8,
    },
    /// Memory-indirect: the pointer is read from `pointer` (a place index): a double word
    /// area-internal pointer for bits and bytes, a word for timers, counters and DB numbers.
    MemoryIndirect {
        area: S7Area,
        pointer: u16,
    },
    /// Register-indirect: AR1/AR2 plus `offset` (a pointer value). `area` is `None` when the
    /// area comes from the register (area-crossing).
    RegisterIndirect {
        area: Option<S7Area>,
        ar: u8,
        offset: u32,
    },
    Timer(u16),
    Counter(u16),
    Constant(u32),
    /// A timer or counter number passed as a parameter (`T 12`, in an FB's instance data).
    TimerFrom {
        place: u16,
    },
    CounterFrom {
        place: u16,
    },
    /// awlsim's test operands.
    Extension(Extension),
    DbRegister(DbRegister),
    /// A status condition's value (an operand of `__ASSERT`).
    Condition(Condition),
}

/// One `CALL FB n, DB m (…)`, or `CALL #instance (…)` of a multi-instance.
#[derive(Debug, Clone, PartialEq)]
pub struct FbCall {
    pub instance_db: u16,
    /// The instance DB's slot (see [`S7Tables::db_numbers`]).
    pub instance_slot: u16,
    /// A multi-instance: its data lie in the caller's instance DB (which stays open), this
    /// many bits after the caller's AR2 offset; AR2 points there during the call.
    pub multi_instance: Option<u32>,
    /// A system FB awl runs itself (the call has no block to enter).
    pub system: Option<u16>,
    /// (actual place, byte/bit offset in the instance DB, width) of each input and in/out.
    pub inputs: Vec<ParamCopy>,
    /// (actual place, offset, width) of each output and in/out.
    pub outputs: Vec<ParamCopy>,
    /// The inputs of a complex type, copied whole into the instance data.
    pub blocks_in: Vec<BlockCopy>,
    /// The outputs of a complex type, copied whole back to their actuals.
    pub blocks_out: Vec<BlockCopy>,
    /// The in/outs of a complex type: (actual place, byte in the instance data), where the
    /// call writes the 6-byte DB pointer to the actual.
    pub pointers: Vec<(u16, u32)>,
}

impl FbCall {
    /// A call of an FB (`system`: of a system FB awl runs itself) on its instance data, with no
    /// parameter copies yet.
    pub fn on(
        instance_db: u16,
        instance_slot: u16,
        multi_instance: Option<u32>,
        system: Option<u16>,
    ) -> Self {
        FbCall {
            instance_db,
            instance_slot,
            multi_instance,
            system,
            inputs: Vec::new(),
            outputs: Vec::new(),
            blocks_in: Vec::new(),
            blocks_out: Vec::new(),
            pointers: Vec::new(),
        }
    }
}

/// A parameter of a complex type (ARRAY, STRUCT, UDT, STRING, DATE_AND_TIME) copied byte by
/// byte between its actual and the instance data, `byte` bytes into them.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockCopy {
    pub source: CopySource,
    pub byte: u32,
    pub size: u32,
}

/// Where a [`BlockCopy`] or a complex FC parameter takes its bytes from.
#[derive(Debug, Clone, PartialEq)]
pub enum CopySource {
    /// The actual's place (its first byte).
    Place(u16),
    /// A constant (`'text'` for a STRING, `DT#…`) laid out as the parameter's type.
    Bytes(Vec<u8>),
}

/// One `CALL FC n (…)`: the actuals passed as copies on the caller's L stack — constants, and
/// the caller's own instance data, which STEP 7 does not pass by pointer (the FC may change
/// DI and AR2) — as (actual place, copy place) pairs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FcCall {
    /// Copied before the call (inputs, in/outs).
    pub inputs: Vec<(u16, u16)>,
    /// Copied back after it (outputs, in/outs).
    pub outputs: Vec<(u16, u16)>,
    /// Constants of parameters of a complex type, written to the caller's L stack: (place,
    /// bytes).
    pub constants: Vec<(u16, Vec<u8>)>,
    /// Parameters of a complex type: (actual place, place of the 6-byte DB pointer to it on the
    /// caller's L stack), written before the call ("Programming with STEP 7", parameter
    /// passing: an FC receives a pointer to a complex actual).
    pub pointers: Vec<(u16, u16)>,
}

/// One parameter copied between an actual and the instance DB.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParamCopy {
    pub actual: u16,
    pub byte: u32,
    pub bit: u8,
    pub width: AccessWidth,
}

/// awlsim's `SFC -1` (`__SFC_NOP`), with the test extensions: does nothing but set BR.
pub const AWLSIM_SFC_NOP: u16 = -1i16 as u16;

/// awlsim's `SFC -2` (`__REBOOT`), with the test extensions: awlsim's system functions
/// `SFC -1` to `SFC -4` are numbered as 16-bit two's complements, 65535 down to 65532.
pub const AWLSIM_SFC_REBOOT: u16 = -2i16 as u16;

/// awlsim's `SFC -3` (`__SHUTDOWN`), with the test extensions: ends the simulation, as
/// `CALL SFC 46` ends a test.
pub const AWLSIM_SFC_SHUTDOWN: u16 = -3i16 as u16;

/// awlsim's `SFC -4` (`__CLKRST`), with the test extensions: restarts the clock memory and
/// the time SFC 64 counts, as if the CPU had just started.
pub const AWLSIM_SFC_CLOCK_RESET: u16 = -4i16 as u16;

/// SFC 0 `SET_CLK`: sets the CPU's clock (date and time of day).
pub const SET_CLK: u16 = 0;

/// SFC 1 `READ_CLK`: reads the CPU's clock.
pub const READ_CLK: u16 = 1;

/// SFC 47 `WAIT`: waits WT microseconds.
pub const WAIT: u16 = 47;

/// SFC 64 `TIME_TCK`: the system time, milliseconds since the CPU started.
pub const TIME_TCK: u16 = 64;

/// SFC 20 `BLKMOV`: copies the area of one ANY into that of another.
pub const BLKMOV: u16 = 20;

/// SFC 21 `FILL`: fills the area of one ANY with copies of another's.
pub const FILL: u16 = 21;

/// One `CALL SFC n (…)`.
#[derive(Debug, Clone, PartialEq)]
pub struct SfcCall {
    pub number: u16,
    /// The parameters' places, by name as written.
    pub params: Vec<(String, u16)>,
    /// The ANY parameters (SFC 20, SFC 21), by name in upper case.
    pub anys: Vec<(String, AnyActual)>,
}

/// The actual of an ANY parameter of a system function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AnyActual {
    /// Known when compiling: its 10 bytes.
    Bytes([u8; 10]),
    /// An ANY variable the program filled: its 10 bytes from this place on.
    At(Place),
}

/// The tables S7 ops index, shared by the whole program.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct S7Tables {
    pub places: Vec<Place>,
    pub constants: Vec<u32>,
    pub fb_calls: Vec<FbCall>,
    pub fc_calls: Vec<FcCall>,
    pub sfc_calls: Vec<SfcCall>,
    pub library_calls: Vec<super::library::LibraryCall>,
    /// The data blocks' initial bytes, by DB number.
    pub data_blocks: Vec<(u16, Vec<u8>)>,
    /// The data blocks by slot: the numbers of the data blocks the program defines or names
    /// (`OPN DB 7`, `DB7.DBW 0`, an instance DB). STEP 7 numbers DBs up to 65535, so the VM
    /// keeps them densely: the DB and DI registers hold slots, and an access indexes the data
    /// with no lookup. Slot 0 is number 0 (no data block); the defined ones follow in order
    /// of number (`defined_dbs` of them, searched when a number is known only at run time,
    /// `OPN DB [MW 10]`); then the named ones the program does not define, so their STOP
    /// names them.
    pub db_numbers: Vec<u16>,
    /// How many slots after slot 0 hold defined data blocks.
    pub defined_dbs: usize,
    /// The data blocks with declarations, by number: their values as the state shows them.
    pub declared_dbs: Vec<(u16, Vec<DeclaredValue>)>,
    /// Each logic block's parameters and temporaries by name, by block index (the debugger's).
    pub block_locals: Vec<(u16, BlockLocals)>,
    /// The awlsim test instructions may run (`awl conformance`, `--extended`).
    pub extensions: bool,
    /// The program is a STEP 7 program (it has an L stack and byte-addressed DBs).
    pub step7: bool,
}

/// How a declared value's bytes read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Bool,
    Byte,
    Char,
    Word,
    Int,
    S5Time,
    Date,
    Dword,
    Dint,
    Real,
    Time,
    TimeOfDay,
    /// `STRING[n]`: maximum and actual length, then the characters.
    String(u8),
    /// What the data view shows as raw bytes: DATE_AND_TIME, POINTER, ANY, an in/out's
    /// pointer.
    Bytes(u8),
}

/// One elementary value of a data block's declaration and where it lies.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeclaredValue {
    /// `setpoint`, `motor.speed`, `table[2]`.
    pub name: String,
    pub byte: u32,
    pub bit: u8,
    pub format: Format,
}

/// A logic block's declared parameters and temporaries, kept for the debugger's Locals.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct BlockLocals {
    /// An FC's parameters in the order of its call's list.
    pub parameters: Vec<DeclaredParameter>,
    /// The temporaries, each at its offset from the block's local data.
    pub temporaries: Vec<DeclaredValue>,
}

/// An FC parameter: its name, its place in the call's list, and how its value reads (`None`
/// for an array, a structure or a UDT, which the call passes as a pointer).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DeclaredParameter {
    pub name: String,
    pub place: u8,
    pub format: Option<Format>,
}

impl S7Tables {
    /// No STEP 7 program: the VM needs no L stack.
    pub fn is_empty(&self) -> bool {
        !self.step7
    }

    pub fn place(&mut self, place: Place) -> u16 {
        self.places.push(place);
        (self.places.len() - 1) as u16
    }

    /// The number of the data block in `slot` (0 for none).
    pub fn db_number(&self, slot: u16) -> u16 {
        self.db_numbers.get(usize::from(slot)).copied().unwrap_or(0)
    }

    /// The slot of data block `number` when the program defines it (0, no data block, is in
    /// slot 0).
    pub fn db_slot(&self, number: u16) -> Option<u16> {
        if number == 0 {
            return Some(0);
        }
        let defined = self.db_numbers.get(1..=self.defined_dbs)?;
        let index = defined.binary_search(&number).ok()?;
        Some(index as u16 + 1)
    }

    pub fn constant(&mut self, value: u32) -> u16 {
        self.constants.push(value);
        (self.constants.len() - 1) as u16
    }
}

/// The execution time of an S7 op, from the profile's classes.
pub fn cost(code: S7Code, t: &crate::profile::Timings) -> u32 {
    match code {
        S7Code::Mem { .. } => t.load_word,
        S7Code::Accu(_) | S7Code::Shift { .. } | S7Code::AddDouble { .. } => t.accumulator,
        S7Code::WordConstant { .. } => t.word_logic,
        S7Code::Jump { .. } | S7Code::Loop { .. } | S7Code::JumpList { .. } => t.jump,
        S7Code::Bracket(_) | S7Code::CloseBracket | S7Code::Condition { .. } => t.bit_image,
        S7Code::OpenDb { .. } | S7Code::OpenDbFrom { .. } | S7Code::ExchangeDbRegisters => {
            t.open_db
        }
        S7Code::FbEnter { .. } | S7Code::FbLeave { .. } => t.load_word,
        // Part of the call's own time (the copies are the CALL's parameter passing).
        S7Code::FcEnter { .. } | S7Code::FcLeave { .. } => 0,
        S7Code::Sfc { .. } | S7Code::Library { .. } => t.block_call + t.block_end,
        _ => t.other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_data_block_number_finds_its_slot_only_when_defined() {
        // DB 0 is no data block; DB 7, 300 and 65535 are defined; DB 9 is only named.
        let tables = S7Tables {
            db_numbers: vec![0, 7, 300, 65535, 9],
            defined_dbs: 3,
            ..S7Tables::default()
        };
        assert_eq!(tables.db_slot(0), Some(0));
        assert_eq!(tables.db_slot(300), Some(2));
        assert_eq!(tables.db_slot(65535), Some(3));
        assert_eq!(tables.db_slot(9), None, "named, not defined");
        assert_eq!(tables.db_slot(8), None);
        assert_eq!(tables.db_number(4), 9);
        assert_eq!(tables.db_number(17), 0, "no such slot");
        assert_eq!(
            S7Tables::default().db_slot(5),
            None,
            "no data blocks at all"
        );
    }
}
