//! The S5-115U with CPU 941 to 945, with the integral FBs 240–243, 250 and 251.

use super::s5_common::*;
use super::{Family, Feature, InterruptPoints, Nesting, Profile};

const MANUAL: &str = "S5-115U programmable controller manual: technical data of the CPUs, \
     organization blocks, interrupt processing, integral blocks";

const INTEGRAL_RULE: &str = "integral FBs, used when the program has no FB of that number: \
     FB 240 COD:B4, FB 241 COD:16, FB 242 MUL:16, FB 243 DIV:16, FB 250 RLG:AE (read an \
     analog value and scale it), FB 251 RLG:AA (scale a value and output it) (S5-115U manual, \
     integral blocks)";

/// The rules of an S5-115U CPU whose interrupt OBs rank as `priority_order` says.
const fn rules(priority_order: &'static str) -> [&'static str; 7] {
    [
        priority_order,
        PRIORITIES,
        BLOCK_POINTS,
        INTERRUPT_REQUESTS,
        INTEGRAL_RULE,
        SYSTEM_OB_CALLS,
        STARTUP,
    ]
}

const RULES_941_943: &[&str] = &rules("priority OB 2 > OB 13 > OB 1");

const RULES_944: &[&str] =
    &rules("priority OB 2 > OB 3 > OB 4 > OB 5 > OB 6 > OB 10 > OB 11 > OB 12 > OB 13 > OB 1");

const BASIC_FEATURES: &[Feature] = &[Feature::AddConstant, Feature::SystemOperations];

const CPU_94X: Profile = Profile {
    name: "",
    family: Family::S5,
    title: "",
    manual: MANUAL,
    sizes: MEDIUM_SIZES,
    nesting_limit: 32,
    nesting: Nesting::PerLevel,
    accumulators: 2,
    bracket_depth: 7,
    watchdog_ns: 500_000_000,
    startup_obs: &[21, 22],
    interrupt_obs: SMALL_INTERRUPTS,
    default_points: InterruptPoints::Block,
    extended_blocks: false,
    features: BASIC_FEATURES,
    integral_fbs: INTEGRAL_FBS_115U,
    system_obs: SYSTEM_OBS_115U,
    timings: estimated_times(1600, 1_000_000, "CPU 941/942"),
    rules: RULES_941_943,
};

pub const CPU_941: Profile = Profile {
    name: "s5-115u-941",
    title: "S5-115U with CPU 941",
    ..CPU_94X
};

pub const CPU_942: Profile = Profile {
    name: "s5-115u-942",
    title: "S5-115U with CPU 942",
    ..CPU_94X
};

pub const CPU_943: Profile = Profile {
    name: "s5-115u-943",
    title: "S5-115U with CPU 943",
    timings: estimated_times(1000, 800_000, "CPU 943"),
    ..CPU_94X
};

pub const CPU_944: Profile = Profile {
    name: "s5-115u-944",
    title: "S5-115U with CPU 944",
    sizes: LARGE_SIZES,
    interrupt_obs: INTERRUPTS_115U,
    timings: estimated_times(800, 600_000, "CPU 944"),
    rules: RULES_944,
    ..CPU_94X
};

pub const CPU_945: Profile = Profile {
    name: "s5-115u-945",
    title: "S5-115U with CPU 945",
    features: ALL_FEATURES.split_at(ALL_FEATURES.len() - 1).0,
    timings: estimated_times(100, 300_000, "CPU 945"),
    ..CPU_944
};
