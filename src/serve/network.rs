//! The servers' side of the CPU's thread: the network runtime (one thread's, the CPU's own)
//! and the requests it produces. The CPU drives it only at its control point: while it waits
//! for the clock there, the connections are read and answered; while a cycle runs, they wait,
//! as a real CPU's communication waits for its cycle control point. So a request and its answer
//! never cross threads, and the VM's loop never sees the network.

use std::time::{Duration, Instant};

use tokio::runtime::Runtime;

use super::request::{Received, Request};

/// One step of a short wait where no alarm can be had: the connections are looked at
/// between two.
const NAP: Duration = Duration::from_micros(50);

pub struct Network {
    runtime: Runtime,
    requests: Received,
    /// Wakes the runtime at the end of a wait; without it, short naps.
    #[cfg(target_os = "linux")]
    alarm: Option<super::alarm::Alarm>,
}

impl Network {
    /// `runtime` runs the servers' tasks (spawned on it); `requests` is what they send.
    pub fn new(runtime: Runtime, requests: Received) -> Self {
        #[cfg(target_os = "linux")]
        let alarm = {
            let _entered = runtime.enter();
            super::alarm::Alarm::new().ok()
        };
        Network {
            runtime,
            requests,
            #[cfg(target_os = "linux")]
            alarm,
        }
    }

    /// A request that has come already, without running the network.
    pub fn try_request(&mut self) -> Option<Request> {
        self.requests.try_recv().ok()
    }

    /// Runs the network until a request comes or `longest` has passed.
    pub fn next_request(&mut self, longest: Duration) -> Option<Request> {
        #[cfg(target_os = "linux")]
        if let Some(alarm) = &self.alarm
            && alarm.set(longest).is_ok()
        {
            let requests = &mut self.requests;
            let received = self.runtime.block_on(async {
                tokio::select! {
                    biased;
                    request = requests.recv() => Some(request),
                    () = alarm.rung() => None,
                }
            });
            return match received {
                Some(Some(request)) => Some(request),
                Some(None) => {
                    // No server is left to send anything: only the clock is waited for.
                    std::thread::sleep(longest);
                    None
                }
                None => None,
            };
        }
        self.next_request_soon(longest)
    }

    /// A short wait: the network polled, then a nap, until a request comes or `longest`
    /// has passed.
    fn next_request_soon(&mut self, longest: Duration) -> Option<Request> {
        let until = Instant::now() + longest;
        loop {
            self.poll();
            if let Some(request) = self.try_request() {
                return Some(request);
            }
            let now = Instant::now();
            if now >= until {
                return None;
            }
            std::thread::sleep((until - now).min(NAP));
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
