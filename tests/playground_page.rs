//! The playground page in a real browser: `web/build.sh` builds the one-file page (awl as
//! WebAssembly), headless Chromium opens it from the file system and runs examples through the
//! address fragment — one that services an interrupt, one with source errors, one that goes to
//! STOP — then drives the step controls and live mode (`#selftest`), runs every sample in the
//! browser to compare its summary with the native one, and takes a screenshot that is not blank.
//! Skipped, with the reason printed, only where Chromium or the wasm32 target is missing.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::browser::{assert_screenshot_shows_the_timeline, chromium, console_errors, headless};

/// Whether the wasm32 target is installed (`.ci/run` installs it through web/build.sh).
fn wasm_target_installed() -> bool {
    let installed = Command::new("rustup")
        .args(["target", "list", "--installed"])
        .output();
    installed.is_ok_and(|output| {
        String::from_utf8_lossy(&output.stdout)
            .lines()
            .any(|target| target == "wasm32-unknown-unknown")
    })
}

/// Builds the page; its path.
fn build() -> PathBuf {
    let output = Command::new("web/build.sh").output().expect("bash runs");
    assert!(
        output.status.success(),
        "web/build.sh failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let page = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/web/awl-playground.html");
    let size = std::fs::metadata(&page).expect("the page is built").len();
    assert!(size < 3_000_000, "the page is {size} bytes");
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

struct Browser {
    path: PathBuf,
    page: PathBuf,
    dir: PathBuf,
}

impl Browser {
    /// The DOM after the page has done what the fragment asks; fails on any console error or
    /// uncaught exception.
    fn open(&self, fragment: &str) -> String {
        let url = format!("file://{}#{fragment}", self.page.display());
        let profile = self.dir.join(format!("profile-{}", fragment.len()));
        let (dom, log) = headless(
            &self.path,
            &profile,
            &["--virtual-time-budget=10000", "--dump-dom", &url],
        );
        assert!(
            console_errors(&log).is_empty(),
            "{fragment}: {:?}",
            console_errors(&log)
        );
        assert!(dom.contains(r#"data-ready="yes""#), "{fragment}: {log}");
        assert!(
            !dom.contains("data-error="),
            "{fragment}: a script error: {dom}"
        );
        dom
    }
}

#[test]
fn the_playground_runs_in_a_headless_browser() {
    let Some(path) = chromium() else {
        println!("skipped: no chromium on this machine (.ci/run installs it)");
        return;
    };
    if !wasm_target_installed() {
        println!(
            "skipped: the wasm32-unknown-unknown target is not installed (.ci/run installs it)"
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("awl-playground-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let browser = Browser {
        path,
        page: build(),
        dir: dir.clone(),
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
    let url = format!(
        "file://{}#example=fig5_2_interrupt&run",
        browser.page.display()
    );
    assert_screenshot_shows_the_timeline(&browser.path, &dir, "1400,1200", &url);
    let _ = std::fs::remove_dir_all(dir);
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
