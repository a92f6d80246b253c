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

/// Each system FB's instance data, section by section (inputs, outputs, statics).
fn sections(number: u16) -> Option<Vec<(VarKind, Vec<VarDecl>)>> {
    Some(match number {
        // SFB 0 CTU: counts up on a rising edge of CU, to 32767; R resets; Q is CV >= PV.
        // CUO keeps CU for the edge.
        0 => vec![
            (
                VarKind::Input,
                vec![
                    var("CU", DataType::Bool),
                    var("R", DataType::Bool),
                    var("PV", DataType::Int),
                ],
            ),
            (
                VarKind::Output,
                vec![var("Q", DataType::Bool), var("CV", DataType::Int)],
            ),
            (VarKind::Static, vec![var("CUO", DataType::Bool)]),
        ],
        _ => return None,
    })
}

/// The system FBs awl runs, for [`Types::instances`].
pub fn instances() -> Vec<(u16, Vec<Vec<VarDecl>>)> {
    [0].into_iter()
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
