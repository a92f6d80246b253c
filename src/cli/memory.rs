//! The options of retentive memory and snapshots that `awl run` and `awl serve` share.

use std::path::PathBuf;
use std::time::Duration;

use crate::retain::RetainOptions;

#[derive(Debug, clap::Args)]
pub struct MemoryArgs {
    /// Keep retentive memory in FILE: loaded at the start (a warm restart after power on; no
    /// file yet: the source's values), written at every STOP, at the end and while running
    /// every --retain-every, crash-safe. `awl help retain` [default: none]
    #[arg(long, value_name = "FILE")]
    pub retain: Option<PathBuf>,
    /// How often retentive memory is written while the CPU runs (wall time), e.g. 500ms
    #[arg(long, value_name = "DURATION", requires = "retain", default_value = "1s", value_parser = parse_wall_duration)]
    pub retain_every: Duration,
    /// Start cold: the source's values, not the retentive memory file's (which is then written
    /// anew) [default: a warm restart from the file]
    #[arg(long, requires = "retain")]
    pub cold: bool,
    /// Load what still fits of a retentive memory file or snapshot that no longer fits the
    /// program (changed data blocks start from the source's values) [default: such a file is
    /// an error]
    #[arg(long)]
    pub retain_what_fits: bool,
}

impl MemoryArgs {
    pub fn retain_options(&self) -> Option<RetainOptions> {
        self.retain.as_ref().map(|path| RetainOptions {
            path: path.clone(),
            every: self.retain_every,
            cold: self.cold,
            what_fits: self.retain_what_fits,
        })
    }
}

fn parse_wall_duration(text: &str) -> Result<Duration, String> {
    match crate::scenario::parse_duration(text) {
        Some(ns) if ns >= 1_000_000 => Ok(Duration::from_nanos(ns)),
        _ => Err(format!(
            "`{text}` is not a duration of 1ms or more; write e.g. 500ms, 1s, 10s"
        )),
    }
}
