//! One client's connection: the COTP handshake, then S7 requests one after the other, each
//! turned into requests to the CPU and answered from what the CPU gives back.

use tokio::io::{AsyncRead, AsyncWrite, AsyncWriteExt};
use tokio::sync::oneshot;

use super::Settings;
use super::decode::{self, BadPdu, Message, Pdu, Target, Userdata, return_code};
use super::encode::{self, ReadReply, UserdataAnswer, error};
use super::frame::{self, Packet, Tpdu};
use super::szl;
use crate::serve::request::{
    Client, Control, ControlError, CpuStatus, Item, ItemError, ItemResult, Request, Requests,
};

/// The PDU length a client gets at most, and before it negotiates one; and at least (what an
/// S7-300 has), so that every answer awl gives fits.
const LARGEST_PDU: u16 = 960;
const SMALLEST_PDU: u16 = 240;
/// The parallel jobs a client may have open: awl answers them in order.
const MOST_PARALLEL_JOBS: u16 = 8;
const PROGRAM_SERVICE: &[u8] = b"P_PROGRAM";
/// A cold restart's argument to the program service (a warm restart has none).
const COLD_ARGUMENT: &[u8] = b"C ";
const SZL_GROUP: u8 = 0x04;
const READ_SZL: u8 = 0x01;
const CLOCK_GROUP: u8 = 0x07;
const READ_CLOCK: u8 = 0x01;

/// The connection ends: the client left, broke the protocol, or the CPU is gone.
struct Closed;

type Served = Result<(), Closed>;

/// The rest of an SZL answer longer than one PDU, sent on the client's follow-up requests.
struct PendingAnswer {
    sequence: u8,
    rest: Vec<u8>,
}

struct Connection<S> {
    stream: S,
    client: Client,
    requests: Requests,
    settings: Settings,
    tpdu_size_code: u8,
    pdu_length: u16,
    /// The S7 PDU being assembled from data TPDUs, and whether it grew past the PDU length.
    message: Vec<u8>,
    overflowed: bool,
    pending: Option<PendingAnswer>,
    last_sequence: u8,
}

/// Serves one connection until the client leaves, breaks the protocol or times out.
pub(super) async fn serve<S: AsyncRead + AsyncWrite + Unpin>(
    stream: S,
    client: Client,
    requests: Requests,
    settings: Settings,
) {
    let mut connection: Connection<tokio::io::BufReader<S>> = Connection {
        // A packet is read in parts (its first byte, its header, its payload): buffered, that
        // is one receive from the socket.
        stream: tokio::io::BufReader::new(stream),
        client,
        requests,
        settings,
        tpdu_size_code: frame::LARGEST_TPDU_SIZE_CODE,
        pdu_length: SMALLEST_PDU,
        message: Vec::new(),
        overflowed: false,
        pending: None,
        last_sequence: 0,
    };
    if connection.handshake().await.is_ok() {
        while connection.serve_packet().await.is_ok() {}
    }
}

impl<S: AsyncRead + AsyncWrite + Unpin> Connection<S> {
    async fn read_packet(&mut self) -> Result<Packet, Closed> {
        let largest = 1usize << self.tpdu_size_code;
        frame::read_packet(
            &mut self.stream,
            largest,
            self.settings.idle_timeout,
            self.settings.packet_timeout,
        )
        .await
        .map_err(|_| Closed)
    }

    async fn write(&mut self, bytes: &[u8]) -> Served {
        let written =
            tokio::time::timeout(self.settings.packet_timeout, self.stream.write_all(bytes)).await;
        match written {
            Ok(Ok(())) => Ok(()),
            _ => Err(Closed),
        }
    }

    async fn answer(&mut self, pdu: &[u8]) -> Served {
        let packets = frame::data_packets(pdu, self.tpdu_size_code);
        self.write(&packets).await
    }

    /// The client's connection request (any TSAPs: any rack and slot), confirmed.
    async fn handshake(&mut self) -> Served {
        let Packet::Whole(payload) = self.read_packet().await? else {
            return Err(Closed);
        };
        let Ok(Tpdu::ConnectionRequest(request)) = frame::decode(&payload) else {
            return Err(Closed);
        };
        self.tpdu_size_code = frame::granted_tpdu_size_code(&request);
        let confirm = frame::connection_confirm(&request, self.tpdu_size_code);
        self.write(&confirm).await
    }

    async fn serve_packet(&mut self) -> Served {
        match self.read_packet().await? {
            Packet::Oversized(head) => {
                self.message.clear();
                self.overflowed = false;
                match frame::decode(&head) {
                    Ok(Tpdu::Data { payload, .. }) => self.refuse_unread(payload).await,
                    _ => Err(Closed),
                }
            }
            Packet::Whole(payload) => match frame::decode(&payload).map_err(|_| Closed)? {
                Tpdu::Data { last, payload } => {
                    self.gather(payload);
                    if last {
                        self.serve_message().await
                    } else {
                        Ok(())
                    }
                }
                Tpdu::ConnectionRequest(_) | Tpdu::DisconnectRequest => Err(Closed),
            },
        }
    }

    /// Adds a piece of the S7 PDU; past the PDU length only its start (which holds the
    /// reference the refusal echoes) is kept.
    fn gather(&mut self, piece: &[u8]) {
        if self.message.len() + piece.len() > usize::from(self.pdu_length) {
            self.overflowed = true;
        }
        let room = if self.overflowed {
            HEAD_KEPT.saturating_sub(self.message.len())
        } else {
            piece.len()
        };
        self.message
            .extend_from_slice(&piece[..room.min(piece.len())]);
    }

    async fn serve_message(&mut self) -> Served {
        let message = std::mem::take(&mut self.message);
        if std::mem::take(&mut self.overflowed) {
            return self.refuse_unread(&message).await;
        }
        match decode::decode(&message) {
            Ok(pdu) => self.serve_pdu(pdu).await,
            Err(BadPdu::NotS7) => Err(Closed),
            Err(BadPdu::Malformed {
                reference,
                function,
            }) => {
                self.answer(&encode::refusal(reference, function, error::WRONG_FRAMES))
                    .await
            }
            Err(BadPdu::Unsupported {
                reference,
                function,
            }) => {
                let refusal = encode::refusal(reference, function, error::NOT_IMPLEMENTED);
                self.answer(&refusal).await
            }
        }
    }

    /// Refuses a request longer than the PDU length from its first bytes.
    async fn refuse_unread(&mut self, head: &[u8]) -> Served {
        match head {
            [
                decode::PROTOCOL_ID,
                _,
                _,
                _,
                high,
                low,
                _,
                _,
                _,
                _,
                function,
                ..,
            ] => {
                let reference = u16::from_be_bytes([*high, *low]);
                let refusal = encode::refusal(reference, *function, error::WRONG_FRAMES);
                self.answer(&refusal).await
            }
            _ => Err(Closed),
        }
    }

    async fn serve_pdu(&mut self, pdu: Pdu<'_>) -> Served {
        let reference = pdu.reference;
        let answer = match pdu.message {
            Message::Setup {
                max_amq_calling,
                max_amq_called,
                pdu_length,
            } => {
                self.pdu_length = pdu_length.clamp(SMALLEST_PDU, LARGEST_PDU);
                let parallel = |asked: u16| asked.clamp(1, MOST_PARALLEL_JOBS);
                encode::setup(
                    reference,
                    parallel(max_amq_calling),
                    parallel(max_amq_called),
                    self.pdu_length,
                )
            }
            Message::Read(items) => self.read(reference, &items).await?,
            Message::Write(items) => self.write_items(reference, &items).await?,
            Message::Control {
                function,
                service,
                argument,
            } => self.control(reference, function, service, argument).await?,
            Message::Userdata(request) => self.userdata(reference, &request).await?,
        };
        self.answer(&answer).await
    }

    /// Asks the CPU; `Closed` when it is gone.
    async fn ask<T>(
        &self,
        request: impl FnOnce(oneshot::Sender<T>) -> Request,
    ) -> Result<T, Closed> {
        let (reply, answer) = oneshot::channel();
        self.requests.send(request(reply)).map_err(|_| Closed)?;
        answer.await.map_err(|_| Closed)
    }

    async fn access(&self, items: Vec<Item>) -> Result<Vec<ItemResult>, Closed> {
        if items.is_empty() {
            return Ok(Vec::new());
        }
        let client = self.client;
        self.ask(|reply| Request::Access {
            client,
            items,
            reply,
        })
        .await
    }

    async fn read(
        &self,
        reference: u16,
        items: &[Result<decode::Address, u8>],
    ) -> Result<Vec<u8>, Closed> {
        let lengths: Vec<usize> = items
            .iter()
            .map(|item| item.map_or(0, |address| address.data_length()))
            .collect();
        if encode::read_answer_length(&lengths) > usize::from(self.pdu_length) {
            return Ok(encode::refusal(
                reference,
                decode::READ_VAR,
                error::WRONG_FRAMES,
            ));
        }
        let reads = items
            .iter()
            .flatten()
            .map(|address| match address.target {
                Target::Bytes(range) => Item::Read(range),
                Target::Bit { area, byte, bit } => Item::ReadBit { area, byte, bit },
            })
            .collect();
        let mut results = self.access(reads).await?.into_iter();
        let replies: Vec<ReadReply> = items
            .iter()
            .map(|item| {
                let address = (*item)?;
                match results.next() {
                    Some(Ok(bytes)) if bytes.len() == address.data_length() => {
                        Ok((address.kind, bytes))
                    }
                    Some(Err(error)) => Err(item_return_code(error)),
                    _ => Err(return_code::HARDWARE_FAULT),
                }
            })
            .collect();
        Ok(encode::read_answer(reference, &replies))
    }

    async fn write_items(
        &self,
        reference: u16,
        items: &[Result<(decode::Address, &[u8]), u8>],
    ) -> Result<Vec<u8>, Closed> {
        let writes = items
            .iter()
            .flatten()
            .map(|(address, bytes)| match address.target {
                Target::Bytes(range) => Item::Write {
                    range,
                    bytes: bytes.to_vec(),
                },
                Target::Bit { area, byte, bit } => Item::WriteBit {
                    area,
                    byte,
                    bit,
                    value: bytes[0] & 1 == 1,
                },
            })
            .collect();
        let mut results = self.access(writes).await?.into_iter();
        let codes: Vec<u8> = items
            .iter()
            .map(|item| match item {
                Err(code) => *code,
                Ok(_) => match results.next() {
                    Some(Ok(_)) => return_code::SUCCESS,
                    Some(Err(error)) => item_return_code(error),
                    None => return_code::HARDWARE_FAULT,
                },
            })
            .collect();
        Ok(encode::write_answer(reference, &codes))
    }

    async fn control(
        &self,
        reference: u16,
        function: u8,
        service: &[u8],
        argument: &[u8],
    ) -> Result<Vec<u8>, Closed> {
        let command = match (function, service, argument) {
            (decode::PLC_STOP, PROGRAM_SERVICE, _) => Control::Stop,
            (decode::PI_START, PROGRAM_SERVICE, []) => Control::HotStart,
            (decode::PI_START, PROGRAM_SERVICE, COLD_ARGUMENT) => Control::ColdStart,
            _ => {
                return Ok(encode::refusal(reference, function, error::NOT_IMPLEMENTED));
            }
        };
        let client = self.client;
        let outcome = self
            .ask(|reply| Request::Control {
                client,
                command,
                reply,
            })
            .await?;
        let refused = outcome.err().map(|refusal| match refusal {
            ControlError::ReadOnly => (error::PROTECTION_LEVEL, 0),
            ControlError::AlreadyRunning => (error::MODE_ALREADY_SET, encode::ALREADY_RUNNING),
        });
        Ok(encode::control_answer(reference, function, refused))
    }

    async fn status(&self) -> Result<CpuStatus, Closed> {
        self.ask(|reply| Request::Status { reply }).await
    }

    async fn userdata(
        &mut self,
        reference: u16,
        request: &Userdata<'_>,
    ) -> Result<Vec<u8>, Closed> {
        let mut answer = UserdataAnswer {
            reference,
            group: request.group,
            subfunction: request.subfunction,
            sequence: request.sequence,
            more: false,
            result: Err(error::NOT_IMPLEMENTED),
        };
        match (request.group, request.subfunction) {
            (SZL_GROUP, READ_SZL) if request.follow_up => {
                let Some(pending) = self.pending.take_if(|p| p.sequence == request.sequence) else {
                    answer.result = Err(error::NO_SUCH_SZL);
                    return Ok(encode::userdata(&answer));
                };
                Ok(self.szl_piece(answer, pending.rest))
            }
            (SZL_GROUP, READ_SZL) => {
                let list = match request.data {
                    &[id_high, id_low, index_high, index_low] => {
                        let status = self.status().await?;
                        let id = u16::from_be_bytes([id_high, id_low]);
                        let index = u16::from_be_bytes([index_high, index_low]);
                        szl::partial_list(id, index, &status, self.communication())
                    }
                    _ => None,
                };
                match list {
                    Some(list) => Ok(self.szl_piece(answer, list)),
                    None => {
                        answer.result = Err(error::NO_SUCH_SZL);
                        Ok(encode::userdata(&answer))
                    }
                }
            }
            (CLOCK_GROUP, READ_CLOCK) => {
                let clock = szl::clock(&self.status().await?);
                answer.result = Ok(&clock);
                Ok(encode::userdata(&answer))
            }
            // Setting the clock among them: the CPU's clock is the simulation's.
            _ => Ok(encode::userdata(&answer)),
        }
    }

    /// What SZL 0x0131 reports of the server: the longest PDU a client may negotiate and the
    /// connections served at once.
    fn communication(&self) -> szl::Communication {
        szl::Communication {
            largest_pdu: LARGEST_PDU,
            max_connections: u16::try_from(self.settings.max_connections).unwrap_or(u16::MAX),
        }
    }

    /// As much of an SZL answer as one PDU holds; the rest waits for the follow-up request.
    fn szl_piece(&mut self, answer: UserdataAnswer<'_>, mut list: Vec<u8>) -> Vec<u8> {
        let room = usize::from(self.pdu_length) - encode::USERDATA_OVERHEAD;
        let mut sequence = answer.sequence;
        let more = list.len() > room;
        if more {
            let rest = list.split_off(room);
            self.last_sequence = self.last_sequence.wrapping_add(1).max(1);
            sequence = self.last_sequence;
            self.pending = Some(PendingAnswer { sequence, rest });
        }
        encode::userdata(&UserdataAnswer {
            sequence,
            more,
            result: Ok(&list),
            ..answer
        })
    }
}

/// How much of a request longer than the PDU length is kept to refuse it: the S7 header and
/// the function code.
const HEAD_KEPT: usize = 11;

/// A real CPU's return code for an item the CPU refused.
fn item_return_code(error: ItemError) -> u8 {
    match error {
        ItemError::NoSuchBlock => return_code::OBJECT_DOES_NOT_EXIST,
        ItemError::OutOfRange => return_code::INVALID_ADDRESS,
        ItemError::ReadOnly => return_code::ACCESS_DENIED,
        ItemError::NotSupported => return_code::TYPE_NOT_SUPPORTED,
    }
}
