//! The Modbus TCP server of `awl serve`: functions 1–6, 15, 16 and 23 on the four tables of
//! [`Map`], each request one access of the CPU through [`crate::serve::request`].

pub mod access;
pub mod connection;
pub mod frame;
pub use crate::address::modbus_map as map;

use std::time::Duration;

use tokio::net::{TcpListener, TcpStream};

pub use map::{Map, Table};

use crate::serve::listen::accept_each;
use crate::serve::request::{Protocol, Requests};

/// How long a frame may take to arrive whole from its first byte, and a response to be taken.
const FRAME_TIMEOUT: Duration = Duration::from_secs(10);

/// Idle time before TCP keep-alive probes a silent client, as the Modbus Messaging on TCP/IP
/// Implementation Guide advises, so a client that vanished frees its connection.
const KEEPALIVE: Duration = Duration::from_secs(60);

/// Serves Modbus TCP on `listener` forever. Past `max_connections` open connections a new one
/// is closed at once; the others are numbered 1, 2, … and announced to the CPU when they open
/// and close.
pub async fn serve(listener: TcpListener, requests: Requests, map: Map, max_connections: usize) {
    serve_with(listener, requests, map, max_connections, FRAME_TIMEOUT).await;
}

async fn serve_with(
    listener: TcpListener,
    requests: Requests,
    map: Map,
    max_connections: usize,
    frame_timeout: Duration,
) {
    accept_each(listener, Protocol::Modbus, requests, max_connections, move |stream, client, requests| {
        keep_alive(&stream);
        async move { connection::converse(stream, client, &requests, &map, frame_timeout).await }
    })
    .await;
}

/// Keep-alive is a help, not a need: a socket that refuses it is served all the same.
fn keep_alive(stream: &TcpStream) {
    let keepalive = socket2::TcpKeepalive::new().with_time(KEEPALIVE);
    #[cfg(any(target_os = "linux", target_os = "macos", target_os = "windows"))]
    let keepalive = keepalive.with_interval(Duration::from_secs(10));
    let _ = socket2::SockRef::from(stream).set_tcp_keepalive(&keepalive);
}

#[cfg(test)]
mod tests {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    use tokio::time::{Instant, timeout};

    use super::*;
    use crate::serve::request::Request;

    #[tokio::test]
    async fn a_frame_that_stalls_is_closed_and_an_idle_client_is_not() {
        let listener = TcpListener::bind("127.0.0.1:0").await.expect("a port");
        let address = listener.local_addr().expect("its address");
        let (requests, mut served) = crate::serve::request::channel();
        let frame_timeout = Duration::from_millis(200);
        tokio::spawn(serve_with(
            listener,
            requests,
            Map::default(),
            4,
            frame_timeout,
        ));
        let mut idle = TcpStream::connect(address).await.expect("a connection");
        let mut stalled = TcpStream::connect(address).await.expect("another");
        stalled.write_all(&[0, 1, 0]).await.expect("a header begun");
        let began = Instant::now();
        let read = timeout(Duration::from_secs(5), stalled.read(&mut [0u8; 8])).await;
        assert!(matches!(read, Ok(Ok(0))), "closed: {read:?}");
        assert!(began.elapsed() >= frame_timeout - Duration::from_millis(50));
        let waited = timeout(3 * frame_timeout, idle.read(&mut [0u8; 8])).await;
        assert!(
            waited.is_err(),
            "the idle client is still served: {waited:?}"
        );
        let announced: Vec<bool> = std::iter::from_fn(|| served.try_recv().ok())
            .map(|request| matches!(request, Request::Connection { open: true, .. }))
            .collect();
        assert_eq!(announced, [true, true, false]);
    }
}
