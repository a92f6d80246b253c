//! Headless Chromium for the tests of pages: where it is missing they fail, saying how to install
//! it (`.ci/run` installs Debian's `chromium`). A page that has done its work at load is read once
//! (`--dump-dom`, `--screenshot`); one that works on in the background (the playground's worker)
//! is driven through the DevTools protocol, in real time.

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

use base64::Engine;
use serde_json::{Value, json};

/// The switches every headless run gets: no sandbox (tests may run as root), nothing from the
/// network, no GPU.
const QUIET: [&str; 9] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-quic",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--enable-logging=stderr",
];

/// The Chromium on this machine; panics, saying how to install it, where there is none.
pub fn chromium() -> PathBuf {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find_map(|name| {
            let found = Command::new("which").arg(name).output().ok()?;
            let path = String::from_utf8_lossy(&found.stdout).trim().to_string();
            (found.status.success() && !path.is_empty()).then(|| PathBuf::from(path))
        })
        .expect(
            "no Chromium on this machine (the pages are tested in headless Chromium): install \
             Chromium: `apt-get install chromium` (Debian, Ubuntu), or put `chromium`, \
             `chromium-browser` or `google-chrome` on PATH",
        )
}

/// Runs Chromium headless with its own profile directory; its stdout and log.
pub fn headless(browser: &Path, profile: &Path, args: &[&str]) -> (String, String) {
    let output = Command::new(browser)
        .args(QUIET)
        .arg("--v=0")
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .output()
        .expect("chromium starts");
    (
        String::from_utf8_lossy(&output.stdout).to_string(),
        String::from_utf8_lossy(&output.stderr).to_string(),
    )
}

/// Console messages and uncaught exceptions in Chromium's log: the page writes none, so any
/// is an error (Chromium logs `console.error` at the same level as `console.log`).
pub fn console_errors(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|line| line.contains(":CONSOLE") || line.contains("Uncaught"))
        .collect()
}

/// Takes a screenshot of `url` in a window of `size` ("1400,600") and checks it: no console
/// error, and the timeline drawn ([`assert_shows_the_timeline`]).
pub fn assert_screenshot_shows_the_timeline(browser: &Path, dir: &Path, size: &str, url: &str) {
    let shot = dir.join("shot.png");
    let (_, log) = headless(
        browser,
        &dir.join("profile-shot"),
        &[
            "--virtual-time-budget=10000",
            &format!("--screenshot={}", shot.display()),
            &format!("--window-size={size}"),
            url,
        ],
    );
    assert!(
        console_errors(&log).is_empty(),
        "{:?}",
        console_errors(&log)
    );
    assert_shows_the_timeline(&std::fs::read(&shot).expect("a screenshot"));
}

/// Checks a screenshot (PNG): not blank (a twentieth of it drawn), and OB 1's lane colour on
/// the screen (the timeline is drawn).
pub fn assert_shows_the_timeline(png: &[u8]) {
    let pixmap = resvg::tiny_skia::Pixmap::decode_png(png).expect("a PNG screenshot");
    let pixels = pixmap.pixels();
    let count = |colour: fn((u8, u8, u8)) -> bool| {
        pixels
            .iter()
            .filter(|p| colour((p.red(), p.green(), p.blue())))
            .count()
    };
    let drawn = count(|rgb| rgb != (255, 255, 255));
    assert!(drawn * 20 > pixels.len(), "the screenshot is blank");
    let lane_blue = count(|rgb| rgb == (0x4e, 0x79, 0xa7));
    assert!(lane_blue > 50, "OB 1's lane colour is on the screen");
}

/// How long the browser may take to answer: a page whose thread is held does not answer.
const ANSWER_WITHIN: Duration = Duration::from_secs(30);

/// Chromium driven through the DevTools protocol on a pipe (`--remote-debugging-pipe`: JSON
/// messages ended by a NUL byte, on its file descriptors 3 and 4).
pub struct DevTools {
    child: Child,
    to_browser: ChildStdin,
    from_browser: Receiver<Value>,
    next_id: u64,
    /// Console messages, uncaught exceptions and logged errors of the pages: the pages write
    /// none, so each is a failure.
    pub problems: Vec<String>,
}

impl DevTools {
    /// Starts Chromium with its own profile in `profile` and a window of `size` ("1400,1200").
    pub fn start(browser: &Path, profile: &Path, size: &str) -> DevTools {
        // The shell hands Chromium our pipes as its descriptors 3 and 4.
        let mut child = Command::new("sh")
            .arg("-c")
            .arg(r#"exec "$0" "$@" 3<&0 4>&1 0</dev/null 1>/dev/null"#)
            .arg(browser)
            .args(QUIET)
            .arg("--remote-debugging-pipe")
            .arg(format!("--window-size={size}"))
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromium starts");
        let to_browser = child.stdin.take().expect("a pipe");
        let mut reader = BufReader::new(child.stdout.take().expect("a pipe"));
        let (sender, from_browser) = channel();
        std::thread::spawn(move || {
            let mut message = Vec::new();
            while reader
                .read_until(0, &mut message)
                .is_ok_and(|read| read > 0)
            {
                message.pop();
                let value = serde_json::from_slice(&message).expect("the protocol speaks JSON");
                if sender.send(value).is_err() {
                    break;
                }
                message.clear();
            }
        });
        DevTools {
            child,
            to_browser,
            from_browser,
            next_id: 0,
            problems: Vec::new(),
        }
    }

    /// Sends a command (to a page's `session`, else to the browser); its result. Events that
    /// come meanwhile are looked at for problems.
    fn call(&mut self, session: Option<&str>, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        let mut message = json!({ "id": id, "method": method, "params": params });
        if let Some(session) = session {
            message["sessionId"] = json!(session);
        }
        let mut bytes = serde_json::to_vec(&message).expect("JSON");
        bytes.push(0);
        self.to_browser.write_all(&bytes).expect("chromium listens");
        let answer = self.wait(method, |message| message["id"] == id);
        assert!(answer.get("error").is_none(), "{method}: {answer}");
        answer["result"].clone()
    }

    /// The first message from the browser that is `wanted`; those before it are looked at for
    /// problems.
    fn wait(&mut self, what: &str, wanted: impl Fn(&Value) -> bool) -> Value {
        let deadline = Instant::now() + ANSWER_WITHIN;
        loop {
            let wait = deadline.saturating_duration_since(Instant::now());
            let message = match self.from_browser.recv_timeout(wait) {
                Ok(message) => message,
                Err(RecvTimeoutError::Timeout) => {
                    panic!("no answer to {what} within {ANSWER_WITHIN:?}: the page is held")
                }
                Err(RecvTimeoutError::Disconnected) => panic!("chromium ended during {what}"),
            };
            self.look_at(&message);
            if wanted(&message) {
                return message;
            }
        }
    }

    fn look_at(&mut self, event: &Value) {
        let params = &event["params"];
        let problem = match event["method"].as_str() {
            Some("Runtime.consoleAPICalled") => {
                Some(format!("console.{}: {}", params["type"], params["args"]))
            }
            Some("Runtime.exceptionThrown") => Some(params["exceptionDetails"].to_string()),
            Some("Log.entryAdded") if params["entry"]["level"] == "error" => {
                Some(params["entry"]["text"].to_string())
            }
            Some("Inspector.targetCrashed") => Some("the page crashed".to_string()),
            _ => None,
        };
        self.problems.extend(problem);
    }

    /// Opens `url` in a new tab, its console and log watched; returns once it has loaded.
    pub fn open(&mut self, url: &str) -> Tab<'_> {
        let target =
            self.call(None, "Target.createTarget", json!({ "url": "about:blank" }))["targetId"]
                .clone();
        let session = self.call(
            None,
            "Target.attachToTarget",
            json!({ "targetId": target, "flatten": true }),
        )["sessionId"]
            .as_str()
            .expect("a session")
            .to_string();
        for domain in [
            "Runtime.enable",
            "Log.enable",
            "Inspector.enable",
            "Page.enable",
        ] {
            self.call(Some(&session), domain, json!({}));
        }
        self.call(Some(&session), "Page.navigate", json!({ "url": url }));
        self.wait("the page's load", |message| {
            message["method"] == "Page.loadEventFired" && message["sessionId"] == session.as_str()
        });
        Tab {
            devtools: self,
            session,
            target,
        }
    }
}

impl Drop for DevTools {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A page open in the browser; closed when dropped.
pub struct Tab<'a> {
    devtools: &'a mut DevTools,
    session: String,
    target: Value,
}

impl Tab<'_> {
    /// The value of a script expression (a promise's, once it is settled).
    pub fn eval(&mut self, expression: &str) -> Value {
        let params =
            json!({ "expression": expression, "returnByValue": true, "awaitPromise": true });
        let result = self
            .devtools
            .call(Some(&self.session), "Runtime.evaluate", params);
        assert!(
            result.get("exceptionDetails").is_none(),
            "{expression}: {result}"
        );
        result["result"]["value"].clone()
    }

    /// Evaluates `expression` every 20 ms until it is true or a non-empty string; that value.
    pub fn wait_for(&mut self, expression: &str, within: Duration) -> Value {
        let deadline = Instant::now() + within;
        loop {
            let value = self.eval(expression);
            if value == json!(true) || value.as_str().is_some_and(|text| !text.is_empty()) {
                return value;
            }
            assert!(
                Instant::now() < deadline,
                "not within {within:?}: {expression}"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// A screenshot of the window (PNG).
    pub fn screenshot(&mut self) -> Vec<u8> {
        let shot = self.devtools.call(
            Some(&self.session),
            "Page.captureScreenshot",
            json!({ "format": "png" }),
        );
        let data = shot["data"].as_str().expect("base64 data");
        base64::engine::general_purpose::STANDARD
            .decode(data)
            .expect("base64")
    }

    /// The problems the pages had so far (see [`DevTools::problems`]).
    pub fn problems(&self) -> &[String] {
        &self.devtools.problems
    }
}

impl Drop for Tab<'_> {
    fn drop(&mut self) {
        let target = json!({ "targetId": self.target });
        self.devtools.call(None, "Target.closeTarget", target);
    }
}
