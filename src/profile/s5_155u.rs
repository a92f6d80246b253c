//! The S5-155U with CPU 946/947 and CPU 948.

use super::s5_135u::ALL_FEATURES;
use super::s5_common::*;
use super::{Family, InterruptPoints, Nesting, Profile};

const RULES: &[&str] = &[
    PRIORITY_ORDER_135U_155U,
    PRIORITIES,
    BLOCK_POINTS,
    INTERRUPT_REQUESTS,
    SYSTEM_OB_CALLS,
    STARTUP,
    "four accumulators",
];

pub const CPU_946_947: Profile = Profile {
    name: "s5-155u-946",
    family: Family::S5,
    title: "S5-155U with CPU 946/947",
    manual: "S5-155U CPU 946/947 programming guide: organization blocks, interrupt \
             processing, technical data",
    sizes: LARGE_SIZES,
    nesting_limit: 32,
    nesting: Nesting::PerLevel,
    accumulators: 4,
    bracket_depth: 7,
    watchdog_ns: 500_000_000,
    startup_obs: &[20, 21, 22],
    interrupt_obs: INTERRUPTS_135U_155U,
    default_points: InterruptPoints::Block,
    extended_blocks: true,
    features: ALL_FEATURES,
    integral_fbs: &[],
    system_obs: SYSTEM_OBS_135U,
    timings: estimated_times(
        400,
        500_000,
        "estimates of the CPU 946/947 class (about 0.4 µs per bit operation, 0.5 ms \
         operating-system time)",
    ),
    rules: RULES,
};

pub const CPU_948: Profile = Profile {
    name: "s5-155u-948",
    title: "S5-155U with CPU 948",
    manual: "S5-155U CPU 948 programming guide: organization blocks, special function \
             OBs, interrupt processing, technical data",
    system_obs: SYSTEM_OBS_948,
    timings: estimated_times(
        100,
        300_000,
        "estimates of the CPU 948 class (about 0.1 µs per bit operation, 0.3 ms \
         operating-system time)",
    ),
    ..CPU_946_947
};
