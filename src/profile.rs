//! CPU profiles: operand ranges, limits, per-operation execution times and interrupt rules of the
//! three CPUs the manuals describe. `awl cpus` prints them with where each figure comes from.

mod retentive;
mod s5_115u;
mod s5_135u;
mod s5_155u;
mod s5_common;
mod s5_small;

use std::sync::{Mutex, OnceLock, PoisonError};

use crate::dialect::Dialect;

pub use retentive::{Preset, Retentive};

/// The CPUs whose interrupt rules differ; each has its rules in `vm::interrupts`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// SINUMERIK 840C PLC (CPU 928B): SINUMERIK 840C PLC manual, 5.3.
    Sinumerik840c,
    /// S5-95F with time-controlled OB 13: S5-95F manual, "Introduction to STEP 5", 7.4.
    S5_95f,
    /// VIPA SPEED7 with hardware interrupt OBs 40/41: VIPA SPEED7 operation list.
    Speed7,
    /// The S5 CPUs of `profile::s5_*`: the generic engine with the profile's OBs, interrupt
    /// requests from the scenario (their manuals are cited per profile).
    S5,
}

/// A group of operations that only some CPUs have, as their programming guides list them.
/// An operation outside every group runs on every profile.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// S5 floating point: `+G -G XG :G`, the `G` comparisons, `FDG GFD` (CPU 928B programming
    /// guide, tables 3-7 and 3-21).
    FloatingPoint,
    /// 32-bit BCD ↔ fixed-point conversions `DED DUD` (CPU 928B programming guide, table 3-21).
    DoubleBcd,
    /// 16-bit BCD ↔ fixed-point conversions `DEF DUF` (CPU 928B programming guide, table
    /// 3-21).
    BcdConversions,
    /// `ADD KB/KF/DH`.
    AddConstant,
    /// System operations on absolute addresses: `TNB LIR TIR`.
    SystemOperations,
    /// Register and page operations: `MBA MAB MSA MAS ABR LRB TRB`.
    RegisterOperations,
}

impl Feature {
    /// The group in words, for "`XG` needs floating point".
    pub fn name(self) -> &'static str {
        match self {
            Feature::FloatingPoint => "floating point",
            Feature::DoubleBcd => "32-bit BCD conversion",
            Feature::BcdConversions => "16-bit BCD conversion",
            Feature::AddConstant => "adding a constant",
            Feature::SystemOperations => "system operations",
            Feature::RegisterOperations => "register operations",
        }
    }
}

/// What the block nesting limit counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Nesting {
    /// The blocks of each processing level on its own.
    PerLevel,
    /// All blocks on the block stack, interrupt levels included.
    WholeCpu,
}

/// Where interrupts may be serviced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InterruptPoints {
    /// Block calls, block ends and the operating system's points of the cycle (normal mode of
    /// the SINUMERIK 840C).
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
    /// A time-controlled OB the S5 CPU calls on its own at this interval (0: requested only).
    pub every_ms: u32,
}

impl InterruptOb {
    /// An OB that runs when it is requested (an interrupt or an event), never by the clock.
    pub const fn requested(ob: u8, priority: u8, summary: &'static str) -> Self {
        InterruptOb {
            ob,
            priority,
            summary,
            every_ms: 0,
        }
    }
}

/// A system OB a program may call (`JU OB 160`), as the CPU's manual lists it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SystemOb {
    pub ob: u8,
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
    /// Delay of the digital input modules (S5-95F 7.4.5 response time).
    pub input_delay: u32,
    /// Where the figures come from.
    pub source: TimesSource,
}

/// Where a profile's times come from.
#[derive(Debug, Clone, Copy)]
pub enum TimesSource {
    /// The manual's figures, or how they were scaled from a manual's figures.
    Stated(&'static str),
    /// Estimated from the bit-operation and operating-system times of the named CPU class.
    Estimated(&'static str),
}

impl Timings {
    /// Where the figures come from, for `awl cpus`.
    pub fn source(&self) -> String {
        match self.source {
            TimesSource::Stated(text) => text.to_string(),
            TimesSource::Estimated(class) => format!(
                "estimates of the {class} class (about {} µs per bit operation, {} ms \
                 operating-system time)",
                f64::from(self.bit_image) / 1e3,
                f64::from(self.cycle_overhead) / 1e6
            ),
        }
    }
}

#[derive(Debug, Clone)]
pub struct Profile {
    pub name: &'static str,
    pub family: Family,
    pub title: &'static str,
    /// The manual the rules come from, by title and section.
    pub manual: &'static str,
    pub sizes: Sizes,
    pub nesting_limit: u16,
    pub nesting: Nesting,
    /// 2, or 4 on the CPU 928B (ACCU 3 and 4).
    pub accumulators: u8,
    pub bracket_depth: u8,
    pub watchdog_ns: u64,
    /// The startup OBs: the first of them the program has runs in STARTUP.
    pub startup_obs: &'static [u8],
    pub interrupt_obs: &'static [InterruptOb],
    pub default_points: InterruptPoints,
    /// FX and DX blocks.
    pub extended_blocks: bool,
    /// The operation groups beyond those every CPU has.
    pub features: &'static [Feature],
    /// The integral FBs built into the CPU (FB 240–243, 250, 251 of the S5-115U).
    pub integral_fbs: &'static [u8],
    /// The system OBs the CPU's manual documents for calls from the program.
    pub system_obs: &'static [SystemOb],
    pub timings: Timings,
    pub rules: &'static [&'static str],
}

impl Profile {
    /// An S7 CPU: it runs STEP 7 programs (and not STEP 5 ones).
    pub fn runs_step7(&self) -> bool {
        self.family == Family::Speed7
    }

    pub fn has(&self, feature: Feature) -> bool {
        self.features.contains(&feature)
    }

    pub fn interrupt_ob(&self, ob: u8) -> Option<&InterruptOb> {
        self.interrupt_obs.iter().find(|entry| entry.ob == ob)
    }

    pub fn has_integral_fb(&self, fb: u8) -> bool {
        self.integral_fbs.contains(&fb)
    }

    pub fn system_ob(&self, ob: u8) -> Option<&SystemOb> {
        self.system_obs.iter().find(|entry| entry.ob == ob)
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
    input_delay: 0,
    source: TimesSource::Stated(
        "CPU 928B operation times (SINUMERIK 840C PLC manual): bit operations on I/Q/F \
             0.57 µs, on D 3.4 µs; L FY 0.81, L FW 0.94, L FD 1.6 µs; fixed-point arithmetic \
             0.94–10 µs. Block call/end, timers, jumps and the 0.4 ms operating-system time are \
             estimates.",
    ),
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
    input_delay: 3_000_000,
    source: TimesSource::Stated(
        "estimates of the S5-95 class (about 1.6 µs per bit operation): the S5-95F manual \
             excerpt gives the rules, not the times. Interrupt data cycles 0.3 ms each, input \
             module delay 3 ms (estimates).",
    ),
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
    input_delay: 0,
    source: TimesSource::Stated(
        "SPEED7 class (0.01 µs per bit and word operation); block calls and the 50 µs \
             operating-system time are estimates.",
    ),
};

/// The cycle-end model every profile shares, as `awl cpus` states it.
pub const CYCLE_MODEL: &str = "a cycle is: PII read, OB 1, PIQ write, operating-system time; \
     interrupts may be serviced between these parts (the operating system's points) as at a \
     block change, never inside one, so the response bound is the longest stretch between two \
     interrupt points anywhere in the cycle, the cycle-end work included";

pub static PROFILES: &[Profile] = &[
    Profile {
        name: "sinumerik-840c",
        family: Family::Sinumerik840c,
        title: "SINUMERIK 840C/880 PLC (CPU 928B), normal mode",
        manual: "SINUMERIK 840C/880 PLC manual, 5.3.1 Normal mode, 5.3.2 Response time",
        sizes: s5_common::LARGE_SIZES,
        nesting_limit: 32,
        nesting: Nesting::PerLevel,
        accumulators: 4,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        startup_obs: &[21, 22],
        interrupt_obs: &[
            InterruptOb::requested(2, 7, "interrupt (special mode only)"),
            InterruptOb::requested(3, 6, "interrupt"),
            InterruptOb::requested(4, 5, "interrupt"),
            InterruptOb::requested(5, 4, "interrupt (special mode only)"),
            InterruptOb::requested(6, 3, "interrupt"),
            InterruptOb::requested(7, 2, "interrupt"),
        ],
        default_points: InterruptPoints::Block,
        extended_blocks: true,
        features: s5_common::ALL_FEATURES,
        integral_fbs: &[],
        system_obs: &[],
        timings: SINUMERIK_840C_TIMES,
        rules: &[
            "normal mode: the cyclic program is interrupted only at block changes (a block call or \
             a block end) and at the operating system's points of the cycle (SINUMERIK 840C PLC \
             manual, 5.3.1)",
            "priority OB 2 > OB 3 > OB 4 > OB 5 > OB 6 > OB 7 > OB 1; simultaneous requests are \
             serviced highest first, and after an interrupt OB ends the pending requests are \
             ranked again (SINUMERIK 840C PLC manual, 5.3.2)",
            "normal mode: requests for OB 2 and OB 5 are ignored even when the OBs exist \
             (SINUMERIK 840C PLC manual, 5.3.1); mode = \"special\" processes them; a program \
             call of OB 2 or OB 5 runs it as a block, with a warning",
            "worst-case response time in normal mode = the processing time of the longest block \
             (SINUMERIK 840C PLC manual, 5.3.2); the summary adds the operating system's work at \
             the cycle end when it is longer",
            "a second request for an OB that is still pending is lost",
            "four accumulators (CPU 928B programming guide, table 3-7): +F -F X F :F move ACCU 3 \
             to ACCU 2 and ACCU 4 to ACCU 3; ENT moves ACCU 2 to ACCU 3 and ACCU 3 to ACCU 4",
        ],
    },
    Profile {
        name: "s5-95f",
        family: Family::S5_95f,
        title: "S5-95F with time-controlled OB 13",
        manual: "S5-95F manual, Introduction to STEP 5, 7.4.4 Time-controlled program \
                 processing, 7.4.5 Maximum response time; 12 Interrupt processing",
        sizes: s5_common::SMALL_SIZES,
        nesting_limit: 16,
        nesting: Nesting::WholeCpu,
        accumulators: 2,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        startup_obs: &[21, 22],
        interrupt_obs: &[
            InterruptOb::requested(2, 4, "process interrupt (interrupt inputs)"),
            InterruptOb::requested(3, 3, "process interrupt"),
            InterruptOb::requested(13, 2, "time-controlled at [ob13].interval"),
        ],
        default_points: InterruptPoints::Operation,
        extended_blocks: false,
        // The S5-95F manual at hand names no floating-point or BCD conversion operations (its
        // operation set is the S5-95U's basic and supplementary operations).
        features: &[],
        integral_fbs: &[],
        system_obs: &[],
        timings: S5_95F_TIMES,
        rules: &[
            "OB 13 can interrupt the cyclic program after any STEP 5 statement; OB 2 and OB 3 can \
             interrupt OB 13; OB 13 cannot interrupt the data cycles, OB 2, OB 3 or a running \
             OB 13 (S5-95F manual, 7.4.4): operation interrupt points, priority OB 2 > OB 3 > \
             OB 13 > OB 1",
            "OB 2 cannot be interrupted; OB 3 only by OB 2; a request made while its OB runs is \
             stored and runs after it (S5-95F manual, 12)",
            "OB 13 is called every [ob13].interval, each call late by the delay t ([ob13].delay, \
             0 by default: the manual's ideal case); with [ob13].max_delay given, an interval \
             not above it is the time interrupt error, STOP cause WECK (S5-95F manual, 7.4.4)",
            "at OB 13's start an interrupt input data cycle reads the input modules into the \
             interrupt PII; inside OB 13, L PY/L PW read the interrupt PII and T PY/T PW write the \
             interrupt PIQ and the normal PIQ; after OB 13 an interrupt output data cycle writes \
             the interrupt PIQ to the modules, only if it was written (S5-95F manual, 7.4.4); \
             the images belong to OB 13's level: an OB 3 inside OB 13 reaches the modules",
            "OB 13 called again before it was completed (running, pending, or in its output data \
             cycle): wake-up error, STOP cause WECK (S5-95F manual, 7.4.4)",
            "IA holds OB 13 and the process interrupts back, they are stored; RA is the default \
             (S5-95F manual, 7.4.4 and 12)",
            "block nesting depth at most 16, interrupt levels included (S5-95F manual, 7.4.4 and \
             12; deeper: STOP cause STUEB)",
            "maximum response of time-controlled processing: OB 13 interval + delay t + OB 13's \
             execution time + data cycles + input module delay (S5-95F manual, 7.4.5)",
        ],
    },
    Profile {
        name: "speed7",
        family: Family::Speed7,
        title: "VIPA SPEED7: hardware interrupts OB 40/OB 41, cyclic interrupt OB 35, OB 80/82/85, \
                SFC 39-42",
        manual: "VIPA SPEED7 operation list, OB 40/OB 41 hardware interrupts, OB 35, OB 80, OB 82, \
                 OB 85; System Software for S7-300/400 System and Standard Functions, 12; \
                 operand ranges: VIPA System 300S SPEED7 CPU manual (CPU 315SB, HB140), \
                 Hardware description, Technical data",
        sizes: Sizes {
            // The SPEED7 CPUs' sizes, from the technical data table of the VIPA System 300S
            // SPEED7 CPU manuals (CPU 315SB/DPM 315-2AG12, HB140, Hardware description,
            // Technical data: "Timers/Counters", "Bit memories", "Input/Output I/O address
            // area", "Process image"): process images of 256 bytes each (their preset; up to
            // 2048 are set in a hardware configuration, which a text program lacks, see
            // `MAX_S7_IMAGE_BYTES`), 8192 flag bytes, 8192 bytes of peripheral inputs and
            // outputs, 512 S7 timers and 512 S7 counters, twice an S7-300's 256.
            image_bytes: 256,
            flag_bytes: 8192,
            peripheral_bytes: 8192,
            timers: 512,
            counters: 512,
            data_words: 4096,
        },
        // Nesting depth per priority class 16 (same table, "Blocks"); the table's 8191 data
        // blocks and 1024 bytes of local data per priority class are stated in the rules:
        // awl takes DB numbers up to 65535 and one 64 KB L stack, so a program written for a
        // larger CPU still runs.
        nesting_limit: 16,
        nesting: Nesting::PerLevel,
        accumulators: 2,
        bracket_depth: 7,
        watchdog_ns: 150_000_000,
        // OB 100, the warm restart, SPEED7's default startup; a program with OB 102 only
        // was written for a CPU set to cold restart (VIPA SPEED7 operation list, OB 100,
        // OB 102).
        startup_obs: &[100, 102],
        interrupt_obs: &[
            InterruptOb::requested(80, 26, "time error (OB 35 requested again before it ran)"),
            InterruptOb::requested(82, 26, "diagnostic interrupt"),
            InterruptOb::requested(85, 26, "program execution error (no OB for a module)"),
            InterruptOb::requested(86, 26, "DP slave failure / return"),
            InterruptOb::requested(41, 17, "hardware interrupt"),
            InterruptOb::requested(40, 16, "hardware interrupt"),
            // Its interval is the scenario's (`[ob35]`), not the profile's.
            InterruptOb::requested(35, 12, "cyclic interrupt"),
        ],
        default_points: InterruptPoints::Operation,
        extended_blocks: false,
        // A SPEED7 CPU runs STEP 7 operations: IEEE floating point (`+R`) and `BTD`/`DTB`, not
        // the S5 groups; its STEP 5 operations are the common ones.
        features: &[],
        integral_fbs: &[],
        system_obs: &[],
        timings: SPEED7_TIMES,
        rules: &[
            "a module's hardware interrupt starts its OB ([[hw_module]]) if the OB's priority is \
             above the active priority class (VIPA SPEED7 operation list, OB 40/OB 41)",
            "the channel is acknowledged after the OB has run",
            "between identification and acknowledgement: a new event on the same channel is \
             lost and its loss starts the diagnostic interrupt OB 82",
            "an event on another channel of the same module is held and triggered after the \
             acknowledgement if still active, else lost",
            "while the OB is busy with another module's interrupt, a new request is processed only \
             if still active after that acknowledgement",
            "no hardware interrupts in STARTUP (events there are no requests); those during the \
             transition to RUN are lost",
            "no OB for the module: OB 85 is called and the interrupt acknowledged; no OB 85 \
             either: STOP cause OB85",
            "interrupt points: after every operation, as S7 CPUs do",
            "OB 35 (priority 12) runs every [ob35].interval (100 ms by default) from the \
             transition to RUN when the program has it (VIPA SPEED7 operation list, OB 28, 29, \
             32-35)",
            "OB 35 requested again while its last request is pending or it runs: time error, \
             OB 80 (priority 26); no OB 80: STOP cause OB80 (System Software for S7-300/400 \
             System and Standard Functions, 1.16 Time Error Organization Block (OB80); VIPA \
             SPEED7 operation list, OB 80)",
            "operand ranges: T 0 to 511, C 0 to 511, M bytes 0 to 8191, I/Q bytes 0 to 255 (the \
             preset process image; up to 2047 with a hardware configuration's), PI/PQ bytes 0 to \
             8191, block nesting depth 16 per priority class; the CPU has DB 1 to 8191 and 1024 \
             bytes of local data per priority class, where awl takes DB numbers up to 65535 and \
             one 64 KB L stack (VIPA System 300S SPEED7 CPU manual, CPU 315SB, Hardware \
             description, Technical data)",
            "a DP station's failure and its return ([[event]] station) call OB 86 (priority \
             26); no OB 86: STOP cause OB86 (VIPA SPEED7 operation list, OB 86)",
            "SFC 39 DIS_IRT discards new events of all interrupt and asynchronous error OBs \
             (MODE 0), of a class (1) or of one OB (2) until SFC 40 EN_IRT; SFC 41 DIS_AIRT \
             delays those of a higher priority until as many SFC 42 EN_AIRT calls, or until the \
             OB that called it ends (System Software for S7-300/400 System and Standard \
             Functions, 12 SFCs for Handling Interrupts and Asynchronous Errors)",
        ],
    },
    s5_small::S5_95U,
    s5_small::S5_100U_103,
    s5_115u::CPU_941,
    s5_115u::CPU_942,
    s5_115u::CPU_943,
    s5_115u::CPU_944,
    s5_115u::CPU_945,
    s5_135u::CPU_922,
    s5_135u::CPU_928,
    s5_135u::CPU_928B,
    s5_155u::CPU_946_947,
    s5_155u::CPU_948,
];

/// Short names for the CPU most programs of a family were written for.
pub const ALIASES: &[(&str, &str)] = &[
    ("s5-100u", "s5-100u-103"),
    ("s5-115u", "s5-115u-944"),
    ("s5-135u", "s5-135u-928b"),
    ("s5-155u", "s5-155u-948"),
];

/// The CPU a program runs on when neither the command line nor the scenario names one: the
/// VIPA SPEED7 for a STEP 7 program (an awlsim project is one: awlsim simulates S7 CPUs), the
/// SINUMERIK 840C for a STEP 5 program. Every command and the scenario choose by this rule.
pub fn default_for(dialect: Dialect) -> &'static Profile {
    let name = match dialect {
        Dialect::Step7 => "speed7",
        Dialect::Step5 => "sinumerik-840c",
    };
    find(name).expect("the default profiles exist")
}

/// The S7 CPUs set to four accumulators: the S7-400 has ACCU 1 to 4, the S7-300 (and the
/// SPEED7 CPUs, which follow it) two ("Statement List (STL) for S7-300 and S7-400
/// Programming", Accumulator Instructions). Made once, on first use, so a run can keep
/// `&'static Profile` as every other profile.
static FOUR_ACCUMULATORS: OnceLock<Vec<Profile>> = OnceLock::new();

/// `profile` with `count` accumulators: itself, or its variant when it is an S7 CPU and
/// `count` is 2 or 4 (`__FEATURE 0, 4` in an awlsim test, a `.conf`'s `accus`, a scenario's
/// `accumulators`); `None` when the CPU cannot have that many.
pub fn with_accumulators(profile: &'static Profile, count: u8) -> Option<&'static Profile> {
    if count == profile.accumulators {
        return Some(profile);
    }
    if !profile.runs_step7() {
        return None;
    }
    match count {
        2 => PROFILES
            .iter()
            .find(|base| base.name == profile.name && base.accumulators == 2),
        4 => FOUR_ACCUMULATORS
            .get_or_init(|| {
                PROFILES
                    .iter()
                    .filter(|base| base.runs_step7())
                    .map(|base| Profile {
                        accumulators: 4,
                        ..base.clone()
                    })
                    .collect()
            })
            .iter()
            .find(|variant| variant.name == profile.name),
        _ => None,
    }
}

/// A CPU with what every profile has at once: each operation group, the largest operand
/// ranges, FX and DX blocks, every integral FB and system OB, four accumulators. A STEP 5
/// program's errors on it are errors on every profile; `awl check` compiles for it to tell the
/// profiles a program compiles on when the default profile's errors hide some checks.
pub fn widest() -> &'static Profile {
    static WIDEST: OnceLock<Profile> = OnceLock::new();
    WIDEST.get_or_init(|| {
        let most = |size: fn(&Sizes) -> u16| {
            PROFILES
                .iter()
                .map(|profile| size(&profile.sizes))
                .max()
                .unwrap_or(0)
        };
        let mut features: Vec<Feature> = Vec::new();
        let mut integral_fbs: Vec<u8> = Vec::new();
        let mut system_obs: Vec<SystemOb> = Vec::new();
        for profile in PROFILES {
            for feature in profile.features {
                if !features.contains(feature) {
                    features.push(*feature);
                }
            }
            for fb in profile.integral_fbs {
                if !integral_fbs.contains(fb) {
                    integral_fbs.push(*fb);
                }
            }
            for ob in profile.system_obs {
                if system_obs.iter().all(|known| known.ob != ob.ob) {
                    system_obs.push(*ob);
                }
            }
        }
        let base = default_for(Dialect::Step5);
        Profile {
            name: "every-profile",
            sizes: Sizes {
                image_bytes: most(|sizes| sizes.image_bytes),
                flag_bytes: most(|sizes| sizes.flag_bytes),
                peripheral_bytes: most(|sizes| sizes.peripheral_bytes),
                timers: most(|sizes| sizes.timers),
                counters: most(|sizes| sizes.counters),
                data_words: most(|sizes| sizes.data_words),
            },
            accumulators: 4,
            bracket_depth: PROFILES
                .iter()
                .map(|profile| profile.bracket_depth)
                .max()
                .unwrap_or(0),
            extended_blocks: true,
            features: features.leak(),
            integral_fbs: integral_fbs.leak(),
            system_obs: system_obs.leak(),
            ..base.clone()
        }
    })
}

/// The largest process image an S7 CPU of awl can be set to, in bytes (the SPEED7 CPUs'; VIPA
/// System 300S CPU manuals, technical data).
pub const MAX_S7_IMAGE_BYTES: u16 = 2048;

/// The S7 CPU variants with larger process images, made as runs ask for them and kept, so a
/// run can keep `&'static Profile` as every other profile.
static RESIZED_IMAGES: Mutex<Vec<&'static Profile>> = Mutex::new(Vec::new());

/// `profile` with process images of `bytes` each, as a hardware configuration sets them (an
/// awlsim project's `nr_inputs`): itself, or its variant when it is an S7 CPU and `bytes` is
/// at most [`MAX_S7_IMAGE_BYTES`]; `None` when the CPU cannot have that many.
pub fn with_image_bytes(profile: &'static Profile, bytes: u16) -> Option<&'static Profile> {
    if bytes == profile.sizes.image_bytes {
        return Some(profile);
    }
    if !profile.runs_step7() || bytes > MAX_S7_IMAGE_BYTES {
        return None;
    }
    let mut made = RESIZED_IMAGES
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    let same = |variant: &&&Profile| {
        variant.name == profile.name
            && variant.accumulators == profile.accumulators
            && variant.sizes.image_bytes == bytes
    };
    if let Some(&variant) = made.iter().find(same) {
        return Some(variant);
    }
    let variant: &'static Profile = Box::leak(Box::new(Profile {
        sizes: Sizes {
            image_bytes: bytes,
            ..profile.sizes
        },
        ..profile.clone()
    }));
    made.push(variant);
    Some(variant)
}

/// The profile of a name or an alias.
pub fn find(name: &str) -> Option<&'static Profile> {
    let name = ALIASES
        .iter()
        .find(|(alias, _)| alias.eq_ignore_ascii_case(name))
        .map_or(name, |(_, target)| target);
    PROFILES
        .iter()
        .find(|profile| profile.name.eq_ignore_ascii_case(name))
}

/// The profiles of S7 CPUs, which run STEP 7 programs.
pub fn step7_profiles() -> Vec<&'static str> {
    PROFILES
        .iter()
        .filter(|profile| profile.runs_step7())
        .map(|profile| profile.name)
        .collect()
}

/// The names of the profiles that have `feature`.
pub fn having(feature: Feature) -> Vec<&'static str> {
    PROFILES
        .iter()
        .filter(|profile| profile.has(feature))
        .map(|profile| profile.name)
        .collect()
}

/// Every profile's name, then the aliases.
pub fn names() -> Vec<&'static str> {
    PROFILES
        .iter()
        .map(|profile| profile.name)
        .chain(ALIASES.iter().map(|(alias, _)| *alias))
        .collect()
}

/// The profiles that have integral FB `fb`, by name.
pub fn with_integral_fb(fb: u8) -> Vec<&'static str> {
    PROFILES
        .iter()
        .filter(|profile| profile.has_integral_fb(fb))
        .map(|profile| profile.name)
        .collect()
}

/// The profiles whose manual documents system OB `ob`, by name.
pub fn with_system_ob(ob: u8) -> Vec<&'static str> {
    PROFILES
        .iter()
        .filter(|profile| profile.system_ob(ob).is_some())
        .map(|profile| profile.name)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aliases_name_the_cpu_most_programs_were_written_for() {
        assert_eq!(find("s5-115u").unwrap().name, "s5-115u-944");
        assert_eq!(find("S5-135U").unwrap().name, "s5-135u-928b");
        assert_eq!(find("s5-155u").unwrap().name, "s5-155u-948");
        assert_eq!(find("s5-100u").unwrap().name, "s5-100u-103");
        assert!(names().contains(&"s5-115u"));
        assert!(ALIASES.iter().all(|(_, target)| find(target).is_some()));
    }

    #[test]
    fn every_profile_has_a_unique_name_and_sane_limits() {
        for profile in PROFILES {
            let same = PROFILES.iter().filter(|other| other.name == profile.name);
            assert_eq!(same.count(), 1, "{}", profile.name);
            let s = &profile.sizes;
            assert!(
                s.image_bytes > 0 && s.flag_bytes > 0 && s.timers > 0,
                "{}",
                profile.name
            );
            assert!(profile.nesting_limit >= 16 && profile.bracket_depth == 7);
            assert!(!profile.rules.is_empty() && !profile.manual.is_empty());
            assert!(profile.timings.bit_image > 0, "{}", profile.name);
            if profile.family == Family::S5 {
                let mut priorities: Vec<u8> =
                    profile.interrupt_obs.iter().map(|ob| ob.priority).collect();
                priorities.dedup();
                assert_eq!(
                    priorities.len(),
                    profile.interrupt_obs.len(),
                    "{}",
                    profile.name
                );
            }
        }
    }

    #[test]
    fn an_s7_cpu_takes_larger_process_images_up_to_the_speed7_s_largest() {
        let speed7 = find("speed7").unwrap();
        let larger = with_image_bytes(speed7, 1024).unwrap();
        assert_eq!(larger.sizes.image_bytes, 1024);
        assert_eq!(larger.sizes.flag_bytes, speed7.sizes.flag_bytes);
        assert!(std::ptr::eq(
            larger,
            with_image_bytes(speed7, 1024).unwrap()
        ));
        assert!(std::ptr::eq(speed7, with_image_bytes(speed7, 256).unwrap()));
        assert!(with_image_bytes(speed7, MAX_S7_IMAGE_BYTES + 1).is_none());
        assert!(with_image_bytes(find("s5-115u").unwrap(), 1024).is_none());
    }

    #[test]
    fn the_s5_profiles_as_their_manuals_list_them() {
        let cpu_944 = find("s5-115u-944").unwrap();
        assert!(cpu_944.has_integral_fb(250) && cpu_944.system_ob(254).is_some());
        assert_eq!(cpu_944.sizes.timers, 256);
        assert_eq!(find("s5-115u-941").unwrap().sizes.timers, 128);
        assert!(find("s5-155u-948").unwrap().system_ob(125).is_some());
        assert!(find("s5-135u-928").unwrap().system_ob(125).is_none());
        assert!(find("s5-135u").unwrap().interrupt_ob(18).is_some());
        assert!(find("s5-115u").unwrap().interrupt_ob(18).is_none());
        assert_eq!(find("s5-135u-922").unwrap().startup_obs, &[20, 21, 22]);
        assert!(!find("sinumerik-840c").unwrap().has_integral_fb(250));
        assert_eq!(with_integral_fb(250).len(), 5);
        assert!(find("s5-135u-928b").unwrap().has(Feature::FloatingPoint));
        assert!(!find("s5-115u-941").unwrap().has(Feature::FloatingPoint));
        let time_controlled = TIME_CONTROLLED_TEXT;
        for profile in PROFILES
            .iter()
            .filter(|profile| profile.family == Family::S5)
        {
            assert!(
                profile
                    .rules
                    .iter()
                    .any(|rule| rule.contains(time_controlled))
            );
        }
    }

    const TIME_CONTROLLED_TEXT: &str = "called at their intervals";
}
