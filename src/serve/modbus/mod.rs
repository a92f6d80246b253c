//! The Modbus TCP server of `awl serve`: functions 1–6, 15, 16 and 23 on the four tables of
//! [`Map`], each request one access of the CPU through [`crate::serve::request`].

pub mod access;
pub mod connection;
pub mod frame;
pub mod map;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use tokio::net::{TcpListener, TcpStream};

pub use map::{Map, Table};

use crate::serve::request::{Client, Protocol, Request, Requests};

/// How long a frame may take to arrive whole from its first byte, and a response to be taken.
const FRAME_TIMEOUT: Duration = Duration::from_secs(10);

/// How long to wait after the listener failed to accept (no file descriptors left, say).
const ACCEPT_PAUSE: Duration = Duration::from_millis(100);

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
    let open = Arc::new(AtomicUsize::new(0));
    let mut number = 0u32;
    loop {
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            Err(_) => {
                tokio::time::sleep(ACCEPT_PAUSE).await;
                continue;
            }
        };
        if open.load(Ordering::SeqCst) >= max_connections {
            continue;
        }
        number = number.wrapping_add(1);
        let connection = Connection::open(number, requests.clone(), open.clone());
        keep_alive(&stream);
        tokio::spawn(async move {
            connection::converse(
                stream,
                connection.client,
                &connection.requests,
                &map,
                frame_timeout,
            )
            .await;
            drop(connection);
        });
    }
}

/// Keep-alive is a help, not a need: a socket that refuses it is served all the same.
fn keep_alive(stream: &TcpStream) {
    let keepalive = socket2::TcpKeepalive::new().with_time(KEEPALIVE);
    #[cfg(any(target_os = "linux", target_os = "macos", target_os = "windows"))]
    let keepalive = keepalive.with_interval(Duration::from_secs(10));
    let _ = socket2::SockRef::from(stream).set_tcp_keepalive(&keepalive);
}

/// An open connection: counted and announced while it lives, its close announced when it is
/// dropped, however its task ends.
struct Connection {
    client: Client,
    requests: Requests,
    open: Arc<AtomicUsize>,
}

impl Connection {
    fn open(number: u32, requests: Requests, open: Arc<AtomicUsize>) -> Connection {
        let client = Client {
            protocol: Protocol::Modbus,
            number,
        };
        open.fetch_add(1, Ordering::SeqCst);
        // A CPU that no longer listens answers no request either; the connection learns so.
        let _ = requests.send(Request::Connection { client, open: true });
        Connection {
            client,
            requests,
            open,
        }
    }
}

impl Drop for Connection {
    fn drop(&mut self) {
        self.open.fetch_sub(1, Ordering::SeqCst);
        let _ = self.requests.send(Request::Connection {
            client: self.client,
            open: false,
        });
    }
}

#[cfg(test)]
mod tests {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    use tokio::time::{Instant, timeout};

    use super::*;

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
