//! Retentive memory: the flags, timers, counters and data blocks a CPU keeps through a power
//! cycle (battery-backed RAM, retentive flash), as each family's manual presets them. The
//! scenario's `[retentive]` table sets them as a hardware configuration would.

use super::{Family, Profile};

/// What survives a power cycle: the first `flag_bytes` flag bytes (from FB 0 / MB 0), the first
/// `timers` timers and `counters` counters, and the data blocks when `data_blocks` is set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Retentive {
    pub flag_bytes: u16,
    pub timers: u16,
    pub counters: u16,
    pub data_blocks: bool,
}

/// A family's preset, with the manual it comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Preset {
    pub ranges: Retentive,
    pub source: &'static str,
}

/// The S7-300 class presets 16 flag bytes, 8 counters and no timers; data blocks are
/// retentive unless made "non-retain".
const S7_SOURCE: &str = "S7-300 CPU 31xC and CPU 31x: Technical data, 4.1.3 Retentivity of \
     memory objects and the technical specifications (retentivity preset MB 0 to MB 15, C 0 to \
     C 7, no timers; DBs retentive); VIPA SPEED7 CPU manual, technical data (the same presets)";

/// The S5 CPUs keep their data blocks in battery-backed RAM; of the flags, timers and counters
/// the first half is retentive at a cold restart unless DX 0 sets otherwise.
const S5_SOURCE: &str = "S5-115U/135U/155U manuals, cold restart (Neustart) and the DX 0 \
     parameters: the first half of the flags, timers and counters is retentive with battery \
     backup; data blocks are kept in the battery-backed user memory";

/// The 840C's PLC CPU is the S5-135U's CPU 928B.
const SINUMERIK_SOURCE: &str = "the SINUMERIK 840C PLC's CPU 928B is an S5-135U CPU: the \
     S5-135U manual's presets (cold restart and DX 0: the first half of the flags, timers and \
     counters retentive; data blocks in the battery-backed user memory)";

/// The S5-95F's manual says what the battery keeps, not how it is split.
const S5_95F_SOURCE: &str = "S5-95F manual, 2.5.5 Function of the Backup Battery (the internal \
     RAM is retained through a power failure); the split into a retentive first half of the \
     flags, timers and counters is the larger S5 CPUs' preset";

impl Profile {
    /// The retentive ranges the CPU has unless the scenario sets others.
    pub fn retentive(&self) -> Preset {
        match self.family {
            Family::Speed7 => Preset {
                ranges: Retentive {
                    flag_bytes: 16,
                    timers: 0,
                    counters: 8,
                    data_blocks: true,
                },
                source: S7_SOURCE,
            },
            Family::Sinumerik840c => self.first_half_retentive(SINUMERIK_SOURCE),
            Family::S5_95f => self.first_half_retentive(S5_95F_SOURCE),
            Family::S5 => self.first_half_retentive(S5_SOURCE),
        }
    }
}

impl Profile {
    /// The S5 CPUs' preset: the first half of the flags, timers and counters, and the data
    /// blocks.
    fn first_half_retentive(&self, source: &'static str) -> Preset {
        Preset {
            ranges: Retentive {
                flag_bytes: self.sizes.flag_bytes / 2,
                timers: self.sizes.timers / 2,
                counters: self.sizes.counters / 2,
                data_blocks: true,
            },
            source,
        }
    }
}

impl Retentive {
    /// `F 0…127, T 0…63, C 0…63, data blocks`: the ranges as `awl cpus` and the diagnostics
    /// name them, in the CPU's own flag letter.
    pub fn describe(&self, flag: &str) -> String {
        let range = |letter: &str, count: u16| match count {
            0 => format!("no {letter}"),
            _ => format!("{letter} 0…{}", count - 1),
        };
        format!(
            "{}, {}, {}, {}",
            range(&format!("{flag}B"), self.flag_bytes),
            range("T", self.timers),
            range("C", self.counters),
            if self.data_blocks {
                "data blocks"
            } else {
                "no data blocks"
            }
        )
    }
}
