//! Modbus TCP frames: the MBAP header that carries each PDU over TCP, the request PDU checked
//! and decoded, the response PDU encoded (Modbus Application Protocol Specification V1.1b3 and
//! Modbus Messaging on TCP/IP Implementation Guide V1.0b).
//!
//! tokio-modbus decodes the request PDU. Its server codec is private and trusts what it reads:
//! a Write Multiple Coils request whose byte count is short of its quantity indexes past the
//! coil bytes (a panic), and a quantity of 0x8000 registers overflows when doubled. So the
//! quantities and byte counts are checked here first, against the specification's limits,
//! which also gives the exception code it names for each (3, illegal data value).

use tokio_modbus::bytes::Bytes;
use tokio_modbus::{ExceptionCode, Request, Response};

/// The MBAP header's length: transaction id, protocol id, length, unit id.
pub const HEADER_LENGTH: usize = 7;

/// The longest PDU (Application Protocol Specification, 4.1): 253 bytes.
pub const MAX_PDU_LENGTH: usize = 253;

/// The longest frame: the header and the longest PDU.
pub const MAX_FRAME_LENGTH: usize = HEADER_LENGTH + MAX_PDU_LENGTH;

/// The header of a request, echoed in its response.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    pub transaction: u16,
    pub unit: u8,
}

/// A frame the stream cannot be trusted past: the connection is closed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadFrame {
    /// The protocol id is not 0, Modbus's.
    Protocol(u16),
    /// The length field counts neither a unit id and a function code nor fits the longest PDU.
    Length(u16),
}

/// One complete frame at the start of a buffer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Frame<'a> {
    pub header: Header,
    pub pdu: &'a [u8],
    /// The frame's bytes in the buffer, header included.
    pub length: usize,
}

fn word(bytes: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes([*bytes.get(at)?, *bytes.get(at + 1)?]))
}

/// The frame at the start of `buffer`: `Ok(None)` until it has arrived whole. The header is
/// checked as soon as it is there, so a bad one closes the connection before its PDU is awaited.
pub fn split(buffer: &[u8]) -> Result<Option<Frame<'_>>, BadFrame> {
    let (Some(transaction), Some(protocol), Some(length), Some(&unit)) = (
        word(buffer, 0),
        word(buffer, 2),
        word(buffer, 4),
        buffer.get(6),
    ) else {
        return Ok(None);
    };
    if protocol != 0 {
        return Err(BadFrame::Protocol(protocol));
    }
    // The length counts the unit id and the PDU, which has at least its function code.
    let pdu_length = usize::from(length).saturating_sub(1);
    if !(1..=MAX_PDU_LENGTH).contains(&pdu_length) {
        return Err(BadFrame::Length(length));
    }
    let end = HEADER_LENGTH + pdu_length;
    Ok(buffer.get(HEADER_LENGTH..end).map(|pdu| Frame {
        header: Header { transaction, unit },
        pdu,
        length: end,
    }))
}

/// The function codes served.
const READ_COILS: u8 = 0x01;
const READ_DISCRETE_INPUTS: u8 = 0x02;
const READ_HOLDING_REGISTERS: u8 = 0x03;
const READ_INPUT_REGISTERS: u8 = 0x04;
const WRITE_SINGLE_COIL: u8 = 0x05;
const WRITE_SINGLE_REGISTER: u8 = 0x06;
const WRITE_MULTIPLE_COILS: u8 = 0x0F;
const WRITE_MULTIPLE_REGISTERS: u8 = 0x10;
const READ_WRITE_MULTIPLE_REGISTERS: u8 = 0x17;

/// The most bits one request reads (2000) or writes (1968), and registers (125, 123; function
/// 23 writes at most 121), as the Application Protocol Specification's sections 6.1–6.17 give.
const MAX_READ_BITS: u16 = 2000;
const MAX_WRITE_BITS: u16 = 1968;
const MAX_READ_REGISTERS: u16 = 125;
const MAX_WRITE_REGISTERS: u16 = 123;
const MAX_READ_WRITE_REGISTERS: u16 = 121;

/// The request a PDU asks, or the exception it is answered with: 1 for a function not served,
/// 3 for a quantity past the function's limit, a byte count that does not match it, or a PDU
/// of the wrong length.
pub fn decode(pdu: &[u8]) -> Result<Request<'static>, ExceptionCode> {
    let function = *pdu.first().ok_or(ExceptionCode::IllegalDataValue)?;
    check_quantities(function, pdu)?;
    Request::try_from(Bytes::copy_from_slice(pdu)).map_err(|_| ExceptionCode::IllegalDataValue)
}

fn check_quantities(function: u8, pdu: &[u8]) -> Result<(), ExceptionCode> {
    let within = |at: usize, max: u16| {
        word(pdu, at)
            .filter(|quantity| (1..=max).contains(quantity))
            .ok_or(ExceptionCode::IllegalDataValue)
    };
    let counts = |at: usize, wanted: usize| {
        if pdu.get(at).map(|count| usize::from(*count)) == Some(wanted) {
            Ok(())
        } else {
            Err(ExceptionCode::IllegalDataValue)
        }
    };
    match function {
        READ_COILS | READ_DISCRETE_INPUTS => within(3, MAX_READ_BITS).map(drop),
        READ_HOLDING_REGISTERS | READ_INPUT_REGISTERS => within(3, MAX_READ_REGISTERS).map(drop),
        WRITE_SINGLE_COIL | WRITE_SINGLE_REGISTER => Ok(()),
        WRITE_MULTIPLE_COILS => {
            let quantity = within(3, MAX_WRITE_BITS)?;
            counts(5, usize::from(quantity).div_ceil(8))
        }
        WRITE_MULTIPLE_REGISTERS => {
            let quantity = within(3, MAX_WRITE_REGISTERS)?;
            counts(5, 2 * usize::from(quantity))
        }
        READ_WRITE_MULTIPLE_REGISTERS => {
            within(3, MAX_READ_REGISTERS)?;
            let quantity = within(7, MAX_READ_WRITE_REGISTERS)?;
            counts(9, 2 * usize::from(quantity))
        }
        _ => Err(ExceptionCode::IllegalFunction),
    }
}

/// The response frame to a request of `function` under `header`.
pub fn encode(header: Header, function: u8, answer: &Result<Response, ExceptionCode>) -> Vec<u8> {
    let mut pdu = Vec::with_capacity(MAX_PDU_LENGTH);
    match answer {
        Ok(response) => response_pdu(response, &mut pdu),
        Err(exception) => {
            pdu.push(function | 0x80);
            pdu.push(u8::from(*exception));
        }
    }
    let mut frame = Vec::with_capacity(HEADER_LENGTH + pdu.len());
    frame.extend_from_slice(&header.transaction.to_be_bytes());
    frame.extend_from_slice(&[0, 0]);
    // At most 1 + 253: the PDU fits a u16 with room.
    frame.extend_from_slice(&(pdu.len() as u16 + 1).to_be_bytes());
    frame.push(header.unit);
    frame.extend_from_slice(&pdu);
    frame
}

fn packed_bits(bits: &[bool], pdu: &mut Vec<u8>) {
    let bytes = bits.len().div_ceil(8);
    // At most 2000 bits: 250 bytes.
    pdu.push(bytes as u8);
    pdu.extend((0..bytes).map(|byte| {
        bits.iter()
            .skip(byte * 8)
            .take(8)
            .enumerate()
            .fold(0u8, |packed, (bit, on)| packed | (u8::from(*on) << bit))
    }));
}

fn registers(words: &[u16], pdu: &mut Vec<u8>) {
    // At most 125 registers: 250 bytes.
    pdu.push((2 * words.len()) as u8);
    pdu.extend(words.iter().flat_map(|word| word.to_be_bytes()));
}

fn response_pdu(response: &Response, pdu: &mut Vec<u8>) {
    pdu.push(response.function_code().value());
    match response {
        Response::ReadCoils(bits) | Response::ReadDiscreteInputs(bits) => packed_bits(bits, pdu),
        Response::ReadHoldingRegisters(words)
        | Response::ReadInputRegisters(words)
        | Response::ReadWriteMultipleRegisters(words) => registers(words, pdu),
        Response::WriteSingleCoil(address, on) => {
            pdu.extend_from_slice(&address.to_be_bytes());
            pdu.extend_from_slice(&if *on { [0xFF, 0x00] } else { [0, 0] });
        }
        Response::WriteSingleRegister(address, value)
        | Response::WriteMultipleCoils(address, value)
        | Response::WriteMultipleRegisters(address, value) => {
            pdu.extend_from_slice(&address.to_be_bytes());
            pdu.extend_from_slice(&value.to_be_bytes());
        }
        // The server answers no other function (`decode` refuses them).
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_is_split_once_whole() {
        let frame = [0x12, 0x34, 0, 0, 0, 6, 0xFF, 3, 0, 1, 0, 2, 0xAA];
        for cut in 0..12 {
            assert_eq!(split(&frame[..cut]), Ok(None), "{cut} bytes");
        }
        let whole = split(&frame).expect("a good header").expect("whole");
        assert_eq!(
            whole.header,
            Header {
                transaction: 0x1234,
                unit: 0xFF
            }
        );
        assert_eq!(whole.pdu, &[3, 0, 1, 0, 2]);
        assert_eq!(whole.length, 12, "the next frame's byte is left");
    }

    #[test]
    fn a_bad_header_is_refused_before_its_pdu_arrives() {
        assert_eq!(split(&[0, 1, 0, 7, 0, 6, 1]), Err(BadFrame::Protocol(7)));
        assert_eq!(split(&[0, 1, 0, 0, 0, 1, 1]), Err(BadFrame::Length(1)));
        assert_eq!(split(&[0, 1, 0, 0, 0, 0, 1]), Err(BadFrame::Length(0)));
        assert_eq!(
            split(&[0, 1, 0, 0, 0xFF, 0xFF, 1]),
            Err(BadFrame::Length(0xFFFF))
        );
        assert_eq!(split(&[0, 1, 0, 0, 0, 255, 1]), Err(BadFrame::Length(255)));
        assert!(split(&[0, 1, 0, 0, 0, 254, 1]).is_ok(), "253 bytes of PDU");
    }

    #[test]
    fn requests_decode_into_tokio_modbus_requests() {
        assert_eq!(decode(&[1, 0, 5, 0, 3]), Ok(Request::ReadCoils(5, 3)));
        assert_eq!(
            decode(&[0x0F, 0, 1, 0, 10, 2, 0xFF, 0x03]),
            Ok(Request::WriteMultipleCoils(
                1,
                vec![true, true, true, true, true, true, true, true, true, true].into()
            ))
        );
        assert_eq!(
            decode(&[0x10, 0, 2, 0, 1, 2, 0x12, 0x34]),
            Ok(Request::WriteMultipleRegisters(2, vec![0x1234].into()))
        );
        assert_eq!(
            decode(&[0x17, 0, 0, 0, 2, 0, 4, 0, 1, 2, 0xAB, 0xCD]),
            Ok(Request::ReadWriteMultipleRegisters(
                0,
                2,
                4,
                vec![0xABCD].into()
            ))
        );
    }

    #[test]
    fn exceptions_follow_the_specification() {
        let illegal_value = Err(ExceptionCode::IllegalDataValue);
        assert_eq!(
            decode(&[0x2B, 0x0E, 1, 0]),
            Err(ExceptionCode::IllegalFunction)
        );
        assert_eq!(decode(&[0x41]), Err(ExceptionCode::IllegalFunction));
        assert_eq!(decode(&[0x81, 0]), Err(ExceptionCode::IllegalFunction));
        assert_eq!(decode(&[1, 0, 0, 0, 0]), illegal_value, "no bits");
        assert_eq!(decode(&[1, 0, 0, 0x07, 0xD1]), illegal_value, "2001 bits");
        assert!(decode(&[1, 0, 0, 0x07, 0xD0]).is_ok(), "2000 bits");
        assert_eq!(decode(&[3, 0, 0, 0, 126]), illegal_value, "126 registers");
        assert_eq!(decode(&[3, 0, 0, 0]), illegal_value, "cut short");
        assert_eq!(
            decode(&[3, 0, 0, 0, 1, 9]),
            illegal_value,
            "a byte too many"
        );
        assert_eq!(decode(&[5, 0, 0, 0x12, 0x34]), illegal_value, "coil value");
        // A byte count short of the quantity: tokio-modbus alone would index past the bytes.
        assert_eq!(decode(&[0x0F, 0, 0, 0, 100, 0]), illegal_value);
        assert_eq!(decode(&[0x0F, 0, 0, 0, 9, 1, 0xFF]), illegal_value);
        // A quantity whose double overflows 16 bits.
        assert_eq!(decode(&[0x10, 0, 0, 0x80, 0, 0]), illegal_value);
        assert_eq!(decode(&[0x17, 0, 0, 0, 1, 0, 0, 0x80, 0, 0]), illegal_value);
        assert_eq!(
            decode(&[0x10, 0, 0, 0, 1, 2, 0x12]),
            illegal_value,
            "cut short"
        );
        assert_eq!(decode(&[]), illegal_value);
    }

    #[test]
    fn responses_encode_with_the_request_s_header() {
        let header = Header {
            transaction: 7,
            unit: 1,
        };
        let bits = vec![true, false, true, true, false, false, false, false, true];
        assert_eq!(
            encode(header, 1, &Ok(Response::ReadCoils(bits))),
            [0, 7, 0, 0, 0, 5, 1, 1, 2, 0b1101, 1]
        );
        assert_eq!(
            encode(header, 3, &Ok(Response::ReadHoldingRegisters(vec![0x1234]))),
            [0, 7, 0, 0, 0, 5, 1, 3, 2, 0x12, 0x34]
        );
        assert_eq!(
            encode(header, 5, &Ok(Response::WriteSingleCoil(9, true))),
            [0, 7, 0, 0, 0, 6, 1, 5, 0, 9, 0xFF, 0]
        );
        assert_eq!(
            encode(header, 0x10, &Ok(Response::WriteMultipleRegisters(2, 3))),
            [0, 7, 0, 0, 0, 6, 1, 0x10, 0, 2, 0, 3]
        );
        assert_eq!(
            encode(header, 0x2B, &Err(ExceptionCode::IllegalFunction)),
            [0, 7, 0, 0, 0, 3, 1, 0xAB, 1]
        );
    }
}
