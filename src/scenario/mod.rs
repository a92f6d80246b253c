//! Scenario files: the program, CPU, run length, timed events and expected results
//! (`programs/README.md` documents every key). Loading checks the keys and durations; the keys
//! that belong to some CPUs only are checked once the run's CPU is known, which without `cpu`
//! is the program's dialect's ([`Scenario::settle_cpu`]); OBs and operands are resolved once the
//! program is compiled, in its mnemonic set or English. Every error of a file is reported, not
//! only the first.

pub mod check;
pub mod error;
pub mod expect;
mod modbus;
pub mod modify;
pub mod operand;
mod raw;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{NamedSource, Report, SourceSpan};
use toml::Spanned;

use crate::compiler::Program;
use crate::diagnostics::Finding;
use crate::dialect::Dialect;
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Family, InterruptPoints, Profile};
use crate::suggest::did_you_mean;
use crate::vm::cycle::RunLimit;
use crate::vm::interrupts::inputs::{Edge, InterruptInput, Raises};
use crate::vm::interrupts::{Happening, InputChange, InputTarget, Ob13Timing, Scheduled};
use crate::vm::stop::StopCause;

pub use check::TimedCheck;
pub use error::ScenarioError;
pub use expect::{Expectation, Expected};
pub use modify::DataWrite;
use operand::{Target, Wanted, parse_target, raw_value, real_value};
use raw::{ProgramList, RawEvent, RawInterruptInput, RawScenario, SpannedTable};

/// The longest cycle watchdog a scenario may set: the longest cycle monitoring time of the
/// S7-300 class CPUs the VIPA SPEED7 follows (6000 ms); the S5 CPUs allow less.
pub const MAX_WATCHDOG_NS: u64 = 6_000_000_000;

/// The most events a scenario's repetitions (`every`) may add up to.
pub const MAX_EVENTS: usize = 1_000_000;

/// What the events of a scenario do: the happenings the engine schedules, and the data block
/// writes made at cycle boundaries ([`modify`]).
#[derive(Debug, Default)]
pub struct Plan {
    pub schedule: Vec<Scheduled>,
    pub writes: Vec<DataWrite>,
    /// The input bits whose edges raise interrupts (`[[interrupt_input]]`).
    pub interrupt_inputs: Vec<InterruptInput>,
}

impl Plan {
    fn len(&self) -> usize {
        self.schedule.len() + self.writes.len()
    }
}

/// What one event does: a happening the engine schedules (if any), and the data block writes
/// (target, raw value) of its `set`.
type Effect = (Option<Happening>, Vec<(Target, u32)>);

/// A loaded scenario.
#[derive(Debug)]
pub struct Scenario {
    pub path: PathBuf,
    text: Arc<str>,
    pub programs: Vec<PathBuf>,
    /// The assignment lists (`symbols = [...]`).
    pub symbols: Vec<PathBuf>,
    /// The CPU the file names.
    pub cpu: Option<&'static Profile>,
    /// The program's STL dialect (`dialect`), when the file names it.
    pub dialect: Option<Dialect>,
    /// awlsim's test operations are accepted (`extended = true`).
    pub extended: bool,
    pub points: Option<InterruptPoints>,
    pub limit: Option<RunLimit>,
    pub watchdog_ns: Option<u64>,
    /// The keys that belong to some CPUs only, as written; [`Scenario::settle_cpu`] checks
    /// them and fills in the settings below.
    cpu_keys: raw::CpuKeys,
    pub special_mode: Option<bool>,
    pub ob13: Option<Ob13Timing>,
    /// The OB 35 interval `[ob35]` gives.
    pub ob35_interval_ns: Option<u64>,
    /// The retentive ranges `[retentive]` sets (else the profile's preset).
    pub retentive: Option<crate::profile::Retentive>,
    pub hw_modules: Vec<(u16, u8)>,
    /// The logical base addresses `[[hw_module]]` gives (module, address).
    pub hw_addresses: Vec<(u16, u16)>,
    /// The clock memory byte's number (`clock_memory = 100`: MB 100).
    pub clock_memory: Option<u16>,
    /// S7: the minimum cycle time (`min_cycle`).
    pub min_cycle_ns: Option<u64>,
    interrupt_inputs: Vec<Spanned<RawInterruptInput>>,
    events: Vec<Spanned<RawEvent>>,
    expect: SpannedTable,
    watch: Vec<Spanned<String>>,
    checks: Vec<Spanned<SpannedTable>>,
    /// `[modbus]`, resolved by `Scenario::modbus_map` once the program is known.
    modbus: raw::RawModbus,
}

fn span<T>(spanned: &Spanned<T>) -> SourceSpan {
    let range = spanned.span();
    (range.start, range.end - range.start).into()
}

/// `"1.5ms"`, `"200us"`, `"200µs"`, `"2s"`, `"100ns"` to nanoseconds.
pub fn parse_duration(text: &str) -> Option<u64> {
    let text = text.trim();
    let split = text.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '+' | ' ')))?;
    let (number, unit) = text.split_at(split);
    let value: f64 = number.trim().parse().ok()?;
    let scale = match unit.trim() {
        "ns" => 1.0,
        "us" | "µs" | "μs" => 1e3,
        "ms" => 1e6,
        "s" => 1e9,
        _ => return None,
    };
    let ns = value * scale;
    (value.is_finite() && (0.0..1e19).contains(&ns)).then_some(ns.round() as u64)
}

fn duration(spanned: &Spanned<String>) -> Result<u64, ScenarioError> {
    parse_duration(spanned.get_ref()).ok_or_else(|| ScenarioError::BadDuration {
        text: spanned.get_ref().clone(),
        at: span(spanned),
    })
}

fn invalid(
    message: impl Into<String>,
    at: SourceSpan,
    label: impl Into<String>,
    help: Option<String>,
) -> ScenarioError {
    ScenarioError::Invalid(Finding::new(message, at, label, help))
}

/// Errors found while checking, kept to report them all.
#[derive(Default)]
struct Errors(Vec<ScenarioError>);

impl Errors {
    fn push(&mut self, error: ScenarioError) {
        self.0.push(error);
    }

    /// The value of a check, or `None` with its error kept.
    fn keep<T>(&mut self, result: Result<T, ScenarioError>) -> Option<T> {
        result.map_err(|error| self.push(error)).ok()
    }

    /// An optional key's value as `check` reads it; `None` when it is absent or wrong (the
    /// error kept).
    fn check<T, U>(
        &mut self,
        key: &Option<T>,
        check: impl FnOnce(&T) -> Result<U, ScenarioError>,
    ) -> Option<U> {
        key.as_ref().and_then(|value| self.keep(check(value)))
    }
}

impl Scenario {
    /// Renders an error with this scenario's text.
    pub fn report(&self, error: ScenarioError) -> Report {
        report(&self.path, &self.text, error)
    }

    /// The span of a table key without its quotes (`"I 0.0" = 1`); a key cut off by the end
    /// of the file has no closing quote to leave out.
    fn key_span(&self, key: &Spanned<String>) -> SourceSpan {
        let range = key.span();
        let written = &self.text[range.clone()];
        let Some(quote) = written.chars().next().filter(|c| matches!(c, '"' | '\'')) else {
            return span(key);
        };
        let closed = written.len() >= 2 && written.ends_with(quote);
        let end = if closed { range.end - 1 } else { range.end };
        (range.start + 1, end - range.start - 1).into()
    }

    /// `value`, or the reports of the errors found reading it.
    fn unless_errors<T>(&self, value: T, errors: Errors) -> Result<T, Vec<Report>> {
        if errors.0.is_empty() {
            Ok(value)
        } else {
            Err(self.reports(errors.0))
        }
    }

    fn reports(&self, errors: Vec<ScenarioError>) -> Vec<Report> {
        sorted(errors)
            .into_iter()
            .map(|error| self.report(error))
            .collect()
    }

    /// Reads and checks a scenario file, but for the keys that depend on the CPU
    /// ([`Scenario::settle_cpu`]). `Err` when the file cannot be read; otherwise the scenario
    /// as far as it could be read, and every error found in it.
    pub fn load(path: &Path) -> Result<(Scenario, Vec<Report>), Report> {
        Scenario::load_in(&crate::source::Files::Disk, path)
    }

    /// [`Scenario::load`] from `store`.
    pub fn load_in(
        store: &crate::source::Files,
        path: &Path,
    ) -> Result<(Scenario, Vec<Report>), Report> {
        let read = |error: std::io::Error| {
            Report::new(ScenarioError::Read {
                path: path.display().to_string(),
                reason: error.to_string(),
            })
        };
        let bytes = store.read(path).map_err(read)?;
        let text = String::from_utf8(bytes)
            .map_err(|error| read(std::io::Error::new(std::io::ErrorKind::InvalidData, error)))?;
        Ok(Scenario::parse(path, &text))
    }

    /// Checks scenario text, but for the keys that depend on the CPU: the scenario as far as
    /// it could be read, and every error.
    pub fn parse(path: &Path, text: &str) -> (Scenario, Vec<Report>) {
        let text: Arc<str> = Arc::from(text);
        let (raw, errors) = raw::parse(&text);
        let mut errors = Errors(errors);
        let scenario = Scenario::from_raw(path, text.clone(), raw, &mut errors);
        let reports = scenario.reports(errors.0);
        (scenario, reports)
    }

    /// Checks the keys that belong to some CPUs only (`mode`, `[ob13]`, `[ob35]`,
    /// `[[hw_module]]`, `clock_memory`, `min_cycle`) against `profile`, the CPU the run uses,
    /// and takes their values: the errors found.
    pub fn settle_cpu(&mut self, profile: &'static Profile) -> Vec<Report> {
        let mut errors = Errors::default();
        let keys = &self.cpu_keys;
        self.special_mode = errors.check(&keys.mode, |mode| check_mode(mode, profile));
        self.ob13 = errors.check(&keys.ob13, |ob13| check_ob13(ob13, profile));
        self.ob35_interval_ns = errors.check(&keys.ob35, |ob35| check_ob35(ob35, profile));
        self.retentive = errors.check(&keys.retentive, |table| check_retentive(table, profile));
        (self.hw_modules, self.hw_addresses) = check_modules(&keys.hw_module, profile, &mut errors);
        self.clock_memory =
            errors.check(&keys.clock_memory, |byte| check_clock_memory(byte, profile));
        self.min_cycle_ns = errors.check(&keys.min_cycle, |min_cycle| {
            check_min_cycle(min_cycle, self.watchdog_ns, profile)
        });
        self.reports(errors.0)
    }

    fn from_raw(path: &Path, text: Arc<str>, raw: RawScenario, errors: &mut Errors) -> Scenario {
        let base = path.parent().unwrap_or(Path::new("."));
        let paths = |list: &Option<Spanned<ProgramList>>| match list.as_ref().map(Spanned::get_ref)
        {
            None => Vec::new(),
            Some(ProgramList::One(one)) => vec![base.join(one)],
            Some(ProgramList::Many(many)) => many.iter().map(|one| base.join(one)).collect(),
        };
        let programs = paths(&raw.program);
        let symbols = paths(&raw.symbols);
        let cpu = errors.check(&raw.cpu, |name| {
            profile::find(name.get_ref()).ok_or_else(|| {
                invalid(
                    format!("unknown CPU `{}`", name.get_ref()),
                    span(name),
                    "no such profile",
                    Some(format!("the profiles are: {}", profile::names().join(", "))),
                )
            })
        });
        Scenario {
            path: path.to_path_buf(),
            text,
            programs,
            symbols,
            cpu,
            dialect: errors.check(&raw.dialect, check_dialect),
            extended: raw.extended.unwrap_or(false),
            points: errors.check(&raw.interrupt_points, check_points),
            limit: errors.check(&raw.run, check_run),
            watchdog_ns: errors.check(&raw.watchdog, check_watchdog),
            cpu_keys: raw.cpu_keys,
            special_mode: None,
            ob13: None,
            ob35_interval_ns: None,
            retentive: None,
            hw_modules: Vec::new(),
            hw_addresses: Vec::new(),
            clock_memory: None,
            min_cycle_ns: None,
            interrupt_inputs: raw.interrupt_input,
            events: raw.event,
            expect: raw.expect,
            watch: raw.watch,
            checks: raw.check,
            modbus: raw.modbus,
        }
    }

    /// The value a `set` or `[expect]` entry gives, as written, and what it stands for in the
    /// operand: an integer (booleans count as 0 and 1), or in a STEP 7 program's double word
    /// also a REAL.
    fn value(
        target: Target,
        value: &Spanned<toml::Value>,
        operand: &str,
        program: &Program,
    ) -> Result<(String, Wanted), ScenarioError> {
        set_value(target, value.get_ref(), operand, program, span(value))
    }
}

/// The value a `set` or `[expect]` entry gives (at `at` in its file), as written, and what it
/// stands for in the operand: an integer (booleans count as 0 and 1), or in a STEP 7 program's
/// double word also a REAL. The online page's modify and force take values so too.
pub fn set_value(
    target: Target,
    value: &toml::Value,
    operand: &str,
    program: &Program,
    at: SourceSpan,
) -> Result<(String, Wanted), ScenarioError> {
    let bad = |shown: String, range: String| ScenarioError::BadValue {
        operand: operand.into(),
        value: shown,
        at,
        range,
    };
    let number = match value {
        toml::Value::Integer(number) => *number,
        toml::Value::Boolean(flag) => i64::from(*flag),
        toml::Value::Float(real) if program.s7.step7 => {
            let bits = real_value(target, *real).map_err(|range| bad(real.to_string(), range))?;
            return Ok((real.to_string(), Wanted::Real(bits)));
        }
        other => return Err(bad(other.to_string(), "an integer".into())),
    };
    let raw = raw_value(target, number).map_err(|range| bad(number.to_string(), range))?;
    Ok((number.to_string(), Wanted::Raw(raw)))
}

impl Scenario {
    /// The timed events, with operands resolved against the compiled program.
    pub fn schedule(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<Scheduled>, Vec<Report>> {
        self.schedule_at_most(program, set, MAX_EVENTS)
    }

    /// [`Scenario::schedule`] holding at most `max_events` events: a caller that must bound
    /// what one scenario costs (a fuzz target) sets it below [`MAX_EVENTS`].
    pub fn schedule_at_most(
        &self,
        program: &Program,
        set: MnemonicSet,
        max_events: usize,
    ) -> Result<Vec<Scheduled>, Vec<Report>> {
        self.plan_at_most(program, set, max_events)
            .map(|plan| plan.schedule)
    }

    /// The timed events and the data block writes of `set`, with operands resolved against
    /// the compiled program.
    pub fn plan(&self, program: &Program, set: MnemonicSet) -> Result<Plan, Vec<Report>> {
        self.plan_at_most(program, set, MAX_EVENTS)
    }

    fn plan_at_most(
        &self,
        program: &Program,
        set: MnemonicSet,
        max_events: usize,
    ) -> Result<Plan, Vec<Report>> {
        let mut errors = Errors::default();
        let mut plan = Plan::default();
        for input in &self.interrupt_inputs {
            let resolved = self.interrupt_input(input, program, set, &mut errors);
            plan.interrupt_inputs.extend(resolved);
        }
        for event in &self.events {
            let at_span = span(&event.get_ref().at);
            let event_span = span(event);
            let event = event.get_ref();
            let at_ns = errors.keep(duration(&event.at));
            let kinds = usize::from(event.set.is_some())
                + usize::from(event.interrupt.is_some())
                + usize::from(event.hw_interrupt.is_some())
                + usize::from(event.station.is_some());
            if kinds != 1 {
                errors.push(invalid(
                    "an [[event]] has exactly one of `set`, `interrupt`, `hw_interrupt`, `station`",
                    if kinds == 0 { event_span } else { at_span },
                    "this event",
                    None,
                ));
                continue;
            }
            let happening = |happening| (Some(happening), Vec::new());
            let what = if let Some(changes) = &event.set {
                self.set_changes(changes, program, set, &mut errors)
            } else if let Some(interrupt) = &event.interrupt {
                errors
                    .keep(Self::interrupt_ob(interrupt, program.profile))
                    .map(|ob| happening(Happening::Interrupt { ob }))
            } else if let Some(hardware) = &event.hw_interrupt {
                errors
                    .keep(self.hardware(hardware, program.profile))
                    .map(happening)
            } else if let Some(station) = &event.station {
                errors
                    .keep(station_failure(station, program.profile))
                    .map(happening)
            } else {
                None
            };
            let times = at_ns.and_then(|at_ns| errors.keep(occurrences(event, at_ns, max_events)));
            if let (Some(times), Some((what, writes))) = (times, what) {
                if plan.len() + times.len() > max_events {
                    errors.push(invalid(
                        format!(
                            "this event repeats {} times; a scenario holds at most {max_events} events",
                            times.len()
                        ),
                        event_span,
                        "too many repetitions",
                        Some("repeat it less often (a longer `every`), or fewer times".into()),
                    ));
                    continue;
                }
                for at_ns in times {
                    if let Some(what) = &what {
                        plan.schedule.push(Scheduled {
                            at_ns,
                            what: what.clone(),
                        });
                    }
                    let timed =
                        writes
                            .iter()
                            .map(|&(target, raw)| DataWrite { at_ns, target, raw });
                    plan.writes.extend(timed);
                }
            }
        }
        self.unless_errors(plan, errors)
    }

    /// What a `set` table does: the input changes (a happening; kept even when empty, as a
    /// `set` of inputs only always was) and the data block writes.
    fn set_changes(
        &self,
        changes: &SpannedTable,
        program: &Program,
        set: MnemonicSet,
        errors: &mut Errors,
    ) -> Option<Effect> {
        let mut inputs = Vec::new();
        let mut writes = Vec::new();
        for (operand, value) in changes {
            let at = self.key_span(operand);
            let text = operand.get_ref();
            let Some(target) = errors.keep(parse_target(text, at, set, program)) else {
                continue;
            };
            let is_data = matches!(target, Target::S7Data { .. });
            if !is_data && input_change(target, program, 0).is_none() {
                errors.push(not_settable(text, at, program));
                continue;
            }
            if let Some((_, wanted)) = errors.keep(Scenario::value(target, value, text, program)) {
                if is_data {
                    writes.push((target, wanted.raw()));
                } else {
                    inputs.extend(input_change(target, program, wanted.raw()));
                }
            }
        }
        if inputs.len() + writes.len() != changes.len() {
            return None;
        }
        let happening = (writes.is_empty() || !inputs.is_empty()).then_some(inputs);
        Some((happening.map(Happening::SetInputs), writes))
    }

    fn hardware(
        &self,
        hardware: &Spanned<raw::RawHardware>,
        profile: &Profile,
    ) -> Result<Happening, ScenarioError> {
        let inner = hardware.get_ref();
        self.hardware_module("`hw_interrupt`", inner.module, span(hardware), profile)?;
        Ok(Happening::Hardware {
            module: inner.module,
            channel: inner.channel,
            active_for_ns: duration(&inner.active_for)?,
        })
    }

    /// A module whose hardware interrupts `what` names: the CPU must be the SPEED7 and the
    /// module mapped by a `[[hw_module]]`.
    fn hardware_module(
        &self,
        what: &str,
        module: u16,
        at: SourceSpan,
        profile: &Profile,
    ) -> Result<(), ScenarioError> {
        if profile.family != Family::Speed7 {
            return Err(invalid(
                format!("{what} belongs to the speed7 profile"),
                at,
                format!("{} has no hardware interrupts", profile.name),
                None,
            ));
        }
        if !self.hw_modules.iter().any(|(known, _)| *known == module) {
            return Err(invalid(
                format!("module {module} has no [[hw_module]] entry"),
                at,
                "unknown module",
                Some("add [[hw_module]] with `module` and `ob = 40` or `41`".into()),
            ));
        }
        Ok(())
    }

    fn interrupt_ob(text: &Spanned<String>, profile: &Profile) -> Result<u8, ScenarioError> {
        let name = text.get_ref();
        let digits = name
            .trim()
            .strip_prefix("OB")
            .or_else(|| name.trim().strip_prefix("ob"))
            .map(str::trim);
        let speed7 = "SPEED7 interrupts come from modules: use `hw_interrupt = { module, channel, active_for }`";
        let ob = digits.and_then(|digits| digits.parse::<u8>().ok());
        Self::requested_ob(ob, name, span(text), speed7, profile)
    }

    /// An OB an `interrupt` event or an `[[interrupt_input]]` requests (`written` as the file
    /// has it): an interrupt OB of the S5 CPU. `speed7` tells what the SPEED7 takes instead.
    fn requested_ob(
        ob: Option<u8>,
        written: &str,
        at: SourceSpan,
        speed7: &str,
        profile: &Profile,
    ) -> Result<u8, ScenarioError> {
        let allowed: Vec<u8> = profile
            .interrupt_obs
            .iter()
            .map(|entry| entry.ob)
            .filter(|ob| match profile.family {
                Family::S5_95f => *ob != 13,
                Family::Speed7 => false,
                Family::Sinumerik840c | Family::S5 => true,
            })
            .collect();
        let help = match profile.family {
            Family::Speed7 => speed7.to_string(),
            Family::S5_95f => {
                "OB 13 runs at its [ob13] interval; `interrupt` requests OB 2 or OB 3".to_string()
            }
            Family::Sinumerik840c | Family::S5 => format!(
                "the interrupt OBs are: {}",
                allowed
                    .iter()
                    .map(|ob| format!("OB {ob}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        match ob {
            Some(ob) if allowed.contains(&ob) => Ok(ob),
            _ => Err(ScenarioError::UnknownOb {
                ob: written.to_string(),
                cpu: profile.name,
                at,
                help: Some(help),
            }),
        }
    }

    /// An `[[interrupt_input]]` resolved against the compiled program; `None` with its errors
    /// kept when it does not fit the program or the CPU.
    fn interrupt_input(
        &self,
        input: &Spanned<RawInterruptInput>,
        program: &Program,
        set: MnemonicSet,
        errors: &mut Errors,
    ) -> Option<InterruptInput> {
        let raw = input.get_ref();
        let bit = errors.keep(self.input_bit(&raw.input, program, set));
        let edge = match &raw.edge {
            None => Some(Edge::Rising),
            Some(edge) => errors.keep(check_edge(edge)),
        };
        let raises = errors.keep(self.raises(raw, span(input), program.profile));
        let ((byte, bit), edge, raises) = (bit?, edge?, raises?);
        Some(InterruptInput {
            byte,
            bit,
            edge,
            raises,
        })
    }

    /// The input bit `input` names: its byte and bit in the input modules.
    fn input_bit(
        &self,
        input: &Spanned<String>,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<(u16, u8), ScenarioError> {
        let at = self.key_span(input);
        let text = input.get_ref();
        let target = parse_target(text, at, set, program)?;
        match input_change(target, program, 0) {
            Some(InputChange {
                target: InputTarget::Process,
                byte,
                bit,
                bytes: 0,
                ..
            }) => Ok((byte, bit)),
            _ => Err(ScenarioError::UnknownOperand {
                operand: text.clone(),
                at,
                reason: "not an input bit".into(),
                help: Some(
                    "an interrupt input is an input bit of the process image: `I 8.0` (German `E 8.0`)"
                        .into(),
                ),
            }),
        }
    }

    /// What an `[[interrupt_input]]` raises: `ob` on the S5 CPUs, `module` and `channel` on the
    /// SPEED7.
    fn raises(
        &self,
        raw: &RawInterruptInput,
        at: SourceSpan,
        profile: &Profile,
    ) -> Result<Raises, ScenarioError> {
        match (&raw.ob, &raw.module, &raw.channel) {
            (Some(ob), None, None) => {
                let speed7 = "SPEED7 interrupts come from modules: give `module` and `channel` of a [[hw_module]]";
                let number = *ob.get_ref();
                Self::requested_ob(
                    Some(number),
                    &format!("OB {number}"),
                    span(ob),
                    speed7,
                    profile,
                )
                .map(Raises::Ob)
            }
            (None, Some(module), Some(channel)) => {
                self.hardware_module(
                    "`module` in [[interrupt_input]]",
                    *module.get_ref(),
                    span(module),
                    profile,
                )?;
                Ok(Raises::Hardware {
                    module: *module.get_ref(),
                    channel: *channel.get_ref(),
                })
            }
            (Some(ob), _, _) => Err(invalid(
                "an [[interrupt_input]] raises an OB's request or a module's hardware interrupt, not both",
                span(ob),
                "`ob` with `module` or `channel`",
                Some("S5 CPUs: `ob = 2`; speed7: `module = 4` and `channel = 1`".into()),
            )),
            (None, module, channel) => {
                let (message, label, at) = match (module, channel) {
                    (Some(module), None) => {
                        ("`module` needs `channel`", "no `channel`", span(module))
                    }
                    (None, Some(channel)) => {
                        ("`channel` needs `module`", "no `module`", span(channel))
                    }
                    _ => (
                        "an [[interrupt_input]] has no `ob` and no `module`",
                        "raises nothing",
                        at,
                    ),
                };
                Err(invalid(
                    message,
                    at,
                    label,
                    Some("S5 CPUs: `ob = 2` (the OB it requests); speed7: `module = 4` and `channel = 1` (the hardware interrupt it raises)".into()),
                ))
            }
        }
    }

    /// A warning for each event later than `end_ns`, the time the run ended: it never fired.
    pub fn events_after(&self, end_ns: u64) -> Vec<Report> {
        self.events
            .iter()
            .filter_map(|event| {
                let at = &event.get_ref().at;
                let when = parse_duration(at.get_ref())?;
                (when > end_ns).then(|| {
                    self.report(ScenarioError::EventAfterEnd {
                        when: at.get_ref().trim().to_string(),
                        end: crate::trace::format_ms(end_ns),
                        at: span(at),
                    })
                })
            })
            .collect()
    }

    /// The `[expect]` table, resolved against the compiled program.
    pub fn expectations(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<Expectation>, Vec<Report>> {
        let mut errors = Errors::default();
        let mut expectations = Vec::new();
        for (key, value) in &self.expect {
            let name = key.get_ref();
            let expected = match name.as_str() {
                "mode" => match value.get_ref().as_str() {
                    Some(mode @ ("RUN" | "STOP")) => Some(Expected::Mode(mode.to_string())),
                    _ => {
                        errors.push(ScenarioError::BadValue {
                            operand: name.clone(),
                            value: value.get_ref().to_string(),
                            at: span(value),
                            range: "\"RUN\" or \"STOP\"".into(),
                        });
                        None
                    }
                },
                "stop_cause" => match value.get_ref().as_str() {
                    Some(cause) if StopCause::CODES.contains(&cause) => {
                        Some(Expected::StopCause(cause.to_string()))
                    }
                    _ => {
                        errors.push(ScenarioError::BadValue {
                            operand: name.clone(),
                            value: value.get_ref().to_string(),
                            at: span(value),
                            range: format!("one of {}", StopCause::CODES.join(", ")),
                        });
                        None
                    }
                },
                _ => self.expected_value(
                    ("[expect]", &["mode", "stop_cause"]),
                    key,
                    value,
                    program,
                    set,
                    &mut errors,
                ),
            };
            if let Some(expected) = expected {
                expectations.push(Expectation {
                    name: name.clone(),
                    expected,
                });
            }
        }
        self.unless_errors(expectations, errors)
    }
}

impl Scenario {
    /// An operand's expected value in `[expect]` or a `[[check]]` (`table`), whose other keys
    /// are `keys`: a key that is no operand but close to one of them is taken for its typo.
    fn expected_value(
        &self,
        (table, keys): (&str, &[&str]),
        key: &Spanned<String>,
        value: &Spanned<toml::Value>,
        program: &Program,
        set: MnemonicSet,
        errors: &mut Errors,
    ) -> Option<Expected> {
        let operand = key.get_ref();
        let at = self.key_span(key);
        let target = parse_target(operand, at, set, program).map_err(|error| {
            match did_you_mean(operand, keys.iter().copied()) {
                Some(known) => ScenarioError::UnknownKey {
                    key: operand.clone(),
                    at,
                    label: format!("neither an operand nor a key of {table}"),
                    help: Some(format!("did you mean `{known}`?")),
                },
                None => error,
            }
        });
        let target = errors.keep(target)?;
        let (written, wanted) = errors.keep(Scenario::value(target, value, operand, program))?;
        Some(Expected::Value {
            target,
            wanted,
            written,
        })
    }

    /// The `[[check]]` tables, resolved against the compiled program.
    pub fn checks(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<TimedCheck>, Vec<Report>> {
        let mut errors = Errors::default();
        let mut checks = Vec::new();
        for table in &self.checks {
            let at = table
                .get_ref()
                .iter()
                .find(|(key, _)| key.get_ref() == "at");
            let misspelt_at = || {
                table
                    .get_ref()
                    .keys()
                    .any(|key| did_you_mean(key.get_ref(), std::iter::once("at")).is_some())
            };
            let at_ns = match at {
                // The misspelt key is reported with its correction.
                None if misspelt_at() => None,
                None => {
                    errors.push(invalid(
                        "a [[check]] needs `at`, the moment it is verified after",
                        span(table),
                        "no `at`",
                        Some(
                            "e.g. `at = \"250ms\"`: verified at the first cycle end at or after it"
                                .into(),
                        ),
                    ));
                    None
                }
                Some((_, value)) => match value.get_ref().as_str() {
                    Some(text) => {
                        errors.keep(duration(&Spanned::new(value.span(), text.to_string())))
                    }
                    None => {
                        errors.push(ScenarioError::WrongType {
                            key: "`at` in [[check]]".into(),
                            takes: raw::DURATION,
                            example: "`at = \"250ms\"`",
                            at: span(value),
                            found: raw::found(value.get_ref().type_str()).into(),
                        });
                        None
                    }
                },
            };
            let mut expectations = Vec::new();
            for (key, value) in table
                .get_ref()
                .iter()
                .filter(|(key, _)| key.get_ref() != "at")
            {
                if matches!(key.get_ref().as_str(), "mode" | "stop_cause") {
                    errors.push(invalid(
                        format!(
                            "a [[check]] checks operands; `{}` belongs in [expect]",
                            key.get_ref()
                        ),
                        self.key_span(key),
                        "not an operand",
                        None,
                    ));
                    continue;
                }
                let keys = ("[[check]]", &["at"][..]);
                if let Some(expected) =
                    self.expected_value(keys, key, value, program, set, &mut errors)
                {
                    expectations.push(Expectation {
                        name: key.get_ref().clone(),
                        expected,
                    });
                }
            }
            if table.get_ref().len() == usize::from(at.is_some()) {
                errors.push(invalid(
                    "a [[check]] without operands checks nothing",
                    span(table),
                    "no operands",
                    Some("add operands as in [expect]: `\"Q 4.0\" = 1`".into()),
                ));
            }
            if let (Some(at_ns), Some((_, value))) = (at_ns, at) {
                checks.push(TimedCheck {
                    at_ns,
                    at: value
                        .get_ref()
                        .as_str()
                        .unwrap_or_default()
                        .trim()
                        .to_string(),
                    expectations,
                });
            }
        }
        self.unless_errors(checks, errors)
    }

    /// The operands of `watch = [...]`, checked like those of `[expect]`.
    pub fn watch_targets(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<(String, Target)>, Vec<Report>> {
        let mut errors = Errors::default();
        let targets: Vec<(String, Target)> = self
            .watch
            .iter()
            .filter_map(|operand| {
                let target = parse_target(operand.get_ref(), self.key_span(operand), set, program);
                errors
                    .keep(target)
                    .map(|target| (operand.get_ref().clone(), target))
            })
            .collect();
        self.unless_errors(targets, errors)
    }
}

fn report(path: &Path, text: &Arc<str>, error: ScenarioError) -> Report {
    Report::new(error).with_source_code(NamedSource::new(path.display().to_string(), text.clone()))
}

/// Errors in the order they stand in the file.
fn sorted(mut errors: Vec<ScenarioError>) -> Vec<ScenarioError> {
    errors.sort_by_key(|error| error.offset());
    errors
}

/// The error for an operand `set` cannot change; a STEP 7 program may also write data blocks.
fn not_settable(text: &str, at: SourceSpan, program: &Program) -> ScenarioError {
    let help = if program.s7.step7 {
        "use I bits, IB, IW, ID, PIB, PIW, PID (German E, EB …, PEB …), or data block operands: `DB5.DBW 4`"
    } else {
        "use I bits, IB, IW, PY, PW, OY or OW"
    };
    let reason = if program.s7.step7 {
        "`set` changes process inputs and data blocks only"
    } else {
        "`set` changes process inputs only"
    };
    ScenarioError::UnknownOperand {
        operand: text.to_string(),
        at,
        reason: reason.into(),
        help: Some(help.into()),
    }
}

/// The change of the input modules that writing `value` to `target` makes; `None` when the
/// target is no input (outputs, flags, timers, counters, data words).
pub fn input_change(target: Target, program: &Program, value: u32) -> Option<InputChange> {
    let outputs = program.layout.output_base();
    let (target, byte, bit, bytes) = match target {
        Target::ImageBit { byte, bit } if byte < outputs => (InputTarget::Process, byte, bit, 0),
        Target::Image { byte, bytes } if byte < outputs => (InputTarget::Process, byte, 0, bytes),
        Target::Periphery {
            byte,
            bytes,
            extended,
        } => {
            let modules = if extended {
                InputTarget::Extended
            } else {
                InputTarget::Process
            };
            (modules, byte, 0, bytes)
        }
        _ => return None,
    };
    Some(InputChange {
        target,
        byte,
        bit,
        bytes,
        value,
    })
}

/// The moments of an event: `at`, and with `every` its repetitions, `count` in all or up to
/// `until`; at most `max_events` of them.
fn occurrences(event: &RawEvent, at_ns: u64, max_events: usize) -> Result<Vec<u64>, ScenarioError> {
    let Some(every) = &event.every else {
        if let Some(count) = &event.count {
            return Err(invalid(
                "`count` repeats an event: give `every` too",
                span(count),
                "no `every`",
                None,
            ));
        }
        if let Some(until) = &event.until {
            return Err(invalid(
                "`until` repeats an event: give `every` too",
                span(until),
                "no `every`",
                None,
            ));
        }
        return Ok(vec![at_ns]);
    };
    let every_ns = duration(every)?;
    if every_ns == 0 {
        return Err(invalid(
            "an event cannot repeat every 0 s",
            span(every),
            "above zero",
            None,
        ));
    }
    let last = match (&event.count, &event.until) {
        (Some(count), None) if *count.get_ref() == 0 => {
            return Err(invalid(
                "`count` is how often the event happens in all: at least 1",
                span(count),
                "at least 1",
                None,
            ));
        }
        (Some(count), None) => (count.get_ref() - 1)
            .checked_mul(every_ns)
            .and_then(|span| span.checked_add(at_ns))
            .unwrap_or(u64::MAX),
        (None, Some(until)) => {
            let until_ns = duration(until)?;
            if until_ns < at_ns {
                return Err(invalid(
                    "`until` is before `at`",
                    span(until),
                    "before the first time",
                    None,
                ));
            }
            until_ns
        }
        (count, _) => {
            let (message, at) = match count {
                Some(count) => ("give `count` or `until`, not both", span(count)),
                None => ("`every` needs `count = N` or `until = \"…\"`", span(every)),
            };
            return Err(invalid(message, at, "how long it repeats", None));
        }
    };
    let times = (last - at_ns) / every_ns + 1;
    if times > max_events as u64 {
        return Err(invalid(
            format!(
                "this event repeats {times} times; a scenario holds at most {max_events} events"
            ),
            span(every),
            "too many repetitions",
            Some("repeat it less often (a longer `every`), or fewer times".into()),
        ));
    }
    Ok((0..times).map(|n| at_ns + n * every_ns).collect())
}

/// A DP station's failure or return (`station`): the SPEED7's.
fn station_failure(
    station: &Spanned<raw::RawStation>,
    profile: &Profile,
) -> Result<Happening, ScenarioError> {
    if profile.family != Family::Speed7 {
        return Err(invalid(
            "`station` belongs to the speed7 profile",
            span(station),
            format!("{} has no DP stations", profile.name),
            None,
        ));
    }
    let inner = station.get_ref();
    Ok(Happening::Station {
        station: inner.number,
        failed: inner.failed,
    })
}

fn check_mode(mode: &Spanned<String>, profile: &Profile) -> Result<bool, ScenarioError> {
    if profile.family != Family::Sinumerik840c {
        return Err(invalid(
            "`mode` belongs to the sinumerik-840c profile",
            span(mode),
            format!("not a setting of {}", profile.name),
            None,
        ));
    }
    match mode.get_ref().as_str() {
        "normal" => Ok(false),
        "special" => Ok(true),
        _ => Err(invalid(
            format!("unknown mode `{}`", mode.get_ref()),
            span(mode),
            "\"normal\" or \"special\"",
            None,
        )),
    }
}

fn check_dialect(dialect: &Spanned<String>) -> Result<Dialect, ScenarioError> {
    match dialect.get_ref().as_str() {
        "s5" => Ok(Dialect::Step5),
        "s7" => Ok(Dialect::Step7),
        other => Err(invalid(
            format!("unknown dialect `{other}`"),
            span(dialect),
            "\"s5\" or \"s7\"",
            Some(
                "`dialect = \"s5\"` reads the program as STEP 5 STL, `\"s7\"` as STEP 7 STL".into(),
            ),
        )),
    }
}

fn check_points(points: &Spanned<String>) -> Result<InterruptPoints, ScenarioError> {
    match points.get_ref().as_str() {
        "block" => Ok(InterruptPoints::Block),
        "operation" => Ok(InterruptPoints::Operation),
        other => Err(invalid(
            format!("unknown interrupt points `{other}`"),
            span(points),
            "\"block\" or \"operation\"",
            None,
        )),
    }
}

fn check_run(run: &Spanned<raw::RawRun>) -> Result<RunLimit, ScenarioError> {
    let run_span = span(run);
    match (&run.get_ref().duration, &run.get_ref().cycles) {
        (Some(text), None) => match duration(text)? {
            0 => Err(invalid("a run of no time", span(text), "0", None)),
            ns => Ok(RunLimit::Duration(ns)),
        },
        (None, Some(cycles)) if *cycles.get_ref() == 0 => Err(invalid(
            "a run of no cycles",
            span(cycles),
            "0",
            Some("run at least one cycle".into()),
        )),
        (None, Some(cycles)) => Ok(RunLimit::Cycles(*cycles.get_ref())),
        _ => Err(invalid(
            "`run` takes either `for` or `cycles`",
            run_span,
            "one of the two",
            Some("run = { for = \"100ms\" } or run = { cycles = 20 }".into()),
        )),
    }
}

fn check_watchdog(watchdog: &Spanned<String>) -> Result<u64, ScenarioError> {
    match duration(watchdog)? {
        ns @ 1..=MAX_WATCHDOG_NS => Ok(ns),
        _ => Err(invalid(
            "the watchdog must be above 0 and at most 6 s",
            span(watchdog),
            "out of range",
            Some("6000 ms is the longest cycle monitoring time the S7-300 class CPUs (and the SPEED7) accept; the S5 CPUs allow less".into()),
        )),
    }
}

/// The edge of an `[[interrupt_input]]`.
fn check_edge(edge: &Spanned<String>) -> Result<Edge, ScenarioError> {
    match edge.get_ref().as_str() {
        "rising" => Ok(Edge::Rising),
        "falling" => Ok(Edge::Falling),
        "both" => Ok(Edge::Both),
        other => Err(invalid(
            format!("unknown edge `{other}`"),
            span(edge),
            "\"rising\", \"falling\" or \"both\"",
            Some("`rising` raises the interrupt when the input goes 0 → 1, `falling` 1 → 0, `both` on either change".into()),
        )),
    }
}

/// The minimum cycle time (`min_cycle`): an S7 CPU's setting, below the cycle monitoring time
/// (S7-400 Automation System, CPU Specifications, 9.3 Different cycle times, "Minimum cycle
/// time"; the SPEED7 is set in STEP 7's hardware configuration as an S7-300 CPU, "Cycle/Clock
/// Memory"). `watchdog_ns` is the scenario's, else the CPU's.
fn check_min_cycle(
    min_cycle: &Spanned<String>,
    watchdog_ns: Option<u64>,
    profile: &Profile,
) -> Result<u64, ScenarioError> {
    if !profile.runs_step7() {
        return Err(invalid(
            format!("the {} CPU has no minimum cycle time", profile.name),
            span(min_cycle),
            "an S7 CPU's setting",
            Some(format!(
                "a minimum scan cycle time is set in an S7 CPU's hardware configuration; the S7 \
                 profiles: {}",
                profile::step7_profiles().join(", ")
            )),
        ));
    }
    let ns = duration(min_cycle)?;
    let watchdog = watchdog_ns.unwrap_or(profile.watchdog_ns);
    if ns == 0 || ns >= watchdog {
        return Err(invalid(
            format!(
                "the minimum cycle time must be above 0 and below the watchdog ({})",
                crate::trace::format_ms(watchdog)
            ),
            span(min_cycle),
            "out of range",
            Some("a cycle waits for the minimum cycle time, and a cycle longer than the watchdog is STOP `ZYK`: set a longer `watchdog`, or a shorter `min_cycle`".into()),
        ));
    }
    Ok(ns)
}

/// The clock memory byte: a flag byte of an S7 CPU (set in its hardware configuration, "Cycle/
/// Clock Memory").
fn check_clock_memory(byte: &Spanned<i64>, profile: &Profile) -> Result<u16, ScenarioError> {
    if !profile.runs_step7() {
        return Err(invalid(
            format!("the {} CPU has no clock memory byte", profile.name),
            span(byte),
            "an S7 CPU's setting",
            Some(format!(
                "the clock memory is set in an S7 CPU's hardware configuration; the S7 \
                 profiles: {}",
                profile::step7_profiles().join(", ")
            )),
        ));
    }
    let flags = i64::from(profile.sizes.flag_bytes);
    match u16::try_from(*byte.get_ref()) {
        Ok(number) if i64::from(number) < flags => Ok(number),
        _ => Err(invalid(
            format!("there is no flag byte MB {}", byte.get_ref()),
            span(byte),
            "out of range",
            Some(format!(
                "the {} CPU has MB 0 to MB {}",
                profile.name,
                flags - 1
            )),
        )),
    }
}

fn check_ob13(
    ob13: &Spanned<raw::RawOb13>,
    profile: &Profile,
) -> Result<Ob13Timing, ScenarioError> {
    let raw = ob13.get_ref();
    if profile.family != Family::S5_95f {
        return Err(invalid(
            "[ob13] belongs to the s5-95f profile",
            span(&raw.interval),
            format!("{} has no time-controlled OB 13", profile.name),
            Some("set `cpu = \"s5-95f\"`".into()),
        ));
    }
    let interval = duration(&raw.interval)?;
    if interval == 0 {
        return Err(invalid(
            "the OB 13 interval must be above zero",
            span(&raw.interval),
            "zero",
            None,
        ));
    }
    let delay = raw.delay.as_ref().map(duration).transpose()?;
    let max_delay = raw.max_delay.as_ref().map(duration).transpose()?;
    if let (Some(delay), Some(max_delay), Some(text)) = (delay, max_delay, &raw.delay)
        && delay > max_delay
    {
        return Err(invalid(
            "the OB 13 delay is above its maximum delay",
            span(text),
            "above `max_delay`",
            Some(
                "the delay t of each call is at most the maximum delay (S5-95F manual, 7.4.4)"
                    .into(),
            ),
        ));
    }
    Ok(Ob13Timing {
        interval_ns: interval,
        delay_ns: delay.unwrap_or(0),
        max_delay_ns: max_delay,
    })
}

/// The OB 35 interval of `[ob35]`: whole milliseconds from 1 to 60000, the range STEP 7
/// configures for the cyclic interrupts of the S7-300 class ("System Software for S7-300/400
/// System and Standard Functions", Organization Blocks, Cyclic Interrupt Organization Blocks;
/// VIPA SPEED7 operation list, OB 28, 29, 32–35); 100 ms without `interval`, their default.
fn check_ob35(ob35: &Spanned<raw::RawOb35>, profile: &Profile) -> Result<u64, ScenarioError> {
    let raw = ob35.get_ref();
    let at = raw.interval.as_ref().map_or_else(|| span(ob35), span);
    if profile.family != Family::Speed7 {
        return Err(invalid(
            "[ob35] belongs to the speed7 profile",
            at,
            format!("{} has no cyclic interrupt OB 35", profile.name),
            Some("OB 35 is an S7 OB: set `cpu = \"speed7\"`".into()),
        ));
    }
    let Some(text) = &raw.interval else {
        return Ok(crate::vm::interrupts::OB35_DEFAULT_NS);
    };
    let interval = duration(text)?;
    if interval == 0 || interval % 1_000_000 != 0 || interval > 60_000_000_000 {
        return Err(invalid(
            format!("the OB 35 interval `{}` is not a whole number of milliseconds from 1 to 60000", text.get_ref()),
            span(text),
            "not configurable",
            Some("STEP 7 sets a cyclic interrupt's interval in ms, 1 ms to 60000 ms; 100 ms is the default".into()),
        ));
    }
    Ok(interval)
}

/// The retentive ranges of `[retentive]`: what it leaves out is the profile's preset; each count
/// within the CPU's operand range.
fn check_retentive(
    table: &Spanned<raw::RawRetentive>,
    profile: &Profile,
) -> Result<crate::profile::Retentive, ScenarioError> {
    let raw = table.get_ref();
    let preset = profile.retentive().ranges;
    let within = |given: &Option<Spanned<u16>>, preset: u16, size: u16, what: &str| match given {
        None => Ok(preset),
        Some(count) if *count.get_ref() <= size => Ok(*count.get_ref()),
        Some(count) => Err(invalid(
            format!(
                "{} retentive {what}, but {} has {size}",
                count.get_ref(),
                profile.name
            ),
            span(count),
            "more than the CPU has",
            Some(format!("give 0 to {size}")),
        )),
    };
    let sizes = profile.sizes;
    Ok(crate::profile::Retentive {
        flag_bytes: within(
            &raw.flag_bytes,
            preset.flag_bytes,
            sizes.flag_bytes,
            "flag bytes",
        )?,
        timers: within(&raw.timers, preset.timers, sizes.timers, "timers")?,
        counters: within(&raw.counters, preset.counters, sizes.counters, "counters")?,
        data_blocks: raw.data_blocks.unwrap_or(preset.data_blocks),
    })
}

/// The logical base addresses `[[hw_module]]` gives: (module, address).
type Addresses = Vec<(u16, u16)>;

fn check_modules(
    modules: &[Spanned<raw::RawHwModule>],
    profile: &Profile,
    errors: &mut Errors,
) -> (Vec<(u16, u8)>, Addresses) {
    let mut mapped: Vec<(u16, u8)> = Vec::new();
    let mut addresses: Vec<(u16, u16)> = Vec::new();
    for module in modules {
        let raw = module.get_ref();
        if profile.family != Family::Speed7 {
            errors.push(invalid(
                "[[hw_module]] belongs to the speed7 profile",
                span(&raw.module),
                format!("{} has no hardware interrupt OBs", profile.name),
                None,
            ));
            continue;
        }
        let (number, ob) = (*raw.module.get_ref(), *raw.ob.get_ref());
        if ob != 40 && ob != 41 {
            errors.push(ScenarioError::UnknownOb {
                ob: format!("OB {ob}"),
                cpu: profile.name,
                at: span(&raw.ob),
                help: Some("hardware interrupts start OB 40 or OB 41".into()),
            });
            continue;
        }
        if mapped.iter().any(|(known, _)| *known == number) {
            errors.push(invalid(
                format!("module {number} is mapped twice"),
                span(&raw.module),
                "mapped before",
                Some("a module's hardware interrupts start one OB: keep one [[hw_module]] per module".into()),
            ));
            continue;
        }
        mapped.push((number, ob));
        let Some(address) = &raw.address else {
            continue;
        };
        let at = *address.get_ref();
        addresses.push((number, at));
    }
    (mapped, addresses)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations() {
        assert_eq!(parse_duration("1.5ms"), Some(1_500_000));
        assert_eq!(parse_duration("200us"), Some(200_000));
        assert_eq!(parse_duration("500µs"), Some(500_000));
        assert_eq!(parse_duration("2s"), Some(2_000_000_000));
        assert_eq!(parse_duration("7 ns"), Some(7));
        assert_eq!(parse_duration("5"), None);
        assert_eq!(parse_duration("-1ms"), None);
        assert_eq!(parse_duration("1h"), None);
    }

    fn parsed(text: &str) -> (Scenario, Vec<String>) {
        let (scenario, reports) = Scenario::parse(Path::new("s.toml"), text);
        let rendered = reports.iter().map(crate::diagnostics::render_plain);
        (scenario, rendered.collect())
    }

    #[test]
    fn the_keys_of_some_cpus_wait_for_the_run_s_cpu() {
        let (mut scenario, errors) = parsed("clock_memory = 100\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(scenario.clock_memory, None);
        let on_step5 = scenario.settle_cpu(profile::default_for(Dialect::Step5));
        let rendered = crate::diagnostics::render_plain(&on_step5[0]);
        assert!(
            rendered.contains("the sinumerik-840c CPU has no clock memory byte"),
            "{rendered}"
        );
        assert!(
            scenario
                .settle_cpu(profile::default_for(Dialect::Step7))
                .is_empty()
        );
        assert_eq!(scenario.clock_memory, Some(100));
    }

    #[test]
    fn dialect_and_extended_are_read() {
        let (scenario, errors) = parsed("dialect = \"s7\"\nextended = true\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(scenario.dialect, Some(Dialect::Step7));
        assert!(scenario.extended);
        let (scenario, errors) = parsed("dialect = \"s5\"\n");
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(scenario.dialect, Some(Dialect::Step5));
        assert!(!scenario.extended);
        let (scenario, _) = parsed("");
        assert_eq!(scenario.dialect, None);
    }

    #[test]
    fn an_unknown_dialect_is_an_error_at_its_value() {
        let (scenario, errors) = parsed("dialect = \"step7\"\nextended = \"yes\"\n");
        assert_eq!(scenario.dialect, None);
        assert_eq!(errors.len(), 2, "{errors:?}");
        assert!(
            errors[0].contains("unknown dialect `step7`"),
            "{}",
            errors[0]
        );
        assert!(errors[0].contains("\"s5\" or \"s7\""), "{}", errors[0]);
        assert!(errors[1].contains("extended = \"yes\""), "{}", errors[1]);
    }
}
