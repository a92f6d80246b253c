//! Forcing, as a PG forces a CPU's inputs and outputs: bits of the process images held at
//! values until the force ends, whatever the modules deliver or the program writes. awl forces
//! as an S7-300 does, where "forcing corresponds to cyclical controlling": the operating system
//! writes the force values into the PII after each PII transfer and into the PIQ before each
//! PIQ transfer to the modules ("S7-300, CPU 31xC and CPU 31x: Installation", 10.2 Overview:
//! Debugging functions, Forcing with S7-300 CPUs, figure 10-1 Principle of forcing in S7-300
//! CPUs). So the program reads a forced input from the PII whatever the input modules hold (a
//! client's or a scenario's input write reaches only the modules), and the output modules get
//! a forced output whatever the program wrote into the PIQ in the cycle. What the manual says
//! is not forced is not forced here either: the peripheral inputs ("Peripheral inputs: –" in
//! its table of forcing and modifying), so a direct read (`L PIW`) reads the module, and a
//! direct write (`T PQW`) reaches the module until the next PIQ transfer ("Force value
//! overwritten by T PQW!").

use crate::address::{ImageArea, Layout};

use super::Cpu;

/// The bits `mask` of image byte `at` held at `bits`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ForcedByte {
    pub at: u16,
    pub mask: u8,
    pub bits: u8,
}

/// The forced bytes of the PII and of the PIQ, as offsets in the image memory.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Forces {
    inputs: Vec<ForcedByte>,
    outputs: Vec<ForcedByte>,
}

impl Forces {
    /// The forces of `held` in order: where two hold the same bit, the later one's value holds
    /// (the last force of an address becomes effective). Bytes outside the process images are
    /// left out.
    pub fn new(layout: Layout, held: impl IntoIterator<Item = ForcedByte>) -> Forces {
        let mut forces = Forces::default();
        for byte in held {
            let bytes = match layout.image_area_of(byte.at) {
                Some((ImageArea::Input, _)) => &mut forces.inputs,
                Some((ImageArea::Output, _)) => &mut forces.outputs,
                _ => continue,
            };
            match bytes.iter_mut().find(|forced| forced.at == byte.at) {
                Some(forced) => {
                    forced.mask |= byte.mask;
                    forced.bits = forced.bits & !byte.mask | byte.bits & byte.mask;
                }
                None => bytes.push(ForcedByte {
                    bits: byte.bits & byte.mask,
                    ..byte
                }),
            }
        }
        forces
    }

    pub fn is_empty(&self) -> bool {
        self.inputs.is_empty() && self.outputs.is_empty()
    }
}

fn hold(image: &mut [u8], forced: &[ForcedByte]) {
    for byte in forced {
        let at = &mut image[usize::from(byte.at)];
        *at = *at & !byte.mask | byte.bits;
    }
}

impl Cpu {
    /// After the PII transfer: the forced inputs replace what the modules delivered.
    pub(super) fn force_pii(&mut self) {
        hold(&mut self.image[..], &self.forces.inputs);
    }

    /// Before the PIQ transfer: the forced outputs replace what the program wrote.
    pub(super) fn force_piq(&mut self) {
        hold(&mut self.image[..], &self.forces.outputs);
    }

    /// Writes the force values into both process images now: a force just set, a restart, or
    /// a client's write at the control point, so the images hold them at once.
    pub fn hold_forces(&mut self) {
        self.force_pii();
        self.force_piq();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vm::cycle::RunLimit;

    fn cpu(source: &str) -> Cpu {
        crate::serve::testing::cpu(source, false)
    }

    fn forced(at: u16, mask: u8, bits: u8) -> ForcedByte {
        ForcedByte { at, mask, bits }
    }

    #[test]
    fn a_later_force_of_the_same_bits_wins() {
        let layout = Layout {
            image_bytes: 128,
            flag_bytes: 256,
        };
        let forces = Forces::new(layout, [forced(0, 0xFF, 0x0F), forced(0, 0x01, 0x00)]);
        assert_eq!(forces.inputs, [forced(0, 0xFF, 0x0E)]);
        assert!(
            Forces::new(layout, [forced(256, 1, 1)]).is_empty(),
            "a flag is no I/O"
        );
    }

    #[test]
    fn a_forced_input_holds_against_the_modules_and_a_forced_output_against_the_program() {
        // The program copies I 0.0 to F 0.0 and I 0.1 to Q 0.1, and writes Q 0.0 = 0 in every cycle.
        let mut cpu =
            cpu("OB 1\n A I 0.0\n = F 0.0\n A F 1.0\n = Q 0.0\n A I 0.1\n = Q 0.1\n BE\n");
        cpu.run(RunLimit::Cycles(1));
        let layout = cpu.program.layout;
        let (pii, piq, flags) = (
            0,
            usize::from(layout.output_base()),
            usize::from(layout.flag_base()),
        );
        cpu.forces = Forces::new(
            layout,
            [forced(0, 0x01, 0x01), forced(piq as u16, 0x01, 0x01)],
        );
        cpu.inputs[0] = 0b10;
        cpu.run(RunLimit::Cycles(3));
        assert_eq!(cpu.image[pii], 0b11, "I 0.0 forced, I 0.1 from the module");
        assert_eq!(cpu.image[flags], 1, "the program read the forced input");
        assert_eq!(
            cpu.outputs[0], 0b11,
            "the module got the forced Q 0.0 and the program's Q 0.1"
        );
        cpu.forces = Forces::default();
        cpu.run(RunLimit::Cycles(4));
        assert_eq!(cpu.image[flags], 0, "unforced: the module's 0 again");
        assert_eq!(cpu.outputs[0], 0b10);
    }
}
