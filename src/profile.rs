//! CPU profiles: operand ranges, limits, per-operation execution times and interrupt rules of the
//! three CPUs the seeds describe. `awl cpus` prints them with where each figure comes from.

/// The CPUs whose interrupt rules differ; each rule in the engine is keyed to one of these.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// SINUMERIK 840C PLC (CPU 928B), seed 000.
    Sinumerik840c,
    /// S5-95F with time-controlled OB 13, seed 002.
    S5_95f,
    /// VIPA SPEED7 with hardware interrupt OBs 40/41, seed 001.
    Speed7,
}

/// Where interrupts may be serviced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InterruptPoints {
    /// Block calls, block ends and the cycle boundary (normal mode of seed 000).
    Block,
    /// After every operation.
    Operation,
}

impl InterruptPoints {
    pub fn name(self) -> &'static str {
        match self {
            InterruptPoints::Block => "block",
            InterruptPoints::Operation => "operation",
        }
    }
}

/// An interrupt OB and its priority (higher number = higher priority).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InterruptOb {
    pub ob: u8,
    pub priority: u8,
    pub summary: &'static str,
}

/// Operand ranges (inclusive upper bounds are `size - 1`).
#[derive(Debug, Clone, Copy)]
pub struct Sizes {
    /// Bytes of the PII (inputs I/IB/IW) and of the PIQ (outputs Q/QB/QW).
    pub image_bytes: u16,
    pub flag_bytes: u16,
    /// Peripheral bytes (PY/PW and OY/OW).
    pub peripheral_bytes: u16,
    pub timers: u16,
    pub counters: u16,
    /// Words of one data block.
    pub data_words: u16,
}

/// Execution times in nanoseconds of simulated time.
#[derive(Debug, Clone, Copy)]
pub struct Timings {
    pub bit_image: u32,
    pub bit_data: u32,
    pub bit_timer_counter: u32,
    pub load_byte: u32,
    pub load_word: u32,
    pub load_double: u32,
    pub load_constant: u32,
    pub load_data: u32,
    pub load_peripheral: u32,
    pub timer_counter: u32,
    pub add_sub: u32,
    pub multiply: u32,
    pub divide: u32,
    pub compare: u32,
    pub word_logic: u32,
    pub accumulator: u32,
    pub jump: u32,
    pub block_call: u32,
    pub block_end: u32,
    pub open_db: u32,
    pub other: u32,
    /// Operating-system time added at every cycle end.
    pub cycle_overhead: u32,
    /// One interrupt input or output data cycle (S5-95F).
    pub data_cycle: u32,
    /// Reading the PII and writing the PIQ, per byte.
    pub process_image_per_byte: u32,
    /// Where the figures come from.
    pub source: &'static str,
}

#[derive(Debug, Clone)]
pub struct Profile {
    pub name: &'static str,
    pub family: Family,
    pub title: &'static str,
    pub seed: &'static str,
    pub sizes: Sizes,
    pub nesting_limit: u16,
    pub bracket_depth: u8,
    pub watchdog_ns: u64,
    pub startup_obs: &'static [u8],
    pub interrupt_obs: &'static [InterruptOb],
    pub default_points: InterruptPoints,
    /// FX and DX blocks.
    pub extended_blocks: bool,
    pub timings: Timings,
    pub rules: &'static [&'static str],
}

impl Profile {
    pub fn interrupt_ob(&self, ob: u8) -> Option<&InterruptOb> {
        self.interrupt_obs.iter().find(|entry| entry.ob == ob)
    }
}

const SINUMERIK_840C_TIMES: Timings = Timings {
    bit_image: 570,
    bit_data: 3400,
    bit_timer_counter: 1200,
    load_byte: 810,
    load_word: 940,
    load_double: 1600,
    load_constant: 570,
    load_data: 1500,
    load_peripheral: 2500,
    timer_counter: 6000,
    add_sub: 940,
    multiply: 5400,
    divide: 10000,
    compare: 1200,
    word_logic: 940,
    accumulator: 570,
    jump: 1000,
    block_call: 6300,
    block_end: 3200,
    open_db: 3500,
    other: 570,
    cycle_overhead: 400_000,
    data_cycle: 0,
    process_image_per_byte: 100,
    source: "CPU 928B table (seed 000 PLC manual): bit operations on I/Q/F 0.57 µs, on D 3.4 µs; \
             L FY 0.81, L FW 0.94, L FD 1.6 µs; fixed-point arithmetic 0.94–10 µs. Block call/end, \
             timers, jumps and the 0.4 ms operating-system time are estimates.",
};

const S5_95F_TIMES: Timings = Timings {
    bit_image: 1600,
    bit_data: 4000,
    bit_timer_counter: 2500,
    load_byte: 1800,
    load_word: 2000,
    load_double: 3500,
    load_constant: 1600,
    load_data: 3000,
    load_peripheral: 12_000,
    timer_counter: 18_000,
    add_sub: 3000,
    multiply: 60_000,
    divide: 90_000,
    compare: 3000,
    word_logic: 2000,
    accumulator: 1600,
    jump: 2500,
    block_call: 14_000,
    block_end: 8000,
    open_db: 8000,
    other: 1600,
    cycle_overhead: 1_000_000,
    data_cycle: 300_000,
    process_image_per_byte: 500,
    source: "estimates of the S5-95 class (about 1.6 µs per bit operation); the seed gives the \
             rules, not the times. Interrupt data cycles 0.3 ms each.",
};

const SPEED7_TIMES: Timings = Timings {
    bit_image: 10,
    bit_data: 10,
    bit_timer_counter: 20,
    load_byte: 10,
    load_word: 10,
    load_double: 10,
    load_constant: 10,
    load_data: 10,
    load_peripheral: 1000,
    timer_counter: 30,
    add_sub: 10,
    multiply: 20,
    divide: 40,
    compare: 10,
    word_logic: 10,
    accumulator: 10,
    jump: 10,
    block_call: 200,
    block_end: 100,
    open_db: 30,
    other: 10,
    cycle_overhead: 50_000,
    data_cycle: 0,
    process_image_per_byte: 20,
    source: "SPEED7 class (0.01 µs per bit and word operation); block calls and the 50 µs \
             operating-system time are estimates.",
};

pub static PROFILES: &[Profile] = &[
    Profile {
        name: "sinumerik-840c",
        family: Family::Sinumerik840c,
        title: "SINUMERIK 840C/880 PLC (CPU 928B), normal mode",
        seed: "seed 000: SINUMERIK 840C/880 PLC manual, 5.3.1 Normal mode, 5.3.2 Response time",
        sizes: Sizes {
            image_bytes: 128,
            flag_bytes: 256,
            peripheral_bytes: 256,
            timers: 256,
            counters: 256,
            data_words: 2048,
        },
        nesting_limit: 32,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        startup_obs: &[21, 22],
        interrupt_obs: &[
            InterruptOb {
                ob: 2,
                priority: 7,
                summary: "interrupt (special mode only)",
            },
            InterruptOb {
                ob: 3,
                priority: 6,
                summary: "interrupt",
            },
            InterruptOb {
                ob: 4,
                priority: 5,
                summary: "interrupt",
            },
            InterruptOb {
                ob: 5,
                priority: 4,
                summary: "interrupt (special mode only)",
            },
            InterruptOb {
                ob: 6,
                priority: 3,
                summary: "interrupt",
            },
            InterruptOb {
                ob: 7,
                priority: 2,
                summary: "interrupt",
            },
        ],
        default_points: InterruptPoints::Block,
        extended_blocks: true,
        timings: SINUMERIK_840C_TIMES,
        rules: &[
            "normal mode: the cyclic program is interrupted only at block changes (a block call or \
             a block end) and at the cycle boundary (seed 000, 5.3.1)",
            "priority OB 2 > OB 3 > OB 4 > OB 5 > OB 6 > OB 7 > OB 1; simultaneous requests are \
             serviced highest first, and after an interrupt OB ends the pending requests are \
             ranked again (seed 000, 5.3.2)",
            "normal mode: requests for OB 2 and OB 5 are ignored even when the OBs exist \
             (seed 000, 5.3.1); mode = \"special\" processes them",
            "worst-case response time in normal mode = the processing time of the longest block \
             (seed 000, 5.3.2)",
            "a second request for an OB that is still pending is lost",
        ],
    },
    Profile {
        name: "s5-95f",
        family: Family::S5_95f,
        title: "S5-95F with time-controlled OB 13",
        seed: "seed 002: Einführung in STEP 5, S5-95F, OB 13 interrupt process images and wake-up error",
        sizes: Sizes {
            image_bytes: 128,
            flag_bytes: 256,
            peripheral_bytes: 256,
            timers: 128,
            counters: 128,
            data_words: 256,
        },
        nesting_limit: 16,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        startup_obs: &[21, 22],
        interrupt_obs: &[
            InterruptOb {
                ob: 3,
                priority: 3,
                summary: "process interrupt",
            },
            InterruptOb {
                ob: 13,
                priority: 2,
                summary: "time-controlled at [ob13].interval",
            },
        ],
        default_points: InterruptPoints::Block,
        extended_blocks: false,
        timings: S5_95F_TIMES,
        rules: &[
            "OB 13 starts every [ob13].interval; at its start an interrupt input data cycle reads \
             the input modules into the interrupt PII (seed 002)",
            "inside OB 13, L PY/L PW read the interrupt PII; T PY/T PW write the interrupt PIQ and \
             the normal PIQ (seed 002)",
            "after OB 13, an interrupt output data cycle writes the interrupt PIQ to the modules, \
             only if it was written; both data cycles cost time (seed 002)",
            "OB 13 due while OB 13 still runs or is still pending: wake-up error, STOP cause WECK \
             (seed 002)",
            "OB 3 (process interrupt) has priority over OB 13",
            "block nesting depth at most 16 (deeper: STOP cause STUEB)",
        ],
    },
    Profile {
        name: "speed7",
        family: Family::Speed7,
        title: "VIPA SPEED7 with hardware interrupts OB 40/OB 41",
        seed: "seed 001: VIPA SPEED7 operation list, OB 40/OB 41 hardware interrupts",
        sizes: Sizes {
            image_bytes: 256,
            flag_bytes: 2048,
            peripheral_bytes: 256,
            timers: 256,
            counters: 256,
            data_words: 4096,
        },
        nesting_limit: 16,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        startup_obs: &[100],
        interrupt_obs: &[
            InterruptOb {
                ob: 82,
                priority: 26,
                summary: "diagnostic interrupt",
            },
            InterruptOb {
                ob: 85,
                priority: 26,
                summary: "program execution error (no OB for a module)",
            },
            InterruptOb {
                ob: 41,
                priority: 17,
                summary: "hardware interrupt",
            },
            InterruptOb {
                ob: 40,
                priority: 16,
                summary: "hardware interrupt",
            },
        ],
        default_points: InterruptPoints::Operation,
        extended_blocks: false,
        timings: SPEED7_TIMES,
        rules: &[
            "a module's hardware interrupt starts its OB ([[hw_module]]) if the OB's priority is \
             above the active priority class (seed 001)",
            "the channel is acknowledged after the OB has run (seed 001)",
            "between identification and acknowledgement: a new event on the same channel is \
             lost and its loss starts the diagnostic interrupt OB 82 (seed 001)",
            "an event on another channel of the same module is held and triggered after the \
             acknowledgement if still active, else lost (seed 001)",
            "while the OB is busy with another module's interrupt, a new request is processed only \
             if still active after that acknowledgement (seed 001)",
            "no hardware interrupts in STARTUP; those during the transition to RUN are lost \
             (seed 001)",
            "no OB for the module: OB 85 is called and the interrupt acknowledged; no OB 85 \
             either: STOP cause OB85 (seed 001)",
            "interrupt points: after every operation, as S7 CPUs do",
        ],
    },
];

pub const DEFAULT_PROFILE: &str = "sinumerik-840c";

pub fn find(name: &str) -> Option<&'static Profile> {
    PROFILES
        .iter()
        .find(|profile| profile.name.eq_ignore_ascii_case(name))
}

pub fn names() -> Vec<&'static str> {
    PROFILES.iter().map(|profile| profile.name).collect()
}
