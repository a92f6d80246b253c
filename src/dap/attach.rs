//! Attaching to `awl serve --http` (`{"connect": "127.0.0.1:8103"}`): the served CPU's own
//! session of the adapter answers the editor's requests (`POST /api/debug`, see
//! `awl help online`); this side relays them, and asks for the events (a breakpoint that holds
//! the CPU, log points, a STOP) whenever the editor is quiet.

use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

use serde_json::{Value, json};

use super::Adapter;
use super::wire::{Incoming, Request};

/// How often the events are asked for while the editor sends nothing; the served CPU
/// detaches a debugger it has not heard from for five seconds.
const EVENTS_EVERY: Duration = Duration::from_millis(50);

/// The longest an answer of the served CPU takes before the server is taken for gone.
const ANSWER_WITHIN: Duration = Duration::from_secs(10);

/// The online API of one `awl serve`.
struct Served {
    agent: ureq::Agent,
    base: String,
}

impl Served {
    fn new(connect: &str) -> Served {
        let agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .timeout_global(Some(ANSWER_WITHIN))
            .build()
            .into();
        Served {
            agent,
            base: format!("http://{connect}/api/debug"),
        }
    }

    /// The messages the served CPU answers `request` with (`None`: asks for its events).
    fn ask(&self, request: Option<&Value>) -> Result<Vec<Value>, String> {
        let answer = match request {
            Some(request) => self
                .agent
                .post(&self.base)
                .header("Content-Type", "application/json")
                .send(request.to_string()),
            None => self.agent.get(&format!("{}/events", self.base)).call(),
        };
        let mut answer = answer.map_err(|error| error.to_string())?;
        let status = answer.status().as_u16();
        let text = answer
            .body_mut()
            .read_to_string()
            .map_err(|error| error.to_string())?;
        let body: Value = serde_json::from_str(&text).map_err(|error| error.to_string())?;
        match body["messages"].as_array() {
            Some(messages) if status == 200 => Ok(messages.clone()),
            _ => Err(body["error"]
                .as_str()
                .map_or_else(|| format!("the server answered {status}"), str::to_string)),
        }
    }
}

fn request_value(request: &Request) -> Value {
    json!({
        "seq": request.seq,
        "type": "request",
        "command": request.command,
        "arguments": request.arguments,
    })
}

/// Relays the session to the served CPU once it took the `attach`; `false` when it did not
/// (the editor was told why), so the adapter takes requests as before.
pub fn attach(adapter: &mut Adapter, request: Request) -> bool {
    let Some(connect) = request.arguments["connect"].as_str() else {
        adapter.out.refuse(
            request.seq,
            "attach",
            "`attach` needs `connect`: the HOST:PORT of `awl serve --http`, e.g. \"127.0.0.1:8103\"",
        );
        return false;
    };
    let served = Served::new(connect);
    let answer = match served.ask(Some(&request_value(&request))) {
        Ok(answer) => answer,
        Err(reason) => {
            let text = format!(
                "cannot attach to awl serve at {connect}: {reason}; start it with \
                 `awl serve PROGRAM --http {connect}`"
            );
            adapter.out.refuse(request.seq, "attach", &text);
            return false;
        }
    };
    let attached = answer
        .iter()
        .any(|message| message["command"] == "attach" && message["success"] == true);
    for message in answer {
        adapter.out.forward(message);
    }
    if attached {
        relay(adapter, &served);
    }
    attached
}

/// Passes the editor's requests on and the served CPU's messages back, until the editor
/// disconnects or goes (which detaches it, so the CPU goes on) or the server goes.
fn relay(adapter: &mut Adapter, served: &Served) {
    loop {
        let incoming = adapter.next_message_within(EVENTS_EVERY);
        let (request, leaving) = match incoming {
            Ok(Incoming::Request(request)) => {
                let leaving = matches!(request.command.as_str(), "disconnect" | "terminate");
                (Some(request), leaving)
            }
            Ok(Incoming::Malformed { seq, reason }) => {
                adapter.out.refuse(seq, "", &reason);
                continue;
            }
            Err(RecvTimeoutError::Timeout) => (None, false),
            Err(RecvTimeoutError::Disconnected) => {
                let _ = served.ask(Some(&json!({
                    "seq": 0, "type": "request", "command": "disconnect", "arguments": {},
                })));
                return;
            }
        };
        match served.ask(request.as_ref().map(request_value).as_ref()) {
            Ok(messages) => {
                for message in messages {
                    adapter.out.forward(message);
                }
            }
            Err(reason) => {
                let text = format!("awl serve does not answer any more: {reason}");
                if let Some(request) = &request {
                    adapter.out.refuse(request.seq, &request.command, &text);
                }
                adapter.out.output("stderr", &format!("{text}\n"));
                adapter.end();
                return;
            }
        }
        if leaving || adapter.out.broken {
            return;
        }
    }
}
