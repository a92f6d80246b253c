//! Snapshot tests of the STEP 7 parser's diagnostics: one case per `awl::s7::…` code, rendered
//! with its source as `awl check` prints it.

use awl::diagnostics::{SourceDiagnostic, render_plain, report};
use awl::mnemonics::MnemonicSet;
use awl::source::{SourceFile, SourceSet};
use awl::step7::{ParseOptions, parse};

fn block(body: &str) -> String {
    format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n{body}END_ORGANIZATION_BLOCK\n")
}

/// Each code with a small file that shows it.
fn cases() -> Vec<(&'static str, String)> {
    vec![
        ("awl::s7::unexpected_character", block("      A     § 1;\n")),
        ("awl::s7::unknown_operation", block("      JUU   M001;\nM001: NOP 0;\n")),
        (
            "awl::s7::mixed_mnemonics",
            block("      A     I 0.0;\n      AN    I 0.1;\n      U     E 0.2;\n      =     Q 4.0;\n"),
        ),
        ("awl::s7::unknown_operand", block("      A     X 1.0;\n")),
        ("awl::s7::missing_operand", block("      L     ;\n")),
        ("awl::s7::unexpected_token", block("      L     5 6;\n")),
        ("awl::s7::bad_address", block("      A     I 0.8;\n")),
        ("awl::s7::bad_constant", block("      L     W#16#XY;\n")),
        ("awl::s7::constant_range", block("      L     S5T#3H;\n")),
        (
            "awl::s7::bad_declaration",
            "FUNCTION FC 1 : VOID\nVAR_TEMP\n  values : ARRAY [5..1] OF INT;\nEND_VAR\nBEGIN\nEND_FUNCTION\n"
                .into(),
        ),
        (
            "awl::s7::unknown_type",
            "FUNCTION FC 1 : VOID\nVAR_TEMP\n  speed : INTT;\nEND_VAR\nBEGIN\nEND_FUNCTION\n".into(),
        ),
        (
            "awl::s7::unclosed_block",
            "FUNCTION FC 1 : VOID\nBEGIN\n      NOP 0;\n\nFUNCTION FC 2 : VOID\nBEGIN\nEND_FUNCTION\n"
                .into(),
        ),
        (
            "awl::s7::mismatched_end",
            "FUNCTION FC 1 : VOID\nBEGIN\n      NOP 0;\nEND_FUNCTION_BLOCK\n".into(),
        ),
        (
            "awl::s7::outside_block",
            format!("stray text\n{}", block("      NOP 0;\n")),
        ),
        (
            "awl::s7::block_number",
            "FUNCTION FC 70000 : VOID\nBEGIN\nEND_FUNCTION\n".into(),
        ),
        ("awl::s7::bad_label", block("LOOPS: NOP 0;\n")),
        ("awl::s7::step5_spelling", block("      L     KT 50.1;\n")),
        (
            "awl::s7::extension_not_enabled",
            block("      __ASSERT== MW 0, 5;\n"),
        ),
    ]
}

#[test]
fn every_step7_code_renders() {
    for (code, source) in cases() {
        let mut sources = SourceSet::default();
        let file = sources
            .add(SourceFile::new("example.awl", source.clone()))
            .expect("one file");
        let parsed = parse(file, &source, ParseOptions::default());
        let codes: Vec<String> = parsed
            .errors
            .iter()
            .map(|error| error.stable_code())
            .collect();
        let rendered: Vec<String> = parsed
            .errors
            .into_iter()
            .map(|error| render_plain(&report(&sources, &SourceDiagnostic::Step7(error))))
            .collect();
        let all = rendered.join("\n");
        assert_eq!(
            codes,
            [code],
            "exactly this code, no follow-on errors, for:\n{source}\n---\n{all}"
        );
        insta::assert_snapshot!(code.replace("::", "__"), all, &source);
    }
}

/// Every documented STEP 7 code has a case above.
#[test]
fn cases_cover_the_step7_codes() {
    let doc = std::fs::read_to_string("grammar/errors.md").unwrap();
    let covered: Vec<&str> = cases().iter().map(|(code, _)| *code).collect();
    let documented: Vec<&str> = doc
        .lines()
        .filter_map(|line| line.strip_prefix("### "))
        .map(|line| line.split_whitespace().next().unwrap())
        .filter(|code| code.starts_with("awl::s7::"))
        .collect();
    assert!(documented.len() >= 18);
    for code in documented {
        assert!(covered.contains(&code), "{code} has no snapshot case");
    }
}

/// A file with three bad lines gives three errors, and the good lines around them are kept.
#[test]
fn three_bad_lines_give_three_errors() {
    let source = block(
        "      A     I 0.0;\n      L     KF +5;\n      =     Q 4.0;\n      JUU   M1;\n      A     I 9.9;\n      BEU;\n",
    );
    let parsed = parse(0, &source, ParseOptions::default());
    assert_eq!(parsed.errors.len(), 3, "{:#?}", parsed.errors);
    let lines: Vec<usize> = parsed
        .errors
        .iter()
        .map(|error| source[..error.span().start as usize].matches('\n').count() + 1)
        .collect();
    assert_eq!(lines, [4, 6, 7]);
    let awl::step7::ast::S7Body::Logic(statements) = &parsed.unit.blocks[0].body else {
        panic!("a logic block");
    };
    assert_eq!(statements.len(), 3);
}

/// A German file forced to English reads its words as English ones: `U` is then foreign.
#[test]
fn forcing_the_set_overrides_detection() {
    let source = block("      U     E 0.0;\n      =     A 4.0;\n");
    let forced = parse(
        0,
        &source,
        ParseOptions {
            mnemonics: Some(MnemonicSet::English),
            extensions: false,
        },
    );
    assert_eq!(forced.unit.mnemonics, MnemonicSet::English);
    assert_eq!(forced.errors.len(), 1);
    assert_eq!(forced.errors[0].stable_code(), "awl::s7::mixed_mnemonics");
    let detected = parse(0, &source, ParseOptions::default());
    assert_eq!(detected.unit.mnemonics, MnemonicSet::German);
    assert!(detected.errors.is_empty());
}
