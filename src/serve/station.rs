//! The CPU's side of `awl serve`: the cycle control point, where the clients' requests are
//! served between two cycles (one consistent state for each) and the cycle waits for the wall
//! clock; and the STOP, where requests are served until a client starts the CPU again. What
//! serves the requests (the [`Desk`]) is shared with the debugger's hold
//! ([`super::hold::Hold`]), which serves them inside a cycle while a breakpoint holds the CPU.

use std::cell::RefCell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use crate::vm::{Cpu, Mode};

use super::access::{probe as probe_one, serve_items};
use super::network::Network;
use super::online::Online;
use super::pacing::Pacer;
use super::request::{
    Client, Control, ControlError, CpuMode, CpuStatus, Protocol, Request, Sample,
};

/// How often the status is reported and a halt looked for while the CPU waits.
pub(super) const LOOK_EVERY: Duration = Duration::from_millis(100);

/// How often the network is looked at when the CPU does not wait (it runs behind the clock,
/// or less than [`RUN_AHEAD`] before it), so the connections are answered.
const POLL_EVERY: Duration = Duration::from_micros(100);

/// How far simulated time may run ahead of the clock: a cycle whose start the clock would
/// reach sooner starts at once, so short cycles (the SPEED7's take 60 µs) do not each cost a
/// wake-up of their own, and the CPU leaves the machine's cores to its clients. It is the
/// network runtime's timer resolution too.
const RUN_AHEAD: Duration = Duration::from_millis(1);

/// A start a client asked for, made once the CPU gets to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Start {
    cold: bool,
}

/// The figures the status line shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Snapshot {
    pub mode: Mode,
    pub cycle: u64,
    pub min_cycle_ns: u64,
    pub max_cycle_ns: u64,
    pub clients: usize,
    pub requests_per_second: f64,
}

/// Counts of what was served, for the summary.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Served {
    pub requests: u64,
    pub writes: u64,
    pub connections: u64,
}

/// What serves the clients' requests: the network, the online page, the counts, the debugger
/// attached.
pub struct Desk {
    network: Network,
    /// When the network last ran.
    last_poll: Instant,
    /// An answer was given that the network has not sent yet.
    answered: bool,
    read_only: bool,
    /// What the online page sees: the diagnostic buffer, the last STOP, a HOLD.
    pub online: Online,
    open_clients: usize,
    pub served: Served,
    wanted: Option<Start>,
    /// Whether the serve is to end (Ctrl-C).
    pub halted: fn() -> bool,
    /// The debugger attached through the online API (`awl dap`'s attach).
    pub debugger: Option<super::hold::Attached>,
    /// A HOLD has ended: simulated time stood still, so the pacer follows on from the CPU's
    /// clock.
    pub hold_ended: bool,
}

pub struct Station<'a> {
    pub desk: Rc<RefCell<Desk>>,
    pub pacer: Pacer,
    report: &'a mut dyn FnMut(&Snapshot),
    last_report: Instant,
    requests_at_last_report: u64,
}

impl<'a> Station<'a> {
    pub fn new(
        network: Network,
        read_only: bool,
        pacer: Pacer,
        online: Online,
        halted: fn() -> bool,
        report: &'a mut dyn FnMut(&Snapshot),
    ) -> Self {
        let desk = Desk {
            network,
            last_poll: Instant::now(),
            answered: false,
            read_only,
            online,
            open_clients: 0,
            served: Served::default(),
            wanted: None,
            halted,
            debugger: None,
            hold_ended: false,
        };
        Station {
            desk: Rc::new(RefCell::new(desk)),
            pacer,
            report,
            last_report: Instant::now(),
            requests_at_last_report: 0,
        }
    }

    /// At a cycle boundary in RUN: serves what came, then waits for the wall clock to reach
    /// the CPU's simulated time, serving what comes meanwhile. `false` leaves the run: a
    /// client's STOP or a halt (Ctrl-C).
    pub fn at_control_point(&mut self, cpu: &mut Cpu) -> bool {
        let mut desk = self.desk.borrow_mut();
        desk.online.at_control_point(cpu);
        if std::mem::take(&mut desk.hold_ended) {
            self.pacer.rebase(cpu.clock);
        }
        super::hold::keep_probe(&self.desk, &mut desk, cpu);
        let deadline = self.pacer.deadline(cpu.clock);
        loop {
            if !desk.serve_waiting(cpu) {
                return false;
            }
            let now = Instant::now();
            if now + RUN_AHEAD < deadline {
                // The network's wait may last a millisecond longer than asked: it is asked to
                // end that much before the clock, and the cycle starts at most that early.
                desk.wait_for_request(cpu, (deadline - now - RUN_AHEAD).min(LOOK_EVERY));
            } else if desk.answered || now - desk.last_poll >= POLL_EVERY {
                // The answers go out before the next cycle; what came meanwhile is served.
                desk.poll_network();
            } else {
                self.pacer.record_start(deadline, now);
                break;
            }
        }
        drop(desk);
        self.report_now_and_then(cpu);
        true
    }

    /// In STOP: serves requests until a client starts the CPU (`Some(cold)`) or a halt
    /// (`None`).
    pub fn while_stopped(&mut self, cpu: &mut Cpu) -> Option<bool> {
        loop {
            {
                let mut desk = self.desk.borrow_mut();
                if (desk.halted)() {
                    return None;
                }
                if let Some(start) = desk.wanted.take() {
                    return Some(start.cold);
                }
                desk.online.at_control_point(cpu);
                desk.wait_for_request(cpu, LOOK_EVERY);
            }
            self.report_now_and_then(cpu);
        }
    }

    fn report_now_and_then(&mut self, cpu: &mut Cpu) {
        let elapsed = self.last_report.elapsed();
        if elapsed < Duration::from_millis(250) {
            return;
        }
        let mut desk = self.desk.borrow_mut();
        desk.online.look_now_and_then(cpu);
        let requests = desk.served.requests - self.requests_at_last_report;
        (self.report)(&Snapshot {
            mode: cpu.mode,
            cycle: cpu.cycle,
            min_cycle_ns: cpu.cycle_times.min_ns,
            max_cycle_ns: cpu.cycle_times.max_ns,
            clients: desk.open_clients,
            requests_per_second: requests as f64 / elapsed.as_secs_f64(),
        });
        self.last_report = Instant::now();
        self.requests_at_last_report = desk.served.requests;
    }
}

impl Desk {
    /// Serves every request that has come; `false` when the run is to be left.
    fn serve_waiting(&mut self, cpu: &mut Cpu) -> bool {
        while let Some(request) = self.network.try_request() {
            self.serve(cpu, request);
        }
        !(self.halted)() && cpu.mode != Mode::Stop
    }

    pub(super) fn wait_for_request(&mut self, cpu: &mut Cpu, longest: Duration) {
        let request = self.network.next_request(longest);
        self.after_network_ran();
        if let Some(request) = request {
            self.serve(cpu, request);
        }
    }

    fn poll_network(&mut self) {
        self.network.poll();
        self.after_network_ran();
    }

    fn after_network_ran(&mut self) {
        self.last_poll = Instant::now();
        self.answered = false;
    }

    fn serve(&mut self, cpu: &mut Cpu, request: Request) {
        self.served.requests += 1;
        self.answered = true;
        match request {
            Request::Access {
                client,
                items,
                reply,
            } => {
                let results = serve_items(cpu, client, &items, self.read_only);
                // A client's output write does not beat a force (its input writes reach only
                // the modules, which the PII transfer then overrides).
                if !cpu.forces.is_empty() {
                    cpu.hold_forces();
                }
                self.served.writes += items
                    .iter()
                    .zip(&results)
                    .filter(|(item, result)| item.writes() && result.is_ok())
                    .count() as u64;
                // A client that left before its answer needs none.
                let _ = reply.send(results);
            }
            Request::Status { reply } => {
                let _ = reply.send(status(cpu, self.read_only, self.online.held));
            }
            Request::Control {
                client,
                command,
                reply,
            } => {
                let _ = reply.send(self.control(cpu, client, command));
            }
            Request::Sample { probes, reply } => {
                let _ = reply.send(sample(cpu, &probes, self.online.held));
            }
            Request::Debug { message, reply } => {
                let _ = reply.send(super::hold::debug(self, cpu, message.as_deref()));
            }
            Request::Online { client, ask } => {
                self.online.serve(cpu, client, ask, self.open_clients);
            }
            Request::Connection { open, .. } => {
                if open {
                    self.open_clients += 1;
                    self.served.connections += 1;
                } else {
                    self.open_clients = self.open_clients.saturating_sub(1);
                }
            }
        }
    }

    /// A mode change a client asks for: the STOP at once (requests are served between two
    /// cycles), a start once the CPU gets back to its STOP loop.
    fn control(
        &mut self,
        cpu: &mut Cpu,
        client: Client,
        command: Control,
    ) -> Result<(), ControlError> {
        if self.read_only {
            return Err(ControlError::ReadOnly);
        }
        let stopped = cpu.mode == Mode::Stop;
        match command {
            Control::Stop => {
                // The trace names the online page's STOP apart from an HMI's.
                let cause = match client.protocol {
                    Protocol::Http | Protocol::Terminal => "online",
                    Protocol::S7 | Protocol::Modbus | Protocol::OpcUa => "client",
                };
                if !stopped {
                    let text = format!("STOP, asked for by {}", client.name());
                    self.online.mode_changed(cpu, text);
                }
                cpu.stop_from_outside(cause);
                self.wanted = None;
                Ok(())
            }
            Control::HotStart | Control::ColdStart if !stopped || self.wanted.is_some() => {
                Err(ControlError::AlreadyRunning)
            }
            Control::HotStart | Control::ColdStart => {
                let cold = command == Control::ColdStart;
                self.wanted = Some(Start { cold });
                Ok(())
            }
        }
    }
}

/// The operands' values and the CPU's figures at this control point.
fn sample(cpu: &mut Cpu, probes: &[super::request::Probe], held: bool) -> Sample {
    Sample {
        readings: probes.iter().map(|probe| probe_one(cpu, *probe)).collect(),
        mode: mode(cpu, held),
        cycles: cpu.cycle,
        cycle_time_ms: cpu.cycle_times.last_ns as f64 / 1e6,
        clock_ms: cpu.clock_ms() as i64,
    }
}

/// The mode a client sees: HOLD while a debugger holds the CPU at a breakpoint.
fn mode(cpu: &Cpu, held: bool) -> CpuMode {
    match cpu.mode {
        Mode::Run if held => CpuMode::Hold,
        Mode::Run => CpuMode::Run,
        Mode::Stop => CpuMode::Stop,
        Mode::Startup => CpuMode::Startup,
    }
}

/// What the CPU reports of itself.
fn status(cpu: &Cpu, read_only: bool, held: bool) -> CpuStatus {
    CpuStatus {
        mode: mode(cpu, held),
        profile: cpu.profile.name,
        order_code: super::identity::order_code(cpu.profile),
        clock_ms: cpu.clock_ms() as i64,
        cycles: cpu.cycle,
        read_only,
    }
}
