//! The operating mode changed from outside, as a PG or an HMI changes it: STOP at a cycle
//! boundary, and a restart from STOP — warm (hot: the memory kept) or cold (the memory as the
//! program loaded it). The restart itself is the usual STARTUP with the profile's startup OB.

use super::{Cpu, Mode};

impl Cpu {
    /// The CPU goes to STOP between two cycles because `cause` asked (a client's PLC stop).
    pub fn stop_from_outside(&mut self, cause: &'static str) {
        if self.mode != Mode::Stop {
            self.set_mode(Mode::Stop, Some(cause));
        }
    }

    /// Readies a CPU in STOP for its next start: what a STOP inside a block left on the block
    /// stack and the interrupt levels goes; a cold restart also puts the process images, the
    /// flags, timers, counters and data blocks back as loaded. The input modules are the
    /// process's and stay as they are.
    pub fn prepare_restart(&mut self, cold: bool) {
        let fresh = Cpu::with_native(
            self.program.clone(),
            self.sources.clone(),
            self.native.clone(),
        );
        self.level = fresh.level;
        self.frames = fresh.frames;
        self.levels.clear();
        self.fb_saves.clear();
        self.stop_requested = None;
        if cold {
            self.image = fresh.image;
            self.outputs = fresh.outputs;
            self.extended_outputs = fresh.extended_outputs;
            self.timers = fresh.timers;
            self.counters = fresh.counters;
            self.data_blocks = fresh.data_blocks;
            self.s7_data = fresh.s7_data;
        }
        // Forces outlast a STOP and a restart, as on a CPU, until they are deleted.
        self.hold_forces();
    }
}
