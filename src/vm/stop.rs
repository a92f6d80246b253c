//! Why the CPU went to STOP, and the report a PLC engineer reads: the cause as the PG's ISTACK
//! names it, the source line, and the block stack (BSTACK) with its return points.

use miette::Diagnostic;
use thiserror::Error;

use crate::source::Span;

/// STOP causes, named as in the CPU 928B interrupt stack (ISTACK).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopCause {
    /// Cycle monitoring time exceeded.
    Zyk,
    /// Block stack overflow: nesting too deep.
    Stueb,
    /// STEP 7: a block's local data do not fit the L stack.
    Lstack,
    /// Runtime error: a called block or opened data block is not loaded.
    LzfBlock,
    /// Runtime error: data word access with no DB open or past the DB's end.
    LzfData,
    /// Operation error: bracket stack overflow or underflow, or a substitution (DO, formal
    /// operand) that gives no valid operation.
    Bcf,
    /// The STP operation.
    Stp,
    /// Wake-up error: a time-controlled OB due while it still runs or is pending.
    Weck,
    /// A hardware interrupt for a module without OB, and no OB 85.
    Ob85,
    /// A time error (OB 35 behind), and no OB 80.
    Ob80,
    /// A DP station failed or returned, and no OB 86.
    Ob86,
    /// An awlsim test assertion (`__ASSERT==` …) did not hold.
    Assert,
    /// No STOP: a probe (program status, the debugger) ended the run here.
    Halt,
}

impl StopCause {
    /// Every code [`StopCause::code`] gives.
    pub const CODES: &'static [&'static str] = &[
        "ZYK", "STUEB", "LSTACK", "LZF", "BCF", "STP", "WECK", "OB85", "OB80", "OB86", "ASSERT",
    ];

    /// The cause as the PG shows it (and as scenario files expect it).
    pub fn code(self) -> &'static str {
        match self {
            StopCause::Zyk => "ZYK",
            StopCause::Stueb => "STUEB",
            StopCause::Lstack => "LSTACK",
            StopCause::LzfBlock | StopCause::LzfData => "LZF",
            StopCause::Bcf => "BCF",
            StopCause::Stp => "STP",
            StopCause::Weck => "WECK",
            StopCause::Ob85 => "OB85",
            StopCause::Ob80 => "OB80",
            StopCause::Ob86 => "OB86",
            StopCause::Assert => "ASSERT",
            StopCause::Halt => "HALT",
        }
    }
}

/// The op index of a STOP that came before its block's first operation (the block's local
/// data did not fit the L stack): every view of the STOP shows the block's header there.
pub const BEFORE_FIRST_OP: u32 = u32::MAX;

/// One BSTACK entry: a block that was called, and where it continues.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StackEntry {
    pub block: String,
    pub line: u32,
    /// The PG listing's segment of the line, in a listing.
    pub segment: Option<u16>,
}

/// The runtime STOP as a diagnostic.
#[derive(Debug, Clone, Error, Diagnostic, PartialEq)]
pub enum StopError {
    #[error("STOP ZYK: {how} in {block}")]
    #[diagnostic(
        code(awl::stop::zyk),
        help(
            "{stack}\nshorten the cycle, or raise the watchdog in the scenario (`watchdog = \"300ms\"`)"
        )
    )]
    CycleTime {
        /// "the cycle reached the watchdog time of 300.000 ms", or how far past it the cycle ran.
        how: String,
        block: String,
        #[label("running here when the watchdog expired")]
        at: Span,
        stack: String,
    },

    #[error("STOP STUEB: block nesting deeper than {limit} in {block}")]
    #[diagnostic(
        code(awl::stop::stueb),
        help("{stack}\nthe CPU allows {limit} nested blocks; look for a block that calls itself")
    )]
    Nesting {
        limit: u16,
        block: String,
        #[label("this call exceeds the block stack")]
        at: Span,
        stack: String,
    },

    #[error(
        "STOP LSTACK: the local data of {entered} need {needed} bytes of the L stack, which has {size}"
    )]
    #[diagnostic(
        code(awl::stop::lstack),
        help(
            "{stack}\nthe L stack holds the temporary variables of every block of the call chain; declare fewer or smaller ones, call fewer blocks deep, or give the CPU a larger L stack (an awlsim project's `nr_localbytes`)"
        )
    )]
    LocalOverflow {
        entered: String,
        /// The L stack's bytes up to the end of the block's local data.
        needed: u32,
        size: u32,
        #[label("{place}")]
        at: Span,
        /// "OB 1 starts here", "FC 2 is called here".
        place: String,
        stack: String,
    },

    #[error("STOP LZF: {target} is not loaded")]
    #[diagnostic(
        code(awl::stop::lzf_block),
        help("{stack}\nadd {target} to the program or load the file that holds it")
    )]
    BlockNotLoaded {
        target: String,
        #[label("called or opened here")]
        at: Span,
        stack: String,
    },

    #[error("STOP LZF: {problem}")]
    #[diagnostic(code(awl::stop::lzf_data), help("{stack}\n{fix}"))]
    DataAccess {
        problem: String,
        /// How a program of its dialect opens a data block.
        fix: &'static str,
        #[label("data access here")]
        at: Span,
        stack: String,
    },

    #[error("STOP BCF: {problem}")]
    #[diagnostic(code(awl::stop::bcf), help("{stack}"))]
    Operation {
        problem: String,
        #[label("this operation")]
        at: Span,
        stack: String,
    },

    #[error("STOP STP: the program executed STP")]
    #[diagnostic(
        code(awl::stop::stp),
        help("{stack}\nSTP sends the CPU to STOP at the end of the cycle")
    )]
    StopOperation {
        #[label("STP")]
        at: Span,
        stack: String,
    },

    #[error("STOP: {problem}")]
    #[diagnostic(
        code(awl::stop::assert),
        help("{stack}\nthe test's expectation does not hold at this line")
    )]
    AssertionFailed {
        problem: String,
        #[label("this assertion")]
        at: Span,
        stack: String,
    },

    #[error("STOP WECK: OB {ob} was due again before it had finished")]
    #[diagnostic(
        code(awl::stop::weck),
        help(
            "{stack}\nthe wake-up error (S5-95F manual, 7.4.4): lengthen the OB 13 interval, shorten OB 13, or reduce the interrupts that delay it"
        )
    )]
    WakeUp {
        ob: u8,
        #[label("running here when OB {ob} was due")]
        at: Span,
        stack: String,
    },

    #[error(
        "STOP WECK: the OB 13 interval {interval_ms} ms is not above the maximum delay {max_delay_ms} ms"
    )]
    #[diagnostic(
        code(awl::stop::weck_interval),
        help(
            "the time interrupt error of the S5-95F manual, 7.4.4: \"OB13 call-up interval > maximum delay t of OB13 processing\"; lengthen `[ob13].interval`"
        )
    )]
    IntervalNotAboveDelay {
        interval_ms: String,
        max_delay_ms: String,
        #[label("RUN began here")]
        at: Span,
    },

    #[error(
        "STOP OB85: hardware interrupt of module {module} has no OB, and OB 85 is not programmed"
    )]
    #[diagnostic(
        code(awl::stop::ob85),
        help(
            "{stack}\nprogram OB {ob} for the module, or OB 85 to handle the missing OB (VIPA SPEED7 operation list, OB 40/OB 41)"
        )
    )]
    MissingOb85 {
        module: u16,
        ob: u8,
        #[label("running here when the interrupt came")]
        at: Span,
        stack: String,
    },
    #[error(
        "STOP OB80: OB {ob} was requested again before its last request had run, and OB 80 is not programmed"
    )]
    #[diagnostic(
        code(awl::stop::ob80),
        help(
            "{stack}\nthe time error (System Software for S7-300/400 System and Standard Functions, 1.16 Time Error Organization Block (OB80)): shorten OB {ob} or what delays it, lengthen `[ob35] interval`, or program OB 80 to handle the error"
        )
    )]
    TimeError {
        ob: u8,
        #[label("running here when OB {ob} was due again")]
        at: Span,
        stack: String,
    },
    #[error("STOP OB86: DP station {station} {event}, and OB 86 is not programmed")]
    #[diagnostic(
        code(awl::stop::ob86),
        help(
            "{stack}\nprogram OB 86 to handle a slave's failure and return: \"If OB 86 has not been programmed, the CPU changes to the STOP mode\" (VIPA SPEED7 operation list, OB 86)"
        )
    )]
    StationEvent {
        station: u8,
        event: &'static str,
        #[label("running here when the station {event}")]
        at: Span,
        stack: String,
    },
}

crate::source::error_span!(StopError {}
    CycleTime, Nesting, LocalOverflow, BlockNotLoaded, DataAccess, Operation, StopOperation,
    AssertionFailed, WakeUp, IntervalNotAboveDelay, MissingOb85, TimeError, StationEvent,
);

/// A STOP as the VM records it: cause and details, where, and the block stack.
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    pub cause: StopCause,
    /// The block index and op index where it happened; no block when it happened between
    /// cycles in a program without OB 1.
    pub block: Option<u16>,
    pub pc: u32,
    pub detail: StopDetail,
    pub stack: Vec<StackEntry>,
}

/// Cause-specific facts for the report.
#[derive(Debug, Clone, PartialEq)]
pub enum StopDetail {
    None,
    Text(String),
    Ob(u8),
    /// SPEED7: DP station `station` failed (`failed`) or returned.
    Station {
        station: u8,
        failed: bool,
    },
    Module {
        module: u16,
        ob: u8,
    },
    Cycle {
        cycle_ns: u64,
        watchdog_ns: u64,
    },
    /// The local data of block `block` would end at byte `end` of the L stack: past its end.
    /// `call`: it was called (else its level was starting).
    LocalData {
        block: u16,
        end: u32,
        call: bool,
    },
    /// S5-95F: the OB 13 interval is not above the maximum delay.
    Ob13Interval {
        interval_ns: u64,
        max_delay_ns: u64,
    },
}
