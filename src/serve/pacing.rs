//! Simulated time paced to the wall clock: at `--speed 1` a simulated second takes a second.
//! A cycle that ends early waits for the clock; how late each cycle starts against the clock
//! is kept for the summary (p50, p99).

use std::time::{Duration, Instant};

/// Lateness is counted in steps of this many microseconds, up to [`LATENESS_STEPS`] of them.
const STEP_US: u64 = 10;
const LATENESS_STEPS: usize = 100_000;

pub struct Pacer {
    /// The wall time simulated time `sim_origin_ns` corresponds to.
    wall_origin: Instant,
    sim_origin_ns: u64,
    speed: f64,
    lateness: Vec<u32>,
    starts: u64,
}

impl Pacer {
    /// A pacer from now on, with the CPU's clock at `sim_now_ns`; `speed` above 0.
    pub fn new(speed: f64, sim_now_ns: u64) -> Self {
        Pacer {
            wall_origin: Instant::now(),
            sim_origin_ns: sim_now_ns,
            speed,
            lateness: vec![0; LATENESS_STEPS + 1],
            starts: 0,
        }
    }

    /// When the simulated moment `sim_ns` comes on the wall clock.
    pub fn deadline(&self, sim_ns: u64) -> Instant {
        let simulated = sim_ns.saturating_sub(self.sim_origin_ns) as f64;
        self.wall_origin + Duration::from_secs_f64(simulated / self.speed / 1e9)
    }

    /// Simulated time stood still (a STOP); from now on the clock follows on from `sim_now_ns`.
    pub fn rebase(&mut self, sim_now_ns: u64) {
        self.wall_origin = Instant::now();
        self.sim_origin_ns = sim_now_ns;
    }

    /// A cycle starts at `now`, meant to start at `deadline`.
    pub fn record_start(&mut self, deadline: Instant, now: Instant) {
        let late_us = now.saturating_duration_since(deadline).as_micros() as u64;
        let step = (late_us / STEP_US).min(LATENESS_STEPS as u64) as usize;
        self.lateness[step] += 1;
        self.starts += 1;
    }

    /// How late cycles started: the median and the 99th percentile, or `None` before any.
    pub fn lateness(&self) -> Option<Lateness> {
        (self.starts > 0).then(|| Lateness {
            cycles: self.starts,
            p50: self.percentile(0.50),
            p99: self.percentile(0.99),
        })
    }

    fn percentile(&self, fraction: f64) -> Duration {
        let wanted = ((self.starts as f64) * fraction).ceil().max(1.0) as u64;
        let mut seen = 0u64;
        for (step, &count) in self.lateness.iter().enumerate() {
            seen += u64::from(count);
            if seen >= wanted {
                return Duration::from_micros(step as u64 * STEP_US);
            }
        }
        Duration::from_micros(LATENESS_STEPS as u64 * STEP_US)
    }
}

/// How late the cycles started against the wall clock.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Lateness {
    pub cycles: u64,
    pub p50: Duration,
    pub p99: Duration,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_deadline_follows_simulated_time_divided_by_the_speed() {
        let pacer = Pacer::new(10.0, 1_000_000);
        let later = pacer.deadline(1_000_000_000 + 1_000_000) - pacer.deadline(1_000_000);
        assert_eq!(later, Duration::from_millis(100));
    }

    #[test]
    fn percentiles_come_from_the_recorded_starts() {
        let mut pacer = Pacer::new(1.0, 0);
        let deadline = Instant::now();
        for late_us in 0..100u64 {
            pacer.record_start(deadline, deadline + Duration::from_micros(late_us * 10));
        }
        let lateness = pacer.lateness().unwrap();
        assert_eq!(lateness.cycles, 100);
        assert_eq!(lateness.p50, Duration::from_micros(490));
        assert_eq!(lateness.p99, Duration::from_micros(980));
    }
}
