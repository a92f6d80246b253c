//! Which files the command line names: files as given, directories as every `.awl` file
//! below them, sorted by path, as awlsim's harness walks its test tree.

use std::path::{Path, PathBuf};

/// A file named on the command line or found below a directory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Entry {
    /// A test to run.
    Test(PathBuf),
    /// A file not to run, with the reason.
    Skip(PathBuf, String),
    /// A directory that holds no `.awl` file: a failure, since a wrong path should not pass
    /// as an empty suite.
    Empty(PathBuf),
}

/// The files only awlsim itself can run, by extension.
const AWLSIM_ONLY: &[(&str, &str)] = &[
    ("awlpro", "awlsim project file"),
    ("sh", "awlsim shell test"),
];

/// The entries `paths` name, in order; a directory's files sorted by path.
pub fn collect(paths: &[PathBuf]) -> Vec<Entry> {
    let mut entries = Vec::new();
    for path in paths {
        if path.is_dir() {
            let found = below(path);
            if found.is_empty() {
                entries.push(Entry::Empty(path.clone()));
            }
            entries.extend(found);
        } else {
            entries.push(match project_file(path) {
                Some(reason) => Entry::Skip(path.clone(), reason),
                None => Entry::Test(path.clone()),
            });
        }
    }
    entries
}

/// Every `.awl` file below `dir`; one that awlsim runs through a project file or a shell
/// script of the same name beside it is skipped, as awlsim's harness skips it.
fn below(dir: &Path) -> Vec<Entry> {
    walkdir::WalkDir::new(dir)
        .sort_by_file_name()
        .into_iter()
        // A directory that cannot be read is left out: none of its files could be run.
        .filter_map(Result::ok)
        .filter(|entry| entry.file_type().is_file() && has_extension(entry.path(), "awl"))
        .map(|entry| {
            let path = entry.into_path();
            let beside = AWLSIM_ONLY
                .iter()
                .map(|&(extension, what)| (path.with_extension(extension), what))
                .find(|(other, _)| other.exists());
            match beside {
                Some((other, what)) => {
                    let name = other.file_name().unwrap_or_default().to_string_lossy();
                    let reason = format!("awlsim runs it through {name} ({what})");
                    Entry::Skip(path, reason)
                }
                None => Entry::Test(path),
            }
        })
        .collect()
}

/// Why a file named on the command line is no `.awl` test: awlsim's project files and shell
/// tests need awlsim itself.
fn project_file(path: &Path) -> Option<String> {
    AWLSIM_ONLY
        .iter()
        .find(|(extension, _)| has_extension(path, extension))
        .map(|(_, what)| format!("awl conformance runs .awl files ({what})"))
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|ext| ext.eq_ignore_ascii_case(extension))
}
