//! The interrupt engine: pending requests, priorities, and where they are serviced.
//!
//! The execution loop reports interrupt points (block calls, block ends, every operation in
//! `operation` mode) only when `clock >= attention_at`; the engine keeps `attention_at` at the
//! next time something is due (a request, OB 13, the watchdog, an input change), or at 0 while
//! a pending request outranks the running level. With nothing pending the loop pays one
//! comparison per block change.
//!
//! The rules, and the seed each comes from:
//! - seed 000 (SINUMERIK 840C, 5.3.1/5.3.2): in normal mode the cyclic program is interrupted
//!   only at block changes; OB 2 and OB 5 are not processed in normal mode; simultaneous
//!   requests are serviced by priority; after an interrupt OB ends, priorities are reassigned.
//! - seed 002 (S5-95F): OB 13 at its interval with the interrupt PII read at its start and the
//!   interrupt PIQ written after it if it was written; OB 13 due again before it finished is the
//!   wake-up error (STOP WECK).
//! - seed 001 (SPEED7): hardware interrupts per module and channel, acknowledged after the OB;
//!   same-channel loss with diagnostic interrupt OB 82; other-channel hold; busy-OB hold; none
//!   in STARTUP, loss at the transition to RUN; OB 85 for a missing OB, STOP without OB 85.

use crate::profile::{Family, InterruptPoints};
use crate::trace::Event;

use super::stop::{Stop, StopCause, StopDetail};
use super::{Cpu, Mode, Point};

/// Something that happens at a simulated time, from the scenario.
#[derive(Debug, Clone, PartialEq)]
pub enum Happening {
    /// Process inputs change: (byte offset in the input modules, width in bytes or a bit).
    SetInputs(Vec<InputChange>),
    /// An S5 interrupt request for an interrupt OB.
    Interrupt { ob: u8 },
    /// A SPEED7 hardware interrupt event on a module's channel.
    Hardware {
        module: u16,
        channel: u16,
        active_for_ns: u64,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InputChange {
    pub target: InputTarget,
    pub byte: u16,
    pub bit: u8,
    pub bytes: u8,
    pub value: u32,
}

impl InputChange {
    /// Writes the change into the input modules' bytes.
    pub fn apply(self, modules: &mut [u8]) {
        let at = usize::from(self.byte);
        if self.bytes == 0 {
            let mask = 1u8 << self.bit;
            if self.value != 0 {
                modules[at] |= mask
            } else {
                modules[at] &= !mask
            }
        } else {
            super::exec::write_bytes(modules, at, usize::from(self.bytes), self.value);
        }
    }
}

/// Which input modules an input change writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputTarget {
    Process,
    Extended,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Scheduled {
    pub at_ns: u64,
    pub what: Happening,
}

/// The engine's settings for one run.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineConfig {
    pub points: InterruptPoints,
    /// SINUMERIK 840C special mode: OB 2 and OB 5 are processed.
    pub special_mode: bool,
    pub ob13_interval_ns: Option<u64>,
    /// SPEED7: which OB a module's hardware interrupts start.
    pub hw_modules: Vec<(u16, u8)>,
    pub watchdog_ns: u64,
}

impl Default for EngineConfig {
    fn default() -> Self {
        EngineConfig {
            points: InterruptPoints::Block,
            special_mode: false,
            ob13_interval_ns: None,
            hw_modules: Vec::new(),
            watchdog_ns: 150_000_000,
        }
    }
}

/// Counts and latencies of one interrupt OB.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ObStats {
    pub requested: u64,
    pub serviced: u64,
    pub lost: u64,
    pub ignored: u64,
    pub latency_min: u64,
    pub latency_max: u64,
    pub latency_sum: u64,
}

/// Where a request came from, for acknowledgement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HardwareSource {
    pub module: u16,
    pub channel: u16,
    pub active_until: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    pub id: u64,
    pub ob: u8,
    pub requested_at: u64,
    pub hardware: Option<HardwareSource>,
}

/// An interrupt OB that is running (or interrupted by a higher one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Active {
    pub request: Request,
    pub priority: u8,
}

/// A hardware event held until an acknowledgement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Held {
    request: Request,
    /// The module whose acknowledgement releases it.
    released_by: u16,
}

/// The engine's state. Every collection gets its capacity when the engine is made, sized from
/// the schedule, so servicing interrupts allocates nothing while the CPU runs.
pub struct Engine {
    pub config: EngineConfig,
    schedule: Vec<Scheduled>,
    next: usize,
    next_ob13_at: Option<u64>,
    ob13_ended_at: u64,
    pending: Vec<Request>,
    pub active: Vec<Active>,
    held: Vec<Held>,
    /// Held events released by an acknowledgement, while they are judged.
    released: Vec<Held>,
    /// SPEED7 modules between identification and acknowledgement: (module, channel, request).
    busy_modules: Vec<(u16, u16, u64)>,
    /// Counts and latencies by OB number.
    stats: Box<[ObStats; 256]>,
    next_id: u64,
    /// S5-95F: OB 13 runs, so PY/PW reach the interrupt images.
    pub interrupt_images: bool,
    /// When RUN began (hardware interrupts before it are not produced).
    run_started_at: Option<u64>,
    /// Hardware events of the STARTUP, judged at the transition to RUN.
    startup_events: Vec<(u64, u8, HardwareSource)>,
}

impl Default for Engine {
    fn default() -> Self {
        Engine::new(EngineConfig::default(), Vec::new())
    }
}

/// Room for pending and active requests: at most one pending request per OB, and one active
/// level per priority.
const LEVELS: usize = 32;

impl Engine {
    pub fn new(config: EngineConfig, mut schedule: Vec<Scheduled>) -> Self {
        schedule.sort_by_key(|item| item.at_ns);
        // Each hardware event is held at most once at a time.
        let hardware = schedule
            .iter()
            .filter(|item| matches!(item.what, Happening::Hardware { .. }))
            .count();
        let modules = config.hw_modules.len();
        Engine {
            schedule,
            next: 0,
            next_ob13_at: None,
            ob13_ended_at: 0,
            pending: Vec::with_capacity(LEVELS + hardware),
            active: Vec::with_capacity(LEVELS),
            held: Vec::with_capacity(hardware),
            released: Vec::with_capacity(hardware),
            busy_modules: Vec::with_capacity(modules),
            stats: Box::new([ObStats::default(); 256]),
            next_id: 0,
            interrupt_images: false,
            run_started_at: None,
            startup_events: Vec::new(),
            config,
        }
    }

    /// Counts and latencies of an OB.
    pub fn stats(&self, ob: u8) -> ObStats {
        self.stats[usize::from(ob)]
    }

    /// The OBs that were requested, with their counts, by OB number.
    pub fn requested_obs(&self) -> impl Iterator<Item = (u8, &ObStats)> {
        (0..=u8::MAX)
            .zip(self.stats.iter())
            .filter(|(_, stats)| stats.requested > 0)
    }

    fn busy_channel(&self, module: u16) -> Option<u16> {
        self.busy_modules
            .iter()
            .find(|(busy, _, _)| *busy == module)
            .map(|(_, channel, _)| *channel)
    }

    fn set_busy(&mut self, module: u16, channel: u16, id: u64) {
        self.busy_modules.push((module, channel, id));
    }

    fn acknowledged(&mut self, module: u16) {
        self.busy_modules.retain(|(busy, _, _)| *busy != module);
    }

    /// Requests for `ob` that were counted but not yet serviced, lost or ignored: pending, or
    /// held until an acknowledgement.
    pub fn waiting(&self, ob: u8) -> u64 {
        let pending = self.pending.iter().filter(|request| request.ob == ob);
        let held = self.held.iter().filter(|held| held.request.ob == ob);
        (pending.count() + held.count()) as u64
    }

    fn new_id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    fn stats_mut(&mut self, ob: u8) -> &mut ObStats {
        &mut self.stats[usize::from(ob)]
    }

    fn record_latency(&mut self, ob: u8, latency: u64) {
        let stats = self.stats_mut(ob);
        stats.latency_min = if stats.serviced == 0 {
            latency
        } else {
            stats.latency_min.min(latency)
        };
        stats.latency_max = stats.latency_max.max(latency);
        stats.latency_sum += latency;
        stats.serviced += 1;
    }

    /// The next time the engine must look, apart from pending requests.
    fn next_due(&self) -> u64 {
        let scheduled = self
            .schedule
            .get(self.next)
            .map_or(u64::MAX, |item| item.at_ns);
        scheduled.min(self.next_ob13_at.unwrap_or(u64::MAX))
    }
}

impl Cpu {
    fn priority_of(&self, ob: u8) -> u8 {
        self.profile
            .interrupt_ob(ob)
            .map_or(0, |entry| entry.priority)
    }

    /// The priority of the running level: 0 for the cyclic and startup levels.
    pub fn running_priority(&self) -> u8 {
        self.engine
            .active
            .last()
            .map_or(0, |active| active.priority)
    }

    /// Traces an event of the engine; `event` builds it only when a trace is written, so the
    /// engine does no string work and allocates nothing otherwise.
    fn emit(&mut self, t_ns: u64, event: impl FnOnce(&Self) -> Event) {
        if self.tracer.enabled {
            let event = event(self);
            let indent = self.frames.len() + 2 * self.levels.len() + 1;
            self.tracer.emit(t_ns, indent, event);
        }
    }

    /// Traces a block call; `defer` leaves it to the engine, which first logs the requests
    /// that came before it.
    pub(super) fn trace_call(&mut self, from: u16, to: u16, defer: bool) {
        let depth = self.depth();
        let event = Event::BlockCall {
            from: self.block_id(from).to_string(),
            to: self.block_id(to).to_string(),
            depth,
        };
        self.trace_block_event(event, defer, 0);
    }

    pub(super) fn trace_end(&mut self, block: u16, defer: bool) {
        let depth = self.depth();
        let event = Event::BlockEnd {
            block: self.block_id(block).to_string(),
            depth,
        };
        self.trace_block_event(event, defer, 1);
    }

    fn trace_block_event(&mut self, event: Event, defer: bool, extra_indent: usize) {
        if defer {
            self.deferred_trace = Some(event);
        } else {
            let indent = self.frames.len() + 2 * self.levels.len() + extra_indent;
            self.tracer.emit(self.clock, indent, event);
        }
    }

    fn flush_deferred_trace(&mut self) {
        if let Some(event) = self.deferred_trace.take() {
            let extra = usize::from(matches!(event, Event::BlockEnd { .. }));
            let indent = self.frames.len() + 2 * self.levels.len() + extra;
            self.tracer.emit(self.clock, indent, event);
        }
    }

    /// A STOP found by the engine, at the op that led to the interrupt point.
    fn stop_at_last_op(&mut self, cause: StopCause, detail: StopDetail) -> Stop {
        let (block, pc) = self.last_op;
        if self.level.block == super::IDLE || block == self.level.block {
            return self.stop(cause, pc, detail);
        }
        let mut stop = self.stop(cause, self.level.pc, detail);
        let called = self.frames.len() > self.level.level_base
            && self.frames.last().is_some_and(|frame| frame.block == block);
        if called {
            // A block call: the running block is the callee; the call is the caller's entry.
            stop.stack.remove(0);
        } else {
            // A block end: the block that ended is no longer on the stack, and its caller's
            // entry is the call, as for every other return point.
            let running = self.level.block;
            stop.stack[0].line = self.line_of(running, self.level.pc.saturating_sub(1));
            let entry = super::stop::StackEntry {
                block: self.block_id(block).to_string(),
                line: self.line_of(block, pc),
            };
            stop.stack.insert(0, entry);
        }
        stop.block = Some(block);
        stop.pc = pc;
        stop
    }

    /// Keeps `attention_at` at the next moment the engine has to look.
    pub fn update_attention(&mut self) {
        let serviceable = self.mode == Mode::Run
            && self.level.interrupts_enabled
            && self
                .engine
                .pending
                .iter()
                .any(|request| self.priority_of(request.ob) > self.running_priority());
        let watchdog = self
            .cycle_started_at
            .saturating_add(self.engine.config.watchdog_ns);
        self.attention_at = if serviceable {
            0
        } else {
            self.engine.next_due().min(watchdog)
        };
    }

    pub fn start_engine_run(&mut self) {
        self.engine.run_started_at = Some(self.clock);
        for (at, ob, source) in std::mem::take(&mut self.engine.startup_events) {
            self.before_run_event(at, ob, source, self.clock);
        }
        if let Some(interval) = self.engine.config.ob13_interval_ns {
            self.engine.next_ob13_at = Some(self.clock + interval);
        }
    }

    /// Handles an interrupt point: takes in what is due, checks the watchdog, and services the
    /// highest pending request that outranks the running level. Returns whether an OB was
    /// entered.
    pub fn at_point(&mut self, point: Point) -> Result<bool, Stop> {
        let polled = self.poll();
        self.flush_deferred_trace();
        polled?;
        let cycle_time = self.clock - self.cycle_started_at;
        if self.mode != Mode::Stop && cycle_time > self.engine.config.watchdog_ns {
            let detail = StopDetail::Cycle {
                cycle_ns: cycle_time,
                watchdog_ns: self.engine.config.watchdog_ns,
            };
            return Err(self.stop_at_last_op(StopCause::Zyk, detail));
        }
        let is_point = match self.engine.config.points {
            InterruptPoints::Block => {
                matches!(point, Point::BlockCall | Point::BlockEnd | Point::Cycle)
            }
            InterruptPoints::Operation => point != Point::Loop,
        };
        let mut entered = false;
        if is_point && self.mode == Mode::Run && self.level.interrupts_enabled {
            entered = self.service(point)?;
        }
        self.update_attention();
        Ok(entered)
    }

    /// Takes in everything due by now, in time order.
    pub(super) fn poll(&mut self) -> Result<(), Stop> {
        loop {
            let scheduled_at = self
                .engine
                .schedule
                .get(self.engine.next)
                .map(|item| item.at_ns);
            let ob13_at = self.engine.next_ob13_at;
            let due = [scheduled_at, ob13_at]
                .into_iter()
                .flatten()
                .filter(|at| *at <= self.clock)
                .min();
            let Some(at) = due else { return Ok(()) };
            if ob13_at == Some(at) {
                let interval = self.engine.config.ob13_interval_ns.unwrap_or(u64::MAX);
                self.engine.next_ob13_at = Some(at.saturating_add(interval));
                self.ob13_due(at)?;
            } else {
                let index = self.engine.next;
                self.engine.next += 1;
                self.happen(index)?;
            }
        }
    }

    /// The scheduled item `index` happens (read in place: a schedule is never copied).
    fn happen(&mut self, index: usize) -> Result<(), Stop> {
        let at = self.engine.schedule[index].at_ns;
        match &self.engine.schedule[index].what {
            Happening::SetInputs(changes) => {
                for change in changes {
                    let modules = match change.target {
                        InputTarget::Process => &mut self.inputs,
                        InputTarget::Extended => &mut self.extended_inputs,
                    };
                    change.apply(modules);
                }
                Ok(())
            }
            &Happening::Interrupt { ob } => {
                self.request(ob, at, None);
                Ok(())
            }
            &Happening::Hardware {
                module,
                channel,
                active_for_ns,
            } => {
                let source = HardwareSource {
                    module,
                    channel,
                    active_until: at.saturating_add(active_for_ns),
                };
                self.hardware_event(at, source)
            }
        }
    }

    /// Where the running level was when a request came at `at`: the block, and the line where
    /// it can be told — the stretch since the last interrupt point runs straight through one
    /// block (no label jumps), so walking back over the op times finds the op.
    fn place_of_request(&self, at: u64) -> (Option<String>, Option<u32>) {
        if self.mode != Mode::Run {
            return (None, None);
        }
        let stretch = self.last_stretch;
        let (block, end_pc, end_ns) = if stretch.end_ns == self.clock && stretch.start_ns <= at {
            (stretch.block, stretch.end_pc, stretch.end_ns)
        } else if self.level.block != super::IDLE
            && self.engine.config.points == InterruptPoints::Operation
        {
            (
                self.level.block,
                self.level.pc.saturating_sub(1),
                self.clock,
            )
        } else {
            return (None, None);
        };
        let Some(code) = self.program.blocks.get(usize::from(block)) else {
            return (None, None);
        };
        let name = Some(code.id.to_string());
        if code
            .code
            .iter()
            .any(|op| matches!(op, crate::compiler::Op::Jump(..)))
        {
            return (name, None);
        }
        let mut t = end_ns;
        for pc in (0..=end_pc as usize).rev() {
            let Some(cost) = code.elapsed.get(pc + 1).map(|_| code.cost(pc)) else {
                break;
            };
            if t.saturating_sub(cost) <= at {
                return (name, Some(self.sources.line_of(code.spans[pc])));
            }
            t -= cost;
        }
        (name, None)
    }

    /// Logs and counts a request; the caller decides what becomes of it.
    fn announce(&mut self, ob: u8, at: u64, hardware: Option<HardwareSource>) -> Request {
        let id = self.engine.new_id();
        self.engine.stats_mut(ob).requested += 1;
        self.emit(at, |cpu| {
            let (block, line) = if cpu
                .engine
                .run_started_at
                .is_some_and(|started| at >= started)
            {
                cpu.place_of_request(at)
            } else {
                (None, None)
            };
            let (module, channel) = hardware.map_or((None, None), |source| {
                (Some(source.module), Some(source.channel))
            });
            Event::IrqRequest {
                id,
                ob,
                module,
                channel,
                block,
                line,
            }
        });
        Request {
            id,
            ob,
            requested_at: at,
            hardware,
        }
    }

    /// An interrupt request for an OB: ignored, lost, or pending.
    fn request(&mut self, ob: u8, at: u64, hardware: Option<HardwareSource>) -> Option<u64> {
        let id = self.announce(ob, at, hardware).id;
        let normal_mode = self.profile.family == Family::Sinumerik840c
            && !self.engine.config.special_mode
            && (ob == 2 || ob == 5);
        if normal_mode || self.program.ob(ob).is_none() {
            self.engine.stats_mut(ob).ignored += 1;
            self.emit(at, |_| Event::IrqIgnored {
                id,
                ob,
                reason: if normal_mode {
                    format!(
                        "normal mode: OB {ob} is not processed, even when it exists (seed 000, 5.3.1)"
                    )
                } else {
                    format!("OB {ob} is not programmed")
                },
            });
            return None;
        }
        if self.engine.pending.iter().any(|request| request.ob == ob) {
            self.engine.stats_mut(ob).lost += 1;
            self.emit(at, |_| Event::IrqLost {
                id,
                ob,
                reason: format!("OB {ob} already has a pending request"),
            });
            return None;
        }
        self.engine.pending.push(Request {
            id,
            ob,
            requested_at: at,
            hardware,
        });
        Some(id)
    }

    /// S5-95F: OB 13 is due. Due again while it runs, is pending, or ran past this moment: the
    /// wake-up error (seed 002).
    fn ob13_due(&mut self, at: u64) -> Result<(), Stop> {
        if self.program.ob(13).is_none() || self.mode != Mode::Run {
            return Ok(());
        }
        let running = self
            .engine
            .active
            .iter()
            .any(|active| active.request.ob == 13);
        let pending = self.engine.pending.iter().any(|request| request.ob == 13);
        if running || pending || self.engine.ob13_ended_at > at {
            return Err(self.stop_at_last_op(StopCause::Weck, StopDetail::Ob(13)));
        }
        self.request(13, at, None);
        Ok(())
    }

    /// SPEED7: a hardware interrupt event on a module's channel (seed 001).
    fn hardware_event(&mut self, at: u64, source: HardwareSource) -> Result<(), Stop> {
        let Some(&(_, ob)) = self
            .engine
            .config
            .hw_modules
            .iter()
            .find(|(module, _)| *module == source.module)
        else {
            return Ok(());
        };
        match self.engine.run_started_at {
            None => {
                self.engine.startup_events.push((at, ob, source));
                return Ok(());
            }
            Some(started) if at < started => {
                self.before_run_event(at, ob, source, started);
                return Ok(());
            }
            Some(_) => {}
        }
        if let Some(channel) = self.engine.busy_channel(source.module) {
            let request = self.announce(ob, at, Some(source));
            let id = request.id;
            if channel == source.channel {
                self.engine.stats_mut(ob).lost += 1;
                self.emit(at, |_| Event::IrqLost {
                    id,
                    ob,
                    reason: "same channel between identification and acknowledgement (seed 001)"
                        .into(),
                });
                if self.program.ob(82).is_some() {
                    self.request(82, at, None);
                }
            } else {
                self.engine.held.push(Held {
                    request,
                    released_by: source.module,
                });
            }
            return Ok(());
        }
        let ob_busy_for = self
            .engine
            .active
            .iter()
            .map(|active| active.request)
            .chain(self.engine.pending.iter().copied())
            .find_map(|request| {
                (request.ob == ob)
                    .then_some(request.hardware)
                    .flatten()
                    .filter(|other| other.module != source.module)
            });
        if let Some(other) = ob_busy_for {
            let request = self.announce(ob, at, Some(source));
            self.engine.held.push(Held {
                request,
                released_by: other.module,
            });
            return Ok(());
        }
        self.identify(at, ob, source)
    }

    /// A hardware event from before RUN: none is produced in STARTUP, and one still active at
    /// the transition to RUN is lost (seed 001).
    fn before_run_event(&mut self, at: u64, ob: u8, source: HardwareSource, run_started: u64) {
        let id = self.announce(ob, at, Some(source)).id;
        let lost = source.active_until > run_started;
        if lost {
            self.engine.stats_mut(ob).lost += 1;
        } else {
            self.engine.stats_mut(ob).ignored += 1;
        }
        self.emit(at.max(run_started.min(self.clock)), |_| {
            if lost {
                Event::IrqLost {
                    id,
                    ob,
                    reason: "hardware interrupt during the transition to RUN (seed 001)".into(),
                }
            } else {
                Event::IrqIgnored {
                    id,
                    ob,
                    reason: "no hardware interrupt is produced in STARTUP (seed 001)".into(),
                }
            }
        });
    }

    /// The OS identifies the module's OB: the OB is requested and the module is busy until the
    /// acknowledgement; a missing OB calls OB 85 (the interrupt is acknowledged), and a missing
    /// OB 85 stops the CPU.
    fn identify(&mut self, at: u64, ob: u8, source: HardwareSource) -> Result<(), Stop> {
        if self.program.ob(ob).is_none() {
            let id = self.announce(ob, at, Some(source)).id;
            self.engine.stats_mut(ob).ignored += 1;
            let ob85 = self.program.ob(85).is_some();
            self.emit(at, |_| Event::IrqIgnored {
                id,
                ob,
                reason: if ob85 {
                    format!(
                        "OB {ob} is not programmed: OB 85 is called, the interrupt acknowledged (seed 001)"
                    )
                } else {
                    format!("OB {ob} is not programmed and OB 85 is missing (seed 001)")
                },
            });
            if !ob85 {
                return Err(self.stop_at_last_op(
                    StopCause::Ob85,
                    StopDetail::Module {
                        module: source.module,
                        ob,
                    },
                ));
            }
            self.request(85, at, None);
            return Ok(());
        }
        if let Some(id) = self.request(ob, at, Some(source)) {
            self.engine.set_busy(source.module, source.channel, id);
        }
        Ok(())
    }

    /// Services the highest pending request above the running priority, if any.
    fn service(&mut self, point: Point) -> Result<bool, Stop> {
        let running = self.running_priority();
        let best = self
            .engine
            .pending
            .iter()
            .enumerate()
            .map(|(index, request)| {
                (
                    self.priority_of(request.ob),
                    std::cmp::Reverse(request.requested_at),
                    index,
                )
            })
            .filter(|(priority, _, _)| *priority > running)
            .max();
        let Some((priority, _, index)) = best else {
            return Ok(false);
        };
        let request = self.engine.pending.remove(index);
        let latency = self.clock - request.requested_at;
        self.engine.record_latency(request.ob, latency);
        self.emit(self.clock, |cpu| {
            // The block the point belongs to: the one that ended, or was called, or ran the op.
            let point_block = match point {
                Point::BlockEnd => Some(cpu.last_stretch.block),
                Point::Cycle => None,
                _ => (cpu.level.block != super::IDLE).then_some(cpu.level.block),
            };
            Event::IrqService {
                id: request.id,
                ob: request.ob,
                latency_ns: latency,
                point: point.name(),
                block: point_block.map(|block| cpu.block_id(block).to_string()),
            }
        });
        self.levels.push(self.level);
        self.engine.active.push(Active { request, priority });
        let block = self
            .program
            .ob(request.ob)
            .expect("requests are only pending for programmed OBs");
        self.enter_level(block);
        if request.ob == 13 && self.profile.family == Family::S5_95f {
            self.interrupt_input_cycle();
        }
        Ok(true)
    }

    fn data_cycle(&mut self, kind: &'static str) {
        let duration = u64::from(self.profile.timings.data_cycle);
        self.emit(self.clock, |_| Event::DataCycle {
            kind,
            duration_ns: duration,
        });
        self.clock += duration;
    }

    /// S5-95F: at OB 13 start the input modules are read into the interrupt PII (seed 002).
    fn interrupt_input_cycle(&mut self) {
        let length = self.interrupt_pii.len();
        self.interrupt_pii.copy_from_slice(&self.inputs[..length]);
        self.data_cycle("interrupt_input");
        self.engine.interrupt_images = true;
        self.interrupt_piq_written = false;
        self.interrupt_piq_dirty.fill(false);
    }

    /// S5-95F: after OB 13, the interrupt PIQ goes to the modules, only if it was written.
    fn interrupt_output_cycle(&mut self) {
        self.engine.interrupt_images = false;
        if !self.interrupt_piq_written {
            return;
        }
        for (byte, written) in self.interrupt_piq_dirty.iter_mut().enumerate() {
            if std::mem::take(written) {
                self.outputs[byte] = self.interrupt_piq[byte];
            }
        }
        self.interrupt_piq_written = false;
        self.data_cycle("interrupt_output");
    }

    /// The interrupt OB's level has ended: acknowledge, restore the interrupted level. Events
    /// up to the OB's end are taken in first: they came before the acknowledgement.
    pub fn leave_interrupt(&mut self) -> Result<(), Stop> {
        self.poll()?;
        let Some(active) = self.engine.active.pop() else {
            return Ok(());
        };
        let request = active.request;
        self.emit(self.clock, |_| Event::IrqEnd {
            id: request.id,
            ob: request.ob,
        });
        if request.ob == 13 && self.profile.family == Family::S5_95f {
            self.interrupt_output_cycle();
            self.engine.ob13_ended_at = self.clock;
        }
        self.level = self
            .levels
            .pop()
            .expect("an interrupt level has a saved level");
        self.last_point_at = self.clock;
        if let Some(source) = request.hardware {
            self.acknowledge(source.module);
        }
        Ok(())
    }

    /// SPEED7: the channel-specific acknowledgement after the OB has run; held events fire now
    /// if still active, else they are lost (seed 001).
    fn acknowledge(&mut self, module: u16) {
        self.engine.acknowledged(module);
        // Judge the events this acknowledgement releases; the lists keep their capacity.
        let mut released = std::mem::take(&mut self.engine.released);
        self.engine.held.retain(|held| {
            let release = held.released_by == module;
            if release {
                released.push(*held);
            }
            !release
        });
        for held in released.drain(..) {
            let request = held.request;
            let source = request
                .hardware
                .expect("held requests are hardware interrupts");
            let busy = self.engine.busy_channel(source.module).is_some();
            if self.clock < source.active_until && !busy {
                self.engine
                    .set_busy(source.module, source.channel, request.id);
                self.engine.pending.push(request);
            } else if busy {
                self.engine.held.push(Held {
                    request,
                    released_by: source.module,
                });
            } else {
                self.engine.stats_mut(request.ob).lost += 1;
                self.emit(self.clock, |_| Event::IrqLost {
                    id: request.id,
                    ob: request.ob,
                    reason: "no longer active at the acknowledgement (seed 001)".into(),
                });
            }
        }
        self.engine.released = released;
    }
}
