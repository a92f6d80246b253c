//! The S5-135U with CPU 922 (R processor), CPU 928 and CPU 928B.

use super::s5_common::*;
use super::{Family, Feature, InterruptPoints, Nesting, Profile};

const RULES_928B: &[&str] =
    &rules_135u_155u("four accumulators (CPU 928B programming guide, table 3-7)");

/// The CPUs with two accumulators say nothing of them.
const RULES: &[&str] = RULES_928B.split_at(RULES_928B.len() - 1).0;

pub const CPU_922: Profile = Profile {
    name: "s5-135u-922",
    family: Family::S5,
    title: "S5-135U with CPU 922 (R processor)",
    manual: "S5-135U CPU 922 programming guide and S5-135U system manual: organization \
             blocks, interrupt processing, technical data",
    sizes: LARGE_SIZES,
    nesting_limit: 32,
    nesting: Nesting::PerLevel,
    accumulators: 2,
    bracket_depth: 7,
    watchdog_ns: 500_000_000,
    startup_obs: &[20, 21, 22],
    interrupt_obs: INTERRUPTS_135U_155U,
    default_points: InterruptPoints::Block,
    extended_blocks: true,
    features: &[
        Feature::AddConstant,
        Feature::SystemOperations,
        Feature::RegisterOperations,
    ],
    integral_fbs: &[],
    system_obs: SYSTEM_OBS_135U,
    timings: estimated_times(2000, 1_000_000, "CPU 922"),
    rules: RULES,
};

pub const CPU_928: Profile = Profile {
    name: "s5-135u-928",
    title: "S5-135U with CPU 928",
    manual: "S5-135U CPU 928 programming guide and S5-135U system manual: organization \
             blocks, interrupt processing, technical data",
    features: ALL_FEATURES,
    timings: estimated_times(800, 600_000, "CPU 928"),
    rules: RULES,
    ..CPU_922
};

pub const CPU_928B: Profile = Profile {
    name: "s5-135u-928b",
    title: "S5-135U with CPU 928B",
    manual: "S5-135U CPU 928B programming guide and S5-135U system manual: organization \
             blocks, interrupt processing, technical data",
    accumulators: 4,
    timings: super::SINUMERIK_840C_TIMES,
    rules: RULES_928B,
    ..CPU_928
};
