//! The interrupt engine: pending requests, priorities, and where they are serviced. What each
//! manual adds lives in a file of its own, behind the [`Rules`] trait:
//! - [`sinumerik840c`]: normal and special mode (SINUMERIK 840C PLC manual, 5.3.1 and 5.3.2);
//! - [`s5_95f`]: OB 13 with its delay, interrupt process images and wake-up error (S5-95F
//!   manual, "Introduction to STEP 5", 7.4.4 and 7.4.5);
//! - [`speed7`]: hardware interrupts by module and channel (VIPA SPEED7 operation list,
//!   OB 40/OB 41);
//! - [`s5`]: the other S5 CPUs, with nothing beyond the generic engine;
//! - [`inputs`]: interrupts raised by the edges of input bits (`[[interrupt_input]]`).
//!
//! The rules every CPU shares (SINUMERIK 840C PLC manual, 5.3.2): a pending request is serviced
//! at the next interrupt point when its OB's priority is above the running level's; of several,
//! the highest first; after an interrupt OB ends, the pending requests are ranked again. An OB
//! holds one pending request; a second one is lost.
//!
//! The execution loop reports interrupt points only when `clock >= attention_at`; the engine
//! keeps `attention_at` at the next moment something is due (a scheduled event, OB 13, the
//! watchdog, a look of the run's pulse), or at 0 while a pending request outranks the running
//! level. With nothing pending the loop pays one comparison per block change.

pub mod control;
pub mod inputs;
pub mod s5;
pub mod s5_95f;
mod saved;
pub mod sinumerik840c;
pub mod speed7;

use crate::profile::{Family, InterruptPoints, Profile};
use crate::trace::Event;

use super::io_trace::Modules;
use super::place::Place;
use super::stop::{Stop, StopCause, StopDetail};
use super::{Cpu, IDLE, Mode, Point, StretchKind};

use inputs::InterruptInput;
use s5::S5;
use s5_95f::S595f;
pub use saved::{EngineState, RulesState};
use sinumerik840c::Sinumerik840c;
use speed7::Speed7;

/// Something that happens at a simulated time, from the scenario.
#[derive(Debug, Clone, PartialEq)]
pub enum Happening {
    /// Process inputs change.
    SetInputs(Vec<InputChange>),
    /// An S5 interrupt request for an interrupt OB.
    Interrupt { ob: u8 },
    /// A SPEED7 hardware interrupt event on a module's channel.
    Hardware {
        module: u16,
        channel: u16,
        active_for_ns: u64,
    },
    /// SPEED7: a DP station fails (`failed`) or returns.
    Station { station: u8, failed: bool },
}

/// A change of the input modules: a bit (`bytes` 0) or 1, 2 or 4 bytes from `byte`.
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
            super::bytes::write_bytes(modules, at, usize::from(self.bytes), self.value);
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

/// When the S5-95F calls OB 13: every `interval_ns`, each call `delay_ns` late (the delay t
/// of the S5-95F manual, 7.4.4; 0 is the manual's ideal case). With `max_delay_ns` given, an
/// interval not above it is the time interrupt error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ob13Timing {
    pub interval_ns: u64,
    pub delay_ns: u64,
    pub max_delay_ns: Option<u64>,
}

/// The engine's settings for one run.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineConfig {
    pub points: InterruptPoints,
    /// SINUMERIK 840C special mode: OB 2 and OB 5 are processed.
    pub special_mode: bool,
    /// S5-95F: the time-controlled OB 13.
    pub ob13: Option<Ob13Timing>,
    /// SPEED7: which OB a module's hardware interrupts start.
    pub hw_modules: Vec<(u16, u8)>,
    /// SPEED7: the logical base addresses of the modules given one.
    pub hw_addresses: Vec<(u16, u16)>,
    /// SPEED7: the cyclic interrupt OB 35's interval (`[ob35]`).
    pub ob35_interval_ns: u64,
    pub watchdog_ns: u64,
    /// The input bits whose edges raise interrupts (`[[interrupt_input]]`).
    pub interrupt_inputs: Vec<InterruptInput>,
    /// S7: the minimum cycle time; 0 for none.
    pub min_cycle_ns: u64,
}

/// OB 35's interval when the scenario gives none: 100 ms, the default of the S7-300 class and
/// the SPEED7 (VIPA SPEED7 operation list, OB 28, 29, 32, 33, 34, 35 - CYC_INTx).
pub const OB35_DEFAULT_NS: u64 = 100_000_000;

impl EngineConfig {
    /// A module's logical base address, for the start information of its OBs: the one given,
    /// else the module's number.
    pub fn module_address(&self, module: u16) -> u16 {
        self.hw_addresses
            .iter()
            .find(|(known, _)| *known == module)
            .map_or(module, |(_, address)| *address)
    }
}

impl Default for EngineConfig {
    fn default() -> Self {
        EngineConfig {
            points: InterruptPoints::Block,
            special_mode: false,
            ob13: None,
            hw_modules: Vec::new(),
            hw_addresses: Vec::new(),
            ob35_interval_ns: OB35_DEFAULT_NS,
            watchdog_ns: 150_000_000,
            interrupt_inputs: Vec::new(),
            min_cycle_ns: 0,
        }
    }
}

/// Why a serviced request waited longer than the response bound allows for: reasons the
/// manuals give, so the bound does not apply to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Wait {
    /// A level of the same or a higher priority ran, or was serviced first (SINUMERIK 840C
    /// PLC manual, 5.3.2).
    Priority,
    /// `IA` held interrupt servicing back.
    Disabled,
    /// It came before RUN.
    NotInRun,
    /// SFC 41 DIS_AIRT delayed it.
    Delayed,
}

impl Wait {
    pub const ALL: [Wait; 4] = [
        Wait::Priority,
        Wait::Disabled,
        Wait::NotInRun,
        Wait::Delayed,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Wait::Priority => "priority",
            Wait::Disabled => "disabled",
            Wait::NotInRun => "startup",
            Wait::Delayed => "delayed",
        }
    }

    /// What it means, for the summary.
    pub fn explanation(self) -> &'static str {
        match self {
            Wait::Priority => "a level of the same or a higher priority ran first",
            Wait::Disabled => "IA held interrupts back",
            Wait::NotInRun => "it came before RUN",
            Wait::Delayed => "SFC 41 DIS_AIRT delayed it",
        }
    }
}

/// Counts and latencies of one interrupt OB.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct ObStats {
    pub requested: u64,
    pub serviced: u64,
    pub lost: u64,
    pub ignored: u64,
    /// Requests SFC 39 DIS_IRT had disabled.
    pub discarded: u64,
    pub latency_min: u64,
    pub latency_max: u64,
    pub latency_sum: u64,
    /// Serviced requests that waited for a reason of [`Wait`], by its order in `Wait::ALL`.
    pub waited: [u64; 4],
    /// The longest time from the OB's start to its end, interruptions included.
    pub run_max: u64,
}

/// Where a hardware request came from, for the acknowledgement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct HardwareSource {
    pub module: u16,
    pub channel: u16,
    pub active_until: u64,
}

/// Why the operating system requested an error OB, for its start information.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Cause {
    #[default]
    None,
    /// OB 82: a module's event on a channel was lost between identification and
    /// acknowledgement (VIPA SPEED7 operation list, OB 40/OB 41).
    LostChannel { module: u16 },
    /// OB 85: a module's hardware interrupt for `ob`, which is not loaded; `active_ob` of
    /// priority `active_priority` was running.
    MissingOb {
        ob: u8,
        module: u16,
        active_ob: u8,
        active_priority: u8,
    },
    /// OB 80: OB `ob` of priority `priority` was requested again while its last request was
    /// still pending or it still ran.
    TimeError { ob: u8, priority: u8 },
    /// OB 86: DP station `station` failed (`failed`) or returned.
    Station { station: u8, failed: bool },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Request {
    pub id: u64,
    pub ob: u8,
    pub requested_at: u64,
    pub hardware: Option<HardwareSource>,
    pub waited: Option<Wait>,
    /// Why an error OB was requested, for its start information.
    pub cause: Cause,
}

/// An interrupt OB that is running (or interrupted by a higher one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Active {
    pub request: Request,
    pub priority: u8,
    pub started_at: u64,
}

/// What one manual adds to the generic engine. Each CPU family implements it in its own file,
/// with the state its rules keep.
pub trait Rules {
    /// Why the CPU does not process a request for `ob`, when it does not.
    fn ignores(&self, _ob: u8) -> Option<&'static str> {
        None
    }
    /// The next moment these rules need the engine to look, besides the schedule.
    fn next_due(&self) -> u64 {
        u64::MAX
    }
    /// Takes in the CPU's own requests due by now.
    fn poll(&mut self, _cpu: &mut Cpu) -> Result<(), Stop> {
        Ok(())
    }
    /// RUN begins.
    fn start_run(&mut self, _cpu: &mut Cpu) -> Result<(), Stop> {
        Ok(())
    }
    /// An interrupt OB's level was entered.
    fn entered(&mut self, _cpu: &mut Cpu, _ob: u8) {}
    /// An interrupt OB's level ended; the interrupted level is not back yet.
    fn ended(&mut self, _cpu: &mut Cpu, _request: Request) {}
    /// An interrupt OB's level ended and the interrupted level is back.
    fn left(&mut self, _cpu: &mut Cpu, _request: Request) {}
    /// A module's hardware interrupt event.
    fn hardware_event(
        &mut self,
        _cpu: &mut Cpu,
        _at: u64,
        _source: HardwareSource,
    ) -> Result<(), Stop> {
        Ok(())
    }
    /// The hardware event an input raised on a module's channel ends at `at`: the input
    /// changed back.
    fn hardware_ended(&mut self, _cpu: &mut Cpu, _module: u16, _channel: u16, _at: u64) {}
    /// A DP station fails or returns (only the SPEED7 has them).
    fn station_event(
        &mut self,
        _cpu: &mut Cpu,
        _at: u64,
        _station: u8,
        _failed: bool,
    ) -> Result<(), Stop> {
        Ok(())
    }
    /// Requests for `ob` these rules hold outside the pending list.
    fn held(&self, _ob: u8) -> u64 {
        0
    }
    /// The time of the earliest event these rules have taken in but not traced yet, because
    /// what it becomes is decided later; the trace is held back from that time on.
    fn untraced_since(&self) -> u64 {
        u64::MAX
    }
    /// What these rules keep between two cycles, for a snapshot.
    fn saved(&self) -> RulesState {
        RulesState::Plain
    }
    /// Takes up what [`Rules::saved`] gave; a state of another family does not fit.
    fn restore(&mut self, state: &RulesState) -> Result<(), &'static str> {
        match state {
            RulesState::Plain => Ok(()),
            _ => Err(FOREIGN_RULES),
        }
    }
}

/// A snapshot's interrupt state is another CPU family's.
pub const FOREIGN_RULES: &str = "the snapshot's interrupt state belongs to another CPU family";

/// The rules of the running CPU's family, with their state.
#[derive(Debug, Default)]
pub enum FamilyRules {
    Sinumerik840c(Sinumerik840c),
    S595f(S595f),
    Speed7(Speed7),
    S5(S5),
    /// Taken out while one of its hooks runs (see `Cpu::with_rules`).
    #[default]
    Taken,
}

/// What the engine sees of the rules while a hook has them.
struct Taken;

impl Rules for Taken {}

impl FamilyRules {
    fn new(profile: &Profile, config: &EngineConfig, schedule: &[Scheduled]) -> Self {
        match profile.family {
            Family::Sinumerik840c => FamilyRules::Sinumerik840c(Sinumerik840c::new(config)),
            Family::S5_95f => FamilyRules::S595f(S595f::new(profile, config)),
            Family::Speed7 => FamilyRules::Speed7(Speed7::new(config, schedule)),
            Family::S5 => FamilyRules::S5(S5::new(profile)),
        }
    }

    fn rules(&self) -> &dyn Rules {
        match self {
            FamilyRules::Sinumerik840c(rules) => rules,
            FamilyRules::S595f(rules) => rules,
            FamilyRules::Speed7(rules) => rules,
            FamilyRules::S5(rules) => rules,
            FamilyRules::Taken => &Taken,
        }
    }

    fn rules_mut(&mut self) -> &mut dyn Rules {
        match self {
            FamilyRules::Sinumerik840c(rules) => rules,
            FamilyRules::S595f(rules) => rules,
            FamilyRules::Speed7(rules) => rules,
            FamilyRules::S5(rules) => rules,
            // A box of a zero-sized type allocates nothing.
            FamilyRules::Taken => Box::leak(Box::new(Taken)),
        }
    }
}

/// How many hardware interrupt events `schedule` can bring at most: its `hw_interrupt` events
/// and those its input changes raise.
fn hardware_events(config: &EngineConfig, schedule: &[Scheduled]) -> usize {
    let events = schedule
        .iter()
        .filter(|item| matches!(item.what, Happening::Hardware { .. }))
        .count();
    let changes = schedule.iter().flat_map(|item| match &item.what {
        Happening::SetInputs(changes) => changes.as_slice(),
        _ => &[],
    });
    events + inputs::hardware_events(&config.interrupt_inputs, changes)
}

/// Room for pending and active requests: one pending request per OB, one active level per
/// priority.
const LEVELS: usize = 32;

/// The engine's state. Every collection gets its capacity when the engine is made, sized from
/// the schedule, so servicing interrupts allocates nothing while the CPU runs.
pub struct Engine {
    pub config: EngineConfig,
    schedule: Vec<Scheduled>,
    next: usize,
    pub(super) pending: Vec<Request>,
    pub active: Vec<Active>,
    /// Counts and latencies by OB number.
    stats: Box<[ObStats; 256]>,
    next_id: u64,
    /// When RUN began (SPEED7: hardware interrupts before it are not produced).
    run_started_at: Option<u64>,
    pub rules: FamilyRules,
    /// The OBs SFC 39 DIS_IRT has disabled.
    pub disabled: control::Disabled,
    /// A STOP an input change from outside the run brought, for the next interrupt point.
    stop_due: Option<Stop>,
}

impl Engine {
    pub fn new(profile: &Profile, config: EngineConfig, mut schedule: Vec<Scheduled>) -> Self {
        schedule.sort_by_key(|item| item.at_ns);
        let hardware = hardware_events(&config, &schedule);
        Engine {
            rules: FamilyRules::new(profile, &config, &schedule),
            schedule,
            next: 0,
            pending: Vec::with_capacity(LEVELS + hardware),
            active: Vec::with_capacity(LEVELS),
            stats: Box::new([ObStats::default(); 256]),
            next_id: 0,
            run_started_at: None,
            disabled: control::Disabled::default(),
            stop_due: None,
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

    /// Requests for `ob` that were counted but not yet serviced, lost or ignored: pending, or
    /// held until an acknowledgement.
    pub fn waiting(&self, ob: u8) -> u64 {
        let pending = self.pending.iter().filter(|request| request.ob == ob);
        pending.count() as u64 + self.rules.rules().held(ob)
    }

    fn new_id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    fn stats_mut(&mut self, ob: u8) -> &mut ObStats {
        &mut self.stats[usize::from(ob)]
    }

    fn record_service(&mut self, request: Request, latency: u64) {
        let stats = self.stats_mut(request.ob);
        stats.latency_min = if stats.serviced == 0 {
            latency
        } else {
            stats.latency_min.min(latency)
        };
        stats.latency_max = stats.latency_max.max(latency);
        stats.latency_sum += latency;
        stats.serviced += 1;
        if let Some(wait) = request.waited {
            let index = Wait::ALL.iter().position(|w| *w == wait).unwrap_or(0);
            stats.waited[index] += 1;
        }
    }

    /// The next moment the engine must look, apart from pending requests.
    pub(crate) fn next_due(&self) -> u64 {
        let scheduled = self
            .schedule
            .get(self.next)
            .map_or(u64::MAX, |item| item.at_ns);
        scheduled.min(self.rules.rules().next_due())
    }
}

impl Cpu {
    pub(super) fn priority_of(&self, ob: u8) -> u8 {
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

    /// Runs a hook of the family's rules, which get the whole CPU: their state is taken out of
    /// it meanwhile (a move, no allocation). Hooks do not nest.
    fn with_rules<T>(&mut self, hook: impl FnOnce(&mut dyn Rules, &mut Cpu) -> T) -> T {
        let mut rules = std::mem::take(&mut self.engine.rules);
        let result = hook(rules.rules_mut(), self);
        self.engine.rules = rules;
        result
    }

    /// Traces an event of the engine; `event` builds it only when a trace is written, so the
    /// engine does no string work and allocates nothing otherwise.
    pub(super) fn emit(&mut self, t_ns: u64, event: impl FnOnce(&Self) -> Event) {
        if self.tracer.enabled {
            let event = event(self);
            self.tracer.emit(t_ns, event);
        }
    }

    /// A STOP found by the engine, at the op that led to the interrupt point.
    pub(super) fn stop_at_last_op(&mut self, cause: StopCause, detail: StopDetail) -> Stop {
        let (block, pc) = self.last_op;
        if self.level.block == IDLE || block == self.level.block {
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
            stop.stack[0] = self.stack_entry(running, self.level.pc.saturating_sub(1));
            let entry = self.stack_entry(block, pc);
            stop.stack.insert(0, entry);
        }
        stop.block = Some(block);
        stop.pc = pc;
        stop
    }

    /// Keeps `attention_at` at the next moment the engine has to look (or the pulse, see
    /// [`super::pulse`]).
    pub fn update_attention(&mut self) {
        let running = self.running_priority();
        let serviceable = self.mode == Mode::Run
            && self.level.interrupts_enabled
            && self.level.airt_delays == 0
            && self
                .engine
                .pending
                .iter()
                .any(|request| self.priority_of(request.ob) > running);
        let watchdog = self
            .cycle_started_at
            .saturating_add(self.engine.config.watchdog_ns);
        self.engine_attention_at = if serviceable || self.engine.stop_due.is_some() {
            0
        } else {
            self.engine.next_due().min(watchdog)
        };
        self.attention_at = self.engine_attention_at.min(self.next_look_ns());
    }

    /// RUN begins: the rules judge what came before it and start their own timing.
    pub(super) fn start_engine_run(&mut self) -> Result<(), Stop> {
        self.engine.run_started_at = Some(self.clock);
        self.with_rules(|rules, cpu| rules.start_run(cpu))?;
        self.update_attention();
        Ok(())
    }

    /// When RUN began, if it has.
    pub fn run_started_at(&self) -> Option<u64> {
        self.engine.run_started_at
    }

    /// Handles an interrupt point: takes in what is due, checks the watchdog, and services the
    /// highest pending request that outranks the running level. Returns whether an OB was
    /// entered.
    pub fn at_point(&mut self, point: Point) -> Result<bool, Stop> {
        if let Some(stop) = self.engine.stop_due.take() {
            return Err(stop);
        }
        self.poll()?;
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
        if is_point && self.mode == Mode::Run {
            if self.level.airt_delays > 0 {
                self.mark_waiting(Wait::Delayed);
            } else if self.level.interrupts_enabled {
                entered = self.service(point)?;
            } else {
                self.mark_waiting(Wait::Disabled);
            }
        }
        self.update_attention();
        Ok(entered)
    }

    /// Pending requests that outrank the running level but cannot be serviced now.
    fn mark_waiting(&mut self, wait: Wait) {
        let running = self.running_priority();
        for index in 0..self.engine.pending.len() {
            let ob = self.engine.pending[index].ob;
            if self.priority_of(ob) > running {
                self.engine.pending[index].waited.get_or_insert(wait);
            }
        }
    }

    /// Takes in everything due by now, in time order. The trace is in time order too: what
    /// it holds back until now is written.
    pub(super) fn poll(&mut self) -> Result<(), Stop> {
        loop {
            let scheduled_at = self
                .engine
                .schedule
                .get(self.engine.next)
                .map_or(u64::MAX, |item| item.at_ns);
            let own = self.engine.rules.rules().next_due();
            if scheduled_at.min(own) > self.clock {
                break;
            }
            if own <= scheduled_at {
                self.with_rules(|rules, cpu| rules.poll(cpu))?;
            } else {
                let index = self.engine.next;
                self.engine.next += 1;
                self.happen(index)?;
            }
        }
        if self.tracer.enabled {
            self.settle_trace();
        }
        Ok(())
    }

    /// Hands on the trace up to now, short of the events the rules have yet to trace: every
    /// event is written in time order, those of STARTUP too.
    pub(super) fn settle_trace(&mut self) {
        let untraced_since = self.engine.rules.rules().untraced_since();
        if untraced_since > self.clock {
            self.tracer.settle(self.clock);
        } else if let Some(before) = untraced_since.checked_sub(1) {
            self.tracer.settle(before);
        }
    }

    /// The scheduled item `index` happens (read in place: a schedule is never copied).
    fn happen(&mut self, index: usize) -> Result<(), Stop> {
        let at = self.engine.schedule[index].at_ns;
        match &self.engine.schedule[index].what {
            Happening::SetInputs(changes) => {
                for index_of_change in 0..changes.len() {
                    self.set_inputs(index, index_of_change, at)?;
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
                self.with_rules(|rules, cpu| rules.hardware_event(cpu, at, source))
            }
            &Happening::Station { station, failed } => {
                self.with_rules(|rules, cpu| rules.station_event(cpu, at, station, failed))
            }
        }
    }

    /// Change `change` of the scheduled item `index` reaches the input modules at `at`.
    fn set_inputs(&mut self, index: usize, change: usize, at: u64) -> Result<(), Stop> {
        let Happening::SetInputs(changes) = &self.engine.schedule[index].what else {
            return Ok(());
        };
        self.inputs_change(changes[change], at)
    }

    /// The input modules deliver `change` now: a scenario's `set`, or a network client's write
    /// to the inputs. The program sees it in the PII at the next cycle start, direct
    /// (peripheral) reads at once; an interrupt input's edge raises its interrupt
    /// ([`inputs`]). A STOP that raising brings (a SPEED7 module's OB and OB 85 both missing)
    /// comes at the next interrupt point.
    pub fn deliver_inputs(&mut self, change: InputChange) {
        if let Err(stop) = self.inputs_change(change, self.clock) {
            self.engine.stop_due = Some(stop);
            self.update_attention();
        }
    }

    /// [`Cpu::deliver_inputs`] at `at`, with the STOP it brings.
    fn inputs_change(&mut self, change: InputChange, at: u64) -> Result<(), Stop> {
        let extended = change.target == InputTarget::Extended;
        let (first, count) = (usize::from(change.byte), usize::from(change.bytes.max(1)));
        let before = self.modules_before(Modules::Inputs, extended, first, count);
        let levels = self.inputs_before(&change);
        change.apply(if extended {
            &mut self.extended_inputs
        } else {
            &mut self.inputs
        });
        if let Some(before) = before {
            self.trace_module_changes(Modules::Inputs, extended, first, &before);
        }
        if self.engine.config.interrupt_inputs.is_empty() {
            return Ok(());
        }
        self.raise_on_edges(&change, levels, at)
    }

    /// Logs and counts a request; the caller decides what becomes of it.
    pub(super) fn announce(
        &mut self,
        ob: u8,
        at: u64,
        hardware: Option<HardwareSource>,
    ) -> Request {
        self.announce_placed(ob, at, hardware, None)
    }

    /// As [`Cpu::announce`], for a request taken in earlier, at `place` (the last stretch no
    /// longer holds its moment).
    pub(super) fn announce_placed(
        &mut self,
        ob: u8,
        at: u64,
        hardware: Option<HardwareSource>,
        place: Option<Place>,
    ) -> Request {
        let id = self.engine.new_id();
        self.engine.stats_mut(ob).requested += 1;
        self.emit(at, |cpu| {
            let place = place.unwrap_or_else(|| cpu.place_of(at));
            let (module, channel) = hardware.map_or((None, None), |source| {
                (Some(source.module), Some(source.channel))
            });
            Event::IrqRequest {
                id,
                ob,
                module,
                channel,
                block: place.block,
                line: place.line,
                segment: place.segment,
                during: place.during,
            }
        });
        self.with_probe((), |probe, cpu| probe.requested(cpu, ob, at));
        let waited = if self.mode != Mode::Run {
            Some(Wait::NotInRun)
        } else if self.running_priority() >= self.priority_of(ob) {
            Some(Wait::Priority)
        } else if !self.level.interrupts_enabled {
            Some(Wait::Disabled)
        } else if self.level.airt_delays > 0 {
            Some(Wait::Delayed)
        } else {
            None
        };
        Request {
            id,
            ob,
            requested_at: at,
            hardware,
            waited,
            cause: Cause::None,
        }
    }

    /// An interrupt request for an OB: ignored, lost, or pending. Returns its id when pending.
    pub(super) fn request(
        &mut self,
        ob: u8,
        at: u64,
        hardware: Option<HardwareSource>,
    ) -> Option<u64> {
        self.request_for(ob, at, hardware, Cause::None)
    }

    /// As [`Cpu::request`], for an error OB requested because of `cause`.
    pub(super) fn request_for(
        &mut self,
        ob: u8,
        at: u64,
        hardware: Option<HardwareSource>,
        cause: Cause,
    ) -> Option<u64> {
        let request = Request {
            cause,
            ..self.announce(ob, at, hardware)
        };
        let id = request.id;
        if self.engine.disabled.has(ob) {
            self.discard(at, request);
            return None;
        }
        let rule = self.engine.rules.rules().ignores(ob);
        if rule.is_some() || self.program.ob(ob).is_none() {
            self.ignore(at, request, rule);
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
        if request.waited == Some(Wait::Delayed) {
            let delays = self.level.airt_delays;
            self.emit(at, |_| Event::IrqDelayed { id, ob, delays });
        }
        self.engine.pending.push(request);
        Some(id)
    }

    /// Counts and traces a request the CPU does not process.
    pub(super) fn ignore(&mut self, at: u64, request: Request, rule: Option<&'static str>) {
        let (id, ob) = (request.id, request.ob);
        self.engine.stats_mut(ob).ignored += 1;
        self.emit(at, |_| Event::IrqIgnored {
            id,
            ob,
            reason: match rule {
                Some(rule) => format!("OB {ob}: {rule}"),
                None => format!("OB {ob} is not programmed"),
            },
        });
    }

    /// Counts and traces a request that is lost.
    pub(super) fn lose(&mut self, at: u64, request: Request, reason: &'static str) {
        let (id, ob) = (request.id, request.ob);
        self.engine.stats_mut(ob).lost += 1;
        self.emit(at, |_| Event::IrqLost {
            id,
            ob,
            reason: reason.to_string(),
        });
    }

    /// Requests an interrupt for `ob` now (the debugger's `fire`): it is serviced at the next
    /// interrupt point, as any other request. Returns whether it is pending.
    pub fn fire(&mut self, ob: u8) -> bool {
        let pending = self.request(ob, self.clock, None).is_some();
        self.update_attention();
        pending
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
        self.engine.record_service(request, latency);
        // The others wait for this OB, unless they outrank it.
        for other in &mut self.engine.pending {
            if self
                .profile
                .interrupt_ob(other.ob)
                .map_or(0, |o| o.priority)
                <= priority
            {
                other.waited.get_or_insert(Wait::Priority);
            }
        }
        self.emit(self.clock, |cpu| Event::IrqService {
            id: request.id,
            ob: request.ob,
            latency_ns: latency,
            point: point.name(),
            block: cpu
                .point_block(point)
                .map(|block| cpu.block_id(block).to_string()),
            waited: request.waited.map(Wait::name),
        });
        self.levels.push(self.level);
        self.engine.active.push(Active {
            request,
            priority,
            started_at: self.clock,
        });
        let block = self
            .program
            .ob(request.ob)
            .expect("requests are only pending for programmed OBs");
        self.enter_level(block)?;
        if !self.local.is_empty() {
            let head = self.interrupt_start_info(&request, priority);
            self.write_start_info(head);
        }
        self.with_rules(|rules, cpu| rules.entered(cpu, request.ob));
        self.with_probe((), |probe, cpu| probe.serviced(cpu, request.ob));
        Ok(true)
    }

    /// The block an interrupt point belongs to: the one that ended, was called, or ran the
    /// operation; none at the cycle's own points.
    fn point_block(&self, point: Point) -> Option<u16> {
        match point {
            Point::Cycle => None,
            _ => match self.last_stretch.kind {
                StretchKind::Block { block, .. } | StretchKind::InterruptEnd { block } => {
                    Some(block)
                }
                _ => None,
            },
        }
    }

    /// The interrupt OB's level has ended: acknowledge, restore the interrupted level. Events
    /// up to the OB's end are taken in first: they came before the acknowledgement.
    pub fn leave_interrupt(&mut self) -> Result<(), Stop> {
        self.poll()?;
        let Some(active) = self.engine.active.pop() else {
            return Ok(());
        };
        let request = active.request;
        self.end_delays(request.ob);
        self.emit(self.clock, |_| Event::IrqEnd {
            id: request.id,
            ob: request.ob,
        });
        self.with_rules(|rules, cpu| rules.ended(cpu, request));
        let stats = self.engine.stats_mut(request.ob);
        stats.run_max = stats.run_max.max(self.clock - active.started_at);
        self.level = self
            .levels
            .pop()
            .expect("an interrupt level has a saved level");
        self.with_rules(|rules, cpu| rules.left(cpu, request));
        Ok(())
    }

    /// An S5 data cycle of the family's rules: traced, and it takes its time.
    pub(super) fn data_cycle(&mut self, kind: &'static str, direction: &'static str) {
        let duration = u64::from(self.profile.timings.data_cycle);
        self.emit(self.clock, |_| Event::DataCycle {
            kind,
            direction,
            duration_ns: duration,
        });
        self.clock += duration;
    }
}
