//! REAL (IEEE 754 single precision) arithmetic `+R -R *R /R`, the functions `SQR SQRT EXP LN
//! SIN COS TAN ASIN ACOS ATAN`, and `ABS NEGR` ("Statement List (STL) for S7-300 and S7-400
//! Programming", the chapter on floating-point math).
//!
//! The status after a result, by the result:
//!
//! | result                       | CC1 CC0 | OV | OS   |
//! |------------------------------|---------|----|------|
//! | +normalized                  | 1 0     | 0  | kept |
//! | −normalized                  | 0 1     | 0  | kept |
//! | ±0                           | 0 0     | 0  | kept |
//! | denormalized, or underflow   | 0 0     | 1  | 1    |
//! | +infinity (overflow)         | 1 0     | 1  | 1    |
//! | −infinity                    | 0 1     | 1  | 1    |
//! | NaN (unordered)              | 1 1     | 1  | 1    |
//!
//! As awlsim does (its tests are awl's reference): a NaN from `+R -R *R /R` is 16#FFFFFFFF
//! (−NaN), a NaN from a function 16#7FFFFFFF (+NaN); a result too small for even a
//! denormalized REAL is +0; the functions pass ±infinity through unchanged (with OV); `/R` by
//! ±0 gives ±infinity by the sign of the dividend (0 / 0 gives +infinity) and by ±infinity
//! gives +0; `*R` with an infinite factor gives 16#FFFFFFFF when the other factor is ±0, and
//! else ACCU 2 with its sign flipped when ACCU 1 is negative; results of `SIN COS TAN` within
//! 1e-7 of −1, 0 or 1 are those values, `TAN` of an argument within 1e-7 of ±π/2 is ±infinity.

use crate::rules::arith::Arith;
use crate::rules::status::Status;

/// The NaN `+R -R *R /R` give.
pub const NEGATIVE_NAN: u32 = 0xFFFF_FFFF;
/// The NaN the functions give.
pub const POSITIVE_NAN: u32 = 0x7FFF_FFFF;

const SIGN: u32 = 0x8000_0000;
/// The smallest positive denormalized REAL.
const SMALLEST: f64 = 1.401_298_464_324_817e-45;
/// How near a result of `SIN COS TAN` must be to −1, 0, 1 to become it.
const SNAP: f64 = 1e-7;

/// The REAL a value is stored as; `nan` for a NaN.
#[inline(always)]
fn bits_of(value: f64, nan: u32) -> u32 {
    if value.is_nan() {
        nan
    } else if value != 0.0 && value.abs() < SMALLEST {
        0
    } else {
        (value as f32).to_bits()
    }
}

/// CC1/CC0, OV and OS for the result `value`, by the table in the module doc.
#[inline]
pub fn set_codes_of(value: f64, status: &mut Status) {
    let stored = bits_of(value, NEGATIVE_NAN);
    let magnitude = stored & !SIGN;
    let negative = stored & SIGN != 0;
    let (cc1, cc0, overflow) = if value != 0.0 && value.abs() < SMALLEST {
        (false, false, true)
    } else if magnitude == 0 {
        (false, false, false)
    } else if magnitude < 0x0080_0000 {
        (false, false, true)
    } else if magnitude == 0x7F80_0000 {
        (!negative, negative, true)
    } else if magnitude > 0x7F80_0000 {
        (true, true, true)
    } else {
        (!negative, negative, false)
    };
    status.set_condition(cc1, cc0);
    status.set_overflow(overflow);
}

#[inline(always)]
fn store(value: f64, nan: u32, accu1: &mut u32, status: &mut Status) {
    *accu1 = bits_of(value, nan);
    set_codes_of(value, status);
}

#[inline(always)]
fn value(bits: u32) -> f64 {
    f64::from(f32::from_bits(bits))
}

#[inline(always)]
fn is_infinite(bits: u32) -> bool {
    bits & !SIGN == 0x7F80_0000
}

/// `+R -R *R /R`: ACCU 1 := ACCU 2 op ACCU 1.
#[inline]
pub fn arithmetic(op: Arith, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (a, b) = (value(accu2), value(*accu1));
    let result = match op {
        Arith::Add => a + b,
        Arith::Sub => a - b,
        Arith::Mul if is_infinite(*accu1) || is_infinite(accu2) => {
            return multiply_infinity(accu1, accu2, status);
        }
        Arith::Mul => a * b,
        Arith::Div if is_infinite(*accu1) => 0.0,
        Arith::Div if b == 0.0 && a >= 0.0 => f64::INFINITY,
        Arith::Div if b == 0.0 => f64::NEG_INFINITY,
        Arith::Div => a / b,
    };
    store(result, NEGATIVE_NAN, accu1, status);
}

/// `*R` with an infinite factor (see the module doc); OV and OS are always set.
#[cold]
fn multiply_infinity(accu1: &mut u32, accu2: u32, status: &mut Status) {
    let is_zero = |bits: u32| bits & !SIGN == 0;
    *accu1 = if is_zero(*accu1) || is_zero(accu2) {
        NEGATIVE_NAN
    } else {
        accu2 ^ (*accu1 & SIGN)
    };
    set_codes_of(value(*accu1), status);
    status.set_overflow(true);
}

/// The REAL functions of ACCU 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Function {
    Sqr,
    Sqrt,
    Exp,
    Ln,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
}

/// `SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN` of ACCU 1.
#[inline]
pub fn function(function: Function, accu1: &mut u32, status: &mut Status) {
    let x = value(*accu1);
    if is_infinite(*accu1) {
        return set_codes_of(x, status);
    }
    let result = match function {
        Function::Sqr => x * x,
        Function::Sqrt => x.sqrt(),
        // EXP of more than 88.0 is beyond the REAL range.
        Function::Exp if x > 88.0 => f64::INFINITY,
        Function::Exp => x.exp(),
        Function::Ln if x <= 0.0 => f64::NAN,
        Function::Ln => x.ln(),
        Function::Sin => snapped(x.sin()),
        Function::Cos => snapped(x.cos()),
        Function::Tan if (x - std::f64::consts::FRAC_PI_2).abs() < SNAP => f64::INFINITY,
        Function::Tan if (x + std::f64::consts::FRAC_PI_2).abs() < SNAP => f64::NEG_INFINITY,
        Function::Tan => snapped(x.tan()),
        Function::Asin => x.asin(),
        Function::Acos => x.acos(),
        Function::Atan => x.atan(),
    };
    store(result, POSITIVE_NAN, accu1, status);
}

/// −1, 0 and 1 for results within [`SNAP`] of them; −0 stays −0.
#[inline(always)]
fn snapped(result: f64) -> f64 {
    if (result + 1.0).abs() < SNAP {
        -1.0
    } else if result.abs() < SNAP && result != 0.0 {
        0.0
    } else if (result - 1.0).abs() < SNAP {
        1.0
    } else {
        result
    }
}

/// `ABS`: clears the sign bit; no status.
#[inline]
pub fn abs(accu1: &mut u32) {
    *accu1 &= !SIGN;
}

/// `NEGR`: flips the sign bit (of NaN and infinity too); no status.
#[inline]
pub fn negate(accu1: &mut u32) {
    *accu1 ^= SIGN;
}

#[cfg(test)]
mod tests {
    use super::*;
    use Arith::{Add, Div, Mul, Sub};

    const PINF: u32 = 0x7F80_0000;
    const NINF: u32 = 0xFF80_0000;
    const PNAN: u32 = POSITIVE_NAN;
    const NNAN: u32 = NEGATIVE_NAN;

    fn r(value: f32) -> u32 {
        value.to_bits()
    }

    /// ACCU 1 and CC1, CC0, OV, OS after `op` on a cleared status.
    fn arith(op: Arith, accu2: u32, accu1: u32) -> (u32, [u8; 4]) {
        let (mut accu, mut status) = (accu1, Status::default());
        arithmetic(op, &mut accu, accu2, &mut status);
        (accu, flags(status))
    }

    fn flags(status: Status) -> [u8; 4] {
        [status.cc1(), status.cc0(), status.ov(), status.os()].map(u8::from)
    }

    fn call(f: Function, accu1: u32) -> (u32, [u8; 4]) {
        let (mut accu, mut status) = (accu1, Status::default());
        function(f, &mut accu, &mut status);
        (accu, flags(status))
    }

    const POSITIVE: [u8; 4] = [1, 0, 0, 0];
    const NEGATIVE: [u8; 4] = [0, 1, 0, 0];
    const ZERO: [u8; 4] = [0, 0, 0, 0];
    const UNDERFLOW: [u8; 4] = [0, 0, 1, 1];
    const PLUS_INFINITY: [u8; 4] = [1, 0, 1, 1];
    const MINUS_INFINITY: [u8; 4] = [0, 1, 1, 1];
    const UNORDERED: [u8; 4] = [1, 1, 1, 1];

    #[test]
    fn ordinary_results() {
        assert_eq!(arith(Add, r(1.0), r(1.0)), (0x4000_0000, POSITIVE));
        assert_eq!(arith(Add, r(1.0), r(-1.0)), (0, ZERO));
        assert_eq!(arith(Add, r(-1.0), r(-1.0)), (0xC000_0000, NEGATIVE));
        assert_eq!(arith(Sub, r(1.0), r(-1.0)), (0x4000_0000, POSITIVE));
        assert_eq!(arith(Sub, r(-1.0), r(-1.0)), (0, ZERO));
        assert_eq!(arith(Mul, r(3.0), r(-2.0)), (0xC0C0_0000, NEGATIVE));
        assert_eq!(arith(Mul, r(-3.0), r(-2.0)), (0x40C0_0000, POSITIVE));
        assert_eq!(arith(Div, r(3.0), r(2.0)), (0x3FC0_0000, POSITIVE));
        assert_eq!(arith(Div, r(3.0), r(-2.0)), (0xBFC0_0000, NEGATIVE));
    }

    #[test]
    fn overflow_gives_infinity_and_underflow_zero_or_a_denormal() {
        assert_eq!(arith(Mul, r(f32::MAX), r(2.0)), (PINF, PLUS_INFINITY));
        assert_eq!(
            arith(Sub, r(-f32::MAX), r(f32::MAX)),
            (NINF, MINUS_INFINITY)
        );
        assert_eq!(arith(Div, 0x0000_0001, r(2.0)), (0, UNDERFLOW));
        assert_eq!(
            arith(Div, 0x8000_0001, r(4.0)),
            (0, UNDERFLOW),
            "+0, not −0"
        );
        assert_eq!(
            arith(Div, r(f32::MIN_POSITIVE), r(2.0)),
            (0x0040_0000, UNDERFLOW),
            "a denormal stays in ACCU 1"
        );
    }

    #[test]
    fn infinity_in_add_and_subtract() {
        assert_eq!(arith(Add, PINF, r(1.0)), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Add, r(-1.0), NINF), (NINF, MINUS_INFINITY));
        assert_eq!(arith(Sub, r(1.0), PINF), (NINF, MINUS_INFINITY));
        assert_eq!(arith(Sub, r(-1.0), NINF), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Sub, PINF, PINF), (NNAN, UNORDERED));
    }

    #[test]
    fn nan_operands_give_negative_nan() {
        for op in [Add, Sub, Mul, Div] {
            for nan in [PNAN, NNAN] {
                assert_eq!(arith(op, nan, r(1.0)), (NNAN, UNORDERED), "{op:?}");
                assert_eq!(arith(op, r(-1.0), nan), (NNAN, UNORDERED), "{op:?}");
            }
        }
    }

    #[test]
    fn multiply_with_an_infinite_factor() {
        assert_eq!(arith(Mul, PINF, r(1.0)), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Mul, PINF, r(-1.0)), (NINF, MINUS_INFINITY));
        assert_eq!(arith(Mul, NINF, r(-1.0)), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Mul, r(1.0), PINF), (r(1.0), PLUS_INFINITY));
        assert_eq!(arith(Mul, r(-1.0), PINF), (r(-1.0), MINUS_INFINITY));
        assert_eq!(arith(Mul, r(1.0), NINF), (r(-1.0), MINUS_INFINITY));
        assert_eq!(arith(Mul, r(-1.0), NINF), (r(1.0), PLUS_INFINITY));
        for (a, b) in [(PINF, 0), (NINF, 0), (0, PINF), (0x8000_0000, NINF)] {
            assert_eq!(arith(Mul, a, b), (NNAN, UNORDERED), "{a:#x} {b:#x}");
        }
    }

    #[test]
    fn divide_by_zero_and_by_infinity() {
        assert_eq!(arith(Div, r(1.5), 0), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Div, r(-1.5), 0), (NINF, MINUS_INFINITY));
        assert_eq!(arith(Div, r(1.5), 0x8000_0000), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Div, 0, 0), (PINF, PLUS_INFINITY));
        assert_eq!(arith(Div, r(1.0), PINF), (0, ZERO));
        assert_eq!(arith(Div, r(-1.0), NINF), (0, ZERO));
        assert_eq!(arith(Div, PINF, r(-1.0)), (NINF, MINUS_INFINITY));
        assert_eq!(arith(Div, NINF, r(-1.0)), (PINF, PLUS_INFINITY));
    }

    #[test]
    fn os_stays_set_after_a_good_result() {
        let mut status = Status::default();
        status.set_overflow(true);
        let mut accu = r(1.0);
        arithmetic(Add, &mut accu, r(2.0), &mut status);
        assert_eq!(flags(status), [1, 0, 0, 1]);
    }

    #[test]
    fn abs_and_negate_flip_the_sign_bit_only() {
        for (value, absolute, negated) in [
            (r(0.0), r(0.0), r(-0.0)),
            (r(-1.5), r(1.5), r(1.5)),
            (PINF, PINF, NINF),
            (NINF, PINF, PINF),
            (PNAN, PNAN, NNAN),
            (NNAN, PNAN, PNAN),
        ] {
            let mut accu = value;
            abs(&mut accu);
            assert_eq!(accu, absolute);
            accu = value;
            negate(&mut accu);
            assert_eq!(accu, negated);
        }
    }

    #[test]
    fn square_and_square_root() {
        use Function::{Sqr, Sqrt};
        assert_eq!(call(Sqr, r(-0.0)), (0, ZERO));
        assert_eq!(call(Sqr, r(-1.5)), (r(2.25), POSITIVE));
        assert_eq!(call(Sqr, NINF), (NINF, MINUS_INFINITY), "infinity passes");
        assert_eq!(call(Sqr, NNAN), (PNAN, UNORDERED));
        assert_eq!(call(Sqr, r(1.0e30)), (PINF, PLUS_INFINITY));
        assert_eq!(call(Sqrt, r(9.0)), (r(3.0), POSITIVE));
        assert_eq!(call(Sqrt, r(-0.0)), (r(-0.0), ZERO));
        assert_eq!(call(Sqrt, r(-0.5)), (PNAN, UNORDERED));
        assert_eq!(call(Sqrt, PINF), (PINF, PLUS_INFINITY));
        assert_eq!(call(Sqrt, NINF), (NINF, MINUS_INFINITY));
        assert_eq!(call(Sqrt, NNAN), (PNAN, UNORDERED));
    }

    #[test]
    fn exp_and_ln() {
        use Function::{Exp, Ln};
        assert_eq!(call(Exp, r(-0.0)), (r(1.0), POSITIVE));
        assert_eq!(call(Exp, r(1.5)), (0x408F_69FF, POSITIVE));
        assert_eq!(call(Exp, r(-1.5)), (0x3E64_7C3C, POSITIVE));
        let (largest, codes) = call(Exp, 0x42B0_0000);
        assert_ne!(largest, PINF, "EXP 88.0 is in range");
        assert_eq!(codes, POSITIVE);
        assert_eq!(call(Exp, 0x42B0_0001), (PINF, PLUS_INFINITY));
        assert_eq!(call(Exp, NINF), (NINF, MINUS_INFINITY));
        assert_eq!(call(Exp, r(-110.0)), (0, UNDERFLOW));
        assert_eq!(call(Exp, PNAN), (PNAN, UNORDERED));
        assert_eq!(call(Ln, r(1.5)), (0x3ECF_991F, POSITIVE));
        assert_eq!(call(Ln, r(1.0)), (0, ZERO));
        assert_eq!(call(Ln, r(0.0)), (PNAN, UNORDERED));
        assert_eq!(call(Ln, r(-0.0)), (PNAN, UNORDERED));
        assert_eq!(call(Ln, r(-1.5)), (PNAN, UNORDERED));
        assert_eq!(call(Ln, NINF), (NINF, MINUS_INFINITY));
        assert_eq!(call(Ln, NNAN), (PNAN, UNORDERED));
    }

    #[test]
    fn trigonometry_snaps_to_minus_one_zero_one() {
        use Function::{Cos, Sin, Tan};
        let pi = std::f32::consts::PI;
        assert_eq!(call(Sin, r(-0.0)), (r(-0.0), ZERO));
        assert_eq!(call(Sin, r(pi / 2.0)), (r(1.0), POSITIVE));
        assert_eq!(call(Sin, r(pi)), (0, ZERO));
        assert_eq!(call(Sin, r(-pi / 2.0)), (r(-1.0), NEGATIVE));
        assert_eq!(call(Sin, r(-pi)), (0, ZERO));
        assert_eq!(call(Cos, r(-0.0)), (r(1.0), POSITIVE));
        assert_eq!(call(Cos, r(pi / 2.0)), (0, ZERO));
        assert_eq!(call(Cos, r(pi)), (r(-1.0), NEGATIVE));
        assert_eq!(call(Tan, r(-0.0)), (r(-0.0), ZERO));
        assert_eq!(call(Tan, r(pi / 4.0)), (r(1.0), POSITIVE));
        assert_eq!(call(Tan, r(-pi / 4.0)), (r(-1.0), NEGATIVE));
        assert_eq!(call(Tan, r(pi / 2.0)), (PINF, PLUS_INFINITY));
        assert_eq!(call(Tan, r(-pi / 2.0)), (NINF, MINUS_INFINITY));
        assert_eq!(call(Tan, r(pi)), (0, ZERO));
        for f in [Sin, Cos, Tan] {
            assert_eq!(call(f, PINF), (PINF, PLUS_INFINITY), "{f:?}");
            assert_eq!(call(f, NNAN), (PNAN, UNORDERED), "{f:?}");
        }
    }

    #[test]
    fn inverse_trigonometry() {
        use Function::{Acos, Asin, Atan};
        let pi = std::f32::consts::PI;
        assert_eq!(call(Asin, r(-0.0)), (r(-0.0), ZERO));
        assert_eq!(call(Asin, r(1.0)), (r(pi / 2.0), POSITIVE));
        assert_eq!(call(Asin, r(-1.0)), (r(-pi / 2.0), NEGATIVE));
        assert_eq!(call(Acos, r(1.0)), (0, ZERO));
        assert_eq!(call(Acos, r(0.0)), (r(pi / 2.0), POSITIVE));
        assert_eq!(call(Acos, r(-1.0)), (r(pi), POSITIVE));
        assert_eq!(call(Atan, r(1.0)), (r(pi / 4.0), POSITIVE));
        assert_eq!(call(Atan, r(-1.0)), (r(-pi / 4.0), NEGATIVE));
        for f in [Asin, Acos] {
            assert_eq!(call(f, r(1.1)), (PNAN, UNORDERED), "{f:?}");
            assert_eq!(call(f, r(-1.1)), (PNAN, UNORDERED), "{f:?}");
        }
        for f in [Asin, Acos, Atan] {
            assert_eq!(call(f, NINF), (NINF, MINUS_INFINITY), "{f:?}");
            assert_eq!(call(f, PNAN), (PNAN, UNORDERED), "{f:?}");
        }
    }
}
