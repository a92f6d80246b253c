//! The S5 CPUs of the S5-95U to S5-155U profiles: the generic engine as it is. Their interrupt
//! OBs and priorities come from the profile, requests from the scenario's `interrupt` events;
//! the time-controlled OBs do not fire on their own (`awl cpus` says so for each profile).

use super::Rules;

#[derive(Debug, Default)]
pub struct S5;

impl Rules for S5 {}
