//! A run's memory from outside it and to outside it: the snapshot it continues from
//! (`--from`), the retentive memory it starts with and keeps (`--retain`), and the snapshot it
//! writes (`--snapshot`). All of it happens at cycle control points, so every file holds the
//! memory of one moment between two cycles.

use std::path::PathBuf;

use miette::Report;

use crate::profile::Retentive;
use crate::retain::keeper::Start;
use crate::retain::{Keeper, RetainError, Snapshot};
use crate::vm::Cpu;

use super::{NotRun, RunOptions};

/// What the run keeps outside itself.
#[derive(Debug, Default)]
pub struct Persistence {
    pub keeper: Option<Keeper>,
    /// Where a snapshot goes and from when; taken once.
    snapshot_to: Option<(PathBuf, Option<u64>)>,
    /// How the memory began, and its file, for the summary.
    pub start: Option<(Start, PathBuf)>,
    /// The first write that failed: reported once, at the end.
    failed: Option<RetainError>,
}

impl Persistence {
    /// Puts the snapshot or the retentive memory into `cpu`, which holds the program as
    /// loaded; a file that cannot be read or does not fit ends the run before it starts.
    pub fn begin(
        options: &RunOptions,
        cpu: &mut Cpu,
        ranges: Retentive,
    ) -> Result<Persistence, NotRun> {
        let failed = |error: RetainError| NotRun::Failed(vec![Report::new(error)]);
        if let Some(path) = &options.from_snapshot {
            let snapshot = Snapshot::read(path).map_err(failed)?;
            snapshot
                .continue_in(cpu, path, options.what_fits)
                .map_err(failed)?;
        }
        let mut persistence = Persistence {
            snapshot_to: options.snapshot_to.clone(),
            ..Persistence::default()
        };
        if let Some(retain) = &options.retain {
            let mut keeper = Keeper::new(retain.clone(), ranges);
            // A run continued from a snapshot has its memory; the file follows it from now.
            if options.from_snapshot.is_none() {
                let start = keeper.start(cpu).map_err(failed)?;
                persistence.start = Some((start, retain.path.clone()));
            }
            persistence.keeper = Some(keeper);
        }
        Ok(persistence)
    }

    /// At a cycle control point: the retentive memory when its interval has passed, the
    /// snapshot when its moment has come.
    pub fn at_control_point(&mut self, cpu: &Cpu) {
        if let Some(keeper) = &mut self.keeper
            && let Err(error) = keeper.at_control_point(cpu)
        {
            self.failed.get_or_insert(error);
        }
        let due = self
            .snapshot_to
            .as_ref()
            .is_some_and(|(_, at)| at.is_some_and(|at| cpu.clock >= at));
        if due {
            self.write_snapshot(cpu);
        }
    }

    /// A STOP, or a cold restart: the retentive memory is written now.
    pub fn write_retained(&mut self, cpu: &Cpu) {
        if let Some(keeper) = &mut self.keeper
            && let Err(error) = keeper.write(cpu)
        {
            self.failed.get_or_insert(error);
        }
    }

    fn write_snapshot(&mut self, cpu: &Cpu) {
        if let Some((path, _)) = self.snapshot_to.take()
            && let Err(error) = Snapshot::of(cpu).write(&path)
        {
            self.failed.get_or_insert(error);
        }
    }

    /// The run's end: the retentive memory, a snapshot not yet taken; what could not be
    /// written, as a report.
    pub fn finish(&mut self, cpu: &Cpu) -> Option<Report> {
        self.write_retained(cpu);
        self.write_snapshot(cpu);
        self.failed.take().map(Report::new)
    }
}
