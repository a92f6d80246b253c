//! Source files as they come: byte-order marks, UTF-16, lone CRs, control characters, and more
//! files than a span can name.

use std::path::PathBuf;

use awl::diagnostics::{render_plain, report};
use awl::frontend;
use awl::profile;
use awl::program_files::read_program;
use awl::source::Files;

fn paths(names: &[&str]) -> Vec<PathBuf> {
    names.iter().map(PathBuf::from).collect()
}

fn rendered(path: &str) -> Vec<String> {
    let sources = read_program(&Files::Disk, &paths(&[path]), &[])
        .unwrap()
        .sources;
    let built = frontend::build(
        sources,
        frontend::Language::default(),
        profile::find("sinumerik-840c").unwrap(),
    );
    built
        .diagnostics
        .iter()
        .map(|d| render_plain(&report(&built.sources, d)))
        .collect()
}

#[test]
fn byte_order_marks_are_read() {
    assert!(rendered("tests/inputs/bom.awl").is_empty());
    assert!(rendered("tests/inputs/utf16.awl").is_empty());
}

#[test]
fn a_cr_only_file_has_its_line_numbers() {
    let all = rendered("tests/inputs/cr_only.awl");
    assert_eq!(all.len(), 1);
    assert!(all[0].contains("cr_only.awl:3:7"), "{}", all[0]);
    assert!(all[0].contains(" 3 │       XYZ Q 4.0"), "{}", all[0]);
    assert!(!all[0].contains(" 0 │"), "{}", all[0]);
}

#[test]
fn control_characters_are_shown_as_pictures() {
    let all = rendered("tests/inputs/control.awl").join("\n");
    assert!(all.contains('\u{2407}'), "BEL as ␇: {all}");
    assert!(
        !all.chars().any(|c| c.is_control() && c != '\n'),
        "no raw control character reaches the terminal: {all:?}"
    );
}

#[test]
fn more_files_than_a_span_can_name_are_an_error() {
    let paths = paths(&vec!["tests/inputs/bom.awl"; 65_537]);
    let errors = read_program(&Files::Disk, &paths, &[]).unwrap_err();
    assert_eq!(errors.len(), 1);
    assert_eq!(
        errors[0].to_string(),
        "65537 source files: awl reads at most 65,536 at once"
    );
    assert_eq!(
        read_program(&Files::Disk, &paths[..65_536], &[])
            .unwrap()
            .sources
            .files
            .len(),
        65_536
    );
}

#[test]
fn a_binary_file_is_one_error_text_with_odd_bytes_is_text() {
    for binary in [
        "tests/inputs/binary/program.s5d",
        "tests/inputs/binary/noise.awl",
    ] {
        let errors = read_program(&Files::Disk, &paths(&[binary]), &[]).unwrap_err();
        assert_eq!(errors.len(), 1, "{binary}");
        assert!(
            errors[0].to_string().contains("is not STL text"),
            "{binary}"
        );
    }
    let text = [
        "tests/inputs/bom.awl",
        "tests/inputs/utf16.awl",
        "tests/inputs/cr_only.awl",
        "tests/inputs/control.awl",
    ];
    assert!(read_program(&Files::Disk, &paths(&text), &[]).is_ok());
}
