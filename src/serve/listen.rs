//! What both servers do with their listener: accept connections, turn one away past the limit,
//! number the clients 1, 2, … and tell the CPU when each comes and goes (its status line
//! counts them), however the connection's task ends.

use std::future::Future;
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use tokio::net::{TcpListener, TcpStream};

use super::request::{Client, Protocol, Request, Requests};

/// How long to wait after the listener failed to accept (no file descriptors left, say): until
/// connections close.
const ACCEPT_PAUSE: Duration = Duration::from_millis(50);

/// Accepts connections on `listener` forever, at most `max_connections` open at once, and
/// serves each with `serve` in a task of its own.
pub async fn accept_each<Serve, Served>(
    listener: TcpListener,
    protocol: Protocol,
    requests: Requests,
    max_connections: usize,
    mut serve: Serve,
) where
    Serve: FnMut(TcpStream, Client, Requests) -> Served,
    Served: Future<Output = ()> + Send + 'static,
{
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
        if open.load(Ordering::Acquire) >= max_connections {
            continue;
        }
        // Requests and answers are small: each is sent at once.
        let _ = stream.set_nodelay(true);
        number = number.wrapping_add(1).max(1);
        let client = Client { protocol, number };
        let guard = OpenConnection::new(client, &open, &requests);
        let connection = serve(stream, client, requests.clone());
        tokio::spawn(async move {
            connection.await;
            drop(guard);
        });
    }
}

/// Counts a connection as open and tells the CPU, from its opening to its end.
struct OpenConnection {
    client: Client,
    open: Arc<AtomicUsize>,
    requests: Requests,
}

impl OpenConnection {
    fn new(client: Client, open: &Arc<AtomicUsize>, requests: &Requests) -> OpenConnection {
        open.fetch_add(1, Ordering::AcqRel);
        // A CPU that no longer listens answers no request either; the connection learns so.
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
