//! From the compiled S7 operations to the semantics in this module's siblings: which function
//! each operation is, with which registers.

use crate::step7::ast::S7Op;
use crate::vm::LevelState;
use crate::vm::arith::{Arith, WordLogic};
use crate::vm::status::{Combination, Status};
use crate::vm::stop::{StopCause, StopDetail};

use super::accu::{self, Accus};
use super::convert::{self, Rounding};
use super::jump::{self, Condition, Jump};
use super::memory::Fault;
use super::real;
use super::shift::{self, Shift};
use super::{bit_logic, compare, integer, word_logic};

fn accus(count: u8) -> Accus {
    if count >= 4 { Accus::Four } else { Accus::Two }
}

fn bcd_fault() -> Fault {
    (
        StopCause::Bcf,
        StopDetail::Text("BCD conversion error: ACCU 1 holds a digit above 9".into()),
    )
}

/// Two-operand arithmetic ends with ACCU 3 and 4 moving down on four accumulators.
fn after_arithmetic(level: &mut LevelState, count: u8) {
    if accus(count) == Accus::Four {
        accu::leave(&mut level.accu2, &mut level.accu3, level.accu4);
    }
}

/// An operation on the accumulators and the status word alone.
pub fn accumulator(level: &mut LevelState, op: S7Op, count: u8) -> Result<(), Fault> {
    let LevelState {
        accu1,
        accu2,
        accu3,
        accu4,
        status,
        br,
        ..
    } = level;
    match op {
        S7Op::OrAlone => bit_logic::or_alone(status),
        S7Op::SetRlo => bit_logic::set_rlo(status, true),
        S7Op::ClearRlo => bit_logic::set_rlo(status, false),
        S7Op::Not => bit_logic::not(status),
        S7Op::Save => bit_logic::save(*status, br),
        S7Op::LoadStatusWord => {
            *accu2 = *accu1;
            *accu1 = u32::from(status.to_word(*br));
        }
        S7Op::TransferStatusWord => (*status, *br) = Status::from_word(*accu1 as u16),
        S7Op::AddInt | S7Op::SubInt | S7Op::MulInt | S7Op::DivInt => {
            let kind = match op {
                S7Op::AddInt => Arith::Add,
                S7Op::SubInt => Arith::Sub,
                S7Op::MulInt => Arith::Mul,
                _ => Arith::Div,
            };
            integer::int(kind, accu1, *accu2, status);
            after_arithmetic(level, count);
        }
        S7Op::AddDint | S7Op::SubDint | S7Op::MulDint | S7Op::DivDint => {
            let kind = match op {
                S7Op::AddDint => Arith::Add,
                S7Op::SubDint => Arith::Sub,
                S7Op::MulDint => Arith::Mul,
                _ => Arith::Div,
            };
            integer::dint(kind, accu1, *accu2, status);
            after_arithmetic(level, count);
        }
        S7Op::ModDint => {
            integer::modulo(accu1, *accu2, status);
            after_arithmetic(level, count);
        }
        S7Op::AddReal | S7Op::SubReal | S7Op::MulReal | S7Op::DivReal => {
            let kind = match op {
                S7Op::AddReal => Arith::Add,
                S7Op::SubReal => Arith::Sub,
                S7Op::MulReal => Arith::Mul,
                _ => Arith::Div,
            };
            real::arithmetic(kind, accu1, *accu2, status);
            after_arithmetic(level, count);
        }
        S7Op::Abs => real::abs(accu1),
        S7Op::NegReal => real::negate(accu1),
        S7Op::Real(function) => real::function(function, accu1, status),
        S7Op::NegInt => integer::negate_int(accu1, status),
        S7Op::NegDint => integer::negate_dint(accu1, status),
        S7Op::InvInt => integer::invert_int(accu1),
        S7Op::InvDint => integer::invert_dint(accu1),
        S7Op::CmpInt(cmp) => compare::int(cmp, *accu1, *accu2, status),
        S7Op::CmpDint(cmp) => compare::dint(cmp, *accu1, *accu2, status),
        S7Op::CmpReal(cmp) => compare::real(cmp, *accu1, *accu2, status),
        S7Op::IntToDint => convert::int_to_dint(accu1),
        S7Op::IntToBcd => convert::int_to_bcd(accu1, status),
        S7Op::BcdToInt => convert::bcd_to_int(accu1).map_err(|_| bcd_fault())?,
        S7Op::BcdToDint => convert::bcd_to_dint(accu1).map_err(|_| bcd_fault())?,
        S7Op::DintToBcd => convert::dint_to_bcd(accu1, status),
        S7Op::DintToReal => convert::dint_to_real(accu1),
        S7Op::Round => convert::real_to_dint(Rounding::Nearest, accu1, status),
        S7Op::RoundUp => convert::real_to_dint(Rounding::Up, accu1, status),
        S7Op::RoundDown => convert::real_to_dint(Rounding::Down, accu1, status),
        S7Op::Truncate => convert::real_to_dint(Rounding::TowardZero, accu1, status),
        S7Op::SwapBytesWord => convert::swap_bytes_word(accu1),
        S7Op::SwapBytesDouble => convert::swap_bytes_double(accu1),
        S7Op::SwapAccus => accu::tak(accu1, accu2),
        S7Op::Push => accu::push(accus(count), *accu1, accu2, accu3, accu4),
        S7Op::Pop => accu::pop(accus(count), accu1, accu2, accu3, *accu4),
        S7Op::Enter => accu::enter(*accu2, accu3, accu4),
        S7Op::Leave => accu::leave(accu2, accu3, *accu4),
        S7Op::RotateLeftViaCc1 => shift::rotate_left_via_cc1(accu1, status),
        S7Op::RotateRightViaCc1 => shift::rotate_right_via_cc1(accu1, status),
        op if word_logic_of(op).is_some() => {
            let value = *accu2;
            word_logic(level, op, value);
        }
        op if shift_of(op).is_some() => {
            let count = shift::count_from_accu2(*accu2);
            self::shift(level, op, count);
        }
        other => {
            return Err((
                StopCause::Bcf,
                StopDetail::Text(format!("{other:?} is not simulated")),
            ));
        }
    }
    Ok(())
}

fn shift_of(op: S7Op) -> Option<Shift> {
    Some(match op {
        S7Op::ShiftSignedInt => Shift::SignedInt,
        S7Op::ShiftSignedDint => Shift::SignedDint,
        S7Op::ShiftLeftWord => Shift::LeftWord,
        S7Op::ShiftRightWord => Shift::RightWord,
        S7Op::ShiftLeftDouble => Shift::LeftDouble,
        S7Op::ShiftRightDouble => Shift::RightDouble,
        S7Op::RotateLeftDouble => Shift::RotateLeft,
        S7Op::RotateRightDouble => Shift::RotateRight,
        _ => return None,
    })
}

/// A shift or rotate by `count`, or `INC`/`DEC` by it.
pub fn shift(level: &mut LevelState, op: S7Op, count: u8) {
    match op {
        S7Op::Increment => accu::increment(&mut level.accu1, count),
        S7Op::Decrement => accu::decrement(&mut level.accu1, count),
        op => {
            if let Some(kind) = shift_of(op) {
                shift::shift(kind, count, &mut level.accu1, &mut level.status);
            }
        }
    }
}

fn word_logic_of(op: S7Op) -> Option<(WordLogic, bool)> {
    Some(match op {
        S7Op::AndWord => (WordLogic::And, false),
        S7Op::OrWord => (WordLogic::Or, false),
        S7Op::XorWord => (WordLogic::Xor, false),
        S7Op::AndDouble => (WordLogic::And, true),
        S7Op::OrDouble => (WordLogic::Or, true),
        S7Op::XorDouble => (WordLogic::Xor, true),
        _ => return None,
    })
}

/// Word logic of ACCU 1 with `operand` (ACCU 2 or a constant).
pub fn word_logic(level: &mut LevelState, op: S7Op, operand: u32) {
    if let Some((kind, double)) = word_logic_of(op) {
        if double {
            word_logic::double(kind, &mut level.accu1, operand, &mut level.status);
        } else {
            word_logic::word(kind, &mut level.accu1, operand, &mut level.status);
        }
    }
}

pub fn jump_taken(level: &mut LevelState, jump: Jump) -> bool {
    jump::taken(jump, &mut level.status, &mut level.br)
}

pub fn loop_taken(accu1: &mut u32) -> bool {
    jump::loop_taken(accu1)
}

pub fn open_bracket(level: &mut LevelState, combination: Combination, depth: u8) -> bool {
    level
        .brackets
        .open_step7(&mut level.status, level.br, combination, depth)
}

pub fn close_bracket(level: &mut LevelState) -> bool {
    level.brackets.close_step7(&mut level.status, &mut level.br)
}

pub fn condition(level: &LevelState, condition: Condition) -> bool {
    condition.holds(level.status, level.br)
}

/// `A AN O ON X XN` with a bit whose signal state is `value`.
pub fn combine(status: &mut Status, combination: Combination, value: bool) {
    status.scanned_step7(combination, value);
}

/// After `=`, `S`, `R` wrote (or did not write) a bit.
pub fn after_assignment(status: &mut Status) {
    let rlo = status.rlo();
    bit_logic::assigned(status, rlo);
}

/// `FP`/`FN`: the new edge memory bit.
pub fn edge(status: &mut Status, rising: bool, memory: bool) -> bool {
    bit_logic::edge(status, rising, memory)
}

/// `__STWRST`: the whole status word, BR included, is 0.
pub fn reset_status_word(level: &mut LevelState) {
    level.status = Status::default();
    level.br = false;
}

/// The status word with BR as bit 8.
pub fn status_word(level: &LevelState) -> u32 {
    u32::from(level.status.to_word(level.br))
}

/// A passed `__ASSERT` clears /FC (a new logic string starts), as awlsim does.
pub fn after_assert(status: &mut Status) {
    status.set_first_check(false);
}
