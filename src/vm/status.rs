//! The status of a processing level: the RLO with its first-check and OR bits and the condition
//! codes, packed in one byte so the execution loop keeps it in a register; and the bracket stack.
//!
//! The RLO is the value of the logic string so far. `A`/`O` with an operand combine into it, the
//! first operation of a string loads it (first check). `O` alone ORs AND functions: it keeps the
//! string so far in the OR bit and starts a new AND function. `=`, `S`, `R` end the string but
//! keep the RLO for further assignments.

use crate::compiler::bytecode::Logic;

const RLO: u8 = 1;
/// A logic string is in progress: the next `A`/`O` combines instead of loading.
const FIRST_CHECK_DONE: u8 = 2;
const OR_BIT: u8 = 4;
const CC1: u8 = 8;
const CC0: u8 = 16;
const OV: u8 = 32;
/// Overflow, stored until a jump on it.
const OS: u8 = 64;
/// STA: the signal state of the last bit operand scanned.
const STA: u8 = 128;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Status {
    bits: u8,
}

impl Status {
    #[inline(always)]
    fn get(self, bit: u8) -> bool {
        self.bits & bit != 0
    }

    #[inline(always)]
    fn put(&mut self, bit: u8, value: bool) {
        self.bits = self.bits & !bit | if value { bit } else { 0 };
    }

    pub fn rlo(self) -> bool {
        self.get(RLO)
    }
    pub fn cc1(self) -> bool {
        self.get(CC1)
    }
    pub fn cc0(self) -> bool {
        self.get(CC0)
    }
    pub fn ov(self) -> bool {
        self.get(OV)
    }
    pub fn os(self) -> bool {
        self.get(OS)
    }
    pub fn sta(self) -> bool {
        self.get(STA)
    }
    /// The first-check bit: a logic string is in progress.
    pub fn first_check(self) -> bool {
        self.get(FIRST_CHECK_DONE)
    }
    pub fn or_bit(self) -> bool {
        self.get(OR_BIT)
    }

    pub fn set_condition(&mut self, cc1: bool, cc0: bool) {
        self.put(CC1, cc1);
        self.put(CC0, cc0);
    }

    /// Sets OV, and OS with it.
    pub fn set_overflow(&mut self, ov: bool) {
        self.put(OV, ov);
        if ov {
            self.bits |= OS;
        }
    }

    #[inline(always)]
    pub fn and(&mut self, value: bool) {
        self.bits = and(self.bits, value);
    }

    #[inline(always)]
    pub fn or(&mut self, value: bool) {
        self.bits = or(self.bits, value);
    }

    /// `A`, `AN`, `O`, `ON` with a bit operand whose signal state is `value`: the scan (STA)
    /// and the combination in one table lookup, so the loop's bit logic does not branch.
    #[inline(always)]
    pub fn scanned(&mut self, logic: Logic, value: bool) {
        let index = usize::from(self.bits) << 1 | usize::from(value);
        self.bits = SCANNED[logic as usize][index];
    }

    /// `O` without an operand: OR of AND functions.
    #[inline(always)]
    pub fn or_alone(&mut self) {
        if self.get(FIRST_CHECK_DONE) {
            self.put(OR_BIT, self.get(RLO));
        }
        self.bits &= !FIRST_CHECK_DONE;
    }

    /// `=`, `S`, `R` and the timer and counter operations end the logic string.
    #[inline(always)]
    pub fn end_string(&mut self) {
        self.bits &= !(FIRST_CHECK_DONE | OR_BIT);
    }

    /// An operation that forms the RLO on its own (comparison, bit test).
    #[inline(always)]
    pub fn load(&mut self, value: bool) {
        self.bits = self.bits & !(RLO | OR_BIT) | FIRST_CHECK_DONE | u8::from(value);
    }

    /// After `JU`/`JC`, `BEC` and block ends the RLO is 1 and a new string starts.
    #[inline(always)]
    pub fn after_jump(&mut self) {
        self.bits = self.bits & !(FIRST_CHECK_DONE | OR_BIT) | RLO;
    }

    /// Condition codes from a 16-bit fixed-point result.
    pub fn set_cc_from(&mut self, result: i16) {
        self.set_condition(result > 0, result < 0);
    }

    /// CC1/CC0 from a fixed-point result and OV (with OS) in one write.
    #[inline(always)]
    pub fn set_result(&mut self, result: i16, overflow: bool) {
        let codes = if result > 0 { CC1 } else { 0 } | if result < 0 { CC0 } else { 0 };
        let flow = if overflow { OV | OS } else { 0 };
        self.bits = self.bits & !(CC1 | CC0 | OV) | codes | flow;
    }
}

const fn and(bits: u8, value: bool) -> u8 {
    let rlo = bits & RLO != 0;
    let first = bits & FIRST_CHECK_DONE == 0;
    let combined = (rlo | first) & value | (bits & OR_BIT != 0);
    bits & !RLO | FIRST_CHECK_DONE | combined as u8
}

const fn or(bits: u8, value: bool) -> u8 {
    let before = if bits & FIRST_CHECK_DONE != 0 {
        bits & RLO != 0
    } else {
        bits & OR_BIT != 0
    };
    bits & !(RLO | OR_BIT) | FIRST_CHECK_DONE | (before | value) as u8
}

/// The status after each of [`Logic`]'s operations, by `status << 1 | signal state`.
static SCANNED: [[u8; 512]; 4] = {
    let mut tables = [[0u8; 512]; 4];
    let mut index = 0;
    while index < 512 {
        let value = index & 1 != 0;
        let bits = (index >> 1) as u8 & !STA | if value { STA } else { 0 };
        tables[Logic::And as usize][index] = and(bits, value);
        tables[Logic::AndNot as usize][index] = and(bits, !value);
        tables[Logic::Or as usize][index] = or(bits, value);
        tables[Logic::OrNot as usize][index] = or(bits, !value);
        index += 1;
    }
    tables
};

/// One open bracket: the status before it, and how its result combines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Bracket {
    pub status: Status,
    pub or: bool,
}

pub const MAX_BRACKETS: usize = 8;

/// The bracket stack of a processing level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Brackets {
    stack: [Bracket; MAX_BRACKETS],
    depth: u8,
}

impl Brackets {
    /// Opens a bracket; `false` when the stack is full.
    pub fn open(&mut self, status: &mut Status, or: bool, limit: u8) -> bool {
        if self.depth >= limit.min(MAX_BRACKETS as u8) {
            return false;
        }
        self.stack[usize::from(self.depth)] = Bracket {
            status: *status,
            or,
        };
        self.depth += 1;
        status.end_string();
        true
    }

    /// Closes a bracket and combines its result; `false` when none is open.
    pub fn close(&mut self, status: &mut Status) -> bool {
        if self.depth == 0 {
            return false;
        }
        self.depth -= 1;
        let inner = status.rlo();
        let outer = self.stack[usize::from(self.depth)];
        let codes = *status;
        *status = outer.status;
        status.set_condition(codes.cc1(), codes.cc0());
        if outer.or {
            status.or(inner)
        } else {
            status.and(inner)
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scan_tables_are_the_scan_then_the_combination() {
        for bits in 0..=u8::MAX {
            for value in [false, true] {
                let scanned = Status {
                    bits: bits & !STA | if value { STA } else { 0 },
                };
                for (logic, combined) in [
                    (Logic::And, and(scanned.bits, value)),
                    (Logic::AndNot, and(scanned.bits, !value)),
                    (Logic::Or, or(scanned.bits, value)),
                    (Logic::OrNot, or(scanned.bits, !value)),
                ] {
                    let mut status = Status { bits };
                    status.scanned(logic, value);
                    assert_eq!(status.bits, combined, "{logic:?} {value} on {bits:#010b}");
                    assert_eq!(status.sta(), value);
                }
            }
        }
    }

    fn string(ops: &[(&str, bool)]) -> bool {
        let mut status = Status::default();
        let mut brackets = Brackets::default();
        for (op, value) in ops {
            match *op {
                "A" => status.scanned(Logic::And, *value),
                "AN" => status.scanned(Logic::AndNot, *value),
                "O" => status.scanned(Logic::Or, *value),
                "ON" => status.scanned(Logic::OrNot, *value),
                "O_" => status.or_alone(),
                "A(" => assert!(brackets.open(&mut status, false, 7)),
                "O(" => assert!(brackets.open(&mut status, true, 7)),
                ")" => assert!(brackets.close(&mut status)),
                "=" => status.end_string(),
                _ => unreachable!(),
            }
        }
        status.rlo()
    }

    #[test]
    fn first_check_loads_after_assignment() {
        let mut status = Status::default();
        status.and(true);
        status.end_string();
        status.and(false);
        assert!(!status.rlo(), "a new string starts after =");
        status.end_string();
        status.or(true);
        assert!(status.rlo());
    }

    #[test]
    fn rlo_is_kept_for_further_assignments() {
        let mut status = Status::default();
        status.and(true);
        status.end_string();
        assert!(status.rlo(), "= Q 4.0 / = Q 4.1 both get the RLO");
    }

    #[test]
    fn or_alone_is_and_before_or() {
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let rlo = string(&[("A", a), ("A", b), ("O_", false), ("A", c), ("A", d)]);
            assert_eq!(rlo, a & b | c & d, "{a} {b} {c} {d}");
        }
    }

    #[test]
    fn or_with_operand_combines_left_to_right() {
        for bits in 0..8u8 {
            let [a, b, c] = [0, 1, 2].map(|i| bits >> i & 1 == 1);
            assert_eq!(string(&[("A", a), ("O", b), ("A", c)]), (a | b) & c);
            assert_eq!(string(&[("ON", a), ("AN", b)]), !a & !b);
        }
    }

    #[test]
    fn nested_brackets() {
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let rlo = string(&[
                ("A", a),
                ("A(", false),
                ("O", b),
                ("O(", false),
                ("A", c),
                ("A", d),
                (")", false),
                (")", false),
            ]);
            assert_eq!(rlo, a & (b | (c & d)), "{a} {b} {c} {d}");
        }
    }

    #[test]
    fn bracket_stack_is_limited() {
        let mut status = Status::default();
        let mut brackets = Brackets::default();
        for _ in 0..7 {
            assert!(brackets.open(&mut status, false, 7));
        }
        assert!(!brackets.open(&mut status, false, 7));
        assert!(!Brackets::default().close(&mut status));
    }
}
