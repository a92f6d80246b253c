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

/// A library FC: its number, its usual symbolic name and its parameters in the order the VM
/// reads them. What each does is in the language reference, "Library blocks" (`awl help
/// library`).
#[derive(Debug)]
pub struct LibraryFc {
    pub number: u16,
    pub name: &'static str,
    pub params: &'static [Param],
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

const fn fc(number: u16, name: &'static str, params: &'static [Param]) -> LibraryFc {
    LibraryFc {
        number,
        name,
        params,
    }
}

/// The library, by number.
pub const LIBRARY: &[LibraryFc] = &[
    fc(
        1,
        "AD_DT_TM",
        &[input("T", Dt), input("D", Time), output("RET_VAL", Dt)],
    ),
    fc(
        2,
        "CONCAT",
        &[input("IN1", Str), input("IN2", Str), output("RET_VAL", Str)],
    ),
    fc(
        3,
        "D_TOD_DT",
        &[
            input("IN1", ParamType::Date),
            input("IN2", TimeOfDay),
            output("RET_VAL", Dt),
        ],
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
    ),
    fc(5, "DI_STRNG", &[input("I", Dint), output("RET_VAL", Str)]),
    fc(
        6,
        "DT_DATE",
        &[input("IN", Dt), output("RET_VAL", ParamType::Date)],
    ),
    fc(7, "DT_DAY", &[input("IN", Dt), output("RET_VAL", Int)]),
    fc(
        8,
        "DT_TOD",
        &[input("IN", Dt), output("RET_VAL", TimeOfDay)],
    ),
    fc(9, "EQ_DT", DT_COMPARE),
    fc(10, "EQ_STRNG", STRING_COMPARE),
    fc(
        11,
        "FIND",
        &[input("IN1", Str), input("IN2", Str), output("RET_VAL", Int)],
    ),
    fc(12, "GE_DT", DT_COMPARE),
    fc(13, "GE_STRNG", STRING_COMPARE),
    fc(14, "GT_DT", DT_COMPARE),
    fc(15, "GT_STRNG", STRING_COMPARE),
    fc(16, "I_STRNG", &[input("I", Int), output("RET_VAL", Str)]),
    fc(
        17,
        "INSERT",
        &[
            input("IN1", Str),
            input("IN2", Str),
            input("P", Int),
            output("RET_VAL", Str),
        ],
    ),
    fc(18, "LE_DT", DT_COMPARE),
    fc(19, "LE_STRNG", STRING_COMPARE),
    fc(20, "LEFT", SIDE),
    fc(21, "LEN", &[input("S", Str), output("RET_VAL", Int)]),
    fc(
        22,
        "LIMIT",
        &[
            input("MN", Number),
            input("IN", Number),
            input("MX", Number),
            output("RET_VAL", Number),
        ],
    ),
    fc(23, "LT_DT", DT_COMPARE),
    fc(24, "LT_STRNG", STRING_COMPARE),
    fc(25, "MAX", EXTREME),
    fc(
        26,
        "MID",
        &[
            input("IN", Str),
            input("L", Int),
            input("P", Int),
            output("RET_VAL", Str),
        ],
    ),
    fc(27, "MIN", EXTREME),
    fc(28, "NE_DT", DT_COMPARE),
    fc(29, "NE_STRNG", STRING_COMPARE),
    fc(30, "R_STRNG", &[input("IN", Real), output("RET_VAL", Str)]),
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
    ),
    fc(32, "RIGHT", SIDE),
    fc(
        33,
        "S5TI_TIM",
        &[input("IN", S5Time), output("RET_VAL", Time)],
    ),
    fc(
        34,
        "SB_DT_DT",
        &[input("IN1", Dt), input("IN2", Dt), output("RET_VAL", Time)],
    ),
    fc(
        35,
        "SB_DT_TM",
        &[input("IN1", Dt), input("IN2", Time), output("RET_VAL", Dt)],
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
    ),
    fc(37, "STRNG_DI", &[input("S", Str), output("RET_VAL", Dint)]),
    fc(38, "STRNG_I", &[input("S", Str), output("RET_VAL", Int)]),
    fc(39, "STRNG_R", &[input("S", Str), output("RET_VAL", Real)]),
    fc(
        40,
        "TIM_S5TI",
        &[input("IN", Time), output("RET_VAL", S5Time)],
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The language reference's table, which `awl help library` prints, gives each block with
    /// its parameters as they are here.
    #[test]
    fn the_reference_lists_every_block_with_its_interface() {
        let reference = include_str!("../../grammar/README.md");
        let type_name = |ty: ParamType| match ty {
            ParamType::Number | ParamType::Elementary => "ANY",
            other => other.name(),
        };
        let list = |output: bool, fc: &LibraryFc| {
            let params: Vec<String> = fc
                .params
                .iter()
                .filter(|param| param.output == output)
                .map(|param| format!("{} {}", param.name, type_name(param.ty)))
                .collect();
            params.join(", ")
        };
        let rows = reference
            .lines()
            .filter(|line| line.starts_with("| FC ") && !line.starts_with("| FC |"))
            .count();
        assert_eq!(rows, LIBRARY.len());
        for fc in LIBRARY {
            let row = format!(
                "| FC {} | {} | {} | {} | ",
                fc.number,
                fc.name,
                list(false, fc),
                list(true, fc)
            );
            assert!(reference.contains(&row), "{row}");
        }
    }

    #[test]
    fn blocks_are_found_by_number_and_by_name_in_any_case() {
        assert_eq!(by_number(105).map(|fc| fc.name), Some("SCALE"));
        assert_eq!(by_name("unscale").map(|fc| fc.number), Some(106));
        assert_eq!(by_name("Strng_R").map(|fc| fc.number), Some(39));
        assert!(by_number(41).is_none() && by_name("SFC").is_none());
    }
}
