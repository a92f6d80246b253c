//! What the fuzz targets share: the bounds on what one input may cost, and the checks every
//! diagnostic and every run must pass.
//!
//! A target panics (and libFuzzer keeps the input) when awl panics, when a diagnostic points
//! outside its source or has no code, or when a run's books do not balance. The bounds live
//! here, in the targets, so every way of running them (`cargo fuzz run`, a replayed artifact,
//! a corpus pass) is bounded alike.

mod bounds;
mod checks;
mod dap;
mod editor;
mod run;

pub use bounds::{
    MAX_CYCLES, MAX_EVENTS, MAX_INPUT_BYTES, OPS_PER_CYCLE, RENDER_ONE_IN, bounded, capped,
    renders_in_full, watchdog_ns,
};
pub use checks::{check_diagnostics, check_report, quiet_reports};
pub use dap::debug_session;
pub use editor::edit_session;
pub use run::{Setup, run};

use awl::frontend::Frontend;
use awl::mnemonics::MnemonicSet;
use awl::profile::{self, Profile};

/// The CPU a header byte picks.
pub fn cpu(byte: u8) -> &'static Profile {
    &profile::PROFILES[usize::from(byte) % profile::PROFILES.len()]
}

/// The mnemonic set the first file was read in.
pub fn mnemonics(built: &Frontend) -> MnemonicSet {
    built
        .mnemonics
        .first()
        .copied()
        .unwrap_or(MnemonicSet::English)
}
