//! Which dialect a text is read in when `--dialect` does not say: STEP 7 source form, the words
//! only one dialect writes, and, where those are missing or disagree, the dialect the text
//! compiles in, with a note. STEP 7 words in a STEP 5 text get help naming `--dialect s7`; bare
//! names in a STEP 7 block are its variables or symbols; a call's errors are reported together.

mod common;

use awl::dialect::Dialect;
use awl::frontend::{self, Frontend, Language};
use awl::source::{SourceFile, SourceSet};
use awl::step7::ast::{PathPart, S7BlockKind, S7BlockRef, S7Body, S7Operand};
use common::step7::passes;
use miette::Diagnostic;

fn input(name: &str) -> String {
    std::fs::read_to_string(format!("tests/inputs/dialect/{name}")).unwrap()
}

/// Built as `awl check` builds it: the CPU is the default of the dialect the text is read in.
fn check_with(text: &str, language: Language, tables: &[(&str, &str)]) -> Frontend {
    let mut sources = SourceSet::default();
    sources.add(SourceFile::new("p.awl", text)).unwrap();
    let profile = frontend::default_profile(&sources, language);
    let tables = tables
        .iter()
        .map(|(name, text)| SourceFile::new(*name, *text))
        .collect();
    frontend::build_with_symbols(sources, tables, language, profile)
}

fn check(text: &str) -> Frontend {
    check_with(text, Language::default(), &[])
}

fn forced(text: &str, dialect: Dialect) -> Frontend {
    let language = Language {
        dialect: Some(dialect),
        ..Language::default()
    };
    check_with(text, language, &[])
}

fn codes(built: &Frontend) -> Vec<String> {
    built
        .diagnostics
        .iter()
        .map(|d| d.code().map(|code| code.to_string()).unwrap_or_default())
        .collect()
}

/// The diagnostic's message, labels and help in one string.
fn text_of(built: &Frontend, code: &str) -> String {
    let diagnostic = built
        .diagnostics
        .iter()
        .find(|d| d.code().is_some_and(|c| c.to_string() == code))
        .unwrap_or_else(|| panic!("no {code} in {:?}", codes(built)));
    let labels: Vec<String> = diagnostic
        .labels()
        .into_iter()
        .flatten()
        .filter_map(|label| label.label().map(str::to_string))
        .collect();
    format!(
        "{diagnostic} | {} | {}",
        labels.join(" | "),
        diagnostic.help().map(|h| h.to_string()).unwrap_or_default()
    )
}

fn is_step7(built: &Frontend) -> bool {
    !built.s7_units.is_empty()
}

const NOTE: &str = "awl::dialect::read_as_step7";

#[test]
fn a_flat_step7_statement_list_is_step7_and_ob_1() {
    let built = check(&input("parking.awl"));
    assert_eq!(codes(&built), [NOTE]);
    assert!(is_step7(&built));
    let text = text_of(&built, NOTE);
    assert!(text.contains("`LW 2`: a STEP 7 operand area"), "{text}");
    assert!(text.contains("OB 1"), "{text}");
    let blocks = &built.s7_units[0].blocks;
    assert_eq!(blocks.len(), 1);
    assert!(matches!(
        blocks[0].name,
        S7BlockRef::Number {
            kind: S7BlockKind::Ob,
            number: 1
        }
    ));
}

#[test]
fn a_flat_step7_statement_list_runs() {
    // 25 places, counter 0: the entry is free, 25 free places shown as BCD 16#25.
    passes(
        &input("parking.awl"),
        "run = { cycles = 1 }\n[expect]\n\"A 4.0\" = true\n\"AW 6\" = 37\n",
    );
}

#[test]
fn step7_only_operations_decide_alone() {
    for word in [
        "ITB", "BTI", "ITD", "DTR", "RND", "LOOP", "SPL", "TAR1", "+I", "==I", "<>R",
    ] {
        let built = check(&format!("      L     MW 10\n      {word}\n"));
        let text = text_of(&built, NOTE);
        assert!(
            text.contains(&format!("`{word}`: a STEP 7 operation")),
            "{word}: {text}"
        );
    }
}

#[test]
fn a_forum_fragment_with_jumps_to_bare_labels_is_step7() {
    let built = check(&input("forum_jumps.awl"));
    assert_eq!(codes(&built), [NOTE]);
    let text = text_of(&built, NOTE);
    assert!(text.contains("`m1`: a STEP 7 jump label"), "{text}");
    passes(
        &input("forum_jumps.awl"),
        "run = { cycles = 1 }\n[expect]\n\"MW 10\" = 100\n",
    );
}

#[test]
fn an_ambiguous_text_is_read_in_the_dialect_it_compiles_in() {
    let built = check(&input("ambiguous.awl"));
    assert_eq!(codes(&built), [NOTE]);
    assert!(is_step7(&built));
    let text = text_of(&built, NOTE);
    assert!(
        text.contains("as STEP 5: a constant needs its format: `L KF +30`"),
        "{text}"
    );
    assert!(text.contains("compiles as STEP 7"), "{text}");
    assert!(text.contains("1 error as STEP 5"), "{text}");
}

#[test]
fn a_text_that_compiles_as_step5_stays_step5() {
    for text in [
        "      A     I 0.0\n      =     Q 4.0\n",
        "OB 1\n      L     KF +30\n      T     FW 10\n      BE\n",
        "OB 1\n      L     KF +30\n      T     MW 10\n      BE\n",
    ] {
        let built = check(text);
        assert!(!is_step7(&built), "{text}");
        assert!(!codes(&built).contains(&NOTE.to_string()), "{text}");
        assert!(!built.has_errors(), "{text}: {:?}", codes(&built));
    }
}

#[test]
fn step7_words_in_a_step5_text_name_dialect_s7() {
    let built = check(&input("step5_with_step7_words.awl"));
    assert!(!is_step7(&built));
    assert_eq!(
        codes(&built),
        ["awl::parse::step7_word", "awl::parse::step7_word"]
    );
    let helps: Vec<String> = built
        .diagnostics
        .iter()
        .map(|d| d.help().unwrap().to_string())
        .collect();
    // `+I` has a STEP 5 spelling: `+F`.
    assert!(helps[0].contains("STEP 5 writes `+F`"), "{}", helps[0]);
    assert!(helps[1].contains("`DUF`"), "{}", helps[1]);
    for help in &helps {
        assert!(help.contains("--dialect s7"), "{help}");
    }
}

#[test]
fn step7_words_forced_to_step5_name_their_step5_spelling() {
    let cases = [
        ("      L     MW 10\n      ITB\n", "STEP 5 writes `DUF`"),
        (
            "      L     FW 10\n      L     FW 12\n      +I\n",
            "STEP 5 writes `+F`",
        ),
        (
            "      L     FW 10\n      L     FW 12\n      ==I\n",
            "STEP 5 writes `!=F`",
        ),
        (
            "      L     FW 10\n      L     FW 12\n      >=R\n",
            "STEP 5 writes `>=G`",
        ),
        ("      L     LW 2\n", "STEP 5 has no operand area `LW`"),
        ("      JU    m1\nm1:   NOP 0\n", "`=m1`"),
        ("      LOOP  next\n", "STEP 5 has no `LOOP`"),
        (
            "      L     2#1010\n",
            "STEP 5 writes a constant with its format",
        ),
        (
            "      A(\n      XN(\n",
            "STEP 5 opens brackets with `A(` and `O(` only",
        ),
    ];
    for (text, help) in cases {
        let built = forced(text, Dialect::Step5);
        let found = text_of(&built, "awl::parse::step7_word");
        assert!(found.contains(help), "{text}: {found}");
        assert!(found.contains("--dialect s7"), "{text}: {found}");
    }
}

#[test]
fn a_step7_source_forced_to_step5_names_the_dialect_option() {
    let built = forced(&input("motor_fb.awl"), Dialect::Step5);
    assert_eq!(codes(&built), ["awl::parse::step7_source"]);
    let text = text_of(&built, "awl::parse::step7_source");
    assert!(text.contains("--dialect s7"), "{text}");
    assert!(!text.contains("Rewrite"), "{text}");
}

#[test]
fn a_bare_name_the_block_declares_is_its_variable() {
    let program = "FUNCTION_BLOCK FB 1\nVAR_INPUT\n  position1 : INT;\n  start : BOOL;\nEND_VAR\nBEGIN\n      L     position1;\n      T     MW 10;\n      A     start;\n      =     Q 0.0;\nEND_FUNCTION_BLOCK\n\nDATA_BLOCK DB 1\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL  FB 1, DB 1 (position1 := 7, start := TRUE);\nEND_ORGANIZATION_BLOCK\n";
    let built = check(program);
    assert_eq!(codes(&built), Vec::<String>::new());
    let S7Body::Logic(statements) = &built.s7_units[0].blocks[0].body else {
        panic!("FB 1 has statements");
    };
    let S7Operand::Local(path) = &statements[0].operand else {
        panic!("{:?}", statements[0].operand);
    };
    assert!(matches!(&path[0], PathPart::Member(name) if name.text == "position1"));
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MW 10\" = 7\n\"Q 0.0\" = true\n",
    );
}

#[test]
fn a_bare_ret_val_is_the_function_s_value() {
    let program = "FUNCTION FC 1 : INT\nVAR_INPUT\n  x : INT;\nEND_VAR\nBEGIN\n      L     x;\n      L     2;\n      *I;\n      T     RET_VAL;\nEND_FUNCTION\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL  FC 1 (x := 21, RET_VAL := MW 4);\nEND_ORGANIZATION_BLOCK\n";
    assert_eq!(codes(&check(program)), Vec::<String>::new());
    passes(program, "run = { cycles = 1 }\n[expect]\n\"MW 4\" = 42\n");
}

#[test]
fn a_quoted_name_stays_the_symbol_even_where_the_block_declares_it() {
    let program = "FUNCTION FC 1 : VOID\nVAR_INPUT\n  start : BOOL;\nEND_VAR\nBEGIN\n      A     \"start\";\n      =     Q 0.0;\nEND_FUNCTION\n";
    let built = check(program);
    assert_eq!(codes(&built), ["awl::symbols::unknown"]);
    let text = text_of(&built, "awl::symbols::unknown");
    assert!(text.contains("unknown symbol `\"start\"`"), "{text}");
}

#[test]
fn any_other_bare_name_is_a_symbol() {
    let built = check(&input("motor_fb.awl"));
    let text = text_of(&built, "awl::symbols::unknown");
    assert!(text.contains("unknown symbol `positon2`"), "{text}");
    assert!(
        text.contains("did you mean `position1`, a variable of FB 1?"),
        "{text}"
    );
    assert!(text.contains("--symbols FILE"), "{text}");
    // With a table: the closest names, and the name that is in it stands for its address.
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A     Start;\n      =     Motr;\nEND_ORGANIZATION_BLOCK\n";
    let table = ("t.csv", "Start;I 0.0;BOOL;\nMotor;Q 4.0;BOOL;\n");
    let built = check_with(program, Language::default(), &[table]);
    assert_eq!(codes(&built), ["awl::symbols::unknown"]);
    let text = text_of(&built, "awl::symbols::unknown");
    assert!(text.contains("unknown symbol `Motr`"), "{text}");
    assert!(text.contains("did you mean `\"Motor\"`?"), "{text}");
}

#[test]
fn a_call_reports_a_wrong_actual_type_and_a_missing_parameter_together() {
    let built = check(&input("motor_fb.awl"));
    assert_eq!(
        codes(&built),
        [
            "awl::symbols::unknown",
            "awl::check::param_count",
            "awl::check::param_mismatch"
        ]
    );
    let count = text_of(&built, "awl::check::param_count");
    assert!(count.contains("missing: COUNT"), "{count}");
    assert!(!count.contains("ENABLE"), "{count}");
    let mismatch = text_of(&built, "awl::check::param_mismatch");
    assert!(
        mismatch.contains("parameter `enable` of FC 2"),
        "{mismatch}"
    );
    assert!(mismatch.contains("expected BOOL"), "{mismatch}");
}

#[test]
fn an_fb_parameter_of_another_width_is_an_error() {
    let program = "FUNCTION_BLOCK FB 1\nVAR_INPUT\n  on : BOOL;\nEND_VAR\nBEGIN\n      A     #on;\n      =     Q 0.0;\nEND_FUNCTION_BLOCK\n\nDATA_BLOCK DB 1\nFB 1\nBEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL  FB 1, DB 1 (on := MW 2);\nEND_ORGANIZATION_BLOCK\n";
    let built = check(program);
    assert_eq!(codes(&built), ["awl::check::param_mismatch"]);
    let text = text_of(&built, "awl::check::param_mismatch");
    assert!(text.contains("parameter `on` of FB 1"), "{text}");
}
