//! The step debugger of `awl debug` on a script of commands. The page keeps the commands given
//! so far (step, next, continue, break …) and runs them all again from the start for each new
//! one: the run is deterministic, so it pauses where the last command leaves it.

use std::cell::RefCell;
use std::rc::Rc;

use serde::Serialize;

use crate::debug::{Debugger, Session};
use crate::state::{self, State};

use super::{Outcome, Place, Pulse, Request, finished};

#[derive(Debug, Clone, Default, Serialize)]
pub struct DebugOutcome {
    /// What the debugger said, the commands echoed after its prompt.
    pub transcript: String,
    /// The operation the CPU is paused before (none once the run has ended).
    pub paused_at: Option<Place>,
    /// The state where it paused.
    pub state: Option<String>,
    /// The run's outcome once it has ended (or could not start).
    pub outcome: Option<Outcome>,
}

/// Runs the request under the debugger with these commands, one per line.
pub fn debug(request: &Request, commands: &str) -> DebugOutcome {
    debug_with(request, commands, None)
}

/// As [`debug`], the pulse telling how far the run has come (a `continue` may run long).
pub fn debug_reporting(request: &Request, commands: &str, pulse: Pulse) -> DebugOutcome {
    debug_with(request, commands, Some(pulse))
}

fn debug_with(request: &Request, commands: &str, pulse: Option<Pulse>) -> DebugOutcome {
    let mut prepared = match request.prepare() {
        Ok(prepared) => prepared,
        Err(outcome) => {
            return DebugOutcome {
                outcome: Some(*outcome),
                ..DebugOutcome::default()
            };
        }
    };
    let session = Rc::new(RefCell::new(Session::recording(
        commands,
        prepared.mnemonics,
    )));
    prepared.cpu.probe = Some(Box::new(Debugger(Rc::clone(&session))));
    if let Some(pulse) = pulse {
        prepared.cpu.set_pulse(pulse);
    }
    let ran = prepared.run(&mut |_| true);
    let mut session = session.borrow_mut();
    if ran.outcome.halted {
        let cpu = &ran.cpu;
        return DebugOutcome {
            transcript: session.take_transcript(),
            paused_at: Place::of_op(cpu, cpu.level.block, cpu.level.pc),
            state: Some(state::render(&State::capture(cpu, None))),
            outcome: None,
        };
    }
    session.after_run(&ran.cpu, ran.outcome.stop.as_ref());
    DebugOutcome {
        transcript: session.take_transcript(),
        paused_at: None,
        state: None,
        outcome: Some(finished(&ran)),
    }
}
