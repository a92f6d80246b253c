//! The S5 floating-point format (not IEEE 754) and its arithmetic, as the CPU 928B and CPU 948
//! programming guides define it (CPU 928B programming guide, 2.2 "Coding floating point
//! numbers" and 3.5 "Conversion operations"; CPU 948 programming guide, the same sections).
//!
//! A number is 32 bits: bits 31–24 the exponent, an 8-bit two's-complement number (−128…+127);
//! bits 23–0 the mantissa, a 24-bit two's-complement fraction with its sign in bit 23 and the
//! binary point right after the sign (bit 22 is 2^-1, bit 0 is 2^-23). The value is
//! mantissa × 2^exponent. Zero is `8000_0000` (the smallest exponent, mantissa 0). Results are
//! normalized (the bit after the sign differs from the sign) and truncated, not rounded, so
//! `+G` of two exact values can lose the last bit; magnitudes run from 0.5 × 2^-128
//! (≈ 1.469368 × 10^-39) to (1 − 2^-23) × 2^127 (≈ 1.701412 × 10^38).

/// The bits of floating-point zero.
pub const ZERO: u32 = 0x8000_0000;
const MANTISSA_BITS: i32 = 23;
const MIN_EXPONENT: i32 = -128;
const MAX_EXPONENT: i32 = 127;
/// The largest mantissa, 1 − 2^-23, and the most negative, −1 (as integers, × 2^23).
const MAX_MANTISSA: i128 = (1 << MANTISSA_BITS) - 1;
const MIN_MANTISSA: i128 = -(1 << MANTISSA_BITS);
/// 0.5: the smallest magnitude of a normalized mantissa.
const HALF: i128 = 1 << (MANTISSA_BITS - 1);
/// Extra fraction bits the arithmetic keeps before it truncates.
const GUARD_BITS: u32 = 64;

/// What the result of an operation is, for the condition codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// A representable result (zero included).
    Exact,
    /// The exponent would exceed +127: the result is the largest number of the right sign.
    Overflow,
    /// The exponent would fall below −128: the result is zero.
    Underflow,
    /// `:G` by zero: ACCU 1 is left as it was.
    DivisionByZero,
}

/// A decoded number: the mantissa as an integer (the fraction × 2^23) and the exponent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Float {
    pub mantissa: i32,
    pub exponent: i8,
}

impl Float {
    pub fn from_bits(bits: u32) -> Float {
        Float {
            mantissa: ((bits << 8) as i32) >> 8,
            exponent: (bits >> 24) as u8 as i8,
        }
    }

    pub fn to_bits(self) -> u32 {
        u32::from(self.exponent as u8) << 24 | (self.mantissa as u32 & 0x00FF_FFFF)
    }

    pub fn to_f64(self) -> f64 {
        f64::from(self.mantissa) * 2f64.powi(i32::from(self.exponent) - MANTISSA_BITS)
    }
}

/// The value of a number's bits.
pub fn decode(bits: u32) -> f64 {
    Float::from_bits(bits).to_f64()
}

/// `value` truncated toward zero to the format, with what happened.
pub fn encode(value: f64) -> (u32, Outcome) {
    if value == 0.0 || !value.is_finite() {
        return (ZERO, Outcome::Exact);
    }
    // value = fraction × 2^exponent with 0.5 ≤ |fraction| < 1; the mantissa gets 40 bits
    // more than the format holds, so `normalize` truncates once.
    let exponent = value.abs().log2().floor() as i32 + 1;
    let mantissa = (value * 2f64.powi(MANTISSA_BITS + 40 - exponent)).trunc() as i128;
    normalize(mantissa, exponent - 40)
}

/// `value` rounded to the nearest number of the format: how a decimal constant (`KG`) becomes
/// binary, so that `KG +2457600+04` × `KG +2500000+01` is 6144, as the decimals say. The
/// arithmetic truncates (`encode`); the conversion of what the programmer wrote rounds.
pub fn encode_nearest(value: f64) -> (u32, Outcome) {
    if value == 0.0 || !value.is_finite() {
        return (ZERO, Outcome::Exact);
    }
    let exponent = value.abs().log2().floor() as i32 + 1;
    let mantissa = (value * 2f64.powi(MANTISSA_BITS - exponent)).round() as i128;
    normalize(mantissa, exponent)
}

/// Packs a mantissa of any size (the value is mantissa × 2^(exponent − 23)) into the format:
/// shifted until normalized, the bits shifted out on the right cut off (toward zero).
fn normalize(mut mantissa: i128, mut exponent: i32) -> (u32, Outcome) {
    if mantissa == 0 {
        return (ZERO, Outcome::Exact);
    }
    while !(MIN_MANTISSA..=MAX_MANTISSA).contains(&mantissa) {
        mantissa /= 2;
        exponent += 1;
    }
    // Normalized: the bit after the sign differs from it (−2^22 is not normalized, −2^23 is).
    while mantissa.abs() < HALF || mantissa == -HALF {
        mantissa *= 2;
        exponent -= 1;
    }
    if exponent > MAX_EXPONENT {
        let largest = if mantissa < 0 {
            MIN_MANTISSA
        } else {
            MAX_MANTISSA
        };
        return (pack(largest, MAX_EXPONENT), Outcome::Overflow);
    }
    if exponent < MIN_EXPONENT {
        return (ZERO, Outcome::Underflow);
    }
    (pack(mantissa, exponent), Outcome::Exact)
}

fn pack(mantissa: i128, exponent: i32) -> u32 {
    Float {
        mantissa: mantissa as i32,
        exponent: exponent as i8,
    }
    .to_bits()
}

/// The sign of a number: −1, 0 or +1 (a mantissa of 0 is zero whatever the exponent).
pub fn sign(bits: u32) -> i32 {
    Float::from_bits(bits).mantissa.signum()
}

/// `+G`: a + b, exact on 64 guard bits, then truncated.
pub fn add(a: u32, b: u32) -> (u32, Outcome) {
    let (a, b) = (Float::from_bits(a), Float::from_bits(b));
    let exponent = i32::from(a.exponent.max(b.exponent));
    let aligned = |x: Float| {
        let shift = (exponent - i32::from(x.exponent)).min(120) as u32;
        (i128::from(x.mantissa) << GUARD_BITS) / (1i128 << shift)
    };
    normalize(aligned(a) + aligned(b), exponent - GUARD_BITS as i32)
}

/// `-G`: a − b.
pub fn subtract(a: u32, b: u32) -> (u32, Outcome) {
    let negated = Float::from_bits(b);
    let (negated, _) = normalize(-i128::from(negated.mantissa), i32::from(negated.exponent));
    add(a, negated)
}

/// `XG`: a × b.
pub fn multiply(a: u32, b: u32) -> (u32, Outcome) {
    let (a, b) = (Float::from_bits(a), Float::from_bits(b));
    let product = i128::from(a.mantissa) * i128::from(b.mantissa);
    normalize(
        product,
        i32::from(a.exponent) + i32::from(b.exponent) - MANTISSA_BITS,
    )
}

/// `:G`: a ÷ b; by zero, `a` unchanged.
pub fn divide(a: u32, b: u32) -> (u32, Outcome) {
    let (a, b) = (Float::from_bits(a), Float::from_bits(b));
    if b.mantissa == 0 {
        return (a.to_bits(), Outcome::DivisionByZero);
    }
    let quotient = (i128::from(a.mantissa) << GUARD_BITS) / i128::from(b.mantissa);
    let exponent = i32::from(a.exponent) - i32::from(b.exponent) + MANTISSA_BITS;
    normalize(quotient, exponent - GUARD_BITS as i32)
}

/// `FDG`: a 32-bit fixed-point number to floating point (truncated to 24 mantissa bits).
pub fn from_fixed(value: i32) -> u32 {
    normalize(i128::from(value), MANTISSA_BITS).0
}

/// `GFD`: floating point to a 32-bit fixed-point number, the fraction cut off (toward zero);
/// `None` when the value is outside −2^31…2^31 − 1.
pub fn to_fixed(bits: u32) -> Option<i32> {
    let float = Float::from_bits(bits);
    let shift = i32::from(float.exponent) - MANTISSA_BITS;
    let mantissa = i128::from(float.mantissa);
    let value = if shift >= 0 {
        if shift > 40 {
            return None;
        }
        mantissa << shift
    } else {
        mantissa / (1i128 << (-shift).min(100))
    };
    i32::try_from(value).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(bits: u32) -> f64 {
        decode(bits)
    }

    #[test]
    fn zero_is_8000_0000() {
        assert_eq!(encode(0.0), (ZERO, Outcome::Exact));
        assert_eq!(value(ZERO), 0.0);
        assert_eq!(sign(ZERO), 0);
    }

    #[test]
    fn positive_and_negative_mantissas() {
        // 1.0 = 0.5 × 2^1: exponent 01, mantissa 40 0000.
        assert_eq!(encode(1.0).0, 0x0140_0000);
        // −1.0 = −1 × 2^0: the mantissa −1 is 80 0000 (normalized: bit 22 differs from the sign).
        assert_eq!(encode(-1.0).0, 0x0080_0000);
        // −0.5 = −1 × 2^-1, not −0.5 × 2^0 (that mantissa, C0 0000, is not normalized).
        assert_eq!(encode(-0.5).0, 0xFF80_0000);
        // 12.34567 = 0.771… × 2^4, the CPU 928B guide's KG example.
        let bits = encode(12.34567).0;
        assert_eq!(bits >> 24, 4);
        assert!((value(bits) - 12.34567).abs() < 1e-5);
        assert_eq!(value(0x0080_0000), -1.0);
    }

    #[test]
    fn the_manuals_range() {
        let largest = pack(MAX_MANTISSA, 127);
        assert_eq!(largest, 0x7F7F_FFFF);
        assert!((value(largest) / 1.701412e38 - 1.0).abs() < 1e-6);
        let smallest = pack(HALF, -128);
        assert_eq!(smallest, 0x8040_0000);
        assert!((value(smallest) / 1.469368e-39 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn overflow_saturates_and_underflow_is_zero() {
        let big = encode(1.0e38).0;
        let (product, outcome) = multiply(big, big);
        assert_eq!(outcome, Outcome::Overflow);
        assert_eq!(product, 0x7F7F_FFFF);
        let (product, outcome) = multiply(big, encode(-1.0e38).0);
        assert_eq!(outcome, Outcome::Overflow);
        assert_eq!(product, 0x7F80_0000, "the most negative number");
        let tiny = encode(1.0e-38).0;
        assert_eq!(multiply(tiny, tiny), (ZERO, Outcome::Underflow));
        assert_eq!(encode(1.0e39).1, Outcome::Overflow);
        assert_eq!(encode(1.0e-40), (ZERO, Outcome::Underflow));
    }

    #[test]
    fn constants_round_to_the_nearest_number() {
        // 0.6 = 0.1001 1001 1001 … : truncated 4CCCCC, rounded 4CCCCD.
        assert_eq!(encode(2457.6).0, 0x0C4C_CCCC);
        assert_eq!(encode_nearest(2457.6).0, 0x0C4C_CCCD);
        assert_eq!(encode_nearest(-2457.6).0, 0x0CB3_3333);
        let product = multiply(encode_nearest(2457.6).0, encode_nearest(2.5).0).0;
        assert_eq!(to_fixed(product), Some(6144));
        // Rounding up to a whole power of two renormalizes: 1 − 2^-30 is 1.0.
        assert_eq!(encode_nearest(1.0 - 2f64.powi(-30)).0, encode(1.0).0);
    }

    #[test]
    fn results_are_truncated_toward_zero() {
        // 1/3 has no end in binary: the 24th bit is cut off, not rounded.
        let third = divide(encode(1.0).0, encode(3.0).0).0;
        assert_eq!(third, 0xFF55_5555);
        let minus_third = divide(encode(-1.0).0, encode(3.0).0).0;
        assert_eq!(value(minus_third), -value(third));
        // 2/3 = 0.AAAAAA… ; rounding would give …AB.
        assert_eq!(add(third, third).0, 0x0055_5555);
    }

    #[test]
    fn arithmetic() {
        let (a, b) = (encode(12.5).0, encode(-2.5).0);
        assert_eq!(value(add(a, b).0), 10.0);
        assert_eq!(value(subtract(a, b).0), 15.0);
        assert_eq!(value(multiply(a, b).0), -31.25);
        assert_eq!(value(divide(a, b).0), -5.0);
        assert_eq!(add(a, subtract(ZERO, a).0), (ZERO, Outcome::Exact));
        assert_eq!(divide(a, ZERO), (a, Outcome::DivisionByZero));
        assert_eq!(value(subtract(ZERO, encode(-1.0).0).0), 1.0);
    }

    #[test]
    fn fixed_point_conversions() {
        assert_eq!(from_fixed(0), ZERO);
        assert_eq!(value(from_fixed(-100_000)), -100_000.0);
        assert_eq!(from_fixed(1), 0x0140_0000);
        // 2^31 − 1 needs 31 bits, the mantissa holds 23 besides its sign: the low 8 are cut off.
        assert_eq!(value(from_fixed(i32::MAX)), 2_147_483_392.0);
        assert_eq!(to_fixed(encode(123.75).0), Some(123));
        assert_eq!(to_fixed(encode(-123.75).0), Some(-123));
        assert_eq!(to_fixed(encode(0.25).0), Some(0));
        assert_eq!(to_fixed(encode(3.0e9).0), None);
        assert_eq!(to_fixed(from_fixed(i32::MIN)), Some(i32::MIN));
    }
}
