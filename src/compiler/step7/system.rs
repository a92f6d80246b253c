//! The interfaces of the system function blocks awl runs, for the multi-instances that embed
//! them ("System Software for S7-300/400 System and Standard Functions", IEC counters).

use crate::ast::Name;
use crate::source::Span;
use crate::step7::ast::{DataType, VarDecl, VarKind};

use super::layout::{Interface, Types};

fn var(name: &str, ty: DataType) -> VarDecl {
    VarDecl {
        name: Name {
            text: name.into(),
            span: Span::default(),
        },
        ty,
        initial: Vec::new(),
        span: Span::default(),
    }
}

/// awlsim's own SFB -1 (`__SFB_NOP`, with the test extensions only): no interface, it sets BR.
pub const AWLSIM_SFB_NOP: u16 = -1i16 as u16;

/// The system FBs awl runs: SFB 0 to 5 and awlsim's SFB -1.
pub const SYSTEM_FBS: [u16; 7] = [0, 1, 2, 3, 4, 5, AWLSIM_SFB_NOP];

/// Why an SFB is not simulated, for [`crate::compiler::CheckError::NotSimulated`].
pub const WHICH: &str = "of the system FBs, awl runs SFB 0 to SFB 5 (CTU, CTD, CTUD, TP, TON, \
                         TOF) and awlsim's SFB -1 (__SFB_NOP)";

/// `SFB n` as written, awlsim's own SFBs with their minus sign.
pub fn label(number: u16) -> String {
    if number == AWLSIM_SFB_NOP {
        format!("SFB {}", number as i16)
    } else {
        format!("SFB {number}")
    }
}

/// Each system FB's instance data, section by section (inputs, outputs, statics), as the
/// System and Standard Functions manual gives them (IEC counters, IEC timers). The counters
/// keep their count inputs of the last call for the edge (CUO, CDO); the timers keep a state
/// byte and the start and last times (STATE, STIME, ATIME), as awlsim lays them out, whose
/// tests read them.
fn sections(number: u16) -> Option<Vec<(VarKind, Vec<VarDecl>)>> {
    use DataType::{Bool, Byte, Int, Time};
    let timer = || {
        vec![
            (VarKind::Input, vec![var("IN", Bool), var("PT", Time)]),
            (VarKind::Output, vec![var("Q", Bool), var("ET", Time)]),
            (
                VarKind::Static,
                vec![var("STATE", Byte), var("STIME", Time), var("ATIME", Time)],
            ),
        ]
    };
    Some(match number {
        // SFB 0 CTU: counts up on a rising edge of CU, to 32767; R resets; Q is CV >= PV.
        0 => vec![
            (
                VarKind::Input,
                vec![var("CU", Bool), var("R", Bool), var("PV", Int)],
            ),
            (VarKind::Output, vec![var("Q", Bool), var("CV", Int)]),
            (VarKind::Static, vec![var("CUO", Bool)]),
        ],
        // SFB 1 CTD: counts down on a rising edge of CD, to -32768; LOAD loads PV; Q is CV <= 0.
        1 => vec![
            (
                VarKind::Input,
                vec![var("CD", Bool), var("LOAD", Bool), var("PV", Int)],
            ),
            (VarKind::Output, vec![var("Q", Bool), var("CV", Int)]),
            (VarKind::Static, vec![var("CDO", Bool)]),
        ],
        // SFB 2 CTUD: both; R before LOAD before the edges; QU is CV >= PV, QD is CV <= 0.
        2 => vec![
            (
                VarKind::Input,
                vec![
                    var("CU", Bool),
                    var("CD", Bool),
                    var("R", Bool),
                    var("LOAD", Bool),
                    var("PV", Int),
                ],
            ),
            (
                VarKind::Output,
                vec![var("QU", Bool), var("QD", Bool), var("CV", Int)],
            ),
            (VarKind::Static, vec![var("CUO", Bool), var("CDO", Bool)]),
        ],
        // SFB 3 TP, SFB 4 TON, SFB 5 TOF.
        3..=5 => timer(),
        AWLSIM_SFB_NOP => Vec::new(),
        _ => return None,
    })
}

/// The system FBs awl runs, for [`Types::instances`].
pub fn instances() -> Vec<(u16, Vec<Vec<VarDecl>>)> {
    SYSTEM_FBS
        .into_iter()
        .filter_map(|number| {
            let sections = sections(number)?;
            Some((number, sections.into_iter().map(|(_, vars)| vars).collect()))
        })
        .collect()
}

/// The interface of system FB `number`, when awl runs it.
pub fn interface(number: u16, types: &Types) -> Option<Interface> {
    let sections = sections(number)?;
    let borrowed: Vec<(VarKind, &[VarDecl])> = sections
        .iter()
        .map(|(kind, vars)| (*kind, vars.as_slice()))
        .collect();
    Some(Interface::build(&borrowed, true, types))
}

/// The label and interface of a called system FB `number`, or why awl does not run it.
pub fn called(
    number: u16,
    types: &Types,
    at: Span,
) -> Result<(String, Interface), crate::compiler::CheckError> {
    let label = label(number);
    match interface(number, types) {
        Some(interface) => Ok((label, interface)),
        None => Err(crate::compiler::CheckError::NotSimulated {
            what: label,
            why: WHICH.into(),
            at,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::step7::layout::Home;

    /// The instance data as the VM reads them (src/vm/s7/system_blocks.rs): each variable's
    /// byte.bit, and the DB's length, which awlsim's tests check with `L DBLG`.
    #[test]
    fn the_instance_data_lie_where_the_vm_reads_them() {
        let types = Types::default();
        let expected: [(u16, Offsets, u32); 6] = [
            (
                0,
                &[
                    ("CU", 0),
                    ("R", 1),
                    ("PV", 16),
                    ("Q", 32),
                    ("CV", 48),
                    ("CUO", 64),
                ],
                10,
            ),
            (
                1,
                &[
                    ("CD", 0),
                    ("LOAD", 1),
                    ("PV", 16),
                    ("Q", 32),
                    ("CV", 48),
                    ("CDO", 64),
                ],
                10,
            ),
            (
                2,
                &[
                    ("CU", 0),
                    ("CD", 1),
                    ("R", 2),
                    ("LOAD", 3),
                    ("PV", 16),
                    ("QU", 32),
                    ("QD", 33),
                    ("CV", 48),
                    ("CUO", 64),
                    ("CDO", 65),
                ],
                10,
            ),
            (3, TIMER, 22),
            (4, TIMER, 22),
            (5, TIMER, 22),
        ];
        for (number, variables, bytes) in expected {
            let interface = interface(number, &types).expect("a system FB");
            for &(name, bits) in variables {
                let home = interface.variables[name].home;
                assert!(
                    matches!(home, Home::Instance(offset) if offset.0 == bits),
                    "SFB {number} {name}: {home:?}"
                );
            }
            assert_eq!(interface.instance_bytes, bytes, "SFB {number}");
        }
        assert_eq!(interface(AWLSIM_SFB_NOP, &types).unwrap().instance_bytes, 0);
        assert!(interface(6, &types).is_none());
    }

    /// Each variable's name and bit offset.
    type Offsets = &'static [(&'static str, u32)];

    const TIMER: Offsets = &[
        ("IN", 0),
        ("PT", 16),
        ("Q", 48),
        ("ET", 64),
        ("STATE", 96),
        ("STIME", 112),
        ("ATIME", 144),
    ];
}
