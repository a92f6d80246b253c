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

/// `awl check` on `text` written to `target/test-linear/NAME`: its exit code and stderr.
fn check(name: &str, text: &str) -> (Option<i32>, String) {
    let dir = std::path::Path::new("target/test-linear");
    std::fs::create_dir_all(dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["check", path.to_str().unwrap()])
        .output()
        .unwrap();
    (
        output.status.code(),
        String::from_utf8(output.stderr).unwrap(),
    )
}

/// Each block defined again and again: three reports of each, then one line counting the
/// rest, where the last of them stood.
#[test]
fn the_command_line_shows_three_of_each_error_and_counts_the_rest() {
    let (code, stderr) = check("dup.awl", &duplicates(20_000));
    assert_eq!(code, Some(1));
    let reports = stderr
        .lines()
        .filter(|line| *line == "awl::check::duplicate_block")
        .count();
    assert_eq!(reports, 3 * 256);
    assert!(stderr.contains(
        "… and 75 more like this (awl::check::duplicate_block: PB 0 is defined twice)\n"
    ));
    assert_eq!(stderr.matches(" more like this ").count(), 256);
    assert!(
        stderr.ends_with(
            "awl check: 19744 errors, 0 warnings in 1 file\nnote: no CPU profile compiles it without errors\n"
        ),
        "{}",
        &stderr[stderr.len() - 300..]
    );
}

/// 1,200 different errors: the first thousand, then a count of the rest.
#[test]
fn the_command_line_shows_the_first_thousand_and_counts_the_rest() {
    let statements: String = (0..1200).map(|i| format!("      A  =S{i}\n")).collect();
    let (code, stderr) = check(
        "symbols.awl",
        // With a DES line the FB's formal operands are its declarations, not guessed from use.
        &format!("FB 1\nNAME :X\nDES  :Y  I BI\n{statements}      BE\n"),
    );
    assert_eq!(code, Some(1));
    assert_eq!(stderr.matches("awl::check::undefined_symbol").count(), 1000);
    assert!(
        stderr.ends_with(
            "awl: 200 more diagnostics not shown (the first 1000 are above)\nawl check: 1200 errors, 0 warnings in 1 file\nnote: no CPU profile compiles it without errors\n"
        ),
        "{}",
        &stderr[stderr.len() - 300..]
    );
}
