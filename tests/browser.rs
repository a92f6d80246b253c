//! The timeline page in a real browser: headless Chromium opens the `.html` timeline from the
//! file system (no server, no network), runs its script without a console error, zooms and
//! shows a mark's details (the page's `#selftest`), and draws a screenshot that is not blank.
//! Without Chromium the test fails, saying how to install it (`.ci/run` installs Debian's
//! `chromium`).

mod common;

use std::process::Command;

use common::browser::{assert_screenshot_shows_the_timeline, chromium, console_errors, headless};

#[test]
fn the_html_timeline_works_in_a_headless_browser() {
    let browser = chromium();
    let dir = std::env::temp_dir().join(format!("awl-browser-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let page = dir.join("nested.html");
    let status = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["run", "--scenario", "programs/nested.toml", "--timeline"])
        .arg(&page)
        .output()
        .expect("awl runs");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let url = format!("file://{}#selftest", page.display());

    let (dom, log) = headless(
        &browser,
        &dir.join("profile-dom"),
        &["--virtual-time-budget=5000", "--dump-dom", &url],
    );
    assert!(
        console_errors(&log).is_empty(),
        "{:?}",
        console_errors(&log)
    );
    assert!(
        dom.contains(r#"data-ready="yes""#),
        "the script ran to its end:\n{log}"
    );
    assert!(!dom.contains(r#"data-error=""#), "a script error: {dom}");
    assert!(
        dom.contains(r#"data-selftest="passed""#),
        "zoom and hover work"
    );
    let html = std::fs::read_to_string(&page).unwrap();
    for outside in ["src=", "href=", "<link", "@import", "url("] {
        assert!(!html.contains(outside), "the page loads nothing: {outside}");
    }

    let url = format!("file://{}", page.display());
    assert_screenshot_shows_the_timeline(&browser, &dir, "1400,600", &url);
    let _ = std::fs::remove_dir_all(dir);
}
