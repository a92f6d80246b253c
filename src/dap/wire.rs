//! The Debug Adapter Protocol's base protocol: messages framed by a `Content-Length` header
//! (as the Language Server Protocol frames them), requests in, responses and events out.

use std::io::{BufRead, Write};

use serde_json::{Value, json};

/// The largest message taken; a longer one is refused without reading it into memory.
const LARGEST: usize = 16 << 20;

/// What came from the client.
#[derive(Debug, Clone, PartialEq)]
pub enum Incoming {
    Request(Request),
    /// A message that is no request awl can read: why, and its `seq` when it has one.
    Malformed {
        seq: i64,
        reason: String,
    },
}

#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    pub seq: i64,
    pub command: String,
    pub arguments: Value,
}

/// Reads the next message; `None` when the input has ended (or broke).
pub fn read(input: &mut impl BufRead) -> Option<Incoming> {
    let mut length = None;
    let mut header_error = None;
    loop {
        let mut line = String::new();
        match input.read_line(&mut line) {
            Ok(0) | Err(_) => return None,
            Ok(_) => {}
        }
        let line = line.trim_end_matches(['\r', '\n']);
        if line.is_empty() {
            if length.is_some() || header_error.is_some() {
                break;
            }
            continue;
        }
        match line.split_once(':') {
            Some((name, value)) if name.trim().eq_ignore_ascii_case("content-length") => {
                match value.trim().parse::<usize>() {
                    Ok(n) if n <= LARGEST => length = Some(n),
                    _ => header_error = Some(format!("`{line}` gives no length awl takes")),
                }
            }
            Some(_) => {}
            None => header_error = Some(format!("`{line}` is no header")),
        }
    }
    let Some(length) = length.filter(|_| header_error.is_none()) else {
        let reason = header_error.unwrap_or_default();
        return Some(Incoming::Malformed { seq: 0, reason });
    };
    let mut body = vec![0; length];
    input.read_exact(&mut body).ok()?;
    Some(parse(&body))
}

/// A message's body as a request.
pub fn parse(body: &[u8]) -> Incoming {
    let value: Value = match serde_json::from_slice(body) {
        Ok(value) => value,
        Err(error) => {
            let reason = format!("the message is no JSON: {error}");
            return Incoming::Malformed { seq: 0, reason };
        }
    };
    let seq = value.get("seq").and_then(Value::as_i64).unwrap_or(0);
    let malformed = |reason: &str| Incoming::Malformed {
        seq,
        reason: reason.to_string(),
    };
    if value.get("type").and_then(Value::as_str) != Some("request") {
        return malformed("the message is no request (its `type` is not \"request\")");
    }
    let Some(command) = value.get("command").and_then(Value::as_str) else {
        return malformed("the request names no `command`");
    };
    Incoming::Request(Request {
        seq,
        command: command.to_string(),
        arguments: value.get("arguments").cloned().unwrap_or(Value::Null),
    })
}

/// The adapter's side: numbers what it sends, and writes it out or (a served session's)
/// queues it until the debugger asks.
pub struct Outgoing {
    out: Option<Box<dyn Write>>,
    queued: Vec<Value>,
    seq: i64,
    /// The client is gone: writing failed.
    pub broken: bool,
}

impl Outgoing {
    pub fn new(out: Box<dyn Write>) -> Self {
        Outgoing {
            out: Some(out),
            queued: Vec::new(),
            seq: 0,
            broken: false,
        }
    }

    /// Messages kept until [`Outgoing::take_queued`].
    pub fn queued() -> Self {
        Outgoing {
            out: None,
            queued: Vec::new(),
            seq: 0,
            broken: false,
        }
    }

    pub fn take_queued(&mut self) -> Vec<Value> {
        std::mem::take(&mut self.queued)
    }

    /// Sends on a message another adapter made (an attached `awl serve`'s), numbered as this
    /// one's.
    pub fn forward(&mut self, message: Value) {
        self.send(message);
    }

    fn send(&mut self, mut message: Value) {
        self.seq += 1;
        message["seq"] = json!(self.seq);
        let Some(out) = self.out.as_mut() else {
            self.queued.push(message);
            return;
        };
        let body = message.to_string();
        let written =
            write!(out, "Content-Length: {}\r\n\r\n{body}", body.len()).and_then(|()| out.flush());
        self.broken |= written.is_err();
    }

    pub fn respond(&mut self, request_seq: i64, command: &str, body: Value) {
        self.send(json!({
            "type": "response",
            "request_seq": request_seq,
            "success": true,
            "command": command,
            "body": body,
        }));
    }

    pub fn refuse(&mut self, request_seq: i64, command: &str, message: &str) {
        self.send(json!({
            "type": "response",
            "request_seq": request_seq,
            "success": false,
            "command": command,
            "message": message,
            "body": { "error": { "id": 1, "format": message, "showUser": true } },
        }));
    }

    pub fn event(&mut self, event: &str, body: Value) {
        self.send(json!({ "type": "event", "event": event, "body": body }));
    }

    /// Text for the editor's debug console.
    pub fn output(&mut self, category: &str, text: &str) {
        self.event("output", json!({ "category": category, "output": text }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn framed(body: &str) -> Vec<u8> {
        format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
    }

    #[test]
    fn reads_requests_and_tells_what_is_wrong() {
        let mut input: &[u8] = &framed(r#"{"seq":3,"type":"request","command":"threads"}"#);
        assert!(matches!(read(&mut input), Some(Incoming::Request(r)) if r.seq == 3));
        assert_eq!(read(&mut input), None);
        let mut input: &[u8] = &framed("{nope");
        assert!(matches!(read(&mut input), Some(Incoming::Malformed { .. })));
        let mut input: &[u8] = b"Content-Length: lots\r\n\r\n";
        assert!(matches!(read(&mut input), Some(Incoming::Malformed { .. })));
        let mut input: &[u8] = &framed(r#"{"seq":4,"type":"event"}"#);
        assert!(matches!(
            read(&mut input),
            Some(Incoming::Malformed { seq: 4, .. })
        ));
    }
}
