//! The repository's own text names package registries by their client (cargo, pip), never by
//! the host they are fetched from: what CI and the docs rely on is the client, and hosts move.

use std::path::{Path, PathBuf};

/// Registry hosts and names, spelled in pieces so this file does not match itself.
const HOSTS: [&str; 6] = [
    concat!("crates", ".io"),
    concat!("pypi", ".org"),
    concat!("Py", "PI"),
    concat!("pythonhosted", ".org"),
    concat!("npmjs", ".org"),
    concat!("npmjs", ".com"),
];

/// What cargo writes itself (the lock files name the index they were resolved from) and what
/// is not text.
fn skipped(path: &Path) -> bool {
    let name = path
        .file_name()
        .and_then(|name| name.to_str())
        .unwrap_or("");
    let extension = path.extension().and_then(|ext| ext.to_str()).unwrap_or("");
    name == "Cargo.lock" || matches!(extension, "png" | "wasm" | "snap" | "proptest-regressions")
}

fn files_under(dir: &Path, found: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            let generated = matches!(name.as_ref(), "target" | "corpus" | "artifacts");
            if !generated && !name.starts_with('.') || name == ".ci" {
                files_under(&path, found);
            }
        } else if !skipped(&path) {
            found.push(path);
        }
    }
}

#[test]
fn no_file_names_a_package_host() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    files_under(root, &mut files);
    assert!(files.iter().any(|path| path.ends_with(".ci/run")));
    let mut found = Vec::new();
    for path in &files {
        let Ok(text) = std::fs::read_to_string(path) else {
            continue;
        };
        for (number, line) in text.lines().enumerate() {
            if let Some(host) = HOSTS.iter().find(|host| line.contains(*host)) {
                let shown = path.strip_prefix(root).unwrap_or(path).display();
                found.push(format!("{shown}:{}: {host}", number + 1));
            }
        }
    }
    assert!(
        found.is_empty(),
        "name the registry by its client (fetched by cargo, installed with pip):\n{}",
        found.join("\n")
    );
}
