//! Where the CPU would do nothing, seen from the program and the CPU alone (no scenario): no
//! OB 1, an OB the CPU never starts, a block no OB reaches. `awl check` prints all three;
//! `awl run` the first two, beside the warnings about its own setup.

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::compiler::Program;
use crate::diagnostics;
use crate::mnemonics::BlockKind;
use crate::profile::Profile;
use crate::source::{SourceSet, Span};

use super::calls;

#[derive(Debug, Error, Diagnostic)]
pub enum ProgramWarning {
    #[error("the program has no OB 1: no block runs cyclically")]
    #[diagnostic(
        code(awl::program::no_ob1),
        severity(Warning),
        help("OB 1 is the cyclic program; add it, or load the file that holds it")
    )]
    NoOb1,

    #[error("the {cpu} has no OB {ob}: it never starts it")]
    #[diagnostic(
        code(awl::program::ob_not_on_cpu),
        severity(Warning),
        help(
            "`awl cpus` lists the OBs of the {cpu}; choose another with `--cpu`, or call it from the program (JU OB {ob}) to run it as an ordinary block"
        )
    )]
    ObNotOnCpu {
        ob: u16,
        cpu: &'static str,
        #[label("not an OB the {cpu} starts")]
        at: Span,
    },

    #[error("never called: {blocks}")]
    #[diagnostic(
        code(awl::program::never_called),
        severity(Warning),
        help(
            "no OB the CPU starts reaches them through block calls; `awl analyze` shows the rest"
        )
    )]
    NeverCalled { blocks: String },
}

/// Every warning about the program on its CPU, in the order `awl check` prints them.
pub fn program_warnings(program: &Program, sources: &SourceSet) -> Vec<Report> {
    let mut warnings: Vec<Report> = no_ob1(program).into_iter().collect();
    warnings.extend(obs_not_on_cpu(program, sources));
    warnings.extend(never_called(program));
    warnings
}

/// The warning for a program without OB 1.
pub fn no_ob1(program: &Program) -> Option<Report> {
    program
        .ob(1)
        .is_none()
        .then(|| Report::new(ProgramWarning::NoOb1))
}

/// Whether the CPU starts OB `ob`: the cyclic OB, a start-up OB or an interrupt OB it has.
fn starts(profile: &Profile, ob: u16) -> bool {
    // The OBs a CPU starts have numbers that fit a byte.
    u8::try_from(ob).is_ok_and(|ob| {
        ob == 1 || profile.startup_obs.contains(&ob) || profile.interrupt_ob(ob).is_some()
    })
}

/// A warning for each OB of the program its CPU does not have and the program does not call.
pub fn obs_not_on_cpu(program: &Program, sources: &SourceSet) -> Vec<Report> {
    let profile = program.profile;
    let called: Vec<u16> = (0..program.blocks.len() as u16)
        .flat_map(|block| calls::callees(program, block))
        .collect();
    program
        .blocks
        .iter()
        .enumerate()
        .filter(|(index, block)| {
            block.id.kind == BlockKind::Ob
                && !starts(profile, block.id.number)
                && !called.contains(&(*index as u16))
        })
        .map(|(_, block)| {
            let warning = ProgramWarning::ObNotOnCpu {
                ob: block.id.number,
                cpu: profile.name,
                at: block.header,
            };
            diagnostics::with_source(sources, block.header, warning)
        })
        .collect()
}

/// One warning naming the logic blocks no OB the CPU starts reaches, if there are any.
pub fn never_called(program: &Program) -> Option<Report> {
    let profile = program.profile;
    let roots: Vec<u16> = program
        .blocks
        .iter()
        .enumerate()
        .filter(|(_, block)| block.id.kind == BlockKind::Ob && starts(profile, block.id.number))
        .map(|(index, _)| index as u16)
        .collect();
    let reached = calls::reachable(program, &roots);
    let unreached: Vec<String> = program
        .blocks
        .iter()
        .zip(&reached)
        .filter(|(block, reached)| !**reached && block.id.kind != BlockKind::Ob)
        .map(|(block, _)| block.id.to_string())
        .collect();
    (!unreached.is_empty()).then(|| {
        Report::new(ProgramWarning::NeverCalled {
            blocks: unreached.join(", "),
        })
    })
}
