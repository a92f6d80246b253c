//! What the editor sees of a paused CPU: the OB levels as threads, each level's block stack as
//! its stack trace, and the scopes of a frame (registers, locals and parameters, the timers
//! and counters its block uses), in the dialect's notation as `awl debug` prints them.

use serde_json::{Value, json};

use crate::address::declared::{self, DeclaredParameter, DeclaredValue, Format};
use crate::debug::show::{self, target};
use crate::mnemonics::{BlockKind, MnemonicSet};
use crate::program_status::operand as status;
use crate::state::{self, StatusBits};
use crate::step7::bytecode::{Place, Target};
use crate::vm::s7::memory::{Context, Located};
use crate::vm::{Cpu, IDLE, LevelState};

/// Frame ids: a thread's frames are numbered from its index times this.
const FRAMES_PER_THREAD: i64 = 1000;
/// Variable references: a frame's scopes are numbered from its id times this.
const SCOPES_PER_FRAME: i64 = 4;

/// The scopes of a frame, in the order the editor lists them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    Registers = 1,
    Locals = 2,
    TimersAndCounters = 3,
}

impl Scope {
    fn name(self) -> &'static str {
        match self {
            Scope::Registers => "Registers",
            Scope::Locals => "Locals",
            Scope::TimersAndCounters => "Timers and counters",
        }
    }
}

/// One OB level.
pub struct Thread<'a> {
    pub id: i64,
    pub name: String,
    pub level: &'a LevelState,
    /// Where this level's frames end on the block stack.
    pub frames: usize,
    /// Innermost first.
    pub stack: Vec<(u16, u32)>,
}

/// The levels, running first; a thread for OB 1 when no block runs (before the run, between
/// cycles), so the editor always has one.
pub fn threads(cpu: &Cpu) -> Vec<Thread<'_>> {
    if cpu.level.block == IDLE {
        return vec![Thread {
            id: 1,
            name: "OB 1".to_string(),
            level: &cpu.level,
            frames: cpu.frames.len(),
            stack: Vec::new(),
        }];
    }
    let levels = cpu.level_stacks(cpu.level.pc);
    let obs: Vec<String> = levels
        .iter()
        .map(|(_, stack)| {
            stack
                .last()
                .map_or(String::new(), |(b, _)| cpu.block_id(*b).to_string())
        })
        .collect();
    // A level's frames end where the level above begins.
    let ends: Vec<usize> = std::iter::once(cpu.frames.len())
        .chain(levels.iter().map(|(level, _)| level.level_base))
        .collect();
    levels
        .into_iter()
        .enumerate()
        .map(|(n, (level, stack))| {
            let ob = stack
                .last()
                .map_or(1, |(block, _)| cpu.block_id(*block).number);
            let name = match obs.get(n + 1) {
                Some(below) => format!("{} (interrupting {below})", obs[n]),
                None => obs[n].clone(),
            };
            Thread {
                id: i64::from(ob),
                name,
                level,
                frames: ends[n],
                stack,
            }
        })
        .collect()
}

pub fn threads_body(cpu: &Cpu) -> Value {
    let threads: Vec<Value> = threads(cpu)
        .iter()
        .map(|thread| json!({ "id": thread.id, "name": thread.name }))
        .collect();
    json!({ "threads": threads })
}

/// The running level's thread.
pub fn running_thread(cpu: &Cpu) -> i64 {
    threads(cpu).first().map_or(1, |thread| thread.id)
}

fn source(cpu: &Cpu, block: u16) -> Value {
    let file = cpu.program.blocks[usize::from(block)].header.file;
    let path = &cpu.sources.get(file).name;
    let name = std::path::Path::new(path)
        .file_name()
        .map_or(path.clone(), |name| name.to_string_lossy().into_owned());
    json!({ "name": name, "path": absolute(path) })
}

/// A path as the editor compares it: absolute.
pub fn absolute(path: &str) -> String {
    std::path::absolute(path).map_or(path.to_string(), |path| path.display().to_string())
}

pub fn stack_trace(cpu: &Cpu, thread_id: i64) -> Option<Value> {
    let threads = threads(cpu);
    let (index, thread) = threads
        .iter()
        .enumerate()
        .find(|(_, thread)| thread.id == thread_id)?;
    let frames: Vec<Value> = thread
        .stack
        .iter()
        .enumerate()
        .map(|(depth, (block, pc))| {
            json!({
                "id": frame_id(index, depth),
                "name": cpu.block_id(*block).to_string(),
                "source": source(cpu, *block),
                "line": cpu.line_of(*block, *pc),
                "column": 1,
            })
        })
        .collect();
    Some(json!({ "stackFrames": frames, "totalFrames": frames.len() }))
}

fn frame_id(thread: usize, depth: usize) -> i64 {
    (thread as i64 + 1) * FRAMES_PER_THREAD + depth as i64
}

/// A frame's thread index and depth.
fn frame_of(id: i64) -> (usize, usize) {
    (
        (id / FRAMES_PER_THREAD - 1).max(0) as usize,
        (id % FRAMES_PER_THREAD) as usize,
    )
}

pub fn scopes(frame: i64) -> Value {
    let scopes: Vec<Value> = [Scope::Registers, Scope::Locals, Scope::TimersAndCounters]
        .iter()
        .map(|scope| {
            json!({
                "name": scope.name(),
                "variablesReference": frame * SCOPES_PER_FRAME + *scope as i64,
                "expensive": false,
            })
        })
        .collect();
    json!({ "scopes": scopes })
}

/// One variable: its name, its value, and the operand `setVariable` writes, if any.
pub struct Variable {
    pub name: String,
    pub value: String,
    pub operand: Option<String>,
}

fn variable(name: impl Into<String>, value: impl Into<String>) -> Variable {
    Variable {
        name: name.into(),
        value: value.into(),
        operand: None,
    }
}

/// The variables of a scope reference; `None` for a reference that names none.
pub fn variables(cpu: &Cpu, reference: i64, set: MnemonicSet) -> Option<Vec<Variable>> {
    let scope = match reference % SCOPES_PER_FRAME {
        1 => Scope::Registers,
        2 => Scope::Locals,
        3 => Scope::TimersAndCounters,
        _ => return None,
    };
    let (thread, depth) = frame_of(reference / SCOPES_PER_FRAME);
    let threads = threads(cpu);
    let thread = threads.get(thread)?;
    let frame = thread.stack.get(depth).copied();
    Some(match (scope, frame) {
        (Scope::Registers, _) => registers(cpu, thread.level),
        (_, None) => Vec::new(),
        (Scope::Locals, Some((block, _))) => {
            let caller = thread.stack.get(depth + 1).copied();
            locals(cpu, thread, block, depth, caller, set)
        }
        (Scope::TimersAndCounters, Some((block, _))) => timers_and_counters(cpu, block, set),
    })
}

fn registers(cpu: &Cpu, level: &LevelState) -> Vec<Variable> {
    let step7 = cpu.program.s7.step7;
    let mut out: Vec<Variable> = state::accumulators(cpu, level)
        .into_iter()
        .enumerate()
        .map(|(n, value)| variable(format!("ACCU {}", n + 1), state::text::accu(value)))
        .collect();
    let bits = StatusBits::of(level, step7);
    let named = [
        ("/FC", bits.first_check),
        ("RLO", bits.rlo),
        ("STA", bits.sta),
        ("OR", bits.or),
        ("OS", bits.os),
        ("OV", bits.ov),
        ("CC 1", bits.cc1),
        ("CC 0", bits.cc0),
    ];
    out.extend(
        named
            .iter()
            .map(|(name, bit)| variable(*name, u8::from(*bit).to_string())),
    );
    if let Some(br) = bits.br {
        out.push(variable("BR", u8::from(br).to_string()));
    }
    let db = |slot: u16| match cpu.program.s7.db_number(slot) {
        0 => "none".to_string(),
        number => format!("DB {number}"),
    };
    if step7 {
        for (name, value) in [("AR1", level.ar1), ("AR2", level.ar2)] {
            let pointer = crate::address::notation::pointer(value);
            out.push(variable(name, format!("DW#16#{value:08X} = {pointer}")));
        }
        out.push(variable("DB register", db(level.db)));
        out.push(variable("DI register", db(level.di)));
    } else {
        let open = level
            .open_db
            .map_or("none".to_string(), |number| format!("DB {number}"));
        out.push(variable("open DB", open));
    }
    out
}

/// The value of an operand as the debugger prints it, or why there is none.
fn operand(cpu: &Cpu, name: &str, operand: &str, set: MnemonicSet) -> Variable {
    let value = show::print(cpu, &[operand.to_string()], set).map_or_else(
        |reason| reason,
        |text| {
            let line = text.trim_end();
            line.split_once(" = ")
                .map_or(line, |(_, value)| value)
                .to_string()
        },
    );
    Variable {
        name: name.to_string(),
        value,
        operand: Some(operand.to_string()),
    }
}

fn locals(
    cpu: &Cpu,
    thread: &Thread,
    block: u16,
    depth: usize,
    caller: Option<(u16, u32)>,
    set: MnemonicSet,
) -> Vec<Variable> {
    if cpu.program.s7.step7 {
        let context = (0..depth).try_fold(
            cpu.level_context(thread.level, thread.frames),
            |context, _| cpu.caller_context(context),
        );
        return context.map_or_else(Vec::new, |context| step7_locals(cpu, context, block, set));
    }
    let compiled = &cpu.program.blocks[usize::from(block)];
    let Some((caller, pc)) = caller else {
        return Vec::new();
    };
    // A STEP 5 FB's formal operands: the actual operands written under its call.
    let file = cpu
        .sources
        .get(cpu.program.blocks[usize::from(caller)].header.file);
    let call_line = cpu.line_of(caller, pc);
    let actuals: Vec<&str> = (call_line + 1..=call_line + 1 + compiled.params.len() as u32)
        .map(|line| file.line(line))
        .collect();
    compiled
        .params
        .iter()
        .map(|param| {
            let name = &param.name.text;
            let actual = actuals.iter().find_map(|line| {
                let (formal, actual) = line.split_once(':')?;
                formal
                    .trim()
                    .eq_ignore_ascii_case(name)
                    .then(|| actual.split(';').next().unwrap_or("").trim().to_string())
            });
            match actual {
                Some(actual) if target(cpu, &actual, set).is_ok() => {
                    let mut shown = operand(cpu, name, &actual, set);
                    shown.value = format!("{actual} = {}", shown.value);
                    shown
                }
                Some(actual) => variable(name.as_str(), actual),
                None => variable(name.as_str(), "?"),
            }
        })
        .collect()
}

/// A STEP 7 block's locals in `context` (its registers at the frame shown): an FC's parameters
/// (the values of their actuals), an FB's instance data, and the temporaries by name; the
/// local data no declaration names (written absolutely, `T LB 0`) as words.
fn step7_locals(cpu: &Cpu, context: Context, block: u16, set: MnemonicSet) -> Vec<Variable> {
    let tables = &cpu.program.s7;
    let declared = tables
        .block_locals
        .iter()
        .find(|(index, _)| *index == block)
        .map(|(_, locals)| locals);
    let mut out: Vec<Variable> = declared
        .iter()
        .flat_map(|locals| &locals.parameters)
        .map(|parameter| fc_parameter(cpu, context, parameter, set))
        .collect();
    if cpu.block_id(block).kind == BlockKind::Fb && context.di != 0 {
        let instance = tables.db_number(context.di);
        if let Some((_, values)) = tables.declared_dbs.iter().find(|(n, _)| *n == instance) {
            for value in values {
                let name = format!("DB{instance}.{}", value.name);
                out.push(operand(cpu, &value.name, &name, set));
            }
        }
    }
    let end = context.local_base + cpu.program.local_bytes(block);
    let local = cpu
        .local
        .get(context.local_base as usize..end as usize)
        .unwrap_or(&[]);
    let temporaries = declared.map_or(&[][..], |locals| &locals.temporaries);
    out.extend(
        temporaries
            .iter()
            .map(|temporary| variable(temporary.name.as_str(), declared::text(temporary, local))),
    );
    // Words no temporary covers: the block's absolutely addressed local data.
    let covered = |byte: usize| {
        temporaries.iter().any(|temporary| {
            let start = temporary.byte as usize;
            (start..start + temporary.format.bytes()).contains(&byte)
        })
    };
    for (n, pair) in local.chunks(2).enumerate() {
        if covered(n * 2) || covered(n * 2 + 1) {
            continue;
        }
        let word = pair
            .iter()
            .fold(0u16, |word, byte| word << 8 | u16::from(*byte));
        out.push(variable(
            format!("LW {}", n * 2),
            format!("W#16#{word:04X}"),
        ));
    }
    out
}

/// An FC parameter's value: its actual's, read where the caller passed it.
fn fc_parameter(
    cpu: &Cpu,
    context: Context,
    parameter: &DeclaredParameter,
    set: MnemonicSet,
) -> Variable {
    let name = parameter.name.as_str();
    let Some(format) = parameter.format else {
        return variable(name, "(passed as a pointer)");
    };
    let Some(width) = format.access_width() else {
        return variable(name, "(passed as a pointer)");
    };
    let place = Place {
        target: Target::Parameter {
            param: parameter.place,
            byte: 0,
            bit: 0,
        },
        width,
    };
    let value = match status::locate(cpu, place, context) {
        Some(Located::Constant(value)) => constant(value, format),
        Some(Located::Timer(n)) => format!("T {n}"),
        Some(Located::Counter(n)) => {
            format!("{} {n}", if set == MnemonicSet::German { "Z" } else { "C" })
        }
        Some(located) => match status::memory_at(cpu, located) {
            Some((bytes, bit)) => declared::text(
                &DeclaredValue {
                    name: String::new(),
                    byte: 0,
                    bit,
                    format,
                },
                bytes,
            ),
            None => "(in the peripherals)".to_string(),
        },
        None => "?".to_string(),
    };
    variable(name, value)
}

/// A constant actual in its parameter's type.
fn constant(value: u32, format: Format) -> String {
    let bytes = value.to_be_bytes();
    let width = format.bytes().min(4);
    let value = DeclaredValue {
        name: String::new(),
        byte: 0,
        bit: 0,
        format,
    };
    declared::text(&value, &bytes[4 - width..])
}

/// The timers and counters the block's statements name, in the dialect's notation.
fn timers_and_counters(cpu: &Cpu, block: u16, set: MnemonicSet) -> Vec<Variable> {
    let compiled = &cpu.program.blocks[usize::from(block)];
    let file = cpu.sources.get(compiled.header.file);
    let mut named: Vec<(char, u16)> = Vec::new();
    for span in &compiled.spans {
        let words: Vec<&str> = file.slice(*span).split_whitespace().collect();
        for pair in words.windows(2) {
            let letter = pair[0].to_ascii_uppercase();
            let kind = match letter.as_str() {
                "T" | "C" | "Z" => letter.chars().next().unwrap_or('T'),
                _ => continue,
            };
            if let Ok(number) = pair[1].parse::<u16>() {
                named.push((kind, number));
            }
        }
    }
    named.sort_unstable();
    named.dedup();
    named
        .into_iter()
        .map(|(kind, number)| format!("{kind} {number}"))
        .filter(|name| target(cpu, name, set).is_ok())
        .map(|name| operand(cpu, &name, &name, set))
        .collect()
}

pub fn variables_body(variables: &[Variable]) -> Value {
    let variables: Vec<Value> = variables
        .iter()
        .map(|variable| {
            json!({
                "name": variable.name,
                "value": variable.value,
                "variablesReference": 0,
                "evaluateName": variable.operand,
            })
        })
        .collect();
    json!({ "variables": variables })
}
