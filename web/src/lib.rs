//! The playground's WebAssembly module: awl's `playground` functions with JSON in and out for
//! the page's script (web/page.js) and its worker (web/worker.js). Everything it does is in the
//! library, tested natively.

use std::time::Duration;

use awl::playground::{Live, Pulse, json};
use wasm_bindgen::prelude::*;

mod examples {
    include!(concat!(env!("OUT_DIR"), "/examples.rs"));
}

/// Every example file by name (`fig5_2.awl`, `bench/calls.toml`, …), the CPU profiles and the
/// words the editor colours (JSON).
#[wasm_bindgen]
pub fn catalogue() -> String {
    json::catalogue(examples::FILES)
}

#[wasm_bindgen]
extern "C" {
    /// Whoever hears how far a run has come: the worker, which posts it to the page.
    pub type Listener;

    #[wasm_bindgen(method)]
    fn progress(this: &Listener, clock_ns: f64, cycle: f64);
}

/// How often a long run tells how far it has come: often enough for a progress line that
/// moves, seldom enough that the messages cost nothing.
const REPORT_EVERY: Duration = Duration::from_millis(100);

fn pulse(listener: Listener) -> Pulse {
    Pulse::new(
        REPORT_EVERY,
        Box::new(move |progress| {
            listener.progress(progress.clock_ns as f64, progress.cycle as f64)
        }),
    )
}

/// Runs a request (JSON) to its end, telling `listener` how far it has come; the outcome as
/// JSON.
#[wasm_bindgen]
pub fn run(request_json: &str, listener: Listener) -> String {
    json::run(request_json, pulse(listener))
}

/// Runs a request under the debugger with these commands, one per line.
#[wasm_bindgen]
pub fn debug(request_json: &str, commands: &str, listener: Listener) -> String {
    json::debug(request_json, commands, pulse(listener))
}

/// A live run; `start` tells whether it could start, else `refusal` says why.
#[wasm_bindgen]
pub struct LiveRun {
    live: Option<Live>,
    refusal: String,
}

#[wasm_bindgen]
impl LiveRun {
    #[wasm_bindgen(constructor)]
    pub fn new(request_json: &str) -> LiveRun {
        match json::start_live(request_json) {
            Ok(live) => LiveRun {
                live: Some(live),
                refusal: String::new(),
            },
            Err(refusal) => LiveRun {
                live: None,
                refusal,
            },
        }
    }

    /// The outcome (JSON) of a run that could not start; empty when it started.
    pub fn refusal(&self) -> String {
        self.refusal.clone()
    }

    /// Runs on by `ns` of simulated time, keeping the events of the last `keep_ns`.
    pub fn advance(&mut self, ns: f64, keep_ns: f64) {
        if let Some(live) = &mut self.live {
            live.advance(ns as u64, keep_ns as u64);
        }
    }

    /// Flips an input; the reason when it cannot be set.
    pub fn set_input(&mut self, operand: &str, on: bool) -> String {
        match &mut self.live {
            Some(live) => live.set_input(operand, on).err().unwrap_or_default(),
            None => "not running".to_string(),
        }
    }

    /// Requests an interrupt OB; whether the request is pending.
    pub fn request(&mut self, ob: u8) -> bool {
        self.live.as_mut().is_some_and(|live| live.request(ob))
    }

    /// The I/O panel, the clock and the timeline of the last `window_ns` (JSON).
    pub fn view(&self, window_ns: f64) -> String {
        match &self.live {
            Some(live) => json::to_json(&live.view(window_ns as u64)),
            None => "null".to_string(),
        }
    }
}
