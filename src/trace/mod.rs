//! The trace: one event per mode change, cycle, block change, interrupt and module change, on
//! simulated time. The tracer hands them, in time order, to its outputs: `jsonl` writes one
//! JSON object per line (stable field names), `text` an indented timeline a person can follow,
//! `chrome` the trace-event JSON of Perfetto and chrome://tracing, and the timeline picture
//! (`crate::timeline`) draws them. Events come out in time order: the tracer holds them back
//! until the CPU has taken in everything due by then (a request is only noticed at the next
//! point, after the block changes it came before).

pub mod activity;
mod chrome;
pub mod filter;
mod jsonl;
mod text;

pub use text::{line as describe, segment_text};

use std::io::Write;

use serde::Serialize;

pub use filter::{Kind, TraceFilter};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceFormat {
    Jsonl,
    Text,
    Chrome,
}

/// A block's name in an event, `"PB 3"`: shared, so an event names a block without
/// allocating.
pub type BlockName = std::sync::Arc<str>;

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
        from: BlockName,
        to: BlockName,
        depth: usize,
    },
    BlockEnd {
        block: BlockName,
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
        /// The line's segment, in a PG listing.
        #[serde(skip_serializing_if = "Option::is_none")]
        segment: Option<u16>,
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
    /// A request SFC 39 DIS_IRT had disabled: discarded, it never runs.
    IrqDiscarded {
        id: u64,
        ob: u8,
        reason: &'static str,
    },
    /// A request SFC 41 DIS_AIRT delays: it runs when the delays end (its `irq_service` says
    /// `waited: "delayed"`).
    IrqDelayed {
        id: u64,
        ob: u8,
        /// The DIS_AIRT calls in force.
        delays: u16,
    },
    /// The delays of SFC 41 DIS_AIRT ended: by SFC 42 EN_AIRT, or with the OB that called it.
    DelayEnd {
        /// The OB whose delays ended.
        ob: u8,
        /// `EN_AIRT` or `OB end`.
        by: &'static str,
    },
    /// A call of SFC 39 DIS_IRT, SFC 40 EN_IRT, SFC 41 DIS_AIRT or SFC 42 EN_AIRT.
    IrtCall {
        sfc: u16,
        name: &'static str,
        #[serde(skip_serializing_if = "Option::is_none")]
        mode: Option<u8>,
        #[serde(skip_serializing_if = "Option::is_none")]
        ob_nr: Option<i16>,
        ret_val: i16,
        /// The OB whose level called it.
        ob: u8,
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
    /// S7: the cycle end waits for the minimum cycle time, this long before the next thing due
    /// (an interrupt is serviced at its end) or the end of the wait.
    CycleWait {
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
        /// The line's segment, in a PG listing.
        #[serde(skip_serializing_if = "Option::is_none")]
        segment: Option<u16>,
    },
    /// A row of the watch table: the watched operands' values at a cycle boundary.
    Watch {
        cycle: u64,
        /// Operand → the value as the watch table shows it (formatted by the state layer).
        values: std::collections::BTreeMap<String, String>,
        /// The same values as numbers, for counters (Chrome trace).
        #[serde(skip)]
        numbers: Vec<(String, i64)>,
    },
    /// A scenario's input change reached the input modules.
    Input {
        operand: String,
        value: u32,
    },
    /// The output modules changed: the PIQ was written, or a direct (peripheral) output.
    Output {
        operand: String,
        value: u32,
    },
    /// A network client wrote to the CPU's memory (`awl serve`), at the cycle control point.
    ClientWrite {
        /// The protocol and the client's number (`s7 #2`, `modbus #1`).
        client: String,
        /// What it wrote, in the program's notation (`MW 10`, `DB1.DBX 0.1`).
        operand: String,
        /// The value: a bit's 0 or 1, up to four bytes as `16#…`, else the bytes in hex.
        value: String,
    },
    /// The online page wrote a value once (modify), at the cycle control point.
    Modify {
        /// `http #3`: the page's connection.
        client: String,
        /// As the page wrote it (`MW 10`, `DB5.DBW 4`, `-START`).
        operand: String,
        /// As written (`42`, `true`, `1.5`).
        value: String,
    },
    /// The online page forced an input or output: held at `value` until unforced.
    Force {
        client: String,
        operand: String,
        value: String,
    },
    /// The online page ended a force.
    Unforce {
        client: String,
        operand: String,
    },
}

/// Where the events go: a trace file, the timeline picture. Every output sees every event in
/// time order (to know which blocks are open) and chooses itself what it writes.
pub trait Sink {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()>;
    /// The run ended at `end_ns`: writes what is left and flushes.
    fn finish(&mut self, end_ns: u64) -> std::io::Result<()>;
}

/// An output and what became of it.
struct Output {
    name: String,
    sink: Box<dyn Sink>,
    /// The events the output shows (its kinds and window), counted as they are handed on.
    shows: TraceFilter,
    events: u64,
    error: Option<std::io::Error>,
}

/// An output at the run's end: how many events it took, and whether it was written to the end.
#[derive(Debug)]
pub struct Finished {
    /// The name the output was added with (its path).
    pub name: String,
    pub events: u64,
    pub error: Option<std::io::Error>,
}

/// Hands events to the outputs; `enabled` is the one flag the loop tests.
pub struct Tracer {
    pub enabled: bool,
    outputs: Vec<Output>,
    /// Events not yet handed on: (time, order of arrival, event).
    held: Vec<(u64, u64, Event)>,
    arrivals: u64,
}

impl Tracer {
    pub fn off() -> Self {
        Tracer {
            enabled: false,
            outputs: Vec::new(),
            held: Vec::new(),
            arrivals: 0,
        }
    }

    /// A tracer writing every event in `format` to `out`.
    pub fn new(format: TraceFormat, out: Box<dyn Write>) -> Self {
        let mut tracer = Tracer::off();
        let sink = trace_sink(
            format,
            out,
            TraceFilter::all(),
            Vec::new(),
            Default::default(),
        );
        tracer.add("trace", sink, TraceFilter::all());
        tracer
    }

    /// Adds an output that shows the events `shows` lets through; `name` identifies it in
    /// [`Finished`].
    pub fn add(&mut self, name: &str, sink: Box<dyn Sink>, shows: TraceFilter) {
        self.outputs.push(Output {
            name: name.to_string(),
            sink,
            shows,
            events: 0,
            error: None,
        });
        self.enabled = true;
    }

    /// Removes the outputs named `name` (the online page's live timeline, when nobody watches
    /// it any more); with no output left, nothing is traced and the loop runs untraced again.
    pub fn remove(&mut self, name: &str) {
        self.outputs.retain(|output| output.name != name);
        self.enabled = self.outputs.iter().any(|output| output.error.is_none());
        if !self.enabled {
            self.held.clear();
        }
    }

    /// Records an event at simulated time `t_ns`. It is handed on by the next
    /// [`Tracer::settle`] that reaches its time.
    pub fn emit(&mut self, t_ns: u64, event: Event) {
        if self.enabled {
            self.arrivals += 1;
            self.held.push((t_ns, self.arrivals, event));
        }
    }

    /// Hands on, in time order (events of one time in the order they came), every event up
    /// to `t_ns`: the caller has taken in everything due by then.
    pub fn settle(&mut self, t_ns: u64) {
        if self.held.is_empty() {
            return;
        }
        self.held.sort_by_key(|(t, arrival, _)| (*t, *arrival));
        let ready = self.held.partition_point(|(t, _, _)| *t <= t_ns);
        // Taken out while its events are handed on, then put back: it keeps its room, so
        // settling allocates nothing.
        let mut held = std::mem::take(&mut self.held);
        for (t, _, event) in held.drain(..ready) {
            self.hand_on(t, &event);
        }
        if self.enabled {
            self.held = held;
        }
    }

    fn hand_on(&mut self, t_ns: u64, event: &Event) {
        for output in &mut self.outputs {
            if output.error.is_some() {
                continue;
            }
            match output.sink.event(t_ns, event) {
                Ok(()) => output.events += u64::from(output.shows.shows(t_ns, event)),
                Err(error) => output.error = Some(error),
            }
        }
        // With every output failed, nothing more is traced (`settle` drops what it held).
        if self.outputs.iter().all(|output| output.error.is_some()) {
            self.enabled = false;
        }
    }

    /// Hands on what is held and finishes every output at the run's end.
    pub fn finish(&mut self, end_ns: u64) -> Vec<Finished> {
        self.settle(u64::MAX);
        self.enabled = false;
        std::mem::take(&mut self.outputs)
            .into_iter()
            .map(|mut output| {
                let error = match output.error.take() {
                    Some(error) => Some(error),
                    None => output.sink.finish(end_ns).err(),
                };
                Finished {
                    name: output.name,
                    events: output.events,
                    error,
                }
            })
            .collect()
    }
}

/// A priority level as a picture or a Chrome trace shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LevelInfo {
    pub ob: u8,
    /// Higher is more urgent; OB 1's cycle is 0.
    pub priority: u8,
    pub what: &'static str,
    /// The program has the OB.
    pub loaded: bool,
}

/// The levels of a run: OB 1's and every interrupt OB of the profile.
pub type Levels = Vec<LevelInfo>;

/// The levels `profile` has, marked with the OBs `program` has.
pub fn levels(profile: &crate::profile::Profile, program: &crate::compiler::Program) -> Levels {
    let cyclic = LevelInfo {
        ob: 1,
        priority: 0,
        what: "cyclic program",
        loaded: program.ob(1).is_some(),
    };
    std::iter::once(cyclic)
        .chain(profile.interrupt_obs.iter().map(|entry| LevelInfo {
            ob: entry.ob,
            priority: entry.priority,
            what: entry.summary,
            loaded: program.ob(entry.ob).is_some(),
        }))
        .collect()
}

/// A trace file's writer in `format`, showing what `filter` lets through; the text trace
/// shows operands and blocks with their `symbols`.
pub fn trace_sink(
    format: TraceFormat,
    out: Box<dyn Write>,
    filter: TraceFilter,
    levels: Levels,
    symbols: crate::symbols::Symbols,
) -> Box<dyn Sink> {
    match format {
        TraceFormat::Jsonl => Box::new(jsonl::Jsonl::new(out, filter)),
        TraceFormat::Text => Box::new(text::Text::new(out, filter, symbols)),
        TraceFormat::Chrome => Box::new(chrome::Chrome::new(out, filter, levels)),
    }
}

pub fn format_ms(ns: u64) -> String {
    format!("{}.{:06} ms", ns / 1_000_000, ns % 1_000_000)
}

pub fn format_us(ns: u64) -> String {
    format!("{}.{:03} µs", ns / 1000, ns % 1000)
}
