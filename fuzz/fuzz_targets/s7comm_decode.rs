//! Any bytes as what an S7comm client sends: as a TPDU (the payload of a TPKT packet) and as
//! an S7 PDU. The decoders never panic; what decodes is answered by the encoders, and every
//! answer holds what its headers say: a confirm's TPKT length, a PDU cut into data TPDUs
//! that join back whole, a read answer as long as the server reckons before asking the CPU,
//! write data as long as its item's address says.
#![no_main]

use awl::serve::s7comm::decode::{self, BadPdu, Message};
use awl::serve::s7comm::encode::{self, ReadReply, UserdataAnswer};
use awl::serve::s7comm::frame::{self, Tpdu};
use libfuzzer_sys::fuzz_target;

/// The largest PDU the server grants: larger read answers are refused before the CPU is asked.
const LARGEST_PDU: usize = 960;

fuzz_target!(|bytes: &[u8]| {
    let bytes = awl_fuzz::bounded(bytes);
    check_tpdu(bytes);
    check_pdu(bytes);
});

fn check_tpdu(bytes: &[u8]) {
    match frame::decode(bytes) {
        Ok(Tpdu::ConnectionRequest(request)) => {
            let granted = frame::granted_tpdu_size_code(&request);
            assert!((7..=frame::LARGEST_TPDU_SIZE_CODE).contains(&granted));
            let confirm = frame::connection_confirm(&request, granted);
            assert_eq!(
                usize::from(u16::from_be_bytes([confirm[2], confirm[3]])),
                confirm.len()
            );
            assert_eq!(usize::from(confirm[4]) + 5, confirm.len());
        }
        Ok(Tpdu::Data { payload, .. }) => {
            let size_code = 7 + bytes[0] % 4;
            let packets = frame::data_packets(payload, size_code);
            assert_eq!(joined(&packets), payload);
        }
        Ok(Tpdu::DisconnectRequest) | Err(_) => {}
    }
}

/// The S7 PDU data packets carry, joined.
fn joined(mut packets: &[u8]) -> Vec<u8> {
    let mut pdu = Vec::new();
    while !packets.is_empty() {
        let length = usize::from(u16::from_be_bytes([packets[2], packets[3]]));
        let Ok(Tpdu::Data { last, payload }) = frame::decode(&packets[frame::TPKT_HEADER..length])
        else {
            panic!("a data packet that does not decode");
        };
        pdu.extend_from_slice(payload);
        packets = &packets[length..];
        assert_eq!(last, packets.is_empty());
    }
    pdu
}

fn check_pdu(bytes: &[u8]) {
    let answer = match decode::decode(bytes) {
        Ok(pdu) => answer(pdu.reference, pdu.message),
        Err(BadPdu::NotS7) => return,
        Err(BadPdu::Malformed {
            reference,
            function,
        })
        | Err(BadPdu::Unsupported {
            reference,
            function,
        }) => encode::refusal(reference, function, encode::error::WRONG_FRAMES),
    };
    check_lengths(&answer);
}

/// An answer as the server would give it, the CPU serving every item with zeros.
fn answer(reference: u16, message: Message<'_>) -> Vec<u8> {
    match message {
        Message::Setup { pdu_length, .. } => encode::setup(reference, 1, 1, pdu_length),
        Message::Read(items) => {
            let lengths: Vec<usize> = items
                .iter()
                .map(|item| item.map_or(0, |address| address.data_length()))
                .collect();
            let length = encode::read_answer_length(&lengths);
            if length > LARGEST_PDU {
                return encode::refusal(reference, decode::READ_VAR, encode::error::WRONG_FRAMES);
            }
            let replies: Vec<ReadReply> = items
                .iter()
                .map(|item| item.map(|address| (address.kind, vec![0; address.data_length()])))
                .collect();
            let answer = encode::read_answer(reference, &replies);
            assert_eq!(answer.len(), length);
            answer
        }
        Message::Write(items) => {
            for (address, bytes) in items.iter().flatten() {
                assert_eq!(bytes.len(), address.data_length());
            }
            let codes: Vec<u8> = items
                .iter()
                .map(|item| item.map_or_else(|code| code, |_| decode::return_code::SUCCESS))
                .collect();
            encode::write_answer(reference, &codes)
        }
        Message::Control { function, .. } => encode::control_answer(reference, function, None),
        Message::Userdata(request) => encode::userdata(&UserdataAnswer {
            reference,
            group: request.group,
            subfunction: request.subfunction,
            sequence: request.sequence,
            more: false,
            result: Ok(request.data),
        }),
    }
}

/// An answer's header names the lengths of the sections after it.
fn check_lengths(answer: &[u8]) {
    let header = if answer[1] == 0x07 { 10 } else { 12 };
    let parameters = usize::from(u16::from_be_bytes([answer[6], answer[7]]));
    let data = usize::from(u16::from_be_bytes([answer[8], answer[9]]));
    assert_eq!(header + parameters + data, answer.len());
}
