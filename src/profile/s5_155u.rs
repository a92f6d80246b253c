//! The S5-155U with CPU 946/947 and CPU 948.

use super::Profile;
use super::s5_common::*;

const RULES: &[&str] = &rules_135u_155u("four accumulators");

/// A 135U CPU 928B in all but its name, manual, speed and rules.
pub const CPU_946_947: Profile = Profile {
    name: "s5-155u-946",
    title: "S5-155U with CPU 946/947",
    manual: "S5-155U CPU 946/947 programming guide: organization blocks, interrupt \
             processing, technical data",
    timings: estimated_times(
        400,
        500_000,
        "estimates of the CPU 946/947 class (about 0.4 µs per bit operation, 0.5 ms \
         operating-system time)",
    ),
    rules: RULES,
    ..super::s5_135u::CPU_928B
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
