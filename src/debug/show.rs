//! What the debugger prints: where the CPU stands, the source around it, the block stack, the
//! registers, and operands by name; and what `set` writes.

use std::fmt::Write;

use crate::mnemonics::MnemonicSet;
use crate::scenario::input_change;
use crate::scenario::modify::write_s7_data;
use crate::scenario::operand::{Target, parse_target, raw_value};
use crate::state::watch::natural;
use crate::state::{self, LevelView, StatusBits};
use crate::trace::format_ms;
use crate::vm::interrupts::{InputChange, InputTarget};
use crate::vm::{Cpu, IDLE};

/// `PB 2 line 19, cycle 1, 0.025100 ms, level OB 1`, then the line itself.
pub fn location(cpu: &Cpu) -> String {
    if cpu.level.block == IDLE {
        return format!(
            "between blocks, cycle {}, {}\n",
            cpu.cycle,
            format_ms(cpu.clock)
        );
    }
    let line = cpu.line_of(cpu.level.block, cpu.level.pc);
    let file = cpu.sources.get(source_file(cpu));
    format!(
        "{} line {line}, cycle {}, {}, level {}\n{line:>6}  {}\n",
        cpu.block_id(cpu.level.block),
        cpu.cycle,
        format_ms(cpu.clock),
        cpu.block_id(cpu.level_block()),
        file.line(line).trim_end()
    )
}

fn source_file(cpu: &Cpu) -> u16 {
    cpu.program.blocks[usize::from(cpu.level.block)].header.file
}

/// The source around the next operation, with a marker at its line.
pub fn listing(cpu: &Cpu) -> String {
    if cpu.level.block == IDLE {
        return "no block runs\n".to_string();
    }
    let current = cpu.line_of(cpu.level.block, cpu.level.pc);
    let file = cpu.sources.get(source_file(cpu));
    let mut out = String::new();
    for line in current.saturating_sub(5).max(1)..=current + 5 {
        let text = file.line(line).trim_end();
        if line > current && text.is_empty() && file.line(line + 1).is_empty() {
            break;
        }
        let marker = if line == current { "=>" } else { "  " };
        let _ = writeln!(out, "{marker}{line:>5}  {text}");
    }
    out
}

/// The block stack, the running block first, with each return point.
pub fn stack(cpu: &Cpu) -> String {
    if cpu.level.block == IDLE {
        return "no block runs\n".to_string();
    }
    let mut out = String::new();
    for (n, (block, pc)) in cpu.block_stack(cpu.level.pc).into_iter().enumerate() {
        let _ = writeln!(
            out,
            "#{n} {} line {}",
            cpu.block_id(block),
            cpu.line_of(block, pc)
        );
    }
    out
}

pub fn accumulators(cpu: &Cpu) -> String {
    let mut out = String::new();
    for (n, value) in state::accumulators(cpu, &cpu.level).into_iter().enumerate() {
        let _ = writeln!(out, "ACCU {}  {}", n + 1, state::text::accu(value));
    }
    out
}

pub fn status_word(cpu: &Cpu) -> String {
    format!(
        "{}\n",
        state::text::status(&StatusBits::from(cpu.level.status))
    )
}

pub fn levels(levels: &[LevelView]) -> String {
    if levels.is_empty() {
        return "no block runs\n".to_string();
    }
    format!("{}\n", state::istack_text(levels))
}

/// The operand `operand` names in the program, or why none.
pub fn target(cpu: &Cpu, operand: &str, set: MnemonicSet) -> Result<Target, String> {
    parse_target(operand, (0, 0).into(), set, &cpu.program).map_err(|error| error.reason())
}

/// `Q 4.0 = 1`, one line per operand.
pub fn print(cpu: &Cpu, operands: &[String], set: MnemonicSet) -> Result<String, String> {
    let mut out = String::new();
    for operand in operands {
        let target =
            target(cpu, operand, set).map_err(|reason| format!("`{operand}`: {reason}"))?;
        let _ = writeln!(out, "{operand} = {}", natural(cpu, target));
    }
    Ok(out)
}

/// Writes an input change into the input modules, as a scenario's `set` does.
fn write_modules(cpu: &mut Cpu, change: InputChange, operand: &str) -> Result<(), String> {
    let modules = match change.target {
        InputTarget::Process => &mut cpu.inputs,
        InputTarget::Extended => &mut cpu.extended_inputs,
    };
    if usize::from(change.byte) + usize::from(change.bytes.max(1)) > modules.len() {
        return Err(format!("`{operand}` is past the input modules"));
    }
    change.apply(modules);
    Ok(())
}

/// Writes into the image memory and, for the PII, into the input modules too, so the forced
/// value holds at the next PII read.
fn force_image(
    cpu: &mut Cpu,
    target: Target,
    write: InputChange,
    operand: &str,
) -> Result<(), String> {
    write.apply(&mut cpu.image[..]);
    match input_change(target, &cpu.program, write.value) {
        Some(change) => write_modules(cpu, change, operand),
        None => Ok(()),
    }
}

/// A timer cannot be written: it runs as the program starts it.
fn not_a_timer(target: Target) -> Result<(), String> {
    match target {
        Target::TimerBit(_) => {
            Err("a timer runs as the program starts it; force its start condition".into())
        }
        _ => Ok(()),
    }
}

/// `set OPERAND VALUE`: what it wrote, or why it cannot.
pub fn force(cpu: &mut Cpu, operand: &str, value: i64, set: MnemonicSet) -> Result<String, String> {
    let target = target(cpu, operand, set).map_err(|reason| format!("`{operand}`: {reason}"))?;
    not_a_timer(target)?;
    let raw = raw_value(target, value)
        .map_err(|allowed| format!("`{operand}` takes {allowed}, not {value}"))?;
    write(cpu, target, raw, operand)?;
    Ok(format!("{operand} = {}\n", natural(cpu, target)))
}

/// Writes `raw` into `target` (named `operand`) once, as a PG's "modify variable": an input into
/// the PII and its modules, so it holds at the next PII read; or why it cannot.
pub fn write(cpu: &mut Cpu, target: Target, raw: u32, operand: &str) -> Result<(), String> {
    let image = |byte, bit, bytes, value| InputChange {
        target: InputTarget::Process,
        byte,
        bit,
        bytes,
        value,
    };
    match target {
        Target::ImageBit { byte, bit } => {
            force_image(cpu, target, image(byte, bit, 0, raw), operand)
        }
        Target::Image { byte, bytes } => {
            force_image(cpu, target, image(byte, 0, bytes, raw), operand)
        }
        Target::Periphery { .. } => match input_change(target, &cpu.program, raw) {
            Some(change) => write_modules(cpu, change, operand),
            None => Ok(()),
        },
        Target::TimerBit(_) => not_a_timer(target),
        Target::CounterValue(n) => {
            if raw > 999 {
                return Err(format!("a counter holds 0…999, not {raw}"));
            }
            cpu.counters[usize::from(n)].value = raw as u16;
            Ok(())
        }
        Target::DataWord { db, word } => {
            let slot = cpu.data_blocks[usize::from(db)]
                .as_mut()
                .ok_or_else(|| format!("DB {db} is not loaded"))?
                .get_mut(usize::from(word))
                .ok_or_else(|| format!("DB {db} has no DW {word}"))?;
            *slot = raw as u16;
            Ok(())
        }
        Target::DataDouble { db, word } => {
            let at = usize::from(word);
            let slots = cpu.data_blocks[usize::from(db)]
                .as_mut()
                .ok_or_else(|| format!("DB {db} is not loaded"))?
                .get_mut(at..at + 2)
                .ok_or_else(|| format!("DB {db} has no DD {word}"))?;
            slots.copy_from_slice(&[(raw >> 16) as u16, raw as u16]);
            Ok(())
        }
        Target::S7Data { .. } => write_s7_data(cpu, target, raw),
    }
}
