//! ISO-on-TCP framing (RFC 1006): each packet is a TPKT (version 3, a reserved byte, the
//! packet's length including these four bytes) carrying one COTP TPDU (ISO 8073 class 0): a
//! connection request or confirm, a data TPDU, a disconnect request.

use std::time::Duration;

use tokio::io::{AsyncRead, AsyncReadExt};

/// The TPKT header's length.
pub const TPKT_HEADER: usize = 4;
/// The COTP data TPDU's header: length indicator 2, code 0xF0, end-of-TSDU bit and number.
pub const DATA_HEADER: usize = 3;

const TPKT_VERSION: u8 = 3;
const CONNECTION_REQUEST: u8 = 0xE0;
const CONNECTION_CONFIRM: u8 = 0xD0;
const DISCONNECT_REQUEST: u8 = 0x80;
const DATA: u8 = 0xF0;
const END_OF_TSDU: u8 = 0x80;
/// The connection parameters S7 clients send: the TPDU size (as a power of two) and the
/// calling and called TSAPs (whose bytes name the rack and slot; any are accepted).
const PARAMETER_TPDU_SIZE: u8 = 0xC0;
const PARAMETER_CALLING_TSAP: u8 = 0xC1;
const PARAMETER_CALLED_TSAP: u8 = 0xC2;
/// The largest TPDU awl confirms: 2^10 = 1024 bytes, room for its largest S7 PDU (960 bytes).
pub const LARGEST_TPDU_SIZE_CODE: u8 = 0x0A;
/// The smallest TPDU size class 0 knows: 2^7 = 128 bytes.
const SMALLEST_TPDU_SIZE_CODE: u8 = 0x07;

/// One TPDU, decoded from a TPKT's payload.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Tpdu<'a> {
    ConnectionRequest(ConnectionRequest),
    /// A piece of an S7 PDU; `last` when it ends the PDU.
    Data {
        last: bool,
        payload: &'a [u8],
    },
    DisconnectRequest,
}

/// What a connection request asks for, as far as the confirm echoes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConnectionRequest {
    pub source_reference: u16,
    /// The TPDU size code the client proposes (bytes = 2^code), if it names one.
    pub tpdu_size_code: Option<u8>,
    /// The calling and called TSAP parameters, echoed in the confirm as a CPU does.
    pub tsaps: Vec<(u8, Vec<u8>)>,
}

/// Why bytes are no TPDU awl serves: the connection is closed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BadTpdu {
    Truncated,
    /// A TPDU code awl does not serve (expedited data, an error TPDU, …).
    Unsupported(u8),
}

pub fn decode(bytes: &[u8]) -> Result<Tpdu<'_>, BadTpdu> {
    let (&length_indicator, rest) = bytes.split_first().ok_or(BadTpdu::Truncated)?;
    let header = rest
        .get(..usize::from(length_indicator))
        .ok_or(BadTpdu::Truncated)?;
    let &code = header.first().ok_or(BadTpdu::Truncated)?;
    match code & 0xF0 {
        CONNECTION_REQUEST => decode_connection_request(header).map(Tpdu::ConnectionRequest),
        DATA => {
            let &number = header.get(1).ok_or(BadTpdu::Truncated)?;
            Ok(Tpdu::Data {
                last: number & END_OF_TSDU != 0,
                payload: &rest[header.len()..],
            })
        }
        DISCONNECT_REQUEST => Ok(Tpdu::DisconnectRequest),
        _ => Err(BadTpdu::Unsupported(code)),
    }
}

/// `header`: the TPDU's header after its length indicator: code, destination reference,
/// source reference, class, then the variable part's parameters (code, length, value).
fn decode_connection_request(header: &[u8]) -> Result<ConnectionRequest, BadTpdu> {
    let fixed = header.get(..6).ok_or(BadTpdu::Truncated)?;
    let source_reference = u16::from_be_bytes([fixed[3], fixed[4]]);
    let mut request = ConnectionRequest {
        source_reference,
        tpdu_size_code: None,
        tsaps: Vec::new(),
    };
    let mut parameters = &header[6..];
    while let [code, length, rest @ ..] = parameters {
        let value = rest.get(..usize::from(*length)).ok_or(BadTpdu::Truncated)?;
        match *code {
            PARAMETER_TPDU_SIZE => request.tpdu_size_code = value.first().copied(),
            PARAMETER_CALLING_TSAP | PARAMETER_CALLED_TSAP => {
                request.tsaps.push((*code, value.to_vec()))
            }
            _ => {}
        }
        parameters = &rest[value.len()..];
    }
    if parameters.is_empty() {
        Ok(request)
    } else {
        Err(BadTpdu::Truncated)
    }
}

/// The TPDU size code the confirm grants: the client's, within class 0's sizes and awl's
/// largest.
pub fn granted_tpdu_size_code(request: &ConnectionRequest) -> u8 {
    request
        .tpdu_size_code
        .unwrap_or(LARGEST_TPDU_SIZE_CODE)
        .clamp(SMALLEST_TPDU_SIZE_CODE, LARGEST_TPDU_SIZE_CODE)
}

/// The connection confirm packet (TPKT included) answering `request`.
pub fn connection_confirm(request: &ConnectionRequest, tpdu_size_code: u8) -> Vec<u8> {
    let mut header = vec![CONNECTION_CONFIRM];
    header.extend_from_slice(&request.source_reference.to_be_bytes());
    // The CPU's own reference for this connection; clients only echo it.
    header.extend_from_slice(&1u16.to_be_bytes());
    header.push(0); // class 0
    header.extend_from_slice(&[PARAMETER_TPDU_SIZE, 1, tpdu_size_code]);
    for (code, value) in &request.tsaps {
        header.push(*code);
        header.push(value.len() as u8);
        header.extend_from_slice(value);
    }
    let mut tpdu = vec![header.len() as u8];
    tpdu.extend_from_slice(&header);
    tpkt(&tpdu)
}

/// The data packets (TPKT included) carrying `pdu`, cut to the granted TPDU size.
pub fn data_packets(pdu: &[u8], tpdu_size_code: u8) -> Vec<u8> {
    let room = (1usize << tpdu_size_code) - DATA_HEADER;
    let pieces = pdu.chunks(room.max(1)).collect::<Vec<_>>();
    let mut packets = Vec::with_capacity(pdu.len() + pieces.len() * (TPKT_HEADER + DATA_HEADER));
    for (index, piece) in pieces.iter().enumerate() {
        let last = index + 1 == pieces.len();
        let mut tpdu = vec![2, DATA, if last { END_OF_TSDU } else { 0 }];
        tpdu.extend_from_slice(piece);
        packets.extend_from_slice(&tpkt(&tpdu));
    }
    if pieces.is_empty() {
        packets.extend_from_slice(&tpkt(&[2, DATA, END_OF_TSDU]));
    }
    packets
}

fn tpkt(payload: &[u8]) -> Vec<u8> {
    let length = (payload.len() + TPKT_HEADER) as u16;
    let mut packet = vec![TPKT_VERSION, 0];
    packet.extend_from_slice(&length.to_be_bytes());
    packet.extend_from_slice(payload);
    packet
}

/// A TPKT packet as read from the stream.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Packet {
    /// The payload after the TPKT header.
    Whole(Vec<u8>),
    /// A packet longer than awl reads: its first bytes (enough for the COTP and S7 headers);
    /// the rest was read and dropped.
    Oversized(Vec<u8>),
}

/// How reading a packet ended without one.
#[derive(Debug)]
pub enum ReadError {
    /// The client sent nothing for the idle time, or left a packet unfinished.
    TimedOut,
    /// The client closed the connection (or it broke) between or inside packets.
    Closed,
    /// The bytes are no TPKT: the stream cannot be resynchronised.
    NotTpkt,
}

/// How much of an oversized packet is kept: the COTP data header and the S7 header.
const OVERSIZED_HEAD: usize = DATA_HEADER + 12;

/// Reads one TPKT packet: waits at most `idle` for its first byte, then at most `within` for
/// the rest. A payload over `largest` bytes is read and dropped, never allocated.
pub async fn read_packet<S: AsyncRead + Unpin>(
    stream: &mut S,
    largest: usize,
    idle: Duration,
    within: Duration,
) -> Result<Packet, ReadError> {
    let mut header = [0u8; TPKT_HEADER];
    let first = tokio::time::timeout(idle, stream.read(&mut header[..1]))
        .await
        .map_err(|_| ReadError::TimedOut)?;
    if !matches!(first, Ok(1)) {
        return Err(ReadError::Closed);
    }
    tokio::time::timeout(within, read_rest(stream, header, largest))
        .await
        .map_err(|_| ReadError::TimedOut)?
}

async fn read_rest<S: AsyncRead + Unpin>(
    stream: &mut S,
    mut header: [u8; TPKT_HEADER],
    largest: usize,
) -> Result<Packet, ReadError> {
    stream
        .read_exact(&mut header[1..])
        .await
        .map_err(|_| ReadError::Closed)?;
    if header[0] != TPKT_VERSION {
        return Err(ReadError::NotTpkt);
    }
    let length = usize::from(u16::from_be_bytes([header[2], header[3]]));
    let payload_length = length
        .checked_sub(TPKT_HEADER)
        .filter(|&payload| payload > 0)
        .ok_or(ReadError::NotTpkt)?;
    if payload_length <= largest {
        let mut payload = vec![0; payload_length];
        stream
            .read_exact(&mut payload)
            .await
            .map_err(|_| ReadError::Closed)?;
        return Ok(Packet::Whole(payload));
    }
    let mut head = vec![0; OVERSIZED_HEAD.min(payload_length)];
    stream
        .read_exact(&mut head)
        .await
        .map_err(|_| ReadError::Closed)?;
    let rest = (payload_length - head.len()) as u64;
    let dropped = tokio::io::copy(&mut stream.take(rest), &mut tokio::io::sink())
        .await
        .map_err(|_| ReadError::Closed)?;
    if dropped < rest {
        return Err(ReadError::Closed);
    }
    Ok(Packet::Oversized(head))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// python-snap7's connection request for rack 0, slot 2: calling TSAP 0x0100, called TSAP
    /// 0x0102, TPDU size 1024.
    const REQUEST: [u8; 18] = [
        17, 0xE0, 0, 0, 0, 1, 0, 0xC1, 2, 1, 0, 0xC2, 2, 1, 2, 0xC0, 1, 0x0A,
    ];

    #[test]
    fn a_connection_request_names_its_reference_tsaps_and_tpdu_size() {
        let Ok(Tpdu::ConnectionRequest(request)) = decode(&REQUEST) else {
            panic!("no connection request");
        };
        assert_eq!(request.source_reference, 1);
        assert_eq!(request.tpdu_size_code, Some(0x0A));
        assert_eq!(request.tsaps, vec![(0xC1, vec![1, 0]), (0xC2, vec![1, 2])]);
    }

    #[test]
    fn the_confirm_echoes_the_reference_and_tsaps_and_grants_at_most_1024_bytes() {
        let Ok(Tpdu::ConnectionRequest(mut request)) = decode(&REQUEST) else {
            panic!("no connection request");
        };
        request.tpdu_size_code = Some(0x0D);
        let granted = granted_tpdu_size_code(&request);
        assert_eq!(granted, 0x0A);
        assert_eq!(
            connection_confirm(&request, granted),
            [
                3, 0, 0, 22, 17, 0xD0, 0, 1, 0, 1, 0, 0xC0, 1, 0x0A, 0xC1, 2, 1, 0, 0xC2, 2, 1, 2
            ]
        );
    }

    #[test]
    fn truncated_or_foreign_tpdus_are_refused() {
        assert_eq!(decode(&[]), Err(BadTpdu::Truncated));
        assert_eq!(decode(&[6, 0xE0, 0, 0]), Err(BadTpdu::Truncated));
        // A parameter whose length runs past the header.
        assert_eq!(
            decode(&[8, 0xE0, 0, 0, 0, 1, 0, 0xC1, 4]),
            Err(BadTpdu::Truncated)
        );
        assert_eq!(decode(&[2, 0x10, 0x80]), Err(BadTpdu::Unsupported(0x10)));
    }

    #[test]
    fn data_tpdus_carry_their_payload_and_end_mark() {
        assert_eq!(
            decode(&[2, 0xF0, 0x80, 0x32, 1]),
            Ok(Tpdu::Data {
                last: true,
                payload: &[0x32, 1]
            })
        );
        assert_eq!(
            decode(&[2, 0xF0, 0x00]),
            Ok(Tpdu::Data {
                last: false,
                payload: &[]
            })
        );
        assert_eq!(
            decode(&[6, 0x80, 0, 1, 0, 1, 0]),
            Ok(Tpdu::DisconnectRequest)
        );
    }

    #[test]
    fn a_pdu_longer_than_the_tpdu_goes_in_pieces_the_last_one_marked() {
        let pdu = [7u8; 130];
        let packets = data_packets(&pdu, 0x07);
        // 125 bytes fit a 128-byte TPDU after its 3-byte header.
        assert_eq!(&packets[..7], &[3, 0, 0, 132, 2, 0xF0, 0x00]);
        assert_eq!(&packets[132..139], &[3, 0, 0, 12, 2, 0xF0, 0x80]);
        assert_eq!(packets.len(), 132 + 12);
    }

    fn read(bytes: &[u8], largest: usize) -> Result<Packet, ReadError> {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_time()
            .build()
            .unwrap();
        let mut stream = bytes;
        let second = Duration::from_secs(1);
        runtime.block_on(read_packet(&mut stream, largest, second, second))
    }

    #[test]
    fn packets_are_read_whole_or_dropped_when_longer_than_allowed() {
        assert!(matches!(
            read(&[3, 0, 0, 7, 2, 0xF0, 0x80], 100),
            Ok(Packet::Whole(payload)) if payload == [2, 0xF0, 0x80]
        ));
        let mut huge = vec![3, 0, 0xFF, 0xFF];
        huge.resize(0xFFFF, 0x32);
        assert!(matches!(
            read(&huge, 100),
            Ok(Packet::Oversized(head)) if head.len() == OVERSIZED_HEAD
        ));
        // A length that promises more than the client sends.
        assert!(matches!(
            read(&[3, 0, 0xFF, 0xFF, 1], 100),
            Err(ReadError::Closed)
        ));
        assert!(matches!(read(&[4, 0, 0, 7], 100), Err(ReadError::NotTpkt)));
        assert!(matches!(read(&[3, 0, 0, 4], 100), Err(ReadError::NotTpkt)));
        assert!(matches!(read(&[], 100), Err(ReadError::Closed)));
    }
}
