//! `awl serve … --http 127.0.0.1:0` for the tests of its JSON API, with a plain HTTP client
//! written by others (ureq).

use std::io::{Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

const AWL: &str = env!("CARGO_BIN_EXE_awl");

/// A running `awl serve … --http 127.0.0.1:0` and the port it printed.
pub struct Online {
    pub child: Child,
    pub port: u16,
    pub agent: ureq::Agent,
}

impl Online {
    pub fn start(args: &[&str]) -> Online {
        let mut child = Command::new(AWL)
            .arg("serve")
            .args(args)
            .args(["--http", "127.0.0.1:0"])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("awl starts");
        let lines = super::lines(child.stdout.take().expect("piped"));
        let deadline = Instant::now() + Duration::from_secs(60);
        let port = loop {
            let line = super::next_line(&mut child, &lines, deadline, "online line");
            if let Some(rest) = line.strip_prefix("Online page at http://127.0.0.1:") {
                break rest.trim_end_matches('/').parse().expect("a port");
            }
        };
        let agent = ureq::Agent::config_builder()
            .http_status_as_error(false)
            .build()
            .into();
        Online { child, port, agent }
    }

    pub fn url(&self, path: &str) -> String {
        format!("http://127.0.0.1:{}{path}", self.port)
    }

    pub fn answer(response: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> (u16, Value) {
        let mut response = response.expect("the server answers");
        let status = response.status().as_u16();
        let text = response.body_mut().read_to_string().expect("a body");
        let value = serde_json::from_str(&text).unwrap_or(Value::String(text));
        (status, value)
    }

    pub fn get(&self, path: &str) -> (u16, Value) {
        Online::answer(self.agent.get(&self.url(path)).call())
    }

    pub fn post(&self, path: &str, body: &Value) -> (u16, Value) {
        let request = self
            .agent
            .post(&self.url(path))
            .header("Content-Type", "application/json");
        Online::answer(request.send(body.to_string()))
    }

    /// The values of `operands` (`MW 10,Q 4.0`) in `formats`.
    pub fn values(&self, operands: &str, formats: &str) -> Vec<Value> {
        let query = format!(
            "/api/values?operands={}&formats={formats}",
            operands.replace(' ', "%20")
        );
        let (status, answer) = self.get(&query);
        assert_eq!(status, 200, "{answer}");
        answer["values"].as_array().expect("values").clone()
    }

    /// Waits until `operand` shows `value` (the CPU takes a write at its next control point).
    pub fn wait_for(&self, operand: &str, value: &str) -> Value {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            let row = self.values(operand, "").remove(0);
            if row["value"] == value || Instant::now() > deadline {
                assert_eq!(row["value"], value, "{operand}");
                return row;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// A request as it is written, over a socket of its own; the status and the body. The
    /// server may answer (and close) before the request is all sent.
    pub fn raw(&self, request: &str) -> (u16, String) {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).expect("connects");
        let _ = stream.write_all(request.as_bytes());
        let mut answer = String::new();
        let _ = stream.read_to_string(&mut answer);
        let status = answer
            .split_whitespace()
            .nth(1)
            .and_then(|code| code.parse().ok())
            .unwrap_or(0);
        let body = answer.split("\r\n\r\n").nth(1).unwrap_or("").to_string();
        (status, body)
    }
}

impl Online {
    pub fn delete(&self, path: &str) -> (u16, Value) {
        Online::answer(self.agent.delete(&self.url(path)).call())
    }

    /// Ends the serve as a service manager does (SIGTERM), so it writes its trace; its stdout.
    pub fn terminate(mut self) -> String {
        super::end_with(&mut self.child, "-TERM");
        let mut stderr = String::new();
        let _ = self
            .child
            .stderr
            .take()
            .map(|mut err| err.read_to_string(&mut stderr));
        stderr
    }
}

impl Drop for Online {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
