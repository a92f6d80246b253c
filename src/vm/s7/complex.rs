//! Parameters of the complex data types at run time ("Programming with STEP 7", parameter
//! passing): an FB's inputs and outputs of a complex type copied whole into and out of its
//! instance data; an FC's passed as a 6-byte DB pointer — the DB number (0 for none), then an
//! area pointer — on the caller's L stack, which the FC reads its parameter through.

use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{BlockCopy, CopySource, FcCall};
use crate::vm::Cpu;

use super::memory::{Context, Fault, Located, area_of_code, fault};

impl Cpu {
    /// Copies `size` bytes from `from` to `to`, a byte at a time: both may lie in the same
    /// memory, and the executor allocates nothing.
    fn copy_bytes(&mut self, from: Located, to: Located, size: u32) -> Result<(), Fault> {
        for byte in 0..size {
            let value = self.fetch(from.offset(byte, 0), AccessWidth::Byte)?;
            self.store(to.offset(byte, 0), AccessWidth::Byte, value)?;
        }
        Ok(())
    }

    pub(super) fn write_bytes(&mut self, to: Located, bytes: &[u8]) -> Result<(), Fault> {
        for (at, byte) in bytes.iter().enumerate() {
            self.store(to.offset(at as u32, 0), AccessWidth::Byte, u32::from(*byte))?;
        }
        Ok(())
    }

    /// An FB call's inputs of a complex type into its instance data at `instance`.
    pub(super) fn copy_blocks_in(
        &mut self,
        copies: &[BlockCopy],
        instance: impl Fn(u32) -> Located,
    ) -> Result<(), Fault> {
        for copy in copies {
            let to = instance(copy.byte);
            match &copy.source {
                CopySource::Place(place) => {
                    let (from, _) = self.locate_index(*place)?;
                    self.copy_bytes(from, to, copy.size)?;
                }
                CopySource::Bytes(bytes) => self.write_bytes(to, bytes)?,
            }
        }
        Ok(())
    }

    /// An FB call's outputs of a complex type from its instance data back to their actuals.
    pub(super) fn copy_blocks_out(
        &mut self,
        copies: &[BlockCopy],
        instance: impl Fn(u32) -> Located,
    ) -> Result<(), Fault> {
        for copy in copies {
            // The compiler lets only a variable be an output's actual.
            if let CopySource::Place(place) = copy.source {
                let (to, _) = self.locate_index(place)?;
                self.copy_bytes(instance(copy.byte), to, copy.size)?;
            }
        }
        Ok(())
    }

    /// Before an FC call: the constants of its complex parameters onto the caller's L stack,
    /// then the DB pointer to each complex actual.
    pub(super) fn write_db_pointers(&mut self, call: &FcCall) -> Result<(), Fault> {
        for (place, bytes) in &call.constants {
            let (to, _) = self.locate_index(*place)?;
            self.write_bytes(to, bytes)?;
        }
        for &(actual, pointer) in &call.pointers {
            let (from, _) = self.locate_index(actual)?;
            let (number, area) = self.db_pointer(from)?;
            let (to, _) = self.locate_index(pointer)?;
            self.store(to, AccessWidth::Word, u32::from(number))?;
            self.store(to.offset(2, 0), AccessWidth::Double, area)?;
        }
        Ok(())
    }

    /// The DB pointer to `located`, as the running block passes it to an FC it calls: a data
    /// block's number with area DB (16#84), or no DB (0) with the area of an image or of the
    /// running block's L stack, which the FC sees as V (16#87).
    fn db_pointer(&self, located: Located) -> Result<(u16, u32), Fault> {
        let offset = |byte: usize, bit: u8| (byte as u32) << 3 | u32::from(bit);
        let layout = self.program.layout;
        let base = self.level.local_base as usize;
        Ok(match located {
            Located::Data { slot, byte, bit } => (
                self.program.s7.db_number(slot),
                0x8400_0000 | offset(byte, bit),
            ),
            Located::Local { byte, bit } if byte >= base => {
                (0, 0x8700_0000 | offset(byte - base, bit))
            }
            Located::Image { byte, bit } => {
                let flag = usize::from(layout.flag_base());
                let output = usize::from(layout.output_base());
                let input = usize::from(layout.input_base());
                let (area, start) = if byte >= flag {
                    (0x8300_0000, flag)
                } else if byte >= output {
                    (0x8200_0000, output)
                } else {
                    (0x8100_0000, input)
                };
                (0, area | offset(byte - start, bit))
            }
            other => {
                return Err(fault(format!(
                    "{other:?} cannot be passed by DB pointer to an FC"
                )));
            }
        })
    }

    /// Before an FB call: the DB pointer to each actual of an in/out of a complex type into the
    /// instance data at `instance`.
    pub(super) fn write_instance_pointers(
        &mut self,
        pointers: &[(u16, u32)],
        instance: impl Fn(u32) -> Located,
    ) -> Result<(), Fault> {
        for &(actual, byte) in pointers {
            let (from, _) = self.locate_index(actual)?;
            let (number, area) = self.db_pointer(from)?;
            let to = instance(byte);
            self.store(to, AccessWidth::Word, u32::from(number))?;
            self.store(to.offset(2, 0), AccessWidth::Double, area)?;
        }
        Ok(())
    }

    /// Where the DB pointer of complex FC parameter `param` points, for the FC of `context`.
    pub(super) fn locate_through(&mut self, param: u8, context: Context) -> Result<Located, Fault> {
        let pointer = self.locate_parameter(param, 0, 0, context)?;
        self.dereference(pointer, context)
    }

    /// Where the DB pointer at byte `pointer` of the running FB's instance data points (an
    /// in/out of a complex type).
    pub(super) fn locate_instance_through(
        &mut self,
        pointer: u32,
        context: Context,
    ) -> Result<Located, Fault> {
        let at = (context.ar2 & 0x0007_FFFF) + (pointer << 3);
        let located = Located::Data {
            slot: context.di,
            byte: (at >> 3) as usize,
            bit: 0,
        };
        self.dereference(located, context)
    }

    /// Where the 6-byte DB pointer at `pointer` points, read by the block of `context` (area
    /// V is its caller's L stack).
    fn dereference(&mut self, pointer: Located, context: Context) -> Result<Located, Fault> {
        let number = self.fetch(pointer, AccessWidth::Word)? as u16;
        let area = self.fetch(pointer.offset(2, 0), AccessWidth::Double)?;
        let code = area >> 24 & 7;
        if code == 4 && number != 0 {
            let Some(slot) = self.program.s7.db_slot(number) else {
                return Err(fault(format!(
                    "a DB pointer into DB {number}, which the program lacks"
                )));
            };
            return Ok(Located::Data {
                slot,
                byte: (area >> 3 & 0xFFFF) as usize,
                bit: (area & 7) as u8,
            });
        }
        let Some(area_code) = area_of_code(code).filter(|_| area >> 24 & 0x80 != 0) else {
            return Err(fault(format!(
                "{area:#010X} is no DB pointer's area pointer"
            )));
        };
        self.locate_pointer(area_code, area & 0x0007_FFFF, context)
    }
}
