//! The conditional jumps and `LOOP`, and the status conditions scanned as bit operands
//! (`A ==0`, `O OV`, …) ("Statement List (STL) for S7-300 and S7-400 Programming", the
//! chapters on jump instructions and on bit logic with the status word).
//!
//! - `JC JCN JCB JNB`: whether or not they jump, /FC = 0, OR = 0, STA = 1, RLO = 1; `JCB`/`JNB`
//!   first copy the RLO into BR.
//! - `JBI JNBI`: /FC = 0, OR = 0, STA = 1; the RLO stays.
//! - `JOS` clears OS when it jumps (it only jumps when OS is set); the other jumps on the
//!   condition codes change nothing.
//! - The status conditions read CC1/CC0, OV, OS and BR and change nothing (`A OS` leaves OS);
//!   `<>0` is CC1 or CC0, so it also holds after an unordered result, while `JN` jumps on
//!   CC1 ≠ CC0 only.
//!
//! BR is not in [`Status`] (see [`crate::rules::status`]): the functions that read or write it
//! take it beside the status.

use crate::rules::status::Status;

/// A condition of the status word, as a bit operand (`A ==0`) and as a jump condition: the
/// results of the last arithmetic or comparison (CC 1 and CC 0), overflow, stored overflow,
/// unordered, and the binary result.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Condition {
    /// `==0`: CC1 CC0 = 0 0.
    Zero,
    /// `<>0`: CC1 or CC0.
    NotZero,
    /// `>0`: CC1 CC0 = 1 0.
    Positive,
    /// `<0`: CC1 CC0 = 0 1.
    Negative,
    /// `>=0`: CC0 = 0.
    PositiveOrZero,
    /// `<=0`: CC1 = 0.
    NegativeOrZero,
    /// `UO`: CC1 CC0 = 1 1, unordered (a REAL operation with an invalid number).
    Unordered,
    /// `OV`
    Overflow,
    /// `OS`
    StoredOverflow,
    /// `BR` (German `BIE`)
    BinaryResult,
}

impl Condition {
    /// The condition's signal state, for `A`, `AN`, `O`, `ON`, `X`, `XN` with it; `br` is the
    /// binary result.
    #[inline]
    pub fn holds(self, status: Status, br: bool) -> bool {
        let (cc1, cc0) = (status.cc1(), status.cc0());
        match self {
            Condition::Zero => !cc1 && !cc0,
            Condition::NotZero => cc1 || cc0,
            Condition::Positive => cc1 && !cc0,
            Condition::Negative => !cc1 && cc0,
            Condition::PositiveOrZero => !cc0,
            Condition::NegativeOrZero => !cc1,
            Condition::Unordered => cc1 && cc0,
            Condition::Overflow => status.ov(),
            Condition::StoredOverflow => status.os(),
            Condition::BinaryResult => br,
        }
    }
}

/// The conditional jumps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Jump {
    /// `JC`
    Rlo,
    /// `JCN`
    NotRlo,
    /// `JCB`: as `JC`, saving the RLO in BR.
    RloSavingBr,
    /// `JNB`: as `JCN`, saving the RLO in BR.
    NotRloSavingBr,
    /// `JBI`
    Br,
    /// `JNBI`
    NotBr,
    /// `JO`
    Overflow,
    /// `JOS`
    StoredOverflow,
    /// `JZ`
    Zero,
    /// `JN`: CC1 ≠ CC0.
    NotZero,
    /// `JP`
    Positive,
    /// `JM`
    Minus,
    /// `JPZ`
    PositiveOrZero,
    /// `JMZ`
    MinusOrZero,
    /// `JUO`
    Unordered,
}

/// After `JC JCN JCB JNB`: a new logic string starts with RLO = 1.
#[inline(always)]
fn after_rlo_jump(status: &mut Status) {
    status.set_first_check(false);
    status.set_or_bit(false);
    status.set_sta(true);
    status.set_rlo(true);
}

/// Whether `jump` jumps, with its effect on the status and the binary result `br`.
#[inline]
pub fn taken(jump: Jump, status: &mut Status, br: &mut bool) -> bool {
    let rlo = status.rlo();
    match jump {
        Jump::Rlo | Jump::NotRlo | Jump::RloSavingBr | Jump::NotRloSavingBr => {
            if matches!(jump, Jump::RloSavingBr | Jump::NotRloSavingBr) {
                *br = rlo;
            }
            after_rlo_jump(status);
            rlo == matches!(jump, Jump::Rlo | Jump::RloSavingBr)
        }
        Jump::Br | Jump::NotBr => {
            status.set_first_check(false);
            status.set_or_bit(false);
            status.set_sta(true);
            *br == (jump == Jump::Br)
        }
        Jump::Overflow => status.ov(),
        Jump::StoredOverflow => {
            let os = status.os();
            status.set_os(false);
            os
        }
        Jump::Zero => Condition::Zero.holds(*status, *br),
        Jump::NotZero => status.cc1() != status.cc0(),
        Jump::Positive => Condition::Positive.holds(*status, *br),
        Jump::Minus => Condition::Negative.holds(*status, *br),
        Jump::PositiveOrZero => Condition::PositiveOrZero.holds(*status, *br),
        Jump::MinusOrZero => Condition::NegativeOrZero.holds(*status, *br),
        Jump::Unordered => Condition::Unordered.holds(*status, *br),
    }
}

/// `LOOP`: ACCU 1-L − 1 (modulo 2^16; ACCU 1-H stays); jumps while the result is not 0.
#[inline]
pub fn loop_taken(accu1: &mut u32) -> bool {
    let count = (*accu1 as u16).wrapping_sub(1);
    *accu1 = *accu1 & 0xFFFF_0000 | u32::from(count);
    count != 0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A status with CC1/CC0 as given and everything else clear.
    fn codes(cc1: bool, cc0: bool) -> Status {
        let mut status = Status::default();
        status.set_condition(cc1, cc0);
        status
    }

    #[test]
    fn conditions_by_condition_codes() {
        use Condition::*;
        let table = [
            // 00 (zero), 01 (negative), 10 (positive), 11 (unordered)
            (Zero, [true, false, false, false]),
            (NotZero, [false, true, true, true]),
            (Positive, [false, false, true, false]),
            (Negative, [false, true, false, false]),
            (PositiveOrZero, [true, false, true, false]),
            (NegativeOrZero, [true, true, false, false]),
            (Unordered, [false, false, false, true]),
        ];
        for (condition, expected) in table {
            let got = [(false, false), (false, true), (true, false), (true, true)]
                .map(|(cc1, cc0)| condition.holds(codes(cc1, cc0), false));
            assert_eq!(got, expected, "{condition:?}");
        }
    }

    #[test]
    fn overflow_conditions_read_without_clearing() {
        let mut status = Status::default();
        status.set_overflow(true);
        assert!(Condition::Overflow.holds(status, false));
        assert!(Condition::StoredOverflow.holds(status, false));
        assert!(Condition::BinaryResult.holds(status, true));
        assert!(!Condition::BinaryResult.holds(status, false));
        assert!(status.os(), "A OS leaves OS");
        status.set_ov(false);
        assert!(
            !Condition::Overflow.holds(status, false)
                && Condition::StoredOverflow.holds(status, false)
        );
    }

    /// /FC, RLO, STA, OR, BR.
    fn logic_bits(status: Status, br: bool) -> [u8; 5] {
        [
            status.first_check(),
            status.rlo(),
            status.sta(),
            status.or_bit(),
            br,
        ]
        .map(u8::from)
    }

    fn string_with_rlo(rlo: bool) -> Status {
        let mut status = Status::default();
        status.set_first_check(true);
        status.set_or_bit(true);
        status.set_rlo(rlo);
        status
    }

    #[test]
    fn jumps_on_the_rlo_start_a_new_string() {
        for (jump, rlo, jumps) in [
            (Jump::Rlo, true, true),
            (Jump::Rlo, false, false),
            (Jump::NotRlo, false, true),
            (Jump::NotRlo, true, false),
        ] {
            let mut status = string_with_rlo(rlo);
            let mut br = false;
            assert_eq!(taken(jump, &mut status, &mut br), jumps, "{jump:?} {rlo}");
            assert_eq!(logic_bits(status, br), [0, 1, 1, 0, 0], "{jump:?} {rlo}");
        }
    }

    #[test]
    fn jcb_and_jnb_save_the_rlo_in_br() {
        for (jump, rlo, jumps) in [
            (Jump::RloSavingBr, true, true),
            (Jump::RloSavingBr, false, false),
            (Jump::NotRloSavingBr, false, true),
            (Jump::NotRloSavingBr, true, false),
        ] {
            let mut status = string_with_rlo(rlo);
            let mut br = !rlo;
            assert_eq!(taken(jump, &mut status, &mut br), jumps, "{jump:?} {rlo}");
            assert_eq!(
                logic_bits(status, br),
                [0, 1, 1, 0, u8::from(rlo)],
                "{jump:?} {rlo}"
            );
        }
    }

    #[test]
    fn jumps_on_br_keep_the_rlo() {
        for (jump, br, jumps) in [
            (Jump::Br, true, true),
            (Jump::Br, false, false),
            (Jump::NotBr, false, true),
            (Jump::NotBr, true, false),
        ] {
            let mut status = string_with_rlo(false);
            let mut kept = br;
            assert_eq!(taken(jump, &mut status, &mut kept), jumps, "{jump:?} {br}");
            assert_eq!(
                logic_bits(status, kept),
                [0, 0, 1, 0, u8::from(br)],
                "{jump:?} {br}"
            );
        }
    }

    #[test]
    fn jumps_on_the_condition_codes() {
        let cases = [
            (Jump::Zero, [true, false, false, false]),
            (Jump::NotZero, [false, true, true, false]),
            (Jump::Positive, [false, false, true, false]),
            (Jump::Minus, [false, true, false, false]),
            (Jump::PositiveOrZero, [true, false, true, false]),
            (Jump::MinusOrZero, [true, true, false, false]),
            (Jump::Unordered, [false, false, false, true]),
        ];
        for (jump, expected) in cases {
            let got =
                [(false, false), (false, true), (true, false), (true, true)].map(|(cc1, cc0)| {
                    let mut status = codes(cc1, cc0);
                    let before = status;
                    let mut br = true;
                    let jumps = taken(jump, &mut status, &mut br);
                    assert_eq!((status, br), (before, true), "{jump:?} changes nothing");
                    jumps
                });
            assert_eq!(got, expected, "{jump:?}");
        }
    }

    #[test]
    fn jo_keeps_os_and_jos_clears_it() {
        let mut status = Status::default();
        let br = &mut false;
        assert!(!taken(Jump::Overflow, &mut status, br));
        assert!(!taken(Jump::StoredOverflow, &mut status, br));
        status.set_overflow(true);
        assert!(taken(Jump::Overflow, &mut status, br));
        assert!(status.os());
        assert!(taken(Jump::StoredOverflow, &mut status, br));
        assert!(!status.os() && status.ov(), "JOS clears OS only");
        assert!(!taken(Jump::StoredOverflow, &mut status, br));
    }

    #[test]
    fn loop_counts_down_accu_1_low() {
        let mut accu = 0xABCD_0003;
        assert!(loop_taken(&mut accu));
        assert_eq!(accu, 0xABCD_0002);
        assert!(loop_taken(&mut accu));
        assert!(!loop_taken(&mut accu));
        assert_eq!(accu, 0xABCD_0000);
        assert!(loop_taken(&mut accu), "0 − 1 = 65535 goes on");
        assert_eq!(accu, 0xABCD_FFFF);
    }
}
