//! Pairs of operations the VM runs as one op: the common STL idioms `A`/`O` chains on image
//! bits, `L` `L` before arithmetic, and arithmetic followed by `T`. Neither op of a pair can
//! fault, so running them as one changes nothing but the dispatch: time and the operation count
//! follow the position, which a pair moves by two. Position `i` holds op `i`, fused with op
//! `i + 1` where they pair; op `i + 1` keeps its own place, so a jump to it still finds it. The
//! stepping loop runs the plain ops; with operation points a pair runs as one only when no point
//! falls due between its ops, else as its first op. STEP 7's scans and writes (`S7Scan`,
//! `S7Write`: their status rules differ) pair only with each other.

use super::bytecode::{ImageBit, Logic, Op, Write};
use crate::rules::status::Combination;

/// `code` with every op that pairs with the next one replaced by the pair.
pub fn fuse(code: &[Op]) -> Vec<Op> {
    code.iter()
        .enumerate()
        .map(|(at, op)| {
            code.get(at + 1)
                .and_then(|next| pair(*op, *next))
                .unwrap_or(*op)
        })
        .collect()
}

fn pair(first: Op, second: Op) -> Option<Op> {
    Some(match (first, second) {
        (Op::LoadImageWord(byte), Op::LoadConstant(value)) => Op::LoadWordConstant {
            byte,
            value: u16::try_from(value).ok()?,
        },
        (Op::LoadImageWord(first), Op::LoadImageWord(second)) => Op::LoadWords { first, second },
        (Op::Arithmetic(kind), Op::TransferImageWord(byte)) => Op::ArithmeticTransferWord {
            kind,
            stack: false,
            byte,
        },
        (Op::ArithmeticStack(kind), Op::TransferImageWord(byte)) => Op::ArithmeticTransferWord {
            kind,
            stack: true,
            byte,
        },
        (Op::S7Scan(combination, scanned), Op::S7Write(write, written)) => Op::S7ScanWrite {
            scan_op: pack_step7(combination, scanned),
            scanned: scanned.byte,
            written: written.byte,
            write_op: pack_write(write, written),
        },
        (Op::S7Scan(first_combination, first), Op::S7Scan(second_combination, second)) => {
            Op::S7ScanPair {
                first_op: pack_step7(first_combination, first),
                first: first.byte,
                second: second.byte,
                second_op: pack_step7(second_combination, second),
            }
        }
        _ if bit_logic(first).is_some() && bit_write(second).is_some() => {
            let (logic, scanned) = bit_logic(first)?;
            let (write, written) = bit_write(second)?;
            Op::LogicWrite {
                logic_op: pack(logic, scanned),
                scanned: scanned.byte,
                written: written.byte,
                write_op: pack_write(write, written),
            }
        }
        _ => {
            let (first_logic, first) = bit_logic(first)?;
            let (second_logic, second) = bit_logic(second)?;
            Op::LogicPair {
                first_op: pack(first_logic, first),
                first: first.byte,
                second: second.byte,
                second_op: pack(second_logic, second),
            }
        }
    })
}

fn bit_logic(op: Op) -> Option<(Logic, ImageBit)> {
    match op {
        Op::And(bit) => Some((Logic::And, bit)),
        Op::AndNot(bit) => Some((Logic::AndNot, bit)),
        Op::Or(bit) => Some((Logic::Or, bit)),
        Op::OrNot(bit) => Some((Logic::OrNot, bit)),
        _ => None,
    }
}

fn bit_write(op: Op) -> Option<(Write, ImageBit)> {
    match op {
        Op::Assign(bit) => Some((Write::Assign, bit)),
        Op::Set(bit) => Some((Write::Set, bit)),
        Op::Reset(bit) => Some((Write::Reset, bit)),
        _ => None,
    }
}

fn pack(logic: Logic, bit: ImageBit) -> u8 {
    (logic as u8) << 3 | bit.bit & 7
}

fn pack_step7(combination: Combination, bit: ImageBit) -> u8 {
    (combination as u8) << 3 | bit.bit & 7
}

/// The combination's code (`as u8`) and the bit an [`Op::S7ScanPair`] or [`Op::S7ScanWrite`]
/// packed with `byte`, for [`crate::rules::status::Status::scanned_step7_code`].
#[inline(always)]
pub fn unpack_step7_code(packed: u8, byte: u16) -> (u8, ImageBit) {
    let bit = ImageBit {
        byte,
        bit: packed & 7,
    };
    (packed >> 3 & 7, bit)
}

/// What a write does to its bit for one value of the RLO: clear it…
const CLEAR: u8 = 1;
/// …or set it (with neither, leave it).
const SET: u8 = 2;

/// The second half of a [`Op::LogicWrite`]: the bit (bits 0–2), then what the write does to it
/// when the RLO is 0 (bits 3–4) and when it is 1 (bits 5–6), so the loop applies it without
/// branching on the kind of write.
fn pack_write(write: Write, bit: ImageBit) -> u8 {
    let (when_0, when_1) = match write {
        Write::Assign => (CLEAR, SET),
        Write::Set => (0, SET),
        Write::Reset => (0, CLEAR),
    };
    when_1 << 5 | when_0 << 3 | bit.bit & 7
}

/// `byte` after the packed write of a [`Op::LogicWrite`] with RLO `rlo`.
#[inline(always)]
pub fn apply_write(packed: u8, rlo: bool, byte: u8) -> u8 {
    let action = packed >> (3 + 2 * u8::from(rlo)) & 3;
    let bit = packed & 7;
    byte & !((action & CLEAR) << bit) | (action >> 1) << bit
}

/// The logic and the bit of a packed half of a [`Op::LogicPair`].
#[inline(always)]
pub fn unpack(packed: u8, byte: u16) -> (Logic, ImageBit) {
    let logic = match packed >> 3 & 3 {
        0 => Logic::And,
        1 => Logic::AndNot,
        2 => Logic::Or,
        _ => Logic::OrNot,
    };
    (
        logic,
        ImageBit {
            byte,
            bit: packed & 7,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_packed_half_unpacks_to_its_logic_and_bit() {
        for logic in [Logic::And, Logic::AndNot, Logic::Or, Logic::OrNot] {
            for bit in 0..8 {
                let image = ImageBit { byte: 300, bit };
                assert_eq!(unpack(pack(logic, image), 300), (logic, image));
            }
        }
    }

    #[test]
    fn a_packed_step7_half_unpacks_to_its_combination_and_bit() {
        use Combination::*;
        for combination in [And, AndNot, Or, OrNot, Xor, XorNot] {
            for bit in 0..8 {
                let image = ImageBit { byte: 300, bit };
                let packed = pack_step7(combination, image);
                assert_eq!(unpack_step7_code(packed, 300), (combination as u8, image));
            }
        }
    }

    #[test]
    fn step7_scans_pair_with_scans_and_writes_but_not_with_step5_ops() {
        let (a, b) = (ImageBit { byte: 1, bit: 2 }, ImageBit { byte: 3, bit: 4 });
        let scan = Op::S7Scan(Combination::Xor, a);
        assert!(matches!(
            pair(scan, Op::S7Scan(Combination::OrNot, b)),
            Some(Op::S7ScanPair {
                first: 1,
                second: 3,
                ..
            })
        ));
        assert!(matches!(
            pair(scan, Op::S7Write(Write::Set, b)),
            Some(Op::S7ScanWrite {
                scanned: 1,
                written: 3,
                ..
            })
        ));
        assert_eq!(pair(scan, Op::Assign(b)), None);
        assert_eq!(pair(Op::And(a), Op::S7Write(Write::Assign, b)), None);
    }

    #[test]
    fn a_packed_write_does_what_its_op_does() {
        for write in [Write::Assign, Write::Set, Write::Reset] {
            for bit in 0..8 {
                let image = ImageBit { byte: 7, bit };
                let Op::LogicWrite {
                    write_op, written, ..
                } = pair(Op::And(image), write_op_of(write, image)).unwrap()
                else {
                    panic!("a logic write");
                };
                assert_eq!(written, 7);
                for (byte, rlo) in [0x00u8, 0xFF, 0x5A, 0xA5]
                    .into_iter()
                    .flat_map(|byte| [(byte, false), (byte, true)])
                {
                    let mask = 1u8 << bit;
                    let expected = match (write, rlo) {
                        (Write::Assign | Write::Set, true) => byte | mask,
                        (Write::Assign, false) | (Write::Reset, true) => byte & !mask,
                        (Write::Set | Write::Reset, false) => byte,
                    };
                    assert_eq!(
                        apply_write(write_op, rlo, byte),
                        expected,
                        "{write:?} {rlo}"
                    );
                }
            }
        }
    }

    fn write_op_of(write: Write, bit: ImageBit) -> Op {
        match write {
            Write::Assign => Op::Assign(bit),
            Write::Set => Op::Set(bit),
            Write::Reset => Op::Reset(bit),
        }
    }

    #[test]
    fn pairs_keep_the_second_op_in_its_place() {
        let code = [
            Op::LoadImageWord(10),
            Op::LoadConstant(3),
            Op::Arithmetic(super::super::bytecode::Arith::Add),
            Op::TransferImageWord(10),
            Op::LoadConstant(0x1_0000),
        ];
        let fused = fuse(&code);
        assert_eq!(fused.len(), code.len());
        assert_eq!(fused[0], Op::LoadWordConstant { byte: 10, value: 3 });
        // `L KF +3` does not pair with `+F`; it stays itself.
        assert_eq!(fused[1], code[1]);
        assert!(matches!(
            fused[2],
            Op::ArithmeticTransferWord { byte: 10, .. }
        ));
        assert_eq!(fused[3], code[3]);
        assert_eq!(fused[4], code[4]);
    }
}
