//! `==I <>I >I <I >=I <=I`, the same for D and R: ACCU 2 compared with ACCU 1 gives the RLO
//! ("Statement List (STL) for S7-300 and S7-400 Programming", the chapter on comparison
//! instructions).
//!
//! A comparison starts a new logic string with its result: RLO and STA = the result, OR = 0,
//! /FC = 1. CC1 CC0 = 1 0 when ACCU 2 > ACCU 1, 0 1 when less, 0 0 when equal. The fixed-point
//! comparisons clear OV, and so do the REAL comparisons of two numbers (±infinity included:
//! +infinity equals +infinity). A REAL comparison with a NaN is unordered: CC1 CC0 = 1 1, OV
//! and OS, and every comparison is false, `<>R` too.

use crate::vm::arith::Comparison;
use crate::vm::status::Status;

#[inline(always)]
fn holds(op: Comparison, greater: bool, less: bool) -> bool {
    match op {
        Comparison::Eq => !greater && !less,
        Comparison::Ne => greater || less,
        Comparison::Gt => greater,
        Comparison::Ge => !less,
        Comparison::Lt => less,
        Comparison::Le => !greater,
    }
}

#[inline(always)]
fn set_result(status: &mut Status, result: bool) {
    status.set_rlo(result);
    status.set_sta(result);
    status.set_or_bit(false);
    status.set_first_check(true);
}

#[inline(always)]
fn ordered<T: PartialOrd>(op: Comparison, a: T, b: T, status: &mut Status) {
    let (greater, less) = (a > b, a < b);
    status.set_condition(greater, less);
    status.set_ov(false);
    set_result(status, holds(op, greater, less));
}

/// `==I …`: ACCU 2-L with ACCU 1-L.
#[inline]
pub fn int(op: Comparison, accu1: u32, accu2: u32, status: &mut Status) {
    ordered(op, accu2 as u16 as i16, accu1 as u16 as i16, status);
}

/// `==D …`: ACCU 2 with ACCU 1.
#[inline]
pub fn dint(op: Comparison, accu1: u32, accu2: u32, status: &mut Status) {
    ordered(op, accu2 as i32, accu1 as i32, status);
}

/// `==R …`: ACCU 2 with ACCU 1 as REAL.
#[inline]
pub fn real(op: Comparison, accu1: u32, accu2: u32, status: &mut Status) {
    let (a, b) = (f32::from_bits(accu2), f32::from_bits(accu1));
    if a.is_nan() || b.is_nan() {
        status.set_condition(true, true);
        status.set_overflow(true);
        return set_result(status, false);
    }
    ordered(op, a, b, status);
}

#[cfg(test)]
mod tests {
    use super::*;
    use Comparison::{Eq, Ge, Gt, Le, Lt, Ne};

    /// RLO, CC1, CC0, OV, OR, STA, /FC.
    fn bits(status: Status) -> [u8; 7] {
        [
            status.rlo(),
            status.cc1(),
            status.cc0(),
            status.ov(),
            status.or_bit(),
            status.sta(),
            status.first_check(),
        ]
        .map(u8::from)
    }

    fn run(
        compare: fn(Comparison, u32, u32, &mut Status),
        op: Comparison,
        a: u32,
        b: u32,
    ) -> [u8; 7] {
        let (mut status, _) = Status::from_word(0x1FF);
        compare(op, b, a, &mut status);
        bits(status)
    }

    #[test]
    fn int_comparisons_by_the_sign() {
        let minus = (-5i16) as u16 as u32;
        assert_eq!(run(int, Gt, 3, minus), [1, 1, 0, 0, 0, 1, 1]);
        assert_eq!(run(int, Lt, 3, minus), [0, 1, 0, 0, 0, 0, 1]);
        assert_eq!(run(int, Lt, minus, 3), [1, 0, 1, 0, 0, 1, 1]);
        assert_eq!(run(int, Eq, 7, 7), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(run(int, Ne, 7, 7), [0, 0, 0, 0, 0, 0, 1]);
        assert_eq!(run(int, Ge, 7, 7), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(run(int, Le, 7, 7), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(run(int, Le, 8, 7), [0, 1, 0, 0, 0, 0, 1]);
        assert_eq!(run(int, Ge, 6, 7), [0, 0, 1, 0, 0, 0, 1]);
        assert_eq!(run(int, Ne, 6, 7), [1, 0, 1, 0, 0, 1, 1]);
        assert_eq!(
            run(int, Eq, 0x1234_0001, 0x5678_0001)[0],
            1,
            "the high words do not count"
        );
    }

    #[test]
    fn dint_comparisons_use_all_32_bits() {
        assert_eq!(
            run(dint, Gt, 0x0001_0000, 0x0000_FFFF),
            [1, 1, 0, 0, 0, 1, 1]
        );
        assert_eq!(
            run(dint, Lt, 0x8000_0000, 0x7FFF_FFFF),
            [1, 0, 1, 0, 0, 1, 1]
        );
        assert_eq!(
            run(dint, Eq, 0x1234_0001, 0x5678_0001),
            [0, 0, 1, 0, 0, 0, 1]
        );
    }

    fn real_bits(value: f32) -> u32 {
        value.to_bits()
    }

    #[test]
    fn real_comparisons() {
        let (small, big) = (real_bits(-1.5), real_bits(1.5));
        assert_eq!(run(real, Eq, big, big), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(run(real, Eq, small, big), [0, 0, 1, 0, 0, 0, 1]);
        assert_eq!(run(real, Ne, small, big), [1, 0, 1, 0, 0, 1, 1]);
        assert_eq!(run(real, Gt, big, small), [1, 1, 0, 0, 0, 1, 1]);
        assert_eq!(run(real, Lt, big, small), [0, 1, 0, 0, 0, 0, 1]);
        assert_eq!(run(real, Ge, small, small), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(run(real, Le, small, big), [1, 0, 1, 0, 0, 1, 1]);
        assert_eq!(run(real, Eq, real_bits(0.0), real_bits(-0.0))[0], 1);
        let infinity = real_bits(f32::INFINITY);
        assert_eq!(run(real, Eq, infinity, infinity), [1, 0, 0, 0, 0, 1, 1]);
        assert_eq!(
            run(real, Gt, infinity, real_bits(f32::MAX)),
            [1, 1, 0, 0, 0, 1, 1]
        );
    }

    #[test]
    fn real_comparisons_with_nan_are_unordered_and_false() {
        for nan in [0x7FFF_FFFF, 0xFFFF_FFFF, 0x7FC0_0000] {
            for op in [Eq, Ne, Gt, Lt, Ge, Le] {
                let mut status = Status::default();
                real(op, nan, nan, &mut status);
                assert_eq!(bits(status), [0, 1, 1, 1, 0, 0, 1], "{op:?} {nan:#x}");
                assert!(status.os());
                real(op, real_bits(1.0), nan, &mut status);
                assert!(!status.rlo() && status.cc1() && status.cc0());
            }
        }
    }

    /// BR is not in the status a comparison gets, so it keeps BR by its signature.
    #[test]
    fn comparisons_keep_os() {
        let (mut status, _) = Status::from_word(0x1FF);
        int(Eq, 1, 1, &mut status);
        assert!(status.os());
    }
}
