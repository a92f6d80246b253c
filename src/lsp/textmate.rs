//! The TextMate grammar of the VS Code extension (`editors/vscode/syntaxes/stl.tmLanguage.json`),
//! generated from the mnemonic tables of both dialects and both sets so that it cannot drift
//! from what awl reads; a test keeps the committed file equal to [`grammar`].

use serde_json::{Value, json};

use crate::dialect::STEP7_LINE_WORDS;
use crate::mnemonics::{self, BlockKind};
use crate::step7::mnemonics as s7_mnemonics;

/// Where the extension keeps the grammar, relative to the repository.
pub const GRAMMAR_PATH: &str = "editors/vscode/syntaxes/stl.tmLanguage.json";

/// The grammar as pretty JSON with a final line end.
pub fn grammar() -> String {
    let mut text = serde_json::to_string_pretty(&grammar_value()).expect("JSON of plain values");
    text.push('\n');
    text
}

fn grammar_value() -> Value {
    let statement = format!(
        r"^(\s*(?:[0-9A-Fa-f]{{4}}\s+)?)(?:([A-Za-z_\x{{C0}}-\x{{FF}}][A-Za-z0-9_\x{{C0}}-\x{{FF}}]*)\s*(:)(?!=))?\s*:?\s*{}(?=[\s(;]|$)(?!\s*:)",
        alternation(&operation_words())
    );
    json!({
        "$schema": "https://raw.githubusercontent.com/martinring/tmlanguage/master/tmlanguage.json",
        "name": "STL (AWL)",
        "scopeName": "source.stl",
        "fileTypes": ["awl", "AWL", "stl"],
        "patterns": [
            {"include": "#comment"},
            {"include": "#statement"},
            {"include": "#keyword"},
            {"include": "#string"},
            {"include": "#symbol"},
            {"include": "#constant"},
            {"include": "#operand"},
            {"include": "#number"}
        ],
        "repository": {
            "comment": {
                "patterns": [
                    {"name": "comment.line.double-slash.stl", "match": "//.*$"},
                    {
                        "comment": "STEP 5: `;` starts a comment; STEP 7: it ends a statement, before a line end or `//`",
                        "name": "comment.line.semicolon.stl",
                        "match": ";(?!\\s*(//|$)).*$"
                    }
                ]
            },
            "statement": {
                "comment": "[address] [label :] [:] operation: the operation words of both sets of STEP 5 and STEP 7",
                "match": statement,
                "captures": {
                    "2": {"name": "entity.name.label.stl"},
                    "3": {"name": "punctuation.separator.label.stl"},
                    "4": {"name": "keyword.operator.operation.stl"}
                }
            },
            "keyword": {
                "comment": "block headers and the frame of a STEP 7 source",
                "name": "keyword.control.block.stl",
                "match": format!("(?i)^\\s*{}\\b", alternation(&frame_words()))
            },
            "string": {"name": "string.quoted.single.stl", "match": "'[^'\\r\\n]*'"},
            "symbol": {
                "patterns": [
                    {"name": "variable.other.symbol.stl", "match": "\"[^\"\\r\\n]*\""},
                    {"name": "variable.other.symbol.stl", "match": "(?<![\\w)])-[A-Za-z_][A-Za-z0-9_]*"},
                    {"name": "variable.parameter.formal.stl", "match": "=[A-Za-z_][A-Za-z0-9_]*"},
                    {"name": "variable.other.local.stl", "match": "#[A-Za-z_][A-Za-z0-9_]*"}
                ]
            },
            "constant": {
                "patterns": [
                    {"name": "constant.numeric.typed.stl", "match": "\\b[A-Za-z0-9_]+#[A-Za-z0-9_.:+\\-#]*"},
                    {
                        "name": "constant.numeric.formatted.stl",
                        "match": format!("(?i)\\b{}\\s+[+\\-]?[0-9A-Za-z.,+\\-]+", alternation(&constant_words()))
                    }
                ]
            },
            "operand": {
                "name": "support.type.area.stl",
                "match": format!("(?i)\\b{}(?=\\s*[0-9\\[])", alternation(&area_words()))
            },
            "number": {"name": "constant.numeric.stl", "match": "\\b[0-9]+(\\.[0-9]+)?\\b"}
        }
    })
}

/// `(?i:(?:W1|W2|…))`: longest words first, so that `AN` is not read as `A`.
fn alternation(words: &[&str]) -> String {
    let mut words: Vec<String> = words.iter().map(|word| escape(word)).collect();
    words.sort_by(|a, b| b.len().cmp(&a.len()).then(a.cmp(b)));
    words.dedup();
    format!("(?i:({}))", words.join("|"))
}

fn escape(word: &str) -> String {
    word.chars()
        .flat_map(|c| {
            let special = "\\^$.|?*+()[]{}".contains(c);
            special.then_some('\\').into_iter().chain([c])
        })
        .collect()
}

fn both(en: &'static str, de: &'static str) -> [&'static str; 2] {
    [en, de]
}

fn operation_words() -> Vec<&'static str> {
    let step5 = mnemonics::OPERATIONS
        .iter()
        .flat_map(|info| both(info.en, info.de));
    let step7 = s7_mnemonics::OPERATIONS
        .iter()
        .flat_map(|words| both(words.en, words.de));
    step5.chain(step7).filter(|word| !word.is_empty()).collect()
}

fn area_words() -> Vec<&'static str> {
    let step5 = mnemonics::AREAS
        .iter()
        .flat_map(|info| both(info.en, info.de));
    let step7 = s7_mnemonics::AREAS
        .iter()
        .flat_map(|words| both(words.en, words.de));
    let blocks = BlockKind::ALL
        .into_iter()
        .chain([BlockKind::Fc])
        .map(BlockKind::name);
    step5
        .chain(step7)
        .chain(blocks)
        .filter(|w| !w.is_empty())
        .collect()
}

fn constant_words() -> Vec<&'static str> {
    mnemonics::CONSTANTS
        .iter()
        .flat_map(|info| both(info.en, info.de))
        .collect()
}

fn frame_words() -> Vec<&'static str> {
    let mut words: Vec<&'static str> = STEP7_LINE_WORDS.to_vec();
    words.extend([
        "END_ORGANIZATION_BLOCK",
        "END_FUNCTION_BLOCK",
        "END_FUNCTION",
        "END_DATA_BLOCK",
        "END_VAR",
        "END_STRUCT",
        "END_TYPE",
        "STRUCT",
        "TYPE",
        "NETWORK",
        "TITLE",
    ]);
    words.extend(crate::parser::listing::SEGMENT_WORDS);
    words.extend([
        mnemonics::NAME_WORD,
        mnemonics::DECLARATION_EN,
        mnemonics::DECLARATION_DE,
    ]);
    words
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grammar_names_the_words_of_both_sets_and_dialects() {
        let text = grammar();
        for word in ["SPBN", "JCN", "ORGANIZATION_BLOCK", "KF", "DBX", "==I"] {
            assert!(text.contains(word), "{word}");
        }
        let parsed: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(parsed["scopeName"], "source.stl");
    }

    #[test]
    fn longer_words_come_first() {
        let alternation = alternation(&["A", "AN", "A("]);
        assert_eq!(alternation, "(?i:(A\\(|AN|A))");
    }
}
