//! What a network client asks of the CPU, and what it gets back: the one interface between the
//! protocol servers (S7comm, Modbus TCP, the online page's HTTP API) and the CPU. A protocol turns its packets into a
//! [`Request`] and sends it down the [`Requests`] channel; the CPU serves it at its cycle control
//! point (between two cycles, or at once while in STOP) and answers on the request's own
//! one-shot channel. The protocols never touch the CPU, so the VM's loop stays free of locks.

use serde::Serialize;
use tokio::sync::oneshot;

pub use crate::address::MemoryArea as Area;
pub use crate::state::watch::{Format, Raw};

/// A run of bytes (or timers, counters) of one area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Range {
    pub area: Area,
    /// The first byte (timer, counter).
    pub start: u32,
    /// How many bytes (timers, counters); at least 1.
    pub length: u32,
}

impl Range {
    pub fn new(area: Area, start: u32, length: u32) -> Range {
        Range {
            area,
            start,
            length,
        }
    }
}

/// One item of a read or write request.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Item {
    Read(Range),
    /// Bytes (two per timer or counter) written from `range.start`; `bytes.len()` is the
    /// range's length in bytes.
    Write {
        range: Range,
        bytes: Vec<u8>,
    },
    /// One bit: `byte` of `area`, bit 0–7.
    ReadBit {
        area: Area,
        byte: u32,
        bit: u8,
    },
    WriteBit {
        area: Area,
        byte: u32,
        bit: u8,
        value: bool,
    },
}

impl Item {
    /// Whether the item writes.
    pub fn writes(&self) -> bool {
        matches!(self, Item::Write { .. } | Item::WriteBit { .. })
    }
}

/// Why one item failed; the other items of the request are served.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ItemError {
    /// The data block does not exist.
    NoSuchBlock,
    /// The address lies past the area's end (or the block's).
    OutOfRange,
    /// The server refuses writes (`--read-only`).
    ReadOnly,
    /// The item asks for what the area cannot give (a bit of the timers).
    NotSupported,
}

/// What one item gave: the bytes read (a bit as one byte 0 or 1), nothing for a write.
pub type ItemResult = Result<Vec<u8>, ItemError>;

/// The operating mode a client sees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CpuMode {
    Run,
    Stop,
    Startup,
    /// A debugger's breakpoint holds the CPU (an S7 CPU's test operation): no cycle runs.
    Hold,
}

/// What the CPU reports of itself (CPU state, order code, CPU info, its clock).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CpuStatus {
    pub mode: CpuMode,
    /// The CPU profile's name (`speed7`, `s5-115u`, …).
    pub profile: &'static str,
    /// The order code the CPU reports (SZL 0x0011).
    pub order_code: String,
    /// The CPU's date and time of day: the simulated clock, in milliseconds since
    /// 1990-01-01 00:00 (the S7 epoch), as SFC 1 READ_CLK reads it.
    pub clock_ms: i64,
    /// The completed cycles.
    pub cycles: u64,
    /// The server refuses writes and mode changes (`--read-only`): the CPU reports itself
    /// protected.
    pub read_only: bool,
}

/// A command to the CPU's operating mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Control {
    Stop,
    /// Warm restart: memory kept, the profile's startup OB, then RUN.
    HotStart,
    /// Cold restart: memory as loaded, the profile's startup OB, then RUN.
    ColdStart,
}

/// Why a control command was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ControlError {
    ReadOnly,
    /// A start while the CPU is in RUN.
    AlreadyRunning,
}

/// Who asks: the protocol and the client's number there, for the trace (`s7 #3`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Client {
    pub protocol: Protocol,
    pub number: u32,
}

impl Client {
    /// `s7 #3`, `http #1`: the client as the trace and the diagnostic buffer name it.
    pub fn name(self) -> String {
        format!("{} #{}", self.protocol.name(), self.number)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Protocol {
    S7,
    Modbus,
    /// The online page and its JSON API (`--http`).
    Http,
    /// The terminal `awl serve` runs in (its snapshot key).
    Terminal,
    /// OPC UA (`--opcua`).
    OpcUa,
}

impl Protocol {
    pub fn name(self) -> &'static str {
        match self {
            Protocol::S7 => "s7",
            Protocol::Modbus => "modbus",
            Protocol::Http => "http",
            Protocol::Terminal => "terminal",
            Protocol::OpcUa => "opcua",
        }
    }
}

/// A client's request, with the channel its answer goes back on.
#[derive(Debug)]
pub enum Request {
    Access {
        client: Client,
        items: Vec<Item>,
        reply: oneshot::Sender<Vec<ItemResult>>,
    },
    Status {
        reply: oneshot::Sender<CpuStatus>,
    },
    Control {
        client: Client,
        command: Control,
        reply: oneshot::Sender<Result<(), ControlError>>,
    },
    /// A client connected (`true`) or left: the status line counts them.
    Connection {
        client: Client,
        open: bool,
    },
    /// What the online page asks (`--http`).
    Online {
        client: Client,
        ask: Ask,
    },
    /// Operands' values and the CPU's figures at one control point, for the OPC UA server's
    /// reads and monitored items (`--opcua`).
    Sample {
        probes: Vec<Probe>,
        reply: oneshot::Sender<Sample>,
    },
    /// A debugger's message (`awl dap` attached, `POST /api/debug`): a Debug Adapter Protocol
    /// request, answered with the messages it brings (its response and events); `None` asks
    /// only for the events that came since (`GET /api/debug/events`).
    Debug {
        message: Option<Vec<u8>>,
        reply: oneshot::Sender<Vec<serde_json::Value>>,
    },
}

/// What a sample reads: an operand as the command line resolves it, or a run of bytes (a
/// STRING).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Probe {
    Operand(crate::address::Target),
    Bytes(Range),
}

/// What a probe read: the operand's raw value (`None`: not there), or the bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reading {
    Operand(Option<Raw>),
    Bytes(ItemResult),
}

/// The values of a [`Request::Sample`] and the CPU at that control point.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub readings: Vec<Reading>,
    pub mode: CpuMode,
    pub cycles: u64,
    /// The last cycle's time.
    pub cycle_time_ms: f64,
    /// The simulated date and time, as [`CpuStatus::clock_ms`].
    pub clock_ms: i64,
}

/// What the online page asks of the CPU: operands as the command line takes them, resolved and
/// written by the CPU's owner at its control point.
#[derive(Debug)]
pub enum Ask {
    /// The CPU's mode, cycle, times, clients, forces and last STOP.
    Cpu { reply: oneshot::Sender<CpuView> },
    /// The values of operands, each in its format (`None`: the dialect's own notation).
    Values {
        watched: Vec<(String, Option<Format>)>,
        reply: Answer<Vec<Value>>,
    },
    /// Writes a value once, as a PG's "modify variable".
    Modify {
        operand: String,
        value: toml::Value,
        reply: Answer<Value>,
    },
    /// Holds an input or output at a value until it is unforced.
    Force {
        operand: String,
        value: toml::Value,
        reply: Answer<Value>,
    },
    /// Ends the force of one operand, or (`None`) of all; answers the operands unforced.
    Unforce {
        operand: Option<String>,
        reply: Answer<Vec<String>>,
    },
    /// The forces in effect.
    Forces { reply: oneshot::Sender<Vec<Value>> },
    /// Program status of a block's latest invocation (on the level of OB `level`).
    ProgramStatus {
        block: String,
        level: Option<String>,
        reply: Answer<StatusView>,
    },
    /// The diagnostic buffer, newest first.
    Diagnostics {
        reply: oneshot::Sender<Vec<DiagnosticEntry>>,
    },
    /// A snapshot of the whole CPU, as the file `--from` continues from.
    Snapshot { reply: oneshot::Sender<String> },
    /// The last `seconds` of simulated time as the timeline draws them (an SVG).
    Timeline {
        seconds: f64,
        reply: oneshot::Sender<String>,
    },
}

/// Where the answer to an [`Ask`] goes: what was asked for, or why it cannot be had.
pub type Answer<T> = oneshot::Sender<Result<T, Refusal>>;

/// Why an online request is refused: the diagnostic the command line would print, and the
/// kind of refusal (the HTTP status).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Refusal {
    #[serde(skip)]
    pub kind: Refused,
    pub error: String,
    pub code: Option<String>,
    pub help: Option<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refused {
    /// The request is malformed or names what cannot be (400).
    BadRequest,
    /// `--read-only`, a foreign host or origin (403).
    Forbidden,
    /// What it names is not there, or did not run (404).
    NotFound,
    /// The path does not take the method (405).
    MethodNotAllowed,
    /// It cannot be done in the CPU's mode (409).
    Conflict,
    /// Too large (413).
    TooLarge,
    /// No more live connections are taken (503).
    Busy,
}

impl Refused {
    /// The HTTP status code.
    pub fn status(self) -> u16 {
        match self {
            Refused::BadRequest => 400,
            Refused::Forbidden => 403,
            Refused::NotFound => 404,
            Refused::MethodNotAllowed => 405,
            Refused::Conflict => 409,
            Refused::TooLarge => 413,
            Refused::Busy => 503,
        }
    }
}

impl Refusal {
    /// The refusal of `diagnostic`: its message, code and help (or, without help, what its
    /// label says: a scenario value's allowed range).
    pub fn of(kind: Refused, diagnostic: &dyn miette::Diagnostic) -> Refusal {
        let label = || {
            diagnostic
                .labels()
                .and_then(|mut labels| labels.find_map(|label| label.label().map(str::to_string)))
        };
        Refusal {
            kind,
            error: diagnostic.to_string(),
            code: diagnostic.code().map(|code| code.to_string()),
            help: diagnostic
                .help()
                .map(|help| help.to_string())
                .or_else(label),
        }
    }
}

/// An operand's value as the online page shows it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Value {
    pub operand: String,
    /// The format's name; `None` in the answers to modify and force.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub format: Option<&'static str>,
    /// In the program's notation.
    pub value: String,
    /// The unsigned bit pattern, a bit's state; `null` when the operand is not there.
    pub raw: Option<Raw>,
}

/// The CPU as `GET /api/cpu` shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CpuView {
    pub mode: &'static str,
    pub cycle: u64,
    pub simulated_ms: f64,
    pub cycle_time_ms: CycleTimesView,
    pub profile: &'static str,
    /// `s5` or `s7`.
    pub dialect: &'static str,
    /// `en` or `de`.
    pub mnemonics: &'static str,
    pub clients: usize,
    pub forces: usize,
    pub read_only: bool,
    /// The program's last STOP, while the CPU is in STOP.
    pub stop: Option<StopView>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CycleTimesView {
    pub last: f64,
    pub min: f64,
    pub max: f64,
    pub mean: f64,
}

/// A STOP: its cause as the PG names it, where, and the report `awl run` prints.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct StopView {
    pub cause: &'static str,
    /// `OB 1`; `null` between cycles.
    pub block: Option<String>,
    pub line: Option<u32>,
    pub report: String,
}

/// Program status of one invocation, as `awl status` shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StatusView {
    pub block: String,
    /// The OB whose level ran it.
    pub level: String,
    pub cycle: u64,
    pub time_ms: f64,
    pub rows: Vec<StatusRow>,
}

/// A statement's line and what it left behind (all `null` when it did not run).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct StatusRow {
    pub line: u32,
    pub statement: String,
    pub executed: bool,
    pub rlo: Option<u8>,
    pub sta: Option<u8>,
    pub accu1: Option<String>,
    pub accu2: Option<String>,
    pub operand: Option<String>,
    /// How often the line ran (a loop).
    pub passes: Option<u64>,
}

/// An entry of the diagnostic buffer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiagnosticEntry {
    pub time_ms: f64,
    pub cycle: u64,
    /// `stop`, `mode`, `interrupt_lost`, `interrupt_late`, `force_set`, `force_cleared`,
    /// `modify`.
    pub kind: &'static str,
    pub text: String,
}

/// The sending end the protocol servers hold; the CPU holds the receiving end, [`Received`].
pub type Requests = tokio::sync::mpsc::UnboundedSender<Request>;

/// The CPU's end of the requests.
pub type Received = tokio::sync::mpsc::UnboundedReceiver<Request>;

/// A channel for the requests: the servers' end and the CPU's.
pub fn channel() -> (Requests, Received) {
    tokio::sync::mpsc::unbounded_channel()
}
