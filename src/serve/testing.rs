//! A CPU with a program compiled from text, for the unit tests of the serve modules.

use std::sync::Arc;

use crate::dialect::Dialect;
use crate::frontend;
use crate::profile;
use crate::vm::Cpu;

/// A STEP 7 program, else a STEP 5 one, on its dialect's default CPU.
pub fn cpu(source: &str, step7: bool) -> Cpu {
    let profile = profile::default_for(if step7 {
        Dialect::Step7
    } else {
        Dialect::Step5
    });
    let built = frontend::build_text("test.awl", source, profile);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let program = Arc::new(built.compiled.program.clone());
    Cpu::new(program, Arc::new(built.sources.clone()))
}
