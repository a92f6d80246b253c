//! A pulse for long runs: the CPU tells a listener how far the run has come, about every so
//! much wall time, from inside a long cycle too (the playground's progress line while a level
//! loops for seconds).
//!
//! It rides on `attention_at`, which the loop already compares at every block change and
//! backward jump: the pulse's next look is folded into it, and when the loop leaves with only
//! the pulse due, the pulse looks and the loop goes on as if it had not left. The engine never
//! sees these looks, so a run with a pulse ends exactly as one without.

use std::time::Duration;

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use super::Cpu;

/// How far a run has come.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Simulated time, ns.
    pub clock_ns: u64,
    /// The cycle running (0 in STARTUP).
    pub cycle: u64,
}

/// Simulated time between two looks at the wall clock at first; each look adjusts it so that
/// looks come about [`LOOKS_PER_REPORT`] times between two reports, whatever the CPU's speed,
/// but never closer than [`SHORTEST_STRIDE_NS`].
const FIRST_STRIDE_NS: u64 = 100_000;

const SHORTEST_STRIDE_NS: u64 = 1_000;

const LOOKS_PER_REPORT: u32 = 8;

/// The listener and when it last heard.
pub struct Pulse {
    every: Duration,
    listener: Box<dyn FnMut(Progress)>,
    /// Simulated time of the next look at the wall clock.
    next_look_ns: u64,
    stride_ns: u64,
    last_look: Instant,
    last_report: Instant,
}

impl Pulse {
    /// Calls `listener` about every `every` of wall time while the run goes on.
    pub fn new(every: Duration, listener: Box<dyn FnMut(Progress)>) -> Pulse {
        let now = Instant::now();
        Pulse {
            every,
            listener,
            next_look_ns: 0,
            stride_ns: FIRST_STRIDE_NS,
            last_look: now,
            last_report: now,
        }
    }

    /// A look at the wall clock: reports when it is time, and sets the next look.
    fn look(&mut self, progress: Progress) {
        let now = Instant::now();
        let aim = self.every / LOOKS_PER_REPORT;
        let since_look = now - self.last_look;
        if since_look < aim / 2 {
            self.stride_ns = self.stride_ns.saturating_mul(2);
        } else if since_look > aim * 2 {
            self.stride_ns = (self.stride_ns / 2).max(SHORTEST_STRIDE_NS);
        }
        self.last_look = now;
        self.next_look_ns = progress.clock_ns.saturating_add(self.stride_ns);
        if now - self.last_report >= self.every {
            self.last_report = now;
            (self.listener)(progress);
        }
    }
}

impl Cpu {
    /// Gives the run a pulse (see [`Pulse`]); it is looked at from the next interrupt point or
    /// block change on.
    pub fn set_pulse(&mut self, pulse: Pulse) {
        self.attention_at = self.engine_attention_at.min(pulse.next_look_ns);
        self.pulse = Some(pulse);
    }

    /// When the pulse looks next (never without one).
    pub(super) fn next_look_ns(&self) -> u64 {
        self.pulse
            .as_ref()
            .map_or(u64::MAX, |pulse| pulse.next_look_ns)
    }

    /// The pulse looks if it is due at `clock`.
    pub(super) fn pulse_at(&mut self, clock: u64) {
        let cycle = self.cycle;
        if let Some(pulse) = self
            .pulse
            .as_mut()
            .filter(|pulse| clock >= pulse.next_look_ns)
        {
            pulse.look(Progress {
                clock_ns: clock,
                cycle,
            });
            self.attention_at = self.engine_attention_at.min(pulse.next_look_ns);
        }
    }
}
