//! Accumulator operations: fixed-point arithmetic and comparison on the low words of ACCU 1 and
//! ACCU 2, word logic, shifts and complements, with the condition codes CC1/CC0 and OV.
//!
//! The status rules and their sources:
//! - fixed-point arithmetic sets CC1/CC0 and OV (OS stays set); after an overflow of `+F`/`-F`
//!   the codes are those of the 16-bit result, after one of `X F`/`:F` those of the true result
//!   (STEP 7 status-word table for integer math, which the VIPA SPEED7 operation list follows;
//!   the S5 manuals at hand do not spell the overflow case out);
//! - `:F` puts the quotient in ACCU 1-L and the remainder in ACCU 1-H (CPU 928B programming
//!   guide, table 3-7); division by 0 leaves ACCU 1 and sets CC1 CC0 = 1 1 and OV;
//! - word logic and shifts set CC1/CC0 and leave the overflow bit alone (S5-101U manual,
//!   5.2.5).

use super::status::Status;

/// The four basic operations, of every number format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Arith {
    Add,
    Sub,
    Mul,
    Div,
}

/// The six comparisons (STEP 7 writes them `==I`, `<>R` …).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Comparison {
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
}

impl Comparison {
    /// Whether `a` (ACCU 2's value) compares so with `b` (ACCU 1's).
    #[inline(always)]
    pub fn holds<T: PartialOrd>(self, a: &T, b: &T) -> bool {
        match self {
            Comparison::Eq => a == b,
            Comparison::Ne => a != b,
            Comparison::Gt => a > b,
            Comparison::Ge => a >= b,
            Comparison::Lt => a < b,
            Comparison::Le => a <= b,
        }
    }
}

/// `AW OW XOW`, and STEP 5's `UW OW XOW`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WordLogic {
    And,
    Or,
    Xor,
}

fn low(accu: u32) -> i16 {
    accu as u16 as i16
}

fn with_low(accu: u32, value: u16) -> u32 {
    accu & 0xFFFF_0000 | u32::from(value)
}

/// `+F -F X F :F`: ACCU 1 := ACCU 2 op ACCU 1 (low words). An overflow keeps the wrapped
/// result and sets OV and OS.
#[inline(always)]
pub fn arithmetic(op: Arith, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (i32::from(low(accu2)), i32::from(low(*accu1)));
    let exact = match op {
        Arith::Add => a + b,
        Arith::Sub => a - b,
        Arith::Mul | Arith::Div => return multiply_divide(op, accu1, a, b, status),
    };
    let wrapped = exact as i16;
    status.set_result(wrapped, i32::from(wrapped) != exact);
    *accu1 = with_low(*accu1, wrapped as u16);
}

/// `X F` and `:F`: after an overflow the condition codes are those of the true result; `:F`
/// leaves the remainder in ACCU 1-H.
#[inline(always)]
fn multiply_divide(op: Arith, accu1: &mut u32, a: i32, b: i32, status: &mut Status) {
    if op == Arith::Div && b == 0 {
        status.set_condition(true, true);
        status.set_overflow(true);
        return;
    }
    let exact = if op == Arith::Mul { a * b } else { a / b };
    let wrapped = exact as i16;
    let overflow = i32::from(wrapped) != exact;
    let codes = if overflow {
        exact.signum() as i16
    } else {
        wrapped
    };
    status.set_result(codes, overflow);
    *accu1 = if op == Arith::Div {
        u32::from((a % b) as u16) << 16 | u32::from(wrapped as u16)
    } else {
        with_low(*accu1, wrapped as u16)
    };
}

/// `!=F ><F >F >=F <F <=F`: ACCU 2 compared with ACCU 1 gives the RLO.
pub fn compare(op: Comparison, accu1: u32, accu2: u32, status: &mut Status) {
    compare_values(op, low(accu2), low(accu1), status);
}

/// ACCU 2's value `a` compared with ACCU 1's `b`: the RLO, and CC 1/CC 0 for `a > b`/`a < b`.
pub fn compare_values<T: PartialOrd>(op: Comparison, a: T, b: T, status: &mut Status) {
    let result = op.holds(&a, &b);
    status.set_condition(a > b, a < b);
    status.load(result);
}

/// `AW OW XOW`: CC1 = result not zero, CC0 = 0; OV unchanged.
pub fn word_logic(op: WordLogic, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (*accu1 as u16, accu2 as u16);
    let result = match op {
        WordLogic::And => a & b,
        WordLogic::Or => a | b,
        WordLogic::Xor => a ^ b,
    };
    status.set_condition(result != 0, false);
    *accu1 = with_low(*accu1, result);
}

/// `SLW n` / `SRW n`: CC1 = the last bit shifted out, CC0 = 0; OV unchanged.
pub fn shift(left: bool, n: u8, accu1: &mut u32, status: &mut Status) {
    let word = *accu1 as u16;
    if n == 0 {
        return;
    }
    let n = u32::from(n);
    let (result, last_out) = if left {
        (
            word.checked_shl(n).unwrap_or(0),
            (word >> (16 - n)) & 1 == 1,
        )
    } else {
        (word.checked_shr(n).unwrap_or(0), (word >> (n - 1)) & 1 == 1)
    };
    status.set_condition(last_out, false);
    *accu1 = with_low(*accu1, result);
}

pub fn ones_complement(accu1: &mut u32) {
    *accu1 = with_low(*accu1, !(*accu1 as u16));
}

/// `CSW`: two's complement; −32768 overflows.
pub fn twos_complement(accu1: &mut u32, status: &mut Status) {
    let value = low(*accu1);
    let (result, overflow) = value.overflowing_neg();
    status.set_overflow(overflow);
    status.set_cc_from(result);
    *accu1 = with_low(*accu1, result as u16);
}

/// `I n` / `D n`: the low byte of ACCU 1, modulo 256.
pub fn increment(accu1: &mut u32, delta: i16) {
    let byte = (*accu1 as u8).wrapping_add(delta as u8);
    *accu1 = *accu1 & 0xFFFF_FF00 | u32::from(byte);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arith(op: Arith, a: i16, b: i16) -> (i16, Status) {
        let mut accu1 = b as u16 as u32;
        let mut status = Status::default();
        arithmetic(op, &mut accu1, a as u16 as u32, &mut status);
        (accu1 as u16 as i16, status)
    }

    #[test]
    fn add_sets_condition_codes_and_overflow() {
        let (sum, status) = arith(Arith::Add, 30000, 10000);
        assert!(status.ov() && status.os());
        assert_eq!(sum, (40000i32 as i16));
        assert!(status.cc0(), "the wrapped result is negative");
        let (sum, status) = arith(Arith::Add, -5, 5);
        assert_eq!(sum, 0);
        assert!(!status.cc1() && !status.cc0() && !status.ov());
    }

    #[test]
    fn sub_mul_div() {
        assert_eq!(arith(Arith::Sub, 5, 8).0, -3);
        assert_eq!(arith(Arith::Mul, -300, 100).0, -30000);
        assert!(arith(Arith::Mul, 300, 300).1.ov());
        assert_eq!(arith(Arith::Div, 7, 2).0, 3);
        assert_eq!(arith(Arith::Div, -7, 2).0, -3);
        assert!(arith(Arith::Div, -32768, -1).1.ov());
    }

    #[test]
    fn division_by_zero_keeps_accu_and_flags() {
        let (result, status) = arith(Arith::Div, 100, 0);
        assert_eq!(result, 0);
        assert!(status.cc1() && status.cc0() && status.ov());
    }

    #[test]
    fn compare_sets_rlo_and_codes() {
        let mut status = Status::default();
        compare(Comparison::Gt, 3, 5, &mut status);
        assert!(status.rlo() && status.cc1() && !status.cc0());
        compare(Comparison::Le, 3, 5, &mut status);
        assert!(!status.rlo());
    }

    /// CC1 says whether the result is non-zero; CC0 is 0 and the overflow bit stays as it was
    /// (S5-101U manual, 5.2.5).
    #[test]
    fn word_logic_codes_say_zero_or_not() {
        let mut status = Status::default();
        status.set_result(0, true);
        let mut accu = 0xFFFF_0F0F;
        word_logic(WordLogic::And, &mut accu, 0xF0F0, &mut status);
        assert_eq!(accu, 0xFFFF_0000, "ACCU 1-H is kept");
        assert!(!status.cc1() && !status.cc0() && status.ov());
        word_logic(WordLogic::Or, &mut accu, 0x0100, &mut status);
        assert_eq!(accu, 0xFFFF_0100);
        assert!(status.cc1() && !status.cc0() && status.ov());
    }

    #[test]
    fn shifts_and_complements() {
        let mut status = Status::default();
        let mut accu = 0x8001;
        shift(true, 1, &mut accu, &mut status);
        assert_eq!(accu, 0x0002);
        assert!(status.cc1());
        shift(false, 2, &mut accu, &mut status);
        assert_eq!(accu, 0);
        assert!(status.cc1());
        let mut accu = 0x00FF;
        ones_complement(&mut accu);
        assert_eq!(accu, 0xFF00);
        let mut accu = 0x8000;
        twos_complement(&mut accu, &mut status);
        assert!(status.ov());
        let mut accu = 0x12FF;
        increment(&mut accu, 1);
        assert_eq!(accu, 0x1200);
    }
}
