//! Snapshot tests of the rendered diagnostics: one case per error code of the front end.

use awl::diagnostics::{render_plain, report};
use awl::frontend;
use awl::profile;

const FB_WITH_TWO_PARAMS: &str =
    "FB 5\nNAME :MOTOR\nDES :EIN I BI\nDES :AUS Q BI\n      A =EIN\n      = =AUS\n      BE\n";

/// Each code with a small program that shows it.
fn cases() -> Vec<(&'static str, &'static str, String)> {
    let call = |params: &str| {
        format!("PB 1\n      JU FB 5\nNAME :MOTOR\n{params}      BE\n{FB_WITH_TWO_PARAMS}")
    };
    vec![
        (
            "awl::lex::unexpected_character",
            "sinumerik-840c",
            "PB 1\n      A  § 1\n      BE\n".into(),
        ),
        (
            "awl::parse::unknown_operation",
            "sinumerik-840c",
            "PB 1\n      JUU PB 2\n      BE\nPB 2\n      BE\n".into(),
        ),
        (
            "awl::parse::mixed_mnemonics",
            "sinumerik-840c",
            "PB 1\n      A  I 0.0\n      AN F 1.0\n      U  E 0.1\n      =  Q 4.0\n      BE\n"
                .into(),
        ),
        (
            "awl::parse::unknown_operand",
            "sinumerik-840c",
            "PB 1\n      A  X 1.0\n      BE\n".into(),
        ),
        (
            "awl::parse::missing_operand",
            "sinumerik-840c",
            "PB 1\n      JU\n      BE\n".into(),
        ),
        (
            "awl::parse::unexpected_token",
            "sinumerik-840c",
            "PB 1\n      A I 0.0\n      BE 5\n".into(),
        ),
        (
            "awl::parse::bad_address",
            "sinumerik-840c",
            "PB 1\n      A  I 4\n      BE\n".into(),
        ),
        (
            "awl::parse::outside_block",
            "sinumerik-840c",
            "PB 1\n      BE\n      A  I 0.0\n".into(),
        ),
        (
            "awl::parse::fragment",
            "sinumerik-840c",
            "0000 :A  I 0.0\n0001 :AN F 10.1\n0002 :=  Q 4.0\n".into(),
        ),
        (
            "awl::parse::bare_constant",
            "sinumerik-840c",
            "PB 1\n      L  1\n      T  FW 10\n      BE\n".into(),
        ),
        (
            "awl::parse::formals_from_use",
            "sinumerik-840c",
            "      A  =EIN\n      AN =EIN\n      =  =AUS\n".into(),
        ),
        (
            "awl::parse::step7_source",
            "sinumerik-840c",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\n      A  I 0.0;\n      =  Q 4.0;\nEND_ORGANIZATION_BLOCK\n"
                .into(),
        ),
        (
            "awl::parse::step7_word",
            "sinumerik-840c",
            "PB 1\n      L  KF +5\n      ITB\n      T  FW 4\n      BE\n".into(),
        ),
        (
            "awl::check::undeclared_local",
            "speed7",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A  #start;\n      =  Q 4.0;\nEND_ORGANIZATION_BLOCK\n".into(),
        ),
        (
            "awl::check::recursive_instance",
            "speed7",
            "FUNCTION_BLOCK FB 1\nVAR\n  again : FB 1;\nEND_VAR\nBEGIN\n      NOP 0;\nEND_FUNCTION_BLOCK\n"
                .into(),
        ),
        (
            "awl::check::undefined_label",
            "speed7",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\n      JU nix;\n      NOP 0;\nEND_ORGANIZATION_BLOCK\n".into(),
        ),
        (
            "awl::check::not_simulated",
            "speed7",
            "FUNCTION_BLOCK FB 1\nBEGIN\n      NOP 0;\nEND_FUNCTION_BLOCK\n\
             ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL FB 1;\nEND_ORGANIZATION_BLOCK\n"
                .into(),
        ),
        (
            "awl::check::library_block_replaced",
            "speed7",
            "FUNCTION FC 21 : INT\nBEGIN\n      L  0;\n      T  #RET_VAL;\nEND_FUNCTION\n\
             ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL \"LEN\" (RET_VAL := MW 0);\nEND_ORGANIZATION_BLOCK\n"
                .into(),
        ),
        (
            "awl::check::undefined_type",
            "speed7",
            "DATA_BLOCK DB 5\nUDT 9\nBEGIN\nEND_DATA_BLOCK\n\
             ORGANIZATION_BLOCK OB 1\nBEGIN\n      NOP 0;\nEND_ORGANIZATION_BLOCK\n"
                .into(),
        ),
        (
            "awl::check::step7_on_step5_cpu",
            "sinumerik-840c",
            "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A  I 0.0;\n      =  Q 4.0;\nEND_ORGANIZATION_BLOCK\n".into(),
        ),
        (
            "awl::parse::block_number",
            "sinumerik-840c",
            "PB 300\n      BE\n".into(),
        ),
        (
            "awl::parse::bad_constant",
            "sinumerik-840c",
            "PB 1\n      L  KH 12345\n      BE\n".into(),
        ),
        (
            "awl::parse::bad_declaration",
            "sinumerik-840c",
            "FB 1\nNAME :X\nDES  :Y I KF\n      BE\n".into(),
        ),
        (
            "awl::parse::bad_data_word",
            "sinumerik-840c",
            "DB 1\n   0: KF +1\n   1: XX 5\n".into(),
        ),
        (
            "awl::check::constant_range",
            "sinumerik-840c",
            "PB 1\n      L  KF 40000\n      BE\n".into(),
        ),
        (
            "awl::check::operand_range",
            "sinumerik-840c",
            "PB 1\n      A  I 200.0\n      BE\n".into(),
        ),
        (
            "awl::check::operand_not_allowed",
            "sinumerik-840c",
            "FB 1\nNAME :X\n      JP PB 3\n      BE\nPB 3\n      BE\n".into(),
        ),
        (
            "awl::check::supplementary_outside_fb",
            "sinumerik-840c",
            "PB 1\n      L  FW 0\n      SLW 3\n      BE\n".into(),
        ),
        (
            "awl::check::label_outside_fb",
            "sinumerik-840c",
            "PB 1\n      A  I 0.0\n      JC =M001\n      =  Q 4.0\nM001 :BE\n".into(),
        ),
        (
            "awl::check::formal_outside_fb",
            "sinumerik-840c",
            "PB 1\n      A  =EIN\n      BE\n".into(),
        ),
        (
            "awl::check::undefined_symbol",
            "sinumerik-840c",
            "FB 1\nNAME :X\n      JU =M002\nM001 :BE\n".into(),
        ),
        (
            "awl::check::duplicate_label",
            "sinumerik-840c",
            "FB 1\nNAME :X\nM001 :NOP 0\nM001 :NOP 0\n      BE\n".into(),
        ),
        (
            "awl::check::label_too_long",
            "sinumerik-840c",
            "FB 1\nNAME :X\nLOOP1 :NOP 0\n      BE\n".into(),
        ),
        (
            "awl::check::duplicate_block",
            "sinumerik-840c",
            "PB 1\n      BE\nPB 1\n      BE\n".into(),
        ),
        (
            "awl::check::missing_be",
            "sinumerik-840c",
            "PB 1\n      A  I 0.0\n      =  Q 4.0\n".into(),
        ),
        (
            "awl::check::extended_block",
            "s5-95f",
            "FX 1\n      BE\n".into(),
        ),
        (
            "awl::check::param_count",
            "sinumerik-840c",
            call("EIN  :I 0.0\n"),
        ),
        (
            "awl::check::param_mismatch",
            "sinumerik-840c",
            call("EIN  :IW 2\nAUS  :Q 4.0\n"),
        ),
        (
            "awl::check::unknown_param",
            "sinumerik-840c",
            call("EIN  :I 0.0\nAUX  :Q 4.0\n"),
        ),
        (
            "awl::check::undefined_block",
            "sinumerik-840c",
            "PB 1\n      JU PB 9\n      BE\n".into(),
        ),
        (
            "awl::check::undefined_db",
            "sinumerik-840c",
            "PB 1\n      C  DB 9\n      BE\n".into(),
        ),
        (
            "awl::check::not_on_cpu",
            "s5-95f",
            "FB 1\nNAME :X\n      ENT\n      BE\n".into(),
        ),
        (
            "awl::check::operation_not_on_cpu",
            "s5-95f",
            "OB 1\n      L  KG +1000000+01\n      L  KG +2000000+01\n      +G\n      BE\n".into(),
        ),
        (
            "awl::parse::decimal_float",
            "sinumerik-840c",
            "OB 1\n      L  KG 2457.6\n      BE\n".into(),
        ),
        (
            "awl::check::indirect_target",
            "sinumerik-840c",
            "FB 1\nNAME :X\n      DO FW 10\n      BE\n".into(),
        ),
        (
            "awl::check::unclosed_bracket",
            "sinumerik-840c",
            "PB 1\n      A(\n      A  I 0.0\n      O  I 0.1\n      =  Q 4.0\n      BE\n".into(),
        ),
        (
            "awl::check::unopened_bracket",
            "sinumerik-840c",
            "PB 1\n      A  I 0.0\n      )\n      =  Q 4.0\n      BE\n".into(),
        ),
        (
            "awl::check::block_not_on_cpu",
            "sinumerik-840c",
            "OB 1\n      JU OB 254\n      BE\n".into(),
        ),
        (
            "awl::check::bracket_depth",
            "s5-95f",
            format!(
                "PB 1\n{}      A  I 0.0\n{}      =  Q 4.0\n      BE\n",
                "      A(\n".repeat(8),
                "      )\n".repeat(8)
            ),
        ),
    ]
}

#[test]
fn every_front_end_code_renders() {
    for (code, cpu, source) in cases() {
        // `awl::parse::step7_source` is what a STEP 7 text gives when read as STEP 5.
        let language = if code == "awl::parse::step7_source" {
            frontend::Language {
                dialect: Some(awl::dialect::Dialect::Step5),
                ..frontend::Language::default()
            }
        } else {
            frontend::Language::default()
        };
        let built = frontend::build_text_with(
            "example.awl",
            &source,
            language,
            profile::find(cpu).unwrap(),
        );
        let rendered: Vec<String> = built
            .diagnostics
            .iter()
            .map(|d| render_plain(&report(&built.sources, d)))
            .collect();
        let all = rendered.join("\n");
        // The note that says which block a fragment became accompanies a fragment's errors.
        let codes: Vec<String> = built
            .diagnostics
            .iter()
            .map(|d| miette::Diagnostic::code(d).unwrap().to_string())
            .filter(|found| found == code || found != "awl::parse::fragment")
            .collect();
        assert_eq!(
            codes,
            [code],
            "exactly this code, no follow-on errors, for:\n{source}\n---\n{all}"
        );
        insta::assert_snapshot!(code.replace("::", "__"), all, &source);
    }
}

#[test]
fn cli_read_error_renders() {
    let errors = awl::program_files::read_program(
        &awl::source::Files::Disk,
        &[std::path::PathBuf::from("does/not/exist.awl")],
        &[],
    )
    .unwrap_err();
    assert_eq!(errors.len(), 1);
    let rendered = render_plain(&errors[0]);
    assert!(rendered.contains("awl::cli::read_file"));
    insta::assert_snapshot!("awl__cli__read_file", rendered);
}

/// A jump to a label one edit from one the block has: the help names that label, in STEP 7 as
/// in STEP 5 (the case of `awl::check::undefined_symbol`).
#[test]
fn a_step7_jump_to_a_misspelt_label_is_told_the_close_one() {
    let source = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A  I 0.0;\n      JC M001;\n      NOP 0;\nM002: NOP 0;\nEND_ORGANIZATION_BLOCK\n";
    let built = frontend::build_text("example.awl", source, profile::find("speed7").unwrap());
    assert_eq!(built.diagnostics.len(), 1);
    let rendered = render_plain(&report(&built.sources, &built.diagnostics[0]));
    assert!(rendered.contains("did you mean `M002`?"), "{rendered}");
    insta::assert_snapshot!("awl__check__undefined_label_close", rendered, source);
}

/// Every documented code of the front end has a case above.
#[test]
fn cases_cover_the_front_end_codes() {
    let doc = std::fs::read_to_string("grammar/errors.md").unwrap();
    let covered: Vec<&str> = cases().iter().map(|(code, _, _)| *code).collect();
    for code in doc
        .lines()
        .filter_map(|line| line.strip_prefix("### "))
        .map(|line| line.split_whitespace().next().unwrap())
    {
        let front_end = code.starts_with("awl::lex")
            || code.starts_with("awl::parse")
            || code.starts_with("awl::check");
        if front_end {
            assert!(covered.contains(&code), "{code} has no snapshot case");
        }
    }
}

/// After a bad line, parsing goes on: the statements after it and the blocks after its block
/// are still in the program.
#[test]
fn recovery_keeps_what_follows_a_bad_line() {
    let source = "PB 1\n      A  I 0.0\n      BE 5\nPB 300\n      A  I 0.1\n      BE\nPB 2\n      A  § 1\n      =  Q 4.0\n      BE\n";
    let parsed = awl::parser::parse_text(source);
    let codes: Vec<String> = parsed
        .errors
        .iter()
        .map(|e| miette::Diagnostic::code(e).unwrap().to_string())
        .collect();
    assert_eq!(
        codes,
        [
            "awl::parse::unexpected_token",
            "awl::parse::block_number",
            "awl::lex::unexpected_character"
        ]
    );
    let blocks: Vec<String> = parsed
        .unit
        .blocks
        .iter()
        .map(|b| b.id.to_string())
        .collect();
    assert_eq!(
        blocks,
        ["PB 1", "PB 2"],
        "the block with the bad number is left out"
    );
    let statements = |index: usize| match &parsed.unit.blocks[index].body {
        awl::ast::BlockBody::Logic(body) => (body.statements.len(), body.end.is_some()),
        awl::ast::BlockBody::Data(_) => unreachable!(),
    };
    assert_eq!(statements(0), (1, true), "PB 1 keeps its A and is ended");
    assert_eq!(
        statements(1),
        (2, true),
        "PB 2 keeps = and BE after the bad line"
    );
}
