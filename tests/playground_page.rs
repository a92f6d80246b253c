//! The playground page in a real browser: `web/build.sh` builds the one-file page (awl as
//! WebAssembly), headless Chromium opens it from the file system and runs examples through the
//! address fragment — one that services an interrupt, one with source errors, one that goes to
//! STOP — then drives the step controls and live mode (`#selftest`), runs every sample in the
//! browser to compare its summary with the native one, stops a run that would go on for an
//! hour while the page stays responsive, and takes a screenshot that is not blank. Runs go to a
//! worker, so the page is driven in real time through the DevTools protocol.
//! `web/build.sh` installs the wasm32 target and `wasm-bindgen` where they are missing (with
//! rustup and cargo); without Chromium the test fails, saying how to install it.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

use common::browser::{DevTools, assert_shows_the_timeline, chromium};

/// Builds the page with `web/build.sh`, which first installs what it needs; its path.
fn build() -> PathBuf {
    let output = Command::new("web/build.sh").output().expect("bash runs");
    assert!(
        output.status.success(),
        "web/build.sh failed (it installs the wasm32-unknown-unknown target with rustup and \
         the wasm-bindgen CLI with cargo install, which need the network the first time):\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web/awl-playground.html");
    let size = std::fs::metadata(&page).expect("the page is built").len();
    // One file for the page, the wasm of both dialects' front ends and VM (with STEP 7's
    // complex types, pointers and system blocks), and the samples: 1.05 MB, the module gzipped
    // and without its names section.
    assert!(size < 1_200_000, "the page is {size} bytes");
    page
}

/// The text of the element with this id in the dumped DOM, entities decoded.
fn element(dom: &str, id: &str) -> String {
    let open = format!(" id=\"{id}\"");
    let start = dom
        .find(&open)
        .unwrap_or_else(|| panic!("no #{id} in {dom}"));
    let content = start + dom[start..].find('>').unwrap() + 1;
    let tag = dom[..start].rsplit('<').next().unwrap();
    let end = content + dom[content..].find(&format!("</{tag}>")).unwrap();
    dom[content..end]
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&amp;", "&")
}

/// `text` as a value in an address fragment.
fn encoded(text: &str) -> String {
    text.bytes()
        .map(|byte| match byte {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'.' => char::from(byte).to_string(),
            _ => format!("%{byte:02X}"),
        })
        .collect()
}

/// Long enough for every sample to run in the browser.
const READY_WITHIN: Duration = Duration::from_secs(120);

struct Browser {
    devtools: DevTools,
    page: PathBuf,
}

impl Browser {
    fn url(&self, fragment: &str) -> String {
        format!("file://{}#{fragment}", self.page.display())
    }

    /// The DOM after the page has done what the fragment asks; fails on any console error or
    /// uncaught exception.
    fn open(&mut self, fragment: &str) -> String {
        let url = self.url(fragment);
        let mut tab = self.devtools.open(&url);
        tab.wait_for("document.body.dataset.ready === 'yes'", READY_WITHIN);
        let dom = tab.eval("document.documentElement.outerHTML");
        assert!(
            tab.problems().is_empty(),
            "{fragment}: {:?}",
            tab.problems()
        );
        let dom = dom.as_str().expect("the page's HTML").to_string();
        assert!(
            !dom.contains("data-error="),
            "{fragment}: a script error: {dom}"
        );
        dom
    }
}

#[test]
fn the_playground_runs_in_a_headless_browser() {
    let path = chromium();
    let dir = std::env::temp_dir().join(format!("awl-playground-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut browser = Browser {
        devtools: DevTools::start(&path, &dir.join("profile"), "1400,1200"),
        page: build(),
    };
    let html = std::fs::read_to_string(&browser.page).unwrap();
    for outside in [
        "<script src",
        "<link",
        "@import",
        "url(",
        "http://",
        "https://",
    ] {
        assert!(!html.contains(outside), "the page loads nothing: {outside}");
    }

    let dom = browser.open("example=fig5_2_interrupt&run");
    assert!(element(&dom, "summary").contains("OB 3: requested 1, serviced 1"));
    assert!(element(&dom, "timeline").starts_with("<svg"));
    assert!(element(&dom, "timeline").contains("OB 3 serviced"));
    assert_eq!(element(&dom, "diagnostics"), "");

    let dom = browser.open("example=mistakes&run");
    assert_eq!(
        element(&dom, "summary"),
        "not run: 3 errors in the program\n"
    );
    let diagnostics = element(&dom, "diagnostics");
    assert!(diagnostics.contains("bit 9 of I 0 is out of range"));
    assert!(diagnostics.contains("help: did you mean `L`?"));
    assert!(
        dom.contains(r#"class="line error""#),
        "error lines are marked"
    );

    let dom = browser.open("example=speed7_stop&run");
    assert!(element(&dom, "summary").contains("mode at end: STOP"));
    assert!(element(&dom, "stop").contains("STOP OB85"));
    assert!(
        dom.contains(r#"class="line stopped""#),
        "the STOP line is marked"
    );

    // A STEP 7 text: `;` ends a statement, `//` comments, `#local` is a name.
    let dom = browser.open("example=motor_fb");
    assert!(!dom.contains(r#"<span class="t-comment">;"#), "{dom}");
    assert!(dom.contains(r#"<span class="t-comment">// Two conveyor motors"#));
    assert!(dom.contains(r#"<span class="t-keyword">FUNCTION_BLOCK</span>"#));
    assert!(dom.contains(r#"<span class="t-symbol">#"#));

    // The address the page writes after a run names the example's file.
    let dom = browser.open("example=fig5_2.awl&run");
    assert!(
        element(&dom, "summary").contains("simulated: 1000."),
        "{dom}"
    );
    assert!(element(&dom, "scenario-name").is_empty());

    let program = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n";
    let shared = format!("pname=mine.awl&program={}&cpu=speed7&run", encoded(program));
    let dom = browser.open(&shared);
    assert!(element(&dom, "summary").contains("cpu: speed7"), "{dom}");
    assert!(element(&dom, "program-name").contains("mine.awl"));

    let dom = browser.open("selftest");
    assert!(dom.contains(r#"data-selftest="passed""#), "{dom}");

    the_browser_gives_the_native_summaries(&browser.open("samples"));
    stop_ends_a_long_run_and_the_page_stays_responsive(&mut browser);

    let url = browser.url("example=fig5_2_interrupt&run");
    let mut tab = browser.devtools.open(&url);
    tab.wait_for("document.body.dataset.ready === 'yes'", READY_WITHIN);
    assert_shows_the_timeline(&tab.screenshot());
    drop(tab);
    drop(browser);
    let _ = std::fs::remove_dir_all(dir);
}

/// A program whose every cycle loops for 4.5 s of simulated time (under a watchdog of 6 s),
/// for an hour: in the browser it would run for many minutes.
const LONG_PROGRAM: &str = "OB 1
      JU FB 1
NAME :WAIT
      BE
FB 1
NAME :WAIT
      L  KF +5000
      T  FW 2
M001: L  KF +30000
M002: L  KF +1
      -F
      JN =M002
      L  FW 2
      L  KF +1
      -F
      T  FW 2
      JN =M001
      BE
";

const LONG_SCENARIO: &str =
    "program = \"long.awl\"\ncpu = \"speed7\"\nwatchdog = \"6s\"\nrun = { for = \"3600s\" }\n";

/// The simulated milliseconds the status line shows while a run goes on.
const SIMULATED_MS: &str =
    "(/^running: ([\\d,.]+) ms simulated/.exec($('status').textContent) || [])[1]";

fn simulated_ms(shown: &serde_json::Value) -> f64 {
    shown.as_str().unwrap().replace(',', "").parse().unwrap()
}

/// The long run goes to the worker: the page's timers fire and its progress line moves while it
/// runs, Stop ends it at once and says where, and the next run works. Esc stops a debugger's
/// `continue` the same way.
fn stop_ends_a_long_run_and_the_page_stays_responsive(browser: &mut Browser) {
    let fragment = format!(
        "pname=long.awl&program={}&sname=long.toml&scenario={}",
        encoded(LONG_PROGRAM),
        encoded(LONG_SCENARIO)
    );
    let url = browser.url(&format!("{fragment}&run"));
    let mut tab = browser.devtools.open(&url);
    let first = simulated_ms(&tab.wait_for(SIMULATED_MS, Duration::from_secs(30)));
    tab.eval("window.ticks = 0; setInterval(() => window.ticks++, 10); true");
    std::thread::sleep(Duration::from_millis(500));
    let ticks = tab.eval("window.ticks").as_u64().unwrap();
    assert!(
        ticks >= 10,
        "the page's timer fired {ticks} times in 0.5 s of the run"
    );
    let later = simulated_ms(&tab.eval(SIMULATED_MS));
    assert!(
        later > first,
        "the progress line moves on: {first} ms, then {later} ms"
    );

    tab.eval("$('stop-run').click(); true");
    let stopped =
        tab.eval("[$('status').textContent, $('summary').textContent, $('stop-run').hidden]");
    let status = stopped[0].as_str().unwrap().to_string();
    assert!(status.starts_with("stopped at "), "{stopped}");
    assert!(status.contains(" ms simulated, cycle "), "{stopped}");
    assert_eq!(stopped[1], format!("not finished: {status}\n"));
    assert_eq!(stopped[2], true, "the Stop button goes away");
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(
        tab.eval("$('status').textContent"),
        status.as_str(),
        "no word from the stopped run"
    );

    tab.eval("$('examples').value = 'fig5_2_interrupt.toml'; $('examples').dispatchEvent(new Event('change')); $('run').click(); true");
    let summary = "$('summary').textContent.includes('OB 3: requested 1, serviced 1')";
    tab.wait_for(summary, Duration::from_secs(30));
    assert!(tab.problems().is_empty(), "{:?}", tab.problems());
    drop(tab);

    let url = browser.url(&fragment);
    let mut tab = browser.devtools.open(&url);
    tab.wait_for("document.body.dataset.ready === 'yes'", READY_WITHIN);
    tab.eval("$('continue').click(); true");
    tab.wait_for(SIMULATED_MS, Duration::from_secs(30));
    tab.eval("document.dispatchEvent(new KeyboardEvent('keydown', { key: 'Escape' })); true");
    let status = tab.eval("$('status').textContent");
    assert!(
        status
            .as_str()
            .unwrap()
            .ends_with(": the debugger is where it was"),
        "{status}"
    );
    assert!(tab.problems().is_empty(), "{:?}", tab.problems());
    assert_eq!(tab.eval("document.body.dataset.error || ''"), "");
}

/// The wasm build and the native build run the same code: every sample prints the same.
fn the_browser_gives_the_native_summaries(dom: &str) {
    let summaries: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(&element(dom, "samples")).expect("the samples' summaries as JSON");
    let files = common::playground_files();
    let scenarios: Vec<&String> = files
        .keys()
        .filter(|name| name.ends_with(".toml"))
        .collect();
    assert_eq!(summaries.len(), scenarios.len());
    for name in scenarios {
        assert_eq!(
            summaries[name.as_str()],
            common::cli_summary(name).as_str(),
            "{name}"
        );
    }
}
