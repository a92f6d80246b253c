//! The S7comm server of `awl serve`: what HMIs and test tools of an S7-300 speak, over
//! ISO-on-TCP (RFC 1006). Each connection is a task of its own; every read, write, state or
//! control request goes down the [`Requests`] channel and is answered from the CPU's state.
//!
//! Why not the `snap7-server` crate (0.1.7): it serves requests from a memory store of its own
//! (`DataStore`, a map the library owns) with synchronous callbacks, so a request cannot wait
//! for the CPU's answer at its cycle control point; it answers every item as successful (no
//! item return codes), acknowledges stop and start without doing them, answers SZLs and the
//! clock with fixed or stored values, and neither checks item lengths against the negotiated
//! PDU nor bounds what a client may hold open. It cannot meet the requirement that every
//! request reaches the CPU through the channel, so the protocol layer is written here.

mod connection;
pub mod decode;
pub mod encode;
pub mod frame;
pub mod szl;

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use tokio::net::TcpListener;

use super::request::{Client, Protocol, Request, Requests};

/// How the server treats its clients.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Connections open at once; a further one is closed at once.
    pub max_connections: usize,
    /// A client that sends nothing for this long is disconnected.
    pub idle_timeout: Duration,
    /// A client must finish a packet it began (and take an answer) within this time.
    pub packet_timeout: Duration,
}

impl Settings {
    pub fn new(max_connections: usize) -> Settings {
        Settings {
            max_connections,
            idle_timeout: Duration::from_secs(60),
            packet_timeout: Duration::from_secs(10),
        }
    }
}

/// Accepts S7comm connections on `listener` forever, at most `max_connections` at once.
pub async fn serve(listener: TcpListener, requests: Requests, max_connections: usize) {
    serve_with(listener, requests, Settings::new(max_connections)).await
}

/// [`serve`] with all of its settings.
pub async fn serve_with(listener: TcpListener, requests: Requests, settings: Settings) {
    let open = Arc::new(AtomicUsize::new(0));
    let mut number = 0u32;
    loop {
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            // Out of file descriptors and the like: wait for connections to close.
            Err(_) => {
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        if open.load(Ordering::Acquire) >= settings.max_connections {
            drop(stream);
            continue;
        }
        let _ = stream.set_nodelay(true);
        number = number.wrapping_add(1).max(1);
        let client = Client {
            protocol: Protocol::S7,
            number,
        };
        let guard = OpenConnection::new(client, &open, &requests);
        let requests = requests.clone();
        tokio::spawn(async move {
            connection::serve(stream, client, requests, settings).await;
            drop(guard);
        });
    }
}

/// Counts a connection as open and tells the CPU, from its opening to its end (whichever way
/// its task ends).
struct OpenConnection {
    client: Client,
    open: Arc<AtomicUsize>,
    requests: Requests,
}

impl OpenConnection {
    fn new(client: Client, open: &Arc<AtomicUsize>, requests: &Requests) -> OpenConnection {
        open.fetch_add(1, Ordering::AcqRel);
        let _ = requests.send(Request::Connection { client, open: true });
        OpenConnection {
            client,
            open: Arc::clone(open),
            requests: requests.clone(),
        }
    }
}

impl Drop for OpenConnection {
    fn drop(&mut self) {
        self.open.fetch_sub(1, Ordering::AcqRel);
        let _ = self.requests.send(Request::Connection {
            client: self.client,
            open: false,
        });
    }
}
