//! Keeping retentive memory while a CPU runs: loaded at the start (a warm restart after power
//! on), written at every STOP, at the end, and at least every so much wall time at a cycle
//! control point, so the file always holds the memory of one moment between two cycles.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use crate::profile::Retentive;
use crate::vm::Cpu;

use super::RetainError;
use super::memory::Retained;

/// What `--retain`, `--retain-every`, `--cold` and `--retain-what-fits` ask for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RetainOptions {
    pub path: PathBuf,
    pub every: Duration,
    /// Start from the source's values and write them.
    pub cold: bool,
    /// Load what still fits of a file that no longer fits the program.
    pub what_fits: bool,
}

/// How the CPU's memory began.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Start {
    /// From the file; with `--retain-what-fits`, what did not fit is listed.
    Loaded { misfits: Vec<String> },
    /// No file yet: the source's values.
    First,
    /// `--cold`: the source's values.
    Cold,
}

impl Start {
    /// The summary's line: how the memory began, and where it is kept.
    pub fn describe(&self, path: &std::path::Path) -> String {
        let path = path.display();
        match self {
            Start::Loaded { misfits } if misfits.is_empty() => {
                format!("retentive memory: loaded from {path}, kept there")
            }
            Start::Loaded { misfits } => format!(
                "retentive memory: what fits loaded from {path}, kept there; not loaded: {}",
                misfits.join("; ")
            ),
            Start::First => {
                format!("retentive memory: a first start from the source's values, kept in {path}")
            }
            Start::Cold => {
                format!("retentive memory: a cold start from the source's values, kept in {path}")
            }
        }
    }
}

/// Writes a CPU's retentive memory to its file.
#[derive(Debug)]
pub struct Keeper {
    pub options: RetainOptions,
    ranges: Retentive,
    last_write: Instant,
}

impl Keeper {
    pub fn new(options: RetainOptions, ranges: Retentive) -> Keeper {
        Keeper {
            options,
            ranges,
            last_write: Instant::now(),
        }
    }

    /// Loads the file into `cpu`, which holds the source's values, unless the start is cold or
    /// the file does not exist yet; a file that does not fit is an error unless
    /// `--retain-what-fits`. A cold start writes the source's values at once.
    pub fn start(&mut self, cpu: &mut Cpu) -> Result<Start, RetainError> {
        let path = &self.options.path;
        if self.options.cold {
            self.write(cpu)?;
            return Ok(Start::Cold);
        }
        if !path.exists() {
            return Ok(Start::First);
        }
        let retained = Retained::read(path)?;
        let misfits = retained.misfits(cpu, self.ranges);
        if !misfits.is_empty() && !self.options.what_fits {
            return Err(RetainError::OutOfDate {
                path: path.clone(),
                misfits,
            });
        }
        retained.load_into(cpu, self.ranges);
        Ok(Start::Loaded { misfits })
    }

    /// At a cycle control point: writes when the interval has passed.
    pub fn at_control_point(&mut self, cpu: &Cpu) -> Result<(), RetainError> {
        if self.last_write.elapsed() < self.options.every {
            return Ok(());
        }
        self.write(cpu)
    }

    /// Writes the retentive memory now (a STOP, the end, a cold restart).
    pub fn write(&mut self, cpu: &Cpu) -> Result<(), RetainError> {
        self.last_write = Instant::now();
        Retained::of(cpu, self.ranges).write(&self.options.path)
    }
}
