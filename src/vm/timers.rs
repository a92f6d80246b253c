//! Timers on simulated time. A timer's state is settled lazily, when an operation touches it, so
//! a running timer costs nothing between accesses. Edge behaviour follows the STEP 5 timing
//! diagrams: pulse (SP) and on-delay (SD) stop when the RLO drops, the extended pulse (SE)
//! restarts on every rising edge, the stored on-delay (SS) holds its bit until reset, and the
//! off-delay (SF) starts on the falling edge and is reset by a rising one.

use crate::compiler::bytecode::TimerKind;
use crate::rules::bcd;

/// Nanoseconds of the time bases 0…3: 10 ms, 100 ms, 1 s, 10 s.
pub const BASE_NS: [u64; 4] = [10_000_000, 100_000_000, 1_000_000_000, 10_000_000_000];

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Timer {
    pub kind: TimerKind,
    pub running: bool,
    pub output: bool,
    start_ns: u64,
    duration_ns: u64,
    base: u8,
    /// The RLO of the last start operation, for edge detection.
    edge: bool,
    /// The RLO of the last `FR`.
    enable_edge: bool,
    /// The RLO the last start operation saw (the on-delay's output needs it).
    input: bool,
    /// The time value, in units of the base, when the timer is not running.
    stopped_value: u16,
}

impl Default for Timer {
    fn default() -> Self {
        Timer {
            kind: TimerKind::Pulse,
            running: false,
            output: false,
            start_ns: 0,
            duration_ns: 0,
            base: 0,
            edge: false,
            enable_edge: false,
            input: false,
            stopped_value: 0,
        }
    }
}

/// The time value (0…999, BCD in bits 0–11) and base (bits 12–13) of a KT word.
pub fn decode_time(word: u32) -> (u16, u8) {
    let digit = |shift: u32| ((word >> shift) & 0xF).min(9) as u16;
    (
        digit(8) * 100 + digit(4) * 10 + digit(0),
        ((word >> 12) & 3) as u8,
    )
}

impl Timer {
    /// Applies an expiry that has happened by `now`.
    pub fn settle(&mut self, now: u64) {
        if self.running && now >= self.start_ns + self.duration_ns {
            self.running = false;
            self.stopped_value = 0;
            self.output = match self.kind {
                TimerKind::Pulse | TimerKind::ExtendedPulse | TimerKind::OffDelay => false,
                TimerKind::OnDelay => self.input,
                TimerKind::StoredOnDelay => true,
            };
        }
    }

    fn start(&mut self, now: u64, time_word: u32) {
        let (value, base) = decode_time(time_word);
        self.running = true;
        self.start_ns = now;
        self.base = base;
        self.duration_ns = u64::from(value) * BASE_NS[usize::from(base)];
        self.stopped_value = value;
    }

    fn stop(&mut self, now: u64) {
        self.stopped_value = self.value(now);
        self.running = false;
    }

    /// A start operation (`SP SE SD SS SF`) with the RLO and the time word from ACCU 1.
    pub fn start_op(&mut self, kind: TimerKind, rlo: bool, time_word: u32, now: u64) {
        self.settle(now);
        let rising = rlo && !self.edge;
        let falling = !rlo && self.edge;
        self.edge = rlo;
        self.kind = kind;
        self.input = rlo;
        match kind {
            TimerKind::Pulse | TimerKind::OnDelay => {
                // Both stop when the RLO drops; the pulse is 1 while it runs, the on-delay
                // only once it has run out.
                if rising {
                    self.start(now, time_word);
                    self.output = kind == TimerKind::Pulse;
                } else if !rlo {
                    if self.running {
                        self.stop(now);
                    }
                    self.output = false;
                }
            }
            TimerKind::ExtendedPulse => {
                if rising {
                    self.start(now, time_word);
                    self.output = true;
                }
            }
            TimerKind::StoredOnDelay => {
                if rising {
                    self.start(now, time_word);
                }
            }
            TimerKind::OffDelay => {
                if rlo {
                    if self.running {
                        self.stop(now);
                    }
                    self.output = true;
                } else if falling {
                    self.start(now, time_word);
                    self.output = true;
                }
            }
        }
        self.settle(now);
    }

    /// The timer as it stands at `from_ns`, carried to a clock that reads `to_ns` (a start
    /// from retentive memory): a running timer keeps the time it has left, as time does not
    /// pass while the CPU is off.
    pub fn carried(mut self, from_ns: u64, to_ns: u64) -> Timer {
        self.settle(from_ns);
        if self.running {
            let left = (self.start_ns + self.duration_ns).saturating_sub(from_ns);
            let elapsed = from_ns.saturating_sub(self.start_ns);
            // The start moves with the clock; where the new clock is too early for the time
            // already run, the duration shrinks so that the time left stays.
            self.start_ns = to_ns.saturating_sub(elapsed);
            self.duration_ns = to_ns - self.start_ns + left;
        }
        self
    }

    /// `R T n`: with RLO 1 the timer stops, its value and bit are cleared.
    pub fn reset(&mut self, rlo: bool) {
        if rlo {
            self.running = false;
            self.output = false;
            self.stopped_value = 0;
        }
    }

    /// `FR T n`: a rising edge lets the next start operation with RLO 1 restart the timer.
    pub fn enable(&mut self, rlo: bool) {
        if rlo && !self.enable_edge {
            self.edge = false;
        }
        self.enable_edge = rlo;
    }

    pub fn bit(&mut self, now: u64) -> bool {
        self.settle(now);
        self.output
    }

    /// The time base, 0…3 (10 ms, 100 ms, 1 s, 10 s).
    pub fn base(&self) -> u8 {
        self.base
    }

    /// The remaining time in units of the base (`L T n`).
    pub fn value(&self, now: u64) -> u16 {
        if !self.running {
            return self.stopped_value;
        }
        let end = self.start_ns + self.duration_ns;
        let base = BASE_NS[usize::from(self.base)];
        (end.saturating_sub(now).div_ceil(base)).min(999) as u16
    }

    /// A PG's or an HMI's write of a time word (BCD value, base in bits 12–13): a running
    /// timer runs on from now with the new remaining time, a stopped one holds the value.
    pub fn write_coded(&mut self, word: u32, now: u64) {
        self.settle(now);
        let (value, base) = decode_time(word);
        self.base = base;
        if self.running {
            self.start_ns = now;
            self.duration_ns = u64::from(value) * BASE_NS[usize::from(base)];
        } else {
            self.stopped_value = value;
        }
    }

    /// BCD value with the time base in bits 12–13 (`LC T n`).
    pub fn coded(&mut self, now: u64) -> u32 {
        self.settle(now);
        bcd::encode(u32::from(self.value(now)), 3) | u32::from(self.base) << 12
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: u64 = 1_000_000;
    /// KT 010.1: one second.
    const ONE_SECOND: u32 = 0x1010;

    fn run(kind: TimerKind, steps: &[(u64, bool)]) -> Vec<bool> {
        let mut timer = Timer::default();
        steps
            .iter()
            .map(|&(at, rlo)| {
                timer.start_op(kind, rlo, ONE_SECOND, at * MS);
                timer.bit(at * MS)
            })
            .collect()
    }

    #[test]
    fn pulse_ends_early_when_the_rlo_drops() {
        assert_eq!(
            run(TimerKind::Pulse, &[(0, true), (500, true), (1000, true)]),
            [true, true, false]
        );
        assert_eq!(
            run(TimerKind::Pulse, &[(0, true), (300, false), (500, true)]),
            [true, false, true]
        );
    }

    #[test]
    fn extended_pulse_runs_on_and_retriggers() {
        assert_eq!(
            run(
                TimerKind::ExtendedPulse,
                &[(0, true), (100, false), (999, false), (1000, false)]
            ),
            [true, true, true, false]
        );
        assert_eq!(
            run(
                TimerKind::ExtendedPulse,
                &[
                    (0, true),
                    (800, false),
                    (900, true),
                    (1500, true),
                    (1900, true)
                ]
            ),
            [true, true, true, true, false]
        );
    }

    #[test]
    fn on_delay_needs_the_rlo_throughout() {
        assert_eq!(
            run(
                TimerKind::OnDelay,
                &[(0, true), (999, true), (1000, true), (1200, false)]
            ),
            [false, false, true, false]
        );
        assert_eq!(
            run(
                TimerKind::OnDelay,
                &[
                    (0, true),
                    (500, false),
                    (600, true),
                    (1500, true),
                    (1600, true)
                ]
            ),
            [false, false, false, false, true]
        );
    }

    #[test]
    fn stored_on_delay_holds_until_reset() {
        let mut timer = Timer::default();
        timer.start_op(TimerKind::StoredOnDelay, true, ONE_SECOND, 0);
        timer.start_op(TimerKind::StoredOnDelay, false, ONE_SECOND, 100 * MS);
        assert!(!timer.bit(999 * MS));
        assert!(timer.bit(1000 * MS));
        assert!(timer.bit(5000 * MS));
        timer.reset(true);
        assert!(!timer.bit(5000 * MS));
    }

    #[test]
    fn off_delay_starts_on_the_falling_edge() {
        assert_eq!(
            run(
                TimerKind::OffDelay,
                &[
                    (0, false),
                    (10, true),
                    (20, false),
                    (1019, false),
                    (1020, false)
                ]
            ),
            [false, true, true, true, false]
        );
        assert_eq!(
            run(
                TimerKind::OffDelay,
                &[(0, true), (10, false), (500, true), (2000, true)]
            ),
            [true, true, true, true]
        );
    }

    #[test]
    fn enable_restarts_without_a_new_edge() {
        let mut timer = Timer::default();
        timer.start_op(TimerKind::OnDelay, true, ONE_SECOND, 0);
        assert!(timer.bit(1000 * MS));
        timer.enable(true);
        timer.start_op(TimerKind::OnDelay, true, ONE_SECOND, 1000 * MS);
        assert!(!timer.bit(1500 * MS), "restarted by FR");
        assert!(timer.bit(2000 * MS));
    }

    #[test]
    fn remaining_time_in_base_units_and_bcd() {
        let mut timer = Timer::default();
        timer.start_op(TimerKind::ExtendedPulse, true, 0x1050, 0);
        assert_eq!(timer.value(1200 * MS), 38);
        assert_eq!(timer.coded(1200 * MS), 0x1038);
        assert_eq!(decode_time(0x2999), (999, 2));
    }

    #[test]
    fn a_stopped_timer_keeps_its_remaining_time() {
        let mut timer = Timer::default();
        timer.start_op(TimerKind::Pulse, true, ONE_SECOND, 0);
        timer.start_op(TimerKind::Pulse, false, ONE_SECOND, 300 * MS);
        assert_eq!(timer.value(300 * MS), 7, "0.7 s left in units of 100 ms");
        assert_eq!(timer.value(900 * MS), 7, "and it stays there");
        assert!(!timer.bit(900 * MS));
    }

    #[test]
    fn enable_needs_a_rising_edge_of_its_own() {
        let mut timer = Timer::default();
        timer.start_op(TimerKind::OnDelay, true, ONE_SECOND, 0);
        assert!(timer.bit(1000 * MS));
        timer.enable(false);
        timer.start_op(TimerKind::OnDelay, true, ONE_SECOND, 1000 * MS);
        assert!(timer.bit(1500 * MS), "FR with RLO 0 does not restart it");
    }
}
