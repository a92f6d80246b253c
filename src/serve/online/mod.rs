//! The CPU's side of the online page (`awl serve --http`): what the page asks, served at the
//! cycle control point from the one CPU, with the command line's operand resolver
//! ([`runner::watch_target`]), its value notation ([`watch::formatted`]) and the debugger's
//! write ([`debug::write`]); and the diagnostic buffer the page shows.

pub mod diagnostics;
pub mod error;

use crate::mnemonics::MnemonicSet;
use crate::runner;
use crate::scenario::operand::Target;
use crate::state::watch::{self, Format};
use crate::vm::Cpu;
use crate::vm::stop::Stop;
use crate::{debug, scenario};

use super::request::{Ask, Client, CpuView, CycleTimesView, Refusal, Refused, StopView, Value};
use diagnostics::Diagnostics;
use error::OnlineError;

/// What the online page sees of the CPU besides its memory.
pub struct Online {
    /// The set the program's operands are written in.
    mnemonics: MnemonicSet,
    read_only: bool,
    pub diagnostics: Diagnostics,
    /// The program's STOP, while the CPU stays in STOP.
    stop: Option<StopView>,
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
        }
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
            Ask::Diagnostics { reply } => {
                let _ = reply.send(self.diagnostics.entries());
            }
        }
    }

    fn cpu_view(&self, cpu: &Cpu, clients: usize) -> CpuView {
        let times = &cpu.cycle_times;
        CpuView {
            mode: cpu.mode.name(),
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
            forces: 0,
            read_only: self.read_only,
            stop: self.stop.clone(),
        }
    }

    /// An operand as the command line takes it.
    fn target(&self, cpu: &Cpu, operand: &str) -> Result<Target, Refusal> {
        runner::watch_target(operand, self.mnemonics, &cpu.program)
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
                let target = self.target(cpu, operand)?;
                if let Some(why) = format.and_then(|format| format.misfit(target)) {
                    let format = format.map_or("", |format| format.name(cpu.program.s7.step7));
                    return Err(OnlineError::FormatMisfit {
                        operand: operand.clone(),
                        format,
                        why,
                    }
                    .refusal());
                }
                Ok(value(cpu, operand, target, *format))
            })
            .collect()
    }

    /// Writes a value once, at this control point.
    fn modify(
        &mut self,
        cpu: &mut Cpu,
        client: Client,
        operand: &str,
        value: &toml::Value,
    ) -> Result<Value, Refusal> {
        if self.read_only {
            return Err(OnlineError::ReadOnly.refusal());
        }
        let target = self.target(cpu, operand)?;
        let (written, wanted) =
            scenario::set_value(target, value, operand, &cpu.program, (0, 0).into())
                .map_err(|error| Refusal::of(Refused::BadRequest, &error))?;
        debug::write(cpu, target, wanted.raw(), operand).map_err(|reason| {
            OnlineError::Modify {
                operand: operand.to_string(),
                reason,
            }
            .refusal()
        })?;
        let by = format!("{} #{}", client.protocol.name(), client.number);
        self.diagnostics
            .record(cpu, "modify", format!("{operand} := {written} ({by})"));
        Ok(Value {
            format: None,
            ..value_of(cpu, operand, target)
        })
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

    /// Now and then (a few times a second): what the engine counted since the last look.
    pub fn look_now_and_then(&mut self, cpu: &Cpu) {
        self.diagnostics.look_at_interrupts(cpu);
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
