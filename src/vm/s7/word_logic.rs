//! `AW OW XOW` (ACCU 1-L) and `AD OD XOD` (ACCU 1) with ACCU 2 or a constant: CC1 = the result
//! is not zero, CC0 = 0, OV = 0; OS is kept ("Statement List (STL) for S7-300 and S7-400
//! Programming", the chapter on word logic instructions).

use crate::vm::arith::WordLogic;
use crate::vm::status::Status;

#[inline(always)]
fn combine(op: WordLogic, a: u32, b: u32) -> u32 {
    match op {
        WordLogic::And => a & b,
        WordLogic::Or => a | b,
        WordLogic::Xor => a ^ b,
    }
}

#[inline(always)]
fn set_codes(status: &mut Status, result: u32) {
    status.set_condition(result != 0, false);
    status.set_ov(false);
}

/// `AW OW XOW`: ACCU 1-L with the low word of `operand` (ACCU 2 or the constant); ACCU 1-H is
/// kept.
#[inline]
pub fn word(op: WordLogic, accu1: &mut u32, operand: u32, status: &mut Status) {
    let result = combine(op, *accu1, operand) & 0xFFFF;
    set_codes(status, result);
    *accu1 = *accu1 & 0xFFFF_0000 | result;
}

/// `AD OD XOD`: ACCU 1 with `operand` (ACCU 2 or the constant).
#[inline]
pub fn double(op: WordLogic, accu1: &mut u32, operand: u32, status: &mut Status) {
    let result = combine(op, *accu1, operand);
    set_codes(status, result);
    *accu1 = result;
}

#[cfg(test)]
mod tests {
    use super::*;
    use WordLogic::{And, Or, Xor};

    /// CC1, CC0, OV, OS.
    fn flags(status: Status) -> [u8; 4] {
        [status.cc1(), status.cc0(), status.ov(), status.os()].map(u8::from)
    }

    fn run(
        f: fn(WordLogic, &mut u32, u32, &mut Status),
        op: WordLogic,
        accu1: u32,
        operand: u32,
    ) -> (u32, [u8; 4]) {
        let mut status = Status::default();
        status.set_condition(false, true);
        status.set_overflow(true);
        let mut accu = accu1;
        f(op, &mut accu, operand, &mut status);
        (accu, flags(status))
    }

    /// Each case: the operation, ACCU 1, the operand, ACCU 1 and CC1 CC0 OV OS after. The word
    /// operations keep ACCU 1-H, and their word result alone decides CC1.
    type Case = (WordLogic, u32, u32, u32, [u8; 4]);

    #[test]
    fn word_and_double_operations() {
        let words: &[Case] = &[
            (And, 0xFFFF_0F0F, 0xABCD_F0F0, 0xFFFF_0000, [0, 0, 0, 1]),
            (Or, 0x1234_0F00, 0xFFFF_00F0, 0x1234_0FF0, [1, 0, 0, 1]),
            (Xor, 0x0000_FFFF, 0x0000_FFFF, 0, [0, 0, 0, 1]),
            (Xor, 0x0000_FF00, 0x0000_0FF0, 0x0000_F0F0, [1, 0, 0, 1]),
            (And, 0xFFFF_0001, 0xFFFF_0002, 0xFFFF_0000, [0, 0, 0, 1]),
        ];
        let doubles: &[Case] = &[
            (And, 0xFFFF_0001, 0x0001_0001, 0x0001_0001, [1, 0, 0, 1]),
            (And, 0xFFFF_0000, 0x0000_FFFF, 0, [0, 0, 0, 1]),
            (Or, 0x8000_0000, 0x0000_0001, 0x8000_0001, [1, 0, 0, 1]),
            (Xor, 0xF0F0_F0F0, 0xFFFF_0000, 0x0F0F_F0F0, [1, 0, 0, 1]),
        ];
        type Width = fn(WordLogic, &mut u32, u32, &mut Status);
        let widths: [(Width, &[Case]); 2] = [(word, words), (double, doubles)];
        for (width, cases) in widths {
            for &(op, accu1, operand, after, status) in cases {
                let case = format!("{op:?} {accu1:#010X} {operand:#010X}");
                assert_eq!(run(width, op, accu1, operand), (after, status), "{case}");
            }
        }
    }
}
