//! The CPU's state at a cycle control point as plain data: the whole of it for a snapshot,
//! and the memory areas retentive memory is cut from. Byte areas are written as hex; S5 data
//! blocks as their words' bytes, high byte first.

use serde::{Deserialize, Serialize};

use super::counters::Counter;
use super::cycle::CycleTimes;
use super::interrupts::EngineState;
use super::timers::Timer;
use super::{Cpu, Mode};

/// Bytes as a hex string in the file.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Bytes(pub Vec<u8>);

impl Serialize for Bytes {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&data_encoding::HEXLOWER.encode(&self.0))
    }
}

impl<'de> Deserialize<'de> for Bytes {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        data_encoding::HEXLOWER_PERMISSIVE
            .decode(text.as_bytes())
            .map(Bytes)
            .map_err(|_| serde::de::Error::custom("not a string of hex digits"))
    }
}

/// One data block's contents.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DataBlock {
    pub number: u16,
    pub bytes: Bytes,
}

/// The memory areas a program keeps its data in: flags, timers, counters, data blocks.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Memory {
    pub flags: Bytes,
    #[serde(with = "sparse")]
    pub timers: Vec<Timer>,
    #[serde(with = "sparse")]
    pub counters: Vec<Counter>,
    pub data_blocks: Vec<DataBlock>,
}

/// Timers and counters as their number and those not as the CPU starts them, by index: most
/// of a CPU's hundreds are never used.
mod sparse {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    #[derive(Serialize, Deserialize)]
    struct Sparse<T> {
        count: usize,
        used: Vec<(usize, T)>,
    }

    pub fn serialize<T, S>(items: &[T], serializer: S) -> Result<S::Ok, S::Error>
    where
        T: Serialize + Default + PartialEq + Clone,
        S: Serializer,
    {
        let unused = T::default();
        Sparse {
            count: items.len(),
            used: items
                .iter()
                .enumerate()
                .filter(|(_, item)| **item != unused)
                .map(|(index, item)| (index, item.clone()))
                .collect(),
        }
        .serialize(serializer)
    }

    pub fn deserialize<'de, T, D>(deserializer: D) -> Result<Vec<T>, D::Error>
    where
        T: Deserialize<'de> + Default + Clone,
        D: Deserializer<'de>,
    {
        let sparse = Sparse::<T>::deserialize(deserializer)?;
        let mut items = vec![T::default(); sparse.count];
        for (index, item) in sparse.used {
            let slot = items
                .get_mut(index)
                .ok_or_else(|| serde::de::Error::custom("an index past the count"))?;
            *slot = item;
        }
        Ok(items)
    }
}

/// Everything the CPU's future depends on, between two cycles.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct CpuState {
    pub mode: Mode,
    /// Simulated time, ns.
    pub clock_ns: u64,
    pub cycle: u64,
    pub instructions: u64,
    /// The PII and the PIQ.
    pub inputs: Bytes,
    pub outputs: Bytes,
    /// The input and output modules, and the extended peripheral area's.
    pub input_modules: Bytes,
    pub output_modules: Bytes,
    pub extended_input_modules: Bytes,
    pub extended_output_modules: Bytes,
    pub memory: Memory,
    /// What OB 1's level left in the registers at the last cycle's end.
    pub registers: Registers,
    pub clock_origin_ns: u64,
    pub clock_set_ms: i64,
    pub cycle_times: CycleTimes,
    pub engine: EngineState,
}

/// The registers a level keeps from one cycle to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Registers {
    pub accus: [u32; 4],
    pub status: crate::rules::status::Status,
    pub br: bool,
    pub ar1: u32,
    pub ar2: u32,
    /// The DB and DI registers' slots, and the open STEP 5 data block.
    pub db: u16,
    pub di: u16,
    pub open_db: Option<u8>,
}

/// What of a saved state does not fit the CPU it is to be loaded into.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Misfit(pub String);

impl Cpu {
    /// The memory areas as they are now.
    pub fn memory(&self) -> Memory {
        let layout = self.program.layout;
        let flags = usize::from(layout.flag_base());
        Memory {
            flags: Bytes(self.image[flags..flags + usize::from(layout.flag_bytes)].to_vec()),
            timers: self.timers.clone(),
            counters: self.counters.clone(),
            data_blocks: self.data_block_contents(),
        }
    }

    fn data_block_contents(&self) -> Vec<DataBlock> {
        let s5 = (0u16..)
            .zip(&self.data_blocks)
            .filter_map(|(number, words)| {
                let words = words.as_ref()?;
                let bytes = words.iter().flat_map(|word| word.to_be_bytes()).collect();
                Some(DataBlock {
                    number,
                    bytes: Bytes(bytes),
                })
            });
        let s7 = self
            .program
            .s7
            .db_numbers
            .iter()
            .zip(&self.s7_data)
            .filter_map(|(number, bytes)| {
                Some(DataBlock {
                    number: *number,
                    bytes: Bytes(bytes.as_ref()?.clone()),
                })
            });
        s5.chain(s7).collect()
    }

    /// The whole state, between two cycles.
    pub fn state(&self) -> CpuState {
        let layout = self.program.layout;
        let image = |base: u16| {
            let base = usize::from(base);
            Bytes(self.image[base..base + usize::from(layout.image_bytes)].to_vec())
        };
        CpuState {
            mode: self.mode,
            clock_ns: self.clock,
            cycle: self.cycle,
            instructions: self.instructions,
            inputs: image(layout.input_base()),
            outputs: image(layout.output_base()),
            input_modules: Bytes(self.inputs.clone()),
            output_modules: Bytes(self.outputs.clone()),
            extended_input_modules: Bytes(self.extended_inputs.clone()),
            extended_output_modules: Bytes(self.extended_outputs.clone()),
            memory: self.memory(),
            registers: Registers {
                accus: [
                    self.level.accu1,
                    self.level.accu2,
                    self.level.accu3,
                    self.level.accu4,
                ],
                status: self.level.status,
                br: self.level.br,
                ar1: self.level.ar1,
                ar2: self.level.ar2,
                db: self.level.db,
                di: self.level.di,
                open_db: self.level.open_db,
            },
            clock_origin_ns: self.clock_origin_ns,
            clock_set_ms: self.clock_set_ms,
            cycle_times: self.cycle_times,
            engine: self.engine.saved(),
        }
    }

    /// Takes up a state [`Cpu::state`] gave, of a CPU with this program's memory shape. What
    /// does not fit is listed and, with `keep_fitting`, left as it is; without, nothing is
    /// taken up when something does not fit.
    pub fn restore(&mut self, state: &CpuState, keep_fitting: bool) -> Result<(), Vec<Misfit>> {
        let mut misfits = Vec::new();
        let layout = self.program.layout;
        let image_bytes = usize::from(layout.image_bytes);
        let shaped = |what: &str, bytes: &Bytes, size: usize, misfits: &mut Vec<Misfit>| {
            if bytes.0.len() != size {
                misfits.push(Misfit(format!(
                    "{what}: {} bytes saved, the CPU has {size}",
                    bytes.0.len()
                )));
            }
        };
        shaped("the PII", &state.inputs, image_bytes, &mut misfits);
        shaped("the PIQ", &state.outputs, image_bytes, &mut misfits);
        let modules = self.inputs.len();
        shaped(
            "the input modules",
            &state.input_modules,
            modules,
            &mut misfits,
        );
        shaped(
            "the output modules",
            &state.output_modules,
            modules,
            &mut misfits,
        );
        shaped(
            "the extended inputs",
            &state.extended_input_modules,
            modules,
            &mut misfits,
        );
        shaped(
            "the extended outputs",
            &state.extended_output_modules,
            modules,
            &mut misfits,
        );
        misfits.extend(self.memory_misfits(&state.memory, None));
        if !misfits.is_empty() && !keep_fitting {
            return Err(misfits);
        }
        let copy = |target: &mut [u8], bytes: &Bytes| {
            let count = target.len().min(bytes.0.len());
            target[..count].copy_from_slice(&bytes.0[..count]);
        };
        let (input, output) = (
            usize::from(layout.input_base()),
            usize::from(layout.output_base()),
        );
        copy(&mut self.image[input..input + image_bytes], &state.inputs);
        copy(
            &mut self.image[output..output + image_bytes],
            &state.outputs,
        );
        copy(&mut self.inputs, &state.input_modules);
        copy(&mut self.outputs, &state.output_modules);
        copy(&mut self.extended_inputs, &state.extended_input_modules);
        copy(&mut self.extended_outputs, &state.extended_output_modules);
        self.mode = state.mode;
        self.clock = state.clock_ns;
        self.take_memory(&state.memory, None, state.clock_ns);
        let registers = state.registers;
        [
            self.level.accu1,
            self.level.accu2,
            self.level.accu3,
            self.level.accu4,
        ] = registers.accus;
        self.level.status = registers.status;
        self.level.br = registers.br;
        self.level.ar1 = registers.ar1;
        self.level.ar2 = registers.ar2;
        self.level.db = registers.db;
        self.level.di = registers.di;
        self.level.open_db = registers.open_db;
        self.cycle = state.cycle;
        self.instructions = state.instructions;
        self.cycle_started_at = state.clock_ns;
        self.last_point_at = state.clock_ns;
        self.clock_origin_ns = state.clock_origin_ns;
        self.clock_set_ms = state.clock_set_ms;
        self.cycle_times = state.cycle_times;
        if let Err(why) = self.engine.restore(&state.engine, state.clock_ns) {
            return Err(vec![Misfit(why.to_string())]);
        }
        self.update_attention();
        Ok(())
    }

    /// What of `memory` does not fit this CPU: an area longer than the CPU's, a data block the
    /// program lacks, has not, or has at another length. `retentive` limits the comparison to
    /// the data blocks retentive memory holds (all, or none).
    pub fn memory_misfits(&self, memory: &Memory, retentive: Option<bool>) -> Vec<Misfit> {
        let mut misfits = Vec::new();
        let flag_bytes = usize::from(self.program.layout.flag_bytes);
        if memory.flags.0.len() > flag_bytes {
            misfits.push(Misfit(format!(
                "{} flag bytes saved, the CPU has {flag_bytes}",
                memory.flags.0.len()
            )));
        }
        let too_many = |what: &str, saved: usize, has: usize, misfits: &mut Vec<Misfit>| {
            if saved > has {
                misfits.push(Misfit(format!("{saved} {what} saved, the CPU has {has}")));
            }
        };
        too_many(
            "timers",
            memory.timers.len(),
            self.timers.len(),
            &mut misfits,
        );
        too_many(
            "counters",
            memory.counters.len(),
            self.counters.len(),
            &mut misfits,
        );
        if retentive == Some(false) {
            return misfits;
        }
        let here = self.data_block_contents();
        for saved in &memory.data_blocks {
            match here.iter().find(|block| block.number == saved.number) {
                None => misfits.push(Misfit(format!(
                    "DB {} is saved, the program has no DB {}",
                    saved.number, saved.number
                ))),
                Some(block) if block.bytes.0.len() != saved.bytes.0.len() => {
                    misfits.push(Misfit(format!(
                        "DB {} is {} bytes long in the program, {} in the file",
                        saved.number,
                        block.bytes.0.len(),
                        saved.bytes.0.len()
                    )))
                }
                Some(_) => {}
            }
        }
        for block in &here {
            if !memory
                .data_blocks
                .iter()
                .any(|saved| saved.number == block.number)
            {
                misfits.push(Misfit(format!(
                    "DB {} is in the program, not in the file",
                    block.number
                )));
            }
        }
        misfits
    }

    /// Writes what of `memory` fits over the CPU's memory; timers saved at `saved_at_ns` keep
    /// the time they had left. `data_blocks`: only these (`None`: every one saved).
    pub fn take_memory(&mut self, memory: &Memory, data_blocks: Option<bool>, saved_at_ns: u64) {
        let layout = self.program.layout;
        let flags = usize::from(layout.flag_base());
        let count = memory.flags.0.len().min(usize::from(layout.flag_bytes));
        self.image[flags..flags + count].copy_from_slice(&memory.flags.0[..count]);
        let now = self.clock;
        for (timer, saved) in self.timers.iter_mut().zip(&memory.timers) {
            *timer = saved.carried(saved_at_ns, now);
        }
        for (counter, saved) in self.counters.iter_mut().zip(&memory.counters) {
            *counter = *saved;
        }
        if data_blocks == Some(false) {
            return;
        }
        for saved in &memory.data_blocks {
            self.take_data_block(saved);
        }
    }

    /// A data block's saved bytes, when the program has the block at that length.
    fn take_data_block(&mut self, saved: &DataBlock) {
        let bytes = &saved.bytes.0;
        if let Some(data) = self.s7_db_mut(saved.number) {
            if data.len() == bytes.len() {
                data.copy_from_slice(bytes);
            }
            return;
        }
        let words = self
            .data_blocks
            .get_mut(usize::from(saved.number))
            .and_then(Option::as_mut);
        if let Some(words) = words
            && words.len() * 2 == bytes.len()
        {
            for (word, pair) in words.iter_mut().zip(bytes.chunks_exact(2)) {
                *word = u16::from_be_bytes([pair[0], pair[1]]);
            }
        }
    }
}
