//! Checking `[expect]` at the end of a run.

use crate::vm::Cpu;
use crate::vm::bytes::read_bytes;
use crate::vm::cycle::RunOutcome;

use super::operand::{Target, Wanted};

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Expected {
    /// The value the operand must hold; `written` is the number as the file gave it.
    Value {
        target: Target,
        wanted: Wanted,
        written: String,
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
        Target::DataDouble { db, word } => {
            let words = cpu.data_blocks[usize::from(db)].as_ref()?;
            let at = usize::from(word);
            let (high, low) = (*words.get(at)?, *words.get(at + 1)?);
            u32::from(high) << 16 | u32::from(low)
        }
        Target::S7Data {
            db,
            byte,
            bit,
            bytes,
        } => {
            let data = s7_data_bytes(cpu, db, byte, bytes.max(1))?;
            match bytes {
                0 => u32::from(data[0] >> bit & 1),
                _ => read_bytes(data, 0, data.len()),
            }
        }
    })
}

/// `count` bytes of STEP 7 data block `db` from `byte`; `None` when the DB is not loaded (or
/// is shorter now: a DB the program deleted and created anew).
pub fn s7_data_bytes(cpu: &Cpu, db: u16, byte: u32, count: u8) -> Option<&[u8]> {
    let data = cpu.s7_db(db)?;
    let start = usize::try_from(byte).ok()?;
    data.get(start..start + usize::from(count))
}

fn show(target: Target, raw: u32) -> String {
    match target.bytes() {
        0 => raw.to_string(),
        1 => format!("{raw} ({raw:#04X})"),
        2 => format!("{} ({raw:#06X})", raw as u16 as i16),
        _ => format!("{} ({raw:#010X})", raw as i32),
    }
}

/// What an operand holds if it is not the value expected: (expected, actual) as shown; a REAL
/// expected shows the actual value as a REAL.
pub fn value_mismatch(
    cpu: &Cpu,
    target: Target,
    wanted: Wanted,
    written: &str,
) -> Option<(String, String)> {
    match (actual(cpu, target), wanted) {
        (Some(value), _) if wanted.matches(value) => None,
        (Some(value), Wanted::Real(_)) => Some((
            written.to_string(),
            format!("{:?} ({value:#010X})", f32::from_bits(value)),
        )),
        (Some(value), Wanted::Raw(_)) => Some((written.to_string(), show(target, value))),
        (None, _) => Some((written.to_string(), "not loaded".to_string())),
    }
}

pub fn check(cpu: &Cpu, outcome: &RunOutcome, expectations: &[Expectation]) -> Vec<Mismatch> {
    let mut mismatches = Vec::new();
    for expectation in expectations {
        let mismatch = match &expectation.expected {
            Expected::Value {
                target,
                wanted,
                written,
            } => value_mismatch(cpu, *target, *wanted, written),
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
