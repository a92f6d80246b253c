//! The most one input may cost: its length, the operations and cycles a run may take, the
//! events a scenario may hold, and how often a diagnostic is rendered in full.

use std::hash::{DefaultHasher, Hasher};

use awl::profile::{Profile, Timings};
use awl::vm::cycle::RunLimit;

/// The longest input a target reads; the bytes after are cut off. The sample programs and
/// scenarios are under 2 KB, and parsing and checking cost about as much as the input is long.
pub const MAX_INPUT_BYTES: usize = 4096;

/// How many operations of the CPU's fastest kind one cycle (its interrupts included) may run
/// before the watchdog stops the CPU: a run's simulated time, and so its operations, are
/// bounded even for an endless loop on the SPEED7, whose operations take 10 ns.
pub const OPS_PER_CYCLE: u64 = 20_000;

/// The most cycles a scenario's run may take (a scenario may ask for more, or for a duration
/// that holds more).
pub const MAX_CYCLES: u64 = 20;

/// The longest simulated time a scenario's run may ask for.
const MAX_DURATION_NS: u64 = 20_000_000;

/// The most events a scenario's repetitions (`every`) may add up to.
pub const MAX_EVENTS: usize = 1_000;

/// One input in this many has its diagnostics and STOP report rendered in full; the others
/// check them cheaply (see [`crate::check_diagnostics`]).
pub const RENDER_ONE_IN: u64 = 16;

/// The input as far as a target reads it.
pub fn bounded(bytes: &[u8]) -> &[u8] {
    &bytes[..bytes.len().min(MAX_INPUT_BYTES)]
}

/// Whether this input's diagnostics are rendered in full. The choice is a hash of the input,
/// so a replayed input is rendered as it was when it was found.
pub fn renders_in_full(bytes: &[u8]) -> bool {
    let mut hasher = DefaultHasher::new();
    hasher.write(bytes);
    hasher.finish().is_multiple_of(RENDER_ONE_IN)
}

/// The watchdog of a fuzzed run on `profile`: the time of [`OPS_PER_CYCLE`] of its fastest
/// operations.
pub fn watchdog_ns(profile: &Profile) -> u64 {
    OPS_PER_CYCLE * fastest_op_ns(&profile.timings)
}

/// The shortest time an operation takes on this CPU: no op costs less (`compiler::cost`).
fn fastest_op_ns(t: &Timings) -> u64 {
    let each = [
        t.bit_image,
        t.bit_data,
        t.bit_timer_counter,
        t.load_byte,
        t.load_word,
        t.load_double,
        t.load_constant,
        t.load_data,
        t.load_peripheral,
        t.timer_counter,
        t.add_sub,
        t.multiply,
        t.divide,
        t.compare,
        t.word_logic,
        t.accumulator,
        t.jump,
        t.block_call,
        t.block_end,
        t.open_db,
        t.other,
    ];
    u64::from(each.into_iter().min().unwrap_or(1).max(1))
}

/// The run a scenario asks for, at most [`MAX_DURATION_NS`] long (the run also stops after
/// [`MAX_CYCLES`] cycles, see [`crate::Setup`]).
pub fn capped(limit: Option<RunLimit>) -> RunLimit {
    match limit {
        Some(RunLimit::Cycles(cycles)) => RunLimit::Cycles(cycles.min(MAX_CYCLES)),
        Some(RunLimit::Duration(ns)) => RunLimit::Duration(ns.min(MAX_DURATION_NS)),
        None => RunLimit::Cycles(3),
    }
}
