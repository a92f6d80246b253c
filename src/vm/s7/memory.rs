//! Where a STEP 7 operand is at run time: the L stack of the running block or of its caller,
//! the DB and DI registers, an FC parameter (a pointer to the caller's actual), a memory- or
//! register-indirect address. [`Cpu::locate`] turns a compiled [`Place`] into a [`Located`]
//! byte and bit; the reads and writes then check it against the memory it is in.

use crate::compiler::Resolved;
use crate::step7::ast::{AccessWidth, S7Area};
use crate::step7::bytecode::{Place, Target};
use crate::vm::stop::{StopCause, StopDetail};
use crate::vm::{Cpu, LevelState};

pub type Fault = (StopCause, StopDetail);

/// The bytes of the L stack every level's blocks share.
pub const LOCAL_BYTES: usize = 64 * 1024;

/// A place made concrete.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Located {
    Image {
        byte: usize,
        bit: u8,
    },
    Peripheral {
        output: bool,
        byte: u16,
    },
    Local {
        byte: usize,
        bit: u8,
    },
    /// A byte of a STEP 7 data block, by the block's slot (see
    /// [`crate::step7::bytecode::S7Tables::db_numbers`]).
    Data {
        slot: u16,
        byte: usize,
        bit: u8,
    },
    Timer(u16),
    Counter(u16),
    Constant(u32),
    /// A test operand or a register: read by the executor.
    Special(Target),
}

impl Located {
    /// A member `byte`/`bit` into a located actual: a structure's member, or the actual itself
    /// (0, 0) with its own bit.
    pub fn offset(self, byte: u32, bit: u8) -> Located {
        let byte = byte as usize;
        match self {
            Located::Image { byte: at, bit: own } => Located::Image {
                byte: at + byte,
                bit: own + bit,
            },
            Located::Local { byte: at, bit: own } => Located::Local {
                byte: at + byte,
                bit: own + bit,
            },
            Located::Data {
                slot,
                byte: at,
                bit: own,
            } => Located::Data {
                slot,
                byte: at + byte,
                bit: own + bit,
            },
            other => other,
        }
    }
}

/// The registers a place is resolved against: the running block's, or a caller's for the
/// actual of a parameter.
#[derive(Debug, Clone, Copy)]
pub struct Context {
    pub local_base: u32,
    /// The calling block's local data (V), if there is a caller on this level.
    pub previous_local: Option<u32>,
    pub db: u16,
    pub di: u16,
    /// AR2: the FB's instance data start at its offset in DI.
    pub ar2: u32,
    pub params: u16,
    /// Frames on the block stack below this context's block.
    pub frames: usize,
    /// Where the frames of this context's processing level begin on the block stack.
    pub level_base: usize,
}

impl Context {
    /// Where `target` lies when the context alone tells: the image, local, data and instance
    /// areas, timers, counters and constants. `None` for a place the CPU must look further
    /// for (a parameter, a pointer, the peripherals) and for V in a block without caller.
    #[inline]
    pub fn locate(&self, target: Target) -> Option<Located> {
        Some(match target {
            Target::Image { byte, bit } => Located::Image {
                byte: usize::from(byte),
                bit,
            },
            Target::Local { byte, bit } => Located::Local {
                byte: (self.local_base + byte) as usize,
                bit,
            },
            Target::PreviousLocal { byte, bit } => Located::Local {
                byte: (self.previous_local? + byte) as usize,
                bit,
            },
            Target::Data {
                instance,
                byte,
                bit,
            } => Located::Data {
                slot: if instance { self.di } else { self.db },
                byte: byte as usize,
                bit,
            },
            Target::Instance { byte, bit } => {
                // Area-internal: AR2's area bits do not count, its byte.bit offset does.
                let at = (self.ar2 & 0x0007_FFFF) + (byte << 3 | u32::from(bit));
                Located::Data {
                    slot: self.di,
                    byte: (at >> 3) as usize,
                    bit: (at & 7) as u8,
                }
            }
            Target::NumberedData {
                slot, byte, bit, ..
            } => Located::Data {
                slot,
                byte: byte as usize,
                bit,
            },
            Target::Timer(n) => Located::Timer(n),
            Target::Counter(n) => Located::Counter(n),
            Target::Constant(value) => Located::Constant(value),
            _ => return None,
        })
    }
}

/// Area-pointer area codes (bits 24–26 of a pointer).
pub fn area_code(area: S7Area) -> u32 {
    match area {
        S7Area::PeripheralInput | S7Area::PeripheralOutput => 0,
        S7Area::Input => 1,
        S7Area::Output => 2,
        S7Area::Flag => 3,
        S7Area::Data => 4,
        S7Area::Instance => 5,
        S7Area::Local => 6,
        S7Area::PreviousLocal => 7,
        S7Area::Timer | S7Area::Counter => 0,
    }
}

pub(super) fn area_of_code(code: u32) -> Option<S7Area> {
    Some(match code {
        0 => S7Area::PeripheralInput,
        1 => S7Area::Input,
        2 => S7Area::Output,
        3 => S7Area::Flag,
        4 => S7Area::Data,
        5 => S7Area::Instance,
        6 => S7Area::Local,
        7 => S7Area::PreviousLocal,
        _ => return None,
    })
}

/// The detail of a STOP when a call's local data do not fit the L stack.
pub(super) fn fault(text: String) -> Fault {
    (StopCause::Bcf, StopDetail::Text(text))
}

fn data_fault(text: String) -> Fault {
    (StopCause::LzfData, StopDetail::Text(text))
}

impl Cpu {
    /// A STEP 7 block call (the frame is pushed): the caller's registers saved beside it, the
    /// callee's local data placed after the caller's. `false` when the L stack has no room.
    #[inline(always)]
    pub(crate) fn enter_s7_block(&mut self, callee: u16) -> bool {
        // As long as the block stack's room, whose push came first: the slot is there.
        if let Some(saved) = self.s7_frames.get_mut(self.frames.len() - 1) {
            *saved = crate::vm::S7Frame {
                db: self.level.db,
                di: self.level.di,
                local_base: self.level.local_base,
            };
        }
        self.level.local_base = self.level.local_end;
        self.level.local_end = self.level.local_base + self.program.local_bytes(callee);
        self.level.local_end as usize <= self.local.len()
    }

    /// A STEP 7 block's end (its frame popped): the caller's registers back.
    #[inline(always)]
    pub(crate) fn leave_s7_block(&mut self) {
        if let Some(saved) = self.s7_frames.get(self.frames.len()) {
            self.level.db = saved.db;
            self.level.di = saved.di;
            // The called block's locals began where the caller's end.
            self.level.local_end = self.level.local_base;
            self.level.local_base = saved.local_base;
        }
    }

    /// The registers of the running block.
    pub fn running_context(&self) -> Context {
        self.level_context(&self.level, self.frames.len())
    }

    /// The registers of the block `level` runs (the running level or an interrupted one),
    /// whose frames end at `frames` on the block stack.
    pub fn level_context(&self, level: &LevelState, frames: usize) -> Context {
        let previous_local = (frames > level.level_base)
            .then(|| self.s7_frames.get(frames - 1).map(|frame| frame.local_base))
            .flatten();
        Context {
            local_base: level.local_base,
            previous_local,
            db: level.db,
            di: level.di,
            ar2: level.ar2,
            params: level.params,
            frames,
            level_base: level.level_base,
        }
    }

    /// The registers of the block that called the block of `context`.
    pub(crate) fn caller_context(&self, context: Context) -> Option<Context> {
        if context.frames <= context.level_base {
            return None;
        }
        let frame = self.frames.get(context.frames - 1)?;
        let saved = self.s7_frames.get(context.frames - 1)?;
        let below = context.frames - 1;
        let previous_local = (below > context.level_base)
            .then(|| self.s7_frames.get(below - 1).map(|frame| frame.local_base))
            .flatten();
        Some(Context {
            local_base: saved.local_base,
            previous_local,
            db: saved.db,
            di: saved.di,
            // A caller's instance variables reach an FC as copies on the caller's L stack
            // (see `FcCall`), so no caller's AR2 is needed; AR2 as it is stands in.
            ar2: context.ar2,
            params: frame.params,
            frames: below,
            level_base: context.level_base,
        })
    }

    pub fn locate_index(&mut self, place: u16) -> Result<(Located, AccessWidth), Fault> {
        let place = self.program.s7.places[usize::from(place)];
        let context = self.running_context();
        Ok((self.locate(place, context)?, place.width))
    }

    /// Where `place` is, resolved in `context`.
    pub fn locate(&mut self, place: Place, context: Context) -> Result<Located, Fault> {
        if let Some(located) = context.locate(place.target) {
            if let Target::NumberedData { slot, .. } = place.target
                && context.frames == self.frames.len()
            {
                self.level.db = slot;
            }
            return Ok(located);
        }
        Ok(match place.target {
            Target::Peripheral { output, byte } => Located::Peripheral { output, byte },
            Target::PreviousLocal { .. } => {
                return Err(fault(
                    "V (the caller's local data) in a block without caller".into(),
                ));
            }
            Target::Parameter { param, byte, bit } => {
                self.locate_parameter(param, byte, bit, context)?
            }
            Target::Through { param, byte, bit } => {
                self.locate_through(param, context)?.offset(byte, bit)
            }
            Target::InstanceThrough { pointer, byte, bit } => self
                .locate_instance_through(pointer, context)?
                .offset(byte, bit),
            Target::MemoryIndirect { area, pointer } => {
                let pointer_place = self.program.s7.places[usize::from(pointer)];
                let located = self.locate(pointer_place, context)?;
                let value = self.fetch(located, pointer_place.width)?;
                self.locate_pointer(area, value, context)?
            }
            Target::RegisterIndirect { area, ar, offset } => {
                let register = if ar == 1 {
                    self.level.ar1
                } else {
                    self.level.ar2
                };
                let sum = (register & 0x0007_FFFF).wrapping_add(offset & 0x0007_FFFF) & 0x0007_FFFF;
                let area = match area {
                    Some(area) => area,
                    None => area_of_code(register >> 24 & 7)
                        .ok_or_else(|| fault(format!("AR{ar} holds no area")))?,
                };
                self.locate_pointer(area, sum, context)?
            }
            Target::TimerFrom { place: number } | Target::CounterFrom { place: number } => {
                let number_place = self.program.s7.places[usize::from(number)];
                let located = self.locate(number_place, context)?;
                let number = match located {
                    Located::Timer(n) | Located::Counter(n) => n,
                    other => self.fetch(other, AccessWidth::Word)? as u16,
                };
                match place.target {
                    Target::TimerFrom { .. } => Located::Timer(number),
                    _ => Located::Counter(number),
                }
            }
            // The test operands and registers; the others were located above.
            _ => Located::Special(place.target),
        })
    }

    /// An FC parameter: the caller's actual, resolved where the caller stands.
    pub(super) fn locate_parameter(
        &mut self,
        param: u8,
        byte: u32,
        bit: u8,
        context: Context,
    ) -> Result<Located, Fault> {
        let Some(actual) = self.passed(context.params, param) else {
            return Err(fault(format!("parameter {} has no actual", param + 1)));
        };
        match actual {
            Resolved::Constant(value) => Ok(Located::Constant(value)),
            Resolved::S7(index) => {
                let Some(caller) = self.caller_context(context) else {
                    return Err(fault("a parameter outside a called block".into()));
                };
                let place = self.program.s7.places[usize::from(index)];
                let located = self.locate(place, caller)?;
                Ok(located.offset(byte, bit))
            }
            _ => Err(fault(format!("parameter {} cannot be reached", param + 1))),
        }
    }

    /// The address a pointer value (byte << 3 | bit) gives in `area`.
    pub(super) fn locate_pointer(
        &mut self,
        area: S7Area,
        pointer: u32,
        context: Context,
    ) -> Result<Located, Fault> {
        let byte = (pointer >> 3 & 0xFFFF) as usize;
        let bit = (pointer & 7) as u8;
        let layout = self.program.layout;
        let image = |base: u16, size: u16| -> Result<Located, Fault> {
            if byte >= usize::from(size) {
                return Err(fault(format!(
                    "indirect address byte {byte} is past the area's {size} bytes"
                )));
            }
            Ok(Located::Image {
                byte: usize::from(base) + byte,
                bit,
            })
        };
        match area {
            S7Area::Input => image(layout.input_base(), layout.image_bytes),
            S7Area::Output => image(layout.output_base(), layout.image_bytes),
            S7Area::Flag => image(layout.flag_base(), layout.flag_bytes),
            S7Area::Local => Ok(Located::Local {
                byte: context.local_base as usize + byte,
                bit,
            }),
            S7Area::PreviousLocal => match context.previous_local {
                Some(base) => Ok(Located::Local {
                    byte: base as usize + byte,
                    bit,
                }),
                None => Err(fault(
                    "V (the caller's local data) in a block without caller".into(),
                )),
            },
            S7Area::Data => Ok(Located::Data {
                slot: context.db,
                byte,
                bit,
            }),
            S7Area::Instance => Ok(Located::Data {
                slot: context.di,
                byte,
                bit,
            }),
            S7Area::PeripheralInput => Ok(Located::Peripheral {
                output: false,
                byte: byte as u16,
            }),
            S7Area::PeripheralOutput => Ok(Located::Peripheral {
                output: true,
                byte: byte as u16,
            }),
            S7Area::Timer => Ok(Located::Timer(pointer as u16)),
            S7Area::Counter => Ok(Located::Counter(pointer as u16)),
        }
    }

    fn bytes_of(&mut self, located: Located, count: usize) -> Result<&mut [u8], Fault> {
        match located {
            Located::Image { byte, .. } => self
                .image
                .get_mut(byte..byte + count)
                .ok_or_else(|| fault(format!("image byte {byte} is out of range"))),
            Located::Local { byte, .. } => self
                .local
                .get_mut(byte..byte + count)
                .ok_or_else(|| fault("the L stack overflows".into())),
            Located::Data { slot, byte, .. } => {
                if slot == 0 {
                    return Err(data_fault(format!(
                        "data byte {byte} accessed with no data block open"
                    )));
                }
                // The number only for a STOP's text: an access goes by the slot alone.
                let db = |program: &crate::compiler::Program| program.s7.db_number(slot);
                let Some(Some(data)) = self.s7_data.get_mut(usize::from(slot)) else {
                    let text = format!("DB {}", db(&self.program));
                    return Err((StopCause::LzfBlock, StopDetail::Text(text)));
                };
                let length = data.len();
                data.get_mut(byte..byte + count).ok_or_else(|| {
                    data_fault(format!(
                        "DB {} byte {byte} is past the end of its {length} bytes",
                        db(&self.program)
                    ))
                })
            }
            other => Err(fault(format!("{other:?} is not memory"))),
        }
    }

    /// A peripheral access (an indirect one is known only now) within the CPU's modules.
    fn peripheral_in_range(&self, byte: u16, width: AccessWidth) -> Result<(), Fault> {
        let end = usize::from(byte) + width.bytes() as usize;
        if end > self.inputs.len() {
            return Err(fault(format!(
                "peripheral byte {byte} is past the CPU's {} peripheral bytes",
                self.inputs.len()
            )));
        }
        Ok(())
    }

    /// Reads a byte, word or double word (bits: 0 or 1).
    pub fn fetch(&mut self, located: Located, width: AccessWidth) -> Result<u32, Fault> {
        if width == AccessWidth::Bit {
            return self.fetch_bit(located).map(u32::from);
        }
        match located {
            Located::Constant(value) => Ok(value),
            Located::Peripheral { output, byte } => {
                self.peripheral_in_range(byte, width)?;
                let width = io_width(width);
                if output {
                    Err(fault(format!(
                        "peripheral output byte {byte} cannot be read"
                    )))
                } else {
                    Ok(self.read_periphery(width, byte, false))
                }
            }
            Located::Timer(n) => Ok(u32::from(n)),
            Located::Counter(n) => Ok(u32::from(n)),
            Located::Special(_) => Err(fault("not readable".into())),
            memory => {
                let count = width.bytes() as usize;
                let bytes = self.bytes_of(memory, count)?;
                Ok(bytes
                    .iter()
                    .fold(0u32, |value, byte| value << 8 | u32::from(*byte)))
            }
        }
    }

    pub fn store(&mut self, located: Located, width: AccessWidth, value: u32) -> Result<(), Fault> {
        if width == AccessWidth::Bit {
            return self.store_bit(located, value & 1 != 0);
        }
        match located {
            Located::Peripheral { output: true, byte } => {
                self.peripheral_in_range(byte, width)?;
                self.write_periphery(io_width(width), byte, value, false);
                Ok(())
            }
            Located::Peripheral {
                output: false,
                byte,
            } => Err(fault(format!(
                "peripheral input byte {byte} cannot be written"
            ))),
            Located::Constant(_) => Err(fault("a constant cannot be written".into())),
            Located::Timer(_) | Located::Counter(_) | Located::Special(_) => {
                Err(fault("not writable".into()))
            }
            memory => {
                let count = width.bytes() as usize;
                let bytes = self.bytes_of(memory, count)?;
                let all = value.to_be_bytes();
                bytes.copy_from_slice(&all[4 - count..]);
                Ok(())
            }
        }
    }

    pub fn fetch_bit(&mut self, located: Located) -> Result<bool, Fault> {
        match located {
            Located::Constant(value) => Ok(value & 1 != 0),
            Located::Timer(n) => {
                let now = self.clock;
                let timer = self
                    .timers
                    .get_mut(usize::from(n))
                    .ok_or_else(|| fault(format!("T {n} is past the CPU's timers")))?;
                Ok(timer.bit(now))
            }
            Located::Counter(n) => self
                .counters
                .get(usize::from(n))
                .map(|counter| counter.bit())
                .ok_or_else(|| fault(format!("C {n} is past the CPU's counters"))),
            Located::Peripheral { byte, .. } => {
                Err(fault(format!("peripheral byte {byte} has no bit access")))
            }
            Located::Special(_) => Err(fault("not a bit".into())),
            memory => {
                let bit = bit_of(memory);
                let bytes = self.bytes_of(memory, 1)?;
                Ok(bytes[0] >> bit & 1 != 0)
            }
        }
    }

    pub fn store_bit(&mut self, located: Located, value: bool) -> Result<(), Fault> {
        match located {
            Located::Image { .. } | Located::Local { .. } | Located::Data { .. } => {
                let bit = bit_of(located);
                let bytes = self.bytes_of(located, 1)?;
                let mask = 1u8 << bit;
                if value {
                    bytes[0] |= mask;
                } else {
                    bytes[0] &= !mask;
                }
                Ok(())
            }
            other => Err(fault(format!("{other:?} cannot be written as a bit"))),
        }
    }
}

fn bit_of(located: Located) -> u8 {
    match located {
        Located::Image { bit, .. } | Located::Local { bit, .. } | Located::Data { bit, .. } => bit,
        _ => 0,
    }
}

fn io_width(width: AccessWidth) -> crate::compiler::bytecode::Width {
    use crate::compiler::bytecode::Width;
    match width {
        AccessWidth::Bit | AccessWidth::Byte => Width::Byte,
        AccessWidth::Word => Width::Word,
        AccessWidth::Double => Width::Double,
    }
}
