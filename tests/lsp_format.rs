//! The editor formatter (`awl lsp`): formatting formatted text changes nothing, and the
//! formatted program compiles to the same bytecode, for every sample program and for
//! generated statement lines.

use awl::frontend::{Frontend, Language, build_text_with, default_profile};
use awl::lsp::format::formatted;
use awl::lsp::text::FileLanguage;
use awl::source::{SourceFile, SourceSet};
use proptest::prelude::*;

fn build(text: &str) -> Frontend {
    let language = Language::default();
    let mut sources = SourceSet::default();
    sources.add(SourceFile::new("t.awl", text)).unwrap();
    build_text_with("t.awl", text, language, default_profile(&sources, language))
}

/// The program's bytecode and data, without where each statement was written.
fn bytecode(frontend: &Frontend) -> String {
    let program = &frontend.compiled.program;
    let blocks: Vec<String> = program
        .blocks
        .iter()
        .map(|block| format!("{} {:?}", block.id, block.code))
        .collect();
    let data: Vec<String> = program
        .data_blocks
        .iter()
        .map(|block| format!("{} {:?}", block.id, block.words))
        .collect();
    format!("{blocks:?}\n{data:?}")
}

/// Formats `text` and checks the formatter's two promises; the formatted text.
fn check(text: &str) -> String {
    let language = FileLanguage::of_text(text);
    let once = formatted(text, language);
    let twice = formatted(&once, FileLanguage::of_text(&once));
    assert_eq!(once, twice, "formatting is not idempotent");
    let (before, after) = (build(text), build(&once));
    assert_eq!(before.has_errors(), after.has_errors(), "{once}");
    if !before.has_errors() {
        assert_eq!(bytecode(&before), bytecode(&after), "{once}");
    }
    once
}

fn sample_programs() -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    let mut folders = vec![std::path::PathBuf::from("programs")];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|ext| ext == "awl") {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

#[test]
fn every_sample_program_formats_to_the_same_bytecode() {
    let programs = sample_programs();
    assert!(programs.len() > 10);
    let mut changed = 0;
    for path in programs {
        let text = std::fs::read_to_string(&path).unwrap();
        let once = std::panic::catch_unwind(|| check(&text))
            .unwrap_or_else(|_| panic!("{}", path.display()));
        changed += usize::from(once != text);
    }
    assert!(changed > 0, "the formatter changed no sample");
}

/// One STEP 5 statement line in the English set, with random blanks, label and comment.
fn statement_line() -> impl Strategy<Value = String> {
    let statements = prop::sample::select(vec![
        "A I 0.0",
        "AN F 1.7",
        "O Q 4.1",
        "= Q 4.0",
        "S F 20.0",
        "R F 20.0",
        "L KF +5",
        "L KT 030.1",
        "T FW 10",
        "L FW 10",
        "SD T 1",
        "A(",
        "O(",
        ")",
        "+F",
        "!=F",
        "NOP 0",
        "L KH 00FF",
        "JC =M002",
    ]);
    (
        statements,
        0..4usize,
        0..3usize,
        prop::bool::ANY,
        prop::bool::ANY,
    )
        .prop_map(|(statement, indent, gap, colon, comment)| {
            let statement = statement.replacen(' ', &" ".repeat(gap + 1), 1);
            let colon = if colon { ":" } else { "" };
            let comment = if comment { " ; note" } else { "" };
            format!("{}{colon}{statement}{comment}", " ".repeat(indent))
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn formatting_keeps_bytecode_and_is_idempotent(lines in prop::collection::vec(statement_line(), 1..12)) {
        let body: Vec<String> = lines
            .into_iter()
            .map(|line| line.replace("JC =M002", "JC =M001"))
            .collect();
        let text = format!(
            "OB 1\n      JU FB 1\nNAME :GEN\n      BE\nFB 1\nNAME :GEN\nM001 :A I 1.0\n{}\n      BE\n",
            body.join("\n")
        );
        check(&text);
    }
}
