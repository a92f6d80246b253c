//! A debugger attached to the served CPU (`awl dap`'s attach, over `POST /api/debug`): the
//! debug adapter's translator ([`crate::dap::Adapter`]) answers its messages from the one CPU,
//! and the engine's breakpoints pause the CPU in HOLD, as an S7 CPU's test operation does: no
//! operation runs, the outputs keep their values, simulated time stands still, and the station
//! goes on serving every client (S7, Modbus, the online page, the debugger) until the
//! debugger lets the CPU go on. The probe sits on the CPU only while a debugger is attached.

use std::cell::RefCell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

use crate::compiler::Op;
use crate::dap::wire::{self, Incoming};
use crate::dap::{Adapter, Told};
use crate::vm::probe::{Flow, Probe};
use crate::vm::stop::Stop;
use crate::vm::{Cpu, Mode};

use super::station::{Desk, LOOK_EVERY};

/// A debugger that has not been heard from for this long (its adapter was killed) is detached,
/// so the CPU does not stay held for ever. `awl dap` asks for events many times a second.
const LEASE: Duration = Duration::from_secs(5);

/// The debugger attached: its translator, and whether it let a held CPU go on.
pub struct Attached {
    adapter: Adapter,
    last_heard: Instant,
    /// `continue` or a step was asked while the CPU is held.
    resumed: bool,
}

/// The probe of an attached debugger; it shares the station's [`Desk`].
pub struct Hold(Rc<RefCell<Desk>>);

/// At a control point: a debugger attached since gets its probe on the CPU (again, if program
/// status of the online page used the probe meanwhile); one not heard from is detached.
pub fn keep_probe(shared: &Rc<RefCell<Desk>>, desk: &mut Desk, cpu: &mut Cpu) {
    if desk
        .debugger
        .as_ref()
        .is_some_and(|attached| attached.last_heard.elapsed() > LEASE)
    {
        detach(desk, cpu);
    }
    if desk.debugger.is_some() && cpu.probe.is_none() {
        cpu.probe = Some(Box::new(Hold(Rc::clone(shared))));
    }
}

fn detach(desk: &mut Desk, cpu: &mut Cpu) {
    desk.debugger = None;
    cpu.probe = None;
}

/// Answers a debugger's message (`None`: only the events waiting): the messages to send it.
pub fn debug(desk: &mut Desk, cpu: &mut Cpu, message: Option<&[u8]>) -> Vec<Value> {
    match message.map(wire::parse) {
        None => {}
        Some(Incoming::Request(request)) if request.command == "attach" => {
            return attach(desk, cpu, request.seq);
        }
        Some(message) => {
            let held = desk.online.held;
            let Some(attached) = desk.debugger.as_mut() else {
                return vec![not_attached(&message)];
            };
            match attached.adapter.served_message(cpu, held, message) {
                Told::GoOn => attached.resumed = true,
                Told::Stay => {}
                Told::Detach => {
                    let mut answer = attached.adapter.take_queued();
                    detach(desk, cpu);
                    answer.push(json!({ "type": "event", "event": "terminated", "body": {} }));
                    return answer;
                }
            }
        }
    }
    events(desk)
}

/// The events waiting for the debugger; hearing from it renews its lease.
fn events(desk: &mut Desk) -> Vec<Value> {
    match desk.debugger.as_mut() {
        Some(attached) => {
            attached.last_heard = Instant::now();
            attached.adapter.take_queued()
        }
        None => Vec::new(),
    }
}

fn attach(desk: &mut Desk, cpu: &Cpu, seq: i64) -> Vec<Value> {
    if desk.debugger.is_some() {
        return vec![refusal(
            seq,
            "attach",
            "another debugger is attached to this CPU; detach it first",
        )];
    }
    let mut adapter = Adapter::served(desk.online.mnemonics());
    adapter.attached(seq, cpu);
    desk.debugger = Some(Attached {
        adapter,
        last_heard: Instant::now(),
        resumed: false,
    });
    events(desk)
}

fn not_attached(message: &Incoming) -> Value {
    match message {
        Incoming::Request(request) => refusal(
            request.seq,
            &request.command,
            "no debugger is attached to this CPU: send `attach` first",
        ),
        Incoming::Malformed { seq, reason } => refusal(*seq, "", reason),
    }
}

fn refusal(seq: i64, command: &str, message: &str) -> Value {
    json!({
        "type": "response", "request_seq": seq, "success": false, "command": command,
        "message": message, "body": { "error": { "id": 1, "format": message, "showUser": true } },
    })
}

impl Hold {
    /// Holds the CPU until the debugger lets it go on, detaches, a client stops the CPU or the
    /// serve ends (`false`).
    fn hold(&self, cpu: &mut Cpu, why: &str) -> bool {
        let mut desk = self.0.borrow_mut();
        desk.online.held = true;
        desk.online.mode_changed(cpu, format!("HOLD: {why}"));
        let going_on = loop {
            if (desk.halted)() {
                break false;
            }
            desk.wait_for_request(cpu, LOOK_EVERY);
            if cpu.mode == Mode::Stop {
                break true;
            }
            let Some(attached) = desk.debugger.as_mut() else {
                break true;
            };
            if std::mem::take(&mut attached.resumed) {
                break true;
            }
            if attached.last_heard.elapsed() > LEASE {
                detach(&mut desk, cpu);
                break true;
            }
        };
        desk.online.held = false;
        desk.hold_ended = true;
        if cpu.mode == Mode::Run {
            desk.online
                .mode_changed(cpu, "RUN: the debugger let the CPU go on".into());
        }
        going_on
    }

    fn with_adapter<T>(&self, idle: T, look: impl FnOnce(&mut Adapter) -> T) -> T {
        match self.0.borrow_mut().debugger.as_mut() {
            Some(attached) => look(&mut attached.adapter),
            None => idle,
        }
    }
}

impl Probe for Hold {
    fn before(&mut self, cpu: &mut Cpu) -> Flow {
        let pause = self.with_adapter(None, |adapter| {
            let pause = adapter.pause_here(cpu)?;
            adapter.stopped(cpu, &pause);
            Some(pause)
        });
        match pause {
            Some(pause) if !self.hold(cpu, &pause.to_string()) => Flow::Halt,
            _ => Flow::Go,
        }
    }

    fn after(&mut self, _cpu: &Cpu, _block: u16, _pc: u32, _op: Op) -> Flow {
        Flow::Go
    }

    fn requested(&mut self, cpu: &Cpu, ob: u8, at_ns: u64) {
        self.with_adapter((), |adapter| adapter.engine.requested(cpu, ob, at_ns));
    }

    fn serviced(&mut self, cpu: &Cpu, ob: u8) {
        self.with_adapter((), |adapter| adapter.engine.serviced(cpu, ob));
    }

    fn stopping(&mut self, cpu: &mut Cpu, stop: &Stop) {
        if self.with_adapter(false, |adapter| adapter.stop_reached(cpu, stop)) {
            self.hold(cpu, &format!("before STOP {}", stop.cause.code()));
        }
    }
}
