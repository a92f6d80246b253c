//! The S7 PDUs a client sends, decoded: the header (protocol id 0x32, the PDU type, the PDU
//! reference the answer echoes, the lengths of the parameter and data sections), then per
//! function the parameters and data. Every length is checked against the bytes there are;
//! nothing is allocated beyond what the packet holds.

use crate::serve::request::{Area, Range};

pub const PROTOCOL_ID: u8 = 0x32;
const JOB: u8 = 0x01;
const USERDATA: u8 = 0x07;
const HEADER: usize = 10;

pub const READ_VAR: u8 = 0x04;
pub const WRITE_VAR: u8 = 0x05;
pub const PI_START: u8 = 0x28;
pub const PLC_STOP: u8 = 0x29;
pub const SETUP_COMMUNICATION: u8 = 0xF0;

/// The return codes of one read or write item ("Programming with STEP 7", S7 communication:
/// the item's access result).
pub mod return_code {
    pub const HARDWARE_FAULT: u8 = 0x01;
    pub const ACCESS_DENIED: u8 = 0x03;
    pub const INVALID_ADDRESS: u8 = 0x05;
    pub const TYPE_NOT_SUPPORTED: u8 = 0x06;
    pub const TYPE_INCONSISTENT: u8 = 0x07;
    pub const OBJECT_DOES_NOT_EXIST: u8 = 0x0A;
    pub const SUCCESS: u8 = 0xFF;
}

/// A decoded request: its reference and what it asks.
#[derive(Debug, Clone, PartialEq)]
pub struct Pdu<'a> {
    pub reference: u16,
    pub message: Message<'a>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Message<'a> {
    Setup {
        max_amq_calling: u16,
        max_amq_called: u16,
        pdu_length: u16,
    },
    Read(Vec<Result<Address, u8>>),
    /// Each item: its address and the bytes to write, or the item's return code.
    Write(Vec<Result<(Address, &'a [u8]), u8>>),
    /// Function 0x29 or 0x28 with a program invocation service.
    Control {
        function: u8,
        service: &'a [u8],
        argument: &'a [u8],
    },
    Userdata(Userdata<'a>),
}

/// A userdata request (function group, subfunction): SZL reads, the clock, …
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Userdata<'a> {
    pub group: u8,
    pub subfunction: u8,
    /// The sequence number of a multi-packet answer this request continues (0 at first).
    pub sequence: u8,
    /// A follow-up request: the next packet of an answer.
    pub follow_up: bool,
    pub data: &'a [u8],
}

/// A request that is no request awl serves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadPdu {
    /// Not an S7 PDU at all: the connection is closed.
    NotS7,
    /// The header is readable but the rest is not (lengths, truncated sections): answered
    /// with "wrong frames".
    Malformed { reference: u16, function: u8 },
    /// A PDU type or function awl does not serve: answered with "service not implemented".
    Unsupported { reference: u16, function: u8 },
}

/// What one read or write item addresses, and how its data travels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Address {
    pub target: Target,
    pub kind: DataKind,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    Bytes(Range),
    Bit { area: Area, byte: u32, bit: u8 },
}

/// The transport size of an item's data in the data section, which also says whether its
/// length counts bits or bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataKind {
    Bit,
    Bytes,
    Integer,
    Real,
    Octets,
}

impl DataKind {
    pub fn transport_size(self) -> u8 {
        match self {
            DataKind::Bit => 0x03,
            DataKind::Bytes => 0x04,
            DataKind::Integer => 0x05,
            DataKind::Real => 0x07,
            DataKind::Octets => 0x09,
        }
    }

    /// The length field of `bytes` bytes of data.
    pub fn length_field(self, bytes: usize) -> u16 {
        match self {
            DataKind::Bytes | DataKind::Integer => (bytes * 8) as u16,
            _ => bytes as u16,
        }
    }
}

impl Address {
    /// The bytes the item's data has.
    pub fn data_length(&self) -> usize {
        match self.target {
            Target::Bytes(range) => match range.area {
                Area::Timers | Area::Counters => range.length as usize * 2,
                _ => range.length as usize,
            },
            Target::Bit { .. } => 1,
        }
    }
}

/// Decodes one S7 PDU (the payload of the COTP data TPDUs).
pub fn decode(bytes: &[u8]) -> Result<Pdu<'_>, BadPdu> {
    let header = bytes.get(..HEADER).ok_or(BadPdu::NotS7)?;
    if header[0] != PROTOCOL_ID {
        return Err(BadPdu::NotS7);
    }
    let pdu_type = header[1];
    let reference = u16::from_be_bytes([header[4], header[5]]);
    let parameter_length = usize::from(u16::from_be_bytes([header[6], header[7]]));
    let data_length = usize::from(u16::from_be_bytes([header[8], header[9]]));
    let body = &bytes[HEADER..];
    let function = body.first().copied().unwrap_or(0);
    let malformed = BadPdu::Malformed {
        reference,
        function,
    };
    if body.len() != parameter_length + data_length || parameter_length == 0 {
        return Err(malformed);
    }
    let (parameters, data) = body.split_at(parameter_length);
    let message = match pdu_type {
        JOB => decode_job(parameters, data),
        USERDATA => decode_userdata(parameters, data).map(Message::Userdata),
        _ => {
            return Err(BadPdu::Unsupported {
                reference,
                function,
            });
        }
    };
    match message {
        Ok(message) => Ok(Pdu { reference, message }),
        Err(Refusal::Malformed) => Err(malformed),
        Err(Refusal::Unsupported) => Err(BadPdu::Unsupported {
            reference,
            function,
        }),
    }
}

enum Refusal {
    Malformed,
    Unsupported,
}

fn decode_job<'a>(parameters: &'a [u8], data: &'a [u8]) -> Result<Message<'a>, Refusal> {
    match parameters[0] {
        SETUP_COMMUNICATION => {
            // Function, a reserved byte, the parallel jobs each side may have open, the PDU
            // length the client proposes.
            let &[
                _,
                _,
                calling_high,
                calling_low,
                called_high,
                called_low,
                high,
                low,
            ] = parameters
            else {
                return Err(Refusal::Malformed);
            };
            Ok(Message::Setup {
                max_amq_calling: u16::from_be_bytes([calling_high, calling_low]),
                max_amq_called: u16::from_be_bytes([called_high, called_low]),
                pdu_length: u16::from_be_bytes([high, low]),
            })
        }
        READ_VAR => {
            let specifications = item_specifications(parameters)?;
            if !data.is_empty() {
                return Err(Refusal::Malformed);
            }
            Ok(Message::Read(
                specifications.into_iter().map(address).collect(),
            ))
        }
        WRITE_VAR => decode_write(parameters, data),
        PLC_STOP => {
            // Function, five reserved bytes, the service name's length and the name.
            let service = counted(parameters.get(6..).ok_or(Refusal::Malformed)?)?;
            Ok(Message::Control {
                function: PLC_STOP,
                service,
                argument: &[],
            })
        }
        PI_START => {
            // Function, seven reserved bytes, the argument's length (a word) and the argument,
            // the service name's length and the name.
            let rest = parameters.get(8..).ok_or(Refusal::Malformed)?;
            let [high, low, rest @ ..] = rest else {
                return Err(Refusal::Malformed);
            };
            let length = usize::from(u16::from_be_bytes([*high, *low]));
            let argument = rest.get(..length).ok_or(Refusal::Malformed)?;
            let service = counted(&rest[length..])?;
            Ok(Message::Control {
                function: PI_START,
                service,
                argument,
            })
        }
        _ => Err(Refusal::Unsupported),
    }
}

/// A byte string after its one-byte length, which must end the section.
fn counted(bytes: &[u8]) -> Result<&[u8], Refusal> {
    let (&length, rest) = bytes.split_first().ok_or(Refusal::Malformed)?;
    if rest.len() == usize::from(length) {
        Ok(rest)
    } else {
        Err(Refusal::Malformed)
    }
}

/// The item specifications of a read or write job: the function, the item count, then each
/// item as 0x12, the length of the rest, and the rest.
fn item_specifications(parameters: &[u8]) -> Result<Vec<&[u8]>, Refusal> {
    let [_, count, rest @ ..] = parameters else {
        return Err(Refusal::Malformed);
    };
    let mut rest = rest;
    let mut specifications = Vec::with_capacity(usize::from(*count).min(rest.len() / 2));
    for _ in 0..*count {
        let [0x12, length, tail @ ..] = rest else {
            return Err(Refusal::Malformed);
        };
        let specification = tail.get(..usize::from(*length)).ok_or(Refusal::Malformed)?;
        specifications.push(specification);
        rest = &tail[specification.len()..];
    }
    if rest.is_empty() {
        Ok(specifications)
    } else {
        Err(Refusal::Malformed)
    }
}

/// Transport sizes of an item specification (the S7ANY pointer's data type).
mod transport {
    pub const BIT: u8 = 0x01;
    pub const BYTE: u8 = 0x02;
    pub const CHAR: u8 = 0x03;
    pub const WORD: u8 = 0x04;
    pub const INT: u8 = 0x05;
    pub const DWORD: u8 = 0x06;
    pub const DINT: u8 = 0x07;
    pub const REAL: u8 = 0x08;
    pub const COUNTER: u8 = 0x1C;
    pub const TIMER: u8 = 0x1D;
}

/// The area codes of an item specification.
mod area_code {
    pub const INPUTS: u8 = 0x81;
    pub const OUTPUTS: u8 = 0x82;
    pub const FLAGS: u8 = 0x83;
    pub const DATA_BLOCK: u8 = 0x84;
    pub const COUNTERS: u8 = 0x1C;
    pub const TIMERS: u8 = 0x1D;
}

/// One item specification of the S7ANY syntax (0x10): transport size, count, DB number, area,
/// and the address (in bits; for timers and counters their number).
fn address(specification: &[u8]) -> Result<Address, u8> {
    let &[
        0x10,
        transport,
        count_high,
        count_low,
        db_high,
        db_low,
        area,
        a0,
        a1,
        a2,
    ] = specification
    else {
        return Err(return_code::TYPE_NOT_SUPPORTED);
    };
    let count = u32::from(u16::from_be_bytes([count_high, count_low]));
    let pointer = u32::from_be_bytes([0, a0, a1, a2]);
    let area = match area {
        area_code::INPUTS => Area::Inputs,
        area_code::OUTPUTS => Area::Outputs,
        area_code::FLAGS => Area::Flags,
        area_code::DATA_BLOCK => Area::DataBlock(u16::from_be_bytes([db_high, db_low])),
        area_code::COUNTERS => Area::Counters,
        area_code::TIMERS => Area::Timers,
        _ => return Err(return_code::OBJECT_DOES_NOT_EXIST),
    };
    if count == 0 {
        return Err(return_code::INVALID_ADDRESS);
    }
    let counted_area = matches!(area, Area::Timers | Area::Counters);
    let (width, kind) = match transport {
        transport::BIT => {
            // One bit per item, as on a real CPU.
            if count != 1 {
                return Err(return_code::INVALID_ADDRESS);
            }
            let target = Target::Bit {
                area,
                byte: pointer >> 3,
                bit: (pointer & 7) as u8,
            };
            return Ok(Address {
                target,
                kind: DataKind::Bit,
            });
        }
        transport::TIMER | transport::COUNTER => {
            let matching = (transport == transport::TIMER && area == Area::Timers)
                || (transport == transport::COUNTER && area == Area::Counters);
            if !matching {
                return Err(return_code::TYPE_NOT_SUPPORTED);
            }
            let range = Range::new(area, pointer, count);
            return Ok(Address {
                target: Target::Bytes(range),
                kind: DataKind::Octets,
            });
        }
        transport::BYTE | transport::WORD | transport::DWORD => {
            (width_of(transport), DataKind::Bytes)
        }
        transport::CHAR => (1, DataKind::Octets),
        transport::INT | transport::DINT => (width_of(transport), DataKind::Integer),
        transport::REAL => (4, DataKind::Real),
        _ => return Err(return_code::TYPE_NOT_SUPPORTED),
    };
    if counted_area {
        return Err(return_code::TYPE_NOT_SUPPORTED);
    }
    if pointer & 7 != 0 {
        return Err(return_code::INVALID_ADDRESS);
    }
    let range = Range::new(area, pointer >> 3, count * width);
    Ok(Address {
        target: Target::Bytes(range),
        kind,
    })
}

fn width_of(transport: u8) -> u32 {
    match transport {
        transport::WORD | transport::INT => 2,
        transport::DWORD | transport::DINT => 4,
        _ => 1,
    }
}

/// A write job: the item specifications, then in the data section per item a reserved byte,
/// the transport size, the length (bits or bytes, by the transport size), the data and a fill
/// byte after an odd length unless it is the last item.
fn decode_write<'a>(parameters: &'a [u8], data: &'a [u8]) -> Result<Message<'a>, Refusal> {
    let specifications = item_specifications(parameters)?;
    let count = specifications.len();
    let mut items = Vec::with_capacity(count);
    let mut rest = data;
    for (index, specification) in specifications.into_iter().enumerate() {
        let [_, transport_size, high, low, tail @ ..] = rest else {
            return Err(Refusal::Malformed);
        };
        let length = usize::from(u16::from_be_bytes([*high, *low]));
        let counts_bits = matches!(transport_size, 0x04..=0x06);
        if counts_bits && length % 8 != 0 {
            return Err(Refusal::Malformed);
        }
        let bytes_length = if counts_bits { length / 8 } else { length };
        let bytes = tail.get(..bytes_length).ok_or(Refusal::Malformed)?;
        let fill = usize::from(bytes_length % 2 == 1 && index + 1 < count);
        rest = tail.get(bytes_length + fill..).ok_or(Refusal::Malformed)?;
        items.push(address(specification).and_then(|address| {
            if address.data_length() == bytes.len() {
                Ok((address, bytes))
            } else {
                Err(return_code::TYPE_INCONSISTENT)
            }
        }));
    }
    if rest.is_empty() {
        Ok(Message::Write(items))
    } else {
        Err(Refusal::Malformed)
    }
}

/// A userdata request's parameters: 0x00 0x01 0x12, the length of the rest (4, or 8 for a
/// follow-up), the method (0x11 request, 0x12 follow-up), type and function group,
/// subfunction, sequence number; then its data: a return code, transport size, length, data.
fn decode_userdata<'a>(parameters: &'a [u8], data: &'a [u8]) -> Result<Userdata<'a>, Refusal> {
    let [
        0x00,
        0x01,
        0x12,
        length,
        method,
        type_group,
        subfunction,
        sequence,
        rest @ ..,
    ] = parameters
    else {
        return Err(Refusal::Malformed);
    };
    if usize::from(*length) != rest.len() + 4 {
        return Err(Refusal::Malformed);
    }
    let follow_up = match method {
        0x11 => false,
        0x12 => true,
        _ => return Err(Refusal::Unsupported),
    };
    let [_, _, high, low, data @ ..] = data else {
        return Err(Refusal::Malformed);
    };
    if usize::from(u16::from_be_bytes([*high, *low])) != data.len() {
        return Err(Refusal::Malformed);
    }
    Ok(Userdata {
        group: type_group & 0x0F,
        subfunction: *subfunction,
        sequence: *sequence,
        follow_up,
        data,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(reference: u16, parameters: &[u8], data: &[u8]) -> Vec<u8> {
        let mut pdu = vec![0x32, JOB, 0, 0];
        pdu.extend_from_slice(&reference.to_be_bytes());
        pdu.extend_from_slice(&(parameters.len() as u16).to_be_bytes());
        pdu.extend_from_slice(&(data.len() as u16).to_be_bytes());
        pdu.extend_from_slice(parameters);
        pdu.extend_from_slice(data);
        pdu
    }

    fn item(transport: u8, count: u16, db: u16, area: u8, pointer: u32) -> Vec<u8> {
        let mut item = vec![0x12, 0x0A, 0x10, transport];
        item.extend_from_slice(&count.to_be_bytes());
        item.extend_from_slice(&db.to_be_bytes());
        item.push(area);
        item.extend_from_slice(&pointer.to_be_bytes()[1..]);
        item
    }

    /// The items of a read job asking for `items`, as decoded.
    fn read_items(items: &[Vec<u8>]) -> Vec<Result<Address, u8>> {
        let mut parameters = vec![READ_VAR, items.len() as u8];
        for item in items {
            parameters.extend_from_slice(item);
        }
        let Ok(Pdu {
            reference: 7,
            message: Message::Read(items),
        }) = decode(&job(7, &parameters, &[]))
        else {
            panic!("no read job");
        };
        items
    }

    fn range(area: Area, start: u32, length: u32) -> Target {
        Target::Bytes(Range::new(area, start, length))
    }

    #[test]
    fn setup_communication_names_the_pdu_length() {
        let pdu = job(1, &[0xF0, 0, 0, 1, 0, 1, 0x01, 0xE0], &[]);
        assert_eq!(
            decode(&pdu),
            Ok(Pdu {
                reference: 1,
                message: Message::Setup {
                    max_amq_calling: 1,
                    max_amq_called: 1,
                    pdu_length: 480
                }
            })
        );
    }

    #[test]
    fn read_items_address_bytes_bits_timers_and_counters() {
        let items = read_items(&[
            item(transport::BYTE, 10, 1, area_code::DATA_BLOCK, 4 * 8),
            item(transport::BIT, 1, 0, area_code::INPUTS, 3 * 8 + 5),
            item(transport::REAL, 2, 0, area_code::FLAGS, 8 * 8),
            item(transport::TIMER, 3, 0, area_code::TIMERS, 2),
            item(transport::COUNTER, 1, 0, area_code::COUNTERS, 15),
            item(transport::INT, 1, 0, area_code::OUTPUTS, 2 * 8),
            item(transport::CHAR, 4, 0, area_code::OUTPUTS, 0),
        ]);
        let targets: Vec<_> = items
            .iter()
            .map(|item| item.map(|address| (address.target, address.kind)))
            .collect();
        assert_eq!(
            targets,
            vec![
                Ok((range(Area::DataBlock(1), 4, 10), DataKind::Bytes)),
                Ok((
                    Target::Bit {
                        area: Area::Inputs,
                        byte: 3,
                        bit: 5
                    },
                    DataKind::Bit
                )),
                Ok((range(Area::Flags, 8, 8), DataKind::Real)),
                Ok((range(Area::Timers, 2, 3), DataKind::Octets)),
                Ok((range(Area::Counters, 15, 1), DataKind::Octets)),
                Ok((range(Area::Outputs, 2, 2), DataKind::Integer)),
                Ok((range(Area::Outputs, 0, 4), DataKind::Octets)),
            ]
        );
        assert_eq!(items[3].unwrap().data_length(), 6);
    }

    #[test]
    fn items_a_cpu_refuses_get_their_return_codes() {
        let items = read_items(&[
            item(transport::BYTE, 1, 0, 0x87, 0),
            item(transport::BYTE, 1, 0, area_code::FLAGS, 3),
            item(transport::BIT, 2, 0, area_code::FLAGS, 0),
            item(transport::BYTE, 0, 0, area_code::FLAGS, 0),
            item(transport::BYTE, 1, 0, area_code::TIMERS, 0),
            item(transport::TIMER, 1, 0, area_code::COUNTERS, 0),
            item(0x13, 1, 0, area_code::FLAGS, 0),
            vec![0x12, 0x02, 0xB0, 0x01],
        ]);
        let codes: Vec<_> = items.iter().map(|item| item.unwrap_err()).collect();
        assert_eq!(codes, [0x0A, 0x05, 0x05, 0x05, 0x06, 0x06, 0x06, 0x06]);
    }

    #[test]
    fn write_items_carry_their_data_with_fill_bytes_between() {
        let mut parameters = vec![WRITE_VAR, 3];
        parameters.extend(item(transport::BYTE, 3, 1, area_code::DATA_BLOCK, 0));
        parameters.extend(item(transport::BIT, 1, 0, area_code::OUTPUTS, 9));
        parameters.extend(item(transport::WORD, 1, 0, area_code::FLAGS, 16));
        let data = [
            0, 0x04, 0, 24, 1, 2, 3, 0, // three bytes and a fill byte
            0, 0x03, 0, 1, 1, 0, // one bit and a fill byte
            0, 0x04, 0, 16, 0xAB, 0xCD,
        ];
        let pdu = job(9, &parameters, &data);
        let Ok(Pdu {
            message: Message::Write(items),
            ..
        }) = decode(&pdu)
        else {
            panic!("no write job");
        };
        let written: Vec<_> = items
            .iter()
            .map(|item| item.map(|(address, bytes)| (address.target, bytes.to_vec())))
            .collect();
        assert_eq!(
            written,
            vec![
                Ok((range(Area::DataBlock(1), 0, 3), vec![1, 2, 3])),
                Ok((
                    Target::Bit {
                        area: Area::Outputs,
                        byte: 1,
                        bit: 1
                    },
                    vec![1]
                )),
                Ok((range(Area::Flags, 2, 2), vec![0xAB, 0xCD])),
            ]
        );
    }

    #[test]
    fn write_data_of_the_wrong_length_is_inconsistent() {
        let mut parameters = vec![WRITE_VAR, 1];
        parameters.extend(item(transport::WORD, 2, 0, area_code::FLAGS, 0));
        let pdu = job(9, &parameters, &[0, 0x04, 0, 16, 1, 2]);
        assert!(matches!(
            decode(&pdu),
            Ok(Pdu { message: Message::Write(items), .. }) if items == [Err(0x07)]
        ));
    }

    #[test]
    fn control_jobs_name_their_service_and_argument() {
        let mut stop = vec![PLC_STOP, 0, 0, 0, 0, 0, 9];
        stop.extend_from_slice(b"P_PROGRAM");
        assert!(matches!(
            decode(&job(2, &stop, &[])),
            Ok(Pdu {
                message: Message::Control {
                    function: PLC_STOP,
                    service: b"P_PROGRAM",
                    argument: &[]
                },
                ..
            })
        ));
        let mut cold = vec![PI_START, 0, 0, 0, 0, 0, 0, 0xFD, 0, 2, b'C', b' ', 9];
        cold.extend_from_slice(b"P_PROGRAM");
        assert!(matches!(
            decode(&job(3, &cold, &[])),
            Ok(Pdu {
                message: Message::Control {
                    function: PI_START,
                    service: b"P_PROGRAM",
                    argument: b"C "
                },
                ..
            })
        ));
    }

    #[test]
    fn userdata_requests_name_group_subfunction_and_data() {
        let mut pdu = vec![0x32, USERDATA, 0, 0, 0, 5, 0, 8, 0, 8];
        pdu.extend_from_slice(&[0, 1, 0x12, 4, 0x11, 0x44, 0x01, 0]);
        pdu.extend_from_slice(&[0xFF, 0x09, 0, 4, 0x04, 0x24, 0, 0]);
        assert_eq!(
            decode(&pdu),
            Ok(Pdu {
                reference: 5,
                message: Message::Userdata(Userdata {
                    group: 4,
                    subfunction: 1,
                    sequence: 0,
                    follow_up: false,
                    data: &[0x04, 0x24, 0, 0]
                })
            })
        );
    }

    #[test]
    fn malformed_and_unknown_pdus_are_told_apart() {
        assert_eq!(decode(&[0x32, 1, 0]), Err(BadPdu::NotS7));
        assert_eq!(decode(&[0x33; 12]), Err(BadPdu::NotS7));
        // The lengths promise more than there is.
        let mut short = job(4, &[READ_VAR, 1], &[]);
        short[7] = 40;
        assert_eq!(
            decode(&short),
            Err(BadPdu::Malformed {
                reference: 4,
                function: READ_VAR
            })
        );
        // An item count larger than the items there are.
        assert_eq!(
            decode(&job(4, &[READ_VAR, 200], &[])),
            Err(BadPdu::Malformed {
                reference: 4,
                function: READ_VAR
            })
        );
        // python-snap7's get_cpu_state: a read job of the function code alone.
        assert_eq!(
            decode(&job(4, &[READ_VAR], &[])),
            Err(BadPdu::Malformed {
                reference: 4,
                function: READ_VAR
            })
        );
        assert_eq!(
            decode(&job(4, &[0x1A, 0, 0], &[])),
            Err(BadPdu::Unsupported {
                reference: 4,
                function: 0x1A
            })
        );
        let mut ack = job(4, &[READ_VAR, 0], &[]);
        ack[1] = 3;
        assert_eq!(
            decode(&ack),
            Err(BadPdu::Unsupported {
                reference: 4,
                function: READ_VAR
            })
        );
    }
}
