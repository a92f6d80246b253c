//! The scenario file as TOML, with spans kept for diagnostics. Every top-level key, and every
//! entry of `[[event]]`, `[[check]]` and `[[hw_module]]`, is read on its own, so one bad key does not hide
//! the errors of the others.

use std::collections::BTreeMap;

use serde::Deserialize;
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

use super::error::ScenarioError;

/// A table whose keys keep their spans (`set = { "I 0.0" = 1 }`, `[expect]`).
pub type SpannedTable = BTreeMap<Spanned<String>, Spanned<toml::Value>>;

/// The top-level keys of a scenario file.
pub const KEYS: &[&str] = &[
    "program",
    "cpu",
    "mode",
    "interrupt_points",
    "run",
    "watchdog",
    "ob13",
    "ob35",
    "hw_module",
    "event",
    "expect",
    "watch",
    "check",
    "symbols",
    "dialect",
    "extended",
    "clock_memory",
];

#[derive(Debug, Default)]
pub struct RawScenario {
    pub program: Option<Spanned<ProgramList>>,
    /// Assignment lists, relative to the scenario.
    pub symbols: Option<Spanned<ProgramList>>,
    pub cpu: Option<Spanned<String>>,
    /// `"s5"` or `"s7"`: the program's STL dialect.
    pub dialect: Option<Spanned<String>>,
    /// awlsim's test operations are accepted.
    pub extended: Option<bool>,
    pub mode: Option<Spanned<String>>,
    pub interrupt_points: Option<Spanned<String>>,
    pub run: Option<Spanned<RawRun>>,
    pub watchdog: Option<Spanned<String>>,
    pub ob13: Option<Spanned<RawOb13>>,
    pub ob35: Option<Spanned<RawOb35>>,
    pub hw_module: Vec<Spanned<RawHwModule>>,
    /// The S7 CPU's clock memory byte (`MB n`).
    pub clock_memory: Option<Spanned<i64>>,
    pub event: Vec<Spanned<RawEvent>>,
    pub expect: SpannedTable,
    pub watch: Vec<Spanned<String>>,
    /// `[[check]]` tables: `at` and operands.
    pub check: Vec<Spanned<SpannedTable>>,
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

/// `[ob35]`: the cyclic interrupt OB 35 of an S7 CPU.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOb35 {
    pub interval: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawHwModule {
    pub module: Spanned<u16>,
    pub ob: Spanned<u8>,
    /// The module's logical base address.
    pub address: Option<Spanned<u16>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEvent {
    pub at: Spanned<String>,
    /// Repeats the event this often, `count` times or until `until`.
    pub every: Option<Spanned<String>>,
    pub count: Option<Spanned<u64>>,
    pub until: Option<Spanned<String>>,
    pub set: Option<SpannedTable>,
    pub interrupt: Option<Spanned<String>>,
    pub hw_interrupt: Option<Spanned<RawHardware>>,
    pub station: Option<Spanned<RawStation>>,
}

/// A DP station's failure (`failed = true`) or return.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStation {
    pub number: u8,
    pub failed: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawHardware {
    pub module: u16,
    pub channel: u16,
    pub active_for: Spanned<String>,
}

fn span_of(range: std::ops::Range<usize>) -> miette::SourceSpan {
    (range.start, range.end - range.start).into()
}

/// A TOML error at its place (or at `fallback` when it has none).
fn toml_error(error: toml::de::Error, fallback: std::ops::Range<usize>) -> ScenarioError {
    ScenarioError::Syntax {
        message: error.message().to_string(),
        at: Some(span_of(error.span().unwrap_or(fallback))),
    }
}

fn read<T: DeserializeOwned>(value: &Spanned<DeValue<'_>>) -> Result<T, ScenarioError> {
    T::deserialize(ValueDeserializer::from(value.clone())).map_err(|e| toml_error(e, value.span()))
}

/// Each element of an array of tables, read on its own.
fn read_each<T: DeserializeOwned>(
    value: &Spanned<DeValue<'_>>,
    errors: &mut Vec<ScenarioError>,
) -> Vec<Spanned<T>> {
    let Some(items) = value.get_ref().as_array() else {
        errors.push(ScenarioError::Syntax {
            message: "expected an array of tables, e.g. `[[event]]`".into(),
            at: Some(span_of(value.span())),
        });
        return Vec::new();
    };
    items
        .iter()
        .filter_map(|item| match read::<T>(item) {
            Ok(value) => Some(Spanned::new(item.span(), value)),
            Err(error) => {
                errors.push(error);
                None
            }
        })
        .collect()
}

/// Reads the file: what could be read, and every error found on the way.
pub fn parse(text: &str) -> (RawScenario, Vec<ScenarioError>) {
    let (table, syntax) = DeTable::parse_recoverable(text);
    let mut errors: Vec<ScenarioError> = syntax
        .into_iter()
        .map(|error| toml_error(error, 0..0))
        .collect();
    let mut raw = RawScenario::default();
    for (key, value) in table.get_ref() {
        let mut keep = |result: Result<(), ScenarioError>| {
            if let Err(error) = result {
                errors.push(error);
            }
        };
        match key.get_ref().as_ref() {
            "program" => keep(read(value).map(|v| raw.program = Some(v))),
            "symbols" => keep(read(value).map(|v| raw.symbols = Some(v))),
            "cpu" => keep(read(value).map(|v| raw.cpu = Some(v))),
            "dialect" => keep(read(value).map(|v| raw.dialect = Some(v))),
            "extended" => keep(read(value).map(|v| raw.extended = Some(v))),
            "mode" => keep(read(value).map(|v| raw.mode = Some(v))),
            "interrupt_points" => keep(read(value).map(|v| raw.interrupt_points = Some(v))),
            "run" => keep(read(value).map(|v| raw.run = Some(v))),
            "watchdog" => keep(read(value).map(|v| raw.watchdog = Some(v))),
            "ob13" => keep(read(value).map(|v| raw.ob13 = Some(v))),
            "ob35" => keep(read(value).map(|v| raw.ob35 = Some(v))),
            "clock_memory" => keep(read(value).map(|v| raw.clock_memory = Some(v))),
            "expect" => keep(read(value).map(|v| raw.expect = v)),
            "watch" => keep(read(value).map(|v| raw.watch = v)),
            "hw_module" => raw.hw_module = read_each(value, &mut errors),
            "event" => raw.event = read_each(value, &mut errors),
            "check" => raw.check = read_each(value, &mut errors),
            other => errors.push(ScenarioError::UnknownKey {
                key: other.to_string(),
                at: span_of(key.span()),
                help: super::did_you_mean(other, KEYS.iter().copied()).map(|known| {
                    format!("did you mean `{known}`? `awl help scenario` lists the keys")
                }),
            }),
        }
    }
    (raw, errors)
}
