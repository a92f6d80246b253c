//! An editor session against `awl lsp`, scripted by fuzz bytes: the document is edited as a
//! user types (the whole text sent after each edit, as the server asks), requests are made
//! at positions in and beyond the text, some are cancelled at once, and the settings change.
//! Every request must get one answer, never `InternalError` (a handler that panicked), and
//! the server must end cleanly at `shutdown` and `exit`.

use std::time::Duration;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId};
use serde_json::{Value, json};

/// What an insertion types: statements of both dialects, symbols, variables, parts of a
/// statement, line ends, and characters outside ASCII (one of them two UTF-16 units long).
const TYPED: &[&str] = &[
    "      A     I 0.0\n",
    "      JC    M001\n",
    "M001 :BE\n",
    "\"START\"",
    "#start",
    "NETWORK\nTITLE = t\n",
    "END_FUNCTION_BLOCK\n",
    "FUNCTION_BLOCK FB 1\nVAR_INPUT\n  start : BOOL;\nEND_VAR\nBEGIN\n",
    "L DB1.DBW 4;\n",
    "T1",
    "U E 1.0\n",
    ":",
    "(",
    ";",
    "\n",
    "\r\n",
    "é",
    "\u{1F600}",
    "'",
    "//",
];

/// The requests a position is asked with.
const AT_POSITION: &[&str] = &[
    "textDocument/hover",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/completion",
];

const DOCUMENT: &str = "file:///fuzz/edited.awl";

/// Runs the session the script describes on `text`; panics where the server misbehaves.
pub fn edit_session(text: &str, script: &[u8]) {
    let (client, server) = Connection::memory();
    let thread = std::thread::spawn(move || awl::lsp::serve(&server));
    let mut session = Session {
        client,
        text: text.to_string(),
        version: 1,
        next_id: 1,
    };
    session.ask("initialize", json!({"capabilities": {}}));
    session.notify("initialized", json!({}));
    let open = json!({"textDocument": {"uri": DOCUMENT, "languageId": "awl", "version": 1, "text": text}});
    session.notify("textDocument/didOpen", open);
    for step in script.chunks(4) {
        let [kind, a, b, c] = [0, 1, 2, 3].map(|i| step.get(i).copied().unwrap_or(0));
        session.step(kind, a, b, c);
    }
    session.ask("shutdown", Value::Null);
    session.notify("exit", Value::Null);
    let ended = thread.join().expect("the server thread does not panic");
    assert_eq!(ended, Ok(()), "the server ends cleanly");
}

struct Session {
    client: Connection,
    text: String,
    version: i32,
    next_id: i32,
}

impl Session {
    fn step(&mut self, kind: u8, a: u8, b: u8, c: u8) {
        let position = json!({"line": a % 64, "character": b % 96});
        let document = json!({"uri": DOCUMENT});
        match kind % 12 {
            0..=3 => {
                let method = AT_POSITION[usize::from(kind % 4)];
                let params = json!({"textDocument": document, "position": position,
                    "context": {"includeDeclaration": c % 2 == 0}});
                self.ask(method, params);
            }
            4 => {
                let end = json!({"line": (a % 64) + c % 4, "character": c});
                let params = json!({"textDocument": document, "range": {"start": position, "end": end},
                    "context": {"diagnostics": []}});
                self.ask("textDocument/codeAction", params);
            }
            5 => {
                let method = match c % 4 {
                    0 => "textDocument/semanticTokens/full",
                    1 => "textDocument/formatting",
                    2 => "textDocument/documentSymbol",
                    _ => "workspace/symbol",
                };
                let params = json!({"textDocument": document, "query": TYPED[usize::from(a) % TYPED.len()],
                    "options": {"tabSize": 4, "insertSpaces": true}});
                self.ask(method, params);
            }
            6 | 7 => self.insert(a, b, TYPED[usize::from(c) % TYPED.len()]),
            8 => self.delete(a, b, c),
            9 => {
                // A request cancelled as soon as it is sent: answered or cancelled, never lost.
                let params = json!({"textDocument": document, "position": position});
                let id = self.send_request("textDocument/hover", params);
                self.notify("$/cancelRequest", json!({"id": id}));
                self.answer_to(id);
            }
            10 => {
                let cpu = ["speed7", "s5-115u", "sinumerik-840c", "no-such-cpu"][usize::from(c % 4)];
                self.notify("workspace/didChangeConfiguration", json!({"settings": {"awl": {"cpu": cpu}}}));
            }
            _ => {
                // Parameters of the wrong shape.
                self.ask(AT_POSITION[usize::from(c % 4)], json!({"textDocument": a, "position": [b]}));
            }
        }
    }

    fn insert(&mut self, line: u8, character: u8, typed: &str) {
        let at = self.offset(line, character);
        self.text.insert_str(at, typed);
        self.changed();
    }

    fn delete(&mut self, line: u8, character: u8, length: u8) {
        let start = self.offset(line, character);
        let end = self.text[start..]
            .char_indices()
            .nth(usize::from(length % 16))
            .map_or(self.text.len(), |(at, _)| start + at);
        self.text.replace_range(start..end, "");
        self.changed();
    }

    /// The byte offset of a line and a UTF-16 column, clamped to the text as an editor does.
    fn offset(&self, line: u8, character: u8) -> usize {
        let mut start = 0;
        for _ in 0..line % 64 {
            match self.text[start..].find('\n') {
                Some(end) => start += end + 1,
                None => return self.text.len(),
            }
        }
        let mut units = 0;
        for (at, char) in self.text[start..].char_indices() {
            if char == '\n' || units >= usize::from(character % 96) {
                return start + at;
            }
            units += char.len_utf16();
        }
        self.text.len()
    }

    fn changed(&mut self) {
        self.version += 1;
        let params = json!({"textDocument": {"uri": DOCUMENT, "version": self.version},
            "contentChanges": [{"text": self.text}]});
        self.notify("textDocument/didChange", params);
    }

    fn notify(&self, method: &str, params: Value) {
        let message = Notification::new(method.to_string(), params);
        self.client.sender.send(message.into()).expect("the server is running");
    }

    fn send_request(&mut self, method: &str, params: Value) -> i32 {
        self.next_id += 1;
        let request = Request::new(RequestId::from(self.next_id), method.to_string(), params);
        self.client.sender.send(request.into()).expect("the server is running");
        self.next_id
    }

    fn ask(&mut self, method: &str, params: Value) {
        let id = self.send_request(method, params);
        self.answer_to(id);
    }

    /// Waits for the answer to request `id`; notifications on the way are skipped.
    fn answer_to(&self, id: i32) {
        loop {
            let message = self
                .client
                .receiver
                .recv_timeout(Duration::from_secs(60))
                .expect("every request is answered");
            if let Message::Response(response) = message {
                assert_eq!(response.id, RequestId::from(id), "answers come in order");
                if let Some(error) = response.error {
                    assert_ne!(error.code, ErrorCode::InternalError as i32, "{}", error.message);
                }
                return;
            }
        }
    }
}
