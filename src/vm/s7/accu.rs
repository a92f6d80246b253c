//! The accumulator operations `TAK PUSH POP ENT LEAVE INC DEC` ("Statement List (STL) for
//! S7-300 and S7-400 Programming", the chapter on accumulator instructions). None of them
//! changes the status.
//!
//! On a CPU with four accumulators `PUSH` and `POP` move the whole stack, `ENT` and `LEAVE`
//! move ACCU 2 to 4; the two-operand arithmetic (`+I` … `MOD`, `+R` … `/R`) ends with
//! [`leave`] there. With two accumulators `ENT` and `LEAVE` do not exist.

/// The accumulator count of the CPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accus {
    Two,
    Four,
}

/// `TAK`: ACCU 1 and ACCU 2 exchange.
#[inline]
pub fn tak(accu1: &mut u32, accu2: &mut u32) {
    std::mem::swap(accu1, accu2);
}

/// `PUSH`: ACCU 1 to ACCU 2 (four: ACCU 3 to 4 and 2 to 3 first); ACCU 1 stays.
#[inline]
pub fn push(accus: Accus, accu1: u32, accu2: &mut u32, accu3: &mut u32, accu4: &mut u32) {
    if accus == Accus::Four {
        *accu4 = *accu3;
        *accu3 = *accu2;
    }
    *accu2 = accu1;
}

/// `POP`: ACCU 2 to ACCU 1 (four: then ACCU 3 to 2 and 4 to 3); ACCU 4 (or ACCU 2) stays.
#[inline]
pub fn pop(accus: Accus, accu1: &mut u32, accu2: &mut u32, accu3: &mut u32, accu4: u32) {
    *accu1 = *accu2;
    if accus == Accus::Four {
        leave(accu2, accu3, accu4);
    }
}

/// `ENT`: ACCU 3 to ACCU 4, ACCU 2 to ACCU 3 (a following `L` then fills ACCU 1 and 2).
#[inline]
pub fn enter(accu2: u32, accu3: &mut u32, accu4: &mut u32) {
    *accu4 = *accu3;
    *accu3 = accu2;
}

/// `LEAVE`, and the end of the two-operand arithmetic with four accumulators: ACCU 3 to
/// ACCU 2, ACCU 4 to ACCU 3; ACCU 4 stays.
#[inline]
pub fn leave(accu2: &mut u32, accu3: &mut u32, accu4: u32) {
    *accu2 = *accu3;
    *accu3 = accu4;
}

/// `INC n`: ACCU 1-LL + n, modulo 256; the rest of ACCU 1 stays.
#[inline]
pub fn increment(accu1: &mut u32, n: u8) {
    *accu1 = *accu1 & 0xFFFF_FF00 | u32::from((*accu1 as u8).wrapping_add(n));
}

/// `DEC n`: ACCU 1-LL − n, modulo 256; the rest of ACCU 1 stays.
#[inline]
pub fn decrement(accu1: &mut u32, n: u8) {
    *accu1 = *accu1 & 0xFFFF_FF00 | u32::from((*accu1 as u8).wrapping_sub(n));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tak_exchanges() {
        let (mut a, mut b) = (0x0123_4567, 0x09AB_CDEF);
        tak(&mut a, &mut b);
        assert_eq!((a, b), (0x09AB_CDEF, 0x0123_4567));
    }

    /// ACCU 1 to 4 after a push and after a pop of `[1, 2, 3, 4]`, with two and four accus.
    #[test]
    fn push_and_pop() {
        for (accus, pushed, popped) in [
            (Accus::Two, [1, 1, 3, 4], [2, 2, 3, 4]),
            (Accus::Four, [1, 1, 2, 3], [2, 3, 4, 4]),
        ] {
            let [a1, mut a2, mut a3, mut a4] = [1, 2, 3, 4];
            push(accus, a1, &mut a2, &mut a3, &mut a4);
            assert_eq!([a1, a2, a3, a4], pushed, "push, {accus:?}");
            let [mut a1, mut a2, mut a3, a4] = [1, 2, 3, 4];
            pop(accus, &mut a1, &mut a2, &mut a3, a4);
            assert_eq!([a1, a2, a3, a4], popped, "pop, {accus:?}");
        }
    }

    /// `L 1337  L 31337  ENT  L 1  ENT  L 2`, then `LEAVE` three times.
    #[test]
    fn enter_and_leave() {
        let load = |value: u32, a: &mut [u32; 4]| {
            a[1] = a[0];
            a[0] = value;
        };
        let mut a = [0; 4];
        load(1337, &mut a);
        load(31337, &mut a);
        let [_, a2, a3, a4] = &mut a;
        enter(*a2, a3, a4);
        load(1, &mut a);
        let [_, a2, a3, a4] = &mut a;
        enter(*a2, a3, a4);
        load(2, &mut a);
        assert_eq!(a, [2, 1, 31337, 1337]);
        let leave_once = |a: &mut [u32; 4]| {
            let [_, a2, a3, a4] = a;
            leave(a2, a3, *a4);
        };
        leave_once(&mut a);
        assert_eq!(a, [2, 31337, 1337, 1337]);
        leave_once(&mut a);
        assert_eq!(a, [2, 1337, 1337, 1337]);
    }

    #[test]
    fn increment_and_decrement_wrap_in_the_low_byte() {
        let run = |f: fn(&mut u32, u8), accu: u32, n: u8| {
            let mut accu = accu;
            f(&mut accu, n);
            accu
        };
        assert_eq!(run(increment, 0, 1), 1);
        assert_eq!(run(increment, 1, 0), 1);
        assert_eq!(run(increment, 0, 255), 255);
        assert_eq!(run(increment, 1, 255), 0);
        assert_eq!(run(increment, 2, 255), 1);
        assert_eq!(run(increment, 0x0000_0100, 255), 0x0000_01FF);
        assert_eq!(run(increment, 0x0000_01FF, 255), 0x0000_01FE);
        assert_eq!(run(decrement, 0, 1), 255);
        assert_eq!(run(decrement, 1, 0), 1);
        assert_eq!(run(decrement, 1, 1), 0);
        assert_eq!(run(decrement, 0, 255), 1);
        assert_eq!(run(decrement, 2, 255), 3);
        assert_eq!(run(decrement, 0x0000_0100, 255), 0x0000_0101);
        assert_eq!(run(decrement, 0x1234_56FF, 255), 0x1234_5600);
    }
}
