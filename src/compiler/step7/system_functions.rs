//! The parameters of the clock SFCs awl runs, checked against their interfaces ("System
//! Software for S7-300/400 System and Standard Functions"): SFC 0 SET_CLK (PDT: the
//! DATE_AND_TIME to set, RET_VAL: INT), SFC 1 READ_CLK (RET_VAL: INT, CDT: the DATE_AND_TIME
//! read), SFC 47 WAIT (WT: INT, microseconds), SFC 64 TIME_TCK (RET_VAL: TIME) and awlsim's
//! SFC -3 (`__SHUTDOWN`, SHUTDOWN_TYPE: INT) and SFC -4 (`__CLKRST`, none). Every parameter must be given, each once.

use crate::compiler::CheckError;
use crate::source::Span;
use crate::step7::ast::{AccessWidth, CallParam, DataType, S7Operand};
use crate::step7::bytecode::{
    AWLSIM_SFC_CLOCK_RESET, AWLSIM_SFC_SHUTDOWN, READ_CLK, SET_CLK, TIME_TCK, WAIT,
};

use super::layout::Home;
use super::operand::Scope;

#[derive(Clone, Copy)]
enum Kind {
    Int,
    Time,
    DateAndTime,
}

impl Kind {
    fn expected(self) -> &'static str {
        match self {
            Kind::Int => "an INT: a word such as MW 4, or a constant",
            Kind::Time => "a TIME: a double word such as MD 4",
            Kind::DateAndTime => {
                "a DATE_AND_TIME variable such as #now (VAR_TEMP) or DB1.now (a global DB)"
            }
        }
    }
}

/// An SFC's name for messages, its parameters and a call to show in help.
type SfcInterface = (&'static str, &'static [(&'static str, Kind)], &'static str);

fn interface(number: u16) -> Option<SfcInterface> {
    Some(match number {
        SET_CLK => (
            "SFC 0 (SET_CLK)",
            &[("PDT", Kind::DateAndTime), ("RET_VAL", Kind::Int)],
            "CALL SFC 0 (PDT := #now, RET_VAL := MW 4)",
        ),
        READ_CLK => (
            "SFC 1 (READ_CLK)",
            &[("RET_VAL", Kind::Int), ("CDT", Kind::DateAndTime)],
            "CALL SFC 1 (RET_VAL := MW 4, CDT := #now)",
        ),
        WAIT => (
            "SFC 47 (WAIT)",
            &[("WT", Kind::Int)],
            "CALL SFC 47 (WT := 100)",
        ),
        TIME_TCK => (
            "SFC 64",
            &[("RET_VAL", Kind::Time)],
            "CALL SFC 64 (RET_VAL := MD 4)",
        ),
        AWLSIM_SFC_SHUTDOWN => (
            "SFC -3",
            &[("SHUTDOWN_TYPE", Kind::Int)],
            "CALL SFC -3 (SHUTDOWN_TYPE := 1)",
        ),
        AWLSIM_SFC_CLOCK_RESET => ("SFC -4", &[], "CALL SFC -4"),
        _ => return None,
    })
}

/// A call of system function `number` with `given` parameters (all different, all declared):
/// an error unless that is all of them.
pub fn given_all(number: u16, given: usize, span: Span) -> Result<(), CheckError> {
    match interface(number) {
        Some((name, interface, example)) if given < interface.len() => {
            Err(CheckError::ParamCount {
                fb: name.into(),
                expected: interface.len(),
                found: given,
                at: span,
                help: Some(format!("write `{example}`")),
            })
        }
        _ => Ok(()),
    }
}

impl super::Compiler<'_> {
    /// The parameters of a call of system function `number`, which are given with `widths`.
    pub(super) fn system_function_params(
        &self,
        number: u16,
        params: &[CallParam],
        widths: &[AccessWidth],
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let Some((name, interface, _)) = interface(number) else {
            return Ok(());
        };
        for (index, (param, width)) in params.iter().zip(widths).enumerate() {
            let upper = param.name.text.to_ascii_uppercase();
            let declared = interface.iter().find(|(declared, _)| *declared == upper);
            let twice = params[..index]
                .iter()
                .any(|other| other.name.text.eq_ignore_ascii_case(&upper));
            let Some(&(_, kind)) = declared.filter(|_| !twice) else {
                let names: Vec<&str> = interface.iter().map(|(name, _)| *name).collect();
                return Err(CheckError::UnknownParam {
                    name: param.name.text.clone(),
                    fb: name.into(),
                    at: param.name.span,
                    help: Some(match (twice, names.as_slice()) {
                        (true, _) => format!("`{upper}` is given twice"),
                        (false, []) => format!("{name} has no parameters"),
                        (false, _) => format!("{name} has {}", names.join(", ")),
                    }),
                });
            };
            let fits = match kind {
                Kind::Int => *width == AccessWidth::Word,
                Kind::Time => *width == AccessWidth::Double,
                Kind::DateAndTime => self.is_date_and_time(&param.actual, param.actual_span, scope),
            };
            if !fits {
                return Err(CheckError::ParamMismatch {
                    name: param.name.text.clone(),
                    fb: name.into(),
                    at: param.actual_span,
                    expected: kind.expected().into(),
                });
            }
        }
        given_all(number, params.len(), span)
    }

    /// Whether `actual` is a variable declared DATE_AND_TIME: one of the block's interface or
    /// a member of a global DB.
    fn is_date_and_time(&self, actual: &S7Operand, at: Span, scope: &Scope<'_>) -> bool {
        let ty = match actual {
            // An FC's DATE_AND_TIME parameter is a pointer to its actual.
            S7Operand::Local(path) => self
                .resolve_local(path, at, scope)
                .ok()
                .filter(|(variable, ..)| !matches!(variable.home, Home::Parameter(..))),
            S7Operand::DbMember { db, path } => self.db_layouts.get(db).and_then(|layout| {
                let scope = Scope {
                    interface: layout,
                    block: format!("DB {db}"),
                };
                self.resolve_local(path, at, &scope).ok()
            }),
            _ => None,
        };
        matches!(ty, Some((_, DataType::DateAndTime, _)))
    }
}
