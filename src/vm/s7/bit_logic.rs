//! STEP 7 bit logic: what `A AN O ON X XN`, the nesting stack, `O`, `SET CLR NOT SAVE`,
//! `= S R` and `FP FN` do to /FC, RLO, STA, OR and BR ("Statement List (STL) for S7-300 and
//! S7-400 Programming", the chapter on bit logic instructions).
//!
//! BR is not in [`Status`] (see [`crate::vm::status`]): `SAVE` and the nesting stack take it
//! beside the status.
//!
//! The scans and the nesting stack are table lookups and bit operations on the status itself:
//! [`Status::scanned_step7`], [`Brackets::open_step7`](crate::vm::status::Brackets::open_step7)
//! and [`Brackets::close_step7`](crate::vm::status::Brackets::close_step7). Here are the
//! operations without an operand to scan.
//!
//! - `O` (OR of AND functions): OR = (RLO or OR) while a string is in progress, STA = 1, and
//!   the string goes on only when its RLO is 1 (/FC = RLO and /FC), so a following `A` loads.
//! - `SET`/`CLR`: RLO = STA = 1 (0), OR = 0, /FC = 0. `NOT`: RLO inverted, STA = 1.
//!   `SAVE`: BR = RLO.
//! - `=`, and `S`/`R` on a bit: OR = 0, /FC = 0, STA = the RLO (`=` under a switched-off
//!   master control relay writes 0 and STA is 0); on a timer or counter STA stays.
//! - `FP`/`FN`: the edge memory bit takes the RLO; the RLO becomes 1 on a rising (falling)
//!   edge only; STA = the RLO before, OR = 0, /FC = 1.

pub use crate::vm::status::Combination;
use crate::vm::status::Status;

/// `O` without an operand.
#[inline]
pub fn or_alone(status: &mut Status) {
    let in_string = status.first_check();
    let rlo = status.rlo();
    status.set_or_bit((rlo || status.or_bit()) && in_string);
    status.set_sta(true);
    status.set_first_check(rlo && in_string);
}

/// `SET` (`value` = 1) and `CLR` (0).
#[inline]
pub fn set_rlo(status: &mut Status, value: bool) {
    status.set_rlo(value);
    status.set_sta(value);
    status.set_or_bit(false);
    status.set_first_check(false);
}

/// `NOT`.
#[inline]
pub fn not(status: &mut Status) {
    status.set_rlo(!status.rlo());
    status.set_sta(true);
}

/// `SAVE`: the binary result `br` takes the RLO.
#[inline]
pub fn save(status: Status, br: &mut bool) {
    *br = status.rlo();
}

/// `=`, `S` and `R` on a bit: the string ends; STA is `written` (the RLO, or 0 for `=` under
/// a switched-off master control relay).
#[inline]
pub fn assigned(status: &mut Status, written: bool) {
    status.assigned_step7(written);
}

/// `S`, `R` and the other RLO-driven operations on a timer or counter: the string ends.
#[inline]
pub fn timer_counter_ended(status: &mut Status) {
    status.set_or_bit(false);
    status.set_first_check(false);
}

/// `FP` (`rising`) and `FN` with the edge memory bit's state `memory`: the new memory bit's
/// state (the RLO before), and the status as the module doc says.
#[inline]
pub fn edge(status: &mut Status, rising: bool, memory: bool) -> bool {
    let rlo = status.rlo();
    status.set_rlo(if rising {
        rlo && !memory
    } else {
        !rlo && memory
    });
    status.set_sta(rlo);
    status.set_or_bit(false);
    status.set_first_check(true);
    rlo
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vm::status::Brackets;
    use Combination::*;

    /// The low nibble of the status word: OR, STA, RLO, /FC.
    fn nibble(status: Status) -> u16 {
        status.to_word(false) & 0xF
    }

    fn with_nibble(nibble: u16) -> Status {
        Status::from_word(nibble).0
    }

    /// After `A` with a 1 and with a 0, from each OR/STA/RLO/(FC) combination.
    #[test]
    fn and_from_every_logic_state() {
        for word in 0..16 {
            let (first, rlo, or) = (word & 1 == 1, word & 2 == 2, word & 8 == 8);
            for value in [false, true] {
                let mut status = with_nibble(word);
                status.scanned_step7(And, value);
                let kept_or = or && first;
                let expected_rlo = ((rlo || !first) && value) || kept_or;
                let expected = 1
                    | u16::from(expected_rlo) << 1
                    | u16::from(value) << 2
                    | u16::from(kept_or) << 3;
                assert_eq!(nibble(status), expected, "A {value} from {word:04b}");
            }
        }
        let mut status = with_nibble(0b0000);
        status.scanned_step7(And, true);
        assert_eq!(nibble(status), 0b0111);
    }

    #[test]
    fn or_and_xor_clear_the_or_bit() {
        for word in 0..16 {
            let (first, rlo) = (word & 1 == 1, word & 2 == 2);
            let before = rlo && first;
            for (combination, combine) in [
                (Or, (|a: bool, b: bool| a || b) as fn(bool, bool) -> bool),
                (OrNot, |a, b| a || !b),
                (Xor, |a, b| a ^ b),
                (XorNot, |a, b| a ^ !b),
            ] {
                for value in [false, true] {
                    let mut status = with_nibble(word);
                    status.scanned_step7(combination, value);
                    let expected =
                        1 | u16::from(combine(before, value)) << 1 | u16::from(value) << 2;
                    assert_eq!(
                        nibble(status),
                        expected,
                        "{combination:?} {value} from {word:04b}"
                    );
                }
            }
        }
    }

    #[test]
    fn and_not_scans_the_operand_not_its_negation() {
        let mut status = Status::default();
        status.scanned_step7(AndNot, false);
        assert!(status.rlo() && !status.sta());
    }

    #[test]
    fn the_scan_keeps_the_other_bits() {
        let (mut status, br) = Status::from_word(0x1F0);
        status.scanned_step7(Xor, true);
        assert_eq!(status.to_word(br) & 0x1F0, 0x1F0);
    }

    /// Evaluates a string of STEP 7 bit logic; `(` opens with the function of the next item.
    fn rlo_of(ops: &[(&str, bool)]) -> bool {
        let mut status = Status::default();
        let mut br = false;
        let mut brackets = Brackets::default();
        for &(op, value) in ops {
            let combination = match op.trim_end_matches('(') {
                "A" => And,
                "AN" => AndNot,
                "O" => Or,
                "ON" => OrNot,
                "X" => Xor,
                "XN" => XorNot,
                ")" => {
                    assert!(brackets.close_step7(&mut status, &mut br));
                    continue;
                }
                "O_" => {
                    or_alone(&mut status);
                    continue;
                }
                _ => unreachable!("{op}"),
            };
            if op.ends_with('(') {
                assert!(brackets.open_step7(&mut status, br, combination, 7));
            } else {
                status.scanned_step7(combination, value);
            }
        }
        status.rlo()
    }

    #[test]
    fn and_before_or() {
        for bits in 0..32u8 {
            let [a, b, c, d, e] = [0, 1, 2, 3, 4].map(|i| bits >> i & 1 == 1);
            let ops = [
                ("A", a),
                ("A", b),
                ("O_", false),
                ("A", c),
                ("A", d),
                ("O", e),
            ];
            assert_eq!(rlo_of(&ops), (a && b) || (c && d) || e, "{bits:05b}");
            let ops = [
                ("A", a),
                ("O_", false),
                ("A", b),
                ("A", c),
                ("O_", false),
                ("AN", d),
            ];
            assert_eq!(rlo_of(&ops), a || (b && c) || !d, "{bits:05b}");
        }
    }

    #[test]
    fn brackets_of_every_function() {
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let inner = |open: &'static str| {
                [
                    ("A", a),
                    (open, false),
                    ("A", b),
                    ("O", c),
                    (")", false),
                    ("A", d),
                ]
            };
            assert_eq!(rlo_of(&inner("A(")), a && (b || c) && d, "A( {bits:04b}");
            assert_eq!(rlo_of(&inner("AN(")), a && !(b || c) && d, "AN( {bits:04b}");
            assert_eq!(rlo_of(&inner("O(")), (a || b || c) && d, "O( {bits:04b}");
            assert_eq!(
                rlo_of(&inner("ON(")),
                (a || !(b || c)) && d,
                "ON( {bits:04b}"
            );
            assert_eq!(rlo_of(&inner("X(")), (a ^ (b || c)) && d, "X( {bits:04b}");
            assert_eq!(
                rlo_of(&inner("XN(")),
                (a ^ !(b || c)) && d,
                "XN( {bits:04b}"
            );
        }
    }

    #[test]
    fn a_bracket_first_in_a_string_loads() {
        for value in [false, true] {
            let mut status = Status::default();
            set_rlo(&mut status, !value);
            let mut brackets = Brackets::default();
            assert!(brackets.open_step7(&mut status, false, And, 7));
            status.scanned_step7(And, value);
            assert!(brackets.close_step7(&mut status, &mut false));
            assert_eq!(status.rlo(), value);
        }
    }

    #[test]
    fn nested_brackets_after_or_alone() {
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let ops = [
                ("A", a),
                ("O_", false),
                ("A(", false),
                ("A", b),
                ("X(", false),
                ("A", c),
                (")", false),
                (")", false),
                ("AN", d),
            ];
            assert_eq!(rlo_of(&ops), a || ((b ^ c) && !d), "{bits:04b}");
        }
    }

    #[test]
    fn opening_and_closing_set_the_logic_bits() {
        let mut status = with_nibble(0b1011);
        let mut brackets = Brackets::default();
        assert!(brackets.open_step7(&mut status, false, Or, 7));
        assert_eq!(nibble(status), 0b0110, "OR 0, STA 1, RLO kept, /FC 0");
        status.scanned_step7(And, false);
        assert!(brackets.close_step7(&mut status, &mut false));
        assert_eq!(nibble(status), 0b0111, "OR 0, STA 1, RLO 1 | 0, /FC 1");
    }

    #[test]
    fn closing_restores_br_and_keeps_the_codes() {
        let mut status = Status::default();
        let mut br = true;
        save(status, &mut br);
        let mut brackets = Brackets::default();
        set_rlo(&mut status, true);
        assert!(brackets.open_step7(&mut status, br, And, 7));
        save(status, &mut br);
        status.set_condition(true, false);
        status.set_overflow(true);
        assert!(br);
        assert!(brackets.close_step7(&mut status, &mut br));
        assert!(!br, "BR as when the bracket opened");
        assert!(status.cc1() && status.ov() && status.os());
    }

    #[test]
    fn the_nesting_stack_has_a_limit() {
        let mut status = Status::default();
        let mut brackets = Brackets::default();
        for _ in 0..7 {
            assert!(brackets.open_step7(&mut status, false, Xor, 7));
        }
        assert!(!brackets.open_step7(&mut status, false, Xor, 7));
        for _ in 0..7 {
            assert!(brackets.close_step7(&mut status, &mut false));
        }
        assert!(!brackets.close_step7(&mut status, &mut false));
    }

    #[test]
    fn or_alone_bits() {
        for word in 0..16 {
            let (first, rlo, or) = (word & 1 == 1, word & 2 == 2, word & 8 == 8);
            let mut status = with_nibble(word);
            or_alone(&mut status);
            let expected = u16::from(rlo && first)
                | u16::from(rlo) << 1
                | 1 << 2
                | u16::from((rlo || or) && first) << 3;
            assert_eq!(nibble(status), expected, "O from {word:04b}");
        }
    }

    #[test]
    fn set_clr_not_save() {
        let mut status = with_nibble(0b1001);
        set_rlo(&mut status, true);
        assert_eq!(nibble(status), 0b0110);
        set_rlo(&mut status, false);
        assert_eq!(nibble(status), 0b0000);
        not(&mut status);
        assert_eq!(nibble(status), 0b0110);
        let mut br = false;
        save(status, &mut br);
        assert!(br);
        not(&mut status);
        assert_eq!(nibble(status), 0b0100);
        save(status, &mut br);
        assert!(!br);
    }

    #[test]
    fn assignment_ends_the_string() {
        let mut status = with_nibble(0b1011);
        let rlo = status.rlo();
        assigned(&mut status, rlo);
        assert_eq!(nibble(status), 0b0110, "OR 0, STA = RLO, RLO kept, /FC 0");
        let mut status = with_nibble(0b1011);
        assigned(&mut status, false);
        assert_eq!(nibble(status), 0b0010, "under a switched-off MCR");
        let mut status = with_nibble(0b1101);
        timer_counter_ended(&mut status);
        assert_eq!(nibble(status), 0b0100, "STA stays");
    }

    #[test]
    fn edges() {
        // (rising, RLO, memory) → (RLO, memory)
        for (rising, rlo, memory, result) in [
            (true, true, false, true),
            (true, true, true, false),
            (true, false, true, false),
            (true, false, false, false),
            (false, false, true, true),
            (false, false, false, false),
            (false, true, false, false),
            (false, true, true, false),
        ] {
            let mut status = Status::default();
            set_rlo(&mut status, rlo);
            status.set_or_bit(true);
            let new_memory = edge(&mut status, rising, memory);
            assert_eq!(new_memory, rlo, "{rising} {rlo} {memory}");
            assert_eq!(status.rlo(), result, "{rising} {rlo} {memory}");
            assert_eq!(
                nibble(status),
                1 | u16::from(result) << 1 | u16::from(rlo) << 2,
                "{rising} {rlo} {memory}"
            );
        }
    }
}
