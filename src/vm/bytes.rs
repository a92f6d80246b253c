//! Values in byte memory: big-endian, 1, 2 or 4 bytes wide, as every area of the CPU holds
//! them (images, modules, the interrupt process images, data blocks).

/// The big-endian value of the `count` bytes (1, 2 or 4) at `at`.
#[inline(always)]
pub fn read_bytes(memory: &[u8], at: usize, count: usize) -> u32 {
    memory[at..at + count]
        .iter()
        .fold(0, |value, byte| value << 8 | u32::from(*byte))
}

/// Writes the low `count` bytes (1, 2 or 4) of `value` big-endian at `at`.
#[inline(always)]
pub fn write_bytes(memory: &mut [u8], at: usize, count: usize, value: u32) {
    memory[at..at + count].copy_from_slice(&value.to_be_bytes()[4 - count..]);
}
