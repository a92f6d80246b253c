//! The S5-95U and the S5-100U with CPU 103.

use super::s5_common::*;
use super::{Family, Feature, InterruptPoints, Nesting, Profile};

const SMALL_RULES: &[&str] = &[
    "priority OB 2 > OB 13 > OB 1",
    PRIORITIES,
    BLOCK_POINTS,
    INTERRUPT_REQUESTS,
    SYSTEM_OB_CALLS,
    STARTUP,
    "block nesting depth at most 16, interrupt levels included",
];

const SMALL: Profile = Profile {
    name: "",
    family: Family::S5,
    title: "",
    manual: "",
    sizes: SMALL_SIZES,
    nesting_limit: 16,
    nesting: Nesting::WholeCpu,
    accumulators: 2,
    bracket_depth: 7,
    watchdog_ns: 300_000_000,
    startup_obs: &[21, 22],
    interrupt_obs: SMALL_INTERRUPTS,
    default_points: InterruptPoints::Block,
    extended_blocks: false,
    features: &[Feature::AddConstant],
    integral_fbs: &[],
    system_obs: SYSTEM_OBS_SMALL,
    timings: estimated_times(2000, 1_000_000, "S5-95U"),
    rules: SMALL_RULES,
};

pub const S5_95U: Profile = Profile {
    name: "s5-95u",
    title: "S5-95U",
    manual: "S5-95U programmable controller system manual: technical data, organization \
             blocks, interrupt processing",
    ..SMALL
};

pub const S5_100U_103: Profile = Profile {
    name: "s5-100u-103",
    title: "S5-100U with CPU 103",
    manual: "S5-100U programmable controller (CPU 100/102/103) system manual: technical \
             data, organization blocks, interrupt processing",
    timings: estimated_times(1600, 1_000_000, "CPU 103"),
    ..SMALL
};
