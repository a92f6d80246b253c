//! Keeps the grammar, the mnemonic table, the error pages and the parser in step.

use awl::frontend;
use awl::mnemonics::{self, MnemonicSet, OPERATIONS, OpCode, OpInfo};
use awl::profile;

fn read(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|error| panic!("{path}: {error}"))
}

/// A function block that uses one operation, with what it needs around it.
fn program_with(set: MnemonicSet, info: &OpInfo) -> String {
    let (des, input, op, operand) = match set {
        MnemonicSet::English => ("DES", "I", info.en, info.example_en),
        MnemonicSet::German => ("BEZ", "E", info.de, info.example_de),
    };
    let (before, after) = bracket_partners(set, info.op);
    let tail = if op == "BE" {
        ""
    } else {
        "M001 :NOP 0\n      BE\n"
    };
    format!(
        "FB 1\nNAME :TEST\n{des} :X {input} BI\n{des} :TIM T\n{des} :KON D KF\n{before}      {op} {operand}\n{after}{tail}{SUPPORT}"
    )
}

/// A bracket needs its partner, or the block does not compile.
fn bracket_partners(set: MnemonicSet, op: OpCode) -> (String, String) {
    match op {
        OpCode::AndBracket | OpCode::OrBracket => (String::new(), "      )\n".into()),
        OpCode::CloseBracket => (
            format!("      {}\n", mnemonics::op_word(set, OpCode::AndBracket)),
            String::new(),
        ),
        _ => (String::new(), String::new()),
    }
}

/// The blocks the examples call and open.
const SUPPORT: &str = "PB 3\n      BE\nFB 5\n      BE\nDB 10\n 0: KF +1\n";

#[test]
fn every_operation_parses_and_compiles_in_both_sets() {
    let cpu = profile::find("sinumerik-840c").unwrap();
    for info in OPERATIONS {
        for set in [MnemonicSet::English, MnemonicSet::German] {
            let source = program_with(set, info);
            let mut sources = awl::source::SourceSet::default();
            sources.add(awl::source::SourceFile::new("op.awl", source.clone()));
            let built = frontend::build(sources, frontend::Language::with_mnemonics(set), cpu);
            assert!(
                built.diagnostics.is_empty(),
                "{set:?} `{}`:\n{source}\n{:#?}",
                info.en,
                built.diagnostics
            );
            let fb = built
                .compiled
                .program
                .blocks
                .iter()
                .find(|b| b.id.kind == mnemonics::BlockKind::Fb)
                .unwrap();
            let (before, after) = bracket_partners(set, info.op);
            let partners = [before, after].iter().filter(|s| !s.is_empty()).count();
            let expected = if info.op == OpCode::BlockEnd {
                1
            } else {
                3 + partners
            };
            assert_eq!(fb.code.len(), expected, "{}: one op per statement", info.en);
        }
    }
}

#[test]
fn detection_picks_the_set_without_override() {
    let cpu = profile::find("sinumerik-840c").unwrap();
    for info in OPERATIONS
        .iter()
        .filter(|info| info.op != mnemonics::OpCode::BlockEnd)
    {
        let (before, after) = bracket_partners(MnemonicSet::German, info.op);
        let german = format!(
            "FB 1\nNAME :TEST\nBEZ :X E BI\nBEZ :TIM T\nBEZ :KON D KF\n      U E 0.0\n{before}      {} {}\n{after}M001 :NOP 0\n      BE\n{SUPPORT}",
            info.de, info.example_de
        );
        let built = frontend::build_text("de.awl", &german, cpu);
        assert!(
            built.diagnostics.is_empty(),
            "{}: {:#?}",
            info.de,
            built.diagnostics
        );
    }
}

#[test]
fn every_mnemonic_is_in_the_table_doc() {
    let doc = read("grammar/mnemonics.md");
    for info in OPERATIONS {
        assert!(
            doc.contains(&format!("| `{}` | `{}` |", info.en, info.de)),
            "{} / {} missing",
            info.en,
            info.de
        );
    }
    for area in mnemonics::AREAS {
        assert!(
            doc.contains(&format!("| `{}` | `{}` |", area.en, area.de)),
            "{} missing",
            area.en
        );
    }
    for constant in mnemonics::CONSTANTS {
        assert!(
            doc.contains(&format!("| `{}` | `{}` |", constant.en, constant.de)),
            "{} missing",
            constant.en
        );
    }
}

#[test]
fn every_english_word_is_a_terminal_of_the_grammar() {
    let grammar = read("grammar/stl.ebnf");
    let words = OPERATIONS
        .iter()
        .map(|info| info.en)
        .chain(mnemonics::AREAS.iter().map(|area| area.en))
        .chain(mnemonics::CONSTANTS.iter().map(|constant| constant.en))
        .chain(mnemonics::BlockKind::ALL.iter().map(|kind| kind.name()));
    for word in words {
        assert!(
            grammar.contains(&format!("\"{word}\"")),
            "\"{word}\" is not in grammar/stl.ebnf"
        );
    }
}

#[test]
fn every_step7_english_word_is_a_terminal_of_its_grammar() {
    use awl::step7::mnemonics as s7;
    let grammar = read("grammar/stl7.ebnf");
    let words = s7::OPERATIONS
        .iter()
        .chain(s7::EXTENSION_OPERATIONS)
        .map(|words| words.en)
        .chain(s7::AREAS.iter().map(|area| area.en))
        .chain(s7::CONDITIONS.iter().map(|(_, en, _)| *en));
    for word in words {
        assert!(
            grammar.contains(&format!("\"{word}\"")),
            "\"{word}\" is not in grammar/stl7.ebnf"
        );
    }
}

/// Every STEP 7 operation word of both sets is in the table of grammar/README.md.
#[test]
fn every_step7_word_is_in_the_readme_table() {
    use awl::step7::mnemonics as s7;
    let readme = read("grammar/README.md");
    let table = &readme[readme.find("# STEP 7 STL").expect("the STEP 7 section")..];
    for words in s7::OPERATIONS {
        for word in [words.en, words.de] {
            let listed = table.contains(&format!("`{word}`"))
                || table.contains(&format!("`{word} "))
                || table.contains(&format!(" {word} "))
                || table.contains(&format!(" {word}`"));
            assert!(
                listed,
                "`{word}` is not in the STEP 7 table of grammar/README.md"
            );
        }
    }
}

/// Every `code(awl::…)` in the sources has a page in errors.md, and every page a code.
#[test]
fn every_error_code_has_a_page() {
    let doc = read("grammar/errors.md");
    let mut codes = Vec::new();
    for entry in walk("src") {
        let text = read(&entry);
        for piece in text.split("code(awl::").skip(1) {
            let code: String = piece
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            codes.push(format!("awl::{code}"));
        }
    }
    assert!(codes.len() > 20);
    for code in &codes {
        assert!(
            doc.contains(&format!("### {code}")),
            "{code} has no page in grammar/errors.md"
        );
    }
    for line in doc.lines().filter_map(|line| line.strip_prefix("### ")) {
        let code = line.split_whitespace().next().unwrap();
        assert!(
            codes.iter().any(|known| known == code),
            "grammar/errors.md documents unknown code {code}"
        );
    }
}

fn walk(dir: &str) -> Vec<String> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(walk(path.to_str().unwrap()));
        } else if path.extension().is_some_and(|ext| ext == "rs") {
            files.push(path.to_string_lossy().into_owned());
        }
    }
    files
}
