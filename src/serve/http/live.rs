//! The live view (`/api/live`): a WebSocket over which the page subscribes to what it shows —
//! the CPU, watch values, program status, the timeline, the diagnostic buffer — and gets each
//! pushed about four times a second, asked of the CPU as the API asks it. A subscription may be
//! sent again at any time; one that cannot be served is answered `{"type": "error", …}` and
//! that part of it left out.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use axum::extract::ws::{Message, WebSocket};
use serde::Serialize;
use serde_json::{Value, json};

use crate::serve::request::{Ask, Client, Refusal};

use super::api::{Subscription, subscription};
use super::{Shared, ask_for};

/// How often the subscribed parts are pushed.
const PUSH_EVERY: Duration = Duration::from_millis(250);

/// The seconds of the pushed timeline.
const TIMELINE_SECONDS: f64 = 5.0;

/// Counts a live connection from its opening to its end.
pub struct LiveSlot {
    open: Arc<AtomicUsize>,
}

impl LiveSlot {
    /// A slot, if fewer than `most` are taken.
    pub fn take(open: &Arc<AtomicUsize>, most: usize) -> Option<LiveSlot> {
        open.fetch_update(Ordering::AcqRel, Ordering::Acquire, |taken| {
            (taken < most).then_some(taken + 1)
        })
        .ok()
        .map(|_| LiveSlot {
            open: Arc::clone(open),
        })
    }
}

impl Drop for LiveSlot {
    fn drop(&mut self) {
        self.open.fetch_sub(1, Ordering::AcqRel);
    }
}

/// What was last pushed of the parts only pushed when they change.
#[derive(Default)]
struct Sent {
    diagnostics: Option<Value>,
    status_error: Option<Refusal>,
}

/// Serves one live connection until the page closes it.
pub async fn serve(mut socket: WebSocket, client: Client, shared: Arc<Shared>, _slot: LiveSlot) {
    let mut subscribed = Subscription::default();
    let mut sent = Sent::default();
    let mut tick = tokio::time::interval(PUSH_EVERY);
    loop {
        let go_on = tokio::select! {
            message = socket.recv() => match message {
                Some(Ok(Message::Text(text))) => {
                    match subscription(text.as_str()) {
                        Ok(subscription) => {
                            subscribed = subscription;
                            sent = Sent::default();
                            push(&mut socket, &mut subscribed, &mut sent, client, &shared).await
                        }
                        Err(error) => send(&mut socket, &error_message(&error.refusal())).await,
                    }
                }
                Some(Ok(Message::Close(_))) | Some(Err(_)) | None => false,
                // Pings are answered by the socket itself; binary messages mean nothing here.
                Some(Ok(_)) => true,
            },
            _ = tick.tick() => push(&mut socket, &mut subscribed, &mut sent, client, &shared).await,
        };
        if !go_on {
            return;
        }
    }
}

fn error_message(refusal: &Refusal) -> Value {
    json!({"type": "error", "error": refusal.error, "code": refusal.code, "help": refusal.help})
}

/// `value`'s fields with `"type"` first.
fn typed(kind: &str, value: &impl Serialize) -> Value {
    let mut object = serde_json::Map::new();
    object.insert("type".into(), kind.into());
    if let Ok(Value::Object(fields)) = serde_json::to_value(value) {
        object.extend(fields);
    }
    Value::Object(object)
}

/// Sends a message; `false` when the page is gone.
async fn send(socket: &mut WebSocket, message: &Value) -> bool {
    socket
        .send(Message::Text(message.to_string().into()))
        .await
        .is_ok()
}

/// Pushes every subscribed part; a part the CPU refuses is reported and left out (program
/// status is kept: its block may run later, and its error is pushed when it changes).
async fn push(
    socket: &mut WebSocket,
    subscribed: &mut Subscription,
    sent: &mut Sent,
    client: Client,
    shared: &Shared,
) -> bool {
    let mut messages = Vec::new();
    if subscribed.cpu {
        match ask_for(shared, client, |reply| Ask::Cpu { reply }).await {
            Ok(cpu) => messages.push(typed("cpu", &cpu)),
            Err(refusal) => return send(socket, &error_message(&refusal)).await,
        }
    }
    if !subscribed.values.is_empty() {
        let watched = subscribed.values.clone();
        match ask_for(shared, client, |reply| Ask::Values { watched, reply }).await {
            Ok(Ok(values)) => messages.push(json!({"type": "values", "values": values})),
            Ok(Err(refusal)) | Err(refusal) => {
                subscribed.values.clear();
                messages.push(error_message(&refusal));
            }
        }
    }
    if let Some((block, level)) = subscribed.status.clone() {
        let make = |reply| Ask::ProgramStatus {
            block,
            level,
            reply,
        };
        match ask_for(shared, client, make).await {
            Ok(Ok(view)) => {
                sent.status_error = None;
                messages.push(typed("status", &view));
            }
            Ok(Err(refusal)) | Err(refusal) => {
                if sent.status_error.as_ref() != Some(&refusal) {
                    messages.push(error_message(&refusal));
                    sent.status_error = Some(refusal);
                }
            }
        }
    }
    if subscribed.timeline {
        let make = |reply| Ask::Timeline {
            seconds: TIMELINE_SECONDS,
            reply,
        };
        if let Ok(svg) = ask_for(shared, client, make).await {
            messages.push(json!({"type": "timeline", "svg": svg}));
        }
    }
    if subscribed.diagnostics
        && let Ok(entries) = ask_for(shared, client, |reply| Ask::Diagnostics { reply }).await
    {
        let message = json!({"type": "diagnostics", "entries": entries});
        if sent.diagnostics.as_ref() != Some(&message) {
            sent.diagnostics = Some(message.clone());
            messages.push(message);
        }
    }
    for message in &messages {
        if !send(socket, message).await {
            return false;
        }
    }
    true
}
