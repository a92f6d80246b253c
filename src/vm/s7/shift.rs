//! Shifts and rotates of ACCU 1 (`SSI SSD SLW SRW SLD SRD RLD RRD RLDA RRDA`), by a count
//! written with the operation (0 to 255) or taken from ACCU 2-LL ("Statement List (STL) for
//! S7-300 and S7-400 Programming", the chapter on shift and rotate instructions).
//!
//! - A count of 0 changes nothing, the status included.
//! - Counts beyond the width: `SSI`/`SSD` shift as far as the width (all sign bits); `SLW SRW
//!   SLD SRD` give 0 with CC1 = 0; `RLD`/`RRD` by n > 32 rotate by ((n − 1) mod 32) + 1.
//! - CC1 = the last bit shifted out (for a rotate: the last bit rotated round), CC0 = 0,
//!   OV = 0; OS is kept. The 16-bit shifts keep ACCU 1-H.
//! - `RLDA`/`RRDA` rotate by one place through CC1.

use crate::vm::status::Status;

/// The shifts and rotates that take a count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Shift {
    /// `SSI`: arithmetic right shift of ACCU 1-L.
    SignedInt,
    /// `SSD`: arithmetic right shift of ACCU 1.
    SignedDint,
    /// `SLW`
    LeftWord,
    /// `SRW`
    RightWord,
    /// `SLD`
    LeftDouble,
    /// `SRD`
    RightDouble,
    /// `RLD`
    RotateLeft,
    /// `RRD`
    RotateRight,
}

/// The count of a shift without operand: ACCU 2-LL.
#[inline]
pub fn count_from_accu2(accu2: u32) -> u8 {
    accu2 as u8
}

#[inline(always)]
fn bit(value: u64, index: u32) -> bool {
    value >> index & 1 == 1
}

/// A rotate by 1 to 32 places; beyond 32 the count wraps so that 33 rotates by 1 place.
#[inline(always)]
fn rotation(count: u32) -> u32 {
    (count - 1) % 32 + 1
}

/// `SSI n` … `RRD n` (or without `n`, with [`count_from_accu2`]).
#[inline]
pub fn shift(op: Shift, count: u8, accu1: &mut u32, status: &mut Status) {
    if count == 0 {
        return;
    }
    let n = u32::from(count);
    let word = u64::from(*accu1 & 0xFFFF);
    let double = u64::from(*accu1);
    let (result, last_out) = match op {
        Shift::SignedInt => {
            let n = n.min(16);
            let signed = i64::from(*accu1 as u16 as i16);
            ((signed >> n) as u64, bit(signed as u64, n - 1))
        }
        Shift::SignedDint => {
            let n = n.min(32);
            let signed = i64::from(*accu1 as i32);
            ((signed >> n) as u64, bit(signed as u64, n - 1))
        }
        Shift::LeftWord | Shift::RightWord if n > 16 => (0, false),
        Shift::LeftDouble | Shift::RightDouble if n > 32 => (0, false),
        Shift::LeftWord => (word << n, bit(word, 16 - n)),
        Shift::RightWord => (word >> n, bit(word, n - 1)),
        Shift::LeftDouble => (double << n, bit(double, 32 - n)),
        Shift::RightDouble => (double >> n, bit(double, n - 1)),
        Shift::RotateLeft => {
            let rotated = accu1.rotate_left(rotation(n));
            (u64::from(rotated), rotated & 1 == 1)
        }
        Shift::RotateRight => {
            let rotated = accu1.rotate_right(rotation(n));
            (u64::from(rotated), rotated >> 31 == 1)
        }
    };
    status.set_condition(last_out, false);
    status.set_ov(false);
    *accu1 = match op {
        Shift::SignedInt | Shift::LeftWord | Shift::RightWord => {
            *accu1 & 0xFFFF_0000 | result as u32 & 0xFFFF
        }
        _ => result as u32,
    };
}

/// `RLDA`: ACCU 1 one place left through CC1 (bit 31 to CC1, CC1 to bit 0).
#[inline]
pub fn rotate_left_via_cc1(accu1: &mut u32, status: &mut Status) {
    let carry_in = u32::from(status.cc1());
    status.set_condition(*accu1 >> 31 == 1, false);
    status.set_ov(false);
    *accu1 = *accu1 << 1 | carry_in;
}

/// `RRDA`: ACCU 1 one place right through CC1 (bit 0 to CC1, CC1 to bit 31).
#[inline]
pub fn rotate_right_via_cc1(accu1: &mut u32, status: &mut Status) {
    let carry_in = u32::from(status.cc1());
    status.set_condition(*accu1 & 1 == 1, false);
    status.set_ov(false);
    *accu1 = *accu1 >> 1 | carry_in << 31;
}

#[cfg(test)]
mod tests {
    use super::*;
    use Shift::*;

    /// ACCU 1 and CC1, CC0, OV, OS after a shift on a status with CC0, OV and OS set.
    fn run(op: Shift, count: u8, accu1: u32) -> (u32, [u8; 4]) {
        let mut status = Status::default();
        status.set_condition(false, true);
        status.set_overflow(true);
        let mut accu = accu1;
        shift(op, count, &mut accu, &mut status);
        (
            accu,
            [status.cc1(), status.cc0(), status.ov(), status.os()].map(u8::from),
        )
    }

    /// Each case: the shift, its count, ACCU 1 before, ACCU 1 after, CC1 CC0 OV OS after.
    #[test]
    fn shifts_and_rotations() {
        let cases: &[(Shift, u8, u32, u32, [u8; 4])] = &[
            // Signed shifts fill with the sign.
            (SignedInt, 3, 0xFFFF_0008, 0xFFFF_0001, [0, 0, 0, 1]),
            (SignedInt, 3, 0x0000_0004, 0x0000_0000, [1, 0, 0, 1]),
            (SignedInt, 3, 0x1234_8000, 0x1234_F000, [0, 0, 0, 1]),
            (SignedInt, 16, 0x0000_8000, 0x0000_FFFF, [1, 0, 0, 1]),
            (SignedInt, 200, 0x0000_7FFF, 0, [0, 0, 0, 1]),
            (SignedDint, 3, 0x8000_0004, 0xF000_0000, [1, 0, 0, 1]),
            (SignedDint, 32, 0x8000_0000, 0xFFFF_FFFF, [1, 0, 0, 1]),
            (SignedDint, 255, 0x7FFF_FFFF, 0, [0, 0, 0, 1]),
            // Word shifts keep ACCU 1-H.
            (LeftWord, 3, 0xABCD_3001, 0xABCD_8008, [1, 0, 0, 1]),
            (LeftWord, 3, 0xABCD_1001, 0xABCD_8008, [0, 0, 0, 1]),
            (LeftWord, 16, 0x0000_0001, 0, [1, 0, 0, 1]),
            (LeftWord, 17, 0x0000_FFFF, 0, [0, 0, 0, 1]),
            (RightWord, 3, 0xABCD_800C, 0xABCD_1001, [1, 0, 0, 1]),
            (RightWord, 16, 0x0000_8000, 0, [1, 0, 0, 1]),
            (RightWord, 255, 0xFFFF_FFFF, 0xFFFF_0000, [0, 0, 0, 1]),
            // Double-word shifts.
            (LeftDouble, 3, 0x3000_0001, 0x8000_0008, [1, 0, 0, 1]),
            (LeftDouble, 32, 0x0000_0001, 0, [1, 0, 0, 1]),
            (LeftDouble, 40, 0xFFFF_FFFF, 0, [0, 0, 0, 1]),
            (RightDouble, 3, 0x8000_000C, 0x1000_0001, [1, 0, 0, 1]),
            (RightDouble, 32, 0x8000_0000, 0, [1, 0, 0, 1]),
            (RightDouble, 33, 0xFFFF_FFFF, 0, [0, 0, 0, 1]),
            // Rotations.
            (RotateLeft, 3, 0x3888_30F0, 0xC441_8781, [1, 0, 0, 1]),
            (RotateLeft, 3, 0x1888_10F0, 0xC440_8780, [0, 0, 0, 1]),
            (RotateLeft, 32, 0x0000_0001, 0x0000_0001, [1, 0, 0, 1]),
            (RotateLeft, 33, 0x8000_0001, 0x0000_0003, [1, 0, 0, 1]),
            (RotateLeft, 64, 0x0000_0001, 0x0000_0001, [1, 0, 0, 1]),
            (RotateRight, 35, 0x0000_000C, 0x8000_0001, [1, 0, 0, 1]),
            (RotateRight, 3, 0x3888_30FC, 0x8711_061F, [1, 0, 0, 1]),
            (RotateRight, 3, 0x1888_10F8, 0x0311_021F, [0, 0, 0, 1]),
            (RotateRight, 32, 0x8000_0000, 0x8000_0000, [1, 0, 0, 1]),
        ];
        for &(op, count, before, after, status) in cases {
            let case = format!("{op:?} {count} of {before:#010X}");
            assert_eq!(run(op, count, before), (after, status), "{case}");
            let unchanged = (0x8421_8421, [0, 1, 1, 1]);
            assert_eq!(
                run(op, 0, 0x8421_8421),
                unchanged,
                "a count of 0 changes nothing"
            );
        }
    }

    #[test]
    fn rotates_through_cc1() {
        let mut status = Status::default();
        // Each step: the rotation, ACCU 1 before, ACCU 1 and CC1 after; CC1 goes round with it.
        type Rotation = fn(&mut u32, &mut Status);
        let steps: [(Rotation, u32, u32, bool); 4] = [
            (rotate_left_via_cc1, 0x8000_0000, 0, true),
            (rotate_left_via_cc1, 0x7FFF_FFF0, 0xFFFF_FFE1, false),
            (rotate_right_via_cc1, 0x0000_0001, 0, true),
            (rotate_right_via_cc1, 0x0000_0002, 0x8000_0001, false),
        ];
        for (rotate, before, after, cc1) in steps {
            let mut accu = before;
            rotate(&mut accu, &mut status);
            assert_eq!((accu, status.cc1()), (after, cc1), "{before:#010X}");
        }
        assert!(!status.cc0() && !status.ov());
    }

    #[test]
    fn the_count_without_operand_is_accu_2_ll() {
        assert_eq!(count_from_accu2(0x1234_5603), 3);
        assert_eq!(count_from_accu2(0x0000_0100), 0);
    }
}
