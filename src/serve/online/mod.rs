//! The CPU's side of the online page (`awl serve --http`): what the page asks, served at the
//! cycle control point from the one CPU, with the command line's operand resolver
//! ([`runner::watch_target`]), its value notation ([`watch::formatted`]) and the debugger's
//! write ([`debug::write`]); and the diagnostic buffer the page shows.

pub mod diagnostics;
pub mod error;
pub mod forces;
pub mod status;
pub mod timeline;

use crate::mnemonics::MnemonicSet;
use crate::runner;
use crate::scenario::operand::Target;
use crate::state::watch::{self, Format};
use crate::vm::Cpu;
use crate::vm::stop::Stop;
use crate::{debug, scenario};

use super::request::{Ask, Client, CpuView, CycleTimesView, Refusal, Refused, StopView, Value};
use crate::trace::Event;
use diagnostics::Diagnostics;
use error::OnlineError;
use forces::{ForceTable, Held};
use status::StatusWatch;
use timeline::LiveTimeline;

/// What the online page sees of the CPU besides its memory.
pub struct Online {
    /// The set the program's operands are written in.
    mnemonics: MnemonicSet,
    read_only: bool,
    pub diagnostics: Diagnostics,
    /// The program's STOP, while the CPU stays in STOP.
    stop: Option<StopView>,
    forces: ForceTable,
    /// A debugger's breakpoint holds the CPU (HOLD).
    pub held: bool,
    /// Program status of the block the page watches.
    status: Option<StatusWatch>,
    /// The live timeline's recording, while the page watches it.
    timeline: Option<LiveTimeline>,
}

fn ms(ns: u64) -> f64 {
    ns as f64 / 1e6
}

impl Online {
    pub fn new(mnemonics: MnemonicSet, read_only: bool) -> Self {
        Online {
            mnemonics,
            read_only,
            diagnostics: Diagnostics::default(),
            stop: None,
            forces: ForceTable::default(),
            held: false,
            status: None,
            timeline: None,
        }
    }

    /// The set the program's operands are written in.
    pub fn mnemonics(&self) -> MnemonicSet {
        self.mnemonics
    }

    /// Serves one request of the page; `clients` are the connections open.
    pub fn serve(&mut self, cpu: &mut Cpu, client: Client, ask: Ask, clients: usize) {
        // A client that left before its answer needs none.
        match ask {
            Ask::Cpu { reply } => {
                let _ = reply.send(self.cpu_view(cpu, clients));
            }
            Ask::Values { watched, reply } => {
                let _ = reply.send(self.values(cpu, &watched));
            }
            Ask::Modify {
                operand,
                value,
                reply,
            } => {
                let _ = reply.send(self.modify(cpu, client, &operand, &value));
            }
            Ask::Force {
                operand,
                value,
                reply,
            } => {
                let _ = reply.send(self.force(cpu, client, &operand, &value));
            }
            Ask::Unforce { operand, reply } => {
                let _ = reply.send(self.unforce(cpu, client, operand.as_deref()));
            }
            Ask::Forces { reply } => {
                let forced = self.forces.held().iter();
                let _ = reply.send(
                    forced
                        .map(|held| answer(cpu, &held.operand, held.target))
                        .collect(),
                );
            }
            Ask::ProgramStatus {
                block,
                level,
                reply,
            } => StatusWatch::ask(&mut self.status, cpu, (block, level), reply),
            Ask::Diagnostics { reply } => {
                let _ = reply.send(self.diagnostics.entries());
            }
            Ask::Snapshot { reply } => {
                let _ = reply.send(crate::retain::Snapshot::of(cpu).encode());
            }
            Ask::Timeline { seconds, reply } => {
                LiveTimeline::ask(&mut self.timeline, cpu, seconds, reply);
            }
        }
    }

    fn cpu_view(&self, cpu: &Cpu, clients: usize) -> CpuView {
        let times = &cpu.cycle_times;
        CpuView {
            mode: if self.held { "HOLD" } else { cpu.mode.name() },
            cycle: cpu.cycle,
            simulated_ms: ms(cpu.clock),
            cycle_time_ms: CycleTimesView {
                last: ms(times.last_ns),
                min: ms(times.min_ns),
                max: ms(times.max_ns),
                mean: ms(times.mean_ns().unwrap_or(0)),
            },
            profile: cpu.profile.name,
            dialect: if cpu.program.s7.step7 { "s7" } else { "s5" },
            mnemonics: match self.mnemonics {
                MnemonicSet::English => "en",
                MnemonicSet::German => "de",
            },
            clients,
            forces: self.forces.held().len(),
            read_only: self.read_only,
            stop: self.stop.clone(),
        }
    }

    /// An operand as the command line takes it.
    fn target(&self, cpu: &Cpu, operand: &str) -> Result<Target, Refusal> {
        self.row(cpu, operand, None)
    }

    /// A watch row's operand, which fits its format, as `--watch-file` takes it.
    fn row(&self, cpu: &Cpu, operand: &str, format: Option<Format>) -> Result<Target, Refusal> {
        runner::watch_row(operand, format, self.mnemonics, &cpu.program)
            .map_err(|error| Refusal::of(Refused::BadRequest, &error))
    }

    fn values(
        &self,
        cpu: &Cpu,
        watched: &[(String, Option<Format>)],
    ) -> Result<Vec<Value>, Refusal> {
        watched
            .iter()
            .map(|(operand, format)| {
                let target = self.row(cpu, operand, *format)?;
                Ok(value(cpu, operand, target, *format))
            })
            .collect()
    }

    /// A modify's or force's operand and value, as a scenario's `set` takes them: the target,
    /// the value as written and its bits; refused on a read-only server.
    fn change(
        &self,
        cpu: &Cpu,
        operand: &str,
        value: &toml::Value,
    ) -> Result<(Target, String, u32), Refusal> {
        if self.read_only {
            return Err(OnlineError::ReadOnly.refusal());
        }
        let target = self.target(cpu, operand)?;
        let (written, wanted) =
            scenario::set_value(target, value, operand, &cpu.program, (0, 0).into())
                .map_err(|error| Refusal::of(Refused::BadRequest, &error))?;
        Ok((target, written, wanted.raw()))
    }

    /// Writes a value once, at this control point.
    fn modify(
        &mut self,
        cpu: &mut Cpu,
        client: Client,
        operand: &str,
        value: &toml::Value,
    ) -> Result<Value, Refusal> {
        let (target, written, raw) = self.change(cpu, operand, value)?;
        debug::write(cpu, target, raw, operand).map_err(|reason| {
            OnlineError::Modify {
                operand: operand.to_string(),
                reason,
            }
            .refusal()
        })?;
        // A modify of a forced input or output does not end its force.
        if !cpu.forces.is_empty() {
            cpu.hold_forces();
        }
        let by = client.name();
        emit(cpu, || Event::Modify {
            client: by.clone(),
            operand: operand.to_string(),
            value: written.clone(),
        });
        self.diagnostics
            .record(cpu, "modify", format!("{operand} := {written} ({by})"));
        Ok(answer(cpu, operand, target))
    }

    /// Holds an input or output at a value from now until it is unforced.
    fn force(
        &mut self,
        cpu: &mut Cpu,
        client: Client,
        operand: &str,
        value: &toml::Value,
    ) -> Result<Value, Refusal> {
        let (target, written, raw) = self.change(cpu, operand, value)?;
        if forces::forced_bytes(target, raw, cpu.program.layout).is_none() {
            return Err(OnlineError::NotForceable {
                operand: operand.to_string(),
            }
            .refusal());
        }
        let held = Held {
            operand: operand.to_string(),
            target,
            raw,
        };
        self.forces.set(cpu, held);
        let by = client.name();
        emit(cpu, || Event::Force {
            client: by.clone(),
            operand: operand.to_string(),
            value: written.clone(),
        });
        let text = format!("{operand} forced to {written} ({by})");
        self.diagnostics.record(cpu, "force_set", text);
        Ok(answer(cpu, operand, target))
    }

    /// Ends the force of `operand`, or of every operand; the operands unforced.
    fn unforce(
        &mut self,
        cpu: &mut Cpu,
        client: Client,
        operand: Option<&str>,
    ) -> Result<Vec<String>, Refusal> {
        if self.read_only {
            return Err(OnlineError::ReadOnly.refusal());
        }
        let ended = match operand {
            None => self.forces.clear(cpu),
            Some(operand) => {
                let target = self.target(cpu, operand)?;
                let held = self.forces.remove(cpu, target).ok_or_else(|| {
                    let forced: Vec<&str> = self
                        .forces
                        .held()
                        .iter()
                        .map(|held| held.operand.as_str())
                        .collect();
                    OnlineError::NotForced {
                        operand: operand.to_string(),
                        forced: match forced.is_empty() {
                            true => "nothing is forced".to_string(),
                            false => format!("forced are: {}", forced.join(", ")),
                        },
                    }
                    .refusal()
                })?;
                vec![held]
            }
        };
        let by = client.name();
        for held in &ended {
            emit(cpu, || Event::Unforce {
                client: by.clone(),
                operand: held.operand.clone(),
            });
            let text = format!("{} unforced ({by})", held.operand);
            self.diagnostics.record(cpu, "force_cleared", text);
        }
        Ok(ended.into_iter().map(|held| held.operand).collect())
    }

    /// The program went to STOP: the page shows the report until the CPU runs again.
    pub fn stopped(&mut self, cpu: &Cpu, stop: &Stop) {
        let report = runner::cpu_stop_report(cpu, stop);
        let view = StopView {
            cause: stop.cause.code(),
            block: stop.block.map(|block| cpu.block_id(block).to_string()),
            line: stop.block.map(|block| cpu.line_of(block, stop.pc)),
            report: crate::diagnostics::render_plain(&report),
        };
        let place = match (&view.block, view.line) {
            (Some(block), Some(line)) => format!(" in {block} line {line}"),
            _ => " between cycles".to_string(),
        };
        self.diagnostics.record(
            cpu,
            "stop",
            format!("STOP: {}{place}: {report}", view.cause),
        );
        self.stop = Some(view);
    }

    /// A mode change from outside: a client's STOP, or a restart.
    pub fn mode_changed(&mut self, cpu: &Cpu, text: String) {
        self.stop = None;
        self.diagnostics.record(cpu, "mode", text);
    }

    /// At every control point, and now and then in STOP: program status looks whether its
    /// recording is done. One comparison when nobody watches.
    pub fn at_control_point(&mut self, cpu: &mut Cpu) {
        if let Some(status) = &mut self.status {
            status.look(cpu);
        }
        if let Some(timeline) = &mut self.timeline {
            timeline.look(cpu);
        }
    }

    /// The serve ends: the live timeline's tracer output and a program status recorder leave
    /// the CPU, so the run's summary and trace are those of the run alone.
    pub fn leave(&mut self, cpu: &mut Cpu) {
        if self.timeline.take().is_some() {
            timeline::stop_recording(cpu);
        }
        if self.status.take().is_some() {
            cpu.probe = None;
        }
    }

    /// Now and then (a few times a second): what the engine counted since the last look.
    pub fn look_now_and_then(&mut self, cpu: &mut Cpu) {
        self.diagnostics.look_at_interrupts(cpu);
        LiveTimeline::look_now_and_then(&mut self.timeline, cpu);
    }
}

/// `operand`'s value in its format, or the dialect's own.
fn value(cpu: &Cpu, operand: &str, target: Target, format: Option<Format>) -> Value {
    let shown = format.unwrap_or_else(|| Format::natural(target, cpu.program.s7.step7));
    Value {
        operand: operand.to_string(),
        format: Some(shown.name(cpu.program.s7.step7)),
        value: watch::formatted(cpu, target, format),
        raw: watch::raw(cpu, target),
    }
}

/// `operand`'s value in the dialect's own notation.
fn value_of(cpu: &Cpu, operand: &str, target: Target) -> Value {
    value(cpu, operand, target, None)
}

/// The answer to a modify or a force: the operand's value now, without a format.
fn answer(cpu: &Cpu, operand: &str, target: Target) -> Value {
    Value {
        format: None,
        ..value_of(cpu, operand, target)
    }
}

/// Traces the event `make` builds, when a trace is written.
fn emit(cpu: &mut Cpu, make: impl FnOnce() -> Event) {
    if cpu.tracer.enabled {
        let event = make();
        cpu.tracer.emit(cpu.clock, event);
    }
}
