//! Checking `[expect]` at the end of a run.

use crate::vm::Cpu;
use crate::vm::cycle::RunOutcome;
use crate::vm::exec::read_bytes;

use super::operand::Target;

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Expected {
    /// The raw value the operand must hold; `written` is the number as the file gave it.
    Value {
        target: Target,
        raw: u32,
        written: i64,
    },
    Mode(String),
    StopCause(String),
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Expectation {
    pub name: String,
    pub expected: Expected,
}

/// One expectation that did not hold.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mismatch {
    pub name: String,
    pub expected: String,
    pub actual: String,
}

/// The raw value of a target in the CPU at the end of the run; `None` when it does not exist
/// (a DB that is not loaded).
pub fn actual(cpu: &Cpu, target: Target) -> Option<u32> {
    Some(match target {
        Target::ImageBit { byte, bit } => u32::from(cpu.image[usize::from(byte)] >> bit & 1),
        Target::Image { byte, bytes } => {
            read_bytes(&cpu.image[..], usize::from(byte), usize::from(bytes))
        }
        Target::Periphery {
            byte,
            bytes,
            extended,
        } => {
            let memory = if extended {
                &cpu.extended_outputs
            } else {
                &cpu.outputs
            };
            read_bytes(memory, usize::from(byte), usize::from(bytes))
        }
        Target::TimerBit(n) => {
            let mut timer = cpu.timers[usize::from(n)];
            u32::from(timer.bit(cpu.clock))
        }
        Target::CounterValue(n) => u32::from(cpu.counters[usize::from(n)].value),
        Target::DataWord { db, word } => u32::from(
            *cpu.data_blocks[usize::from(db)]
                .as_ref()?
                .get(usize::from(word))?,
        ),
    })
}

fn show(target: Target, raw: u32) -> String {
    match target.bytes() {
        0 => raw.to_string(),
        1 => format!("{raw} ({raw:#04X})"),
        2 => format!("{} ({raw:#06X})", raw as u16 as i16),
        _ => format!("{} ({raw:#010X})", raw as i32),
    }
}

/// What an operand holds if it is not the value expected: (expected, actual) as shown.
pub fn value_mismatch(
    cpu: &Cpu,
    target: Target,
    raw: u32,
    written: i64,
) -> Option<(String, String)> {
    match actual(cpu, target) {
        Some(value) if value == raw => None,
        Some(value) => Some((written.to_string(), show(target, value))),
        None => Some((written.to_string(), "not loaded".to_string())),
    }
}

pub fn check(cpu: &Cpu, outcome: &RunOutcome, expectations: &[Expectation]) -> Vec<Mismatch> {
    let mut mismatches = Vec::new();
    for expectation in expectations {
        let mismatch = match &expectation.expected {
            Expected::Value {
                target,
                raw,
                written,
            } => value_mismatch(cpu, *target, *raw, *written),
            Expected::Mode(mode) => (outcome.mode.name() != mode)
                .then(|| (mode.clone(), outcome.mode.name().to_string())),
            Expected::StopCause(cause) => {
                let actual = outcome
                    .stop
                    .as_ref()
                    .map_or("none", |stop| stop.cause.code());
                (actual != cause).then(|| (cause.clone(), actual.to_string()))
            }
        };
        if let Some((expected, actual)) = mismatch {
            mismatches.push(Mismatch {
                name: expectation.name.clone(),
                expected,
                actual,
            });
        }
    }
    mismatches
}
