//! The status-word and accumulator semantics of the STEP 7 operations, as the executor calls
//! them.

use crate::step7::ast::S7Op;
use crate::step7::bytecode::{Condition, MemOp};
use crate::vm::LevelState;
use crate::vm::status::Status;

use super::memory::Fault;

pub fn accumulator(_level: &mut LevelState, op: S7Op, _accus: u8) -> Result<(), Fault> {
    Err((
        crate::vm::stop::StopCause::Bcf,
        crate::vm::stop::StopDetail::Text(format!("{op:?} is not simulated yet")),
    ))
}

pub fn shift(_level: &mut LevelState, _op: S7Op, _count: Option<u8>) {}

pub fn word_logic(_level: &mut LevelState, _op: S7Op, _value: u32) {}

pub fn jump_taken(status: &mut Status, op: S7Op) -> bool {
    let _ = (status, op);
    false
}

pub fn open_bracket(_level: &mut LevelState, _op: S7Op, _depth: u8) -> bool {
    false
}

pub fn close_bracket(level: &mut LevelState) -> bool {
    level.brackets.close(&mut level.status)
}

pub fn condition(_status: Status, _condition: Condition) -> bool {
    false
}

pub fn combine(status: &mut Status, op: MemOp, value: bool) {
    use crate::compiler::bytecode::Logic;
    let logic = match op {
        MemOp::AndNot => Logic::AndNot,
        MemOp::Or => Logic::Or,
        MemOp::OrNot => Logic::OrNot,
        _ => Logic::And,
    };
    status.scanned(logic, value);
}

pub fn after_assignment(status: &mut Status) {
    status.end_string();
}

pub fn edge(status: &mut Status, rising: bool, memory: bool) -> (bool, bool) {
    let rlo = status.rlo();
    let result = if rising {
        rlo && !memory
    } else {
        !rlo && memory
    };
    status.load(result);
    (result, rlo)
}

pub fn reset_status_word(level: &mut LevelState) {
    level.status = Status::default();
}

pub fn status_word(level: &LevelState) -> u32 {
    let status = level.status;
    u32::from(status.first_check())
        | u32::from(status.rlo()) << 1
        | u32::from(status.sta()) << 2
        | u32::from(status.or_bit()) << 3
        | u32::from(status.os()) << 4
        | u32::from(status.ov()) << 5
        | u32::from(status.cc0()) << 6
        | u32::from(status.cc1()) << 7
}

pub fn after_assert(_status: &mut Status) {}
