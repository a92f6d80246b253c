//! The registers a STEP 7 PG shows beside the accumulators: the status word with BR, AR1,
//! AR2, and the DB and DI registers.

use serde::Serialize;

use crate::vm::Cpu;

/// The registers of a STEP 7 program's running level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Registers {
    /// The status word as `L STW` loads it.
    pub stw: u16,
    pub ar1: u32,
    pub ar2: u32,
    /// The DB register's data block; 0 when none is open.
    pub db: u16,
    /// The DI register's (instance) data block; 0 when none is open.
    pub di: u16,
}

impl Registers {
    pub fn of(cpu: &Cpu) -> Registers {
        let level = &cpu.level;
        Registers {
            stw: level.status.to_word(level.br),
            ar1: level.ar1,
            ar2: level.ar2,
            db: cpu.program.s7.db_number(level.db),
            di: cpu.program.s7.db_number(level.di),
        }
    }
}
