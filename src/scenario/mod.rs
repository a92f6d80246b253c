//! Scenario files (SPEC §3): the program, CPU, run length, timed events and expected results.
//! Loading checks the keys, durations and OBs; operands are resolved once the program is
//! compiled, in its mnemonic set or English.

pub mod error;
pub mod expect;
pub mod operand;
mod raw;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{NamedSource, Report, SourceSpan};
use toml::Spanned;

use crate::compiler::Program;
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Family, InterruptPoints, Profile};
use crate::vm::cycle::RunLimit;
use crate::vm::interrupts::{Happening, InputChange, InputTarget, Ob13Timing, Scheduled};

pub use error::ScenarioError;
pub use expect::{Expectation, Expected};
use operand::{Target, parse_target, raw_value};
use raw::{ProgramList, RawEvent, RawScenario};

/// A loaded scenario.
#[derive(Debug)]
pub struct Scenario {
    pub path: PathBuf,
    text: Arc<str>,
    pub programs: Vec<PathBuf>,
    pub cpu: Option<&'static Profile>,
    pub special_mode: Option<bool>,
    pub points: Option<InterruptPoints>,
    pub limit: Option<RunLimit>,
    pub watchdog_ns: Option<u64>,
    pub ob13: Option<Ob13Timing>,
    pub hw_modules: Vec<(u16, u8)>,
    events: Vec<RawEvent>,
    expect: Vec<(String, Spanned<toml::Value>)>,
}

fn span<T>(spanned: &Spanned<T>) -> SourceSpan {
    let range = spanned.span();
    (range.start, range.end - range.start).into()
}

/// `"1.5ms"`, `"200us"`, `"2s"`, `"100ns"` to nanoseconds.
pub fn parse_duration(text: &str) -> Option<u64> {
    let text = text.trim();
    let split = text.find(|c: char| c.is_ascii_alphabetic())?;
    let (number, unit) = text.split_at(split);
    let value: f64 = number.trim().parse().ok()?;
    let scale = match unit.trim() {
        "ns" => 1.0,
        "us" | "µs" => 1e3,
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
    ScenarioError::Invalid {
        message: message.into(),
        at,
        label: label.into(),
        help,
    }
}

impl Scenario {
    /// Renders an error with this scenario's text.
    pub fn report(&self, error: ScenarioError) -> Report {
        Report::new(error).with_source_code(NamedSource::new(
            self.path.display().to_string(),
            self.text.clone(),
        ))
    }

    pub fn load(path: &Path) -> Result<Scenario, Report> {
        let text = std::fs::read_to_string(path).map_err(|error| {
            Report::new(ScenarioError::Read {
                path: path.display().to_string(),
                reason: error.to_string(),
            })
        })?;
        Scenario::parse(path, &text)
    }

    pub fn parse(path: &Path, text: &str) -> Result<Scenario, Report> {
        let text: Arc<str> = Arc::from(text);
        let with_source = |error: ScenarioError| {
            Report::new(error)
                .with_source_code(NamedSource::new(path.display().to_string(), text.clone()))
        };
        let raw: RawScenario = toml::from_str(&text).map_err(|error| {
            let at = error
                .span()
                .map(|range| SourceSpan::from((range.start, range.end - range.start)));
            with_source(ScenarioError::Syntax {
                message: error.message().to_string(),
                at,
            })
        })?;
        Scenario::from_raw(path, text.clone(), raw).map_err(with_source)
    }

    fn from_raw(path: &Path, text: Arc<str>, raw: RawScenario) -> Result<Scenario, ScenarioError> {
        let base = path.parent().unwrap_or(Path::new("."));
        let programs = match raw.program.as_ref().map(Spanned::get_ref) {
            None => Vec::new(),
            Some(ProgramList::One(one)) => vec![base.join(one)],
            Some(ProgramList::Many(many)) => many.iter().map(|one| base.join(one)).collect(),
        };
        let cpu = match &raw.cpu {
            None => None,
            Some(name) => Some(profile::find(name.get_ref()).ok_or_else(|| {
                invalid(
                    format!("unknown CPU `{}`", name.get_ref()),
                    span(name),
                    "no such profile",
                    Some(format!("the profiles are: {}", profile::names().join(", "))),
                )
            })?),
        };
        let profile = cpu
            .unwrap_or_else(|| profile::find(profile::DEFAULT_PROFILE).expect("default profile"));
        let special_mode = match &raw.mode {
            None => None,
            Some(mode) => {
                if profile.family != Family::Sinumerik840c {
                    return Err(invalid(
                        "`mode` belongs to the sinumerik-840c profile",
                        span(mode),
                        format!("not a setting of {}", profile.name),
                        None,
                    ));
                }
                match mode.get_ref().as_str() {
                    "normal" => Some(false),
                    "special" => Some(true),
                    _ => {
                        return Err(invalid(
                            format!("unknown mode `{}`", mode.get_ref()),
                            span(mode),
                            "\"normal\" or \"special\"",
                            None,
                        ));
                    }
                }
            }
        };
        let points = match &raw.interrupt_points {
            None => None,
            Some(points) => Some(match points.get_ref().as_str() {
                "block" => InterruptPoints::Block,
                "operation" => InterruptPoints::Operation,
                other => {
                    return Err(invalid(
                        format!("unknown interrupt points `{other}`"),
                        span(points),
                        "\"block\" or \"operation\"",
                        None,
                    ));
                }
            }),
        };
        let limit = match &raw.run {
            None => None,
            Some(run) => {
                let run_span = span(run);
                let run = run.get_ref();
                match (&run.duration, &run.cycles) {
                    (Some(duration_text), None) => {
                        Some(RunLimit::Duration(duration(duration_text)?))
                    }
                    (None, Some(cycles)) => Some(RunLimit::Cycles(*cycles.get_ref())),
                    _ => {
                        return Err(invalid(
                            "`run` takes either `for` or `cycles`",
                            run_span,
                            "one of the two",
                            Some("run = { for = \"100ms\" } or run = { cycles = 20 }".into()),
                        ));
                    }
                }
            }
        };
        let watchdog_ns = raw.watchdog.as_ref().map(duration).transpose()?;
        let ob13 = match &raw.ob13 {
            None => None,
            Some(ob13) => {
                if profile.family != Family::S5_95f {
                    return Err(invalid(
                        "[ob13] belongs to the s5-95f profile",
                        span(&ob13.interval),
                        format!("{} has no time-controlled OB 13", profile.name),
                        Some("set `cpu = \"s5-95f\"`".into()),
                    ));
                }
                let interval = duration(&ob13.interval)?;
                if interval == 0 {
                    return Err(invalid(
                        "the OB 13 interval must be above zero",
                        span(&ob13.interval),
                        "zero",
                        None,
                    ));
                }
                let delay = ob13.delay.as_ref().map(duration).transpose()?;
                let max_delay = ob13.max_delay.as_ref().map(duration).transpose()?;
                if let (Some(delay), Some(max_delay), Some(text)) = (delay, max_delay, &ob13.delay)
                    && delay > max_delay
                {
                    return Err(invalid(
                        "the OB 13 delay is above its maximum delay",
                        span(text),
                        "above `max_delay`",
                        Some("the delay t of each call is at most the maximum delay (S5-95F manual, 7.4.4)".into()),
                    ));
                }
                Some(Ob13Timing {
                    interval_ns: interval,
                    delay_ns: delay.unwrap_or(0),
                    max_delay_ns: max_delay,
                })
            }
        };
        let mut hw_modules = Vec::new();
        for module in raw.hw_module.iter().flatten() {
            if profile.family != Family::Speed7 {
                return Err(invalid(
                    "[[hw_module]] belongs to the speed7 profile",
                    span(&module.module),
                    format!("{} has no hardware interrupt OBs", profile.name),
                    None,
                ));
            }
            let ob = *module.ob.get_ref();
            if ob != 40 && ob != 41 {
                return Err(ScenarioError::UnknownOb {
                    ob: format!("OB {ob}"),
                    cpu: profile.name,
                    at: span(&module.ob),
                    help: Some("hardware interrupts start OB 40 or OB 41".into()),
                });
            }
            hw_modules.push((*module.module.get_ref(), ob));
        }
        let events = raw.event.unwrap_or_default();
        let expect = raw.expect.unwrap_or_default().into_iter().collect();
        Ok(Scenario {
            path: path.to_path_buf(),
            text,
            programs,
            cpu,
            special_mode,
            points,
            limit,
            watchdog_ns,
            ob13,
            hw_modules,
            events,
            expect,
        })
    }

    /// Where the key `key` stands before `value_start`, for labels on expectation keys.
    fn key_span(&self, key: &str, value_start: usize) -> SourceSpan {
        let before = &self.text[..value_start.min(self.text.len())];
        match before.rfind(key) {
            Some(start) => (start, key.len()).into(),
            None => (value_start, 0).into(),
        }
    }

    /// The integer a `set` or `[expect]` entry gives (booleans count as 0 and 1) and the raw
    /// value it stands for in the operand.
    fn value(
        &self,
        target: Target,
        value: &Spanned<toml::Value>,
        operand: &str,
    ) -> Result<(i64, u32), ScenarioError> {
        let bad = |shown: String, range: String| ScenarioError::BadValue {
            operand: operand.into(),
            value: shown,
            at: span(value),
            range,
        };
        let number = match value.get_ref() {
            toml::Value::Integer(number) => *number,
            toml::Value::Boolean(flag) => i64::from(*flag),
            other => return Err(bad(other.to_string(), "an integer".into())),
        };
        let raw = raw_value(target, number).map_err(|range| bad(number.to_string(), range))?;
        Ok((number, raw))
    }

    /// The timed events, with operands resolved against the compiled program.
    pub fn schedule(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<Scheduled>, ScenarioError> {
        let profile = program.profile;
        let mut schedule = Vec::new();
        for event in &self.events {
            let at_ns = duration(&event.at)?;
            let kinds = usize::from(event.set.is_some())
                + usize::from(event.interrupt.is_some())
                + usize::from(event.hw_interrupt.is_some());
            if kinds != 1 {
                return Err(invalid(
                    "an [[event]] has exactly one of `set`, `interrupt`, `hw_interrupt`",
                    span(&event.at),
                    "this event",
                    None,
                ));
            }
            if let Some(changes) = &event.set {
                let mut resolved = Vec::new();
                for (operand, value) in changes {
                    let at = self.key_span(&format!("\"{operand}\""), value.span().start);
                    let target = parse_target(operand, at, set, profile, program.layout)?;
                    let (input_target, byte, bit, bytes) = match target {
                        Target::ImageBit { byte, bit } if byte < program.layout.output_base() => {
                            (InputTarget::Process, byte, bit, 0)
                        }
                        Target::Image { byte, bytes } if byte < program.layout.output_base() => {
                            (InputTarget::Process, byte, 0, bytes)
                        }
                        Target::Periphery {
                            byte,
                            bytes,
                            extended,
                        } => (
                            if extended {
                                InputTarget::Extended
                            } else {
                                InputTarget::Process
                            },
                            byte,
                            0,
                            bytes,
                        ),
                        _ => {
                            return Err(ScenarioError::UnknownOperand {
                                operand: operand.clone(),
                                at,
                                reason: "`set` changes process inputs only".into(),
                                help: Some("use I bits, IB, IW, PY, PW, OY or OW".into()),
                            });
                        }
                    };
                    let (_, raw) = self.value(target, value, operand)?;
                    resolved.push(InputChange {
                        target: input_target,
                        byte,
                        bit,
                        bytes,
                        value: raw,
                    });
                }
                schedule.push(Scheduled {
                    at_ns,
                    what: Happening::SetInputs(resolved),
                });
            }
            if let Some(interrupt) = &event.interrupt {
                let ob = self.interrupt_ob(interrupt, profile)?;
                schedule.push(Scheduled {
                    at_ns,
                    what: Happening::Interrupt { ob },
                });
            }
            if let Some(hardware) = &event.hw_interrupt {
                if profile.family != Family::Speed7 {
                    return Err(invalid(
                        "`hw_interrupt` belongs to the speed7 profile",
                        span(hardware),
                        format!("{} has no hardware interrupts", profile.name),
                        None,
                    ));
                }
                let inner = hardware.get_ref();
                if !self
                    .hw_modules
                    .iter()
                    .any(|(module, _)| *module == inner.module)
                {
                    return Err(invalid(
                        format!("module {} has no [[hw_module]] entry", inner.module),
                        span(hardware),
                        "unknown module",
                        Some("add [[hw_module]] with `module` and `ob = 40` or `41`".into()),
                    ));
                }
                let active_for_ns = duration(&inner.active_for)?;
                schedule.push(Scheduled {
                    at_ns,
                    what: Happening::Hardware {
                        module: inner.module,
                        channel: inner.channel,
                        active_for_ns,
                    },
                });
            }
        }
        Ok(schedule)
    }

    fn interrupt_ob(
        &self,
        text: &Spanned<String>,
        profile: &'static Profile,
    ) -> Result<u8, ScenarioError> {
        let name = text.get_ref();
        let digits = name
            .trim()
            .strip_prefix("OB")
            .or_else(|| name.trim().strip_prefix("ob"))
            .map(str::trim);
        let allowed: Vec<u8> = profile
            .interrupt_obs
            .iter()
            .map(|entry| entry.ob)
            .filter(|ob| match profile.family {
                Family::S5_95f => *ob != 13,
                Family::Speed7 => false,
                Family::Sinumerik840c => true,
            })
            .collect();
        let help = match profile.family {
            Family::Speed7 => Some("SPEED7 interrupts come from modules: use `hw_interrupt = { module, channel, active_for }`".to_string()),
            Family::S5_95f => Some("OB 13 runs at its [ob13] interval; `interrupt` requests OB 2 or OB 3".to_string()),
            Family::Sinumerik840c => Some(format!("the interrupt OBs are: {}", allowed.iter().map(|ob| format!("OB {ob}")).collect::<Vec<_>>().join(", "))),
        };
        match digits.and_then(|digits| digits.parse::<u8>().ok()) {
            Some(ob) if allowed.contains(&ob) => Ok(ob),
            _ => Err(ScenarioError::UnknownOb {
                ob: name.clone(),
                cpu: profile.name,
                at: span(text),
                help,
            }),
        }
    }

    /// The `[expect]` table, resolved against the compiled program.
    pub fn expectations(
        &self,
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Vec<Expectation>, ScenarioError> {
        let mut expectations = Vec::new();
        for (key, value) in &self.expect {
            let at = self.key_span(key, value.span().start);
            let expected = match key.as_str() {
                "mode" => match value.get_ref().as_str() {
                    Some(mode @ ("RUN" | "STOP")) => Expected::Mode(mode.to_string()),
                    _ => {
                        return Err(ScenarioError::BadValue {
                            operand: key.clone(),
                            value: value.get_ref().to_string(),
                            at: span(value),
                            range: "\"RUN\" or \"STOP\"".into(),
                        });
                    }
                },
                "stop_cause" => match value.get_ref().as_str() {
                    Some(cause) => Expected::StopCause(cause.to_string()),
                    None => {
                        return Err(ScenarioError::BadValue {
                            operand: key.clone(),
                            value: value.get_ref().to_string(),
                            at: span(value),
                            range: "a cause such as \"WECK\"".into(),
                        });
                    }
                },
                operand => {
                    let target = parse_target(operand, at, set, program.profile, program.layout)?;
                    let (number, raw) = self.value(target, value, operand)?;
                    Expected::Value {
                        target,
                        raw,
                        written: number,
                    }
                }
            };
            expectations.push(Expectation {
                name: key.clone(),
                expected,
            });
        }
        Ok(expectations)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations() {
        assert_eq!(parse_duration("1.5ms"), Some(1_500_000));
        assert_eq!(parse_duration("200us"), Some(200_000));
        assert_eq!(parse_duration("2s"), Some(2_000_000_000));
        assert_eq!(parse_duration("7 ns"), Some(7));
        assert_eq!(parse_duration("5"), None);
        assert_eq!(parse_duration("-1ms"), None);
        assert_eq!(parse_duration("1h"), None);
    }
}
