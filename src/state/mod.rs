//! The CPU's state as a PG shows it: accumulators, status word, open DB, the non-zero bytes of
//! the process images and flags, the timers and counters in use, the data words that are not
//! zero, and at a STOP the processing levels (the ISTACK). One plain structure, printed as text
//! (`--state`) or as JSON (`--state-format json`); `programs/README.md` documents the schema.
//! A STEP 7 program's state is shown the STEP 7 way, with its registers ([`registers`]).

pub mod registers;
pub mod text;
pub mod watch;
pub mod widths;

use std::collections::BTreeMap;

use serde::Serialize;

use crate::address::Layout;
use crate::address::declared::{self, ValueView};
use crate::rules::status::Status;
use crate::vm::stop::Stop;
use crate::vm::{Cpu, IDLE, LevelState, Mode};

pub use registers::Registers;
pub use text::{istack_text, render};

/// The status word, bit by bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct StatusBits {
    pub first_check: bool,
    pub rlo: bool,
    pub sta: bool,
    pub or: bool,
    pub os: bool,
    pub ov: bool,
    pub cc1: bool,
    pub cc0: bool,
    /// The binary result, of a STEP 7 program only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub br: Option<bool>,
}

impl From<Status> for StatusBits {
    fn from(status: Status) -> Self {
        StatusBits {
            first_check: status.first_check(),
            rlo: status.rlo(),
            sta: status.sta(),
            or: status.or_bit(),
            os: status.os(),
            ov: status.ov(),
            cc1: status.cc1(),
            cc0: status.cc0(),
            br: None,
        }
    }
}

impl StatusBits {
    /// The bits of a program's status: with BR when the program is a STEP 7 one.
    pub fn of(level: &crate::vm::LevelState, step7: bool) -> Self {
        StatusBits {
            br: step7.then_some(level.br),
            ..StatusBits::from(level.status)
        }
    }

    /// The status word as a STEP 7 `L STW` loads it: /FC, RLO, STA, OR, OS, OV, CC0, CC1, BR
    /// in bits 0 to 8.
    pub fn word(&self) -> u16 {
        [
            self.first_check,
            self.rlo,
            self.sta,
            self.or,
            self.os,
            self.ov,
            self.cc0,
            self.cc1,
            self.br.unwrap_or(false),
        ]
        .iter()
        .enumerate()
        .fold(0, |word, (n, bit)| word | u16::from(*bit) << n)
    }
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct TimerState {
    pub number: u16,
    /// The remaining time in units of the base.
    pub value: u16,
    /// 0…3: 10 ms, 100 ms, 1 s, 10 s.
    pub base: u8,
    pub running: bool,
    pub bit: bool,
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct CounterState {
    pub number: u16,
    pub value: u16,
    pub bit: bool,
}

/// A return point on a level's block stack.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ReturnPoint {
    pub block: String,
    pub line: u32,
}

/// One processing level at a STOP: the one that was running first, then those it interrupted.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct LevelView {
    pub block: String,
    pub line: u32,
    pub accu: Vec<u32>,
    pub status: StatusBits,
    /// The open DB (STEP 7: the DB register's).
    pub open_db: Option<u16>,
    /// Innermost first.
    pub return_points: Vec<ReturnPoint>,
}

#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct State {
    pub mode: &'static str,
    /// ACCU 1, ACCU 2 (and 3, 4 on CPUs with four).
    pub accu: Vec<u32>,
    pub status: StatusBits,
    /// The open DB (STEP 7: the DB register's).
    pub open_db: Option<u16>,
    /// A STEP 7 program's status word, address registers, DB and DI registers.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registers: Option<Registers>,
    /// `"I"`, `"Q"`, `"F"` (STEP 7: `"M"`) → byte number → value, the non-zero bytes only.
    pub images: BTreeMap<&'static str, BTreeMap<String, u8>>,
    pub timers: Vec<TimerState>,
    pub counters: Vec<CounterState>,
    /// `"DB 10"` → word number → value, the non-zero words only; a STEP 7 program's data
    /// blocks byte by byte: byte offset → value.
    pub data_blocks: BTreeMap<String, BTreeMap<String, u16>>,
    /// A STEP 7 program's data blocks with declarations: `"DB 5"` → each declared value in
    /// address order, as STEP 7's data view shows it (the bytes stay in `data_blocks`).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    pub declared_data_blocks: BTreeMap<String, Vec<ValueView>>,
    /// At a STOP: the running level first, then the interrupted ones.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub levels: Option<Vec<LevelView>>,
    /// The widths the program uses its addresses in, for the text (JSON keeps bytes).
    #[serde(skip)]
    pub widths: widths::Widths,
    /// The program is a STEP 7 one: the text is in STEP 7 notation.
    #[serde(skip)]
    pub step7: bool,
}

/// ACCU 1 and 2 of a level, and 3 and 4 on the CPUs that have four.
pub fn accumulators(cpu: &Cpu, level: &LevelState) -> Vec<u32> {
    let mut accu = vec![level.accu1, level.accu2];
    if cpu.profile.accumulators == 4 {
        accu.extend([level.accu3, level.accu4]);
    }
    accu
}

fn non_zero_bytes(bytes: &[u8]) -> BTreeMap<String, u8> {
    bytes
        .iter()
        .enumerate()
        .filter(|(_, byte)| **byte != 0)
        .map(|(n, byte)| (n.to_string(), *byte))
        .collect()
}

/// The name of the flag area: `F` in STEP 5, `M` in STEP 7.
pub fn flag_area(step7: bool) -> &'static str {
    if step7 { "M" } else { "F" }
}

fn images(cpu: &Cpu) -> BTreeMap<&'static str, BTreeMap<String, u8>> {
    let layout: Layout = cpu.program.layout;
    let image = usize::from(layout.image_bytes);
    let flags = usize::from(layout.flag_base());
    [
        ("I", &cpu.image[..image]),
        ("Q", &cpu.image[image..2 * image]),
        (
            flag_area(cpu.program.s7.step7),
            &cpu.image[flags..flags + usize::from(layout.flag_bytes)],
        ),
    ]
    .into_iter()
    .map(|(area, bytes)| (area, non_zero_bytes(bytes)))
    .collect()
}

fn timers(cpu: &Cpu) -> Vec<TimerState> {
    touched(&cpu.timers, |number, mut timer| TimerState {
        number,
        bit: timer.bit(cpu.clock),
        value: timer.value(cpu.clock),
        base: timer.base(),
        running: timer.running,
    })
}

fn counters(cpu: &Cpu) -> Vec<CounterState> {
    touched(&cpu.counters, |number, counter| CounterState {
        number,
        value: counter.value,
        bit: counter.bit(),
    })
}

/// The state of each timer (counter) the run changed from its start, by number.
fn touched<T: Copy + Default + PartialEq, S>(all: &[T], state: impl Fn(u16, T) -> S) -> Vec<S> {
    let untouched = T::default();
    let changed = all
        .iter()
        .enumerate()
        .filter(|(_, item)| **item != untouched);
    changed
        .map(|(number, item)| state(number as u16, *item))
        .collect()
}

/// The data blocks' units that are not 0 (a STEP 5 block's words, a STEP 7 block's bytes):
/// `"DB 5"` → offset → value.
fn data_blocks(cpu: &Cpu) -> BTreeMap<String, BTreeMap<String, u16>> {
    let tables = &cpu.program.s7;
    if tables.step7 {
        non_zero(
            cpu.s7_data.iter().enumerate().filter_map(|(slot, bytes)| {
                Some((tables.db_number(slot as u16), bytes.as_deref()?))
            }),
        )
    } else {
        non_zero(
            cpu.data_blocks
                .iter()
                .enumerate()
                .filter_map(|(number, words)| Some((number as u16, words.as_deref()?))),
        )
    }
}

fn non_zero<'a, T: Copy + Into<u16> + 'a>(
    blocks: impl Iterator<Item = (u16, &'a [T])>,
) -> BTreeMap<String, BTreeMap<String, u16>> {
    blocks
        .map(|(number, units)| {
            let non_zero = units
                .iter()
                .map(|unit| (*unit).into())
                .enumerate()
                .filter(|(_, unit)| *unit != 0)
                .map(|(n, unit)| (n.to_string(), unit))
                .collect();
            (format!("DB {number}"), non_zero)
        })
        .collect()
}

/// The STEP 7 data blocks with declarations: `"DB 5"` → its values by name, in their types.
fn declared_data_blocks(cpu: &Cpu) -> BTreeMap<String, Vec<ValueView>> {
    let tables = &cpu.program.s7;
    tables
        .declared_dbs
        .iter()
        .filter_map(|(number, values)| {
            let slot = tables.db_slot(*number)?;
            let bytes = cpu.s7_data.get(usize::from(slot))?.as_ref()?;
            Some((format!("DB {number}"), declared::view(values, bytes)))
        })
        .collect()
}

fn return_points(cpu: &Cpu, frames: std::ops::Range<usize>) -> Vec<ReturnPoint> {
    cpu.return_points(frames)
        .map(|(block, pc)| ReturnPoint {
            block: cpu.block_id(block).to_string(),
            line: cpu.line_of(block, pc),
        })
        .collect()
}

/// The levels the running one interrupted, innermost first, from their saved registers.
fn interrupted(cpu: &Cpu) -> Vec<LevelView> {
    let mut interrupted = Vec::new();
    if cpu.level.block == IDLE {
        return interrupted;
    }
    let mut base = cpu.level.level_base;
    for level in cpu.levels.iter().rev() {
        if level.block == IDLE {
            break;
        }
        let top = base;
        base = level.level_base;
        interrupted.push(LevelView {
            block: cpu.block_id(level.block).to_string(),
            line: cpu.line_of(level.block, level.pc),
            accu: accumulators(cpu, level),
            status: StatusBits::of(level, cpu.program.s7.step7),
            open_db: open_db(cpu, level),
            return_points: return_points(cpu, base..top),
        });
    }
    interrupted
}

fn running(cpu: &Cpu, block: u16, pc: u32, return_points: Vec<ReturnPoint>) -> LevelView {
    LevelView {
        block: cpu.block_id(block).to_string(),
        line: cpu.line_of(block, pc),
        accu: accumulators(cpu, &cpu.level),
        status: StatusBits::of(&cpu.level, cpu.program.s7.step7),
        open_db: open_db(cpu, &cpu.level),
        return_points,
    }
}

/// The open DB of a level: a STEP 7 program's DB register (0 is none).
fn open_db(cpu: &Cpu, level: &LevelState) -> Option<u16> {
    if cpu.program.s7.step7 {
        (level.db != 0).then(|| cpu.program.s7.db_number(level.db))
    } else {
        level.open_db.map(u16::from)
    }
}

/// The levels at a STOP: the running one as the STOP recorded it (its return points are the
/// head of the STOP's BSTACK), then the interrupted ones.
pub fn levels(cpu: &Cpu, stop: &Stop) -> Vec<LevelView> {
    let Some(block) = stop.block else {
        return Vec::new();
    };
    let interrupted = interrupted(cpu);
    let below: usize = interrupted
        .iter()
        .map(|level| 1 + level.return_points.len())
        .sum();
    let own = stop.stack.len().saturating_sub(1 + below);
    let points = stop
        .stack
        .iter()
        .skip(1)
        .take(own)
        .map(|entry| ReturnPoint {
            block: entry.block.clone(),
            line: entry.line,
        })
        .collect();
    std::iter::once(running(cpu, block, stop.pc, points))
        .chain(interrupted)
        .collect()
}

/// The levels of a CPU stopped between two operations (the debugger): the running one at its
/// next operation first.
pub fn levels_now(cpu: &Cpu) -> Vec<LevelView> {
    if cpu.level.block == IDLE {
        return Vec::new();
    }
    let points = return_points(cpu, cpu.level.level_base..cpu.frames.len());
    let now = running(cpu, cpu.level.block, cpu.level.pc, points);
    std::iter::once(now).chain(interrupted(cpu)).collect()
}

impl State {
    /// The state of `cpu` now; `stop` adds the levels.
    pub fn capture(cpu: &Cpu, stop: Option<&Stop>) -> State {
        let step7 = cpu.program.s7.step7;
        State {
            mode: cpu.mode.name(),
            accu: accumulators(cpu, &cpu.level),
            status: StatusBits::of(&cpu.level, step7),
            open_db: open_db(cpu, &cpu.level),
            registers: step7.then(|| Registers::of(cpu)),
            images: images(cpu),
            timers: timers(cpu),
            counters: counters(cpu),
            data_blocks: data_blocks(cpu),
            declared_data_blocks: declared_data_blocks(cpu),
            levels: stop
                .filter(|_| cpu.mode == Mode::Stop)
                .map(|stop| levels(cpu, stop)),
            widths: widths::Widths::of(&cpu.program),
            step7,
        }
    }
}
