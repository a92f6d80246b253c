//! The trace: one event per mode change, cycle, block change and interrupt, on simulated time.
//! `jsonl` writes one JSON object per line (stable field names); `text` writes an indented
//! timeline a person can follow. Events come out in time order: the tracer holds them back
//! until the CPU has taken in everything due by then (a request is only noticed at the next
//! point, after the block changes it came before).

use std::io::Write;

use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceFormat {
    Jsonl,
    Text,
}

/// The trace events; `programs/README.md` documents every field. Block names are written
/// `"PB 3"`.
#[derive(Debug, Clone, Serialize, PartialEq)]
#[serde(tag = "ev", rename_all = "snake_case")]
pub enum Event {
    Mode {
        from: &'static str,
        to: &'static str,
        #[serde(skip_serializing_if = "Option::is_none")]
        cause: Option<&'static str>,
    },
    CycleStart {
        cycle: u64,
    },
    CycleEnd {
        cycle: u64,
        cycle_time_ns: u64,
    },
    BlockCall {
        from: String,
        to: String,
        depth: usize,
    },
    BlockEnd {
        block: String,
        depth: usize,
    },
    IrqRequest {
        id: u64,
        ob: u8,
        #[serde(skip_serializing_if = "Option::is_none")]
        module: Option<u16>,
        #[serde(skip_serializing_if = "Option::is_none")]
        channel: Option<u16>,
        /// The block running when the request came.
        #[serde(skip_serializing_if = "Option::is_none")]
        block: Option<String>,
        /// Its source line, where it can be told (operation points, or straight-line code).
        #[serde(skip_serializing_if = "Option::is_none")]
        line: Option<u32>,
        /// The operating system's work it came in, when no block ran.
        #[serde(skip_serializing_if = "Option::is_none")]
        during: Option<&'static str>,
    },
    IrqService {
        id: u64,
        ob: u8,
        latency_ns: u64,
        point: &'static str,
        /// The block of the interrupt point: the one that ended, was called, or ran the operation.
        #[serde(skip_serializing_if = "Option::is_none")]
        block: Option<String>,
        /// Why it waited longer than the response bound: `priority`, `disabled`, `startup`.
        #[serde(skip_serializing_if = "Option::is_none")]
        waited: Option<&'static str>,
    },
    IrqEnd {
        id: u64,
        ob: u8,
    },
    IrqLost {
        id: u64,
        ob: u8,
        reason: String,
    },
    IrqIgnored {
        id: u64,
        ob: u8,
        reason: String,
    },
    DataCycle {
        kind: &'static str,
        /// `input` (read into an image) or `output` (written to the modules).
        direction: &'static str,
        duration_ns: u64,
    },
    /// The operating system's time at the cycle end.
    OsTime {
        duration_ns: u64,
    },
    /// A module's hardware event that is no request (SPEED7: in STARTUP).
    ModuleEvent {
        module: u16,
        channel: u16,
        ob: u8,
        reason: &'static str,
    },
    Stop {
        cause: &'static str,
        block: String,
        line: u32,
    },
    /// A row of the watch table: the watched operands' values at a cycle boundary.
    Watch {
        cycle: u64,
        values: crate::state::watch::WatchValues,
    },
}

#[derive(Serialize)]
struct Record<'a> {
    t_ns: u64,
    #[serde(flatten)]
    event: &'a Event,
}

/// Width of the text timeline's time column: aligned up to 999 s (`999999.999999 ms`).
const TIME_WIDTH: usize = 16;

/// Writes events when a trace was asked for; `enabled` is the one flag the loop tests.
pub struct Tracer {
    pub enabled: bool,
    format: TraceFormat,
    out: Option<Box<dyn Write>>,
    /// Events not yet written: (time, order of arrival, indent, event).
    held: Vec<(u64, u64, usize, Event)>,
    arrivals: u64,
    error: Option<std::io::Error>,
}

impl Tracer {
    pub fn off() -> Self {
        Tracer {
            enabled: false,
            format: TraceFormat::Jsonl,
            out: None,
            held: Vec::new(),
            arrivals: 0,
            error: None,
        }
    }

    pub fn new(format: TraceFormat, out: Box<dyn Write>) -> Self {
        Tracer {
            enabled: true,
            format,
            out: Some(out),
            held: Vec::new(),
            arrivals: 0,
            error: None,
        }
    }

    /// Records an event at simulated time `t_ns`; `indent` is the nesting for the text
    /// timeline. It is written by the next [`Tracer::settle`] that reaches its time.
    pub fn emit(&mut self, t_ns: u64, indent: usize, event: Event) {
        if self.out.is_some() {
            self.arrivals += 1;
            self.held.push((t_ns, self.arrivals, indent, event));
        }
    }

    /// Writes, in time order (events of one time in the order they came), every event up to
    /// `t_ns`: the caller has taken in everything due by then.
    pub fn settle(&mut self, t_ns: u64) {
        if self.held.is_empty() {
            return;
        }
        self.held.sort_by_key(|(t, arrival, _, _)| (*t, *arrival));
        let ready = self.held.partition_point(|(t, _, _, _)| *t <= t_ns);
        let held = std::mem::take(&mut self.held);
        let mut rest = held.into_iter();
        for (t, _, indent, event) in rest.by_ref().take(ready) {
            self.write(t, indent, &event);
        }
        self.held = rest.collect();
    }

    fn write(&mut self, t_ns: u64, indent: usize, event: &Event) {
        let Some(out) = self.out.as_mut() else { return };
        let result = match self.format {
            TraceFormat::Jsonl => serde_json::to_writer(&mut *out, &Record { t_ns, event })
                .map_err(std::io::Error::other)
                .and_then(|()| out.write_all(b"\n")),
            TraceFormat::Text => writeln!(
                out,
                "{:>TIME_WIDTH$}  {}{}",
                format_ms(t_ns),
                "  ".repeat(indent),
                text(event)
            ),
        };
        if let Err(error) = result {
            self.error.get_or_insert(error);
            self.enabled = false;
            self.out = None;
            self.held.clear();
        }
    }

    /// Writes what is held, flushes the output; the first write error, if any.
    pub fn finish(&mut self) -> Result<(), std::io::Error> {
        self.settle(u64::MAX);
        if let Some(out) = self.out.as_mut()
            && let Err(error) = out.flush()
        {
            self.error.get_or_insert(error);
        }
        self.out = None;
        self.enabled = false;
        match self.error.take() {
            Some(error) => Err(error),
            None => Ok(()),
        }
    }
}

pub fn format_ms(ns: u64) -> String {
    format!("{}.{:06} ms", ns / 1_000_000, ns % 1_000_000)
}

pub fn format_us(ns: u64) -> String {
    format!("{}.{:03} µs", ns / 1000, ns % 1000)
}

fn text(event: &Event) -> String {
    match event {
        Event::Mode { from, to, cause } => match cause {
            Some(cause) => format!("mode {from} → {to} (cause {cause})"),
            None => format!("mode {from} → {to}"),
        },
        Event::CycleStart { cycle } => format!("── cycle {cycle} ──"),
        Event::CycleEnd {
            cycle,
            cycle_time_ns,
        } => format!(
            "── cycle {cycle} end, cycle time {} ──",
            format_ms(*cycle_time_ns)
        ),
        Event::BlockCall { from, to, .. } => format!("{from} calls {to}"),
        Event::BlockEnd { block, .. } => format!("{block} ends (BE)"),
        Event::IrqRequest {
            id,
            ob,
            module,
            channel,
            block,
            line,
            during,
        } => {
            let source = match (module, channel) {
                (Some(module), Some(channel)) => format!(" by module {module} channel {channel}"),
                _ => String::new(),
            };
            let place = match (block, line, during) {
                (Some(block), Some(line), _) => format!(" while {block} runs line {line}"),
                (Some(block), None, _) => format!(" while {block} runs"),
                (None, _, Some(during)) => format!(" during the {during}"),
                _ => " between cycles".to_string(),
            };
            format!("⚡ OB {ob} requested (#{id}){source}{place}")
        }
        Event::IrqService {
            id,
            ob,
            latency_ns,
            point,
            block,
            waited,
        } => {
            let block = block.as_deref().unwrap_or("?");
            let place = match *point {
                "block_end" => format!("at the block end of {block}"),
                "block_call" => format!("at the call of {block}"),
                "operation" => format!("after an operation of {block}"),
                _ => "at a point of the operating system".to_string(),
            };
            let waited = match waited {
                Some("priority") => " (a higher or equal priority ran first)",
                Some("disabled") => " (IA held it back)",
                Some("startup") => " (it came before RUN)",
                _ => "",
            };
            format!(
                "▶ OB {ob} serviced (#{id}) {place}, latency {}{waited}",
                format_us(*latency_ns)
            )
        }
        Event::IrqEnd { id, ob } => {
            format!("◀ OB {ob} done (#{id}), back to the interrupted level")
        }
        Event::IrqLost { id, ob, reason } => format!("✗ OB {ob} request #{id} lost: {reason}"),
        Event::IrqIgnored { id, ob, reason } => {
            format!("✗ OB {ob} request #{id} ignored: {reason}")
        }
        Event::DataCycle {
            kind,
            direction,
            duration_ns,
        } => {
            let what = match (*kind, *direction) {
                ("process_image", "input") => "process image read (PII)",
                ("process_image", _) => "process image write (PIQ)",
                ("interrupt_input", _) => "interrupt input data cycle",
                _ => "interrupt output data cycle",
            };
            format!("{what}, {}", format_us(*duration_ns))
        }
        Event::OsTime { duration_ns } => {
            format!("operating-system time, {}", format_us(*duration_ns))
        }
        Event::ModuleEvent {
            module,
            channel,
            ob,
            reason,
        } => format!("· module {module} channel {channel} (OB {ob}): {reason}"),
        Event::Stop { cause, block, line } => format!("STOP {cause} in {block} line {line}"),
        Event::Watch { values, .. } => {
            let values: Vec<String> = values
                .iter()
                .map(|(operand, value)| format!("{operand} = {value}"))
                .collect();
            format!("watch: {}", values.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jsonl_has_the_stable_field_names() {
        let record = Record {
            t_ns: 1500,
            event: &Event::IrqService {
                id: 1,
                ob: 3,
                latency_ns: 20,
                point: "block_end",
                block: None,
                waited: None,
            },
        };
        assert_eq!(
            serde_json::to_string(&record).unwrap(),
            r#"{"t_ns":1500,"ev":"irq_service","id":1,"ob":3,"latency_ns":20,"point":"block_end"}"#
        );
    }
}
