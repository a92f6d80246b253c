//! The status of a processing level: the RLO with its first-check and OR bits and the condition
//! codes, packed in one byte so the execution loop keeps it in a register; and the bracket stack.
//!
//! The RLO is the value of the logic string so far. `A`/`O` with an operand combine into it, the
//! first operation of a string loads it (first check). `O` alone ORs AND functions: it keeps the
//! string so far in the OR bit and starts a new AND function. `=`, `S`, `R` end the string but
//! keep the RLO for further assignments.
//!
//! STEP 7's binary result BR is not in the byte: it is `LevelState::br`, beside the status, and
//! the STEP 7 operations that read or write it take it as an argument. A ninth bit would widen
//! the status the STEP 5 loop keeps in a register, and that loop never uses it.
//! [`Status::to_word`] and [`Status::from_word`] give the STEP 7 status word (`L STW`, `T STW`)
//! with BR as its bit 8.

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

/// The STEP 7 status word's bits, in its order (`L STW`): /FC, RLO, STA, OR, OS, OV, CC0, CC1
/// are bits 0 to 7, BR is bit 8 ("Statement List (STL) for S7-300 and S7-400 Programming", the
/// status word in the appendix on programming examples and the chapter on bit logic).
const WORD_ORDER: [u8; 8] = [FIRST_CHECK_DONE, RLO, STA, OR_BIT, OS, OV, CC0, CC1];
const WORD_BR: u16 = 1 << 8;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
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

    pub fn set_rlo(&mut self, value: bool) {
        self.put(RLO, value);
    }
    pub fn set_first_check(&mut self, value: bool) {
        self.put(FIRST_CHECK_DONE, value);
    }
    pub fn set_or_bit(&mut self, value: bool) {
        self.put(OR_BIT, value);
    }
    pub fn set_sta(&mut self, value: bool) {
        self.put(STA, value);
    }
    pub fn set_ov(&mut self, value: bool) {
        self.put(OV, value);
    }
    pub fn set_os(&mut self, value: bool) {
        self.put(OS, value);
    }

    /// The STEP 7 status word of this status and the binary result `br`: /FC, RLO, STA, OR,
    /// OS, OV, CC0, CC1, BR in bits 0 to 8.
    pub fn to_word(self, br: bool) -> u16 {
        let word = WORD_ORDER
            .iter()
            .enumerate()
            .fold(0, |word, (index, &bit)| {
                word | u16::from(self.get(bit)) << index
            });
        word | if br { WORD_BR } else { 0 }
    }

    /// The status and the binary result BR from a STEP 7 status word's bits 0 to 8; the bits
    /// above are ignored.
    pub fn from_word(word: u16) -> (Status, bool) {
        let bits = WORD_ORDER
            .iter()
            .enumerate()
            .filter(|&(index, _)| word >> index & 1 == 1)
            .fold(0, |bits, (_, &bit)| bits | bit);
        (Status { bits }, word & WORD_BR != 0)
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

/// STEP 5's `A AN O ON` with a bit operand (the first four [`Combination`]s).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum Logic {
    And,
    AndNot,
    Or,
    OrNot,
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

/// How a scanned bit, or a closed bracket's result, combines with the RLO. STEP 5 uses the
/// first four (its table is [`Logic`]'s), STEP 7 all six.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[repr(u8)]
pub enum Combination {
    #[default]
    And,
    AndNot,
    Or,
    OrNot,
    Xor,
    XorNot,
}

impl Combination {
    /// Every combination, in the order of their codes (`as u8`).
    pub const ALL: [Combination; 6] = [
        Combination::And,
        Combination::AndNot,
        Combination::Or,
        Combination::OrNot,
        Combination::Xor,
        Combination::XorNot,
    ];
}

/// STEP 7's scan of a bit operand with the signal state `value` ("Statement List (STL) for
/// S7-300 and S7-400 Programming", the chapter on bit logic): STA = `value`, /FC = 1. `A`/`AN`
/// keep the OR bit within a string and clear it at the first check; `O ON X XN` clear it.
const fn step7_scan(bits: u8, combination: Combination, value: bool) -> u8 {
    let first_check_done = bits & FIRST_CHECK_DONE != 0;
    let rlo = bits & RLO != 0;
    let or_bit = bits & OR_BIT != 0;
    let (rlo, or_bit) = match combination {
        Combination::And | Combination::AndNot => {
            let operand = value ^ matches!(combination, Combination::AndNot);
            let kept_or = or_bit & first_check_done;
            (((rlo | !first_check_done) & operand) | kept_or, kept_or)
        }
        Combination::Or => ((rlo & first_check_done) | value, false),
        Combination::OrNot => ((rlo & first_check_done) | !value, false),
        Combination::Xor => ((rlo & first_check_done) ^ value, false),
        Combination::XorNot => ((rlo & first_check_done) ^ !value, false),
    };
    bits & !(RLO | OR_BIT | STA)
        | FIRST_CHECK_DONE
        | rlo as u8
        | if or_bit { OR_BIT } else { 0 }
        | if value { STA } else { 0 }
}

/// The status after each of STEP 7's scans, by [`Combination`] and `status << 1 | value`; eight
/// rows (the last two `A`'s), so a combination's code masked to three bits needs no check.
static STEP7_SCANNED: [[u8; 512]; 8] = {
    let mut tables = [[0u8; 512]; 8];
    let combinations = Combination::ALL;
    let mut kind = 0;
    while kind < 8 {
        let mut index = 0;
        while index < 512 {
            let bits = (index >> 1) as u8;
            let combination = if kind < 6 {
                combinations[kind]
            } else {
                Combination::And
            };
            tables[kind][index] = step7_scan(bits, combination, index & 1 != 0);
            index += 1;
        }
        kind += 1;
    }
    tables
};

impl Status {
    /// The status as one byte, for native code that keeps it in a register.
    pub fn bits(self) -> u8 {
        self.bits
    }

    pub fn from_bits(bits: u8) -> Status {
        Status { bits }
    }

    /// The table [`Status::scanned`] looks `logic` up in, by `status << 1 | signal state`.
    pub fn scan_table(logic: Logic) -> &'static [u8; 512] {
        &SCANNED[logic as usize]
    }

    /// The table [`Status::scanned_step7`] looks `combination` up in.
    pub fn step7_scan_table(combination: Combination) -> &'static [u8; 512] {
        &STEP7_SCANNED[combination as usize]
    }

    /// [`Status::scanned_step7`] by the combination's code (`as u8`), as packed ops carry it.
    #[inline(always)]
    pub fn scanned_step7_code(&mut self, code: u8, value: bool) {
        let index = usize::from(self.bits) << 1 | usize::from(value);
        self.bits = STEP7_SCANNED[usize::from(code & 7)][index];
    }

    /// STEP 7's `=`, `S`, `R`: STA takes the RLO written, the string ends (OR and /FC cleared).
    #[inline(always)]
    pub fn assigned_step7(&mut self, written: bool) {
        self.bits = self.bits & !(STA | OR_BIT | FIRST_CHECK_DONE) | if written { STA } else { 0 };
    }

    /// STEP 7's `A AN O ON X XN` with a bit operand whose signal state is `value`, in one
    /// table lookup.
    #[inline(always)]
    pub fn scanned_step7(&mut self, combination: Combination, value: bool) {
        let index = usize::from(self.bits) << 1 | usize::from(value);
        self.bits = STEP7_SCANNED[combination as usize][index];
    }
}

/// One open bracket: the status before it, how its result combines, and (STEP 7) the binary
/// result BR before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Bracket {
    pub status: Status,
    pub function: Combination,
    pub br: bool,
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
        let function = if or {
            Combination::Or
        } else {
            Combination::And
        };
        self.push(*status, function, false);
        status.end_string();
        true
    }

    #[inline(always)]
    fn push(&mut self, status: Status, function: Combination, br: bool) {
        self.stack[usize::from(self.depth)] = Bracket {
            status,
            function,
            br,
        };
        self.depth += 1;
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
        if outer.function == Combination::Or {
            status.or(inner)
        } else {
            status.and(inner)
        }
        true
    }

    /// STEP 7's `A( AN( O( ON( X( XN(`: the entry keeps /FC, RLO, OR and BR (`br`) with the
    /// function; then OR = 0, STA = 1, /FC = 0 and the RLO stays. `false` when the stack is
    /// full.
    pub fn open_step7(
        &mut self,
        status: &mut Status,
        br: bool,
        function: Combination,
        limit: u8,
    ) -> bool {
        if self.depth >= limit.min(MAX_BRACKETS as u8) {
            return false;
        }
        self.push(*status, function, br);
        status.bits = status.bits & !(OR_BIT | FIRST_CHECK_DONE) | STA;
        true
    }

    /// STEP 7's `)`: the bracket's RLO combines with the entry's RLO (and, for `A(`/`AN(`, its
    /// OR bit) by the entry's function, as a scan would; STA = 1, /FC = 1, `br` as in the
    /// entry. The condition codes and overflow bits stay as the bracket left them. `false`
    /// when none is open.
    pub fn close_step7(&mut self, status: &mut Status, br: &mut bool) -> bool {
        if self.depth == 0 {
            return false;
        }
        self.depth -= 1;
        let outer = self.stack[usize::from(self.depth)];
        let combined = step7_scan(outer.status.bits, outer.function, status.rlo());
        let logic = RLO | OR_BIT | FIRST_CHECK_DONE;
        status.bits = status.bits & !logic | combined & logic | STA;
        *br = outer.br;
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

    #[test]
    fn the_status_word_has_the_step_7_bit_order() {
        let mut status = Status::default();
        status.set_first_check(true);
        assert_eq!(status.to_word(false), 0x001);
        status = Status::default();
        status.set_rlo(true);
        assert_eq!(status.to_word(false), 0x002);
        status = Status::default();
        status.set_sta(true);
        status.set_or_bit(true);
        assert_eq!(status.to_word(false), 0x00C);
        status = Status::default();
        status.set_overflow(true);
        assert_eq!(status.to_word(false), 0x030, "OV sets OS");
        status = Status::default();
        status.set_condition(true, false);
        assert_eq!(status.to_word(false), 0x080);
        status.set_condition(false, true);
        assert_eq!(status.to_word(false), 0x040);
        assert_eq!(Status::default().to_word(true), 0x100, "BR");
    }

    #[test]
    fn the_status_word_round_trips() {
        for word in 0..=0x1FF {
            let (status, br) = Status::from_word(word);
            assert_eq!(status.to_word(br), word);
        }
        let (status, br) = Status::from_word(0xFE00);
        assert_eq!(status.to_word(br), 0, "bits 9 to 15 do not exist");
    }

    /// BR lives beside the one-byte status: a bracket keeps it, and `L STW`/`T STW` carry it
    /// as bit 8 of the status word.
    #[test]
    fn br_survives_brackets_and_the_status_word_beside_a_one_byte_status() {
        assert_eq!(std::mem::size_of::<Status>(), 1);
        for br_before in [false, true] {
            let mut status = Status::default();
            let mut br = br_before;
            let mut brackets = Brackets::default();
            assert!(brackets.open_step7(&mut status, br, Combination::And, 7));
            br = !br_before;
            status.scanned_step7(Combination::Or, true);
            assert!(brackets.close_step7(&mut status, &mut br));
            assert_eq!(br, br_before, "`)` gives BR back as `A(` found it");

            let word = status.to_word(br);
            assert_eq!(word & 0x100 != 0, br_before, "L STW: BR is bit 8");
            let (loaded, loaded_br) = Status::from_word(word);
            assert_eq!((loaded, loaded_br), (status, br_before), "T STW");
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
