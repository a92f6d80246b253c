//! The watch table (a PG's STATUS VAR): chosen operands read at every cycle boundary, a row
//! each time one of them changed, or one every `--watch-every` of simulated time.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::scenario::expect::actual;
use crate::scenario::operand::Target;
use crate::trace::Event;
use crate::vm::Cpu;

use crate::address::declared;
use crate::address::notation as s7;

/// One row: when, and every watched value in its natural notation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WatchRow {
    pub t_ns: u64,
    pub cycle: u64,
    pub values: Vec<String>,
}

#[derive(Debug, Default)]
pub struct WatchTable {
    names: Vec<String>,
    targets: Vec<Target>,
    every_ns: Option<u64>,
    next_sample_ns: u64,
    last: Option<Vec<String>>,
    pub rows: Vec<WatchRow>,
}

/// A value as the PG shows it: bits 0/1, timers `KT value.base`, counters `KZ`, bytes `KH`,
/// words `KF`, double words `KH`; in a STEP 7 program as STEP 7 shows it: timers `S5T#…`,
/// counters `C#…`, bytes `B#16#…`, words the INT, double words `L#…` or the REAL they hold,
/// and a data block's declared value in its type, as `--state` shows it.
pub fn natural(cpu: &Cpu, target: Target) -> String {
    if let Some(text) = declared_value(cpu, target) {
        return text;
    }
    let step7 = cpu.program.s7.step7;
    match target {
        Target::TimerBit(n) => {
            let mut timer = cpu.timers[usize::from(n)];
            let bit = timer.bit(cpu.clock);
            let (value, base) = (timer.value(cpu.clock), timer.base());
            let time = if step7 {
                s7::s5time(value, base)
            } else {
                format!("KT {value:03}.{base}")
            };
            format!("{time} ({})", u8::from(bit))
        }
        Target::CounterValue(n) => {
            let counter = cpu.counters[usize::from(n)];
            let value = if step7 {
                format!("C#{}", counter.value)
            } else {
                format!("KZ {:03}", counter.value)
            };
            format!("{value} ({})", u8::from(counter.bit()))
        }
        _ => match (actual(cpu, target), target.bytes()) {
            (None, _) => "-".to_string(),
            (Some(raw), 0) => raw.to_string(),
            (Some(raw), 1) if step7 => s7::byte(raw as u8),
            (Some(raw), 1) => format!("KH {raw:02X}"),
            (Some(raw), 2) if step7 => (raw as u16 as i16).to_string(),
            (Some(raw), 2) => format!("KF {:+}", raw as u16 as i16),
            (Some(raw), _) if step7 => s7::double_value(raw),
            (Some(raw), _) => format!("KH {raw:08X}"),
        },
    }
}

/// The value a STEP 7 data block operand reads, in the type its declaration gives it
/// (`W#16#0200`, `T#1S500MS`, `TRUE`); `None` for an operand no declared value is.
fn declared_value(cpu: &Cpu, target: Target) -> Option<String> {
    let Target::S7Data {
        db,
        byte,
        bit,
        bytes,
    } = target
    else {
        return None;
    };
    let tables = &cpu.program.s7.declared_dbs;
    let (_, values) = tables.iter().find(|(number, _)| *number == db)?;
    let value = declared::at(values, byte, bit, bytes)?;
    Some(declared::text(value, cpu.s7_db(db)?))
}

/// A value as a number, for a counter track: timers and counters their value, words signed.
fn number(cpu: &Cpu, target: Target) -> i64 {
    match target {
        Target::TimerBit(n) => i64::from(cpu.timers[usize::from(n)].value(cpu.clock)),
        Target::CounterValue(n) => i64::from(cpu.counters[usize::from(n)].value),
        _ => match (actual(cpu, target), target.bytes()) {
            (None, _) => 0,
            (Some(raw), 2) => i64::from(raw as u16 as i16),
            (Some(raw), _) => i64::from(raw),
        },
    }
}

impl WatchTable {
    pub fn new(watched: Vec<(String, Target)>, every_ns: Option<u64>) -> Self {
        let (names, targets) = watched.into_iter().unzip();
        WatchTable {
            names,
            targets,
            every_ns,
            ..WatchTable::default()
        }
    }

    pub fn is_empty(&self) -> bool {
        self.targets.is_empty()
    }

    /// At a cycle boundary: records a row if a value changed (or the sampling time came), and
    /// traces it.
    pub fn observe(&mut self, cpu: &mut Cpu) {
        if self.is_empty() {
            return;
        }
        let values: Vec<String> = self.targets.iter().map(|t| natural(cpu, *t)).collect();
        let due = match self.every_ns {
            Some(every) => {
                let due = cpu.clock >= self.next_sample_ns;
                while self.next_sample_ns <= cpu.clock {
                    self.next_sample_ns += every;
                }
                due
            }
            None => self.last.as_ref() != Some(&values),
        };
        if !due {
            return;
        }
        if cpu.tracer.enabled {
            let event = Event::Watch {
                cycle: cpu.cycle,
                values: self.names.iter().cloned().zip(values.clone()).collect(),
                numbers: self
                    .names
                    .iter()
                    .zip(&self.targets)
                    .map(|(name, target)| (name.clone(), number(cpu, *target)))
                    .collect(),
            };
            cpu.tracer.emit(cpu.clock, event);
        }
        self.rows.push(WatchRow {
            t_ns: cpu.clock,
            cycle: cpu.cycle,
            values: values.clone(),
        });
        self.last = Some(values);
    }

    /// The table as text: a header with the operands, one line per row.
    pub fn render(&self) -> String {
        let widths: Vec<usize> = self
            .names
            .iter()
            .enumerate()
            .map(|(n, name)| {
                let widest = self.rows.iter().map(|row| row.values[n].len()).max();
                widest.unwrap_or(0).max(name.len())
            })
            .collect();
        let mut out = format!("{:>14}  {:>6}", "time", "cycle");
        for (name, width) in self.names.iter().zip(&widths) {
            let _ = write!(out, "  {name:>width$}");
        }
        out.push('\n');
        for row in &self.rows {
            let _ = write!(
                out,
                "{:>14}  {:>6}",
                crate::trace::format_ms(row.t_ns),
                row.cycle
            );
            for (value, width) in row.values.iter().zip(&widths) {
                let _ = write!(out, "  {value:>width$}");
            }
            out.push('\n');
        }
        out
    }
}

/// The values of a watch event, by operand.
pub type WatchValues = BTreeMap<String, String>;
