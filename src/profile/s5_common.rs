//! What the S5 profiles share: operand ranges, the time table scaled from one figure, the
//! interrupt OB lists, the integral FBs and the rules `awl cpus` prints for every S5 CPU.

use super::{Feature, InterruptOb, Sizes, SystemOb, TimesSource, Timings};

/// Every S5 operation group: the S5-135U and S5-155U CPUs have them all. The S5-115U CPU 945
/// lacks the last, the register operations.
pub const ALL_FEATURES: &[Feature] = &[
    Feature::FloatingPoint,
    Feature::DoubleBcd,
    Feature::BcdConversions,
    Feature::AddConstant,
    Feature::SystemOperations,
    Feature::RegisterOperations,
];

/// I/Q 0…127, F 0…255, P 0…255, T and C 0…127, DW 0…255: the smallest S5 CPUs.
pub const SMALL_SIZES: Sizes = Sizes {
    image_bytes: 128,
    flag_bytes: 256,
    peripheral_bytes: 256,
    timers: 128,
    counters: 128,
    data_words: 256,
};

/// The S5-115U CPU 941–943: 128 timers and counters, data blocks up to 2048 words.
pub const MEDIUM_SIZES: Sizes = Sizes {
    timers: 128,
    counters: 128,
    data_words: 2048,
    ..SMALL_SIZES
};

/// The CPU 944 and up: 256 timers and counters.
pub const LARGE_SIZES: Sizes = Sizes {
    timers: 256,
    counters: 256,
    ..MEDIUM_SIZES
};

/// A time table built from the time of one bit operation on I/Q/F, with the other operations
/// in the proportions of the CPU 928B's table (SINUMERIK 840C PLC manual); every figure it
/// gives is an estimate of the CPU class `class`, and the table's source says so.
pub const fn estimated_times(bit_image: u32, cycle_overhead: u32, class: &'static str) -> Timings {
    Timings {
        bit_image,
        bit_data: scale(bit_image, 6000),
        bit_timer_counter: scale(bit_image, 2100),
        load_byte: scale(bit_image, 1400),
        load_word: scale(bit_image, 1650),
        load_double: scale(bit_image, 2800),
        load_constant: bit_image,
        load_data: scale(bit_image, 2600),
        load_peripheral: scale(bit_image, 4400),
        timer_counter: scale(bit_image, 10_500),
        add_sub: scale(bit_image, 1650),
        multiply: scale(bit_image, 9500),
        divide: scale(bit_image, 17_500),
        compare: scale(bit_image, 2100),
        word_logic: scale(bit_image, 1650),
        accumulator: bit_image,
        jump: scale(bit_image, 1750),
        block_call: scale(bit_image, 11_000),
        block_end: scale(bit_image, 5600),
        open_db: scale(bit_image, 6100),
        other: bit_image,
        cycle_overhead,
        data_cycle: 0,
        process_image_per_byte: scale(bit_image, 200),
        input_delay: 0,
        source: TimesSource::Estimated(class),
    }
}

const fn scale(bit_image: u32, per_mille: u32) -> u32 {
    bit_image * per_mille / 1000
}

const fn process(ob: u8, priority: u8) -> InterruptOb {
    InterruptOb::requested(ob, priority, "process interrupt")
}

/// A time-controlled OB, called every `every_ms` once the program has it.
const fn timed(ob: u8, priority: u8, summary: &'static str, every_ms: u32) -> InterruptOb {
    InterruptOb {
        ob,
        priority,
        summary,
        every_ms,
    }
}

const CLOCK: InterruptOb = InterruptOb::requested(6, 11, "clock-time interrupt");

/// S5-95U, S5-100U and S5-115U CPU 941–943: one process interrupt OB and OB 13.
pub const SMALL_INTERRUPTS: &[InterruptOb] = &[
    process(2, 3),
    timed(13, 2, "time-controlled, every 100 ms", 100),
];

/// S5-115U CPU 944 and 945: process interrupts A–D, the clock and OB 10–13, the first nine
/// of the S5-135U's.
pub const INTERRUPTS_115U: &[InterruptOb] = INTERRUPTS_135U_155U.split_at(9).0;

/// The priorities of [`INTERRUPTS_135U_155U`], as a rule line.
pub const PRIORITY_ORDER_135U_155U: &str = "priority OB 2 > OB 3 > OB 4 > OB 5 > OB 6 > OB 10 > \
     OB 11 > … > OB 18 > OB 1";

/// S5-135U and S5-155U: process interrupts A–D, the clock and OB 10–18.
pub const INTERRUPTS_135U_155U: &[InterruptOb] = &[
    process(2, 15),
    process(3, 14),
    process(4, 13),
    process(5, 12),
    CLOCK,
    timed(10, 10, "time-controlled, every 10 ms", 10),
    timed(11, 9, "time-controlled, every 20 ms", 20),
    timed(12, 8, "time-controlled, every 50 ms", 50),
    timed(13, 7, "time-controlled, every 100 ms", 100),
    timed(14, 6, "time-controlled, every 200 ms", 200),
    timed(15, 5, "time-controlled, every 500 ms", 500),
    timed(16, 4, "time-controlled, every 1 s", 1000),
    timed(17, 3, "time-controlled, every 2 s", 2000),
    timed(18, 2, "time-controlled, every 5 s", 5000),
];

/// FB 240–243, 250 and 251, built into the S5-115U.
pub const INTEGRAL_FBS_115U: &[u8] = &[240, 241, 242, 243, 250, 251];

const fn system(ob: u8, summary: &'static str) -> SystemOb {
    SystemOb { ob, summary }
}

pub const TIME_LOOP: SystemOb = system(160, "time loop");
pub const PID: SystemOb = system(251, "PID control algorithm");
pub const SCAN_TRIGGER: SystemOb = system(31, "retrigger the scan time monitor");

pub const SYSTEM_OBS_SMALL: &[SystemOb] = &[SCAN_TRIGGER, PID];

pub const SYSTEM_OBS_115U: &[SystemOb] = &[
    SCAN_TRIGGER,
    TIME_LOOP,
    PID,
    system(254, "read in data blocks"),
    system(255, "copy data blocks"),
];

/// The CPU 948's system OBs: its own four, then the S5-135U's.
pub const SYSTEM_OBS_948: &[SystemOb] = &[
    system(121, "set and read the system clock"),
    system(122, "disable and enable interrupts"),
    system(124, "delete STEP 5 blocks"),
    system(125, "generate STEP 5 blocks"),
    TIME_LOOP,
    system(170, "read the block stack"),
    system(190, "transfer flags to a data block"),
    system(191, "transfer a data block to flags"),
    system(221, "set the scan time monitor"),
    system(222, "restart the scan time monitor"),
    system(223, "compare the start-up types"),
    PID,
    system(254, "read in data blocks"),
    system(255, "copy data blocks"),
];

pub const SYSTEM_OBS_135U: &[SystemOb] = SYSTEM_OBS_948.split_at(4).1;

/// The rules of the S5-135U and S5-155U CPUs, the last one what their accumulators do.
pub const fn rules_135u_155u(accumulators: &'static str) -> [&'static str; 7] {
    [
        PRIORITY_ORDER_135U_155U,
        PRIORITIES,
        BLOCK_POINTS,
        INTERRUPT_REQUESTS,
        SYSTEM_OB_CALLS,
        STARTUP,
        accumulators,
    ]
}

/// The rules every S5 profile shares, after its own.
pub const INTERRUPT_REQUESTS: &str = "the time-controlled OBs the program has are called at \
     their intervals from the start of RUN (a call while the last one of the same OB is still \
     pending is lost); process interrupts and the clock-time interrupt run when a scenario's \
     `interrupt` event requests them, and an event may request a time-controlled OB as well";
pub const PRIORITIES: &str = "a pending request is serviced at the next interrupt point when \
     its OB's priority is above the running level's; of several, the highest first; a second \
     request for an OB still pending is lost";
pub const BLOCK_POINTS: &str = "interrupt points: block boundaries (block calls and ends) and \
     the cycle's points by default; `interrupt_points = \"operation\"` in a scenario makes every \
     operation one, as the CPU's setting for interruption at operation boundaries does";
pub const SYSTEM_OB_CALLS: &str = "`JU OB n` of a system OB the manual lists is accepted by \
     `check`; awl does not simulate system OBs: running one is a STOP naming it";
pub const STARTUP: &str = "the run starts with the first start-up OB of the list that the \
     program has";
