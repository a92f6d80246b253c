//! The scenario file as TOML, with spans kept for diagnostics.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScenario {
    pub program: Option<Spanned<ProgramList>>,
    pub cpu: Option<Spanned<String>>,
    pub mode: Option<Spanned<String>>,
    pub interrupt_points: Option<Spanned<String>>,
    pub run: Option<Spanned<RawRun>>,
    pub watchdog: Option<Spanned<String>>,
    pub ob13: Option<RawOb13>,
    pub hw_module: Option<Vec<RawHwModule>>,
    pub event: Option<Vec<RawEvent>>,
    pub expect: Option<BTreeMap<String, Spanned<toml::Value>>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum ProgramList {
    One(String),
    Many(Vec<String>),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRun {
    #[serde(rename = "for")]
    pub duration: Option<Spanned<String>>,
    pub cycles: Option<Spanned<u64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOb13 {
    pub interval: Spanned<String>,
    pub delay: Option<Spanned<String>>,
    pub max_delay: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawHwModule {
    pub module: Spanned<u16>,
    pub ob: Spanned<u8>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEvent {
    pub at: Spanned<String>,
    pub set: Option<BTreeMap<String, Spanned<toml::Value>>>,
    pub interrupt: Option<Spanned<String>>,
    pub hw_interrupt: Option<Spanned<RawHardware>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawHardware {
    pub module: u16,
    pub channel: u16,
    pub active_for: Spanned<String>,
}
