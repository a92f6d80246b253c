//! The scenario file as TOML, with spans kept for diagnostics. Every key of the file and of each
//! of its tables (`run`, `[ob13]`, `[[event]]`, …) is read on its own against that table's keys,
//! so one bad key does not hide the errors of the others, and each error is told in the format's
//! words: what the key takes, with an example, or the key a wrong one stands for: the closest in
//! spelling, else the one it means in other words (`runtime` → `run`, `profile` → `cpu`).

use std::collections::BTreeMap;
use std::ops::Range;

use serde::Deserialize;
use serde::de::DeserializeOwned;
use toml::Spanned;
use toml::de::{DeString, DeTable, DeValue, ValueDeserializer};

use super::error::ScenarioError;

/// A table whose keys keep their spans (`set = { "I 0.0" = 1 }`, `[expect]`).
pub type SpannedTable = BTreeMap<Spanned<String>, Spanned<toml::Value>>;

/// A key of a scenario table: what its value is, in the words `awl help scenario` uses, a line
/// that gives one, and the words a user may write for it instead (lower case).
pub struct Key {
    pub name: &'static str,
    pub takes: &'static str,
    pub example: &'static str,
    pub meant_by: &'static [&'static str],
}

/// A table of the scenario format, as the user writes it, and its keys.
pub struct Table {
    /// `[[event]]`, `run`; empty for the file's top level.
    pub name: &'static str,
    pub keys: &'static [Key],
}

const fn key(name: &'static str, takes: &'static str, example: &'static str) -> Key {
    Key {
        name,
        takes,
        example,
        meant_by: &[],
    }
}

impl Key {
    /// The key, taken for each of `words` written in its place.
    const fn meant_by(self, words: &'static [&'static str]) -> Key {
        Key {
            meant_by: words,
            ..self
        }
    }
}

pub const DURATION: &str = "a duration in quotes, with its unit";

/// A TOML value's kind (as `type_str` names it) in the user's words.
pub fn found(kind: &str) -> &'static str {
    match kind {
        "string" => "a string",
        "integer" => "a whole number",
        "float" => "a decimal number",
        "boolean" => "true or false",
        "datetime" => "a date or time",
        "array" => "a list",
        _ => "a table",
    }
}

/// The top level of a scenario file.
pub const SCENARIO: Table = Table {
    name: "",
    keys: &[
        key(
            "program",
            "a program file in quotes, or a list of them",
            "`program = [\"conveyor.awl\"]`",
        )
        .meant_by(&[
            "source", "sources", "file", "files", "awl", "project", "code",
        ]),
        key(
            "symbols",
            "an assignment list or symbol table in quotes, or a list of them",
            "`symbols = [\"symbols.seq\"]`",
        )
        .meant_by(&[
            "symbol_table",
            "assignments",
            "assignment_list",
            "seq",
            "tags",
        ]),
        key(
            "cpu",
            "a CPU profile in quotes (`awl cpus`)",
            "`cpu = \"s5-115u\"`",
        )
        .meant_by(&[
            "profile",
            "plc",
            "processor",
            "cpu_type",
            "model",
            "target",
            "device",
        ]),
        key("dialect", "\"s5\" or \"s7\"", "`dialect = \"s7\"`")
            .meant_by(&["language", "step", "stl"]),
        key("extended", "true or false", "`extended = true`").meant_by(&[
            "extensions",
            "awlsim",
            "test_operations",
        ]),
        key("mode", "\"normal\" or \"special\"", "`mode = \"special\"`")
            .meant_by(&["operating_mode", "special"]),
        key(
            "interrupt_points",
            "\"block\" or \"operation\"",
            "`interrupt_points = \"operation\"`",
        )
        .meant_by(&["points", "preemption"]),
        key(
            "run",
            "a table with `for` (a duration) or `cycles` (a count)",
            "`run = { for = \"100ms\" }` or `run = { cycles = 20 }`",
        )
        .meant_by(&[
            "runtime", "run_time", "time", "duration", "length", "limit", "for", "cycles",
        ]),
        key("watchdog", DURATION, "`watchdog = \"300ms\"`").meant_by(&[
            "cycle_time",
            "scan_time",
            "max_cycle",
            "max_cycle_time",
            "cycle_limit",
            "timeout",
        ]),
        key("min_cycle", DURATION, "`min_cycle = \"10ms\"`").meant_by(&[
            "min_cycle_time",
            "minimum_cycle",
            "minimum_cycle_time",
        ]),
        key("clock_memory", "a flag byte number", "`clock_memory = 100`").meant_by(&[
            "clock",
            "clock_byte",
            "clock_flags",
            "taktmerker",
        ]),
        key(
            "ob13",
            "a table `[ob13]` with `interval`",
            "`[ob13]` with `interval = \"100ms\"`",
        ),
        key(
            "ob35",
            "a table `[ob35]` with `interval`",
            "`[ob35]` with `interval = \"100ms\"`",
        )
        .meant_by(&["cyclic_interrupt"]),
        key(
            "retentive",
            "a table `[retentive]` with `flag_bytes`, `timers`, `counters`, `data_blocks`",
            "`[retentive]` with `flag_bytes = 16`",
        )
        .meant_by(&["retain", "retentivity", "remanent", "remanence"]),
        key(
            "hw_module",
            "`[[hw_module]]` tables with `module` and `ob`",
            "`[[hw_module]]` with `module = 4` and `ob = 40`",
        )
        .meant_by(&["module", "modules", "hardware"]),
        key(
            "interrupt_input",
            "`[[interrupt_input]]` tables with `input` and `ob`, or `module` and `channel`",
            "`[[interrupt_input]]` with `input = \"I 8.0\"` and `ob = 2`",
        )
        .meant_by(&["edge", "edges"]),
        key(
            "event",
            "`[[event]]` tables with `at` and what happens",
            "`[[event]]` with `at = \"25us\"` and `interrupt = \"OB 3\"`",
        )
        .meant_by(&[
            "at",
            "set",
            "interrupt",
            "interrupts",
            "inputs",
            "stimuli",
            "schedule",
            "actions",
            "steps",
        ]),
        key(
            "expect",
            "a table `[expect]` of operands and their values",
            "`[expect]` with `\"Q 4.0\" = 1`",
        )
        .meant_by(&[
            "expectations",
            "assert",
            "asserts",
            "result",
            "results",
            "outputs",
            "verify",
        ]),
        key(
            "watch",
            "a list of operands in quotes",
            "`watch = [\"Q 4.0\", \"FW 10\"]`",
        )
        .meant_by(&["monitor", "observe", "show", "variables"]),
        key(
            "check",
            "`[[check]]` tables with `at` and operands",
            "`[[check]]` with `at = \"250ms\"` and `\"Q 4.0\" = 1`",
        )
        .meant_by(&["checkpoint", "checkpoints"]),
        key(
            "modbus",
            "a table `[modbus]` of where the Modbus tables start",
            "`[modbus]` with `coils = \"I 0.0\"`",
        )
        .meant_by(&["modbus_map", "registers"]),
    ],
};

const RUN: Table = Table {
    name: "`run`",
    keys: &[
        key("for", DURATION, "`run = { for = \"100ms\" }`")
            .meant_by(&["duration", "time", "length", "runtime"]),
        key(
            "cycles",
            "a whole number of cycles",
            "`run = { cycles = 20 }`",
        )
        .meant_by(&["count", "scans", "loops"]),
    ],
};

const OB13: Table = Table {
    name: "[ob13]",
    keys: &[
        key("interval", DURATION, "`interval = \"100ms\"`"),
        key("delay", DURATION, "`delay = \"1ms\"`"),
        key("max_delay", DURATION, "`max_delay = \"2ms\"`"),
    ],
};

const OB35: Table = Table {
    name: "[ob35]",
    keys: &[key("interval", DURATION, "`interval = \"100ms\"`")],
};

const RETENTIVE: Table = Table {
    name: "[retentive]",
    keys: &[
        key(
            "flag_bytes",
            "the number of retentive flag bytes from FB 0 / MB 0",
            "`flag_bytes = 16`",
        )
        .meant_by(&["flags", "memory_bytes", "merker", "markers"]),
        key(
            "timers",
            "the number of retentive timers from T 0",
            "`timers = 0`",
        ),
        key(
            "counters",
            "the number of retentive counters from C 0",
            "`counters = 8`",
        ),
        key(
            "data_blocks",
            "whether the data blocks are retentive",
            "`data_blocks = true`",
        )
        .meant_by(&["dbs", "db"]),
    ],
};

const HW_MODULE: Table = Table {
    name: "[[hw_module]]",
    keys: &[
        key("module", "a module number, 0 to 65535", "`module = 4`"),
        key("ob", "the OB number 40 or 41", "`ob = 40`"),
        key(
            "address",
            "a logical base address, 0 to 65535",
            "`address = 256`",
        ),
    ],
};

const BIT_OPERAND: &str = "a bit operand in quotes";
const WORD_OPERAND: &str = "a word operand in quotes";

const MODBUS: Table = Table {
    name: "[modbus]",
    keys: &[
        key(
            "discrete_inputs",
            BIT_OPERAND,
            "`discrete_inputs = \"I 0.0\"`",
        ),
        key("coils", BIT_OPERAND, "`coils = \"Q 0.0\"`"),
        key(
            "input_registers",
            WORD_OPERAND,
            "`input_registers = \"IW 0\"`",
        ),
        key(
            "holding_registers",
            WORD_OPERAND,
            "`holding_registers = \"MW 0\"`",
        ),
    ],
};

const INTERRUPT_INPUT: Table = Table {
    name: "[[interrupt_input]]",
    keys: &[
        key("input", "an input bit in quotes", "`input = \"I 8.0\"`"),
        key(
            "edge",
            "\"rising\", \"falling\" or \"both\"",
            "`edge = \"falling\"`",
        ),
        key("ob", "an interrupt OB number", "`ob = 2`"),
        key("module", "a module number, 0 to 65535", "`module = 4`"),
        key("channel", "a channel number, 0 to 65535", "`channel = 1`"),
    ],
};

const EVENT: Table = Table {
    name: "[[event]]",
    keys: &[
        key("at", DURATION, "`at = \"100ms\"`").meant_by(&["time", "when", "t"]),
        key("every", DURATION, "`every = \"10ms\"`").meant_by(&["repeat", "period", "interval"]),
        key("count", "a whole number of times", "`count = 5`").meant_by(&["times"]),
        key("until", DURATION, "`until = \"1s\"`").meant_by(&["end", "till", "to"]),
        key(
            "set",
            "a table of operands in quotes and their values",
            "`set = { \"I 0.0\" = 1 }`",
        )
        .meant_by(&["inputs", "values", "write", "force"]),
        key(
            "interrupt",
            "an interrupt OB in quotes",
            "`interrupt = \"OB 3\"`",
        )
        .meant_by(&["ob", "request"]),
        key(
            "hw_interrupt",
            "a table with `module`, `channel` and `active_for`",
            "`hw_interrupt = { module = 4, channel = 1, active_for = \"200us\" }`",
        )
        .meant_by(&["hardware_interrupt", "hardware", "alarm"]),
        key(
            "station",
            "a table with `number` and `failed`",
            "`station = { number = 3, failed = true }`",
        )
        .meant_by(&["dp_station", "slave"]),
    ],
};

const HW_INTERRUPT: Table = Table {
    name: "`hw_interrupt`",
    keys: &[
        key("module", "a module number, 0 to 65535", "`module = 4`"),
        key("channel", "a channel number, 0 to 65535", "`channel = 1`"),
        key("active_for", DURATION, "`active_for = \"200us\"`"),
    ],
};

const STATION: Table = Table {
    name: "`station`",
    keys: &[
        key("number", "a DP station number, 0 to 255", "`number = 3`"),
        key(
            "failed",
            "true (the station fails) or false (it returns)",
            "`failed = true`",
        ),
    ],
};

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
    pub interrupt_points: Option<Spanned<String>>,
    pub run: Option<Spanned<RawRun>>,
    pub watchdog: Option<Spanned<String>>,
    pub cpu_keys: CpuKeys,
    /// `[[interrupt_input]]`: input bits whose edges raise interrupts.
    pub interrupt_input: Vec<Spanned<RawInterruptInput>>,
    pub event: Vec<Spanned<RawEvent>>,
    pub expect: SpannedTable,
    pub watch: Vec<Spanned<String>>,
    /// `[[check]]` tables: `at` and operands.
    pub check: Vec<Spanned<SpannedTable>>,
    pub modbus: RawModbus,
}

/// The keys that belong to some CPUs only, as written: checked once the run's CPU is known.
#[derive(Debug, Default)]
pub struct CpuKeys {
    pub mode: Option<Spanned<String>>,
    pub ob13: Option<Spanned<RawOb13>>,
    pub ob35: Option<Spanned<RawOb35>>,
    pub retentive: Option<Spanned<RawRetentive>>,
    pub hw_module: Vec<Spanned<RawHwModule>>,
    /// S7: the minimum cycle time.
    pub min_cycle: Option<Spanned<String>>,
    /// The S7 CPU's clock memory byte (`MB n`).
    pub clock_memory: Option<Spanned<i64>>,
}

/// `[modbus]`: the operand each Modbus table starts at, as written.
#[derive(Debug, Default)]
pub struct RawModbus {
    pub discrete_inputs: Option<Spanned<String>>,
    pub coils: Option<Spanned<String>>,
    pub input_registers: Option<Spanned<String>>,
    pub holding_registers: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum ProgramList {
    One(String),
    Many(Vec<String>),
}

#[derive(Debug)]
pub struct RawRun {
    pub duration: Option<Spanned<String>>,
    pub cycles: Option<Spanned<u64>>,
}

#[derive(Debug)]
pub struct RawOb13 {
    pub interval: Spanned<String>,
    pub delay: Option<Spanned<String>>,
    pub max_delay: Option<Spanned<String>>,
}

/// `[retentive]`: the memory kept through a power cycle, as a hardware configuration sets it.
#[derive(Debug)]
pub struct RawRetentive {
    pub flag_bytes: Option<Spanned<u16>>,
    pub timers: Option<Spanned<u16>>,
    pub counters: Option<Spanned<u16>>,
    pub data_blocks: Option<bool>,
}

/// `[ob35]`: the cyclic interrupt OB 35 of an S7 CPU.
#[derive(Debug)]
pub struct RawOb35 {
    pub interval: Option<Spanned<String>>,
}

#[derive(Debug)]
pub struct RawHwModule {
    pub module: Spanned<u16>,
    pub ob: Spanned<u8>,
    /// The module's logical base address.
    pub address: Option<Spanned<u16>>,
}

/// An input bit tied to an interrupt: an OB (S5) or a module's channel (SPEED7).
#[derive(Debug)]
pub struct RawInterruptInput {
    pub input: Spanned<String>,
    pub edge: Option<Spanned<String>>,
    pub ob: Option<Spanned<u8>>,
    pub module: Option<Spanned<u16>>,
    pub channel: Option<Spanned<u16>>,
}

#[derive(Debug)]
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
#[derive(Debug)]
pub struct RawStation {
    pub number: u8,
    pub failed: bool,
}

#[derive(Debug)]
pub struct RawHardware {
    pub module: u16,
    pub channel: u16,
    pub active_for: Spanned<String>,
}

fn span_of(range: Range<usize>) -> miette::SourceSpan {
    (range.start, range.end - range.start).into()
}

/// A TOML syntax error at its place (or at `fallback` when it has none).
fn syntax_error(error: toml::de::Error, fallback: Range<usize>) -> ScenarioError {
    ScenarioError::Syntax {
        message: error.message().to_string(),
        at: Some(span_of(error.span().unwrap_or(fallback))),
    }
}

impl Table {
    fn key(&self, name: &str) -> &'static Key {
        self.keys
            .iter()
            .find(|key| key.name == name)
            .expect("a key of the table")
    }

    /// How a key of this table is named in a message: `run`, `at` in [[event]].
    fn named(&self, key: &str) -> String {
        if self.name.is_empty() {
            format!("`{key}`")
        } else {
            format!("`{key}` in {}", self.name)
        }
    }

    fn names(&self) -> String {
        let names: Vec<&str> = self.keys.iter().map(|key| key.name).collect();
        names.join(", ")
    }

    /// The key `written` stands for: the closest in spelling, else the one whose meaning it
    /// names (`runtime` → `run`).
    fn meant(&self, written: &str) -> Option<&'static str> {
        crate::suggest::did_you_mean(written, self.keys.iter().map(|key| key.name)).or_else(|| {
            let word = written.trim().to_ascii_lowercase().replace(['-', ' '], "_");
            self.keys
                .iter()
                .find(|key| key.meant_by.contains(&word.as_str()))
                .map(|key| key.name)
        })
    }

    fn unknown_key(&self, key: &Spanned<DeString<'_>>) -> ScenarioError {
        let written = key.get_ref().as_ref();
        let close = self
            .meant(written)
            .map(|known| format!("did you mean `{known}`? "))
            .unwrap_or_default();
        let (label, help) = if self.name.is_empty() {
            let list = if close.is_empty() {
                format!(
                    "the keys of a scenario: {}; `awl help scenario` describes them",
                    self.names()
                )
            } else {
                "`awl help scenario` describes the keys".to_string()
            };
            ("not a scenario key".to_string(), format!("{close}{list}"))
        } else {
            (
                format!("not a key of {}", self.name),
                format!("{close}the keys of {}: {}", self.name, self.names()),
            )
        };
        ScenarioError::UnknownKey {
            key: written.to_string(),
            at: span_of(key.span()),
            label,
            help: Some(help),
        }
    }

    /// A value of `key` that is not what the key takes.
    fn wrong_value(&self, key: &'static Key, value: &Spanned<DeValue<'_>>) -> ScenarioError {
        ScenarioError::WrongType {
            key: self.named(key.name),
            takes: key.takes,
            example: key.example,
            at: span_of(value.span()),
            found: found(value.get_ref().type_str()).to_string(),
        }
    }

    /// A value of one of this table's keys; a value the key does not take is reported.
    fn read<T: DeserializeOwned>(
        &self,
        key: &str,
        value: &Spanned<DeValue<'_>>,
        errors: &mut Vec<ScenarioError>,
    ) -> Option<T> {
        T::deserialize(ValueDeserializer::from(value.clone()))
            .map_err(|error| {
                let mut wrong = self.wrong_value(self.key(key), value);
                // serde's words for a value of the right kind that does not fit (`ob = 300`).
                if error.message().starts_with("invalid value")
                    && let ScenarioError::WrongType { found, .. } = &mut wrong
                {
                    *found = "out of range".into();
                }
                errors.push(wrong);
            })
            .ok()
    }

    /// The entries of `value`, which `holder` of `parent` holds, when it is a table of this
    /// kind; every key it does not have is reported.
    fn entries<'t, 'i>(
        &'static self,
        parent: &Table,
        holder: &str,
        value: &'t Spanned<DeValue<'i>>,
        errors: &mut Vec<ScenarioError>,
    ) -> Option<Entries<'t, 'i>> {
        let Some(table) = value.get_ref().as_table() else {
            errors.push(parent.wrong_value(parent.key(holder), value));
            return None;
        };
        for key in table.keys() {
            if !self.keys.iter().any(|known| known.name == key.get_ref()) {
                errors.push(self.unknown_key(key));
            }
        }
        Some(Entries {
            table: self,
            entries: table,
            span: value.span(),
        })
    }
}

/// The entries of one table of the format, read key by key.
struct Entries<'t, 'i> {
    table: &'static Table,
    entries: &'t DeTable<'i>,
    span: Range<usize>,
}

impl Entries<'_, '_> {
    /// The value of an optional key; `None` when it is absent or reported.
    fn get<T: DeserializeOwned>(&self, key: &str, errors: &mut Vec<ScenarioError>) -> Option<T> {
        let value = self.entries.get(key)?;
        self.table.read(key, value, errors)
    }

    /// The value of a key the table needs; its absence is reported.
    fn needs<T: DeserializeOwned>(&self, key: &str, errors: &mut Vec<ScenarioError>) -> Option<T> {
        let misspelt = self
            .entries
            .keys()
            .any(|written| self.table.meant(written.get_ref()) == Some(key));
        if !self.entries.contains_key(key) && !misspelt {
            let known = self.table.key(key);
            errors.push(super::invalid(
                format!("{} has no `{key}`", self.table.name),
                span_of(self.span.clone()),
                format!("needs `{key}`: {}", known.takes),
                Some(format!("e.g. {}", known.example)),
            ));
            return None;
        }
        self.get(key, errors)
    }

    /// The table an optional key holds, read by `read`.
    fn table<T>(
        &self,
        key: &str,
        errors: &mut Vec<ScenarioError>,
        read: fn(&Spanned<DeValue<'_>>, &mut Vec<ScenarioError>) -> Option<T>,
    ) -> Option<Spanned<T>> {
        let value = self.entries.get(key)?;
        read(value, errors).map(|read| Spanned::new(value.span(), read))
    }
}

/// The tables of an array of tables (`[[event]]`), each read on its own by `read`.
fn read_each<T>(
    key: &str,
    value: &Spanned<DeValue<'_>>,
    errors: &mut Vec<ScenarioError>,
    read: impl Fn(&Spanned<DeValue<'_>>, &mut Vec<ScenarioError>) -> Option<T>,
) -> Vec<Spanned<T>> {
    let Some(items) = value.get_ref().as_array() else {
        errors.push(SCENARIO.wrong_value(SCENARIO.key(key), value));
        return Vec::new();
    };
    items
        .iter()
        .filter_map(|item| read(item, errors).map(|read| Spanned::new(item.span(), read)))
        .collect()
}

/// `read`'s result when it reported no error.
fn unless_reported<T>(
    errors: &mut Vec<ScenarioError>,
    read: impl FnOnce(&mut Vec<ScenarioError>) -> Option<T>,
) -> Option<T> {
    let before = errors.len();
    let value = read(errors);
    value.filter(|_| errors.len() == before)
}

fn run(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawRun> {
    unless_reported(errors, |errors| {
        let entries = RUN.entries(&SCENARIO, "run", value, errors)?;
        Some(RawRun {
            duration: entries.get("for", errors),
            cycles: entries.get("cycles", errors),
        })
    })
}

fn ob13(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawOb13> {
    unless_reported(errors, |errors| {
        let entries = OB13.entries(&SCENARIO, "ob13", value, errors)?;
        let interval = entries.needs("interval", errors);
        Some(RawOb13 {
            delay: entries.get("delay", errors),
            max_delay: entries.get("max_delay", errors),
            interval: interval?,
        })
    })
}

fn retentive(
    value: &Spanned<DeValue<'_>>,
    errors: &mut Vec<ScenarioError>,
) -> Option<RawRetentive> {
    unless_reported(errors, |errors| {
        let entries = RETENTIVE.entries(&SCENARIO, "retentive", value, errors)?;
        Some(RawRetentive {
            flag_bytes: entries.get("flag_bytes", errors),
            timers: entries.get("timers", errors),
            counters: entries.get("counters", errors),
            data_blocks: entries.get("data_blocks", errors),
        })
    })
}

fn ob35(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawOb35> {
    unless_reported(errors, |errors| {
        let entries = OB35.entries(&SCENARIO, "ob35", value, errors)?;
        Some(RawOb35 {
            interval: entries.get("interval", errors),
        })
    })
}

fn hw_module(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawHwModule> {
    unless_reported(errors, |errors| {
        let entries = HW_MODULE.entries(&SCENARIO, "hw_module", value, errors)?;
        let (module, ob) = (entries.needs("module", errors), entries.needs("ob", errors));
        Some(RawHwModule {
            address: entries.get("address", errors),
            module: module?,
            ob: ob?,
        })
    })
}

fn interrupt_input(
    value: &Spanned<DeValue<'_>>,
    errors: &mut Vec<ScenarioError>,
) -> Option<RawInterruptInput> {
    unless_reported(errors, |errors| {
        let entries = INTERRUPT_INPUT.entries(&SCENARIO, "interrupt_input", value, errors)?;
        let input = entries.needs("input", errors);
        Some(RawInterruptInput {
            edge: entries.get("edge", errors),
            ob: entries.get("ob", errors),
            module: entries.get("module", errors),
            channel: entries.get("channel", errors),
            input: input?,
        })
    })
}

fn hardware(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawHardware> {
    let entries = HW_INTERRUPT.entries(&EVENT, "hw_interrupt", value, errors)?;
    let (module, channel) = (
        entries.needs("module", errors),
        entries.needs("channel", errors),
    );
    Some(RawHardware {
        active_for: entries.needs("active_for", errors)?,
        module: module?,
        channel: channel?,
    })
}

fn station(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawStation> {
    let entries = STATION.entries(&EVENT, "station", value, errors)?;
    let number = entries.needs("number", errors);
    Some(RawStation {
        failed: entries.needs("failed", errors)?,
        number: number?,
    })
}

fn event(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawEvent> {
    unless_reported(errors, |errors| {
        let entries = EVENT.entries(&SCENARIO, "event", value, errors)?;
        let hw_interrupt = entries.table("hw_interrupt", errors, hardware);
        let station = entries.table("station", errors, station);
        let at = entries.needs("at", errors);
        Some(RawEvent {
            every: entries.get("every", errors),
            count: entries.get("count", errors),
            until: entries.get("until", errors),
            set: entries.get("set", errors),
            interrupt: entries.get("interrupt", errors),
            hw_interrupt,
            station,
            at: at?,
        })
    })
}

fn modbus(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<RawModbus> {
    let entries = MODBUS.entries(&SCENARIO, "modbus", value, errors)?;
    Some(RawModbus {
        discrete_inputs: entries.get("discrete_inputs", errors),
        coils: entries.get("coils", errors),
        input_registers: entries.get("input_registers", errors),
        holding_registers: entries.get("holding_registers", errors),
    })
}

/// A `[[check]]` table: `at` and operands, checked against the program later.
fn check(value: &Spanned<DeValue<'_>>, errors: &mut Vec<ScenarioError>) -> Option<SpannedTable> {
    SCENARIO.read("check", value, errors)
}

/// Reads the file: what could be read, and every error found on the way.
pub fn parse(text: &str) -> (RawScenario, Vec<ScenarioError>) {
    let (table, syntax) = DeTable::parse_recoverable(text);
    let mut errors: Vec<ScenarioError> = syntax
        .into_iter()
        .map(|error| syntax_error(error, 0..0))
        .collect();
    let mut raw = RawScenario::default();
    for (key, value) in table.get_ref() {
        let errors = &mut errors;
        let name = key.get_ref().as_ref();
        match name {
            "program" => raw.program = SCENARIO.read(name, value, errors),
            "symbols" => raw.symbols = SCENARIO.read(name, value, errors),
            "cpu" => raw.cpu = SCENARIO.read(name, value, errors),
            "dialect" => raw.dialect = SCENARIO.read(name, value, errors),
            "extended" => raw.extended = SCENARIO.read(name, value, errors),
            "mode" => raw.cpu_keys.mode = SCENARIO.read(name, value, errors),
            "interrupt_points" => raw.interrupt_points = SCENARIO.read(name, value, errors),
            "watchdog" => raw.watchdog = SCENARIO.read(name, value, errors),
            "min_cycle" => raw.cpu_keys.min_cycle = SCENARIO.read(name, value, errors),
            "clock_memory" => raw.cpu_keys.clock_memory = SCENARIO.read(name, value, errors),
            "expect" => raw.expect = SCENARIO.read(name, value, errors).unwrap_or_default(),
            "watch" => raw.watch = SCENARIO.read(name, value, errors).unwrap_or_default(),
            "run" => raw.run = run(value, errors).map(|run| Spanned::new(value.span(), run)),
            "ob13" => {
                raw.cpu_keys.ob13 = ob13(value, errors).map(|ob13| Spanned::new(value.span(), ob13))
            }
            "ob35" => {
                raw.cpu_keys.ob35 = ob35(value, errors).map(|ob35| Spanned::new(value.span(), ob35))
            }
            "retentive" => {
                raw.cpu_keys.retentive =
                    retentive(value, errors).map(|table| Spanned::new(value.span(), table))
            }
            "hw_module" => raw.cpu_keys.hw_module = read_each(name, value, errors, hw_module),
            "interrupt_input" => {
                raw.interrupt_input = read_each(name, value, errors, interrupt_input)
            }
            "event" => raw.event = read_each(name, value, errors, event),
            "check" => raw.check = read_each(name, value, errors, check),
            "modbus" => raw.modbus = modbus(value, errors).unwrap_or_default(),
            _ => errors.push(SCENARIO.unknown_key(key)),
        }
    }
    (raw, errors)
}

#[cfg(test)]
mod tests {
    use miette::Diagnostic;

    use super::*;

    /// Each error of `text`: its message, labels and help on one line.
    fn errors(text: &str) -> Vec<String> {
        let (_, errors) = parse(text);
        errors
            .iter()
            .map(|error| {
                let labels: Vec<String> = error
                    .labels()
                    .into_iter()
                    .flatten()
                    .filter_map(|label| label.label().map(str::to_string))
                    .collect();
                let help = error.help().map(|help| help.to_string());
                format!(
                    "{error} | {} | {}",
                    labels.join(", "),
                    help.unwrap_or_default()
                )
            })
            .collect()
    }

    fn one_error(text: &str) -> String {
        let found = errors(text);
        assert_eq!(found.len(), 1, "{text}: {found:#?}");
        found.into_iter().next().unwrap()
    }

    /// Words of Rust and serde that mean nothing to a user of the format.
    fn assert_in_user_words(error: &str) {
        for word in [
            "Raw",
            "struct",
            "sequence",
            "map",
            "variant",
            "u8",
            "u16",
            "u64",
            "i64",
            "field",
            "Spanned",
            "ProgramList",
            "expected",
        ] {
            assert!(!error.contains(word), "`{word}` in {error}");
        }
    }

    #[test]
    fn a_value_of_the_wrong_kind_says_what_the_key_takes() {
        for (text, says, example) in [
            (
                "run = \"3s\"\n",
                "`run` takes a table with `for`",
                "run = { for = \"100ms\" }",
            ),
            (
                "[[event]]\nat = 100\ninterrupt = \"OB 3\"\n",
                "`at` in [[event]] takes a duration in quotes",
                "at = \"100ms\"",
            ),
            (
                "[[event]]\nat = \"1ms\"\nevery = 5\ncount = 2\ninterrupt = \"OB 3\"\n",
                "`every` in [[event]] takes a duration",
                "every = \"10ms\"",
            ),
            (
                "watchdog = 300\n",
                "`watchdog` takes a duration",
                "watchdog = \"300ms\"",
            ),
            (
                "watch = \"Q 4.0\"\n",
                "`watch` takes a list of operands",
                "watch = [",
            ),
            (
                "program = 5\n",
                "`program` takes a program file",
                "program = [",
            ),
            (
                "extended = \"yes\"\n",
                "`extended` takes true or false",
                "extended = true",
            ),
            ("expect = 5\n", "`expect` takes a table", "[expect]"),
            (
                "event = 3\n",
                "`event` takes `[[event]]` tables",
                "[[event]]",
            ),
            (
                "check = [1]\n",
                "`check` takes `[[check]]` tables",
                "[[check]]",
            ),
            (
                "[ob13]\ninterval = 5\n",
                "`interval` in [ob13] takes a duration",
                "interval =",
            ),
            (
                "ob35 = \"100ms\"\n",
                "`ob35` takes a table `[ob35]`",
                "[ob35]",
            ),
            (
                "[[event]]\nat = \"1ms\"\nhw_interrupt = { module = 4, channel = 1, active_for = 5 }\n",
                "`active_for` in `hw_interrupt` takes a duration",
                "active_for = \"200us\"",
            ),
            (
                "[[event]]\nat = \"1ms\"\nstation = { number = 3, failed = \"yes\" }\n",
                "`failed` in `station` takes true",
                "failed = true",
            ),
        ] {
            let error = one_error(text);
            assert!(error.starts_with(says), "{text}: {error}");
            assert!(error.contains(example), "{text}: {error}");
            assert_in_user_words(&error);
        }
    }

    #[test]
    fn a_number_out_of_range_is_labelled_so() {
        let error = one_error("[[hw_module]]\nmodule = 4\nob = 400\n");
        assert!(
            error.starts_with("`ob` in [[hw_module]] takes the OB number 40 or 41 | out of range"),
            "{error}"
        );
    }

    #[test]
    fn a_typo_in_a_table_is_answered_with_that_table_s_keys() {
        for (text, typo, meant, table) in [
            (
                "[[event]]\natt = \"1ms\"\ninterrupt = \"OB 3\"\n",
                "att",
                "at",
                "[[event]]",
            ),
            (
                "[ob13]\nintervall = \"1ms\"\n",
                "intervall",
                "interval",
                "[ob13]",
            ),
            (
                "[ob35]\nintervl = \"1ms\"\n",
                "intervl",
                "interval",
                "[ob35]",
            ),
            (
                "[[hw_module]]\nmodul = 4\nob = 40\n",
                "modul",
                "module",
                "[[hw_module]]",
            ),
            ("run = { fro = \"1s\" }\n", "fro", "for", "`run`"),
            (
                "[[event]]\nat = \"1ms\"\nhw_interrupt = { module = 4, chanel = 1, active_for = \"1ms\" }\n",
                "chanel",
                "channel",
                "`hw_interrupt`",
            ),
            (
                "[[event]]\nat = \"1ms\"\nstation = { numbr = 3, failed = true }\n",
                "numbr",
                "number",
                "`station`",
            ),
        ] {
            let error = one_error(text);
            assert!(
                error.starts_with(&format!("unknown key `{typo}` | not a key of {table} |")),
                "{error}"
            );
            assert!(
                error.contains(&format!("did you mean `{meant}`? the keys of {table}: ")),
                "{error}"
            );
            assert!(!error.contains("program"), "the top-level keys in {error}");
        }
    }

    #[test]
    fn a_key_written_in_other_words_is_told_the_one_it_means() {
        for (text, written, meant) in [
            ("runtime = \"1s\"\n", "runtime", "run"),
            ("duration = \"1s\"\n", "duration", "run"),
            ("length = \"1s\"\n", "length", "run"),
            ("time = \"1s\"\n", "time", "run"),
            ("profile = \"speed7\"\n", "profile", "cpu"),
            ("plc = \"speed7\"\n", "plc", "cpu"),
            ("processor = \"speed7\"\n", "processor", "cpu"),
            ("source = \"a.awl\"\n", "source", "program"),
            ("files = [\"a.awl\"]\n", "files", "program"),
            ("language = \"s7\"\n", "language", "dialect"),
            ("cycle_time = \"100ms\"\n", "cycle_time", "watchdog"),
            ("Scan-Time = \"100ms\"\n", "Scan-Time", "watchdog"),
            ("[results]\n\"Q 4.0\" = 1\n", "results", "expect"),
            ("monitor = [\"Q 4.0\"]\n", "monitor", "watch"),
        ] {
            let error = one_error(text);
            assert!(
                error.starts_with(&format!(
                    "unknown key `{written}` | not a scenario key | did you mean `{meant}`? `awl help scenario` describes the keys"
                )),
                "{error}"
            );
        }
    }

    #[test]
    fn a_key_of_a_table_written_in_other_words_counts_as_given() {
        let error = one_error("[[event]]\ntime = \"1ms\"\ninterrupt = \"OB 3\"\n");
        assert!(
            error.starts_with("unknown key `time` | not a key of [[event]] | did you mean `at`?"),
            "{error}"
        );
        let error = one_error("run = { duration = \"1s\" }\n");
        assert!(error.contains("did you mean `for`?"), "{error}");
    }

    #[test]
    fn spelling_comes_before_meaning() {
        let error = one_error("runn = { for = \"1s\" }\n");
        assert!(error.contains("did you mean `run`?"), "{error}");
        let error = one_error("events = []\n");
        assert!(error.contains("did you mean `event`?"), "{error}");
    }

    #[test]
    fn a_top_level_typo_lists_the_keys_when_none_is_close() {
        let error = one_error("colour = \"red\"\n");
        assert!(
            error.contains("the keys of a scenario: program, symbols"),
            "{error}"
        );
        assert!(
            error.contains("clock_memory") && error.contains("ob35"),
            "{error}"
        );
        assert!(error.contains("`awl help scenario`"), "{error}");
    }

    #[test]
    fn a_missing_key_is_named_with_an_example() {
        let error = one_error("[[hw_module]]\nob = 40\n");
        assert!(
            error.starts_with("[[hw_module]] has no `module`"),
            "{error}"
        );
        assert!(error.contains("e.g. `module = 4`"), "{error}");
        let error = one_error("[[event]]\ninterrupt = \"OB 3\"\n");
        assert!(error.starts_with("[[event]] has no `at`"), "{error}");
    }

    #[test]
    fn a_toml_syntax_error_gets_help_on_the_format_not_a_key_list() {
        let error = one_error("watchdog = \"1s\n");
        assert!(error.contains("a scenario is TOML"), "{error}");
        assert!(!error.contains("interrupt_points"), "{error}");
    }

    #[test]
    fn modbus_keys_are_read_and_checked_one_by_one() {
        let (raw, errors) =
            parse("[modbus]\ncoils = \"I 0.0\"\nholding_registers = \"DB1.DBW 0\"\n");
        assert!(errors.is_empty(), "{errors:?}");
        let modbus = raw.modbus;
        assert_eq!(
            modbus.coils.map(|coils| coils.into_inner()),
            Some("I 0.0".into())
        );
        assert!(modbus.discrete_inputs.is_none() && modbus.input_registers.is_none());
        assert!(modbus.holding_registers.is_some());
        let error = one_error("[modbus]\ncoil = \"I 0.0\"\n");
        assert!(
            error.starts_with("unknown key `coil` | not a key of [modbus] | did you mean `coils`?"),
            "{error}"
        );
        let error = one_error("[modbus]\ncoils = \"I 0.0\"\ninput_registers = 4\n");
        assert!(
            error.starts_with(
                "`input_registers` in [modbus] takes a word operand in quotes | a whole number"
            ),
            "{error}"
        );
        assert!(
            error.contains("e.g. `input_registers = \"IW 0\"`"),
            "{error}"
        );
        let error = one_error("modbus = \"I 0.0\"\n");
        assert!(
            error.starts_with("`modbus` takes a table `[modbus]`"),
            "{error}"
        );
        assert_in_user_words(&error);
    }

    #[test]
    fn a_good_file_reads_without_errors() {
        let text = "program = \"a.awl\"\nrun = { cycles = 3 }\nwatchdog = \"300ms\"\nwatch = [\"Q 4.0\"]\n[[hw_module]]\nmodule = 4\nob = 40\naddress = 8\n[[event]]\nat = \"1ms\"\nevery = \"1ms\"\ncount = 2\nhw_interrupt = { module = 4, channel = 1, active_for = \"1ms\" }\n[[event]]\nat = \"2ms\"\nstation = { number = 3, failed = true }\n[expect]\nmode = \"RUN\"\n[[check]]\nat = \"1ms\"\n\"Q 4.0\" = 1\n";
        let (raw, errors) = parse(text);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(raw.event.len(), 2);
        assert_eq!(raw.cpu_keys.hw_module.len(), 1);
        assert_eq!(raw.check.len(), 1);
        assert!(raw.run.is_some() && raw.watchdog.is_some());
    }
}
