//! The online page's forces: which operands are held at which values, in the order they were
//! set, and the VM's forced process-image bytes ([`crate::vm::force`]) made from them.

use crate::address::{ImageArea, Layout};
use crate::scenario::operand::Target;
use crate::vm::Cpu;
use crate::vm::force::{ForcedByte, Forces};

/// One forced operand.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Held {
    /// As the page wrote it.
    pub operand: String,
    pub target: Target,
    pub raw: u32,
}

/// The process-image bytes of `target` held at `raw`; `None` for what cannot be forced:
/// anything but a bit, byte or word of the PII or the PIQ.
pub fn forced_bytes(target: Target, raw: u32, layout: Layout) -> Option<Vec<ForcedByte>> {
    let bytes = match target {
        Target::ImageBit { byte, bit } => vec![ForcedByte {
            at: byte,
            mask: 1 << bit,
            bits: ((raw & 1) as u8) << bit,
        }],
        Target::Image { byte, bytes } if bytes == 1 || bytes == 2 => {
            let count = usize::from(bytes);
            raw.to_be_bytes()[4 - count..]
                .iter()
                .zip(byte..)
                .map(|(&bits, at)| ForcedByte {
                    at,
                    mask: 0xFF,
                    bits,
                })
                .collect()
        }
        _ => return None,
    };
    let in_images = bytes.iter().all(|byte| {
        matches!(
            layout.image_area_of(byte.at),
            Some((ImageArea::Input | ImageArea::Output, _))
        )
    });
    in_images.then_some(bytes)
}

#[derive(Debug, Default)]
pub struct ForceTable {
    held: Vec<Held>,
}

impl ForceTable {
    pub fn held(&self) -> &[Held] {
        &self.held
    }

    /// Forces `held` (a new value for an operand forced already), now.
    pub fn set(&mut self, cpu: &mut Cpu, held: Held) {
        self.held.retain(|other| other.target != held.target);
        self.held.push(held);
        self.apply(cpu);
    }

    /// Ends the force of `target`; what it was, if it was forced.
    pub fn remove(&mut self, cpu: &mut Cpu, target: Target) -> Option<Held> {
        let index = self.held.iter().position(|held| held.target == target)?;
        let removed = self.held.remove(index);
        self.apply(cpu);
        Some(removed)
    }

    /// Ends every force; the ones there were.
    pub fn clear(&mut self, cpu: &mut Cpu) -> Vec<Held> {
        let removed = std::mem::take(&mut self.held);
        self.apply(cpu);
        removed
    }

    /// Hands the CPU the forced bytes and writes them into its images at once. An unforced
    /// operand keeps its last value until the modules or the program change it, as on a CPU.
    fn apply(&self, cpu: &mut Cpu) {
        let layout = cpu.program.layout;
        let bytes = self
            .held
            .iter()
            .filter_map(|held| forced_bytes(held.target, held.raw, layout))
            .flatten();
        cpu.forces = Forces::new(layout, bytes);
        cpu.hold_forces();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LAYOUT: Layout = Layout {
        image_bytes: 128,
        flag_bytes: 256,
    };

    #[test]
    fn bits_bytes_and_words_of_the_process_images_are_forced() {
        let bit = Target::ImageBit { byte: 4, bit: 3 };
        assert_eq!(
            forced_bytes(bit, 1, LAYOUT),
            Some(vec![ForcedByte {
                at: 4,
                mask: 0x08,
                bits: 0x08
            }])
        );
        let word = Target::Image {
            byte: 128,
            bytes: 2,
        };
        let forced = forced_bytes(word, 0x1234, LAYOUT).unwrap();
        assert_eq!((forced[0].at, forced[0].bits), (128, 0x12));
        assert_eq!((forced[1].at, forced[1].bits), (129, 0x34));
    }

    #[test]
    fn flags_double_words_and_the_periphery_are_not() {
        let flag = Target::ImageBit { byte: 256, bit: 0 };
        let double = Target::Image { byte: 0, bytes: 4 };
        let periphery = Target::Periphery {
            byte: 0,
            bytes: 2,
            extended: false,
        };
        let straddling = Target::Image {
            byte: 255,
            bytes: 2,
        };
        for target in [flag, double, periphery, straddling, Target::CounterValue(1)] {
            assert_eq!(forced_bytes(target, 1, LAYOUT), None, "{target:?}");
        }
    }
}
