//! The value of an operation's operand, as program status shows it next to the statement, in
//! the program's dialect. STEP 5: bits 0/1, bytes `KH`, words `KF`, timers `KT`, counters
//! `KZ`. STEP 7: bits `0`/`1`, bytes `B#16#0F`, words as INT (`-5`), double words `DW#16#…`,
//! timers `S5T#…`, counters `C#…`; an S7 operand (`#start`, `DB1.DBW 2`, a parameter) is read
//! where the running block sees it, without touching the CPU (a status must not open a DB).

use crate::address::Target;
use crate::address::notation;
use crate::compiler::bytecode::{BitSource, BitTarget, DataPart, ImageBit, Width};
use crate::compiler::{Op, Resolved};
use crate::state::watch::natural;
use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{Place, S7Code, Target as S7Target};
use crate::vm::Cpu;
use crate::vm::s7::memory::{Context, Located};

fn image_bit(cpu: &Cpu, bit: ImageBit) -> String {
    natural(
        cpu,
        Target::ImageBit {
            byte: bit.byte,
            bit: bit.bit,
        },
    )
}

fn image(cpu: &Cpu, width: Width, byte: u16) -> String {
    let bytes = width.bytes() as u8;
    natural(cpu, Target::Image { byte, bytes })
}

/// A data word of the open DB, or `-` when there is none.
fn data(cpu: &Cpu, part: DataPart, word: u16) -> String {
    let Some(value) = cpu.data_word(word) else {
        return "-".to_string();
    };
    match part {
        DataPart::Left => format!("KH {:02X}", value >> 8),
        DataPart::Right => format!("KH {:02X}", value & 0xFF),
        DataPart::Word => format!("KF {:+}", value as i16),
        DataPart::Double => match cpu.data_word(word + 1) {
            Some(low) => format!("KH {value:04X}{low:04X}"),
            None => "-".to_string(),
        },
    }
}

fn raw(value: u32, width: Width) -> String {
    match width {
        Width::Byte => format!("KH {:02X}", value as u8),
        Width::Word => format!("KF {:+}", value as u16 as i16),
        Width::Double => format!("KH {value:08X}"),
    }
}

fn data_bit(cpu: &Cpu, word: u16, bit: u8) -> String {
    cpu.data_word(word)
        .map_or("-".to_string(), |value| (value >> bit & 1).to_string())
}

fn bit_target(cpu: &Cpu, target: BitTarget) -> String {
    match target {
        BitTarget::Image(bit) => image_bit(cpu, bit),
        BitTarget::Data { word, bit } => data_bit(cpu, word, bit),
    }
}

/// The operand of `op` as it is now, in the program's dialect; `None` for operations without
/// one that holds a value (constants, jumps, block calls, accumulator operations).
pub fn value(cpu: &Cpu, op: Op) -> Option<String> {
    if cpu.program.s7.step7 {
        step7_value(cpu, op)
    } else {
        step5_value(cpu, op)
    }
}

fn step5_value(cpu: &Cpu, op: Op) -> Option<String> {
    let timer = |n| natural(cpu, Target::TimerBit(n));
    let counter = |n| natural(cpu, Target::CounterValue(n));
    if let Some(bit) = op.image_bit() {
        return Some(image_bit(cpu, bit));
    }
    Some(match op {
        Op::LogicOther(_, BitSource::Data { word, bit }) | Op::WriteData { word, bit, .. } => {
            data_bit(cpu, word, bit)
        }
        Op::LogicOther(_, BitSource::Timer(n))
        | Op::LoadTimer(n)
        | Op::LoadTimerCoded(n)
        | Op::StartTimer(_, n)
        | Op::EnableTimer(n)
        | Op::ResetTimer(n) => timer(n),
        Op::LogicOther(_, BitSource::Counter(n))
        | Op::LoadCounter(n)
        | Op::LoadCounterCoded(n)
        | Op::CountUp(n)
        | Op::CountDown(n)
        | Op::SetCounter(n)
        | Op::ResetCounter(n)
        | Op::EnableCounter(n) => counter(n),
        Op::LoadImageByte(byte) | Op::TransferImageByte(byte) => image(cpu, Width::Byte, byte),
        Op::LoadImageWord(byte) | Op::TransferImageWord(byte) => image(cpu, Width::Word, byte),
        Op::LoadImageDouble(byte) | Op::TransferImageDouble(byte) => {
            image(cpu, Width::Double, byte)
        }
        Op::LoadData(part, word) | Op::TransferData(part, word) => data(cpu, part, word),
        Op::SetUnconditional(target)
        | Op::ResetUnconditional(target)
        | Op::TestBit { target, .. } => bit_target(cpu, target),
        // What a load read from an input module is in ACCU 1 now.
        Op::LoadPeripheral { width, .. } => raw(cpu.level.accu1, width),
        Op::TransferPeripheral {
            width,
            byte,
            extended,
        } => natural(
            cpu,
            Target::Periphery {
                byte,
                bytes: width.bytes() as u8,
                extended,
            },
        ),
        // Constants, jumps, block calls, accumulator operations: no operand that holds a value.
        _ => return None,
    })
}

/// The operand of `op` as it is now, in STEP 7 spelling.
fn step7_value(cpu: &Cpu, op: Op) -> Option<String> {
    match op {
        Op::S7(S7Code::Mem { place, .. }) => {
            let place = *cpu.program.s7.places.get(usize::from(place))?;
            let located = locate(cpu, place, cpu.running_context())?;
            read(cpu, located, place.width)
        }
        Op::S7(_) => None,
        // An operation STEP 5 shares (`A I 0.0`, `L MW 10`): its value, respelled.
        shared => step5_value(cpu, shared).map(|text| respell(&text)),
    }
}

/// A STEP 5 status value (`KF +5`, `KH 0F`, `KT 050.1 (1)`, `KZ 003 (0)`) in STEP 7 spelling.
fn respell(text: &str) -> String {
    let (value, bit) = match text.split_once(" (") {
        Some((value, bit)) => (value, Some(bit.trim_end_matches(')'))),
        None => (text, None),
    };
    let spelled = match value.split_once(' ') {
        Some(("KF", number)) => number.trim_start_matches('+').to_string(),
        Some(("KH", hex)) if hex.len() <= 2 => format!("B#16#{hex}"),
        Some(("KH", hex)) if hex.len() <= 4 => format!("W#16#{hex}"),
        Some(("KH", hex)) => format!("DW#16#{hex}"),
        Some(("KT", time)) => s5_time(time).unwrap_or_else(|| value.to_string()),
        Some(("KZ", count)) => format!("C#{}", count.trim_start_matches('0').max("0")),
        _ => value.to_string(),
    };
    match bit {
        Some(bit) => format!("{spelled} ({bit})"),
        None => spelled,
    }
}

/// `050.1` (50 × 100 ms) → `S5T#5S`.
fn s5_time(kt: &str) -> Option<String> {
    let (count, base) = kt.split_once('.')?;
    let base: u8 = base.parse().ok().filter(|base| *base <= 3)?;
    Some(notation::s5time(count.parse().ok()?, base))
}

/// Where `place` is in `context`; `None` for what status does not show (indirect
/// addresses, test operands).
pub(crate) fn locate(cpu: &Cpu, place: Place, context: Context) -> Option<Located> {
    if let Some(located) = context.locate(place.target) {
        return Some(located);
    }
    Some(match place.target {
        S7Target::Parameter { param, byte, bit } => match cpu.passed(context.params, param)? {
            Resolved::Constant(value) => Located::Constant(value),
            Resolved::S7(index) => {
                let place = *cpu.program.s7.places.get(usize::from(index))?;
                locate(cpu, place, cpu.caller_context(context)?)?.offset(byte, bit)
            }
            _ => return None,
        },
        _ => return None,
    })
}

/// The bytes of the CPU's memory from `located` on, and its bit; `None` for what is not in
/// the CPU's memory (constants, timers, counters, the peripherals).
pub(crate) fn memory_at(cpu: &Cpu, located: Located) -> Option<(&[u8], u8)> {
    Some(match located {
        Located::Image { byte, bit } => (cpu.image.get(byte..)?, bit),
        Located::Local { byte, bit } => (cpu.local.get(byte..)?, bit),
        Located::Data { slot, byte, bit } => (
            cpu.s7_data.get(usize::from(slot))?.as_ref()?.get(byte..)?,
            bit,
        ),
        Located::Constant(_)
        | Located::Timer(_)
        | Located::Counter(_)
        | Located::Peripheral { .. }
        | Located::Special(_) => return None,
    })
}

/// The value at `located`, spelled for its width.
fn read(cpu: &Cpu, located: Located, width: AccessWidth) -> Option<String> {
    let (bytes, bit): (&[u8], u8) = match located {
        Located::Constant(_) => return None,
        Located::Timer(n) => {
            let mut timer = *cpu.timers.get(usize::from(n))?;
            let kt = format!("KT {:03}.{}", timer.value(cpu.clock), timer.base());
            return Some(format!(
                "{} ({})",
                respell(&kt),
                u8::from(timer.bit(cpu.clock))
            ));
        }
        Located::Counter(n) => {
            let counter = cpu.counters.get(usize::from(n))?;
            return Some(format!("C#{} ({})", counter.value, u8::from(counter.bit())));
        }
        memory => memory_at(cpu, memory)?,
    };
    let take = |count: usize| {
        bytes.get(..count).map(|bytes| {
            bytes
                .iter()
                .fold(0u32, |value, b| value << 8 | u32::from(*b))
        })
    };
    Some(match width {
        AccessWidth::Bit => (bytes.first()? >> bit & 1).to_string(),
        AccessWidth::Byte => format!("B#16#{:02X}", take(1)?),
        AccessWidth::Word => (take(2)? as u16 as i16).to_string(),
        AccessWidth::Double => format!("DW#16#{:08X}", take(4)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step5_values_in_step7_spelling() {
        assert_eq!(respell("KF +5"), "5");
        assert_eq!(respell("KF -12"), "-12");
        assert_eq!(respell("KH 0F"), "B#16#0F");
        assert_eq!(respell("KH 0001ABCD"), "DW#16#0001ABCD");
        assert_eq!(respell("KT 050.1 (1)"), "S5T#5S (1)");
        assert_eq!(respell("KT 090.2 (0)"), "S5T#1M30S (0)");
        assert_eq!(respell("KT 000.0 (0)"), "S5T#0MS (0)");
        assert_eq!(respell("KZ 007 (1)"), "C#7 (1)");
        assert_eq!(respell("KZ 000 (0)"), "C#0 (0)");
        assert_eq!(respell("1"), "1");
    }
}
