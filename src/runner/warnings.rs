//! Warnings about a run's setup: what the program holds that this mode and scenario will never
//! run, and what the run could not finish (its trace). What the CPU alone never runs is in
//! [`crate::analyze::warnings`].

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::compiler::{Op, Program};
use crate::diagnostics;
use crate::mnemonics::BlockKind;
use crate::profile::{Family, Profile};
use crate::source::{SourceSet, Span};
use crate::vm::interrupts::EngineConfig;
use crate::vm::interrupts::sinumerik840c::{NORMAL_MODE, normal_mode_skips};

#[derive(Debug, Error, Diagnostic)]
pub enum RunWarning {
    #[error("the program calls {ob}, which normal mode does not process")]
    #[diagnostic(
        code(awl::run::ob_call_normal_mode),
        severity(Warning),
        help(
            "SINUMERIK 840C PLC manual, 5.3.1: OB 2 and OB 5 \"cannot be called up in normal mode\"; this call runs {ob} as an ordinary block. Use `mode = \"special\"`, or move the code into a PB"
        )
    )]
    ObCallNormalMode {
        ob: String,
        #[label("called here")]
        at: Span,
    },

    #[error("OB {ob} never runs in this run")]
    #[diagnostic(code(awl::run::ob_never_runs), severity(Warning))]
    ObNeverRuns {
        ob: u8,
        #[label("{reason}")]
        at: Span,
        reason: String,
        #[help]
        help: Option<String>,
    },

    #[error("the {what} to `{path}` is incomplete: {reason}")]
    #[diagnostic(
        code(awl::run::trace_incomplete),
        severity(Warning),
        help("the run itself went on; its report and exit code are below")
    )]
    TraceIncomplete {
        /// `trace` or `timeline`.
        what: &'static str,
        path: String,
        reason: String,
    },
}

/// Why OB `ob` can never run on `profile` with `config`, and what would make it run.
fn never_runs(
    ob: u8,
    profile: &Profile,
    config: &EngineConfig,
) -> Option<(String, Option<String>)> {
    // Only interrupt OBs depend on the setup: OB 1 and the start-up OBs always run, and an OB
    // the CPU does not have at all is the program's warning (`awl check` prints it too).
    profile.interrupt_ob(ob)?;
    match profile.family {
        Family::Sinumerik840c if !config.special_mode && normal_mode_skips(ob) => Some((
            NORMAL_MODE.to_string(),
            Some("run it in special mode: `mode = \"special\"` or `--mode special`".into()),
        )),
        Family::S5_95f if ob == 13 && config.ob13.is_none() => Some((
            "OB 13 runs at the interval of the scenario's [ob13] table, and there is none".into(),
            Some("add `[ob13]` with `interval = \"100ms\"` to the scenario".into()),
        )),
        Family::Speed7
            if (ob == 40 || ob == 41) && !config.hw_modules.iter().any(|(_, to)| *to == ob) =>
        {
            Some((
                format!("no [[hw_module]] of the scenario starts OB {ob}"),
                Some(format!(
                    "map a module to it: `[[hw_module]]` with `module = 1` and `ob = {ob}`"
                )),
            ))
        }
        _ => None,
    }
}

/// Whether the program itself calls block `index` (then it runs as an ordinary block).
fn called(program: &Program, index: u16) -> bool {
    program.blocks.iter().any(|block| {
        block
            .code
            .iter()
            .any(|op| matches!(*op, Op::Call { block, .. } if block == index))
    })
}

/// A warning for each OB of the program the run will never start, nor the program call.
pub fn obs_never_run(program: &Program, sources: &SourceSet, config: &EngineConfig) -> Vec<Report> {
    let mut warnings = Vec::new();
    for (index, block) in program.blocks.iter().enumerate() {
        if block.id.kind != BlockKind::Ob || called(program, index as u16) {
            continue;
        }
        // An OB numbered above 255 is no OB a CPU starts: the program's warning.
        let Ok(ob) = u8::try_from(block.id.number) else {
            continue;
        };
        if let Some((reason, help)) = never_runs(ob, program.profile, config) {
            let warning = RunWarning::ObNeverRuns {
                ob,
                at: block.header,
                reason,
                help,
            };
            warnings.push(diagnostics::with_source(sources, block.header, warning));
        }
    }
    warnings
}

/// On the 840C in normal mode, a warning for each program call of OB 2 or OB 5.
pub fn normal_mode_calls(program: &Program, sources: &SourceSet) -> Vec<Report> {
    let mut warnings = Vec::new();
    for block in &program.blocks {
        for (op, span) in block.code.iter().zip(&block.spans) {
            let Op::Call { block: target, .. } = *op else {
                continue;
            };
            let id = program.blocks[usize::from(target)].id;
            let skipped = u8::try_from(id.number).is_ok_and(normal_mode_skips);
            if id.kind == BlockKind::Ob && skipped {
                let warning = RunWarning::ObCallNormalMode {
                    ob: id.to_string(),
                    at: *span,
                };
                warnings.push(diagnostics::with_source(sources, *span, warning));
            }
        }
    }
    warnings
}
