//! How the CPU names itself to a client (order code, module name).

use crate::profile::Profile;

/// The SPEED7 CPUs are configured in STEP 7 as this S7-300 CPU (VIPA System 300S SPEED7 CPU
/// manual, Hardware configuration: "CPU 315-2 PN/DP"), and report its order code so that
/// HMIs take them for it.
const SPEED7_AS: &str = "6ES7 315-2EH14-0AB0";

/// The order code: the S7-300 CPU a SPEED7 stands for; on an S5 profile, which no S7 client
/// can know, `AWL` and the profile's name (the S5 CPUs spoke no S7comm).
pub fn order_code(profile: &Profile) -> String {
    if profile.name == "speed7" {
        SPEED7_AS.to_string()
    } else {
        format!("AWL {}", profile.name.to_uppercase())
    }
}
