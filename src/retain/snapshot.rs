//! Snapshots: the whole CPU between two cycles (every area, timers with their time left,
//! counters, data blocks, the interrupt engine, the mode and the simulated time), to continue
//! from with `--from`.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::vm::Cpu;
use crate::vm::saved::CpuState;

use super::RetainError;
use super::file::{self, Kind};

pub const KIND: Kind = Kind {
    format: "awl-snapshot",
    name: "a snapshot",
};

/// A snapshot file's body.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The CPU profile it was taken of.
    pub cpu: String,
    pub state: CpuState,
}

impl Snapshot {
    pub fn of(cpu: &Cpu) -> Snapshot {
        Snapshot {
            cpu: cpu.profile.name.to_string(),
            state: cpu.state(),
        }
    }

    /// The file's text.
    pub fn encode(&self) -> String {
        file::encode(KIND, self)
    }

    pub fn read(path: &Path) -> Result<Snapshot, RetainError> {
        file::read(KIND, path)
    }

    pub fn write(&self, path: &Path) -> Result<(), RetainError> {
        file::write_durably(path, &self.encode())
    }

    /// Continues `cpu` from the snapshot read from `path`; with `what_fits`, what does not fit
    /// the program is left as the program loads it.
    pub fn continue_in(
        &self,
        cpu: &mut Cpu,
        path: &Path,
        what_fits: bool,
    ) -> Result<(), RetainError> {
        let mut misfits = Vec::new();
        if self.cpu != cpu.profile.name {
            misfits.push(format!(
                "it was taken of the {} CPU, this run's is {}",
                self.cpu, cpu.profile.name
            ));
        }
        if let Err(found) = cpu.restore(&self.state, what_fits) {
            misfits.extend(found.into_iter().map(|misfit| misfit.0));
        }
        if misfits.is_empty() || what_fits && self.cpu == cpu.profile.name {
            return Ok(());
        }
        Err(RetainError::OutOfDate {
            path: path.to_path_buf(),
            misfits,
        })
    }
}

/// A file name beside `program` no snapshot has yet: `tank.snapshot-1.json`, `-2`, …
pub fn beside(program: &Path) -> PathBuf {
    let stem = program.file_stem().unwrap_or_default().to_string_lossy();
    (1..)
        .map(|number| program.with_file_name(format!("{stem}.snapshot-{number}.json")))
        .find(|path| !path.exists())
        .expect("some number is free")
}
