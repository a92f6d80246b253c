//! `+I -I *I /I`, `+D -D *D /D MOD`, `NEGI NEGD INVI INVD` and `+ constant`: ACCU 1 := ACCU 2 op
//! ACCU 1, with CC1/CC0 and OV/OS ("Statement List (STL) for S7-300 and S7-400 Programming",
//! the chapters on integer math and on accumulator operations).
//!
//! - `+I -I NEGI` (and `+D -D NEGD`): the result wraps to 16 (32) bits and CC1/CC0 give the
//!   sign of the wrapped result (1 0 positive, 0 1 negative, 0 0 zero), so −32768 − 1 gives
//!   +32767 with CC1 CC0 = 1 0 and OV; ACCU 1-H is kept by the 16-bit operations.
//! - `*I`: the full 32-bit product goes to ACCU 1; `*I` and `*D` set CC1/CC0 by the sign of the
//!   true product and OV when it leaves the 16 (32) bit range.
//! - `/I`: quotient in ACCU 1-L, remainder (with the dividend's sign) in ACCU 1-H; `/D` the
//!   quotient, `MOD` the remainder; CC1/CC0 by the true quotient (remainder), so −32768 / −1
//!   gives 0x8000 with CC1 CC0 = 1 0 and OV.
//! - Division by zero leaves ACCU 1 and sets CC1 CC0 = 1 1, OV and OS.
//!
//! On a CPU with four accumulators ACCU 3 and 4 move down after these (see
//! [`super::accu::leave`]); the functions here see only ACCU 1 and 2.

use crate::vm::arith::Arith;
use crate::vm::status::Status;

#[inline(always)]
fn low(accu: u32) -> i32 {
    i32::from(accu as u16 as i16)
}

#[inline(always)]
fn with_low(accu: u32, value: i32) -> u32 {
    accu & 0xFFFF_0000 | u32::from(value as u16)
}

/// CC1/CC0 from the sign of `value`, and OV (with OS when set).
#[inline(always)]
fn set_codes(status: &mut Status, value: i64, overflow: bool) {
    status.set_condition(value > 0, value < 0);
    status.set_overflow(overflow);
}

#[inline(always)]
fn division_by_zero(status: &mut Status) {
    status.set_condition(true, true);
    status.set_overflow(true);
}

/// `+I -I *I /I` on ACCU 2-L and ACCU 1-L.
#[inline]
pub fn int(op: Arith, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (low(accu2), low(*accu1));
    match op {
        Arith::Add | Arith::Sub => {
            let exact = if op == Arith::Add { a + b } else { a - b };
            let wrapped = exact as i16;
            set_codes(status, i64::from(wrapped), i32::from(wrapped) != exact);
            *accu1 = with_low(*accu1, exact);
        }
        Arith::Mul => {
            let exact = a * b;
            set_codes(status, i64::from(exact), i32::from(exact as i16) != exact);
            *accu1 = exact as u32;
        }
        Arith::Div => {
            if b == 0 {
                return division_by_zero(status);
            }
            let (quotient, remainder) = (a / b, a % b);
            set_codes(
                status,
                i64::from(quotient),
                i32::from(quotient as i16) != quotient,
            );
            *accu1 = u32::from(remainder as u16) << 16 | u32::from(quotient as u16);
        }
    }
}

/// `+D -D *D /D` on ACCU 2 and ACCU 1.
#[inline]
pub fn dint(op: Arith, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (i64::from(accu2 as i32), i64::from(*accu1 as i32));
    let exact = match op {
        Arith::Add => a + b,
        Arith::Sub => a - b,
        Arith::Mul => a * b,
        Arith::Div if b == 0 => return division_by_zero(status),
        Arith::Div => a / b,
    };
    let wrapped = exact as i32;
    let overflow = i64::from(wrapped) != exact;
    let codes = match op {
        Arith::Add | Arith::Sub => i64::from(wrapped),
        Arith::Mul | Arith::Div => exact,
    };
    set_codes(status, codes, overflow);
    *accu1 = wrapped as u32;
}

/// `MOD`: the remainder of ACCU 2 / ACCU 1, with the dividend's sign; OV cleared.
#[inline]
pub fn modulo(accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (i64::from(accu2 as i32), i64::from(*accu1 as i32));
    if b == 0 {
        return division_by_zero(status);
    }
    let remainder = a % b;
    set_codes(status, remainder, false);
    *accu1 = remainder as i32 as u32;
}

/// `NEGI`: two's complement of ACCU 1-L; −32768 stays −32768 with OV.
#[inline]
pub fn negate_int(accu1: &mut u32, status: &mut Status) {
    let exact = -low(*accu1);
    let wrapped = exact as i16;
    set_codes(status, i64::from(wrapped), i32::from(wrapped) != exact);
    *accu1 = with_low(*accu1, exact);
}

/// `NEGD`: two's complement of ACCU 1; −2147483648 stays with OV.
#[inline]
pub fn negate_dint(accu1: &mut u32, status: &mut Status) {
    let (result, overflow) = (*accu1 as i32).overflowing_neg();
    set_codes(status, i64::from(result), overflow);
    *accu1 = result as u32;
}

/// `INVI`: ones' complement of ACCU 1-L; no status.
#[inline]
pub fn invert_int(accu1: &mut u32) {
    *accu1 ^= 0x0000_FFFF;
}

/// `INVD`: ones' complement of ACCU 1; no status.
#[inline]
pub fn invert_dint(accu1: &mut u32) {
    *accu1 = !*accu1;
}

/// `+ 5`: a 16-bit constant added to ACCU 1-L, wrapping; ACCU 1-H and the status are kept.
#[inline]
pub fn add_int_constant(accu1: &mut u32, constant: i16) {
    *accu1 = with_low(*accu1, low(*accu1).wrapping_add(i32::from(constant)));
}

/// `+ L#5`: a 32-bit constant added to ACCU 1, wrapping; the status is kept.
#[inline]
pub fn add_dint_constant(accu1: &mut u32, constant: i32) {
    *accu1 = accu1.wrapping_add(constant as u32);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// CC1, CC0, OV, OS after an operation on a cleared status.
    fn flags(status: Status) -> [u8; 4] {
        [status.cc1(), status.cc0(), status.ov(), status.os()].map(u8::from)
    }

    fn int_op(op: Arith, accu2: u32, accu1: u32) -> (u32, [u8; 4]) {
        let (mut accu, mut status) = (accu1, Status::default());
        int(op, &mut accu, accu2, &mut status);
        (accu, flags(status))
    }

    fn dint_op(op: Arith, accu2: i32, accu1: i32) -> (i32, [u8; 4]) {
        let (mut accu, mut status) = (accu1 as u32, Status::default());
        dint(op, &mut accu, accu2 as u32, &mut status);
        (accu as i32, flags(status))
    }

    fn word(value: i16) -> u32 {
        value as u16 as u32
    }

    #[test]
    fn add_and_subtract_int_wrap_with_the_sign_of_the_wrapped_result() {
        use Arith::{Add, Sub};
        assert_eq!(int_op(Add, word(-32768), word(-1)), (32767, [1, 0, 1, 1]));
        assert_eq!(int_op(Sub, word(-32768), 1), (32767, [1, 0, 1, 1]));
        assert_eq!(int_op(Add, 32767, 1), (0x8000, [0, 1, 1, 1]));
        assert_eq!(int_op(Sub, 32767, word(-1)), (0x8000, [0, 1, 1, 1]));
        assert_eq!(int_op(Add, word(-32767), word(-1)), (0x8000, [0, 1, 0, 0]));
        assert_eq!(int_op(Sub, word(-32767), 1), (0x8000, [0, 1, 0, 0]));
        assert_eq!(int_op(Add, 32766, 1), (32767, [1, 0, 0, 0]));
        assert_eq!(int_op(Sub, 32766, word(-1)), (32767, [1, 0, 0, 0]));
        assert_eq!(int_op(Add, word(-32767), 32767), (0, [0, 0, 0, 0]));
        assert_eq!(int_op(Sub, word(-32767), word(-32767)), (0, [0, 0, 0, 0]));
        assert_eq!(
            int_op(Add, 0x8000, 0x8000),
            (0, [0, 0, 1, 1]),
            "−65536 wraps to zero"
        );
    }

    #[test]
    fn int_add_keeps_accu_1_high() {
        assert_eq!(int_op(Arith::Add, 0xAAAA_0001, 0x1234_0002).0, 0x1234_0003);
    }

    #[test]
    fn multiply_int_gives_the_32_bit_product() {
        assert_eq!(
            int_op(Arith::Mul, word(-10000), 4),
            (-40000i32 as u32, [0, 1, 1, 1])
        );
        assert_eq!(int_op(Arith::Mul, 10000, 4), (40000, [1, 0, 1, 1]));
        assert_eq!(
            int_op(Arith::Mul, word(-10000), 2),
            (-20000i32 as u32, [0, 1, 0, 0])
        );
        assert_eq!(int_op(Arith::Mul, 10000, 2), (20000, [1, 0, 0, 0]));
        assert_eq!(int_op(Arith::Mul, word(-10000), 0), (0, [0, 0, 0, 0]));
        assert_eq!(int_op(Arith::Mul, 32767, 2), (65534, [1, 0, 1, 1]));
        assert_eq!(
            int_op(Arith::Mul, 0xFFFF_0003, 0x1234_0002).0,
            6,
            "the high words are not factors"
        );
    }

    #[test]
    fn divide_int_puts_the_remainder_in_accu_1_high() {
        use Arith::Div;
        assert_eq!(int_op(Div, 18, 4), (0x0002_0004, [1, 0, 0, 0]));
        assert_eq!(int_op(Div, 1010, 500), (0x000A_0002, [1, 0, 0, 0]));
        assert_eq!(int_op(Div, 1010, word(-500)), (0x000A_FFFE, [0, 1, 0, 0]));
        assert_eq!(int_op(Div, word(-1010), 500), (0xFFF6_FFFE, [0, 1, 0, 0]));
        assert_eq!(
            int_op(Div, word(-1010), word(-500)),
            (0xFFF6_0002, [1, 0, 0, 0])
        );
        assert_eq!(int_op(Div, word(-10000), 2), (0xEC78, [0, 1, 0, 0]));
        assert_eq!(int_op(Div, 0x8000, 1), (0x8000, [0, 1, 0, 0]));
        assert_eq!(int_op(Div, 1000, 500), (2, [1, 0, 0, 0]));
        assert_eq!(int_op(Div, 3, 4), (0x0003_0000, [0, 0, 0, 0]));
    }

    #[test]
    fn divide_int_overflow_and_division_by_zero() {
        assert_eq!(
            int_op(Arith::Div, word(-32768), word(-1)),
            (0x8000, [1, 0, 1, 1]),
            "the true quotient +32768 is positive"
        );
        assert_eq!(
            int_op(Arith::Div, 1, 0x5555_0000),
            (0x5555_0000, [1, 1, 1, 1]),
            "ACCU 1 stays"
        );
    }

    #[test]
    fn dint_add_subtract() {
        use Arith::{Add, Sub};
        assert_eq!(dint_op(Add, i32::MIN, -1), (i32::MAX, [1, 0, 1, 1]));
        assert_eq!(dint_op(Sub, i32::MIN, 1), (i32::MAX, [1, 0, 1, 1]));
        assert_eq!(dint_op(Add, i32::MAX, 1), (i32::MIN, [0, 1, 1, 1]));
        assert_eq!(dint_op(Add, i32::MIN, i32::MIN), (0, [0, 0, 1, 1]));
        assert_eq!(dint_op(Add, -5, 5), (0, [0, 0, 0, 0]));
        assert_eq!(dint_op(Sub, 1, 2), (-1, [0, 1, 0, 0]));
        assert_eq!(dint_op(Add, 100_000, 1), (100_001, [1, 0, 0, 0]));
    }

    #[test]
    fn dint_multiply_divide() {
        use Arith::{Div, Mul};
        assert_eq!(dint_op(Mul, 65536, 65536), (0, [1, 0, 1, 1]));
        assert_eq!(dint_op(Mul, -65536, 65536), (0, [0, 1, 1, 1]));
        assert_eq!(dint_op(Mul, -3, 100_000), (-300_000, [0, 1, 0, 0]));
        assert_eq!(dint_op(Mul, 0, -7), (0, [0, 0, 0, 0]));
        assert_eq!(dint_op(Div, -7, 2), (-3, [0, 1, 0, 0]));
        assert_eq!(dint_op(Div, 7, 8), (0, [0, 0, 0, 0]));
        assert_eq!(dint_op(Div, i32::MIN, -1), (i32::MIN, [1, 0, 1, 1]));
        assert_eq!(dint_op(Div, 5, 0), (0, [1, 1, 1, 1]));
    }

    #[test]
    fn modulo_has_the_sign_of_the_dividend() {
        let run = |accu2: i32, accu1: i32| {
            let (mut accu, mut status) = (accu1 as u32, Status::default());
            modulo(&mut accu, accu2 as u32, &mut status);
            (accu as i32, flags(status))
        };
        assert_eq!(run(7, 3), (1, [1, 0, 0, 0]));
        assert_eq!(run(-7, 3), (-1, [0, 1, 0, 0]));
        assert_eq!(run(7, -3), (1, [1, 0, 0, 0]));
        assert_eq!(run(6, 3), (0, [0, 0, 0, 0]));
        assert_eq!(run(i32::MIN, -1), (0, [0, 0, 0, 0]));
        assert_eq!(run(7, 0), (0, [1, 1, 1, 1]), "ACCU 1 stays");
    }

    #[test]
    fn negate() {
        let mut status = Status::default();
        let mut accu = 0xABCD_0005;
        negate_int(&mut accu, &mut status);
        assert_eq!((accu, flags(status)), (0xABCD_FFFB, [0, 1, 0, 0]));
        let mut accu = 0x8000;
        negate_int(&mut accu, &mut status);
        assert_eq!((accu, flags(status)), (0x8000, [0, 1, 1, 1]));
        let mut status = Status::default();
        let mut accu = 0;
        negate_int(&mut accu, &mut status);
        assert_eq!((accu, flags(status)), (0, [0, 0, 0, 0]));
        let mut accu = (-5i32) as u32;
        negate_dint(&mut accu, &mut status);
        assert_eq!((accu, flags(status)), (5, [1, 0, 0, 0]));
        let mut accu = 0x8000_0000;
        negate_dint(&mut accu, &mut status);
        assert_eq!((accu, flags(status)), (0x8000_0000, [0, 1, 1, 1]));
    }

    #[test]
    fn invert() {
        let mut accu = 0x1234_00FF;
        invert_int(&mut accu);
        assert_eq!(accu, 0x1234_FF00);
        invert_dint(&mut accu);
        assert_eq!(accu, 0xEDCB_00FF);
    }

    #[test]
    fn add_constants() {
        let mut accu = 10;
        add_int_constant(&mut accu, 20);
        assert_eq!(accu, 30);
        accu = 0xFFFF;
        add_int_constant(&mut accu, 20);
        assert_eq!(accu, 19, "the carry does not reach ACCU 1-H");
        accu = 10;
        add_int_constant(&mut accu, -20);
        assert_eq!(accu, 0xFFF6);
        accu = 0xFFFF;
        add_dint_constant(&mut accu, 20);
        assert_eq!(accu, 0x0001_0013);
        accu = 10;
        add_dint_constant(&mut accu, -20);
        assert_eq!(accu, 0xFFFF_FFF6);
        accu = u32::MAX;
        add_dint_constant(&mut accu, 1);
        assert_eq!(accu, 0);
    }
}
