//! The supplementary operations that are not bit or word logic: `ADD` of a constant, and the
//! system and register operations on absolute addresses, which awl parses and times but cannot
//! run (it has no S5 memory map, no base address register and no STEP address counter).

use crate::mnemonics::OpCode;

use super::stop::{StopCause, StopDetail};

/// `ADD KB/KF n` adds to the low word of ACCU 1 (the high word stays); `ADD DH n` to all 32
/// bits. Both wrap around, and neither touches ACCU 2 or the status bits.
pub fn add_constant(accu1: &mut u32, value: u32, double: bool) {
    *accu1 = if double {
        accu1.wrapping_add(value)
    } else {
        let low = (*accu1 as u16).wrapping_add(value as u16);
        *accu1 & 0xFFFF_0000 | u32::from(low)
    };
}

/// The STOP of a system or register operation awl cannot simulate: the cause names the
/// operation and what it would need.
#[cold]
#[inline(never)]
pub fn not_simulated(op: OpCode, operand: u16) -> (StopCause, StopDetail) {
    let info = crate::mnemonics::op_info(op);
    let (statement, needs) = match op {
        OpCode::TransferBytes => (
            format!("TNB {operand}"),
            "it copies bytes between absolute memory addresses",
        ),
        OpCode::LoadIndirect | OpCode::TransferIndirect => (
            format!("{} {operand}", info.en),
            "it reaches the memory word at the absolute address in ACCU 1",
        ),
        OpCode::AddToBr | OpCode::LoadRelativeBr | OpCode::TransferRelativeBr => (
            format!("{} {operand}", info.en),
            "it works on the base address register BR, an absolute memory address",
        ),
        OpCode::MoveSaToAccu | OpCode::MoveAccuToSa => (
            info.en.to_string(),
            "it works on the STEP address counter, an absolute program address",
        ),
        _ => (
            info.en.to_string(),
            "it works on the base address register BR, an absolute memory address",
        ),
    };
    let text = format!(
        "`{statement}` is not simulated: {needs}, and awl has no S5 memory map (`awl help language`, \"System and register operations\")"
    );
    (StopCause::Bcf, StopDetail::Text(text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn word_addition_keeps_the_high_word_and_wraps() {
        let mut accu1 = 0x1234_7FFF;
        add_constant(&mut accu1, 1, false);
        assert_eq!(accu1, 0x1234_8000);
        let mut accu1 = 0x0001_0005;
        add_constant(&mut accu1, 0xFFFE, false); // KF -2
        assert_eq!(accu1, 0x0001_0003);
    }

    #[test]
    fn double_addition_carries_into_the_high_word() {
        let mut accu1 = 0x0000_FFFF;
        add_constant(&mut accu1, 1, true);
        assert_eq!(accu1, 0x0001_0000);
    }
}
