//! S5 floating point and the conversions of ACCU 1, with their condition codes. The number
//! format and the arithmetic are in `crate::s5_float`; here is what the operations do to the
//! accumulators and the status (`grammar/README.md`, "Floating point", has the table).
//!
//! - `+G -G XG :G`: ACCU 1 := ACCU 2 op ACCU 1 (32 bits). CC1/CC0 = 1 0 for a positive, 0 1
//!   for a negative result, 0 0 for zero; an exponent overflow gives the largest number of
//!   the result's sign, CC1/CC0 by that sign, OV and OS; an underflow gives zero, CC1/CC0 = 0 0,
//!   OV and OS; `:G` by zero leaves ACCU 1 and sets CC1 CC0 = 1 1 with OV and OS, as `:F` does.
//! - `!=G … <=G`: the RLO, CC1/CC0 = 1 0 when ACCU 2 > ACCU 1, 0 1 when less, 0 0 when equal;
//!   OV is kept, as by the fixed-point comparisons.
//! - `FDG`: CC1/CC0 from the result, OV cleared; `GFD` likewise, and a value outside the 32-bit
//!   range leaves ACCU 1 and sets OV and OS.
//! - `DEF DED` (BCD to fixed point) leave the status; `DUF DUD` of a number with more digits
//!   than the BCD holds (3, or 7) leave ACCU 1 and set OV and OS.

use crate::compiler::bytecode::Conversion;
use crate::s5_float::{self, Outcome};
use crate::vm::arith::{Arith, Comparison};

use super::status::Status;

/// `+G -G XG :G`.
pub fn arithmetic(kind: Arith, accu1: &mut u32, accu2: u32, status: &mut Status) {
    let (result, outcome) = match kind {
        Arith::Add => s5_float::add(accu2, *accu1),
        Arith::Sub => s5_float::subtract(accu2, *accu1),
        Arith::Mul => s5_float::multiply(accu2, *accu1),
        Arith::Div => s5_float::divide(accu2, *accu1),
    };
    if outcome == Outcome::DivisionByZero {
        status.set_condition(true, true);
        status.set_overflow(true);
        return;
    }
    *accu1 = result;
    set_sign(status, s5_float::sign(result));
    status.set_overflow(outcome != Outcome::Exact);
}

fn set_sign(status: &mut Status, sign: i32) {
    status.set_condition(sign > 0, sign < 0);
}

/// `!=G ><G >G >=G <G <=G`: ACCU 2 compared with ACCU 1 gives the RLO.
pub fn compare(kind: Comparison, accu1: u32, accu2: u32, status: &mut Status) {
    // Both values are exact in an f64 (24-bit mantissas, exponents within ±151).
    let (a, b) = (s5_float::decode(accu2), s5_float::decode(accu1));
    super::arith::compare_values(kind, a, b, status);
}

/// `FDG GFD DEF DUF DED DUD`.
pub fn convert(conversion: Conversion, accu1: &mut u32, status: &mut Status) {
    match conversion {
        Conversion::FixedToFloat => {
            *accu1 = s5_float::from_fixed(*accu1 as i32);
            set_sign(status, s5_float::sign(*accu1));
            status.set_overflow(false);
        }
        Conversion::FloatToFixed => match s5_float::to_fixed(*accu1) {
            Some(value) => {
                *accu1 = value as u32;
                set_sign(status, value.signum());
                status.set_overflow(false);
            }
            None => status.set_overflow(true),
        },
        Conversion::BcdToFixed => {
            let value = from_bcd(u32::from(*accu1 as u16), 3) as i16;
            *accu1 = *accu1 & 0xFFFF_0000 | u32::from(value as u16);
        }
        Conversion::BcdToFixedDouble => *accu1 = from_bcd(*accu1, 7) as u32,
        Conversion::FixedToBcd => match to_bcd(i32::from(*accu1 as u16 as i16), 3) {
            Some(bcd) => *accu1 = *accu1 & 0xFFFF_0000 | bcd,
            None => status.set_overflow(true),
        },
        Conversion::FixedToBcdDouble => match to_bcd(*accu1 as i32, 7) {
            Some(bcd) => *accu1 = bcd,
            None => status.set_overflow(true),
        },
    }
}

/// A BCD number of `digits` decimal digits with the sign in the nibble above them (all four
/// bits 1 for negative, CPU 928B programming guide, table 3-21).
fn from_bcd(bcd: u32, digits: u32) -> i32 {
    let magnitude = crate::rules::bcd::decode(bcd, digits) as i32;
    if (bcd >> (4 * digits)) & 0x8 != 0 {
        -magnitude
    } else {
        magnitude
    }
}

/// `value` as BCD of `digits` digits with the sign nibble; `None` when it has more digits.
fn to_bcd(value: i32, digits: u32) -> Option<u32> {
    let magnitude = value.unsigned_abs();
    if magnitude >= 10u32.pow(digits) {
        return None;
    }
    let sign = if value < 0 { 0xF << (4 * digits) } else { 0 };
    Some(crate::rules::bcd::encode(magnitude, digits) | sign)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(kind: Arith, a: f64, b: f64) -> (f64, Status) {
        let mut status = Status::default();
        let mut accu1 = s5_float::encode(b).0;
        arithmetic(kind, &mut accu1, s5_float::encode(a).0, &mut status);
        (s5_float::decode(accu1), status)
    }

    #[test]
    fn arithmetic_sets_the_codes_by_sign() {
        let (sum, status) = run(Arith::Add, 1.5, 2.25);
        assert_eq!(sum, 3.75);
        assert!(status.cc1() && !status.cc0() && !status.ov());
        let (difference, status) = run(Arith::Sub, 1.5, 2.25);
        assert_eq!(difference, -0.75);
        assert!(!status.cc1() && status.cc0() && !status.ov());
        let (zero, status) = run(Arith::Sub, 2.0, 2.0);
        assert_eq!(zero, 0.0);
        assert!(!status.cc1() && !status.cc0() && !status.ov());
    }

    #[test]
    fn overflow_underflow_and_division_by_zero() {
        let (_, status) = run(Arith::Mul, -1.0e38, 1.0e38);
        assert!(!status.cc1() && status.cc0() && status.ov() && status.os());
        let (zero, status) = run(Arith::Div, 1.0e-38, 1.0e38);
        assert_eq!(zero, 0.0);
        assert!(!status.cc1() && !status.cc0() && status.ov() && status.os());
        let (kept, status) = run(Arith::Div, 5.0, 0.0);
        assert_eq!(kept, 0.0, "ACCU 1 (the divisor) stays");
        assert!(status.cc1() && status.cc0() && status.ov());
    }

    #[test]
    fn comparisons() {
        let mut status = Status::default();
        let (small, big) = (s5_float::encode(-2.5).0, s5_float::encode(1.0e10).0);
        compare(Comparison::Lt, big, small, &mut status);
        assert!(status.rlo() && !status.cc1() && status.cc0());
        compare(Comparison::Eq, s5_float::ZERO, 0x0000_0000, &mut status);
        assert!(status.rlo(), "every zero mantissa is zero");
    }

    #[test]
    fn conversions() {
        let mut status = Status::default();
        let mut accu = (-1234i32) as u32;
        convert(Conversion::FixedToFloat, &mut accu, &mut status);
        assert_eq!(s5_float::decode(accu), -1234.0);
        assert!(status.cc0());
        convert(Conversion::FloatToFixed, &mut accu, &mut status);
        assert_eq!(accu as i32, -1234);
        let mut accu = s5_float::encode(1.0e12).0;
        convert(Conversion::FloatToFixed, &mut accu, &mut status);
        assert!(status.ov() && s5_float::decode(accu) > 9.0e11);

        let mut status = Status::default();
        let mut accu = 0xABCD_F123;
        convert(Conversion::BcdToFixed, &mut accu, &mut status);
        assert_eq!(accu, 0xABCD_0000 | u32::from((-123i16) as u16));
        convert(Conversion::FixedToBcd, &mut accu, &mut status);
        assert_eq!(accu, 0xABCD_F123);
        let mut accu = 0x0123_4567;
        convert(Conversion::BcdToFixedDouble, &mut accu, &mut status);
        assert_eq!(accu, 1_234_567);
        accu = (-7_654_321i32) as u32;
        convert(Conversion::FixedToBcdDouble, &mut accu, &mut status);
        assert_eq!(accu, 0xF765_4321);
        assert!(!status.ov());
        accu = 1000;
        convert(Conversion::FixedToBcd, &mut accu, &mut status);
        assert_eq!(accu, 1000);
        assert!(status.ov());
    }
}
