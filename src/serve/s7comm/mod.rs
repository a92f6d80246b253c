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

use std::time::Duration;

use tokio::net::TcpListener;

use super::listen::accept_each;
use super::request::{Protocol, Requests};

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
    let max_connections = settings.max_connections;
    accept_each(
        listener,
        Protocol::S7,
        requests,
        max_connections,
        move |stream, client, requests| connection::serve(stream, client, requests, settings),
    )
    .await;
}
