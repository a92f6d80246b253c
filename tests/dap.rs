//! `awl dap` driven by a plain Debug Adapter Protocol client over stdio, as an editor drives
//! it: launch, each breakpoint kind, stepping, OB levels as threads, scopes and evaluate,
//! attach with HOLD, and the errors.

mod common;

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

const WAIT: Duration = Duration::from_secs(60);

struct Client {
    child: Child,
    stdin: Option<ChildStdin>,
    messages: Receiver<Value>,
    /// Events and responses read while waiting for others.
    seen: Vec<Value>,
    seq: i64,
}

fn read_message(input: &mut impl BufRead) -> Option<Value> {
    let mut length = 0;
    loop {
        let mut line = String::new();
        if input.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let line = line.trim_end();
        if line.is_empty() {
            break;
        }
        if let Some(value) = line.strip_prefix("Content-Length:") {
            length = value.trim().parse().ok()?;
        }
    }
    let mut body = vec![0; length];
    input.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}

fn path(relative: &str) -> String {
    format!("{}/{relative}", env!("CARGO_MANIFEST_DIR"))
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_awl"))
            .arg("dap")
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("awl starts");
        let stdout = child.stdout.take().expect("piped");
        let (send, messages) = channel();
        std::thread::spawn(move || {
            let mut input = BufReader::new(stdout);
            while let Some(message) = read_message(&mut input) {
                if send.send(message).is_err() {
                    return;
                }
            }
        });
        let stdin = child.stdin.take();
        Client {
            child,
            stdin,
            messages,
            seen: Vec::new(),
            seq: 0,
        }
    }

    fn send_raw(&mut self, bytes: &[u8]) {
        let stdin = self.stdin.as_mut().expect("open");
        stdin.write_all(bytes).unwrap();
        stdin.flush().unwrap();
    }

    fn send(&mut self, command: &str, arguments: Value) -> i64 {
        self.seq += 1;
        let body = json!({
            "seq": self.seq, "type": "request", "command": command, "arguments": arguments
        })
        .to_string();
        let framed = format!("Content-Length: {}\r\n\r\n{body}", body.len());
        self.send_raw(framed.as_bytes());
        self.seq
    }

    /// The first message (kept or coming) that `wanted` picks.
    fn wait_for(&mut self, what: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        if let Some(at) = self.seen.iter().position(&wanted) {
            return self.seen.remove(at);
        }
        let deadline = Instant::now() + WAIT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            let message = self
                .messages
                .recv_timeout(left)
                .unwrap_or_else(|_| panic!("no {what}; seen {:#?}", self.seen));
            if wanted(&message) {
                return message;
            }
            self.seen.push(message);
        }
    }

    fn response(&mut self, seq: i64) -> Value {
        self.wait_for(&format!("response to {seq}"), |m| {
            m["type"] == "response" && m["request_seq"] == seq
        })
    }

    /// Sends a request and waits for its response, which must succeed.
    fn ok(&mut self, command: &str, arguments: Value) -> Value {
        let seq = self.send(command, arguments);
        let response = self.response(seq);
        assert_eq!(response["success"], true, "{command}: {response:#}");
        response["body"].clone()
    }

    /// Sends a request whose response must fail; its message.
    fn refused(&mut self, command: &str, arguments: Value) -> String {
        let seq = self.send(command, arguments);
        let response = self.response(seq);
        assert_eq!(response["success"], false, "{command}: {response:#}");
        response["message"].as_str().unwrap_or("").to_string()
    }

    fn event(&mut self, name: &str) -> Value {
        self.wait_for(&format!("event {name}"), |m| {
            m["type"] == "event" && m["event"] == name
        })["body"]
            .clone()
    }

    /// Initializes and launches; the launch's response.
    fn launch(&mut self, arguments: Value) -> Value {
        self.ok("initialize", json!({ "adapterID": "awl" }));
        let seq = self.send("launch", arguments);
        self.response(seq)
    }

    /// Launches, sets the filters, and starts the run.
    fn launched(
        arguments: Value,
        filters: &[&str],
        before_run: impl FnOnce(&mut Client),
    ) -> Client {
        let mut client = Client::start();
        let launch = client.launch(arguments);
        assert_eq!(launch["success"], true, "{launch:#}");
        client.event("initialized");
        client.ok("setExceptionBreakpoints", json!({ "filters": filters }));
        before_run(&mut client);
        client.ok("configurationDone", json!({}));
        client
    }

    fn stopped(&mut self) -> Value {
        self.event("stopped")
    }

    /// The top frame of the thread: its name and line.
    fn top(&mut self, thread: i64) -> (String, i64, i64) {
        let trace = self.ok("stackTrace", json!({ "threadId": thread }));
        let frame = &trace["stackFrames"][0];
        (
            frame["name"].as_str().unwrap().to_string(),
            frame["line"].as_i64().unwrap(),
            frame["id"].as_i64().unwrap(),
        )
    }

    fn stopped_at(&mut self) -> (String, i64) {
        let stopped = self.stopped();
        let thread = stopped["threadId"].as_i64().unwrap();
        let (name, line, _) = self.top(thread);
        (name, line)
    }

    fn variables(&mut self, frame: i64, scope: &str) -> Vec<(String, String)> {
        let scopes = self.ok("scopes", json!({ "frameId": frame }));
        let reference = scopes["scopes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == scope)
            .unwrap_or_else(|| panic!("no scope {scope}: {scopes:#}"))["variablesReference"]
            .clone();
        let body = self.ok("variables", json!({ "variablesReference": reference }));
        body["variables"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| {
                (
                    v["name"].as_str().unwrap().to_string(),
                    v["value"].as_str().unwrap().to_string(),
                )
            })
            .collect()
    }

    fn finish(mut self) {
        self.ok("disconnect", json!({}));
        let deadline = Instant::now() + WAIT;
        while Instant::now() < deadline {
            if self.child.try_wait().unwrap().is_some() {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        panic!("awl dap did not end after disconnect");
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn interrupt_scenario() -> Value {
    json!({ "scenario": "programs/fig5_2_interrupt.toml", "stopOnEntry": true })
}

const PROGRAM: &str = "programs/fig5_2_interrupt.awl";

fn source() -> Value {
    json!({ "path": path(PROGRAM) })
}

#[test]
fn launch_stops_on_entry_and_steps() {
    let mut client = Client::launched(interrupt_scenario(), &[], |_| {});
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "entry");
    let threads = client.ok("threads", json!({}));
    assert_eq!(threads["threads"][0]["name"], "OB 1");
    assert_eq!(client.top(1).0, "OB 1");
    assert_eq!(client.top(1).1, 8);
    for line in [9, 10, 11] {
        client.ok("next", json!({ "threadId": 1 }));
        assert_eq!(client.stopped_at(), ("OB 1".to_string(), line));
    }
    client.ok("stepIn", json!({ "threadId": 1 }));
    assert_eq!(client.stopped_at(), ("PB 3".to_string(), 20));
    let trace = client.ok("stackTrace", json!({ "threadId": 1 }));
    assert_eq!(trace["stackFrames"][1]["name"], "OB 1");
    assert_eq!(trace["stackFrames"][1]["line"], 11);
    assert!(
        trace["stackFrames"][0]["source"]["path"]
            .as_str()
            .unwrap()
            .ends_with("fig5_2_interrupt.awl")
    );
    client.ok("stepOut", json!({ "threadId": 1 }));
    let (block, line) = client.stopped_at();
    assert_eq!(block, "OB 1");
    assert!(line == 12, "after PB 3 returned: {line}");
    client.ok("next", json!({ "threadId": 1 }));
    assert_eq!(client.stopped_at(), ("OB 1".to_string(), 13));
    client.ok("continue", json!({ "threadId": 1 }));
    client.event("terminated");
    client.finish();
}

#[test]
fn line_breakpoints_move_to_the_next_statement() {
    let mut client = Client::launched(interrupt_scenario(), &[], |client| {
        let body = client.ok(
            "setBreakpoints",
            json!({ "source": source(), "breakpoints": [{ "line": 18 }, { "line": 37 }, { "line": 500 }] }),
        );
        let set = body["breakpoints"].as_array().unwrap();
        assert_eq!(set[0]["verified"], true);
        assert_eq!(
            set[0]["line"], 20,
            "the blank line moves to PB 3's first statement"
        );
        assert_eq!(set[1]["line"], 37);
        assert_eq!(set[2]["verified"], false);
    });
    assert_eq!(client.stopped()["reason"], "entry");
    client.ok("continue", json!({ "threadId": 1 }));
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "breakpoint");
    assert!(stopped["hitBreakpointIds"].is_array());
    assert_eq!(client.top(1).1, 20);
    client.ok("continue", json!({ "threadId": 1 }));
    assert_eq!(client.stopped_at(), ("PB 13".to_string(), 37));
    client.ok("continue", json!({ "threadId": 1 }));
    client.event("terminated");
    client.finish();
}

/// What the log points said so far.
fn logged(client: &Client) -> Vec<String> {
    client
        .seen
        .iter()
        .filter(|m| m["event"] == "output" && m["body"]["category"] == "console")
        .map(|m| m["body"]["output"].as_str().unwrap().to_string())
        .collect()
}

#[test]
fn conditions_hit_counts_and_log_points() {
    // Without the scenario the program runs 1 s of cycles.
    let arguments = json!({ "program": PROGRAM, "cpu": "sinumerik-840c" });
    let mut client = Client::launched(arguments, &[], |client| {
        let body = client.ok(
            "setBreakpoints",
            json!({ "source": source(), "breakpoints": [
                { "line": 8, "hitCondition": "3" },
                { "line": 9, "logMessage": "F 60.0 is {F 60.0}" },
                { "line": 20, "condition": "FW 62 > 5" },
                { "line": 36, "condition": "XW 4 > 5" },
                { "line": 37, "condition": "F 60.1 = 1" },
                { "line": 38, "condition": "F 60.1 = 1" },
            ] }),
        );
        let set = body["breakpoints"].as_array().unwrap();
        assert_eq!(
            set[3]["verified"], false,
            "an unknown operand is refused when set"
        );
        assert!(set[3]["message"].as_str().unwrap().contains("XW 4"));
        assert_eq!(set[4]["verified"], true);
        assert_eq!(set[5]["verified"], true);
    });
    // F 60.1 is 0 on line 37, which sets it, and 1 on line 38: the first cycle stops there.
    assert_eq!(client.stopped_at(), ("PB 13".to_string(), 38));
    assert_eq!(logged(&client), ["F 60.0 is 0\n"]);
    client.ok(
        "setBreakpoints",
        json!({ "source": source(), "breakpoints": [
            { "line": 8, "hitCondition": "3" },
            { "line": 9, "logMessage": "F 60.0 is {F 60.0}" },
            { "line": 20, "condition": "FW 62 > 5" },
        ] }),
    );
    // The hit count: the third time OB 1 starts from now (cycles 2, 3, 4), after the log
    // points of cycles 2 and 3; FW 62 stays 0 without interrupts, so line 20 never stops.
    client.ok("continue", json!({ "threadId": 1 }));
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "breakpoint");
    assert_eq!(client.top(1).1, 8);
    assert_eq!(logged(&client).len(), 3);
    let value = client.ok(
        "evaluate",
        json!({ "expression": "FW 62", "frameId": 1000 }),
    );
    assert!(value["result"].as_str().unwrap().contains('0'), "{value:#}");
    client.finish();
}

#[test]
fn function_breakpoints_and_locals() {
    let mut client = Client::launched(interrupt_scenario(), &[], |client| {
        let body = client.ok(
            "setFunctionBreakpoints",
            json!({ "breakpoints": [{ "name": "PB 3" }, { "name": "FB 5" }, { "name": "PB 99" }, { "name": "FC 1" }] }),
        );
        let set = body["breakpoints"].as_array().unwrap();
        assert_eq!(set[0]["verified"], true);
        assert_eq!(set[0]["line"], 20);
        assert_eq!(set[2]["verified"], false);
        assert!(set[2]["message"].as_str().unwrap().contains("PB 99"));
        assert_eq!(set[3]["verified"], false, "a STEP 5 program has no FC");
    });
    client.stopped();
    client.ok("continue", json!({ "threadId": 1 }));
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "function breakpoint");
    assert_eq!(client.top(1).0, "PB 3");
    client.ok("continue", json!({ "threadId": 1 }));
    assert_eq!(client.stopped_at(), ("FB 5".to_string(), 54));
    let (_, _, frame) = client.top(1);
    let locals = client.variables(frame, "Locals");
    let ein = locals.iter().find(|(name, _)| name == "EIN").expect("EIN");
    assert!(ein.1.starts_with("I 0.0 = "), "{locals:?}");
    assert!(locals.iter().any(|(name, _)| name == "AUS"));
    client.finish();
}

#[test]
fn interrupt_obs_are_threads_and_stepping_goes_into_them() {
    let mut client = Client::launched(interrupt_scenario(), &[], |client| {
        client.ok(
            "setBreakpoints",
            json!({ "source": source(), "breakpoints": [{ "line": 33 }] }),
        );
    });
    client.stopped();
    client.ok("continue", json!({ "threadId": 1 }));
    assert_eq!(client.stopped_at(), ("PB 3".to_string(), 33));
    // PB 3's block end is the interrupt point: a step in goes into OB 3.
    client.ok("stepIn", json!({ "threadId": 1 }));
    let stopped = client.stopped();
    assert_eq!(stopped["threadId"], 3);
    let threads = client.ok("threads", json!({}));
    let names: Vec<&str> = threads["threads"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["OB 3 (interrupting OB 1)", "OB 1"]);
    let (block, line, frame) = client.top(3);
    assert_eq!((block.as_str(), line), ("OB 3", 62));
    assert_eq!(
        client.top(1).0,
        "OB 1",
        "OB 1's level waits after PB 3's block end"
    );
    // Scopes: the registers, and evaluate and set of an operand.
    let registers = client.variables(frame, "Registers");
    let names: Vec<&str> = registers.iter().map(|(n, _)| n.as_str()).collect();
    for name in ["ACCU 1", "ACCU 2", "RLO", "/FC", "OV", "open DB"] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    client.variables(frame, "Timers and counters");
    let set = client.ok(
        "evaluate",
        json!({ "expression": "set FW 62 41", "frameId": frame }),
    );
    assert!(set["result"].as_str().unwrap().contains("41"), "{set:#}");
    let read = client.ok(
        "evaluate",
        json!({ "expression": "FW 62", "frameId": frame }),
    );
    assert!(read["result"].as_str().unwrap().contains("41"));
    let unknown = client.refused(
        "evaluate",
        json!({ "expression": "XW 9", "frameId": frame }),
    );
    assert!(unknown.contains("XW 9"));
    client.ok("continue", json!({ "threadId": 3 }));
    client.event("terminated");
    client.finish();
}

#[test]
fn interrupt_filter_and_set_variable() {
    let mut client = Client::launched(interrupt_scenario(), &["request", "interrupt"], |_| {});
    client.stopped();
    client.ok("continue", json!({ "threadId": 1 }));
    // Taken in and serviced at the same interrupt point (PB 3's block end): one pause.
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "exception");
    let text = stopped["text"].as_str().unwrap();
    assert!(text.contains("request for OB 3"), "{text}");
    assert!(text.contains("OB 3 serviced"), "{text}");
    let (_, line, frame) = client.top(3);
    assert_eq!(line, 62);
    let registers = client.variables(frame, "Registers");
    assert!(registers.iter().any(|(n, _)| n == "ACCU 1"));
    let scopes = client.ok("scopes", json!({ "frameId": frame }));
    let reference = scopes["scopes"][0]["variablesReference"].clone();
    let refused = client.refused(
        "setVariable",
        json!({ "variablesReference": reference, "name": "RLO", "value": "1" }),
    );
    assert!(refused.contains("RLO"));
    client.finish();
}

#[test]
fn a_stop_pauses_with_its_cause() {
    let arguments = json!({ "scenario": "programs/speed7_stop.toml" });
    let mut client = Client::launched(arguments, &["stop"], |_| {});
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "exception");
    assert!(stopped["description"].as_str().unwrap().starts_with("STOP"));
    assert!(!stopped["text"].as_str().unwrap().is_empty());
    client.ok("threads", json!({}));
    client.ok("continue", json!({ "threadId": 1 }));
    client.event("terminated");
    client.finish();
}

#[test]
fn a_stop_inside_a_block_pauses_before_the_cpu_leaves_it() {
    let dir = std::env::temp_dir().join(format!("awl-dap-stop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("stop.awl");
    std::fs::write(&program, "OB 1\n      L  KF +1\n      C  DB 99\n      BE\n").unwrap();
    let arguments = json!({ "program": program.display().to_string() });
    let mut client = Client::launched(arguments, &["stop"], |_| {});
    let stopped = client.stopped();
    assert_eq!(stopped["description"], "STOP: LZF");
    assert!(stopped["text"].as_str().unwrap().contains("DB 99"));
    // Before the STOP: OB 1 is still on the block stack, at the faulting line.
    let (block, line, _) = client.top(stopped["threadId"].as_i64().unwrap());
    assert_eq!((block.as_str(), line), ("OB 1", 3));
    client.ok("continue", json!({ "threadId": 1 }));
    client.event("terminated");
    client.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn launch_errors_are_the_diagnostics() {
    let mut client = Client::start();
    let missing = client.launch(json!({ "program": "programs/no_such_file.awl" }));
    assert_eq!(missing["success"], false);
    assert!(
        missing["message"]
            .as_str()
            .unwrap()
            .contains("no_such_file.awl")
    );
    let dir = std::env::temp_dir().join(format!("awl-dap-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.awl");
    std::fs::write(&bad, "OB 1\n      XYZZY F 1.0\n      BE\n").unwrap();
    let seq = client.send("launch", json!({ "program": bad.display().to_string() }));
    let response = client.response(seq);
    assert_eq!(response["success"], false);
    let message = response["message"].as_str().unwrap();
    assert!(message.contains("XYZZY"), "{message}");
    assert!(
        message.contains("awl::"),
        "the diagnostic's code: {message}"
    );
    let nothing = client.refused("launch", json!({}));
    assert!(nothing.contains("program"));
    let cpu = client.refused("launch", json!({ "program": PROGRAM, "cpu": "s9-9000" }));
    assert!(cpu.contains("s9-9000"));
    // Requests that need a run are refused, not lost.
    assert!(
        client
            .refused("stackTrace", json!({ "threadId": 1 }))
            .contains("launch")
    );
    assert!(
        client
            .refused("flyToTheMoon", json!({}))
            .contains("flyToTheMoon")
    );
    let _ = std::fs::remove_dir_all(&dir);
    client.finish();
}

#[test]
fn malformed_messages_are_answered_and_the_session_goes_on() {
    let mut client = Client::start();
    client.send_raw(b"Content-Length: 5\r\n\r\n{nope");
    let answer = client.wait_for("an error", |m| m["type"] == "response");
    assert_eq!(answer["success"], false);
    client.send_raw(b"Content-Length: 26\r\n\r\n{\"seq\":7,\"type\":\"event\"}  ");
    let answer = client.wait_for("an error", |m| m["request_seq"] == 7);
    assert_eq!(answer["success"], false);
    let capabilities = client.ok("initialize", json!({}));
    assert_eq!(capabilities["supportsConfigurationDoneRequest"], true);
    client.finish();
}

#[test]
fn a_vanished_client_ends_the_adapter() {
    let mut client = Client::launched(interrupt_scenario(), &[], |_| {});
    client.stopped();
    client.stdin = None;
    let deadline = Instant::now() + WAIT;
    while client.child.try_wait().unwrap().is_none() {
        assert!(
            Instant::now() < deadline,
            "awl dap still runs without its client"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// OB 1 counts its cycles in FW 4 and shows the count in QW 0.
const COUNTER: &str =
    "OB 1\n      L  FW 4\n      L  KF +1\n      +F\n      T  FW 4\n      T  QW 0\n      BE\n";

/// `GET` on the online API of `awl serve --http` at `port`: the answer's JSON.
fn online(port: u16, path: &str) -> Value {
    let mut answer = ureq::get(&format!("http://127.0.0.1:{port}{path}"))
        .call()
        .expect("the online API answers");
    serde_json::from_str(&answer.body_mut().read_to_string().unwrap()).unwrap()
}

/// The value of `operand` as the online page shows it.
fn online_value(port: u16, operand: &str) -> String {
    let path = format!("/api/values?operands={}", operand.replace(' ', "%20"));
    online(port, &path)["values"][0]["value"]
        .as_str()
        .unwrap()
        .to_string()
}

/// SZL 0x0424's mode byte and QW 0, read by python-snap7.
fn s7_mode_and_outputs(port: u16) -> (u8, u16) {
    let printed = common::python::client("snap7", "dap_hold.py", &[&port.to_string()]);
    let mut numbers = printed
        .split_whitespace()
        .map(|n| n.parse::<u16>().unwrap());
    (numbers.next().unwrap() as u8, numbers.next().unwrap())
}

/// Waits until the online API shows the CPU in `mode`.
fn wait_for_mode(port: u16, mode: &str) -> Value {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        let cpu = online(port, "/api/cpu");
        if cpu["mode"] == mode || Instant::now() > deadline {
            assert_eq!(cpu["mode"], mode, "{cpu:#}");
            return cpu;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn attach_holds_the_served_cpu_at_a_breakpoint() {
    let dir = std::env::temp_dir().join(format!("awl-dap-attach-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("counter.awl");
    std::fs::write(&program, COUNTER).unwrap();
    let program = program.display().to_string();
    let args = [
        program.as_str(),
        "--s7",
        "127.0.0.1:0",
        "--http",
        "127.0.0.1:0",
    ];
    let (_serving, ports) =
        common::serve::Serving::start(&args, &["S7 server listening on ", "Online page at "]);
    let (s7, http) = (ports[0], ports[1]);
    wait_for_mode(http, "RUN");
    let mut client = Client::start();
    client.ok("initialize", json!({ "adapterID": "awl" }));
    client.ok("attach", json!({ "connect": format!("127.0.0.1:{http}") }));
    client.event("initialized");
    let source = json!({ "path": program });
    let breakpoint = |line: i64| json!({ "source": source, "breakpoints": [{ "line": line }] });
    let set = client.ok("setBreakpoints", breakpoint(5));
    assert_eq!(set["breakpoints"][0]["verified"], true, "{set:#}");
    client.ok("setExceptionBreakpoints", json!({ "filters": ["stop"] }));
    client.ok("configurationDone", json!({}));
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "breakpoint");
    assert_eq!(client.top(stopped["threadId"].as_i64().unwrap()).1, 5);

    // HOLD: the online API and an S7 client see it; no cycle runs, the outputs keep their
    // values, simulated time stands still, and the clients are served.
    let held = wait_for_mode(http, "HOLD");
    let outputs = online_value(http, "QW 0");
    let (mode, s7_outputs) = s7_mode_and_outputs(s7);
    assert_eq!(mode, 0x0A, "SZL 0x0424 shows HOLD");
    std::thread::sleep(Duration::from_millis(300));
    let still = online(http, "/api/cpu");
    assert_eq!(still["mode"], "HOLD");
    assert_eq!(still["cycle"], held["cycle"]);
    assert_eq!(still["simulated_ms"], held["simulated_ms"]);
    assert_eq!(online_value(http, "QW 0"), outputs);
    assert_eq!(s7_mode_and_outputs(s7).1, s7_outputs);
    let count = client.ok("evaluate", json!({ "expression": "FW 4" }));
    assert!(!count["result"].as_str().unwrap().is_empty());

    // Without the breakpoint, continue returns the CPU to RUN; the clock follows on.
    let cleared = client.ok(
        "setBreakpoints",
        json!({ "source": source, "breakpoints": [] }),
    );
    assert_eq!(cleared["breakpoints"], json!([]));
    client.ok("continue", json!({ "threadId": 1 }));
    let running = wait_for_mode(http, "RUN");
    assert_eq!(s7_mode_and_outputs(s7).0, 0x08, "SZL 0x0424 shows RUN");
    let jump = running["simulated_ms"].as_f64().unwrap() - held["simulated_ms"].as_f64().unwrap();
    assert!(
        jump < 250.0,
        "the clock did not jump by the hold: {jump} ms"
    );
    assert_ne!(online_value(http, "QW 0"), outputs);

    // Held again, the debugger leaves: its breakpoints go and the CPU runs on.
    client.ok("setBreakpoints", breakpoint(5));
    client.stopped();
    wait_for_mode(http, "HOLD");
    client.ok("disconnect", json!({}));
    wait_for_mode(http, "RUN");
    std::thread::sleep(Duration::from_millis(200));
    assert_eq!(online(http, "/api/cpu")["mode"], "RUN");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn attach_errors_are_told() {
    let mut client = Client::start();
    client.ok("initialize", json!({ "adapterID": "awl" }));
    let missing = client.refused("attach", json!({}));
    assert!(missing.contains("connect"), "{missing}");
    // A port nobody listens on: the one a listener just gave back.
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let gone = client.refused("attach", json!({ "connect": format!("127.0.0.1:{port}") }));
    assert!(gone.contains("cannot attach"), "{gone}");
    client.finish();
}

#[test]
fn step7_conditions_and_function_breakpoints() {
    let program = path("programs/s7/traffic_light.awl");
    let arguments = json!({ "scenario": "programs/s7/traffic_light.toml" });
    let mut client = Client::launched(arguments, &[], |client| {
        // FC 1 loads "Step" on line 30; the condition holds once the crossing left step 0.
        let lines = json!({
            "source": { "path": program },
            "breakpoints": [{ "line": 30, "condition": "MW 10 > 0" }],
        });
        let set = client.ok("setBreakpoints", lines);
        assert_eq!(set["breakpoints"][0]["verified"], true, "{set:#}");
        let refused = client.ok(
            "setBreakpoints",
            json!({ "source": { "path": program }, "breakpoints": [{ "line": 30, "condition": "MX 10 > 0" }] }),
        );
        assert_eq!(refused["breakpoints"][0]["verified"], false, "{refused:#}");
        let lines = json!({
            "source": { "path": program },
            "breakpoints": [{ "line": 30, "condition": "MW 10 > 0" }],
        });
        client.ok("setBreakpoints", lines);
    });
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "breakpoint");
    let (block, line, _) = client.top(stopped["threadId"].as_i64().unwrap());
    assert_eq!((block.as_str(), line), ("FC 1", 30));
    let step = client.ok("evaluate", json!({ "expression": "MW 10" }));
    assert_ne!(step["result"], "0", "{step:#}");
    // A function breakpoint on FC 2: its formals among its Locals, with their actuals' values.
    let set = client.ok(
        "setFunctionBreakpoints",
        json!({ "breakpoints": [{ "name": "FC 2" }] }),
    );
    assert_eq!(set["breakpoints"][0]["verified"], true, "{set:#}");
    client.ok(
        "setBreakpoints",
        json!({ "source": { "path": program }, "breakpoints": [] }),
    );
    client.ok("continue", json!({ "threadId": 1 }));
    let stopped = client.stopped();
    assert_eq!(stopped["reason"], "function breakpoint");
    let (block, _, frame) = client.top(stopped["threadId"].as_i64().unwrap());
    assert_eq!(block, "FC 2");
    let locals = client.variables(frame, "Locals");
    let names: Vec<&str> = locals.iter().map(|(name, _)| name.as_str()).collect();
    assert_eq!(
        names[..6],
        [
            "step",
            "car_red",
            "car_amber",
            "car_green",
            "ped_red",
            "ped_green"
        ],
        "{locals:?}"
    );
    client.ok("disconnect", json!({}));
}

/// An FC with inputs from a flag word, a constant and a flag bit, an output, and temporaries;
/// OB 1 with temporaries of its own.
const FC_WITH_LOCALS: &str = "\
FUNCTION FC 3 : VOID
VAR_INPUT
  speed : INT;
  limit : INT;
  enable : BOOL;
END_VAR
VAR_OUTPUT
  running : BOOL;
END_VAR
VAR_TEMP
  doubled : INT;
  flag : BOOL;
END_VAR
BEGIN
NETWORK
      L     #speed;
      L     2;
      *I    ;
      T     #doubled;
      A     #enable;
      =     #flag;
      A     #flag;
      =     #running;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
VAR_TEMP
  info : ARRAY [1..20] OF BYTE;
  count : INT;
END_VAR
BEGIN
NETWORK
      L     21;
      T     MW    20;
      SET   ;
      =     M      1.0;
      L     7;
      T     #count;
      CALL  FC     3 (
           speed                    := MW    20,
           limit                    := 300,
           enable                   := M      1.0,
           running                  := Q      4.0);
END_ORGANIZATION_BLOCK
";

#[test]
fn step7_locals_name_an_fc_s_formals_and_temporaries() {
    let folder = common::scratch("dap", "fc_locals");
    let program = folder.join("fc_locals.awl");
    std::fs::write(&program, FC_WITH_LOCALS).unwrap();
    let program = program.display().to_string();
    let arguments = json!({ "program": program });
    let mut client = Client::launched(arguments, &[], |client| {
        let lines = json!({ "source": { "path": program }, "breakpoints": [{ "line": 23 }] });
        let set = client.ok("setBreakpoints", lines);
        assert_eq!(set["breakpoints"][0]["verified"], true, "{set:#}");
    });
    assert_eq!(client.stopped_at(), ("FC 3".to_string(), 23));
    let (_, _, frame) = client.top(1);
    let locals = client.variables(frame, "Locals");
    let expected = [
        ("speed", "21"),
        ("limit", "300"),
        ("enable", "TRUE"),
        ("running", "FALSE"),
        ("doubled", "42"),
        ("flag", "TRUE"),
    ];
    let shown: Vec<(&str, &str)> = locals
        .iter()
        .map(|(name, value)| (name.as_str(), value.as_str()))
        .collect();
    assert_eq!(shown, expected, "{locals:?}");
    // The caller's frame: OB 1's temporaries by name.
    let caller = client.variables(frame + 1, "Locals");
    assert!(
        caller.contains(&("count".to_string(), "7".to_string())),
        "{caller:?}"
    );
    assert!(
        caller.iter().any(|(name, _)| name == "info[20]"),
        "{caller:?}"
    );
    client.finish();
}
