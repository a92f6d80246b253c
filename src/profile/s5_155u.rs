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
    timings: estimated_times(400, 500_000, "CPU 946/947"),
    rules: RULES,
    ..super::s5_135u::CPU_928B
};

pub const CPU_948: Profile = Profile {
    name: "s5-155u-948",
    title: "S5-155U with CPU 948",
    manual: "S5-155U CPU 948 programming guide: organization blocks, special function \
             OBs, interrupt processing, technical data",
    system_obs: SYSTEM_OBS_948,
    timings: estimated_times(100, 300_000, "CPU 948"),
    ..CPU_946_947
};
