//! The editor modules of `awl lsp` take any text without panicking: a document being typed is
//! mostly not a program.

use awl::dialect::Dialect;
use awl::lsp::complete::{CompletionContext, completions};
use awl::lsp::fixes::{Diagnostic, FIXABLE, quick_fixes};
use awl::lsp::format::format;
use awl::lsp::text::{FileLanguage, LineIndex};
use awl::lsp::tokens::semantic_tokens;
use awl::mnemonics::MnemonicSet;
use proptest::prelude::*;

fn languages() -> Vec<FileLanguage> {
    let mut all = Vec::new();
    for dialect in [Dialect::Step5, Dialect::Step7] {
        for mnemonics in [MnemonicSet::English, MnemonicSet::German] {
            all.push(FileLanguage { dialect, mnemonics });
        }
    }
    all
}

/// Pieces of STL of both dialects, and characters that break them.
fn document() -> impl Strategy<Value = String> {
    let pieces = prop::sample::select(vec![
        "PB 1",
        "FB 2",
        "NAME :X",
        "DES :EIN I BI",
        "M001 :",
        ":",
        "A",
        "U",
        "I 0.0",
        "E 1.",
        "=EIN",
        "-START",
        "KF +5",
        "KT 030.1",
        "'A;B'",
        "; c",
        "// c",
        "\n",
        "\r\n",
        " ",
        "BE",
        "0004 ",
        "***",
        "FUNCTION FC 1 : VOID",
        "BEGIN",
        "VAR_TEMP",
        "t : INT;",
        "END_VAR",
        "L W#16#FF;",
        "#t",
        "\"Sym\"",
        "END_FUNCTION",
        "Ä",
        "𝄞",
        "(",
        ")",
        "DATA_BLOCK DB 1",
    ]);
    prop::collection::vec(pieces, 0..40).prop_map(|pieces| pieces.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]
    #[test]
    fn no_editor_function_panics(text in document(), at in 0usize..400, len in 0usize..8) {
        let index = LineIndex::new(&text);
        let position = index.position(at);
        for language in languages() {
            semantic_tokens(&text, language);
            format(&text, language);
            let context = CompletionContext {
                language,
                symbols: Vec::new(),
                variables: Vec::new(),
                db_members: Vec::new(),
                blocks: Vec::new(),
                labels: Vec::new(),
            };
            completions(&text, position, &context);
            for code in FIXABLE {
                let diagnostic = Diagnostic {
                    code,
                    start: at,
                    end: at + len,
                    message: "`KG +1000000+01`",
                    help: Some("did you mean `A`? write `DES :X I BI` `M001 :A`"),
                };
                quick_fixes(&text, &diagnostic, language);
            }
        }
    }
}
