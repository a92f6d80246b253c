//! The modes and the cycle: STOP → STARTUP (startup OB) → RUN, then cycles of read PII, OB 1,
//! write PIQ, operating-system time, and the cycle boundary, until the run's limit.

use std::time::Duration;

#[cfg(not(target_arch = "wasm32"))]
use std::time::Instant;
#[cfg(target_arch = "wasm32")]
use web_time::Instant;

use super::io_trace::Modules;
use crate::profile::InterruptPoints;
use crate::trace::Event;

use super::stop::{Stop, StopCause};
use super::{Cpu, Exit, IDLE, LastStretch, Mode, Point, StretchKind};

/// How long a run goes on: a number of cycles, or simulated time (the run ends at the first
/// cycle end at or after it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunLimit {
    Cycles(u64),
    Duration(u64),
}

/// The cycle times of the completed cycles.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct CycleTimes {
    pub count: u64,
    pub min_ns: u64,
    pub max_ns: u64,
    pub total_ns: u64,
    /// The last one's.
    pub last_ns: u64,
}

impl CycleTimes {
    fn record(&mut self, ns: u64) {
        self.min_ns = if self.count == 0 {
            ns
        } else {
            self.min_ns.min(ns)
        };
        self.max_ns = self.max_ns.max(ns);
        self.last_ns = ns;
        self.total_ns += ns;
        self.count += 1;
    }

    pub fn mean_ns(&self) -> Option<u64> {
        self.total_ns.checked_div(self.count)
    }
}

/// What a run did.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    pub mode: Mode,
    pub stop: Option<Stop>,
    pub cycles: u64,
    pub clock_ns: u64,
    pub instructions: u64,
    pub wall: Duration,
    /// The run was halted from outside (Ctrl-C) at a cycle boundary, before its limit.
    pub halted: bool,
}

impl Cpu {
    pub(super) fn set_mode(&mut self, to: Mode, cause: Option<&'static str>) {
        let from = self.mode;
        self.mode = to;
        if self.tracer.enabled {
            self.tracer.emit(
                self.clock,
                Event::Mode {
                    from: from.name(),
                    to: to.name(),
                    cause,
                },
            );
        }
    }

    /// Runs the current level until its bottom block ends; interrupt OBs entered on the way run
    /// inside this loop.
    fn run_level(&mut self) -> Result<(), Stop> {
        let depth = self.levels.len();
        let operation_points = self.engine.config.points == InterruptPoints::Operation;
        loop {
            let exit = self.execute(operation_points);
            if matches!(exit, Exit::Point(_)) && self.clock < self.engine_attention_at {
                // The loop left only for the pulse: the engine does not see this point.
                self.pulse_at(self.clock);
                continue;
            }
            if operation_points {
                self.operation_boundary(&exit);
            }
            match exit {
                Exit::Point(point) => {
                    self.at_point(point)?;
                }
                Exit::LevelEnd if self.levels.len() == depth => {
                    // OB 1 or the startup OB has ended, and with it its DIS_AIRT delays.
                    if depth == 0 {
                        let ob = self.active_ob().0;
                        self.end_delays(ob);
                    }
                    // OB 1's own block end is a block change too: pending interrupts run
                    // before the operating system ends the cycle.
                    if depth == 0 && self.mode == Mode::Run {
                        self.level.block = IDLE;
                        self.interrupts_between_levels(Point::BlockEnd)?;
                    }
                    return Ok(());
                }
                Exit::LevelEnd => {
                    self.end_interrupt_level()?;
                    self.at_point(Point::BlockEnd)?;
                }
                Exit::Stop(stop) => return Err(stop),
            }
        }
    }

    /// With operation points every operation ends at a point: the loop left at one (or, at an
    /// interrupt OB's block end, the point is the start of that block end: its data cycle
    /// follows before the next point).
    fn operation_boundary(&mut self, exit: &Exit) {
        match exit {
            Exit::Point(Point::Operation) => {
                let (block, pc) = self.last_op;
                let start = self.clock - self.program.blocks[usize::from(block)].cost(pc as usize);
                self.last_stretch = LastStretch {
                    kind: StretchKind::Block { block, end_pc: pc },
                    start_ns: start,
                    end_ns: self.clock,
                };
                self.last_point_at = self.clock;
            }
            Exit::Point(_) => self.last_point_at = self.clock,
            Exit::LevelEnd if !self.levels.is_empty() => {
                let (block, pc) = self.last_op;
                let start = self.clock - self.program.blocks[usize::from(block)].cost(pc as usize);
                self.last_point_at = start;
                self.last_stretch.start_ns = start;
            }
            Exit::LevelEnd | Exit::Stop(_) => {}
        }
    }

    /// An interrupt OB's level has ended: the interrupted level comes back, and the OB's end
    /// (with its data cycle) closes a stretch.
    fn end_interrupt_level(&mut self) -> Result<(), Stop> {
        let block = self.level.block;
        self.leave_interrupt()?;
        self.mark_system_point(StretchKind::InterruptEnd { block });
        Ok(())
    }

    /// A point of the operating system's own work (between the parts of the cycle, or after
    /// an interrupt OB's end): the stretch since the last point ends here. A stretch of the
    /// wait for the minimum cycle time ends at whatever is due, so it holds no request back and
    /// does not count for the response bound.
    fn mark_system_point(&mut self, kind: StretchKind) {
        let ns = self.clock - self.last_point_at;
        self.last_stretch = LastStretch {
            kind,
            start_ns: self.last_point_at,
            end_ns: self.clock,
        };
        if kind != StretchKind::MinCycleWait {
            self.longest_system.record(ns, kind);
        }
        self.last_point_at = self.clock;
    }

    /// A point between the parts of the cycle: pending interrupts run here, highest first,
    /// until none outranks the cyclic level.
    fn cycle_point(&mut self, after: StretchKind) -> Result<(), Stop> {
        self.mark_system_point(after);
        self.level.block = IDLE;
        self.interrupts_between_levels(Point::Cycle)
    }

    /// With no block running, pending interrupts run one after the other, highest first,
    /// until none outranks the cyclic level.
    fn interrupts_between_levels(&mut self, point: Point) -> Result<(), Stop> {
        while self.at_point(point)? {
            self.run_level()?;
            self.end_interrupt_level()?;
        }
        Ok(())
    }

    fn startup(&mut self) -> Result<(), Stop> {
        self.set_mode(Mode::Startup, None);
        self.cycle_started_at = self.clock;
        self.update_attention();
        if let Some((ob, block)) = self.startup_ob() {
            self.enter_level(block)?;
            if !self.local.is_empty() {
                self.write_start_info(Self::startup_start_info(ob));
            }
            self.last_point_at = self.clock;
            self.run_level()?;
        }
        self.set_mode(Mode::Run, None);
        self.start_engine_run()
    }

    fn process_image_cycle(&mut self, read: bool) {
        let bytes = usize::from(self.program.layout.image_bytes);
        let piq = usize::from(self.program.layout.output_base());
        // Forcing works at the transfers (see [`super::force`]), once per cycle.
        if read {
            self.image[..bytes].copy_from_slice(&self.inputs[..bytes]);
            if !self.forces.is_empty() {
                self.force_pii();
            }
        } else {
            if !self.forces.is_empty() {
                self.force_piq();
            }
            let before = self.modules_before(Modules::Outputs, false, 0, bytes);
            self.outputs[..bytes].copy_from_slice(&self.image[piq..piq + bytes]);
            if let Some(before) = before {
                self.trace_module_changes(Modules::Outputs, false, 0, &before);
            }
        }
        let duration = u64::from(self.profile.timings.process_image_per_byte) * bytes as u64;
        if self.tracer.enabled {
            let event = Event::DataCycle {
                kind: "process_image",
                direction: if read { "input" } else { "output" },
                duration_ns: duration,
            };
            self.tracer.emit(self.clock, event);
        }
        self.clock += duration;
    }

    /// The operating system's time at the cycle end.
    fn os_time(&mut self) {
        let duration = u64::from(self.profile.timings.cycle_overhead);
        if self.tracer.enabled {
            let event = Event::OsTime {
                duration_ns: duration,
            };
            self.tracer.emit(self.clock, event);
        }
        self.clock += duration;
    }

    /// One cycle: PII read, OB 1, PIQ write, operating-system time; interrupts may be
    /// serviced between these parts.
    fn one_cycle(&mut self) -> Result<(), Stop> {
        self.cycle += 1;
        if self.tracer.enabled {
            self.tracer
                .emit(self.clock, Event::CycleStart { cycle: self.cycle });
        }
        self.poll()?;
        self.process_image_cycle(true);
        if let Some(at) = self.clock_memory {
            self.image[usize::from(at)] =
                clock_memory_byte(self.clock.saturating_sub(self.clock_origin_ns));
        }
        self.cycle_point(StretchKind::ProcessImageRead)?;
        if let Some(block) = self.program.ob(1) {
            self.enter_level(block)?;
            if !self.local.is_empty() {
                self.write_start_info(self.cycle_start_info());
            }
            self.update_attention();
            self.run_level()?;
        }
        self.process_image_cycle(false);
        self.cycle_point(StretchKind::ProcessImageWrite)?;
        self.os_time();
        if let Some((block, pc)) = self.stop_requested.take() {
            self.level.block = block;
            return Err(self.stop(StopCause::Stp, pc, super::stop::StopDetail::None));
        }
        let last = self.wait_for_min_cycle()?;
        let cycle_time = self.clock - self.cycle_started_at;
        self.cycle_times.record(cycle_time);
        if self.tracer.enabled {
            let event = Event::CycleEnd {
                cycle: self.cycle,
                cycle_time_ns: cycle_time,
            };
            self.tracer.emit(self.clock, event);
        }
        self.cycle_started_at = self.clock;
        self.cycle_point(last)
    }

    /// S7: the cycle end waits until the minimum cycle time has passed since the cycle start,
    /// and interrupts that come meanwhile are serviced in the wait ("S7-400 Automation System,
    /// CPU Specifications", 9.3 Different cycle times, Minimum cycle time: in Twait, the
    /// difference between the minimum and the actual cycle time, interrupts that occur are
    /// processed; the cycle time is always at least the minimum). The wait runs in stretches,
    /// each up to the next thing due, where the requests are taken in and serviced. Returns the
    /// kind of the cycle's last stretch.
    fn wait_for_min_cycle(&mut self) -> Result<StretchKind, Stop> {
        let end = self
            .cycle_started_at
            .saturating_add(self.engine.config.min_cycle_ns);
        if self.clock >= end {
            return Ok(StretchKind::OsTime);
        }
        // What came in the operating-system time runs first.
        self.cycle_point(StretchKind::OsTime)?;
        while self.clock < end {
            let until = self.engine.next_due().clamp(self.clock + 1, end);
            if self.tracer.enabled {
                let event = Event::CycleWait {
                    duration_ns: until - self.clock,
                };
                self.tracer.emit(self.clock, event);
            }
            self.clock = until;
            self.cycle_point(StretchKind::MinCycleWait)?;
        }
        Ok(StretchKind::MinCycleWait)
    }

    fn limit_reached(&self, limit: RunLimit) -> bool {
        match limit {
            RunLimit::Cycles(cycles) => self.cycle >= cycles,
            RunLimit::Duration(ns) => self.clock >= ns,
        }
    }

    /// STOP → STARTUP → RUN, then cycles until the limit or a STOP.
    pub fn run(&mut self, limit: RunLimit) -> RunOutcome {
        self.run_watched(limit, &mut |_| true)
    }

    /// As [`Cpu::run`], asking `go_on` at every cycle boundary whether to go on (progress
    /// display, Ctrl-C); a `false` halts the run there. A CPU in RUN goes on from where it is
    /// (the playground's live mode runs a slice of time at a time).
    pub fn run_watched(
        &mut self,
        limit: RunLimit,
        go_on: &mut dyn FnMut(&mut Cpu) -> bool,
    ) -> RunOutcome {
        let started = Instant::now();
        let mut halted = false;
        let start = if self.mode == Mode::Run {
            Ok(())
        } else {
            self.startup()
        };
        let result = start.and_then(|()| {
            while !self.limit_reached(limit) {
                self.pulse_at(self.clock);
                if !go_on(self) {
                    halted = true;
                    break;
                }
                self.one_cycle()?;
            }
            Ok(())
        });
        let mut stop = result.err();
        if stop
            .as_ref()
            .is_some_and(|stop| stop.cause == StopCause::Halt)
        {
            stop = None;
            halted = true;
        }
        if let Some(stop) = &stop {
            self.with_probe((), |probe, cpu| probe.stopping(cpu, stop));
            self.set_mode(Mode::Stop, Some(stop.cause.code()));
            if self.tracer.enabled {
                let (block, line, segment) = match stop.block {
                    Some(block) => (
                        self.block_id(block).to_string(),
                        self.line_of(block, stop.pc),
                        self.segment_of(block, stop.pc),
                    ),
                    None => ("between cycles".to_string(), 0, None),
                };
                self.tracer.emit(
                    self.clock,
                    Event::Stop {
                        cause: stop.cause.code(),
                        block,
                        line,
                        segment,
                    },
                );
            }
        }
        RunOutcome {
            mode: self.mode,
            stop,
            cycles: self.cycle,
            clock_ns: self.clock,
            instructions: self.instructions,
            wall: started.elapsed(),
            halted,
        }
    }
}

impl Cpu {
    /// SFC 64 (TIME_TCK)'s value: the milliseconds of simulated time since the CPU started
    /// (or awlsim's `__CLKRST` restarted the clocks), as a TIME that wraps from 2^31 − 1 to 0
    /// ("System Software for S7-300/400 System and Standard Functions", SFC 64 TIME_TCK).
    pub fn time_tick(&self) -> u32 {
        time_tick(self.clock.saturating_sub(self.clock_origin_ns))
    }

    /// awlsim's `SFC -4` (`__CLKRST`): the clock memory and SFC 64 count from now, the clock
    /// memory byte 0 again.
    pub fn restart_clocks(&mut self) {
        self.clock_origin_ns = self.clock;
        if let Some(at) = self.clock_memory {
            self.image[usize::from(at)] = clock_memory_byte(0);
        }
    }
}

/// SFC 64's TIME after `elapsed_ns`: whole milliseconds, 31 bits.
fn time_tick(elapsed_ns: u64) -> u32 {
    ((elapsed_ns / 1_000_000) & 0x7FFF_FFFF) as u32
}

/// Half the period of each clock memory bit, bit 0 first: 0.1 s (10 Hz) to 2 s (0.5 Hz), as
/// an S7 CPU's clock memory ("Programming with STEP 7", the clock memory): each bit is 0 for
/// half its period, then 1.
const CLOCK_HALF_PERIODS_NS: [u64; 8] = [
    50_000_000,
    100_000_000,
    200_000_000,
    250_000_000,
    400_000_000,
    500_000_000,
    800_000_000,
    1_000_000_000,
];

/// The clock memory byte at simulated time `now_ns`; the CPU writes it at each cycle start.
pub fn clock_memory_byte(now_ns: u64) -> u8 {
    CLOCK_HALF_PERIODS_NS
        .iter()
        .enumerate()
        .fold(0, |byte, (bit, half)| {
            byte | (((now_ns / half) & 1) as u8) << bit
        })
}

#[cfg(test)]
mod tests {
    use super::time_tick;

    #[test]
    fn sfc_64_counts_whole_milliseconds_and_wraps_at_2_to_the_31() {
        assert_eq!(time_tick(0), 0);
        assert_eq!(time_tick(1_999_999), 1);
        let wrap_ns = (1u64 << 31) * 1_000_000;
        assert_eq!(time_tick(wrap_ns - 1_000_000), 0x7FFF_FFFF);
        assert_eq!(time_tick(wrap_ns), 0);
        assert_eq!(time_tick(wrap_ns + 5_000_000), 5);
    }
}
