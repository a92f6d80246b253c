//! Live mode, like a PLC trainer case: the program runs a slice of simulated time at a time
//! (the page paces the slices against the wall clock), its inputs are switches the user
//! flips, its outputs lamps, and interrupt OBs are requested by hand. The timeline shows the
//! last stretch of simulated time.

use std::cell::RefCell;
use std::rc::Rc;

use serde::Serialize;

use crate::compiler::bytecode::ImageBit;
use crate::diagnostics::render_plain;
use crate::mnemonics::MnemonicSet;
use crate::runner::cpu_stop_report;
use crate::timeline::Recorder;
use crate::trace::{self, Event, Sink, TraceFilter, format_ms};
use crate::vm::Cpu;
use crate::vm::cycle::RunLimit;
use crate::vm::stop::Stop;

use super::{Outcome, Place, Request};

/// An input or output bit of the program, with its symbol and its value now.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct IoBit {
    /// As the program writes it: `I 0.1` (`E 0.1` in German mnemonics).
    pub operand: String,
    /// Its name in the assignment list, if there is one.
    pub name: Option<String>,
    pub value: bool,
}

#[derive(Debug, Clone, Serialize)]
pub struct LiveView {
    pub clock: String,
    pub cycles: u64,
    pub mode: &'static str,
    pub inputs: Vec<IoBit>,
    pub outputs: Vec<IoBit>,
    /// The interrupt OBs the program has, to request by hand.
    pub interrupt_obs: Vec<u8>,
    /// The timeline of the last stretch of simulated time (SVG).
    pub timeline: String,
    pub stop: Option<String>,
    pub stop_at: Option<Place>,
}

/// The run's events since a cycle start (so every bar the picture shows has its start).
#[derive(Clone, Default)]
struct Recent(Rc<RefCell<Vec<(u64, Event)>>>);

impl Sink for Recent {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        self.0.borrow_mut().push((t_ns, event.clone()));
        Ok(())
    }

    fn finish(&mut self, _end_ns: u64) -> std::io::Result<()> {
        Ok(())
    }
}

impl Recent {
    /// Forgets the events before the last cycle start at or before `t_ns`.
    fn forget_before(&self, t_ns: u64) {
        let mut events = self.0.borrow_mut();
        let last_start = events
            .iter()
            .rposition(|(at, event)| *at <= t_ns && matches!(event, Event::CycleStart { .. }));
        if let Some(index) = last_start {
            events.drain(..index);
        }
    }
}

pub struct Live {
    cpu: Cpu,
    mnemonics: MnemonicSet,
    recent: Recent,
    inputs: Vec<ImageBit>,
    outputs: Vec<ImageBit>,
    stop: Option<Stop>,
}

impl Live {
    /// The run set up (in STOP until the first slice), or why it cannot run.
    pub fn start(request: &Request) -> Result<Live, Box<Outcome>> {
        let mut prepared = request.prepare()?;
        let recent = Recent::default();
        prepared
            .cpu
            .tracer
            .add("live", Box::new(recent.clone()), TraceFilter::all());
        let (inputs, outputs) = io_bits(&prepared.cpu);
        Ok(Live {
            cpu: prepared.cpu,
            mnemonics: prepared.mnemonics,
            recent,
            inputs,
            outputs,
            stop: None,
        })
    }

    /// Runs on for `ns` of simulated time (to the cycle end after it), unless in STOP; the
    /// events kept reach back at least `keep_ns` before the end.
    pub fn advance(&mut self, ns: u64, keep_ns: u64) {
        if self.stop.is_some() {
            return;
        }
        let until = self.cpu.clock.saturating_add(ns.max(1));
        let outcome = self
            .cpu
            .run_watched(RunLimit::Duration(until), &mut |_| true);
        if outcome.stop.is_some() {
            self.cpu.tracer.finish(self.cpu.clock);
            self.stop = outcome.stop;
        }
        self.recent
            .forget_before(self.cpu.clock.saturating_sub(keep_ns));
    }

    /// Sets an input as a switch does (the debugger's `set`): `I 0.1`, `-START`.
    pub fn set_input(&mut self, operand: &str, on: bool) -> Result<(), String> {
        crate::debug::force(&mut self.cpu, operand, i64::from(on), self.mnemonics).map(|_| ())
    }

    /// Requests interrupt OB `ob` now; whether the request is pending.
    pub fn request(&mut self, ob: u8) -> bool {
        self.stop.is_none() && self.cpu.fire(ob)
    }

    /// What the trainer case shows now; the timeline covers the last `window_ns`.
    pub fn view(&self, window_ns: u64) -> LiveView {
        let cpu = &self.cpu;
        let now = cpu.clock;
        let from = now.saturating_sub(window_ns);
        let caption = format!(
            "live — {}, the last {} ms",
            cpu.profile.name,
            window_ns as f64 / 1e6
        );
        let window = TraceFilter::all().window(Some(from), Some(now.max(from + 1)));
        let mut recorder = Recorder::new(window, trace::levels(cpu.profile, &cpu.program), caption);
        for (at, event) in self.recent.0.borrow().iter() {
            recorder.record(*at, event);
        }
        let stop = self.stop.as_ref();
        LiveView {
            clock: format_ms(now),
            cycles: cpu.cycle,
            mode: cpu.mode.name(),
            inputs: self.bits(&self.inputs),
            outputs: self.bits(&self.outputs),
            interrupt_obs: cpu
                .profile
                .interrupt_obs
                .iter()
                .map(|entry| entry.ob)
                .filter(|ob| cpu.program.ob(*ob).is_some())
                .collect(),
            timeline: recorder.svg(now),
            stop: stop.map(|stop| render_plain(&cpu_stop_report(cpu, stop))),
            stop_at: stop.and_then(|stop| Place::of_op(cpu, stop.block?, stop.pc)),
        }
    }

    fn bits(&self, bits: &[ImageBit]) -> Vec<IoBit> {
        let layout = self.cpu.program.layout;
        bits.iter()
            .map(|bit| {
                let (letter, byte, module) = if bit.byte >= layout.output_base() {
                    let letter = match self.mnemonics {
                        MnemonicSet::German => "A",
                        MnemonicSet::English => "Q",
                    };
                    (letter, bit.byte - layout.output_base(), &self.cpu.outputs)
                } else {
                    let letter = match self.mnemonics {
                        MnemonicSet::German => "E",
                        MnemonicSet::English => "I",
                    };
                    (letter, bit.byte, &self.cpu.inputs)
                };
                let operand = format!("{letter} {byte}.{}", bit.bit);
                let value = module
                    .get(usize::from(byte))
                    .is_some_and(|value| value & (1 << bit.bit) != 0);
                IoBit {
                    name: self
                        .cpu
                        .program
                        .symbols
                        .name_of(&operand)
                        .map(str::to_string),
                    operand,
                    value,
                }
            })
            .collect()
    }
}

/// The input bits the program reads and the output bits it reads or writes, in address order.
fn io_bits(cpu: &Cpu) -> (Vec<ImageBit>, Vec<ImageBit>) {
    let layout = cpu.program.layout;
    let mut bits: Vec<ImageBit> = cpu
        .program
        .blocks
        .iter()
        .flat_map(|block| block.code.iter())
        .filter_map(|op| op.image_bit())
        .filter(|bit| bit.byte < layout.flag_base())
        .collect();
    bits.sort_by_key(|bit| (bit.byte, bit.bit));
    bits.dedup();
    bits.into_iter()
        .partition(|bit| bit.byte < layout.output_base())
}
