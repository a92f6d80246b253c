//! SFC 20 BLKMOV and SFC 21 FILL ("System Software for S7-300/400 System and Standard
//! Functions", copy and block functions): the areas of two ANY pointers, checked, then copied
//! (BLKMOV: as much of the source as the destination holds) or filled (FILL: the source
//! repeated over the destination). RET_VAL is 0 and BR 1, or the manual's general error code
//! with the parameter's number (1 the source, 3 the destination) in its second digit and BR 0:
//! nothing is written then.

use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{AnyActual, FILL};
use crate::vm::Cpu;

use super::memory::{Fault, Located};

/// Area length error on reading (`8x22`); writing is one more.
const LENGTH: u16 = 0x8022;
/// Area error on reading (`8x24`).
const AREA: u16 = 0x8024;
/// Alignment error on reading (`8x28`).
const ALIGNMENT: u16 = 0x8028;
/// The data block is not loaded (`8x3A`).
const NO_DB: u16 = 0x803A;

/// The first byte of an S7 ANY pointer.
const ANY_MAGIC: u8 = 0x10;

/// The width in bits of an element of ANY type `code`, for the types these SFCs copy.
fn element_bits(code: u8) -> Option<u32> {
    Some(match code {
        0x01 => 1,
        0x02 | 0x03 => 8,
        0x04 | 0x05 | 0x09 | 0x0C => 16,
        0x06..=0x08 | 0x0A | 0x0B => 32,
        0x0E => 64,
        _ => return None,
    })
}

/// One of the two parameters: which, and whether it is read.
#[derive(Clone, Copy)]
struct Side {
    /// The parameter's number: 1 the source, 3 the destination.
    number: u16,
    read: bool,
}

impl Side {
    /// Error code `base` (a read error) for this parameter.
    fn error(self, base: u16) -> u16 {
        let base = if self.read || base == NO_DB {
            base
        } else {
            base + 1
        };
        (base & 0xF0FF) | self.number << 8
    }
}

impl Cpu {
    /// `CALL SFC 20`/`CALL SFC 21`; the compiler put the source ANY first, the destination
    /// second, and RET_VAL among the places.
    pub(super) fn block_move(&mut self, number: u16, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.sfc_calls[usize::from(call)];
        let [(_, source), (_, destination)] = call.anys.as_slice() else {
            return Err(super::exec::fault(
                "SFC 20/21 without its two ANY parameters",
            ));
        };
        let source = self.any_bytes(*source)?;
        let destination = self.any_bytes(*destination)?;
        let code = match self.move_areas(number, &source, &destination) {
            Ok(()) => 0,
            Err(code) => code,
        };
        if let Some(&(_, place)) = call.params.iter().find(|(name, _)| name == "RET_VAL") {
            let (to, _) = self.locate_index(place)?;
            self.store(to, AccessWidth::Word, u32::from(code))?;
        }
        self.level.br = code == 0;
        Ok(())
    }

    /// The 10 bytes of an ANY parameter.
    fn any_bytes(&mut self, actual: AnyActual) -> Result<[u8; 10], Fault> {
        let place = match actual {
            AnyActual::Bytes(bytes) => return Ok(bytes),
            AnyActual::At(place) => place,
        };
        let context = self.running_context();
        let at = self.locate(place, context)?;
        let mut bytes = [0; 10];
        for (index, byte) in bytes.iter_mut().enumerate() {
            *byte = self.fetch(at.offset(index as u32, 0), AccessWidth::Byte)? as u8;
        }
        Ok(bytes)
    }

    /// The copy itself, or the RET_VAL of its error.
    fn move_areas(
        &mut self,
        number: u16,
        source: &[u8; 10],
        destination: &[u8; 10],
    ) -> Result<(), u16> {
        let read = Side {
            number: 1,
            read: true,
        };
        let write = Side {
            number: 3,
            read: false,
        };
        let source_length = any_length(source, read)?;
        let destination_length = any_length(destination, write)?;
        let from = self.any_area(source, source_length, read)?;
        let to = self.any_area(destination, destination_length, write)?;
        let count = if number == FILL {
            destination_length
        } else {
            source_length.min(destination_length)
        };
        // Byte by byte: the areas are checked, and a copy needs no buffer.
        for index in 0..count {
            let value = self
                .fetch(
                    from.offset((index % source_length) as u32, 0),
                    AccessWidth::Byte,
                )
                .map_err(|_| read.error(AREA))?;
            self.store(to.offset(index as u32, 0), AccessWidth::Byte, value)
                .map_err(|_| write.error(AREA))?;
        }
        Ok(())
    }

    /// Where the area of an ANY starts, checked to hold `length` bytes.
    fn any_area(&mut self, any: &[u8; 10], length: usize, side: Side) -> Result<Located, u16> {
        let db = u16::from_be_bytes([any[4], any[5]]);
        let pointer = u32::from_be_bytes([any[6], any[7], any[8], any[9]]);
        let byte = (pointer >> 3 & 0xFFFF) as usize;
        let bit = (pointer & 7) as u8;
        let area = pointer >> 24;
        let context = self.running_context();
        let layout = self.program.layout;
        let located = match area {
            // DB and DI: the data block the ANY names.
            0x84 | 0x85 => {
                let slot = self
                    .program
                    .s7
                    .db_slot(db)
                    .filter(|&slot| slot != 0)
                    .filter(|&slot| matches!(self.s7_data.get(usize::from(slot)), Some(Some(_))))
                    .ok_or(side.error(NO_DB))?;
                Located::Data { slot, byte, bit }
            }
            0x81 => Located::Image {
                byte: usize::from(layout.input_base()) + byte,
                bit,
            },
            0x82 => Located::Image {
                byte: usize::from(layout.output_base()) + byte,
                bit,
            },
            0x83 => Located::Image {
                byte: usize::from(layout.flag_base()) + byte,
                bit,
            },
            0x86 => Located::Local {
                byte: context.local_base as usize + byte,
                bit,
            },
            0x87 => Located::Local {
                byte: context.previous_local.ok_or(side.error(AREA))? as usize + byte,
                bit,
            },
            _ => return Err(side.error(AREA)),
        };
        if bit != 0 {
            return Err(side.error(ALIGNMENT));
        }
        let size = match area {
            0x81 | 0x82 => usize::from(layout.image_bytes),
            0x83 => usize::from(layout.flag_bytes),
            _ => usize::MAX,
        };
        if byte + length > size
            || (length > 0
                && self
                    .fetch(located.offset(length as u32 - 1, 0), AccessWidth::Byte)
                    .is_err())
        {
            return Err(side.error(AREA));
        }
        Ok(located)
    }
}

/// The length in bytes of an ANY's area; a length error when it is not whole bytes.
fn any_length(any: &[u8; 10], side: Side) -> Result<usize, u16> {
    if any[0] != ANY_MAGIC {
        return Err(side.error(AREA));
    }
    let bits = element_bits(any[1]).ok_or(side.error(AREA))?;
    let count = u32::from(u16::from_be_bytes([any[2], any[3]]));
    let total = bits * count;
    if total == 0 || total % 8 != 0 {
        return Err(side.error(LENGTH));
    }
    Ok((total / 8) as usize)
}
