//! The editor's breakpoints as the engine's: lines (moved to the next line that holds a
//! statement), blocks by name (`FC 1`, `PB 3`, a symbol), with conditions, hit counts and log
//! messages checked when they are set; and the exception filters.

use std::collections::BTreeMap;

use serde_json::{Value, json};

use crate::ast::BlockId;
use crate::debug::command::{self, BreakAt, Command};
use crate::debug::condition::{Condition, HitCondition, LogMessage};
use crate::debug::engine::{Breakpoint, Filters};
use crate::debug::{Engine, named_block};
use crate::mnemonics::MnemonicSet;
use crate::vm::Cpu;

use super::inspect::absolute;

/// Which engine breakpoints the editor set, by where it set them.
#[derive(Debug, Default)]
pub struct Set {
    by_source: BTreeMap<String, Vec<usize>>,
    functions: Vec<usize>,
}

/// An unverified breakpoint with why.
fn refused(message: &str) -> Value {
    json!({ "verified": false, "message": message })
}

/// Breakpoints set before a launch: none can be checked yet.
pub fn before_launch(asked: &Value) -> Value {
    let count = asked.as_array().map_or(0, Vec::len);
    let breakpoints = vec![refused("no program is launched yet"); count];
    json!({ "breakpoints": breakpoints })
}

/// The exception filters the editor chose, answered each as verified.
pub struct Chosen {
    pub engine: Filters,
    pub stop: bool,
    pub verified: Vec<Value>,
}

pub fn filters(arguments: &Value) -> Chosen {
    let names: Vec<&str> = arguments["filters"]
        .as_array()
        .map(|names| names.iter().filter_map(Value::as_str).collect())
        .unwrap_or_default();
    let known = ["interrupt", "request", "stop"];
    Chosen {
        engine: Filters {
            interrupt: names.contains(&"interrupt"),
            request: names.contains(&"request"),
        },
        stop: names.contains(&"stop"),
        verified: names
            .iter()
            .map(|name| {
                if known.contains(name) {
                    json!({ "verified": true })
                } else {
                    refused(&format!("awl has no exception filter `{name}`"))
                }
            })
            .collect(),
    }
}

/// The first statement on `line` of file `file` or after it: its block, op and line.
fn statement_at(cpu: &Cpu, file: u16, line: u32) -> Option<(u16, u32, u32)> {
    let mut best: Option<(u16, u32, u32)> = None;
    for (index, block) in cpu.program.blocks.iter().enumerate() {
        if block.header.file != file {
            continue;
        }
        let index = index as u16;
        for pc in 0..block.spans.len() as u32 {
            let at = cpu.line_of(index, pc);
            if at >= line && best.is_none_or(|(_, _, best)| at < best) {
                best = Some((index, pc, at));
            }
        }
    }
    best
}

/// The condition, hit count and log message of one asked breakpoint.
fn qualify(
    cpu: &Cpu,
    asked: &Value,
    mut breakpoint: Breakpoint,
    set: MnemonicSet,
) -> Result<Breakpoint, String> {
    let given = |key: &str| asked[key].as_str().filter(|text| !text.trim().is_empty());
    if let Some(condition) = given("condition") {
        breakpoint.condition = Some(Condition::parse(cpu, condition, set)?);
    }
    if let Some(hits) = given("hitCondition") {
        breakpoint.hit_condition = Some(HitCondition::parse(hits)?);
    }
    if let Some(message) = given("logMessage") {
        breakpoint.log = Some(LogMessage::parse(cpu, message, set)?);
    }
    Ok(breakpoint)
}

fn delete(engine: &mut Engine, numbers: &[usize]) {
    for n in numbers {
        if let Some(slot) = engine.breakpoints.get_mut(n - 1) {
            *slot = None;
        }
    }
}

impl Set {
    /// `setBreakpoints`: the source's breakpoints replace those it had.
    pub fn set_lines(
        &mut self,
        engine: &mut Engine,
        cpu: &Cpu,
        arguments: &Value,
        set: MnemonicSet,
    ) -> Value {
        let path = arguments["source"]["path"].as_str().unwrap_or("");
        let path = absolute(path);
        delete(engine, &self.by_source.remove(&path).unwrap_or_default());
        let file = cpu
            .sources
            .files
            .iter()
            .position(|file| absolute(&file.name) == path);
        let asked = arguments["breakpoints"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let mut numbers = Vec::new();
        let answers: Vec<Value> = asked
            .iter()
            .map(|asked| {
                let Some(file) = file else {
                    return refused("the launched program has no such file");
                };
                let line = asked["line"].as_u64().unwrap_or(0) as u32;
                let Some((block, pc, at)) = statement_at(cpu, file as u16, line) else {
                    return refused(&format!("no statement is on line {line} or after it"));
                };
                let id = cpu.block_id(block);
                let at_block = BreakAt::Block {
                    block: id,
                    line: Some(at),
                };
                match qualify(
                    cpu,
                    asked,
                    Breakpoint::new(at_block, Some((block, pc))),
                    set,
                ) {
                    Ok(breakpoint) => {
                        let n = engine.insert(breakpoint);
                        numbers.push(n);
                        json!({ "id": n, "verified": true, "line": at })
                    }
                    Err(reason) => refused(&reason),
                }
            })
            .collect();
        self.by_source.insert(path, numbers);
        json!({ "breakpoints": answers })
    }

    /// `setFunctionBreakpoints`: blocks by name (`FC 1`, `PB 3`, `"Valve"`, `-FILL`), and
    /// `request OB 3`, `service OB 3` as `awl debug`'s `break` takes them.
    pub fn set_functions(
        &mut self,
        engine: &mut Engine,
        cpu: &Cpu,
        arguments: &Value,
        set: MnemonicSet,
    ) -> Value {
        delete(engine, &std::mem::take(&mut self.functions));
        let asked = arguments["breakpoints"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        let answers: Vec<Value> = asked
            .iter()
            .map(|asked| {
                let name = asked["name"].as_str().unwrap_or("");
                let at = break_at(cpu, name).and_then(|at| {
                    let place = match at {
                        BreakAt::Block { block, line } => {
                            Some(Engine::block_place(cpu, block, line).map_err(|e| e.to_string())?)
                        }
                        _ => None,
                    };
                    if let BreakAt::Request(ob) | BreakAt::Service(ob) = at
                        && cpu.profile.interrupt_ob(ob).is_none()
                    {
                        let name = cpu.profile.name;
                        return Err(format!("OB {ob} is no interrupt OB of the {name}"));
                    }
                    qualify(cpu, asked, Breakpoint::new(at, place), set)
                });
                match at {
                    Ok(breakpoint) => {
                        let line = breakpoint.place.map(|(b, pc)| cpu.line_of(b, pc));
                        let n = engine.insert(breakpoint);
                        self.functions.push(n);
                        json!({ "id": n, "verified": true, "line": line })
                    }
                    Err(reason) => refused(&reason),
                }
            })
            .collect();
        json!({ "breakpoints": answers })
    }

    /// The `stopped` reason of breakpoint `n`.
    pub fn reason(&self, n: usize) -> &'static str {
        if self.functions.contains(&n) {
            "function breakpoint"
        } else {
            "breakpoint"
        }
    }
}

/// What a function breakpoint's name names, as `break NAME` would.
fn break_at(cpu: &Cpu, name: &str) -> Result<BreakAt, String> {
    let block = |block: BlockId| BreakAt::Block { block, line: None };
    match command::parse(&format!("break {name}")) {
        Some(Ok(Command::Break(at))) => Ok(at),
        Some(Ok(Command::BreakNamed { symbol, line })) => named_block(cpu, &symbol)
            .map(|found| BreakAt::Block { block: found, line })
            .map_err(|error| error.to_string()),
        Some(Err(error)) => Err(error.to_string()),
        _ => BlockId::parse(name)
            .map(block)
            .ok_or_else(|| format!("`{name}` names no block")),
    }
}
