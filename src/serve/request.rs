//! What a network client asks of the CPU, and what it gets back: the one interface between the
//! protocol servers (S7comm, Modbus TCP) and the CPU. A protocol turns its packets into a
//! [`Request`] and sends it down the [`Requests`] channel; the CPU serves it at its cycle control
//! point (between two cycles, or at once while in STOP) and answers on the request's own
//! one-shot channel. The protocols never touch the CPU, so the VM's loop stays free of locks.

use tokio::sync::oneshot;

pub use crate::address::MemoryArea as Area;

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

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Protocol {
    S7,
    Modbus,
}

impl Protocol {
    pub fn name(self) -> &'static str {
        match self {
            Protocol::S7 => "s7",
            Protocol::Modbus => "modbus",
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
}

/// The sending end the protocol servers hold; the CPU holds the receiving end, [`Received`].
pub type Requests = tokio::sync::mpsc::UnboundedSender<Request>;

/// The CPU's end of the requests.
pub type Received = tokio::sync::mpsc::UnboundedReceiver<Request>;

/// A channel for the requests: the servers' end and the CPU's.
pub fn channel() -> (Requests, Received) {
    tokio::sync::mpsc::unbounded_channel()
}
