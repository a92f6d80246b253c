//! The parameters of SFC 39 DIS_IRT, SFC 40 EN_IRT, SFC 41 DIS_AIRT and SFC 42 EN_AIRT
//! ("System Software for S7-300/400 System and Standard Functions", 12.2 to 12.5): every one
//! given once, each with an operand of its type; laid out in the order the VM reads them
//! ([`parameters`], which the VM's [`crate::vm::interrupts::control`] reads too).

use crate::compiler::CheckError;
use crate::source::Span;
use crate::step7::ast::{AccessWidth, CallParam, S7Operand};
use crate::step7::bytecode::{Place, Target};

/// SFC 39 DIS_IRT.
pub const DIS_IRT: u16 = 39;
/// SFC 40 EN_IRT.
pub const EN_IRT: u16 = 40;
/// SFC 41 DIS_AIRT.
pub const DIS_AIRT: u16 = 41;
/// SFC 42 EN_AIRT.
pub const EN_AIRT: u16 = 42;

/// The parameters of one call, in the order the compiler lays them out: MODE, OB_NR, RET_VAL
/// for SFC 39 and SFC 40, RET_VAL alone for SFC 41 and SFC 42.
pub fn parameters(number: u16) -> &'static [(&'static str, AccessWidth)] {
    match number {
        DIS_IRT | EN_IRT => &[
            ("MODE", AccessWidth::Byte),
            ("OB_NR", AccessWidth::Word),
            ("RET_VAL", AccessWidth::Word),
        ],
        DIS_AIRT | EN_AIRT => &[("RET_VAL", AccessWidth::Word)],
        _ => &[],
    }
}

/// The SFC's name, as STEP 7's library names it.
pub fn name(number: u16) -> &'static str {
    match number {
        DIS_IRT => "DIS_IRT",
        EN_IRT => "EN_IRT",
        DIS_AIRT => "DIS_AIRT",
        _ => "EN_AIRT",
    }
}

/// Whether `number` is one of these SFCs.
pub fn is_interrupt_sfc(number: u16) -> bool {
    (DIS_IRT..=EN_AIRT).contains(&number)
}

/// The call's name in diagnostics: `SFC 41 (DIS_AIRT)`.
pub fn call_name(number: u16) -> String {
    format!("SFC {number} ({})", name(number))
}

/// Each parameter of an SFC call must be one of the `declared` and be given once: an error for
/// each that is not. Whether all were.
pub(super) fn known_and_once(
    fb: &str,
    params: &[CallParam],
    declared: &[&str],
    errors: &mut Vec<CheckError>,
) -> bool {
    let mut ok = true;
    for (index, param) in params.iter().enumerate() {
        let name = param.name.text.to_ascii_uppercase();
        let known = declared.contains(&name.as_str());
        let first = !params[..index]
            .iter()
            .any(|other| other.name.text.eq_ignore_ascii_case(&name));
        if !known || !first {
            errors.push(CheckError::UnknownParam {
                name: param.name.text.clone(),
                fb: fb.to_string(),
                at: param.name.span,
                help: Some(if known {
                    format!("`{name}` is given twice")
                } else {
                    format!("{fb} has {}", declared.join(", "))
                }),
            });
            ok = false;
        }
    }
    ok
}

/// A call of an SFC that leaves out some of its `declared` parameters: an SFC needs them all.
pub(super) fn missing_some(fb: String, declared: usize, missing: &[&str], at: Span) -> CheckError {
    CheckError::ParamCount {
        fb,
        expected: declared,
        found: declared - missing.len(),
        at,
        help: Some(format!(
            "an SFC needs every parameter; missing: {}",
            missing.join(", ")
        )),
    }
}

/// A call without its parameters (`UC SFC 41`, `CALL SFC 41`).
pub fn missing_all(number: u16, at: Span) -> CheckError {
    CheckError::ParamCount {
        fb: call_name(number),
        expected: parameters(number).len(),
        found: 0,
        at,
        help: Some(format!(
            "write the call with its parameters: `CALL SFC {number} ({})`",
            parameters(number)
                .iter()
                .map(|(name, _)| format!("{name} := …"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// The call's parameters in the VM's order, each resolved by `place`; every error found is
/// pushed to `errors`, and then there is no list.
pub fn ordered(
    number: u16,
    params: &[CallParam],
    at: Span,
    errors: &mut Vec<CheckError>,
    mut place: impl FnMut(&CallParam) -> Result<Place, CheckError>,
) -> Option<Vec<(String, Place)>> {
    let declared_params = parameters(number);
    let fb = call_name(number);
    let names: Vec<&str> = declared_params.iter().map(|(name, _)| *name).collect();
    let mut ok = known_and_once(&fb, params, &names, errors);
    let mut list = Vec::with_capacity(declared_params.len());
    let mut missing = Vec::new();
    for &(name, width) in declared_params {
        let Some(param) = params
            .iter()
            .find(|param| param.name.text.eq_ignore_ascii_case(name))
        else {
            missing.push(name);
            continue;
        };
        let resolved = match place(param) {
            Ok(resolved) => resolved,
            Err(error) => {
                errors.push(error);
                ok = false;
                continue;
            }
        };
        let output = name == "RET_VAL";
        let fits = match (resolved.target, &param.actual) {
            (Target::Constant(_), _) if output => false,
            // A BYTE takes a constant up to 255; an INT any the parser accepted.
            (Target::Constant(value), S7Operand::Constant(_)) => {
                width == AccessWidth::Word || value <= u32::from(u8::MAX)
            }
            _ => resolved.width == width,
        };
        if !fits {
            errors.push(CheckError::ParamMismatch {
                name: name.to_string(),
                fb: fb.clone(),
                at: param.actual_span,
                expected: match (name, output) {
                    ("MODE", _) => "a BYTE (a constant such as B#16#1, or a byte: MB 10)".into(),
                    (_, true) => "an INT to write to (a word: MW 10, #ret)".into(),
                    _ => "an INT (a constant such as 40, or a word: MW 10)".into(),
                },
            });
            ok = false;
            continue;
        }
        list.push((name.to_string(), resolved));
    }
    if !missing.is_empty() {
        errors.push(missing_some(
            fb.clone(),
            declared_params.len(),
            &missing,
            at,
        ));
        ok = false;
    }
    ok.then_some(list)
}
