//! The VIPA SPEED7: hardware interrupts by module and channel (VIPA SPEED7 operation list,
//! "OB 40, OB 41 - HW_INTx - Hardware Interrupt").
//!
//! - "the operating system identifies the slot and the corresponding hardware interrupt OB. If
//!   this OB has a higher priority than the currently active priority class, it will be
//!   started" (the generic engine's priorities);
//! - "the channel-specific acknowledgement is sent after this hardware interrupt OB has been
//!   executed";
//! - between identification and acknowledgement, a new event "on the channel that previously
//!   triggered the hardware interrupt" is lost, and the loss "is announced by means of a
//!   diagnostic interrupt" (OB 82); one "on another channel of the same module" is held and
//!   "triggered if just active after the acknowledgement ... Else it is lost";
//! - "if a hardware interrupt is triggered and its OB is currently active due to a hardware
//!   interrupt from another module, the new request can be processed only if it is still
//!   active after acknowledgement";
//! - "During STARTUP there is no hardware interrupt produced ... Hardware interrupts during
//!   transition to RUN are lost";
//! - no OB for the module: "OB 85 is called ... The hardware interrupt is acknowledged. If OB 85
//!   has not been programmed, the CPU goes to STOP".
//!
//! The cyclic interrupt OB 35 (VIPA SPEED7 operation list, "OB 28, 29, 32, 33, 34, 35 -
//! CYC_INTx"): priority 12, every `[ob35]` interval (100 ms by default) counted from the
//! transition to RUN, when the program has OB 35 ("A cyclic interrupt is activated by
//! programming the corresponding OB"). A request while the last one is still pending or OB 35
//! still runs is the time error: the operating system calls OB 80 ("System Software for
//! S7-300/400 System and Standard Functions", 1.16 Time Error Organization Block (OB80): "If,
//! for example, a start event for a cyclic interrupt OB occurs while the same OB is still being
//! executed following a previous call, the operating system calls OB80. If OB80 has not been
//! programmed, the CPU changes to the STOP mode"; the SPEED7 operation list, "OB 80 -
//! CYCL_FLT", says the same). The new request runs later ("The cyclic interrupt that caused the
//! error is executed later") unless one is still pending: an OB holds one pending request.
//!
//! A DP station's failure and its return (VIPA SPEED7 operation list, "OB 86 - RACK_FLT - Slave
//! Failure / Restart"): "The operating system of the CPU calls OB 86 whenever the failure of a
//! slave is detected (both when entering and outgoing event). If OB 86 has not been programmed,
//! the CPU changes to the STOP mode"; "OB 86 may be delayed by means of the SFC 41".

use crate::trace::Event;

use super::super::place::Place;
use super::Cause;
use super::inputs::WHILE_INPUT_HOLDS;

use super::super::stop::{Stop, StopCause, StopDetail};
use super::{
    Cpu, EngineConfig, FOREIGN_RULES, HardwareSource, Request, Rules, RulesState, Scheduled, Wait,
};

/// A hardware event held until an acknowledgement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Held {
    request: Request,
    /// The module whose acknowledgement releases it.
    released_by: u16,
}

#[derive(Debug, Default)]
pub struct Speed7 {
    /// Which OB each module's hardware interrupts start.
    modules: Vec<(u16, u8)>,
    /// Modules between identification and acknowledgement: (module, channel).
    busy: Vec<(u16, u16)>,
    held: Vec<Held>,
    /// Held events released by an acknowledgement, while they are judged.
    released: Vec<Held>,
    /// Events of the STARTUP, judged at the transition to RUN, with where the CPU was when
    /// each came (when a trace is written).
    startup_events: Vec<(u64, u8, HardwareSource, Option<Place>)>,
    /// OB 35's interval and its next request (`u64::MAX`: none).
    ob35_every_ns: u64,
    ob35_next: u64,
}

/// The cyclic interrupt OB and the time error OB.
const CYCLIC_OB: u8 = 35;
const TIME_ERROR_OB: u8 = 80;
/// The slave failure / restart OB.
const STATION_OB: u8 = 86;
const OB35_BEHIND: &str = "its last request has not run yet: a time error (System Software \
     for S7-300/400 System and Standard Functions, 1.16)";

const SAME_CHANNEL: &str = "same channel between identification and acknowledgement \
     (VIPA SPEED7 operation list, OB 40/OB 41)";
const GONE: &str =
    "no longer active at the acknowledgement (VIPA SPEED7 operation list, OB 40/OB 41)";
const TRANSITION: &str =
    "hardware interrupt during the transition to RUN (VIPA SPEED7 operation list, OB 40/OB 41)";
const IN_STARTUP: &str =
    "during STARTUP no hardware interrupt is produced (VIPA SPEED7 operation list, OB 40/OB 41)";
const OB85_CALLED: &str = "not programmed: OB 85 is called and the interrupt acknowledged \
     (VIPA SPEED7 operation list, OB 40/OB 41)";
const NO_OB85: &str =
    "not programmed and OB 85 is missing (VIPA SPEED7 operation list, OB 40/OB 41)";

impl Speed7 {
    pub fn new(config: &EngineConfig, schedule: &[Scheduled]) -> Self {
        // Each event is held at most once at a time.
        let events = super::hardware_events(config, schedule);
        Speed7 {
            modules: config.hw_modules.clone(),
            busy: Vec::with_capacity(config.hw_modules.len()),
            held: Vec::with_capacity(events),
            released: Vec::with_capacity(events),
            startup_events: Vec::with_capacity(events),
            ob35_every_ns: config.ob35_interval_ns.max(1),
            ob35_next: u64::MAX,
        }
    }

    /// OB 35 is due: requested, or the time error when it is behind.
    fn cyclic_interrupt(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        let at = self.ob35_next;
        self.ob35_next = at.saturating_add(self.ob35_every_ns);
        let running = cpu.engine.active.iter().any(|a| a.request.ob == CYCLIC_OB);
        let pending = cpu.engine.pending.iter().any(|r| r.ob == CYCLIC_OB);
        if cpu.engine.disabled.has(CYCLIC_OB) || !(running || pending) {
            cpu.request(CYCLIC_OB, at, None);
            return Ok(());
        }
        if pending {
            let request = cpu.announce(CYCLIC_OB, at, None);
            cpu.lose(at, request, OB35_BEHIND);
        } else {
            cpu.request(CYCLIC_OB, at, None);
        }
        let disabled = cpu.engine.disabled.has(TIME_ERROR_OB);
        if cpu.program.ob(TIME_ERROR_OB).is_none() && !disabled {
            return Err(cpu.stop_at_last_op(StopCause::Ob80, StopDetail::Ob(CYCLIC_OB)));
        }
        let cause = Cause::TimeError {
            ob: CYCLIC_OB,
            priority: cpu.priority_of(CYCLIC_OB),
        };
        cpu.request_for(TIME_ERROR_OB, at, None, cause);
        Ok(())
    }

    fn busy_channel(&self, module: u16) -> Option<u16> {
        self.busy
            .iter()
            .find(|(busy, _)| *busy == module)
            .map(|(_, channel)| *channel)
    }

    fn hold(&mut self, mut request: Request, released_by: u16) {
        request.waited.get_or_insert(Wait::Priority);
        self.held.push(Held {
            request,
            released_by,
        });
    }

    /// A hardware event from before RUN: in STARTUP none is produced (it is no request), and
    /// one still active at the transition to RUN is lost.
    fn before_run(
        &mut self,
        cpu: &mut Cpu,
        at: u64,
        ob: u8,
        source: HardwareSource,
        place: Option<Place>,
    ) {
        let run_started = cpu.run_started_at().unwrap_or(cpu.clock);
        if source.active_until > run_started {
            let request = cpu.announce_placed(ob, at, Some(source), place);
            cpu.lose(run_started, request, TRANSITION);
        } else {
            cpu.emit(at, |_| Event::ModuleEvent {
                module: source.module,
                channel: source.channel,
                ob,
                reason: IN_STARTUP,
            });
        }
    }

    /// The OS identifies the module's OB: the OB is requested and the module is busy until the
    /// acknowledgement; a missing OB calls OB 85 (the interrupt is acknowledged), and a missing
    /// OB 85 stops the CPU.
    fn identify(
        &mut self,
        cpu: &mut Cpu,
        at: u64,
        ob: u8,
        source: HardwareSource,
    ) -> Result<(), Stop> {
        if cpu.program.ob(ob).is_none() {
            let request = cpu.announce(ob, at, Some(source));
            let ob85 = cpu.program.ob(85).is_some();
            cpu.ignore(at, request, Some(if ob85 { OB85_CALLED } else { NO_OB85 }));
            if !ob85 {
                let detail = StopDetail::Module {
                    module: source.module,
                    ob,
                };
                return Err(cpu.stop_at_last_op(StopCause::Ob85, detail));
            }
            let (active_ob, active_priority) = cpu.active_ob();
            let cause = Cause::MissingOb {
                ob,
                module: source.module,
                active_ob,
                active_priority,
            };
            cpu.request_for(85, at, None, cause);
            return Ok(());
        }
        if cpu.request(ob, at, Some(source)).is_some() {
            self.busy.push((source.module, source.channel));
        }
        Ok(())
    }

    /// The channel-specific acknowledgement after the OB has run: held events fire now if
    /// still active, else they are lost.
    fn acknowledge(&mut self, cpu: &mut Cpu, module: u16) {
        self.busy.retain(|(busy, _)| *busy != module);
        let mut released = std::mem::take(&mut self.released);
        self.held.retain(|held| {
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
            let busy = self.busy_channel(source.module).is_some();
            if cpu.clock < source.active_until && !busy {
                self.busy.push((source.module, source.channel));
                cpu.engine.pending.push(request);
            } else if busy {
                self.hold(request, source.module);
            } else {
                cpu.lose(cpu.clock, request, GONE);
            }
        }
        self.released = released;
    }
}

impl Rules for Speed7 {
    fn saved(&self) -> RulesState {
        RulesState::Speed7 {
            busy: self.busy.clone(),
            held: self
                .held
                .iter()
                .map(|held| (held.request, held.released_by))
                .collect(),
            ob35_next: self.ob35_next,
        }
    }

    fn restore(&mut self, state: &RulesState) -> Result<(), &'static str> {
        let RulesState::Speed7 {
            busy,
            held,
            ob35_next,
        } = state
        else {
            return Err(FOREIGN_RULES);
        };
        self.busy.clear();
        self.busy.extend_from_slice(busy);
        self.held.clear();
        self.held
            .extend(held.iter().map(|(request, released_by)| Held {
                request: *request,
                released_by: *released_by,
            }));
        self.ob35_next = *ob35_next;
        Ok(())
    }

    /// Events an input raised on the channel are no longer active: one held until an
    /// acknowledgement is then lost, one of STARTUP is no request at the transition to RUN.
    fn hardware_ended(&mut self, _cpu: &mut Cpu, module: u16, channel: u16, at: u64) {
        let sources = self
            .held
            .iter_mut()
            .filter_map(|held| held.request.hardware.as_mut())
            .chain(
                self.startup_events
                    .iter_mut()
                    .map(|(_, _, source, _)| source),
            );
        for source in sources {
            if source.module == module
                && source.channel == channel
                && source.active_until == WHILE_INPUT_HOLDS
            {
                source.active_until = at;
            }
        }
    }

    fn station_event(
        &mut self,
        cpu: &mut Cpu,
        at: u64,
        station: u8,
        failed: bool,
    ) -> Result<(), Stop> {
        let disabled = cpu.engine.disabled.has(STATION_OB);
        if cpu.program.ob(STATION_OB).is_none() && !disabled {
            let detail = StopDetail::Station { station, failed };
            return Err(cpu.stop_at_last_op(StopCause::Ob86, detail));
        }
        cpu.request_for(STATION_OB, at, None, Cause::Station { station, failed });
        Ok(())
    }

    fn hardware_event(
        &mut self,
        cpu: &mut Cpu,
        at: u64,
        source: HardwareSource,
    ) -> Result<(), Stop> {
        let Some(&(_, ob)) = self
            .modules
            .iter()
            .find(|(module, _)| *module == source.module)
        else {
            return Ok(());
        };
        match cpu.run_started_at() {
            None => {
                let place = cpu.tracer.enabled.then(|| cpu.place_of(at));
                self.startup_events.push((at, ob, source, place));
                return Ok(());
            }
            Some(started) if at < started => {
                self.before_run(cpu, at, ob, source, None);
                return Ok(());
            }
            Some(_) => {}
        }
        if let Some(channel) = self.busy_channel(source.module) {
            let request = cpu.announce(ob, at, Some(source));
            if channel == source.channel {
                cpu.lose(at, request, SAME_CHANNEL);
                if cpu.program.ob(82).is_some() {
                    let cause = Cause::LostChannel {
                        module: source.module,
                    };
                    cpu.request_for(82, at, None, cause);
                }
            } else {
                self.hold(request, source.module);
            }
            return Ok(());
        }
        let busy_for_another_module = cpu
            .engine
            .active
            .iter()
            .map(|active| active.request)
            .chain(cpu.engine.pending.iter().copied())
            .find_map(|request| {
                (request.ob == ob)
                    .then_some(request.hardware)
                    .flatten()
                    .filter(|other| other.module != source.module)
            });
        if let Some(other) = busy_for_another_module {
            let request = cpu.announce(ob, at, Some(source));
            self.hold(request, other.module);
            return Ok(());
        }
        self.identify(cpu, at, ob, source)
    }

    fn next_due(&self) -> u64 {
        self.ob35_next
    }

    fn poll(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        self.cyclic_interrupt(cpu)
    }

    fn start_run(&mut self, cpu: &mut Cpu) -> Result<(), Stop> {
        if cpu.program.ob(CYCLIC_OB).is_some() {
            self.ob35_next = cpu.clock.saturating_add(self.ob35_every_ns);
        }
        let mut events = std::mem::take(&mut self.startup_events);
        for (at, ob, source, place) in events.drain(..) {
            self.before_run(cpu, at, ob, source, place);
        }
        self.startup_events = events;
        Ok(())
    }

    fn left(&mut self, cpu: &mut Cpu, request: Request) {
        if let Some(source) = request.hardware {
            self.acknowledge(cpu, source.module);
        }
    }

    fn held(&self, ob: u8) -> u64 {
        self.held
            .iter()
            .filter(|held| held.request.ob == ob)
            .count() as u64
    }

    /// The events of STARTUP are traced at the transition to RUN, which decides whether they
    /// were requests (lost) or not.
    fn untraced_since(&self) -> u64 {
        self.startup_events
            .iter()
            .map(|(at, ..)| *at)
            .min()
            .unwrap_or(u64::MAX)
    }
}
