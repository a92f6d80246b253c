//! The STEP 7 operations the execution loop hands off ([`crate::step7::bytecode::S7Code`]):
//! [`memory`] finds where an operand is, [`exec`] runs the operations.

mod bridge;
pub mod exec;
pub mod memory;

use crate::compiler::Program;

/// The STEP 7 data blocks at the start, indexed by number.
pub fn initial_data(program: &Program) -> Vec<Option<Vec<u8>>> {
    let count = program
        .s7
        .data_blocks
        .iter()
        .map(|(number, _)| usize::from(*number) + 1)
        .max()
        .unwrap_or(0);
    let mut data = vec![None; count];
    for (number, bytes) in &program.s7.data_blocks {
        data[usize::from(*number)] = Some(bytes.clone());
    }
    data
}
