//! The library FCs a STEP 7 program calls without writing them: the IEC functions FC 1 to
//! FC 40 of the S7 Standard Library ("System Software for S7-300/400 System and Standard
//! Functions", IEC functions) and the TI-S7 converting blocks FC 105 SCALE and FC 106 UNSCALE.
//! Their interfaces are here, for the compiler, the VM and `awl help library`; a program's own
//! FC of the same number replaces the library's.

/// A parameter's type, as the library's interfaces declare it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamType {
    Bool,
    Int,
    Dint,
    Real,
    Word,
    Time,
    S5Time,
    Date,
    TimeOfDay,
    String,
    DateAndTime,
    /// An ANY of LIMIT, MAX, MIN: an INT, a DINT or a REAL, the same for all of the call.
    Number,
    /// An ANY of SEL: any elementary type, the same for both inputs and the result.
    Elementary,
}

impl ParamType {
    pub fn name(self) -> &'static str {
        match self {
            ParamType::Bool => "BOOL",
            ParamType::Int => "INT",
            ParamType::Dint => "DINT",
            ParamType::Real => "REAL",
            ParamType::Word => "WORD",
            ParamType::Time => "TIME",
            ParamType::S5Time => "S5TIME",
            ParamType::Date => "DATE",
            ParamType::TimeOfDay => "TIME_OF_DAY",
            ParamType::String => "STRING",
            ParamType::DateAndTime => "DATE_AND_TIME",
            ParamType::Number => "ANY (INT, DINT, REAL)",
            ParamType::Elementary => "ANY (elementary)",
        }
    }

    /// Whether the actual is passed as a whole (a STRING or DATE_AND_TIME variable).
    pub fn is_complex(self) -> bool {
        matches!(self, ParamType::String | ParamType::DateAndTime)
    }
}

/// One parameter: its name, whether the block writes it, and its type.
#[derive(Debug, Clone, Copy)]
pub struct Param {
    pub name: &'static str,
    pub output: bool,
    pub ty: ParamType,
}

const fn input(name: &'static str, ty: ParamType) -> Param {
    Param {
        name,
        output: false,
        ty,
    }
}

const fn output(name: &'static str, ty: ParamType) -> Param {
    Param {
        name,
        output: true,
        ty,
    }
}

/// A library FC: its number, its usual symbolic name, its parameters in the order the VM reads
/// them, and what it does.
#[derive(Debug)]
pub struct LibraryFc {
    pub number: u16,
    pub name: &'static str,
    pub params: &'static [Param],
    pub summary: &'static str,
}

use ParamType::{
    Bool, DateAndTime as Dt, Dint, Elementary, Int, Number, Real, S5Time, String as Str, Time,
    TimeOfDay, Word,
};

const DT_COMPARE: &[Param] = &[input("DT1", Dt), input("DT2", Dt), output("RET_VAL", Bool)];
const STRING_COMPARE: &[Param] = &[input("S1", Str), input("S2", Str), output("RET_VAL", Bool)];
const SIDE: &[Param] = &[input("IN", Str), input("L", Int), output("RET_VAL", Str)];
const EXTREME: &[Param] = &[
    input("IN1", Number),
    input("IN2", Number),
    input("IN3", Number),
    output("RET_VAL", Number),
];

const fn fc(
    number: u16,
    name: &'static str,
    params: &'static [Param],
    summary: &'static str,
) -> LibraryFc {
    LibraryFc {
        number,
        name,
        params,
        summary,
    }
}

/// The library, by number.
pub const LIBRARY: &[LibraryFc] = &[
    fc(
        1,
        "AD_DT_TM",
        &[input("T", Dt), input("D", Time), output("RET_VAL", Dt)],
        "T plus the duration D; limited to 1990-01-01 … 2089-12-31 (BR 0)",
    ),
    fc(
        2,
        "CONCAT",
        &[input("IN1", Str), input("IN2", Str), output("RET_VAL", Str)],
        "IN1 followed by IN2",
    ),
    fc(
        3,
        "D_TOD_DT",
        &[
            input("IN1", ParamType::Date),
            input("IN2", TimeOfDay),
            output("RET_VAL", Dt),
        ],
        "the DATE IN1 at the TIME_OF_DAY IN2",
    ),
    fc(
        4,
        "DELETE",
        &[
            input("IN", Str),
            input("L", Int),
            input("P", Int),
            output("RET_VAL", Str),
        ],
        "IN without the L characters from position P",
    ),
    fc(
        5,
        "DI_STRNG",
        &[input("I", Dint), output("RET_VAL", Str)],
        "the DINT as a sign and digits (at least STRING[11])",
    ),
    fc(
        6,
        "DT_DATE",
        &[input("IN", Dt), output("RET_VAL", ParamType::Date)],
        "the date of a DATE_AND_TIME",
    ),
    fc(
        7,
        "DT_DAY",
        &[input("IN", Dt), output("RET_VAL", Int)],
        "the weekday of a DATE_AND_TIME: 1 Sunday … 7 Saturday",
    ),
    fc(
        8,
        "DT_TOD",
        &[input("IN", Dt), output("RET_VAL", TimeOfDay)],
        "the time of day of a DATE_AND_TIME",
    ),
    fc(9, "EQ_DT", DT_COMPARE, "DT1 = DT2"),
    fc(10, "EQ_STRNG", STRING_COMPARE, "S1 = S2"),
    fc(
        11,
        "FIND",
        &[input("IN1", Str), input("IN2", Str), output("RET_VAL", Int)],
        "the position of IN2 in IN1, 0 when it is not there",
    ),
    fc(12, "GE_DT", DT_COMPARE, "DT1 >= DT2"),
    fc(
        13,
        "GE_STRNG",
        STRING_COMPARE,
        "S1 >= S2 (by character codes)",
    ),
    fc(14, "GT_DT", DT_COMPARE, "DT1 > DT2"),
    fc(15, "GT_STRNG", STRING_COMPARE, "S1 > S2"),
    fc(
        16,
        "I_STRNG",
        &[input("I", Int), output("RET_VAL", Str)],
        "the INT as a sign and digits (at least STRING[6])",
    ),
    fc(
        17,
        "INSERT",
        &[
            input("IN1", Str),
            input("IN2", Str),
            input("P", Int),
            output("RET_VAL", Str),
        ],
        "IN1 with IN2 inserted after its character P",
    ),
    fc(18, "LE_DT", DT_COMPARE, "DT1 <= DT2"),
    fc(19, "LE_STRNG", STRING_COMPARE, "S1 <= S2"),
    fc(20, "LEFT", SIDE, "the first L characters of IN"),
    fc(
        21,
        "LEN",
        &[input("S", Str), output("RET_VAL", Int)],
        "the current length of S",
    ),
    fc(
        22,
        "LIMIT",
        &[
            input("MN", Number),
            input("IN", Number),
            input("MX", Number),
            output("RET_VAL", Number),
        ],
        "IN limited to MN … MX",
    ),
    fc(23, "LT_DT", DT_COMPARE, "DT1 < DT2"),
    fc(24, "LT_STRNG", STRING_COMPARE, "S1 < S2"),
    fc(25, "MAX", EXTREME, "the largest of IN1, IN2, IN3"),
    fc(
        26,
        "MID",
        &[
            input("IN", Str),
            input("L", Int),
            input("P", Int),
            output("RET_VAL", Str),
        ],
        "the L characters of IN from position P",
    ),
    fc(27, "MIN", EXTREME, "the smallest of IN1, IN2, IN3"),
    fc(28, "NE_DT", DT_COMPARE, "DT1 <> DT2"),
    fc(29, "NE_STRNG", STRING_COMPARE, "S1 <> S2"),
    fc(
        30,
        "R_STRNG",
        &[input("IN", Real), output("RET_VAL", Str)],
        "the REAL as ±v.nnnnnnnE±xx (at least STRING[14])",
    ),
    fc(
        31,
        "REPLACE",
        &[
            input("IN1", Str),
            input("IN2", Str),
            input("L", Int),
            input("P", Int),
            output("RET_VAL", Str),
        ],
        "IN1 with its L characters from position P replaced by IN2",
    ),
    fc(32, "RIGHT", SIDE, "the last L characters of IN"),
    fc(
        33,
        "S5TI_TIM",
        &[input("IN", S5Time), output("RET_VAL", Time)],
        "an S5TIME as a TIME",
    ),
    fc(
        34,
        "SB_DT_DT",
        &[input("IN1", Dt), input("IN2", Dt), output("RET_VAL", Time)],
        "IN1 minus IN2 as a TIME; limited to the TIME range (BR 0)",
    ),
    fc(
        35,
        "SB_DT_TM",
        &[input("IN1", Dt), input("IN2", Time), output("RET_VAL", Dt)],
        "IN1 minus the duration IN2; limited to 1990 … 2089 (BR 0)",
    ),
    fc(
        36,
        "SEL",
        &[
            input("G", Bool),
            input("IN0", Elementary),
            input("IN1", Elementary),
            output("RET_VAL", Elementary),
        ],
        "IN0 when G is 0, IN1 when G is 1",
    ),
    fc(
        37,
        "STRNG_DI",
        &[input("S", Str), output("RET_VAL", Dint)],
        "the DINT a sign and digits spell",
    ),
    fc(
        38,
        "STRNG_I",
        &[input("S", Str), output("RET_VAL", Int)],
        "the INT a sign and digits spell",
    ),
    fc(
        39,
        "STRNG_R",
        &[input("S", Str), output("RET_VAL", Real)],
        "the REAL ±v.nnnnnnnE±xx spells",
    ),
    fc(
        40,
        "TIM_S5TI",
        &[input("IN", Time), output("RET_VAL", S5Time)],
        "a TIME as an S5TIME, cut to its time base; at most 9990 s (BR 0)",
    ),
    fc(
        105,
        "SCALE",
        &[
            input("IN", Int),
            input("HI_LIM", Real),
            input("LO_LIM", Real),
            input("BIPOLAR", Bool),
            output("RET_VAL", Word),
            output("OUT", Real),
        ],
        "IN (0 … 27648, bipolar -27648 … 27648) scaled to LO_LIM … HI_LIM; \
         beyond: OUT limited, RET_VAL 16#0008",
    ),
    fc(
        106,
        "UNSCALE",
        &[
            input("IN", Real),
            input("HI_LIM", Real),
            input("LO_LIM", Real),
            input("BIPOLAR", Bool),
            output("RET_VAL", Word),
            output("OUT", Int),
        ],
        "IN (LO_LIM … HI_LIM) scaled to 0 … 27648 (bipolar -27648 … 27648); \
         beyond: OUT limited, RET_VAL 16#0008",
    ),
];

/// Library FC `number`.
pub fn by_number(number: u16) -> Option<&'static LibraryFc> {
    LIBRARY.iter().find(|fc| fc.number == number)
}

/// The library FC with the usual symbolic name `name` (any case).
pub fn by_name(name: &str) -> Option<&'static LibraryFc> {
    LIBRARY.iter().find(|fc| fc.name.eq_ignore_ascii_case(name))
}

impl LibraryFc {
    /// `FC 105 (SCALE)`, for messages.
    pub fn label(&self) -> String {
        format!("FC {} ({})", self.number, self.name)
    }

    /// The call with every parameter, for help.
    pub fn signature(&self) -> String {
        let params: Vec<String> = self
            .params
            .iter()
            .map(|param| {
                let direction = if param.output { "out" } else { "in" };
                format!("{} {direction} {}", param.name, param.ty.name())
            })
            .collect();
        format!(
            "FC {:<3} {:<8} ({})",
            self.number,
            self.name,
            params.join(", ")
        )
    }
}

/// The text of `awl help library`.
pub fn help_text() -> String {
    let mut text = String::from(
        "The library blocks: a STEP 7 program calls them without writing them, by number \
         (`CALL FC 105`) or by their usual name (`CALL \"SCALE\"`), with every parameter.\n\
         The IEC functions FC 1 to FC 40 (\"System Software for S7-300/400 System and Standard \
         Functions\", IEC functions) and the TI-S7 converting blocks FC 105 and FC 106.\n\
         A program's own FC of the same number, or a symbol table entry that gives the name to \
         another block, is called instead (with a note).\n\
         On an error BR (ENO) is 0: a string result longer than its destination is cut to it; \
         a conversion out of range gives the limit; LEFT, RIGHT, MID, DELETE, INSERT and \
         REPLACE give an empty string for a negative length or position; a DATE_AND_TIME that \
         is none leaves the result unchanged.\n\
         STRING and DATE_AND_TIME parameters take variables (a temporary, a DB member) or, for \
         inputs, constants; the ANY parameters of LIMIT, MAX, MIN and SEL take variables or \
         constants of one type for the whole call (an address takes the type of the others).\n\n",
    );
    for fc in LIBRARY {
        text.push_str(&fc.signature());
        text.push_str("\n        ");
        text.push_str(fc.summary);
        text.push('\n');
    }
    text
}

/// One `CALL` of a library FC: the places of its parameters in the order of
/// [`LibraryFc::params`], and the constants of its STRING and DATE_AND_TIME inputs, written to
/// the caller's L stack before it runs.
#[derive(Debug, Clone, PartialEq)]
pub struct LibraryCall {
    pub number: u16,
    pub params: Vec<u16>,
    pub constants: Vec<(u16, Vec<u8>)>,
    /// The type of the ANY parameters of LIMIT, MAX, MIN and SEL.
    pub any_type: AnyType,
}

/// The type the ANY parameters of a call share.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AnyType {
    #[default]
    Int,
    Dint,
    Real,
    /// Any other elementary type of SEL, copied as it is.
    Bits,
}
