//! A Modbus request as the items of one CPU access, and the items' results as the response.
//! One request is one access, served at one cycle control point: what it reads is one
//! consistent state. Bits are read as the whole bytes they lie in and sliced; coils are written
//! whole bytes where the request covers them, bit by bit at its ragged ends.

use tokio_modbus::{ExceptionCode, Request, Response};

use super::map::{Map, Table};
use crate::serve::request::{Item, ItemError, ItemResult, Range};

/// Modbus addresses are 16-bit: a request may reach address 65535 and no further.
const ADDRESSES: u32 = 1 << 16;

/// The items a request needs, or the exception it is answered with at once.
pub fn items(request: &Request<'_>, map: &Map) -> Result<Vec<Item>, ExceptionCode> {
    Ok(match request {
        Request::ReadCoils(address, quantity) => vec![read_bits(map.coils, *address, *quantity)?],
        Request::ReadDiscreteInputs(address, quantity) => {
            vec![read_bits(map.discrete_inputs, *address, *quantity)?]
        }
        Request::ReadHoldingRegisters(address, quantity) => {
            vec![read_registers(map.holding_registers, *address, *quantity)?]
        }
        Request::ReadInputRegisters(address, quantity) => {
            vec![read_registers(map.input_registers, *address, *quantity)?]
        }
        Request::WriteSingleCoil(address, on) => write_bits(map.coils, *address, &[*on])?,
        Request::WriteMultipleCoils(address, bits) => write_bits(map.coils, *address, bits)?,
        Request::WriteSingleRegister(address, word) => {
            vec![write_registers(map.holding_registers, *address, &[*word])?]
        }
        Request::WriteMultipleRegisters(address, words) => {
            vec![write_registers(map.holding_registers, *address, words)?]
        }
        // The write comes first (Application Protocol Specification, 6.17).
        Request::ReadWriteMultipleRegisters(read, quantity, write, words) => vec![
            write_registers(map.holding_registers, *write, words)?,
            read_registers(map.holding_registers, *read, *quantity)?,
        ],
        _ => return Err(ExceptionCode::IllegalFunction),
    })
}

/// The first address and the count of a request, when it asks for some and all of it lies
/// below address 65536.
fn span(address: u16, count: usize) -> Result<(u32, u32), ExceptionCode> {
    if count == 0 {
        return Err(ExceptionCode::IllegalDataValue);
    }
    let (first, count) = (u32::from(address), count as u32);
    if first + count > ADDRESSES {
        return Err(ExceptionCode::IllegalDataAddress);
    }
    Ok((first, count))
}

/// The bytes bits `first` to `first + count - 1` of `table` lie in.
fn bit_bytes(table: Table, first: u32, count: u32) -> Range {
    let (from, to) = (table.start + first, table.start + first + count - 1);
    Range::new(table.area, from / 8, to / 8 - from / 8 + 1)
}

fn read_bits(table: Table, address: u16, quantity: u16) -> Result<Item, ExceptionCode> {
    let (first, count) = span(address, usize::from(quantity))?;
    Ok(Item::Read(bit_bytes(table, first, count)))
}

fn read_registers(table: Table, address: u16, quantity: u16) -> Result<Item, ExceptionCode> {
    let (first, count) = span(address, usize::from(quantity))?;
    Ok(Item::Read(Range::new(
        table.area,
        table.start + 2 * first,
        2 * count,
    )))
}

fn write_registers(table: Table, address: u16, words: &[u16]) -> Result<Item, ExceptionCode> {
    let (first, count) = span(address, words.len())?;
    Ok(Item::Write {
        range: Range::new(table.area, table.start + 2 * first, 2 * count),
        bytes: words.iter().flat_map(|word| word.to_be_bytes()).collect(),
    })
}

/// Whole bytes for the bytes the bits fill, single bits before and after them.
fn write_bits(table: Table, address: u16, bits: &[bool]) -> Result<Vec<Item>, ExceptionCode> {
    let (first, count) = span(address, bits.len())?;
    let first = table.start + first;
    let end = first + count;
    let (whole_from, whole_to) = (first.div_ceil(8), end / 8);
    let bit_item = |at: u32, value: bool| Item::WriteBit {
        area: table.area,
        byte: at / 8,
        bit: (at % 8) as u8,
        value,
    };
    let value = |at: u32| bits[(at - first) as usize];
    let mut items = Vec::new();
    if whole_from >= whole_to {
        items.extend((first..end).map(|at| bit_item(at, value(at))));
        return Ok(items);
    }
    items.extend((first..whole_from * 8).map(|at| bit_item(at, value(at))));
    let bytes = (whole_from..whole_to)
        .map(|byte| {
            (0..8).fold(0u8, |packed, bit| {
                packed | u8::from(value(byte * 8 + bit)) << bit
            })
        })
        .collect();
    items.push(Item::Write {
        range: Range::new(table.area, whole_from, whole_to - whole_from),
        bytes,
    });
    items.extend((whole_to * 8..end).map(|at| bit_item(at, value(at))));
    Ok(items)
}

/// The exception an item error is answered with: an address past the mapped area or a data
/// block that does not exist is an illegal data address (2); a refused write (`--read-only`) an
/// illegal function (1), the function is not allowed on this server; what the CPU cannot give a
/// server device failure (4).
fn exception(error: ItemError) -> ExceptionCode {
    match error {
        ItemError::OutOfRange | ItemError::NoSuchBlock => ExceptionCode::IllegalDataAddress,
        ItemError::ReadOnly => ExceptionCode::IllegalFunction,
        ItemError::NotSupported => ExceptionCode::ServerDeviceFailure,
    }
}

/// The response to `request` from the results of its items, in the order [`items`] gave them.
pub fn response(
    request: &Request<'_>,
    map: &Map,
    results: Vec<ItemResult>,
) -> Result<Response, ExceptionCode> {
    let mut results = results
        .into_iter()
        .map(|result| result.map_err(exception))
        .collect::<Result<Vec<_>, _>>()?;
    // A request's read, when it has one, is its last item.
    let read = results.pop().unwrap_or_default();
    Ok(match request {
        Request::ReadCoils(address, quantity) => {
            Response::ReadCoils(bits_of(&read, map.coils, *address, *quantity)?)
        }
        Request::ReadDiscreteInputs(address, quantity) => {
            Response::ReadDiscreteInputs(bits_of(&read, map.discrete_inputs, *address, *quantity)?)
        }
        Request::ReadHoldingRegisters(_, quantity) => {
            Response::ReadHoldingRegisters(words_of(&read, *quantity)?)
        }
        Request::ReadInputRegisters(_, quantity) => {
            Response::ReadInputRegisters(words_of(&read, *quantity)?)
        }
        Request::ReadWriteMultipleRegisters(_, quantity, _, _) => {
            Response::ReadWriteMultipleRegisters(words_of(&read, *quantity)?)
        }
        Request::WriteSingleCoil(address, on) => Response::WriteSingleCoil(*address, *on),
        Request::WriteMultipleCoils(address, bits) => {
            Response::WriteMultipleCoils(*address, bits.len() as u16)
        }
        Request::WriteSingleRegister(address, word) => {
            Response::WriteSingleRegister(*address, *word)
        }
        Request::WriteMultipleRegisters(address, words) => {
            Response::WriteMultipleRegisters(*address, words.len() as u16)
        }
        _ => return Err(ExceptionCode::IllegalFunction),
    })
}

/// The bits a read asked for, cut from the bytes they lie in.
fn bits_of(
    bytes: &[u8],
    table: Table,
    address: u16,
    quantity: u16,
) -> Result<Vec<bool>, ExceptionCode> {
    let range = bit_bytes(table, u32::from(address), u32::from(quantity));
    if bytes.len() != range.length as usize {
        return Err(ExceptionCode::ServerDeviceFailure);
    }
    let first = (table.start + u32::from(address)) as usize - 8 * range.start as usize;
    Ok((first..first + usize::from(quantity))
        .map(|at| bytes[at / 8] >> (at % 8) & 1 == 1)
        .collect())
}

/// Big-endian words: register n is the S7 word at byte 2n of the table.
fn words_of(bytes: &[u8], quantity: u16) -> Result<Vec<u16>, ExceptionCode> {
    if bytes.len() != 2 * usize::from(quantity) {
        return Err(ExceptionCode::ServerDeviceFailure);
    }
    Ok(bytes
        .chunks_exact(2)
        .map(|word| u16::from_be_bytes([word[0], word[1]]))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::serve::request::Area;

    fn coils_at(area: Area, start: u32) -> Map {
        Map {
            coils: Table { area, start },
            ..Map::default()
        }
    }

    #[test]
    fn a_bit_read_reads_the_bytes_the_bits_lie_in() {
        let map = coils_at(Area::Inputs, 3);
        let request = Request::ReadCoils(10, 4);
        let range = Range::new(Area::Inputs, 1, 2);
        assert_eq!(items(&request, &map), Ok(vec![Item::Read(range)]));
        // Bits 13 to 16 of the area: byte 1 bits 5 to 7, byte 2 bit 0.
        assert_eq!(
            response(&request, &map, vec![Ok(vec![0b1010_0000, 0b0000_0001])]),
            Ok(Response::ReadCoils(vec![true, false, true, true]))
        );
    }

    #[test]
    fn registers_are_big_endian_words_two_bytes_apart() {
        let map = Map::default();
        let request = Request::ReadHoldingRegisters(5, 2);
        let range = Range::new(Area::Flags, 10, 4);
        assert_eq!(items(&request, &map), Ok(vec![Item::Read(range)]));
        assert_eq!(
            response(&request, &map, vec![Ok(vec![0x12, 0x34, 0xAB, 0xCD])]),
            Ok(Response::ReadHoldingRegisters(vec![0x1234, 0xABCD]))
        );
        let write = Request::WriteMultipleRegisters(1, vec![0xBEEF].into());
        assert_eq!(
            items(&write, &map),
            Ok(vec![Item::Write {
                range: Range::new(Area::Flags, 2, 2),
                bytes: vec![0xBE, 0xEF]
            }])
        );
    }

    #[test]
    fn coils_are_written_as_whole_bytes_and_the_bits_at_the_ends() {
        let map = Map::default();
        let mut bits = vec![false; 20];
        bits[0] = true;
        bits[6] = true;
        bits[19] = true;
        let written = items(&Request::WriteMultipleCoils(5, bits.into()), &map).expect("items");
        let bit = |byte, bit, value| Item::WriteBit {
            area: Area::Outputs,
            byte,
            bit,
            value,
        };
        // Bits 5 to 24: byte 0 bits 5–7, bytes 1 and 2 whole, byte 3 bit 0.
        assert_eq!(
            written,
            vec![
                bit(0, 5, true),
                bit(0, 6, false),
                bit(0, 7, false),
                Item::Write {
                    range: Range::new(Area::Outputs, 1, 2),
                    bytes: vec![0b0000_1000, 0]
                },
                bit(3, 0, true),
            ]
        );
        assert_eq!(
            items(&Request::WriteSingleCoil(9, true), &map),
            Ok(vec![bit(1, 1, true)])
        );
    }

    #[test]
    fn a_write_then_read_writes_first() {
        let map = Map::default();
        let request = Request::ReadWriteMultipleRegisters(0, 1, 3, vec![7].into());
        let found = items(&request, &map).expect("items");
        assert!(matches!(found[0], Item::Write { .. }));
        assert!(matches!(found[1], Item::Read(_)));
        assert_eq!(
            response(&request, &map, vec![Ok(vec![]), Ok(vec![0, 7])]),
            Ok(Response::ReadWriteMultipleRegisters(vec![7]))
        );
    }

    #[test]
    fn item_errors_and_addresses_past_65535_are_exceptions() {
        let map = Map::default();
        let request = Request::ReadHoldingRegisters(0, 1);
        let answer = |error| response(&request, &map, vec![Err(error)]);
        assert_eq!(
            answer(ItemError::OutOfRange),
            Err(ExceptionCode::IllegalDataAddress)
        );
        assert_eq!(
            answer(ItemError::NoSuchBlock),
            Err(ExceptionCode::IllegalDataAddress)
        );
        assert_eq!(
            answer(ItemError::ReadOnly),
            Err(ExceptionCode::IllegalFunction)
        );
        assert_eq!(
            response(&request, &map, vec![Ok(vec![1])]),
            Err(ExceptionCode::ServerDeviceFailure),
            "a short answer"
        );
        assert_eq!(
            items(&Request::ReadCoils(65535, 2), &map),
            Err(ExceptionCode::IllegalDataAddress)
        );
        assert!(items(&Request::ReadCoils(65535, 1), &map).is_ok());
        assert_eq!(
            items(&Request::ReadCoils(0, 0), &map),
            Err(ExceptionCode::IllegalDataValue),
            "nothing to read"
        );
        assert_eq!(
            items(&Request::WriteMultipleCoils(0, vec![].into()), &map),
            Err(ExceptionCode::IllegalDataValue)
        );
    }
}
