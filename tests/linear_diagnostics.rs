//! Error-heavy files cost work in proportion to their size: every diagnostic reads only the
//! lines around its span, found through the file's line index. The work is counted (bytes of
//! source the rendering read), not timed. Alone in its test binary, so the count is this
//! test's.

use awl::diagnostics::{render_plain, report};
use awl::frontend;
use awl::profile;
use awl::source::snippet_bytes_read;

/// `n` blocks `PB 0`…`PB 255` over and over: every block after the 256th is a duplicate.
fn duplicates(n: usize) -> String {
    (0..n)
        .map(|i| format!("PB {}\n      BE\n", i % 256))
        .collect()
}

/// Source bytes read to render every diagnostic of `text`, and the number of diagnostics.
fn rendering_work(text: &str) -> (u64, usize) {
    let built = frontend::build_text("dup.awl", text, profile::find("sinumerik-840c").unwrap());
    let before = snippet_bytes_read();
    for diagnostic in &built.diagnostics {
        render_plain(&report(&built.sources, diagnostic));
    }
    (snippet_bytes_read() - before, built.diagnostics.len())
}

#[test]
fn rendering_grows_linearly_with_the_errors() {
    let (small, small_count) = rendering_work(&duplicates(20_000));
    let (large, large_count) = rendering_work(&duplicates(40_000));
    assert_eq!(small_count, 20_000 - 256);
    assert_eq!(large_count, 40_000 - 256);
    assert!(small > 0, "diagnostics read through the line index");
    // Each diagnostic reads a few lines around its span, wherever it is in the file: the
    // same bytes per diagnostic in both files (a rescan from the start would double them).
    let per_small = small as f64 / small_count as f64;
    let per_large = large as f64 / large_count as f64;
    assert!(per_small < 100.0, "{per_small} bytes per diagnostic");
    assert!(
        (per_large / per_small - 1.0).abs() < 0.05,
        "{per_small} vs {per_large} bytes per diagnostic"
    );
}

#[test]
fn the_command_line_shows_the_first_thousand_and_counts_the_rest() {
    let dir = std::path::Path::new("target/test-linear");
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join("dup.awl");
    std::fs::write(&path, duplicates(20_000)).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.matches("awl::check::duplicate_block").count(), 1000);
    assert!(
        stderr.ends_with(
            "awl: 18744 more diagnostics not shown (the first 1000 are above)\nawl check: 19744 errors, 0 warnings in 1 file\nnote: no CPU profile compiles it without errors\n"
        ),
        "{}",
        &stderr[stderr.len() - 300..]
    );
}
