//! Retentive memory: the part of the memory areas a power cycle leaves, cut by the retentive
//! ranges, saved with the ranges, the CPU and the simulated time it was taken at.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::profile::Retentive;
use crate::vm::Cpu;
use crate::vm::saved::{Bytes, Memory};

use super::RetainError;
use super::file::{self, Kind};

pub const KIND: Kind = Kind {
    format: "awl-retain",
    name: "a retentive memory file",
};

/// The retentive ranges as the file records them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Ranges {
    pub flag_bytes: u16,
    pub timers: u16,
    pub counters: u16,
    pub data_blocks: bool,
}

impl From<Retentive> for Ranges {
    fn from(ranges: Retentive) -> Ranges {
        Ranges {
            flag_bytes: ranges.flag_bytes,
            timers: ranges.timers,
            counters: ranges.counters,
            data_blocks: ranges.data_blocks,
        }
    }
}

/// A retentive memory file's body.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Retained {
    /// The CPU profile it was written by.
    pub cpu: String,
    pub ranges: Ranges,
    /// The simulated time it was taken at (its timers' times count from it).
    pub clock_ns: u64,
    pub memory: Memory,
}

impl Retained {
    /// The retentive part of `cpu`'s memory now.
    pub fn of(cpu: &Cpu, ranges: Retentive) -> Retained {
        let memory = cpu.memory();
        let cut = |count: u16, len: usize| usize::from(count).min(len);
        Retained {
            cpu: cpu.profile.name.to_string(),
            ranges: ranges.into(),
            clock_ns: cpu.clock,
            memory: Memory {
                flags: Bytes(
                    memory.flags.0[..cut(ranges.flag_bytes, memory.flags.0.len())].to_vec(),
                ),
                timers: memory.timers[..cut(ranges.timers, memory.timers.len())].to_vec(),
                counters: memory.counters[..cut(ranges.counters, memory.counters.len())].to_vec(),
                data_blocks: if ranges.data_blocks {
                    memory.data_blocks
                } else {
                    Vec::new()
                },
            },
        }
    }

    pub fn read(path: &Path) -> Result<Retained, RetainError> {
        file::read(KIND, path)
    }

    pub fn write(&self, path: &Path) -> Result<(), RetainError> {
        file::write_durably(path, &file::encode(KIND, self))
    }

    /// What of the file does not fit `cpu` with `ranges`: another CPU, other ranges, areas
    /// or data blocks of other sizes.
    pub fn misfits(&self, cpu: &Cpu, ranges: Retentive) -> Vec<String> {
        let mut misfits = Vec::new();
        if self.cpu != cpu.profile.name {
            misfits.push(format!(
                "it was written by the {} CPU, this run's is {}",
                self.cpu, cpu.profile.name
            ));
        }
        let now: Ranges = ranges.into();
        if self.ranges != now {
            let flag = if cpu.profile.runs_step7() { "M" } else { "F" };
            let describe = |ranges: Ranges| {
                Retentive {
                    flag_bytes: ranges.flag_bytes,
                    timers: ranges.timers,
                    counters: ranges.counters,
                    data_blocks: ranges.data_blocks,
                }
                .describe(flag)
            };
            misfits.push(format!(
                "its retentive ranges are {}, this run's {}",
                describe(self.ranges),
                describe(now)
            ));
        }
        let data_blocks = Some(self.ranges.data_blocks && now.data_blocks);
        misfits.extend(
            cpu.memory_misfits(&self.memory, data_blocks)
                .into_iter()
                .map(|misfit| misfit.0),
        );
        misfits
    }

    /// Loads what fits of the file into `cpu`'s retentive ranges `ranges`.
    pub fn load_into(&self, cpu: &mut Cpu, ranges: Retentive) {
        let cut = Memory {
            flags: Bytes(
                self.memory.flags.0
                    [..usize::from(ranges.flag_bytes).min(self.memory.flags.0.len())]
                    .to_vec(),
            ),
            timers: self.memory.timers[..usize::from(ranges.timers).min(self.memory.timers.len())]
                .to_vec(),
            counters: self.memory.counters
                [..usize::from(ranges.counters).min(self.memory.counters.len())]
                .to_vec(),
            data_blocks: self.memory.data_blocks.clone(),
        };
        cpu.take_memory(&cut, Some(ranges.data_blocks), self.clock_ns);
    }
}
