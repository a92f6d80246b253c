//! A debug session against `awl dap`, scripted by fuzz bytes: the program is kept in memory,
//! and each step of the script sends one message (a request of the protocol with arguments
//! picked by the next bytes, or a broken message). Every request must be answered exactly
//! once, whatever came before it, and the adapter must end when its input does.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;

use awl::source::Files;
use serde_json::{Value, json};

const PROGRAM: &str = "fuzz.awl";

/// What the adapter wrote, kept for the checks.
#[derive(Clone, Default)]
struct Written(Rc<RefCell<Vec<u8>>>);

impl Write for Written {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(bytes);
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

const COMMANDS: &[&str] = &[
    "initialize",
    "launch",
    "setBreakpoints",
    "setFunctionBreakpoints",
    "setExceptionBreakpoints",
    "configurationDone",
    "threads",
    "stackTrace",
    "scopes",
    "variables",
    "evaluate",
    "setVariable",
    "continue",
    "next",
    "stepIn",
    "stepOut",
    "pause",
    "attach",
    "source",
    "disconnect",
];

const NAMES: &[&str] = &[
    "OB 1",
    "PB 3",
    "FB 5",
    "FC 1",
    "\"Valve\"",
    "request OB 3",
    "",
    "X 9",
];
const EXPRESSIONS: &[&str] = &[
    "FW 10",
    "MW 4",
    "set FW 10 7",
    "I 0.0",
    "T 1",
    "{",
    "= 5",
    "",
];
const CONDITIONS: &[&str] = &["FW 10 = 0", "MW 4 > 5", "I 0.0 <> 1", "XW 1 = 0", "= 3", ""];

fn pick<'a>(table: &[&'a str], byte: u8) -> &'a str {
    table[usize::from(byte) % table.len()]
}

/// The arguments of `command`, from the step's two bytes.
fn arguments(command: &str, a: u8, b: u8) -> Value {
    let number = i64::from(a) * 37 + i64::from(b);
    match command {
        "launch" => {
            json!({ "program": if a % 4 == 0 { "missing.awl" } else { PROGRAM }, "stopOnEntry": b % 2 == 0 })
        }
        "setBreakpoints" => json!({ "source": { "path": PROGRAM }, "breakpoints": [
            { "line": a % 40, "condition": pick(CONDITIONS, b), "hitCondition": pick(&["", "2", "% 3", "x"], a) },
            { "line": b % 40, "logMessage": pick(&["", "v {FW 10}", "{", "{X 1}"], b) },
        ] }),
        "setFunctionBreakpoints" => {
            json!({ "breakpoints": [{ "name": pick(NAMES, a), "condition": pick(CONDITIONS, b) }] })
        }
        "setExceptionBreakpoints" => {
            json!({ "filters": [pick(&["interrupt", "request", "stop", "other"], a)] })
        }
        "stackTrace" => json!({ "threadId": a % 4 }),
        "scopes" => json!({ "frameId": number }),
        "variables" => json!({ "variablesReference": number }),
        "evaluate" => json!({ "expression": pick(EXPRESSIONS, a), "frameId": number }),
        "setVariable" => {
            json!({ "variablesReference": number, "name": pick(&["ACCU 1", "T 1", "EIN"], a), "value": pick(&["1", "x", "-70000"], b) })
        }
        _ if a % 16 == 0 => json!(number),
        _ => json!({ "threadId": 1 }),
    }
}

fn framed(body: &str) -> Vec<u8> {
    format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
}

/// The adapter's messages, read back from its output.
fn messages(mut written: &[u8]) -> Vec<Value> {
    let mut out = Vec::new();
    while let Some(start) = written.windows(4).position(|w| w == b"\r\n\r\n") {
        let header = std::str::from_utf8(&written[..start]).expect("a text header");
        let length: usize = header
            .trim()
            .strip_prefix("Content-Length: ")
            .and_then(|n| n.parse().ok())
            .expect("a Content-Length header");
        let body = &written[start + 4..start + 4 + length];
        out.push(serde_json::from_slice(body).expect("a JSON body"));
        written = &written[start + 4 + length..];
    }
    out
}

/// Runs `program` under the `script`'s messages (three bytes a step) and checks the answers.
pub fn debug_session(program: &str, script: &[u8]) {
    let mut input = Vec::new();
    let mut requests = Vec::new();
    // Every message with a sequence number: a client's event is no request, but the adapter
    // may answer it with an error as it answers other malformed messages.
    let mut numbered = Vec::new();
    for (seq, step) in script.chunks(3).enumerate() {
        let seq = seq as i64 + 1;
        let (a, b) = (
            step.get(1).copied().unwrap_or(0),
            step.get(2).copied().unwrap_or(0),
        );
        match step[0] {
            250 => input.extend_from_slice(&framed("{broken")),
            251 => {
                let event = json!({ "seq": seq, "type": "event" });
                input.extend_from_slice(&framed(&event.to_string()));
                numbered.push(seq);
            }
            byte => {
                let command = pick(COMMANDS, byte);
                let body = json!({ "seq": seq, "type": "request", "command": command, "arguments": arguments(command, a, b) });
                input.extend_from_slice(&framed(&body.to_string()));
                requests.push(seq);
                numbered.push(seq);
            }
        }
    }
    let files = BTreeMap::from([(PathBuf::from(PROGRAM), program.as_bytes().to_vec())]);
    let written = Written::default();
    awl::dap::session(
        std::io::Cursor::new(input),
        Box::new(written.clone()),
        Files::Memory(Arc::new(files)),
    );
    let answered: Vec<i64> = messages(&written.0.borrow())
        .iter()
        .filter(|message| message["type"] == "response")
        .filter_map(|message| message["request_seq"].as_i64())
        .filter(|seq| *seq > 0)
        .collect();
    // The session ends at the first disconnect; every request before it is answered once.
    let disconnect = requests.iter().position(|seq| {
        let step = &script[(*seq as usize - 1) * 3];
        pick(COMMANDS, *step) == "disconnect"
    });
    let expected = &requests[..disconnect.map_or(requests.len(), |at| at + 1)];
    for seq in expected {
        let count = answered.iter().filter(|answer| *answer == seq).count();
        assert_eq!(count, 1, "request {seq} answered {count} times");
    }
    for seq in &answered {
        assert!(
            numbered.contains(seq),
            "an answer to message {seq}, which was not sent"
        );
        let count = answered.iter().filter(|answer| *answer == seq).count();
        assert_eq!(count, 1, "message {seq} answered {count} times");
    }
}
