//! Headless Chromium for the tests of pages: `.ci/run` installs Debian's `chromium`; where it
//! is missing the tests say so and skip.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The Chromium on this machine, if any.
pub fn chromium() -> Option<PathBuf> {
    ["chromium", "chromium-browser", "google-chrome"]
        .into_iter()
        .find_map(|name| {
            let found = Command::new("which").arg(name).output().ok()?;
            let path = String::from_utf8_lossy(&found.stdout).trim().to_string();
            (found.status.success() && !path.is_empty()).then(|| PathBuf::from(path))
        })
}

/// Runs Chromium headless with its own profile directory; its stdout and log.
pub fn headless(browser: &Path, profile: &Path, args: &[&str]) -> (String, String) {
    let output = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-quic",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
        ])
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
/// error, not blank (a twentieth of it drawn), and OB 1's lane colour on the screen (the
/// timeline is drawn).
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
    let pixmap = resvg::tiny_skia::Pixmap::load_png(&shot).expect("a PNG screenshot");
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
