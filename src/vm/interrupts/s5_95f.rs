//! The S5-95F: time-controlled OB 13 with its interrupt process images and the wake-up error.
//!
//! S5-95F manual, "Introduction to STEP 5":
//! - 7.4.4: OB 13 is called every call-up interval, each time late by a delay t; "in the ideal
//!   case OB13 is processed directly when the previous OB13 time has elapsed (t = 0)", which is
//!   the default here, and a scenario may set a fixed delay. "OB13 call-up interval > maximum
//!   delay t of OB13 processing", else a time interrupt error sends the CPU to STOP.
//! - 7.4.4: OB 13 can interrupt the cyclic program after any STEP 5 statement; OB 2 and OB 3
//!   can interrupt OB 13; OB 13 cannot interrupt the data cycles, OB 2, OB 3 or a running
//!   OB 13 (the priorities and the operation points of the profile); `IA` holds it back.
//! - Reading the interrupt PII: "when OB13 is called, the signals of the external input modules
//!   are read into the interrupt PII", in an interrupt input data cycle; in OB 13 `L PY`/`L PW`
//!   read that image.
//! - Writing the interrupt PIQ: `T PY`/`T PW` in OB 13 write the interrupt PIQ and the normal
//!   PIQ; after OB 13 an interrupt output data cycle sends it to the modules, "only if the
//!   interrupt PIQ was written".
//! - Wake-up error: OB 13 called again before its processing is completed: STOP.
//!
//! Whether the images are in use belongs to the OB 13 level (saved and restored with it), so
//! an OB 3 that interrupts OB 13 reads and writes the modules directly.

use crate::profile::Profile;

use super::super::bytes::{read_bytes, write_bytes};
use super::super::io_trace::Modules;
use super::super::stop::{Stop, StopCause, StopDetail};
use super::{Cpu, EngineConfig, FOREIGN_RULES, Ob13Timing, Request, Rules, RulesState};

#[derive(Debug, Default)]
pub struct S595f {
    timing: Option<Ob13Timing>,
    /// When OB 13 is next called; `u64::MAX` before RUN or without OB 13.
    next_call: u64,
    /// When the last OB 13 was completed, its output data cycle included.
    completed_at: u64,
    interrupt_pii: Vec<u8>,
    interrupt_piq: Vec<u8>,
    /// Which bytes of the interrupt PIQ the running OB 13 wrote.
    written: Vec<bool>,
}

impl S595f {
    pub fn new(profile: &Profile, config: &EngineConfig) -> Self {
        let bytes = usize::from(profile.sizes.peripheral_bytes);
        S595f {
            timing: config.ob13,
            next_call: u64::MAX,
            completed_at: 0,
            interrupt_pii: vec![0; bytes],
            interrupt_piq: vec![0; bytes],
            written: vec![false; bytes],
        }
    }

    /// `L PY`/`L PW` in OB 13: the interrupt PII.
    pub fn read_interrupt_pii(&self, at: usize, count: usize) -> u32 {
        read_bytes(&self.interrupt_pii, at, count)
    }

    /// `T PY`/`T PW` in OB 13: the interrupt PIQ (the caller writes the normal PIQ).
    pub fn write_interrupt_piq(&mut self, at: usize, count: usize, value: u32) {
        write_bytes(&mut self.interrupt_piq, at, count, value);
        self.written[at..at + count].fill(true);
    }

    /// Whether OB 13 goes to STOP instead of running: called again before the last call was
    /// completed (still running, still pending, or its output data cycle still under way).
    fn wake_up_error(&self, cpu: &Cpu, at: u64) -> bool {
        let running = cpu
            .engine
            .active
            .iter()
            .any(|active| active.request.ob == 13);
        let pending = cpu.engine.pending.iter().any(|request| request.ob == 13);
        running || pending || self.completed_at > at
    }
}

impl Rules for S595f {
    fn saved(&self) -> RulesState {
        RulesState::S595f {
            next_call: self.next_call,
            completed_at: self.completed_at,
            interrupt_pii: self.interrupt_pii.clone(),
            interrupt_piq: self.interrupt_piq.clone(),
        }
    }

    fn restore(&mut self, state: &RulesState) -> Result<(), &'static str> {
        let RulesState::S595f {
            next_call,
            completed_at,
            interrupt_pii,
            interrupt_piq,
        } = state
        else {
            return Err(FOREIGN_RULES);
        };
        if interrupt_pii.len() != self.interrupt_pii.len()
            || interrupt_piq.len() != self.interrupt_piq.len()
        {
            return Err(FOREIGN_RULES);
        }
        self.next_call = *next_call;
        self.completed_at = *completed_at;
        self.interrupt_pii.copy_from_slice(interrupt_pii);
        self.interrupt_piq.copy_from_slice(interrupt_piq);
        Ok(())
    }

    fn next_due(&self) -> u64 {
        self.next_call
    }

    fn start_run(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        let Some(timing) = self.timing else {
            return Ok(());
        };
        if cpu.program.ob(13).is_none() {
            // "Cyclical program processing continues if OB13 is not programmed."
            return Ok(());
        }
        if let Some(max_delay) = timing.max_delay_ns
            && timing.interval_ns <= max_delay
        {
            let detail = StopDetail::Ob13Interval {
                interval_ns: timing.interval_ns,
                max_delay_ns: max_delay,
            };
            return Err(cpu.stop(StopCause::Weck, 0, detail));
        }
        self.next_call = cpu.clock + timing.interval_ns + timing.delay_ns;
        Ok(())
    }

    fn poll(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        let at = self.next_call;
        let interval = self.timing.map_or(u64::MAX, |timing| timing.interval_ns);
        self.next_call = at.saturating_add(interval);
        if self.wake_up_error(cpu, at) {
            return Err(cpu.stop_at_last_op(StopCause::Weck, StopDetail::Ob(13)));
        }
        cpu.request(13, at, None);
        Ok(())
    }

    fn entered(&mut self, cpu: &mut Cpu, ob: u8) {
        if ob != 13 {
            return;
        }
        let length = self.interrupt_pii.len();
        self.interrupt_pii.copy_from_slice(&cpu.inputs[..length]);
        self.written.fill(false);
        cpu.data_cycle("interrupt_input", "input");
        cpu.level.interrupt_images = true;
    }

    fn ended(&mut self, cpu: &mut Cpu, request: Request) {
        if request.ob != 13 {
            return;
        }
        if self.written.contains(&true) {
            let before = cpu.modules_before(Modules::Outputs, false, 0, self.written.len());
            for (byte, written) in self.written.iter_mut().enumerate() {
                if std::mem::take(written) {
                    cpu.outputs[byte] = self.interrupt_piq[byte];
                }
            }
            if let Some(before) = before {
                cpu.trace_module_changes(Modules::Outputs, false, 0, &before);
            }
            cpu.data_cycle("interrupt_output", "output");
        }
        self.completed_at = cpu.clock;
    }
}
