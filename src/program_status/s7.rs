//! Program status values of a STEP 7 program in STEP 7 spelling: bits `0`/`1`, bytes
//! `B#16#0F`, words as INT (`-5`), double words `DW#16#…`, timers `S5T#…`, counters `C#…`;
//! the accumulators as `W#16#…`/`DW#16#…`. An S7 operand (`#start`, `DB1.DBW 2`, a
//! parameter) is read where the running block sees it, without touching the CPU (a status
//! must not open a DB).

use crate::compiler::{Op, Resolved};
use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{Place, S7Code, Target};
use crate::vm::Cpu;
use crate::vm::s7::memory::{Context, Located};

/// An accumulator: a word while the high word is 0, else the double word.
pub fn accu(value: u32) -> String {
    if value >> 16 == 0 {
        format!("W#16#{value:04X}")
    } else {
        format!("DW#16#{value:08X}")
    }
}

/// The operand of `op` as it is now, in STEP 7 spelling.
pub fn value(cpu: &Cpu, op: Op) -> Option<String> {
    match op {
        Op::S7(S7Code::Mem { place, .. }) => {
            let place = *cpu.program.s7.places.get(usize::from(place))?;
            let located = locate(cpu, place, cpu.running_context())?;
            read(cpu, located, place.width)
        }
        Op::S7(_) => None,
        // An operation STEP 5 shares (`A I 0.0`, `L MW 10`): its value, respelled.
        shared => crate::state::operand::value(cpu, shared).map(|text| respell(&text)),
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
    let count: u64 = count.parse().ok()?;
    let unit_ms = match base {
        "0" => 10,
        "1" => 100,
        "2" => 1_000,
        "3" => 10_000,
        _ => return None,
    };
    Some(format!("S5T#{}", duration(count * unit_ms)))
}

/// `1H2M3S40MS`, `0MS`.
fn duration(ms: u64) -> String {
    let parts = [
        (ms / 3_600_000, "H"),
        (ms / 60_000 % 60, "M"),
        (ms / 1_000 % 60, "S"),
        (ms % 1_000, "MS"),
    ];
    let text: String = parts
        .iter()
        .filter(|(count, _)| *count > 0)
        .map(|(count, unit)| format!("{count}{unit}"))
        .collect();
    if text.is_empty() { "0MS".into() } else { text }
}

/// Where `place` is in `context`; `None` for what status does not show (indirect
/// addresses, test operands).
fn locate(cpu: &Cpu, place: Place, context: Context) -> Option<Located> {
    Some(match place.target {
        Target::Image { byte, bit } => Located::Image {
            byte: usize::from(byte),
            bit,
        },
        Target::Local { byte, bit } => Located::Local {
            byte: (context.local_base + byte) as usize,
            bit,
        },
        Target::PreviousLocal { byte, bit } => Located::Local {
            byte: (context.previous_local? + byte) as usize,
            bit,
        },
        Target::Instance { byte, bit } => {
            let at = (context.ar2 & 0x0007_FFFF) + (byte << 3 | u32::from(bit));
            Located::Data {
                slot: context.di,
                byte: (at >> 3) as usize,
                bit: (at & 7) as u8,
            }
        }
        Target::Data {
            instance,
            byte,
            bit,
        } => Located::Data {
            slot: if instance { context.di } else { context.db },
            byte: byte as usize,
            bit,
        },
        Target::NumberedData {
            slot, byte, bit, ..
        } => Located::Data {
            slot,
            byte: byte as usize,
            bit,
        },
        Target::Parameter { param, byte, bit } => {
            let actual = cpu
                .program
                .param_lists
                .get(usize::from(context.params))?
                .get(usize::from(param))?;
            match *actual {
                Resolved::Constant(value) => Located::Constant(value),
                Resolved::S7(index) => {
                    let place = *cpu.program.s7.places.get(usize::from(index))?;
                    locate(cpu, place, cpu.caller_context(context)?)?.offset(byte, bit)
                }
                _ => return None,
            }
        }
        Target::Timer(n) => Located::Timer(n),
        Target::Counter(n) => Located::Counter(n),
        Target::Constant(value) => Located::Constant(value),
        _ => return None,
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
        Located::Image { byte, bit } => (cpu.image.get(byte..)?, bit),
        Located::Local { byte, bit } => (cpu.local.get(byte..)?, bit),
        Located::Data { slot, byte, bit } => (
            cpu.s7_data.get(usize::from(slot))?.as_ref()?.get(byte..)?,
            bit,
        ),
        Located::Peripheral { .. } | Located::Special(_) => return None,
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

    #[test]
    fn accumulators_as_words_or_double_words() {
        assert_eq!(accu(5), "W#16#0005");
        assert_eq!(accu(0x0001_0000), "DW#16#00010000");
    }
}
