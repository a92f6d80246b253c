//! Conversions of ACCU 1: `ITD ITB BTI BTD DTB DTR RND RND+ RND- TRUNC CAW CAD` ("Statement
//! List (STL) for S7-300 and S7-400 Programming", the chapter on conversion instructions).
//!
//! - BCD numbers have three (`BTI ITB`) or seven (`BTD DTB`) digits and the sign in the top bit
//!   of the word (double word); `ITB`/`DTB` write all four top bits for a negative number. A
//!   digit from 10 to 15 is a programming error (`BTI`/`BTD` return [`InvalidBcd`]; the CPU
//!   goes to STOP with a BCD conversion error), ACCU 1 is left as it was.
//! - `ITB`/`DTB` of a number with more digits than the BCD holds set OV and OS and leave
//!   ACCU 1; otherwise they clear OV.
//! - `RND` rounds to the nearest integer, halves to even; `RND+` up, `RND-` down, `TRUNC`
//!   toward zero. A REAL outside the DINT range, infinity or NaN sets OV and OS and leaves
//!   ACCU 1.
//! - `ITD BTI BTD DTR CAW CAD` and the successful roundings change no status bit.

use crate::rules::bcd;
use crate::vm::status::Status;

/// A BCD digit from 10 to 15 in ACCU 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InvalidBcd;

/// `ITD`: ACCU 1-L sign-extended to 32 bits.
#[inline]
pub fn int_to_dint(accu1: &mut u32) {
    *accu1 = i32::from(*accu1 as u16 as i16) as u32;
}

/// `DTR`: ACCU 1 as DINT to REAL, rounded to nearest.
#[inline]
pub fn dint_to_real(accu1: &mut u32) {
    *accu1 = (*accu1 as i32 as f32).to_bits();
}

/// `CAW`: the two bytes of ACCU 1-L exchange.
#[inline]
pub fn swap_bytes_word(accu1: &mut u32) {
    *accu1 = *accu1 & 0xFFFF_0000 | u32::from((*accu1 as u16).swap_bytes());
}

/// `CAD`: the four bytes of ACCU 1 in reverse order.
#[inline]
pub fn swap_bytes_double(accu1: &mut u32) {
    *accu1 = accu1.swap_bytes();
}

/// The magnitude of `digits` BCD digits, or [`InvalidBcd`].
fn bcd_magnitude(bcd: u32, digits: u32) -> Result<u32, InvalidBcd> {
    (0..digits)
        .rev()
        .try_fold(0, |value, digit| match bcd >> (4 * digit) & 0xF {
            nibble @ 0..=9 => Ok(value * 10 + nibble),
            _ => Err(InvalidBcd),
        })
}

/// `BTI`: 3-digit BCD in ACCU 1-L (sign in bit 15) to INT in ACCU 1-L; ACCU 1-H stays.
#[inline]
pub fn bcd_to_int(accu1: &mut u32) -> Result<(), InvalidBcd> {
    let magnitude = bcd_magnitude(*accu1, 3)? as i32;
    let value = if *accu1 & 0x8000 != 0 {
        -magnitude
    } else {
        magnitude
    };
    *accu1 = *accu1 & 0xFFFF_0000 | u32::from(value as u16);
    Ok(())
}

/// `BTD`: 7-digit BCD in ACCU 1 (sign in bit 31) to DINT.
#[inline]
pub fn bcd_to_dint(accu1: &mut u32) -> Result<(), InvalidBcd> {
    let magnitude = bcd_magnitude(*accu1, 7)? as i32;
    *accu1 = if *accu1 & 0x8000_0000 != 0 {
        -magnitude
    } else {
        magnitude
    } as u32;
    Ok(())
}

/// `ITB`: INT in ACCU 1-L to 3-digit BCD (sign nibble 16#F for negative); ACCU 1-H stays.
#[inline]
pub fn int_to_bcd(accu1: &mut u32, status: &mut Status) {
    let value = *accu1 as u16 as i16;
    let magnitude = u32::from(value.unsigned_abs());
    if magnitude > 999 {
        return status.set_overflow(true);
    }
    let sign = if value < 0 { 0xF000 } else { 0 };
    *accu1 = *accu1 & 0xFFFF_0000 | sign | bcd::encode(magnitude, 3);
    status.set_ov(false);
}

/// `DTB`: DINT in ACCU 1 to 7-digit BCD (sign nibble 16#F for negative).
#[inline]
pub fn dint_to_bcd(accu1: &mut u32, status: &mut Status) {
    let value = *accu1 as i32;
    let magnitude = value.unsigned_abs();
    if magnitude > 9_999_999 {
        return status.set_overflow(true);
    }
    let sign = if value < 0 { 0xF000_0000 } else { 0 };
    *accu1 = sign | bcd::encode(magnitude, 7);
    status.set_ov(false);
}

/// How a REAL becomes a DINT.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Rounding {
    /// `RND`: to nearest, halves to even.
    Nearest,
    /// `RND+`
    Up,
    /// `RND-`
    Down,
    /// `TRUNC`
    TowardZero,
}

/// `RND RND+ RND- TRUNC`: the REAL in ACCU 1 to a DINT.
#[inline]
pub fn real_to_dint(rounding: Rounding, accu1: &mut u32, status: &mut Status) {
    let value = f64::from(f32::from_bits(*accu1));
    let rounded = match rounding {
        Rounding::Nearest => value.round_ties_even(),
        Rounding::Up => value.ceil(),
        Rounding::Down => value.floor(),
        Rounding::TowardZero => value.trunc(),
    };
    // NaN fails both comparisons.
    if (f64::from(i32::MIN)..=f64::from(i32::MAX)).contains(&rounded) {
        *accu1 = rounded as i32 as u32;
    } else {
        status.set_overflow(true);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn int_to_dint_extends_the_sign() {
        let mut accu = 0xABCD_1234;
        int_to_dint(&mut accu);
        assert_eq!(accu, 0x0000_1234);
        accu = 0x0000_F234;
        int_to_dint(&mut accu);
        assert_eq!(accu, 0xFFFF_F234);
    }

    #[test]
    fn dint_to_real_rounds_to_nearest() {
        for (value, real) in [
            (1, 1.0f32),
            (-1, -1.0),
            (0, 0.0),
            (16_777_217, 16_777_216.0),
        ] {
            let mut accu = value as u32;
            dint_to_real(&mut accu);
            assert_eq!(accu, real.to_bits(), "{value}");
        }
    }

    #[test]
    fn byte_swaps() {
        let mut accu = 0x1234_5678;
        swap_bytes_word(&mut accu);
        assert_eq!(accu, 0x1234_7856);
        swap_bytes_double(&mut accu);
        assert_eq!(accu, 0x5678_3412);
    }

    #[test]
    fn bcd_to_binary() {
        let mut accu = 0x0000_0123;
        assert_eq!(bcd_to_int(&mut accu), Ok(()));
        assert_eq!(accu, 123);
        accu = 0xABCD_8123;
        assert_eq!(bcd_to_int(&mut accu), Ok(()));
        assert_eq!(accu, 0xABCD_FF85, "−123, ACCU 1-H kept");
        accu = 0x0000_F999;
        assert_eq!(bcd_to_int(&mut accu), Ok(()));
        assert_eq!(accu, 0x0000_FC19, "bits 12 to 14 do not count");
        accu = 0x0123_4567;
        assert_eq!(bcd_to_dint(&mut accu), Ok(()));
        assert_eq!(accu, 1_234_567);
        accu = 0x8123_4567;
        assert_eq!(bcd_to_dint(&mut accu), Ok(()));
        assert_eq!(accu, 0xFFED_2979);
    }

    #[test]
    fn invalid_bcd_digits_are_an_error_and_leave_accu_1() {
        for bcd in [0x0000_012A, 0x0000_0B00, 0x0000_0F99] {
            let mut accu = bcd;
            assert_eq!(bcd_to_int(&mut accu), Err(InvalidBcd), "{bcd:#x}");
            assert_eq!(accu, bcd);
        }
        let mut accu = 0x0A00_0000;
        assert_eq!(bcd_to_dint(&mut accu), Err(InvalidBcd));
        assert_eq!(accu, 0x0A00_0000);
    }

    /// ACCU 1, OV and OS after a conversion on a status with OV set.
    fn to_bcd_with(f: fn(&mut u32, &mut Status), accu1: u32) -> (u32, bool, bool) {
        let mut status = Status::default();
        status.set_overflow(true);
        let mut accu = accu1;
        f(&mut accu, &mut status);
        (accu, status.ov(), status.os())
    }

    #[test]
    fn binary_to_bcd() {
        assert_eq!(to_bcd_with(int_to_bcd, 321), (0x321, false, true));
        assert_eq!(
            to_bcd_with(int_to_bcd, 0x1234_0000 | u32::from((-321i16) as u16)),
            (0x1234_F321, false, true)
        );
        assert_eq!(to_bcd_with(int_to_bcd, 999), (0x999, false, true));
        assert_eq!(to_bcd_with(int_to_bcd, 1000), (1000, true, true));
        let minus_1000 = u32::from((-1000i16) as u16);
        assert_eq!(
            to_bcd_with(int_to_bcd, minus_1000),
            (minus_1000, true, true)
        );
        assert_eq!(
            to_bcd_with(dint_to_bcd, 7_654_321),
            (0x0765_4321, false, true)
        );
        assert_eq!(
            to_bcd_with(dint_to_bcd, (-7_654_321i32) as u32),
            (0xF765_4321, false, true)
        );
        assert_eq!(
            to_bcd_with(dint_to_bcd, 10_000_000),
            (10_000_000, true, true)
        );
        let minimum = i32::MIN as u32;
        assert_eq!(to_bcd_with(dint_to_bcd, minimum), (minimum, true, true));
    }

    /// ACCU 1 as DINT, or `None` with OV and OS set and ACCU 1 unchanged.
    fn round(rounding: Rounding, value: f32) -> Option<i32> {
        let mut status = Status::default();
        let mut accu = value.to_bits();
        real_to_dint(rounding, &mut accu, &mut status);
        if status.ov() {
            assert!(status.os());
            assert_eq!(accu, value.to_bits());
            None
        } else {
            assert!(!status.os() && !status.cc1() && !status.cc0());
            Some(accu as i32)
        }
    }

    #[test]
    fn roundings() {
        use Rounding::*;
        let cases: [(f32, [i32; 4]); 12] = [
            (0.0, [0, 0, 0, 0]),
            (0.1, [0, 1, 0, 0]),
            (0.5, [0, 1, 0, 0]),
            (1.0, [1, 1, 1, 1]),
            (1.1, [1, 2, 1, 1]),
            (1.5, [2, 2, 1, 1]),
            (2.5, [2, 3, 2, 2]),
            (-0.1, [0, 0, -1, 0]),
            (-0.5, [0, 0, -1, 0]),
            (-1.1, [-1, -1, -2, -1]),
            (-1.5, [-2, -1, -2, -1]),
            (-2.5, [-2, -2, -3, -2]),
        ];
        for (value, [nearest, up, down, toward_zero]) in cases {
            assert_eq!(round(Nearest, value), Some(nearest), "RND {value}");
            assert_eq!(round(Up, value), Some(up), "RND+ {value}");
            assert_eq!(round(Down, value), Some(down), "RND- {value}");
            assert_eq!(round(TowardZero, value), Some(toward_zero), "TRUNC {value}");
        }
    }

    #[test]
    fn roundings_out_of_range() {
        use Rounding::*;
        for rounding in [Nearest, Up, Down, TowardZero] {
            for value in [
                3.0e9,
                -3.0e9,
                2_147_483_648.0,
                f32::INFINITY,
                f32::NEG_INFINITY,
            ] {
                assert_eq!(round(rounding, value), None, "{rounding:?} {value}");
            }
            for nan in [0x7FFF_FFFF, 0xFFFF_FFFF] {
                assert_eq!(round(rounding, f32::from_bits(nan)), None, "{rounding:?}");
            }
            assert_eq!(round(rounding, -2_147_483_648.0), Some(i32::MIN));
            assert_eq!(round(rounding, 2_147_483_520.0), Some(2_147_483_520));
        }
    }
}
