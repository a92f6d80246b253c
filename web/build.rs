//! Puts every sample of `programs/` (and the playground's own examples) into the module, so
//! the page needs no files: writes `examples.rs`, a list of (name, text) pairs.

use std::fmt::Write;
use std::path::{Path, PathBuf};

/// The files a sample run can read; pictures and the folder's README are left out.
fn wanted(path: &Path) -> bool {
    path.extension()
        .and_then(|extension| extension.to_str())
        .is_some_and(|extension| matches!(extension, "awl" | "toml" | "seq" | "csv"))
}

/// The files under `dir`, named by their path below `root`.
fn collect(root: &Path, dir: &Path, found: &mut Vec<(String, PathBuf)>) {
    let entries =
        std::fs::read_dir(dir).unwrap_or_else(|error| panic!("{}: {error}", dir.display()));
    for entry in entries {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            collect(root, &path, found);
        } else if wanted(&path) {
            let name = path.strip_prefix(root).expect("below the root");
            found.push((name.to_string_lossy().replace('\\', "/"), path));
        }
    }
}

fn main() {
    let web = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let mut found = Vec::new();
    for dir in [web.join("../programs"), web.join("examples")] {
        println!("cargo::rerun-if-changed={}", dir.display());
        collect(&dir, &dir, &mut found);
    }
    found.sort();
    let mut out = String::from("pub const FILES: &[(&str, &str)] = &[\n");
    for (name, path) in found {
        let path = path.canonicalize().expect("the file exists");
        writeln!(out, "    ({name:?}, include_str!({:?})),", path.display()).expect("a String");
    }
    out.push_str("];\n");
    let target =
        PathBuf::from(std::env::var("OUT_DIR").expect("cargo sets it")).join("examples.rs");
    std::fs::write(target, out).expect("OUT_DIR is writable");
}
