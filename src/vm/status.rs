//! The status of a processing level: the RLO with its first-check and OR bits, the condition
//! codes, and the bracket stack.
//!
//! The RLO is the value of the logic string so far. `A`/`O` with an operand combine into it, the
//! first operation of a string loads it (first check). `O` alone ORs AND functions: it keeps the
//! string so far in the OR bit and starts a new AND function. `=`, `S`, `R` end the string but
//! keep the RLO for further assignments.

/// One open bracket: what was before it, and how its result combines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Bracket {
    pub rlo: bool,
    pub first_check_done: bool,
    pub or_bit: bool,
    pub or: bool,
}

pub const MAX_BRACKETS: usize = 8;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Status {
    pub rlo: bool,
    /// A logic string is in progress (the next `A`/`O` combines instead of loading).
    pub first_check_done: bool,
    pub or_bit: bool,
    pub cc1: bool,
    pub cc0: bool,
    pub ov: bool,
    /// Overflow, stored until a jump on it.
    pub os: bool,
    pub brackets: [Bracket; MAX_BRACKETS],
    pub depth: u8,
}

impl Status {
    #[inline(always)]
    pub fn and(&mut self, value: bool) {
        self.rlo = ((self.rlo | !self.first_check_done) & value) | self.or_bit;
        self.first_check_done = true;
    }

    #[inline(always)]
    pub fn or(&mut self, value: bool) {
        let before = if self.first_check_done { self.rlo } else { self.or_bit };
        self.rlo = before | value;
        self.or_bit = false;
        self.first_check_done = true;
    }

    /// `O` without an operand: OR of AND functions.
    #[inline(always)]
    pub fn or_alone(&mut self) {
        if self.first_check_done {
            self.or_bit = self.rlo;
        }
        self.first_check_done = false;
    }

    /// `=`, `S`, `R` and the timer and counter operations end the logic string.
    #[inline(always)]
    pub fn end_string(&mut self) {
        self.first_check_done = false;
        self.or_bit = false;
    }

    /// An operation that forms the RLO on its own (comparison, bit test).
    #[inline(always)]
    pub fn load(&mut self, value: bool) {
        self.rlo = value;
        self.or_bit = false;
        self.first_check_done = true;
    }

    /// After `JU`/`JC`, `BEC` and block ends the RLO is 1 and a new string starts.
    #[inline(always)]
    pub fn after_jump(&mut self) {
        self.rlo = true;
        self.end_string();
    }

    /// Opens a bracket; `false` when the bracket stack is full.
    pub fn open_bracket(&mut self, or: bool, limit: u8) -> bool {
        if self.depth >= limit.min(MAX_BRACKETS as u8) {
            return false;
        }
        self.brackets[usize::from(self.depth)] =
            Bracket { rlo: self.rlo, first_check_done: self.first_check_done, or_bit: self.or_bit, or };
        self.depth += 1;
        self.end_string();
        true
    }

    /// Closes a bracket and combines its result; `false` when none is open.
    pub fn close_bracket(&mut self) -> bool {
        if self.depth == 0 {
            return false;
        }
        self.depth -= 1;
        let inner = self.rlo;
        let outer = self.brackets[usize::from(self.depth)];
        self.rlo = outer.rlo;
        self.first_check_done = outer.first_check_done;
        self.or_bit = outer.or_bit;
        if outer.or { self.or(inner) } else { self.and(inner) }
        true
    }

    /// Condition codes from a 16-bit fixed-point result.
    pub fn set_cc_from(&mut self, result: i16) {
        self.cc1 = result > 0;
        self.cc0 = result < 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(ops: &[(&str, bool)]) -> bool {
        let mut status = Status::default();
        for (op, value) in ops {
            match *op {
                "A" => status.and(*value),
                "AN" => status.and(!value),
                "O" => status.or(*value),
                "ON" => status.or(!value),
                "O_" => status.or_alone(),
                "A(" => assert!(status.open_bracket(false, 7)),
                "O(" => assert!(status.open_bracket(true, 7)),
                ")" => assert!(status.close_bracket()),
                "=" => status.end_string(),
                _ => unreachable!(),
            }
        }
        status.rlo
    }

    #[test]
    fn first_check_loads_after_assignment() {
        let mut status = Status::default();
        status.and(true);
        status.end_string();
        status.and(false);
        assert!(!status.rlo, "a new string starts after =");
        status.end_string();
        status.or(true);
        assert!(status.rlo);
    }

    #[test]
    fn or_alone_is_and_before_or() {
        // a & b | c & d
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let rlo = string(&[("A", a), ("A", b), ("O_", false), ("A", c), ("A", d)]);
            assert_eq!(rlo, a & b | c & d, "{a} {b} {c} {d}");
        }
    }

    #[test]
    fn nested_brackets() {
        // a & (b | (c & d))
        for bits in 0..16u8 {
            let [a, b, c, d] = [0, 1, 2, 3].map(|i| bits >> i & 1 == 1);
            let rlo = string(&[("A", a), ("A(", false), ("O", b), ("O(", false), ("A", c), ("A", d), (")", false), (")", false)]);
            assert_eq!(rlo, a & (b | (c & d)), "{a} {b} {c} {d}");
        }
    }

    #[test]
    fn bracket_stack_is_limited() {
        let mut status = Status::default();
        for _ in 0..7 {
            assert!(status.open_bracket(false, 7));
        }
        assert!(!status.open_bracket(false, 7));
        let mut empty = Status::default();
        assert!(!empty.close_bracket());
    }
}
