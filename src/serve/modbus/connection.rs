//! One client's connection: frames in, one CPU access per request, responses out, in order.
//! A frame whose header cannot be trusted, a frame that does not arrive whole in time, a client
//! that does not take its response, or an end of the stream closes the connection; the other
//! connections go on.

use std::time::Duration;

use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::oneshot;
use tokio::time::{Instant, timeout, timeout_at};
use tokio_modbus::{ExceptionCode, Request as ModbusRequest, Response};

use super::access;
use super::frame::{self, BadFrame, Header, MAX_FRAME_LENGTH};
use super::map::Map;
use crate::serve::request::{Client, Item, Request, Requests};

/// A request of the buffer's first frame: its header and function code (for the response),
/// its length in the buffer, and the request with its CPU items, or the exception that answers
/// it without the CPU.
#[derive(Debug)]
pub struct Incoming {
    pub header: Header,
    pub function: u8,
    pub length: usize,
    pub request: Result<(ModbusRequest<'static>, Vec<Item>), ExceptionCode>,
}

/// The request at the start of `buffer` (`Ok(None)` until its frame is whole), as the server
/// reads it.
pub fn incoming(buffer: &[u8], map: &Map) -> Result<Option<Incoming>, BadFrame> {
    let Some(frame) = frame::split(buffer)? else {
        return Ok(None);
    };
    let request = frame::decode(frame.pdu).and_then(|request| {
        let items = access::items(&request, map)?;
        Ok((request, items))
    });
    Ok(Some(Incoming {
        header: frame.header,
        function: frame.pdu[0],
        length: frame.length,
        request,
    }))
}

/// The answer of the CPU to a request: the response, or the exception an item error or a CPU
/// that no longer serves (4, server device failure) gives.
async fn answer(
    request: ModbusRequest<'static>,
    items: Vec<Item>,
    client: Client,
    requests: &Requests,
    map: &Map,
) -> Result<Response, ExceptionCode> {
    let (reply, results) = oneshot::channel();
    requests
        .send(Request::Access {
            client,
            items,
            reply,
        })
        .map_err(|_| ExceptionCode::ServerDeviceFailure)?;
    let results = results
        .await
        .map_err(|_| ExceptionCode::ServerDeviceFailure)?;
    access::response(&request, map, results)
}

/// Serves one connection until it closes. A frame must arrive whole within `frame_timeout` of
/// its first byte, and a response must be taken within it; between frames the client may wait
/// as long as it likes (TCP keep-alive finds a client that vanished).
pub async fn converse(
    mut stream: TcpStream,
    client: Client,
    requests: &Requests,
    map: &Map,
    frame_timeout: Duration,
) {
    let mut buffer: Vec<u8> = Vec::with_capacity(2 * MAX_FRAME_LENGTH);
    let mut chunk = [0u8; MAX_FRAME_LENGTH];
    let mut frame_began: Option<Instant> = None;
    loop {
        let Ok(found) = incoming(&buffer, map) else {
            return;
        };
        if let Some(Incoming {
            header,
            function,
            length,
            request,
        }) = found
        {
            let answer = match request {
                Ok((request, items)) => answer(request, items, client, requests, map).await,
                Err(exception) => Err(exception),
            };
            let response = frame::encode(header, function, &answer);
            match timeout(frame_timeout, stream.write_all(&response)).await {
                Ok(Ok(())) => {}
                _ => return,
            }
            buffer.drain(..length);
            frame_began = (!buffer.is_empty()).then(Instant::now);
            continue;
        }
        let read = match frame_began {
            None => stream.read(&mut chunk).await,
            Some(began) => match timeout_at(began + frame_timeout, stream.read(&mut chunk)).await {
                Ok(read) => read,
                Err(_) => return,
            },
        };
        match read {
            Ok(0) | Err(_) => return,
            Ok(count) => {
                buffer.extend_from_slice(&chunk[..count]);
                frame_began.get_or_insert_with(Instant::now);
            }
        }
    }
}
