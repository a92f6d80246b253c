//! The servers' side of the CPU's thread: the network runtime (one thread's, the CPU's own)
//! and the requests it produces. The CPU drives it only at its control point: while it waits
//! for the clock there, the connections are read and answered; while a cycle runs, they wait,
//! as a real CPU's communication waits for its cycle control point. So a request and its answer
//! never cross threads, and the VM's loop never sees the network.

use std::time::Duration;

use tokio::runtime::Runtime;

use super::request::{Received, Request};

pub struct Network {
    runtime: Runtime,
    requests: Received,
}

impl Network {
    /// `runtime` runs the servers' tasks (spawned on it); `requests` is what they send.
    pub fn new(runtime: Runtime, requests: Received) -> Self {
        Network { runtime, requests }
    }

    /// A request that has come already, without running the network.
    pub fn try_request(&mut self) -> Option<Request> {
        self.requests.try_recv().ok()
    }

    /// Runs the network until a request comes or `longest` has passed; the runtime's timers
    /// count whole milliseconds, so the wait may last up to a millisecond longer.
    pub fn next_request(&mut self, longest: Duration) -> Option<Request> {
        if let Some(request) = self.try_request() {
            return Some(request);
        }
        let requests = &mut self.requests;
        let received = self
            .runtime
            .block_on(async { tokio::time::timeout(longest, requests.recv()).await });
        match received {
            Ok(Some(request)) => Some(request),
            Ok(None) => {
                // No server is left to send anything: only the clock is waited for.
                std::thread::sleep(longest);
                None
            }
            Err(_elapsed) => None,
        }
    }

    /// Lets the network take in what has arrived and send the answers given, without waiting:
    /// the connections' sockets are polled once and their tasks run.
    pub fn poll(&mut self) {
        self.runtime.block_on(async {
            // The first yield lets the runtime poll its sockets, the second run the tasks
            // they woke (tokio runs a yielded task after the driver's poll).
            tokio::task::yield_now().await;
            tokio::task::yield_now().await;
        });
    }
}
