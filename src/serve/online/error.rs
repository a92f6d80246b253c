//! Why the online page's server refuses a request: each refusal a diagnostic with its code, as
//! the command line reports its errors, and the HTTP status it is answered with.

use miette::Diagnostic;
use thiserror::Error;

use crate::serve::request::{Refusal, Refused};

/// The API's paths, for a request that names none of them.
const PATHS: &str = "the page is at `/`; the API: GET /api/cpu, POST /api/mode, GET /api/values, \
POST /api/modify, POST and DELETE /api/force, GET /api/forces, GET /api/status, \
GET /api/diagnostics, GET /api/timeline, and the WebSocket /api/live (`awl help online`)";

#[derive(Debug, Error, Diagnostic)]
pub enum OnlineError {
    #[error("`{path}` is no page of the online view")]
    #[diagnostic(code(awl::online::not_found), help("{}", PATHS))]
    NoSuchPath { path: String },

    #[error("{path} does not take {method}")]
    #[diagnostic(code(awl::online::method), help("{path} takes {allowed}"))]
    Method {
        method: String,
        path: &'static str,
        allowed: &'static str,
    },

    #[error("the request is not the JSON {path} takes: {reason}")]
    #[diagnostic(code(awl::online::bad_json), help("send e.g. {example}"))]
    BadJson {
        path: &'static str,
        reason: String,
        example: &'static str,
    },

    #[error("{path} needs `{name}`")]
    #[diagnostic(code(awl::online::missing), help("e.g. {example}"))]
    Missing {
        path: &'static str,
        name: &'static str,
        example: &'static str,
    },

    #[error("`{format}` is no display format")]
    #[diagnostic(
        code(awl::online::format),
        help(
            "the formats: BOOL, BIN, HEX, DEC, REAL, S5TIME (KT), KZ, CHAR; leave it empty for the program's own notation"
        )
    )]
    UnknownFormat { format: String },

    #[error("`{mode}` is no mode to change to")]
    #[diagnostic(
        code(awl::online::mode),
        help(
            "send {{\"mode\": \"stop\"}}, {{\"mode\": \"warm\"}} (warm restart) or {{\"mode\": \"cold\"}} (cold restart)"
        )
    )]
    UnknownMode { mode: String },

    #[error("the CPU is in RUN: a restart starts from STOP")]
    #[diagnostic(
        code(awl::online::running),
        help("stop it first: POST /api/mode {{\"mode\": \"stop\"}}")
    )]
    Running,

    #[error("the server is read-only: it does not modify, force or change the mode")]
    #[diagnostic(
        code(awl::online::read_only),
        help("`awl serve` was started with `--read-only`; start it without to change the CPU")
    )]
    ReadOnly,

    #[error("`{host}` is not this server's host")]
    #[diagnostic(
        code(awl::online::host),
        help(
            "open the page as http://{listening}/ or http://localhost:{port}/; other host names are refused, so that no web site can reach the PLC through its own name (DNS rebinding)"
        )
    )]
    ForeignHost {
        host: String,
        listening: String,
        port: u16,
    },

    #[error("a page from `{origin}` may not change the CPU")]
    #[diagnostic(
        code(awl::online::origin),
        help(
            "only the online page itself (http://{host}) may modify, force, change the mode or open the live connection"
        )
    )]
    ForeignOrigin { origin: String, host: String },

    #[error("the request is larger than 64 KiB")]
    #[diagnostic(code(awl::online::too_large), help("ask for fewer operands at a time"))]
    TooLarge,

    #[error("`{text}` is no value")]
    #[diagnostic(
        code(awl::online::value),
        help(
            "write it as a scenario's `set` takes it: an integer (42, -5, 0x2A), true or false, or in a STEP 7 double word a REAL (1.5)"
        )
    )]
    Value { text: String },

    #[error("`{operand}` cannot be forced: only inputs and outputs are, as bits, bytes or words")]
    #[diagnostic(
        code(awl::online::not_forceable),
        help(
            "force the process image, e.g. `I 0.0`, `QB 4`, `IW 2`; modify flags, timers, counters and data blocks once instead (POST /api/modify)"
        )
    )]
    NotForceable { operand: String },

    #[error("`{operand}` is not forced")]
    #[diagnostic(code(awl::online::not_forced), help("{forced}"))]
    NotForced { operand: String, forced: String },

    #[error("`{text}` names no block: {reason}")]
    #[diagnostic(
        code(awl::online::block),
        help("name a logic block as the program writes it: `OB 1`, `PB 3`, `FC 1`, or its symbol")
    )]
    Block { text: String, reason: String },

    #[error("`{text}` is no processing level")]
    #[diagnostic(
        code(awl::online::level),
        help("name the OB whose level calls the block, e.g. `OB 1` or `OB 35`")
    )]
    Level { text: String },

    #[error("{block} did not run{on_level} (the CPU is in {mode})")]
    #[diagnostic(
        code(awl::online::did_not_run),
        help(
            "program status shows a block's latest invocation; check that the program calls it (on that level), and that the CPU runs"
        )
    )]
    DidNotRun {
        block: String,
        on_level: String,
        mode: &'static str,
    },

    #[error("`{text}` is no number of seconds the timeline shows")]
    #[diagnostic(
        code(awl::online::seconds),
        help("give a number above 0 and up to 60, e.g. `seconds=5` (the default)")
    )]
    Seconds { text: String },

    #[error("/api/live is a WebSocket: the request did not ask to open one")]
    #[diagnostic(
        code(awl::online::websocket),
        help(
            "open it with a WebSocket client, e.g. `new WebSocket(\"ws://\" + location.host + \"/api/live\")`"
        )
    )]
    NotWebSocket,

    #[error("cannot modify `{operand}`: {reason}")]
    #[diagnostic(code(awl::online::modify))]
    Modify { operand: String, reason: String },

    #[error("the CPU no longer answers: the serve is ending")]
    #[diagnostic(code(awl::online::gone), help("start `awl serve` again"))]
    Gone,

    #[error("{live} live connections are open, as many as the server takes")]
    #[diagnostic(
        code(awl::online::busy),
        help("close a page, or start `awl serve` with a higher `--max-connections`")
    )]
    Busy { live: usize },
}

impl OnlineError {
    /// How the request is answered.
    pub fn kind(&self) -> Refused {
        match self {
            OnlineError::NoSuchPath { .. }
            | OnlineError::NotForced { .. }
            | OnlineError::DidNotRun { .. } => Refused::NotFound,
            OnlineError::Method { .. } => Refused::MethodNotAllowed,
            OnlineError::Running => Refused::Conflict,
            OnlineError::ReadOnly
            | OnlineError::ForeignHost { .. }
            | OnlineError::ForeignOrigin { .. } => Refused::Forbidden,
            OnlineError::TooLarge => Refused::TooLarge,
            OnlineError::Busy { .. } | OnlineError::Gone => Refused::Busy,
            OnlineError::BadJson { .. }
            | OnlineError::Missing { .. }
            | OnlineError::UnknownFormat { .. }
            | OnlineError::UnknownMode { .. }
            | OnlineError::Value { .. }
            | OnlineError::NotForceable { .. }
            | OnlineError::Block { .. }
            | OnlineError::Level { .. }
            | OnlineError::Seconds { .. }
            | OnlineError::NotWebSocket
            | OnlineError::Modify { .. } => Refused::BadRequest,
        }
    }

    pub fn refusal(&self) -> Refusal {
        Refusal::of(self.kind(), self)
    }
}

impl From<OnlineError> for Refusal {
    fn from(error: OnlineError) -> Refusal {
        error.refusal()
    }
}
