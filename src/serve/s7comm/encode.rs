//! The S7 PDUs awl answers with: acknowledgements with data (PDU type 3: a 12-byte header
//! whose last two bytes are the error class and code) and userdata answers (PDU type 7: a
//! 10-byte header, the error in the parameters).

use super::decode::{DataKind, PROTOCOL_ID, return_code};

const ACK_DATA: u8 = 0x03;
const USERDATA: u8 = 0x07;

/// Header errors (class and code), as S7 clients name them.
pub mod error {
    /// "S7 protocol error: wrong frames": a request awl cannot read, or whose answer would not
    /// fit the negotiated PDU.
    pub const WRONG_FRAMES: u16 = 0x8500;
    /// "This service is not implemented on the module".
    pub const NOT_IMPLEMENTED: u16 = 0x8104;
    /// "Operating mode already set": a start while the CPU runs.
    pub const MODE_ALREADY_SET: u16 = 0xD0AD;
    /// "The function is not permitted in the current protection level": a control command
    /// or clock setting the server refuses.
    pub const PROTECTION_LEVEL: u16 = 0xD241;
    /// "Information function unavailable": an SZL awl does not have.
    pub const NO_SUCH_SZL: u16 = 0xD402;
}

/// The error parameter of a refused start: the CPU already runs.
pub const ALREADY_RUNNING: u8 = 0x03;

/// An acknowledgement with data: `error` in the header, then the sections.
pub fn ack_data(reference: u16, error: u16, parameters: &[u8], data: &[u8]) -> Vec<u8> {
    let mut pdu = Vec::with_capacity(12 + parameters.len() + data.len());
    pdu.extend_from_slice(&[PROTOCOL_ID, ACK_DATA, 0, 0]);
    pdu.extend_from_slice(&reference.to_be_bytes());
    pdu.extend_from_slice(&(parameters.len() as u16).to_be_bytes());
    pdu.extend_from_slice(&(data.len() as u16).to_be_bytes());
    pdu.extend_from_slice(&error.to_be_bytes());
    pdu.extend_from_slice(parameters);
    pdu.extend_from_slice(data);
    pdu
}

/// A refused job: the header's error and the function echoed with no items.
pub fn refusal(reference: u16, function: u8, error: u16) -> Vec<u8> {
    ack_data(reference, error, &[function, 0], &[])
}

/// The answer to setup communication: the parallel jobs granted and the PDU length.
pub fn setup(reference: u16, max_amq_calling: u16, max_amq_called: u16, pdu: u16) -> Vec<u8> {
    let mut parameters = vec![super::decode::SETUP_COMMUNICATION, 0];
    parameters.extend_from_slice(&max_amq_calling.to_be_bytes());
    parameters.extend_from_slice(&max_amq_called.to_be_bytes());
    parameters.extend_from_slice(&pdu.to_be_bytes());
    ack_data(reference, 0, &parameters, &[])
}

/// What one read item gave: its data and how it travels, or its return code.
pub type ReadReply = Result<(DataKind, Vec<u8>), u8>;

/// The bytes a read answer takes: header, parameters, then per item four bytes, its data and a
/// fill byte after an odd length unless it is the last item.
pub fn read_answer_length(data_lengths: &[usize]) -> usize {
    let items: usize = data_lengths
        .iter()
        .enumerate()
        .map(|(index, &length)| {
            4 + length + usize::from(length % 2 == 1 && index + 1 < data_lengths.len())
        })
        .sum();
    12 + 2 + items
}

/// The answer to a read job.
pub fn read_answer(reference: u16, replies: &[ReadReply]) -> Vec<u8> {
    let mut data = Vec::new();
    for (index, reply) in replies.iter().enumerate() {
        match reply {
            Ok((kind, bytes)) => {
                data.extend_from_slice(&[return_code::SUCCESS, kind.transport_size()]);
                data.extend_from_slice(&kind.length_field(bytes.len()).to_be_bytes());
                data.extend_from_slice(bytes);
                if bytes.len() % 2 == 1 && index + 1 < replies.len() {
                    data.push(0);
                }
            }
            Err(code) => data.extend_from_slice(&[*code, 0, 0, 0]),
        }
    }
    let parameters = [super::decode::READ_VAR, replies.len() as u8];
    ack_data(reference, 0, &parameters, &data)
}

/// The answer to a write job: one return code per item.
pub fn write_answer(reference: u16, codes: &[u8]) -> Vec<u8> {
    let parameters = [super::decode::WRITE_VAR, codes.len() as u8];
    ack_data(reference, 0, &parameters, codes)
}

/// The answer to a control job (stop, start): the function and, when refused, the header's
/// error and the refusal's parameter.
pub fn control_answer(reference: u16, function: u8, refused: Option<(u16, u8)>) -> Vec<u8> {
    match refused {
        None => ack_data(reference, 0, &[function], &[]),
        Some((error, parameter)) => ack_data(reference, error, &[function, parameter], &[]),
    }
}

/// A userdata answer: the group and subfunction echoed, the sequence number a follow-up names,
/// whether more packets follow, the error; then the data (return code 0xFF, octet string) or,
/// on an error, the empty data of return code 0x0A.
pub struct UserdataAnswer<'a> {
    pub reference: u16,
    pub group: u8,
    pub subfunction: u8,
    pub sequence: u8,
    pub more: bool,
    pub result: Result<&'a [u8], u16>,
}

/// The bytes a userdata answer adds to its data: header, parameters, the data's header.
pub const USERDATA_OVERHEAD: usize = 10 + 12 + 4;

pub fn userdata(answer: &UserdataAnswer<'_>) -> Vec<u8> {
    let error = answer.result.err().unwrap_or(0);
    let mut parameters = vec![0x00, 0x01, 0x12, 0x08, 0x12, 0x80 | answer.group];
    parameters.extend_from_slice(&[
        answer.subfunction,
        answer.sequence,
        0,
        u8::from(answer.more),
    ]);
    parameters.extend_from_slice(&error.to_be_bytes());
    let mut data = Vec::new();
    match answer.result {
        Ok(bytes) => {
            data.extend_from_slice(&[return_code::SUCCESS, DataKind::Octets.transport_size()]);
            data.extend_from_slice(&(bytes.len() as u16).to_be_bytes());
            data.extend_from_slice(bytes);
        }
        Err(_) => data.extend_from_slice(&[return_code::OBJECT_DOES_NOT_EXIST, 0, 0, 0]),
    }
    let mut pdu = Vec::with_capacity(10 + parameters.len() + data.len());
    pdu.extend_from_slice(&[PROTOCOL_ID, USERDATA, 0, 0]);
    pdu.extend_from_slice(&answer.reference.to_be_bytes());
    pdu.extend_from_slice(&(parameters.len() as u16).to_be_bytes());
    pdu.extend_from_slice(&(data.len() as u16).to_be_bytes());
    pdu.extend_from_slice(&parameters);
    pdu.extend_from_slice(&data);
    pdu
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn setup_answers_with_the_granted_pdu_length() {
        assert_eq!(
            setup(1, 1, 1, 960),
            [
                0x32, 3, 0, 0, 0, 1, 0, 8, 0, 0, 0, 0, 0xF0, 0, 0, 1, 0, 1, 0x03, 0xC0
            ]
        );
    }

    #[test]
    fn read_answers_give_lengths_in_bits_or_bytes_and_fill_odd_items() {
        let replies = [
            Ok((DataKind::Bytes, vec![1, 2, 3])),
            Err(0x0A),
            Ok((DataKind::Bit, vec![1])),
            Ok((DataKind::Real, vec![0x3F, 0x80, 0, 0])),
        ];
        let answer = read_answer(0x0102, &replies);
        assert_eq!(
            answer,
            [
                0x32, 3, 0, 0, 1, 2, 0, 2, 0, 26, 0, 0, // header
                0x04, 4, // read, four items
                0xFF, 0x04, 0, 24, 1, 2, 3, 0, // three bytes (24 bits), a fill byte
                0x0A, 0, 0, 0, // the DB does not exist
                0xFF, 0x03, 0, 1, 1, 0, // one bit, a fill byte
                0xFF, 0x07, 0, 4, 0x3F, 0x80, 0, 0, // a REAL: its length in bytes
            ]
        );
        assert_eq!(read_answer_length(&[3, 0, 1, 4]), answer.len());
    }

    #[test]
    fn write_and_control_answers() {
        assert_eq!(
            write_answer(9, &[0xFF, 0x03]),
            [0x32, 3, 0, 0, 0, 9, 0, 2, 0, 2, 0, 0, 0x05, 2, 0xFF, 0x03]
        );
        assert_eq!(
            control_answer(4, 0x29, None),
            [0x32, 3, 0, 0, 0, 4, 0, 1, 0, 0, 0, 0, 0x29]
        );
        assert_eq!(
            control_answer(4, 0x28, Some((error::MODE_ALREADY_SET, ALREADY_RUNNING))),
            [0x32, 3, 0, 0, 0, 4, 0, 2, 0, 0, 0xD0, 0xAD, 0x28, 0x03]
        );
        assert_eq!(
            refusal(4, 0x1A, error::NOT_IMPLEMENTED),
            [0x32, 3, 0, 0, 0, 4, 0, 2, 0, 0, 0x81, 0x04, 0x1A, 0]
        );
    }

    #[test]
    fn userdata_answers_carry_data_or_an_error() {
        let answer = UserdataAnswer {
            reference: 3,
            group: 4,
            subfunction: 1,
            sequence: 2,
            more: true,
            result: Ok(&[0xAA, 0xBB]),
        };
        assert_eq!(
            userdata(&answer),
            [
                0x32, 7, 0, 0, 0, 3, 0, 12, 0, 6, // header
                0, 1, 0x12, 8, 0x12, 0x84, 1, 2, 0, 1, 0, 0, // parameters
                0xFF, 0x09, 0, 2, 0xAA, 0xBB
            ]
        );
        let refused = UserdataAnswer {
            result: Err(error::NO_SUCH_SZL),
            more: false,
            ..answer
        };
        assert_eq!(
            userdata(&refused)[10..],
            [
                0, 1, 0x12, 8, 0x12, 0x84, 1, 2, 0, 0, 0xD4, 0x02, 0x0A, 0, 0, 0
            ]
        );
    }
}
