//! Source files as they come: byte-order marks, UTF-16, lone CRs, control characters, and more
//! files than a span can name.

use awl::diagnostics::{render_plain, report};
use awl::frontend::{self, SourceError};
use awl::profile;

fn rendered(path: &str) -> Vec<String> {
    let sources = frontend::read_sources(&[path]).unwrap();
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
    let paths = vec!["tests/inputs/bom.awl"; 65_537];
    let errors = frontend::read_sources(&paths).unwrap_err();
    assert!(matches!(
        errors[..],
        [SourceError::TooMany { count: 65_537 }]
    ));
    assert_eq!(
        frontend::read_sources(&paths[..65_536])
            .unwrap()
            .files
            .len(),
        65_536
    );
}
