//! The editor files: the VS Code extension's JSON files parse, its package.json names files
//! that exist, and its TextMate grammar is the one the mnemonic tables generate.

use std::path::{Path, PathBuf};

use serde_json::Value;

const EXTENSION: &str = "editors/vscode";

fn json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn json_files(folder: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(folder).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() && path.file_name().is_some_and(|name| name != "node_modules") {
            found.extend(json_files(&path));
        } else if path.extension().is_some_and(|ext| ext == "json") {
            found.push(path);
        }
    }
    found
}

#[test]
fn every_json_file_of_the_extension_parses() {
    let files = json_files(Path::new(EXTENSION));
    assert!(files.len() >= 3, "{files:?}");
    for file in files {
        json(&file);
    }
}

/// A path of package.json (`./extension.js`) as a path of the repository.
fn in_extension(relative: &Value) -> PathBuf {
    let relative = relative.as_str().expect("a path is a string");
    Path::new(EXTENSION).join(relative.trim_start_matches("./"))
}

#[test]
fn package_json_names_files_that_exist() {
    let package = json(&Path::new(EXTENSION).join("package.json"));
    let main = in_extension(&package["main"]);
    assert!(main.is_file(), "{}", main.display());
    let client = std::fs::read_to_string(&main).unwrap();
    assert!(client.contains("vscode-languageclient") && client.contains("\"lsp\""));
    assert!(package["dependencies"]["vscode-languageclient"].is_string());

    let contributes = &package["contributes"];
    let languages = contributes["languages"].as_array().unwrap();
    assert!(languages.iter().any(|language| {
        language["id"] == "stl"
            && language["extensions"]
                .as_array()
                .unwrap()
                .contains(&Value::from(".awl"))
    }));
    for language in languages {
        let configuration = in_extension(&language["configuration"]);
        assert!(configuration.is_file(), "{}", configuration.display());
    }
    for grammar in contributes["grammars"].as_array().unwrap() {
        let path = in_extension(&grammar["path"]);
        assert!(path.is_file(), "{}", path.display());
        assert_eq!(json(&path)["scopeName"], grammar["scopeName"]);
        assert!(
            languages
                .iter()
                .any(|language| language["id"] == grammar["language"])
        );
    }
    assert!(
        package["activationEvents"]
            .as_array()
            .unwrap()
            .contains(&Value::from("onLanguage:stl"))
    );
}

/// The server's semantic token types are standard ones or declared by the extension.
#[test]
fn the_extension_declares_the_servers_own_token_types() {
    let package = json(&Path::new(EXTENSION).join("package.json"));
    let declared: Vec<&str> = package["contributes"]["semanticTokenTypes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|token| token["id"].as_str())
        .collect();
    let standard = ["keyword", "variable", "number", "comment"];
    for name in awl::lsp::tokens::LEGEND {
        assert!(standard.contains(name) || declared.contains(name), "{name}");
    }
}

/// Run with `AWL_WRITE_GRAMMAR=1` to write the generated grammar after a table changed.
#[test]
fn the_textmate_grammar_is_the_generated_one() {
    let generated = awl::lsp::textmate::grammar();
    let path = awl::lsp::textmate::GRAMMAR_PATH;
    if std::env::var_os("AWL_WRITE_GRAMMAR").is_some() {
        std::fs::write(path, &generated).unwrap();
    }
    let committed = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        committed == generated,
        "{path} is not the grammar the mnemonic tables generate; run this test with \
         AWL_WRITE_GRAMMAR=1 to write it"
    );
}
