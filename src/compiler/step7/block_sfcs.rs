//! The calls of SFC 20 BLKMOV and SFC 21 FILL ("System Software for S7-300/400 System and
//! Standard Functions", copy and block functions): every parameter given once, the two ANY
//! parameters as the pointers the VM reads, RET_VAL an INT to write to.

use crate::compiler::CheckError;
use crate::source::Span;
use crate::step7::ast::{AccessWidth, CallSpec, DataType};
use crate::step7::bytecode::{BLKMOV, SfcCall, Target};

use super::operand::Scope;
use super::pointers::{Formal, View};

/// The parameters of SFC `number` (20 or 21) in their order: the source ANY, RET_VAL, the
/// destination ANY.
pub fn parameters(number: u16) -> [&'static str; 3] {
    if number == BLKMOV {
        ["SRCBLK", "RET_VAL", "DSTBLK"]
    } else {
        ["BVAL", "RET_VAL", "BLK"]
    }
}

fn call_name(number: u16) -> String {
    let name = if number == BLKMOV { "BLKMOV" } else { "FILL" };
    format!("SFC {number} ({name})")
}

impl super::Compiler<'_> {
    /// `CALL SFC 20 (…)` / `CALL SFC 21 (…)`: the index of the call in
    /// [`crate::step7::bytecode::S7Tables::sfc_calls`], `None` when it has errors.
    pub(super) fn block_sfc(
        &mut self,
        number: u16,
        call: &CallSpec,
        at: Span,
        scope: &Scope<'_>,
    ) -> Option<u16> {
        let names = parameters(number);
        let fb = call_name(number);
        let mut ok =
            super::interrupt_sfcs::known_and_once(&fb, &call.params, &names, &mut self.errors);
        let mut params = Vec::new();
        let mut anys = Vec::new();
        let mut missing = Vec::new();
        for name in names {
            let Some(param) = call
                .params
                .iter()
                .find(|param| param.name.text.eq_ignore_ascii_case(name))
            else {
                missing.push(name);
                continue;
            };
            if name == "RET_VAL" {
                match self.place(&param.actual, param.actual_span, scope) {
                    Ok(place)
                        if place.width == AccessWidth::Word
                            && !matches!(place.target, Target::Constant(_)) =>
                    {
                        params.push((name.to_string(), self.tables.place(place)));
                    }
                    Ok(_) => {
                        self.errors.push(CheckError::ParamMismatch {
                            name: name.to_string(),
                            fb: fb.clone(),
                            at: param.actual_span,
                            expected: "an INT to write to (a word: MW 10, #ret)".into(),
                        });
                        ok = false;
                    }
                    Err(error) => {
                        self.errors.push(error);
                        ok = false;
                    }
                }
                continue;
            }
            let formal = Formal {
                ty: &DataType::Any,
                name,
                callee: &fb,
                view: View::SystemFunction,
            };
            match self.pointer_actual(&param.actual, formal, param.actual_span, scope) {
                Ok(actual) => anys.push((name.to_string(), actual.any())),
                Err(error) => {
                    self.errors.push(error);
                    ok = false;
                }
            }
        }
        if !missing.is_empty() {
            let error = super::interrupt_sfcs::missing_some(fb, names.len(), &missing, at);
            self.errors.push(error);
            ok = false;
        }
        if !ok {
            return None;
        }
        self.tables.sfc_calls.push(SfcCall {
            number,
            params,
            anys,
        });
        Some((self.tables.sfc_calls.len() - 1) as u16)
    }
}
