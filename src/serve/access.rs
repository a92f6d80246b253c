//! A client's reads and writes of the CPU's memory, served at the cycle control point: where
//! each area lies in either dialect, what an input write reaches (the input modules), and the
//! trace event each write leaves.

use crate::trace::Event;
use crate::vm::Cpu;
use crate::vm::bytes::read_bytes;
use crate::vm::interrupts::{InputChange, InputTarget};

use super::request::{Area, Client, Item, ItemError, ItemResult, Probe, Range, Reading};

/// Serves the items of one request in order, each on its own: a failed item leaves the others.
pub fn serve_items(
    cpu: &mut Cpu,
    client: Client,
    items: &[Item],
    read_only: bool,
) -> Vec<ItemResult> {
    items
        .iter()
        .map(|item| serve_item(cpu, client, item, read_only))
        .collect()
}

/// What one probe of a sample reads: an operand as a watch row shows it raw, or bytes as a
/// client's read gets them.
pub fn probe(cpu: &mut Cpu, probe: Probe) -> Reading {
    match probe {
        Probe::Operand(target) => Reading::Operand(crate::state::watch::raw(cpu, target)),
        Probe::Bytes(range) => Reading::Bytes(read(cpu, range)),
    }
}

fn serve_item(cpu: &mut Cpu, client: Client, item: &Item, read_only: bool) -> ItemResult {
    match item {
        Item::Read(range) => read(cpu, *range),
        Item::ReadBit {
            area: Area::Timers | Area::Counters,
            ..
        } => Err(ItemError::NotSupported),
        Item::ReadBit { area, byte, bit } => {
            let byte = read(cpu, byte_range(*area, *byte))?;
            Ok(vec![byte[0] >> (bit & 7) & 1])
        }
        Item::Write { .. } | Item::WriteBit { .. } if read_only => Err(ItemError::ReadOnly),
        Item::Write { range, bytes } => {
            // The write is traced before its effects (an input's edge raising an interrupt),
            // once the range is known to be there.
            read(cpu, *range)?;
            if !length_fits(*range, bytes) {
                return Err(ItemError::NotSupported);
            }
            trace_write(cpu, client, *range, None, bytes);
            write(cpu, *range, bytes)?;
            Ok(Vec::new())
        }
        &Item::WriteBit {
            area,
            byte,
            bit,
            value,
        } => {
            let range = byte_range(area, byte);
            let mut current = read(cpu, range)?;
            let mask = 1u8 << (bit & 7);
            current[0] = if value {
                current[0] | mask
            } else {
                current[0] & !mask
            };
            trace_write(cpu, client, range, Some(bit & 7), &[u8::from(value)]);
            write_bit(cpu, range, bit & 7, value, current[0])?;
            Ok(Vec::new())
        }
    }
}

fn byte_range(area: Area, byte: u32) -> Range {
    Range::new(area, byte, 1)
}

/// The byte indexes `range` covers in a memory of `size` bytes.
fn span(range: Range, size: usize) -> Result<std::ops::Range<usize>, ItemError> {
    let start = usize::try_from(range.start).map_err(|_| ItemError::OutOfRange)?;
    let length = usize::try_from(range.length).map_err(|_| ItemError::OutOfRange)?;
    let end = start.checked_add(length).ok_or(ItemError::OutOfRange)?;
    if length == 0 || end > size {
        return Err(ItemError::OutOfRange);
    }
    Ok(start..end)
}

/// The bytes an area shows: the process images below their size, the modules above (what a
/// direct read gives), the flags, a data block.
fn read(cpu: &mut Cpu, range: Range) -> ItemResult {
    let layout = cpu.program.layout;
    let image = usize::from(layout.image_bytes);
    match range.area {
        Area::Inputs | Area::Outputs => {
            let (base, modules) = if range.area == Area::Inputs {
                (layout.input_base(), &cpu.inputs)
            } else {
                (layout.output_base(), &cpu.outputs)
            };
            let span = span(range, modules.len())?;
            Ok(span
                .map(|at| match at < image {
                    true => cpu.image[usize::from(base) + at],
                    false => modules[at],
                })
                .collect())
        }
        Area::Flags => {
            let span = span(range, usize::from(layout.flag_bytes))?;
            let base = usize::from(layout.flag_base());
            Ok(cpu.image[base + span.start..base + span.end].to_vec())
        }
        Area::DataBlock(number) => read_data_block(cpu, number, range),
        Area::Timers => {
            let span = span(range, cpu.timers.len())?;
            let now = cpu.clock;
            Ok(cpu.timers[span]
                .iter_mut()
                .flat_map(|timer| (timer.coded(now) as u16).to_be_bytes())
                .collect())
        }
        Area::Counters => {
            let span = span(range, cpu.counters.len())?;
            Ok(cpu.counters[span]
                .iter()
                .flat_map(|counter| (counter.coded() as u16).to_be_bytes())
                .collect())
        }
    }
}

/// A data block's bytes: STEP 7's as they are, STEP 5's data words high byte first.
fn read_data_block(cpu: &Cpu, number: u16, range: Range) -> ItemResult {
    if cpu.program.s7.step7 {
        let data = cpu.s7_db(number).ok_or(ItemError::NoSuchBlock)?;
        return Ok(data[span(range, data.len())?].to_vec());
    }
    let words = step5_words(cpu, number)?;
    let span = span(range, words.len() * 2)?;
    Ok(span.map(|at| words[at / 2].to_be_bytes()[at % 2]).collect())
}

fn step5_words(cpu: &Cpu, number: u16) -> Result<&Vec<u16>, ItemError> {
    cpu.data_blocks
        .get(usize::from(number))
        .and_then(Option::as_ref)
        .ok_or(ItemError::NoSuchBlock)
}

/// Whether `bytes` are as many as the range holds: two per timer or counter.
fn length_fits(range: Range, bytes: &[u8]) -> bool {
    let per_element = match range.area {
        Area::Timers | Area::Counters => 2,
        _ => 1,
    };
    bytes.len() == range.length as usize * per_element
}

/// Writes `bytes` (the range's length; two per timer or counter).
fn write(cpu: &mut Cpu, range: Range, bytes: &[u8]) -> Result<(), ItemError> {
    if !length_fits(range, bytes) {
        return Err(ItemError::NotSupported);
    }
    let layout = cpu.program.layout;
    match range.area {
        Area::Inputs => {
            span(range, cpu.inputs.len())?;
            deliver(cpu, range.start, bytes);
        }
        Area::Outputs => {
            let span = span(range, cpu.outputs.len())?;
            let image = usize::from(layout.image_bytes);
            let base = usize::from(layout.output_base());
            for (at, &byte) in span.zip(bytes) {
                match at < image {
                    true => cpu.image[base + at] = byte,
                    false => cpu.outputs[at] = byte,
                }
            }
        }
        Area::Flags => {
            let span = span(range, usize::from(layout.flag_bytes))?;
            let base = usize::from(layout.flag_base());
            cpu.image[base + span.start..base + span.end].copy_from_slice(bytes);
        }
        Area::DataBlock(number) => write_data_block(cpu, number, range, bytes)?,
        Area::Timers => {
            let span = span(range, cpu.timers.len())?;
            let now = cpu.clock;
            for (timer, word) in cpu.timers[span].iter_mut().zip(bytes.chunks(2)) {
                timer.write_coded(read_bytes(word, 0, 2), now);
            }
        }
        Area::Counters => {
            let span = span(range, cpu.counters.len())?;
            for (counter, word) in cpu.counters[span].iter_mut().zip(bytes.chunks(2)) {
                counter.value = crate::vm::counters::decode_count(read_bytes(word, 0, 2));
            }
        }
    }
    Ok(())
}

/// A bit write: an input bit reaches its module as a bit change (so an interrupt input sees
/// the edge of that bit alone); elsewhere the byte with the bit changed is written.
fn write_bit(cpu: &mut Cpu, range: Range, bit: u8, value: bool, byte: u8) -> Result<(), ItemError> {
    match range.area {
        Area::Timers | Area::Counters => Err(ItemError::NotSupported),
        Area::Inputs => {
            cpu.deliver_inputs(InputChange {
                target: InputTarget::Process,
                byte: u16::try_from(range.start).map_err(|_| ItemError::OutOfRange)?,
                bit,
                bytes: 0,
                value: u32::from(value),
            });
            Ok(())
        }
        _ => write(cpu, range, &[byte]),
    }
}

/// Input bytes reach the input modules, up to four at a time, as a scenario's `set` does.
fn deliver(cpu: &mut Cpu, start: u32, bytes: &[u8]) {
    for (index, chunk) in bytes.chunks(4).enumerate() {
        let Ok(byte) = u16::try_from(start as usize + index * 4) else {
            return;
        };
        cpu.deliver_inputs(InputChange {
            target: InputTarget::Process,
            byte,
            bit: 0,
            bytes: chunk.len() as u8,
            value: read_bytes(chunk, 0, chunk.len()),
        });
    }
}

fn write_data_block(
    cpu: &mut Cpu,
    number: u16,
    range: Range,
    bytes: &[u8],
) -> Result<(), ItemError> {
    if cpu.program.s7.step7 {
        let data = cpu.s7_db_mut(number).ok_or(ItemError::NoSuchBlock)?;
        let span = span(range, data.len())?;
        data[span].copy_from_slice(bytes);
        return Ok(());
    }
    let words = cpu
        .data_blocks
        .get_mut(usize::from(number))
        .and_then(Option::as_mut)
        .ok_or(ItemError::NoSuchBlock)?;
    let span = span(range, words.len() * 2)?;
    for (at, &byte) in span.zip(bytes) {
        let mut word = words[at / 2].to_be_bytes();
        word[at % 2] = byte;
        words[at / 2] = u16::from_be_bytes(word);
    }
    Ok(())
}

/// The trace's record of a client's write: who wrote what, in the program's notation.
fn trace_write(cpu: &mut Cpu, client: Client, range: Range, bit: Option<u8>, bytes: &[u8]) {
    if !cpu.tracer.enabled {
        return;
    }
    let operand = super::notation::operand(cpu.program.s7.step7, range, bit);
    let value = match bytes.len() {
        1..=4 if bit.is_none() => format!("16#{:X}", read_bytes(bytes, 0, bytes.len())),
        _ if bit.is_some() => bytes[0].to_string(),
        _ => bytes
            .iter()
            .map(|byte| format!("{byte:02X}"))
            .collect::<Vec<_>>()
            .join(" "),
    };
    let event = Event::ClientWrite {
        client: client.name(),
        operand,
        value,
    };
    cpu.tracer.emit(cpu.clock, event);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::serve::request::Protocol;

    const CLIENT: Client = Client {
        protocol: Protocol::S7,
        number: 1,
    };

    fn cpu(source: &str, dialect_step7: bool) -> Cpu {
        crate::serve::testing::cpu(source, dialect_step7)
    }

    #[test]
    fn a_step7_data_block_is_read_and_written_by_byte() {
        let mut cpu = cpu(
            "DATA_BLOCK DB 1\nSTRUCT\n a : INT := 5;\n b : INT;\nEND_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n NOP 0;\nEND_ORGANIZATION_BLOCK\n",
            true,
        );
        let range = Range::new(Area::DataBlock(1), 0, 4);
        assert_eq!(read(&mut cpu, range), Ok(vec![0, 5, 0, 0]));
        let write = Item::Write {
            range,
            bytes: vec![1, 2, 3, 4],
        };
        assert_eq!(
            serve_items(&mut cpu, CLIENT, &[write], false),
            vec![Ok(vec![])]
        );
        assert_eq!(read(&mut cpu, range), Ok(vec![1, 2, 3, 4]));
        let past = Range { start: 3, ..range };
        assert_eq!(read(&mut cpu, past), Err(ItemError::OutOfRange));
        let absent = Range {
            area: Area::DataBlock(2),
            ..range
        };
        assert_eq!(read(&mut cpu, absent), Err(ItemError::NoSuchBlock));
    }

    #[test]
    fn a_step5_data_block_is_reached_at_twice_the_data_word_number() {
        let mut cpu = cpu("DB 10\n KH = 1234;\n KH = 5678;\nOB 1\n BE\n", false);
        let word1 = Range::new(Area::DataBlock(10), 2, 2);
        assert_eq!(read(&mut cpu, word1), Ok(vec![0x56, 0x78]));
        write(
            &mut cpu,
            Range {
                start: 1,
                length: 1,
                ..word1
            },
            &[0xAB],
        )
        .unwrap();
        assert_eq!(cpu.data_blocks[10].as_ref().unwrap()[0], 0x12AB);
    }

    #[test]
    fn an_input_write_reaches_the_modules_and_the_image_at_the_next_cycle() {
        let mut cpu = cpu("OB 1\n BE\n", false);
        let bit = Item::WriteBit {
            area: Area::Inputs,
            byte: 1,
            bit: 3,
            value: true,
        };
        serve_items(&mut cpu, CLIENT, &[bit], false);
        assert_eq!(cpu.inputs[1], 0b1000);
        assert_eq!(cpu.image[1], 0, "the PII is read at the cycle start");
        cpu.run(crate::vm::cycle::RunLimit::Cycles(1));
        let read_bit = Item::ReadBit {
            area: Area::Inputs,
            byte: 1,
            bit: 3,
        };
        assert_eq!(
            serve_items(&mut cpu, CLIENT, &[read_bit], false),
            vec![Ok(vec![1])]
        );
    }

    #[test]
    fn read_only_refuses_writes_and_serves_reads() {
        let mut cpu = cpu("OB 1\n BE\n", false);
        let flags = Range::new(Area::Flags, 0, 2);
        let items = [
            Item::Write {
                range: flags,
                bytes: vec![1, 2],
            },
            Item::Read(flags),
        ];
        assert_eq!(
            serve_items(&mut cpu, CLIENT, &items, true),
            vec![Err(ItemError::ReadOnly), Ok(vec![0, 0])]
        );
    }

    #[test]
    fn timers_and_counters_are_words_in_bcd() {
        let mut cpu = cpu("OB 1\n BE\n", false);
        let counters = Range::new(Area::Counters, 2, 1);
        write(&mut cpu, counters, &[0x01, 0x23]).unwrap();
        assert_eq!(cpu.counters[2].value, 123);
        assert_eq!(read(&mut cpu, counters), Ok(vec![0x01, 0x23]));
        let timers = Range {
            area: Area::Timers,
            ..counters
        };
        write(&mut cpu, timers, &[0x25, 0x00]).unwrap();
        assert_eq!(read(&mut cpu, timers), Ok(vec![0x25, 0x00]));
        let bit = Item::ReadBit {
            area: Area::Timers,
            byte: 0,
            bit: 0,
        };
        assert_eq!(
            serve_items(&mut cpu, CLIENT, &[bit], false),
            vec![Err(ItemError::NotSupported)]
        );
    }
}
