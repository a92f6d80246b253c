//! Binary-coded decimal, four bits a decimal digit: how timers, counters, S5TIME and
//! DATE_AND_TIME hold their values and what the BCD conversions read and write. One encoder and
//! one decoder for both dialects' constants, the VM and the values a watch shows.

/// The low `digits` decimal digits of `magnitude`, four bits each.
#[inline]
pub fn encode(magnitude: u32, digits: u32) -> u32 {
    (0..digits).fold(0, |bcd, digit| {
        bcd | (magnitude / 10u32.pow(digit) % 10) << (4 * digit)
    })
}

/// The low `digits` nibbles of `bcd` read as decimal digits; a nibble above 9 counts as what it
/// is.
#[inline]
pub fn decode(bcd: u32, digits: u32) -> u32 {
    (0..digits)
        .rev()
        .fold(0, |value, digit| value * 10 + (bcd >> (4 * digit) & 0xF))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digits_four_bits_each() {
        for (value, digits, bcd) in [(503, 3, 0x503), (0, 3, 0), (1_234_567, 7, 0x0123_4567)] {
            assert_eq!(encode(value, digits), bcd);
            assert_eq!(decode(bcd, digits), value);
        }
        assert_eq!(
            decode(0xFFF, 3),
            1665,
            "a nibble above 9 counts as what it is"
        );
    }
}
