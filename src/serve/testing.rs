//! A CPU with a program compiled from text, for the unit tests of the serve modules.

use std::sync::Arc;

use crate::frontend;
use crate::profile::{self, DEFAULT_PROFILE, DEFAULT_STEP7_PROFILE};
use crate::vm::Cpu;

/// A STEP 7 program on the speed7, else a STEP 5 one on the default S5 CPU.
pub fn cpu(source: &str, step7: bool) -> Cpu {
    let name = if step7 {
        DEFAULT_STEP7_PROFILE
    } else {
        DEFAULT_PROFILE
    };
    let profile = profile::find(name).expect("the default profiles exist");
    let built = frontend::build_text("test.awl", source, profile);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let program = Arc::new(built.compiled.program.clone());
    Cpu::new(program, Arc::new(built.sources.clone()))
}
