//! Which files the command line names: files as given, directories as every `.awl` and
//! `.awlpro` file below them, sorted by path, as awlsim's harness walks its test tree. A file
//! gets the same verdict named or found: one awlsim runs through another file beside it (the
//! source of a project file) is skipped either way.

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
const AWLSIM_ONLY: &[(&str, &str)] = &[("sh", "awlsim shell test")];

/// What awlsim's harness runs instead of a test file of the same name beside it: a `.awl`
/// file through its project file or shell test, a project file through its shell test.
const RUN_INSTEAD: &[(&str, &str, &str)] = &[
    ("awl", "awlpro", "awlsim project file"),
    ("awl", "sh", "awlsim shell test"),
    ("awlpro", "sh", "awlsim shell test"),
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
            entries.push(match awlsim_only(path) {
                Some(reason) => Entry::Skip(path.clone(), reason),
                None => test_or_skip(path.clone()),
            });
        }
    }
    entries
}

/// Every `.awl` and `.awlpro` file below `dir`; one that awlsim runs through another file of
/// the same name beside it is skipped, as awlsim's harness skips it.
fn below(dir: &Path) -> Vec<Entry> {
    walkdir::WalkDir::new(dir)
        .sort_by_file_name()
        .into_iter()
        // A directory that cannot be read is left out: none of its files could be run.
        .filter_map(Result::ok)
        .filter(|entry| {
            entry.file_type().is_file()
                && (has_extension(entry.path(), "awl") || has_extension(entry.path(), "awlpro"))
        })
        .map(|entry| test_or_skip(entry.into_path()))
        .collect()
}

/// A test, or a skip when awlsim runs `path` through another file of the same name beside it.
fn test_or_skip(path: PathBuf) -> Entry {
    let beside = RUN_INSTEAD
        .iter()
        .filter(|(test, _, _)| has_extension(&path, test))
        .map(|&(_, extension, what)| (path.with_extension(extension), what))
        .find(|(other, _)| other.exists());
    match beside {
        Some((other, what)) => {
            let name = other.file_name().unwrap_or_default().to_string_lossy();
            let reason = format!("awlsim runs it through {name} ({what})");
            Entry::Skip(path, reason)
        }
        None => Entry::Test(path),
    }
}

/// Why a file named on the command line is no test awl runs: awlsim's shell tests need
/// awlsim itself.
fn awlsim_only(path: &Path) -> Option<String> {
    AWLSIM_ONLY
        .iter()
        .find(|(extension, _)| has_extension(path, extension))
        .map(|(_, what)| format!("awl conformance runs .awl and .awlpro files ({what})"))
}

/// Whether `path` is an awlsim project file, run through [`super::project`].
pub fn is_project(path: &Path) -> bool {
    has_extension(path, "awlpro")
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|ext| ext.eq_ignore_ascii_case(extension))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A project's source beside its project file, named or found in its directory.
    #[test]
    fn a_file_gets_the_same_verdict_named_or_found() {
        let dir = std::env::temp_dir().join(format!("awl-collect-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let source = dir.join("chain.awl");
        std::fs::write(
            &source,
            "ORGANIZATION_BLOCK OB 1\nBEGIN\nEND_ORGANIZATION_BLOCK\n",
        )
        .unwrap();
        std::fs::write(dir.join("chain.awlpro"), "").unwrap();
        let named = collect(std::slice::from_ref(&source));
        let found = collect(std::slice::from_ref(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
        let skip = Entry::Skip(
            source,
            "awlsim runs it through chain.awlpro (awlsim project file)".into(),
        );
        assert_eq!(named, vec![skip.clone()]);
        assert!(found.contains(&skip), "{found:?}");
    }
}
