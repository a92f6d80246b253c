//! Native code for awl's straight-line stretches: a run of STL operations without a jump, call
//! or block end, compiled with Cranelift into one host function that runs them all on a
//! register file, the CPU's image memory and the data it is given (an instance DB).
//!
//! The crate knows the operations only as [`Step`]s over a status byte whose bits the caller
//! names ([`StatusBits`]) and whose bit-logic rules it passes as tables, so the rules stay where
//! they are written (awl's status word) and the code here only reads them. This is the one
//! crate of awl with `unsafe` code: calling the functions Cranelift wrote.

mod codegen;

use cranelift_codegen::settings::{self, Configurable};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Module, default_libcall_names};

/// The registers a stretch reads and writes, laid out for the native code.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Registers {
    pub accu1: u32,
    pub accu2: u32,
    pub accu3: u32,
    pub accu4: u32,
    /// The status byte in its low bits (see [`StatusBits`]).
    pub status: u32,
}

/// Where the caller keeps each status bit in its status byte: one bit each.
#[derive(Debug, Clone, Copy)]
pub struct StatusBits {
    pub rlo: u8,
    pub first_check: u8,
    pub or: u8,
    pub cc1: u8,
    pub cc0: u8,
    pub ov: u8,
    pub os: u8,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Width {
    Byte,
    Word,
    Double,
}

impl Width {
    fn bytes(self) -> usize {
        match self {
            Width::Byte => 1,
            Width::Word => 2,
            Width::Double => 4,
        }
    }
}

/// What a bit write does to its bit for one value of the RLO.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BitAction {
    Keep,
    Clear,
    Set,
}

/// A comparison of ACCU 2 with ACCU 1 as 16-bit integers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Comparison {
    Equal,
    NotEqual,
    Greater,
    GreaterOrEqual,
    Less,
    LessOrEqual,
}

/// Which memory a step reaches: the image, or the data the stretch is run on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Memory {
    Image,
    Data,
}

/// A place in one of the memories: a byte, and a bit in it for a bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Spot {
    pub memory: Memory,
    pub byte: u16,
    pub bit: u8,
}

/// One operation of a stretch. Offsets are bytes; multi-byte values are big-endian.
#[derive(Debug, Clone, Copy)]
pub enum Step {
    /// A bit scan: the status becomes `table[status << 1 | signal state]`.
    Scan {
        memory: Memory,
        byte: u16,
        bit: u8,
        table: &'static [u8; 512],
    },
    /// A bit write driven by the RLO, then the status becomes `after[status]`.
    Write {
        memory: Memory,
        byte: u16,
        bit: u8,
        rlo_0: BitAction,
        rlo_1: BitAction,
        after: &'static [u8; 256],
    },
    /// The status becomes `table[status]`.
    Status(&'static [u8; 256]),
    /// ACCU 1 moves to ACCU 2, the value at `byte` is loaded into ACCU 1.
    Load {
        memory: Memory,
        width: Width,
        byte: u16,
    },
    /// ACCU 1 moves to ACCU 2, the constant is loaded into ACCU 1.
    LoadConstant(u32),
    /// ACCU 1's low `width` bytes are stored at `byte`.
    Transfer {
        memory: Memory,
        width: Width,
        byte: u16,
    },
    /// The value at `from` copied to `to`, the registers untouched (a call's parameter copy);
    /// `width` `None`: a bit.
    Copy {
        width: Option<Width>,
        from: Spot,
        to: Spot,
    },
    /// A constant's low `width` bytes (`None`: its lowest bit) written to `to`.
    Put {
        width: Option<Width>,
        to: Spot,
        value: u32,
    },
    /// ACCU 2 plus (or minus) ACCU 1 as 16-bit integers into ACCU 1's low word, wrapped; CC 1
    /// and CC 0 by the wrapped result (positive, negative), OV (with OS) on overflow. `stack`:
    /// then ACCU 3 moves to ACCU 2 and ACCU 4 to ACCU 3.
    AddSub { subtract: bool, stack: bool },
    /// The RLO by the comparison, CC 1 and CC 0 for greater and less; the string goes on
    /// (first check set, OR cleared).
    Compare(Comparison),
    /// Nothing.
    Nop,
}

/// A stretch that ends in a jump back to its start: the jump's decision and its effect on the
/// status, as tables over the status byte (0 or 1 in `taken`).
#[derive(Debug, Clone, Copy)]
pub struct LoopBack {
    pub taken: &'static [u8; 256],
    pub after: &'static [u8; 256],
}

/// What [`Code::run`] reports: how many passes of a loop ran (each the stretch and the jump back
/// taken), and whether it ended on the jump not taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Passes {
    pub done: u32,
    pub left_loop: bool,
}

#[derive(Debug)]
pub struct Error(String);

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "native code: {}", self.0)
    }
}

impl std::error::Error for Error {}

fn fail(error: impl std::fmt::Display) -> Error {
    Error(error.to_string())
}

/// Compiles stretches one by one into a module; [`Compiler::finish`] makes them callable.
pub struct Compiler {
    module: JITModule,
    bits: StatusBits,
    image_len: usize,
    functions: Vec<FuncId>,
    /// How many bytes of data each stretch reaches.
    data_lens: Vec<usize>,
    context: cranelift_codegen::Context,
    builder: cranelift_frontend::FunctionBuilderContext,
}

impl Compiler {
    /// A compiler for the host, for stretches on an image of `image_len` bytes; an error when
    /// Cranelift has no backend for the host.
    pub fn new(bits: StatusBits, image_len: usize) -> Result<Self, Error> {
        let mut flags = settings::builder();
        flags.set("opt_level", "speed").map_err(fail)?;
        flags.set("is_pic", "false").map_err(fail)?;
        flags.set("use_colocated_libcalls", "false").map_err(fail)?;
        // The stretches are small and made from checked steps: no IR verification per function.
        flags.set("enable_verifier", "false").map_err(fail)?;
        let isa = cranelift_native::builder()
            .map_err(fail)?
            .finish(settings::Flags::new(flags))
            .map_err(fail)?;
        let module = JITModule::new(JITBuilder::with_isa(isa, default_libcall_names()));
        let context = module.make_context();
        Ok(Compiler {
            module,
            bits,
            image_len,
            functions: Vec::new(),
            data_lens: Vec::new(),
            context,
            builder: cranelift_frontend::FunctionBuilderContext::new(),
        })
    }

    /// Adds a stretch, and with `loop_back` the jump after it back to its start; its index in
    /// [`Code::run`] is the number of stretches added before it. An image offset beyond the
    /// image is an error; the data it is run on must reach as far as its steps do.
    pub fn add(&mut self, steps: &[Step], loop_back: Option<LoopBack>) -> Result<usize, Error> {
        let spots = || steps.iter().flat_map(spots);
        if let Some((memory, end)) =
            spots().find(|&(memory, end)| memory == Memory::Image && end > self.image_len)
        {
            return Err(Error(format!(
                "{memory:?} up to byte {end} is past the image"
            )));
        }
        let data_len = spots()
            .filter(|(memory, _)| *memory == Memory::Data)
            .map(|(_, end)| end)
            .max()
            .unwrap_or(0);
        let pointer = self.module.target_config().pointer_type();
        let mut signature = self.module.make_signature();
        // (registers, image, data, most passes) -> passes: see `Entry`.
        let int = cranelift_codegen::ir::types::I32;
        let param = cranelift_codegen::ir::AbiParam::new;
        signature.params = vec![param(pointer), param(pointer), param(pointer), param(int)];
        signature.returns = vec![param(int)];
        let name = format!("stretch{}", self.functions.len());
        let id = self
            .module
            .declare_function(&name, cranelift_module::Linkage::Local, &signature)
            .map_err(fail)?;
        self.context.func.signature = signature;
        codegen::build(
            &mut self.context.func,
            &mut self.builder,
            self.module.target_config(),
            self.bits,
            steps,
            loop_back,
        );
        self.module
            .define_function(id, &mut self.context)
            .map_err(fail)?;
        self.module.clear_context(&mut self.context);
        self.functions.push(id);
        self.data_lens.push(data_len);
        Ok(self.functions.len() - 1)
    }

    /// The compiled stretches, ready to run.
    pub fn finish(mut self) -> Result<Code, Error> {
        self.module.finalize_definitions().map_err(fail)?;
        let entries = self
            .functions
            .iter()
            .map(|&id| {
                let address = self.module.get_finalized_function(id);
                // SAFETY: `codegen::build` gave every function this signature: three pointers
                // and a 32-bit count in, a 32-bit result, the target's default calling convention
                // (`extern "C"`).
                unsafe { std::mem::transmute::<*const u8, Entry>(address) }
            })
            .collect();
        Ok(Code {
            module: Some(self.module),
            entries,
            image_len: self.image_len,
            data_lens: self.data_lens,
        })
    }
}

/// The memories a step reaches, each with the end of what it reaches there (a bit past its
/// byte's 8 reaches past any memory).
fn spots(step: &Step) -> Vec<(Memory, usize)> {
    let end = |byte: u16, width: Option<Width>, bit: u8| match width {
        Some(width) => usize::from(byte) + width.bytes(),
        None if bit < 8 => usize::from(byte) + 1,
        None => usize::MAX,
    };
    let spot = |spot: Spot, width| (spot.memory, end(spot.byte, width, spot.bit));
    match *step {
        Step::Scan {
            memory, byte, bit, ..
        }
        | Step::Write {
            memory, byte, bit, ..
        } => vec![(memory, end(byte, None, bit))],
        Step::Load {
            memory,
            width,
            byte,
        }
        | Step::Transfer {
            memory,
            width,
            byte,
        } => vec![(memory, end(byte, Some(width), 0))],
        Step::Copy { width, from, to } => vec![spot(from, width), spot(to, width)],
        Step::Put { width, to, .. } => vec![spot(to, width)],
        _ => Vec::new(),
    }
}

type Entry = extern "C" fn(*mut Registers, *mut u8, *mut u8, u32) -> u32;

/// Compiled stretches. The code lives as long as this value.
pub struct Code {
    module: Option<JITModule>,
    entries: Vec<Entry>,
    image_len: usize,
    data_lens: Vec<usize>,
}

impl Code {
    /// Runs stretch `index` on `registers`, `image` and `data`: a loop's stretch with its jump
    /// back for up to `most` passes, or (`most` 0, or a stretch without a loop) the stretch
    /// once. The image must be as long as the one the stretches were compiled for, the data as
    /// long as the stretch reaches; an unknown index or shorter memory runs nothing (`None`).
    #[inline(always)]
    pub fn run(
        &self,
        index: usize,
        registers: &mut Registers,
        (image, data): (&mut [u8], &mut [u8]),
        most: u32,
    ) -> Option<Passes> {
        let entry = self.entries.get(index)?;
        if image.len() < self.image_len || data.len() < self.data_lens[index] {
            return None;
        }
        // Every offset the code uses was checked against `image_len` when it was compiled, and
        // against the data's length just above.
        let memories = (image.as_mut_ptr(), data.as_mut_ptr());
        let result = entry(
            registers,
            memories.0,
            memories.1,
            most.min(!codegen::NOT_TAKEN),
        );
        Some(Passes {
            done: result & !codegen::NOT_TAKEN,
            left_loop: result & codegen::NOT_TAKEN != 0,
        })
    }

    /// How many stretches there are.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}

// SAFETY: after `finalize_definitions` the module's memory is read-only code that no method
// changes, and the functions touch only what their arguments point to: sharing `Code` between
// threads, or moving it to another, shares or moves immutable machine code.
unsafe impl Send for Code {}
unsafe impl Sync for Code {}

impl Drop for Code {
    fn drop(&mut self) {
        self.entries.clear();
        if let Some(module) = self.module.take() {
            // SAFETY: the entries into the module's memory were dropped just above, and no
            // caller holds one: `run` borrows `self`.
            unsafe { module.free_memory() };
        }
    }
}

impl std::fmt::Debug for Code {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Code({} stretches)", self.entries.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BITS: StatusBits = StatusBits {
        rlo: 1,
        first_check: 2,
        or: 4,
        cc1: 8,
        cc0: 16,
        ov: 32,
        os: 64,
    };

    fn compile(steps: &[Step], loop_back: Option<LoopBack>) -> Code {
        let mut compiler = Compiler::new(BITS, 16).expect("a host Cranelift knows");
        compiler.add(steps, loop_back).expect("compiled");
        compiler.finish().expect("finished")
    }

    #[test]
    fn words_are_loaded_added_and_stored_big_endian_with_the_condition_codes() {
        let code = compile(
            &[
                Step::Load {
                    memory: Memory::Image,
                    width: Width::Word,
                    byte: 0,
                },
                Step::LoadConstant(1),
                Step::AddSub {
                    subtract: false,
                    stack: false,
                },
                Step::Transfer {
                    memory: Memory::Image,
                    width: Width::Word,
                    byte: 2,
                },
            ],
            None,
        );
        let mut image = [0u8; 16];
        image[..2].copy_from_slice(&0x7FFFu16.to_be_bytes());
        let mut registers = Registers::default();
        let ran = code.run(0, &mut registers, (&mut image, &mut []), 0);
        assert_eq!(ran.map(|passes| passes.done), Some(0));
        // 32767 + 1 overflows to -32768: negative, OV and OS.
        assert_eq!(image[2..4], 0x8000u16.to_be_bytes());
        assert_eq!(registers.status, u32::from(BITS.cc0 | BITS.ov | BITS.os));
        assert_eq!((registers.accu1, registers.accu2), (0x8000, 0x7FFF));
    }

    #[test]
    fn a_loop_runs_its_passes_until_the_jump_is_not_taken_or_the_passes_are_done() {
        // Counts the word at 0 down; the jump back is taken while CC 1 (positive) is set.
        static TAKEN: [u8; 256] = {
            let mut table = [0; 256];
            let mut status = 0;
            while status < 256 {
                table[status] = (status & 8 != 0) as u8;
                status += 1;
            }
            table
        };
        static SAME: [u8; 256] = {
            let mut table = [0; 256];
            let mut status = 0;
            while status < 256 {
                table[status] = status as u8;
                status += 1;
            }
            table
        };
        let steps = [
            Step::Load {
                memory: Memory::Image,
                width: Width::Word,
                byte: 0,
            },
            Step::LoadConstant(1),
            Step::AddSub {
                subtract: true,
                stack: false,
            },
            Step::Transfer {
                memory: Memory::Image,
                width: Width::Word,
                byte: 0,
            },
        ];
        let loop_back = LoopBack {
            taken: &TAKEN,
            after: &SAME,
        };
        let code = compile(&steps, Some(loop_back));
        let mut image = [0u8; 16];
        image[1] = 10;
        let mut registers = Registers::default();
        let passes = code.run(0, &mut registers, (&mut image, &mut []), 4);
        assert_eq!(
            passes,
            Some(Passes {
                done: 4,
                left_loop: false
            })
        );
        assert_eq!(image[1], 6);
        let passes = code.run(0, &mut registers, (&mut image, &mut []), 100);
        // Five passes down to 1, then the body once more to 0 and the jump not taken.
        assert_eq!(
            passes,
            Some(Passes {
                done: 5,
                left_loop: true
            })
        );
        assert_eq!(image[1], 0);
        assert!(
            code.run(1, &mut registers, (&mut image, &mut []), 1)
                .is_none()
        );
        assert!(
            code.run(0, &mut registers, (&mut image[..8], &mut []), 1)
                .is_none()
        );
    }

    #[test]
    fn copies_and_data_steps_reach_the_data_and_the_image_without_the_registers() {
        let image_bit = Spot {
            memory: Memory::Image,
            byte: 1,
            bit: 3,
        };
        let data_bit = Spot {
            memory: Memory::Data,
            byte: 0,
            bit: 6,
        };
        let data_word = Spot {
            memory: Memory::Data,
            byte: 2,
            bit: 0,
        };
        let code = compile(
            &[
                Step::Copy {
                    width: None,
                    from: image_bit,
                    to: data_bit,
                },
                Step::Copy {
                    width: Some(Width::Word),
                    from: Spot {
                        memory: Memory::Image,
                        byte: 4,
                        bit: 0,
                    },
                    to: data_word,
                },
                Step::Put {
                    width: Some(Width::Byte),
                    to: Spot {
                        memory: Memory::Data,
                        byte: 4,
                        bit: 0,
                    },
                    value: 0x1FF,
                },
                Step::Load {
                    memory: Memory::Data,
                    width: Width::Word,
                    byte: 2,
                },
                Step::Transfer {
                    memory: Memory::Image,
                    width: Width::Word,
                    byte: 8,
                },
            ],
            None,
        );
        let mut image = [0u8; 16];
        image[1] = 1 << 3;
        image[4..6].copy_from_slice(&0x1234u16.to_be_bytes());
        let mut data = [0u8; 5];
        let mut registers = Registers::default();
        assert!(
            code.run(0, &mut registers, (&mut image, &mut data[..4]), 0)
                .is_none()
        );
        assert!(
            code.run(0, &mut registers, (&mut image, &mut data), 0)
                .is_some()
        );
        assert_eq!(data, [1 << 6, 0, 0x12, 0x34, 0xFF]);
        assert_eq!(image[8..10], 0x1234u16.to_be_bytes());
        assert_eq!(registers.accu1, 0x1234);
    }
}
