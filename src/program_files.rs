//! The files a command reads as its program: STL source files, awlsim projects (their sources,
//! symbol tables and CPU settings, [`crate::project`]) and the assignment lists or symbol
//! tables beside them. A scenario file or a binary file given as a program is told as such,
//! once, not parsed as STL.

use std::path::{Path, PathBuf};

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::project::{self, Project};
use crate::source::{self, Files, SourceFile, SourceSet};

/// Why the program's files could not be loaded.
#[derive(Debug, Error, Diagnostic)]
pub enum SourceError {
    #[error("cannot read `{}`: {reason}", path.display())]
    #[diagnostic(
        code(awl::cli::read_file),
        help("check the path; program files are plain text (.awl)")
    )]
    Read { path: PathBuf, reason: String },

    #[error("`{}` is a scenario file, not a program", path.display())]
    #[diagnostic(
        code(awl::cli::scenario_as_program),
        help("run a scenario with `awl run --scenario {}`", path.display())
    )]
    ScenarioAsProgram { path: PathBuf },

    #[error("`{}` is not STL text: {reason}", path.display())]
    #[diagnostic(
        code(awl::cli::not_text),
        help(
            "awl reads STL source text (.awl) and awlsim projects (.awlpro); STEP 5 binaries \
             (.S5D) must be exported as text from the PG software"
        )
    )]
    NotText { path: PathBuf, reason: String },

    #[error("`{}` is a second awlsim project", path.display())]
    #[diagnostic(
        code(awl::cli::two_projects),
        help(
            "a program takes its CPU settings from one project; name one, with .awl files \
             beside it if need be"
        )
    )]
    TwoProjects { path: PathBuf },

    #[error("{count} source files: awl reads at most 65,536 at once")]
    #[diagnostic(
        code(awl::cli::too_many_files),
        help("join the files, or check them in parts")
    )]
    TooMany { count: usize },
}

/// A program's files, read.
#[derive(Debug, Default)]
pub struct ProgramFiles {
    pub sources: SourceSet,
    /// The assignment lists or symbol tables: the project's, then those named besides.
    pub symbol_files: Vec<SourceFile>,
    /// The awlsim project among the program files, whose settings count where the command
    /// line and the scenario leave them open; its sources are in `sources`, its symbol tables
    /// in `symbol_files`.
    pub project: Option<Project>,
}

/// Reads the program files `programs` (projects opened into their sources) and the symbol
/// files `symbols` from `store`; every file that cannot be read is reported.
pub fn read_program(
    store: &Files,
    programs: &[PathBuf],
    symbols: &[PathBuf],
) -> Result<ProgramFiles, Vec<Report>> {
    let mut read = ProgramFiles::default();
    let mut errors: Vec<Report> = Vec::new();
    // Each program text with its name: the files, and a project's sources in its place.
    let mut texts: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut project_symbols = Vec::new();
    for path in programs {
        if has_extension(path, "toml") {
            errors.push(Report::new(SourceError::ScenarioAsProgram {
                path: path.clone(),
            }));
            continue;
        }
        let bytes = match store.read(path) {
            Ok(bytes) => bytes,
            Err(error) => {
                errors.push(read_error(path, &error));
                continue;
            }
        };
        if !project::is_project(path, &bytes) {
            texts.push((path.clone(), bytes));
        } else if read.project.is_some() {
            errors.push(Report::new(SourceError::TwoProjects { path: path.clone() }));
        } else {
            match project::project_of(store, path, bytes) {
                Ok(mut project) => {
                    texts.append(&mut project.programs);
                    project_symbols = std::mem::take(&mut project.symbols);
                    read.project = Some(project);
                }
                Err(reports) => errors.extend(reports),
            }
        }
    }
    let count = texts.len();
    for (name, bytes) in texts {
        if let Some(reason) = source::binary_reason(&bytes) {
            errors.push(Report::new(SourceError::NotText { path: name, reason }));
            continue;
        }
        let file = SourceFile::from_bytes(name.display().to_string(), bytes);
        if read.sources.add(file).is_none() {
            return Err(vec![Report::new(SourceError::TooMany { count })]);
        }
    }
    read.symbol_files = project_symbols
        .into_iter()
        .map(|(name, bytes)| SourceFile::from_bytes(name.display().to_string(), bytes))
        .collect();
    match read_symbol_files(store, symbols) {
        Ok(files) => read.symbol_files.extend(files),
        Err(more) => errors.extend(more.into_iter().map(Report::new)),
    }
    if errors.is_empty() {
        Ok(read)
    } else {
        Err(errors)
    }
}

/// Reads the assignment lists from `store`; every file that cannot be read is reported.
fn read_symbol_files(
    store: &Files,
    paths: &[impl AsRef<Path>],
) -> Result<Vec<SourceFile>, Vec<SourceError>> {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for path in paths {
        let path = path.as_ref();
        match store.source(path) {
            Ok(file) => files.push(file),
            Err(error) => errors.push(SourceError::Read {
                path: path.to_path_buf(),
                reason: error.to_string(),
            }),
        }
    }
    if errors.is_empty() {
        Ok(files)
    } else {
        Err(errors)
    }
}

fn read_error(path: &Path, error: &std::io::Error) -> Report {
    Report::new(SourceError::Read {
        path: path.to_path_buf(),
        reason: error.to_string(),
    })
}

fn has_extension(path: &Path, extension: &str) -> bool {
    path.extension()
        .is_some_and(|ext| ext.eq_ignore_ascii_case(extension))
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::sync::Arc;

    use super::*;

    fn store(files: &[(&str, &[u8])]) -> Files {
        let map: BTreeMap<PathBuf, Vec<u8>> = files
            .iter()
            .map(|(name, bytes)| (PathBuf::from(name), bytes.to_vec()))
            .collect();
        Files::Memory(Arc::new(map))
    }

    fn codes(result: Result<ProgramFiles, Vec<Report>>) -> Vec<String> {
        result
            .expect_err("errors")
            .iter()
            .map(|report| {
                report
                    .code()
                    .map(|code| code.to_string())
                    .unwrap_or_default()
            })
            .collect()
    }

    const PROJECT: &[u8] =
        b"[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nawl_file_0=a.awl\nnr_accus=4\n\
                             [SYMBOLS]\nsym_tab_file_0=a.sym\n";

    #[test]
    fn a_project_opens_into_its_sources_and_symbol_tables() {
        let files = store(&[
            ("p/x.awlpro", PROJECT),
            (
                "p/a.awl",
                b"ORGANIZATION_BLOCK OB 1\nBEGIN\nEND_ORGANIZATION_BLOCK\n",
            ),
            ("p/a.sym", b"\"Start\" I 0.0 BOOL\n"),
            ("b.awl", b"FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION\n"),
            ("more.sym", b"\"Stop\" I 0.1 BOOL\n"),
        ]);
        let paths = [PathBuf::from("b.awl"), PathBuf::from("p/x.awlpro")];
        let read = read_program(&files, &paths, &[PathBuf::from("more.sym")]).unwrap();
        let names = |files: &[SourceFile]| -> Vec<String> {
            files.iter().map(|file| file.name.clone()).collect()
        };
        assert_eq!(names(&read.sources.files), ["b.awl", "p/a.awl"]);
        assert_eq!(names(&read.symbol_files), ["p/a.sym", "more.sym"]);
        assert_eq!(read.project.map(|project| project.accus), Some(4));
    }

    #[test]
    fn what_is_no_program_is_told_once_each() {
        let files = store(&[
            ("x.awlpro", PROJECT),
            ("y.awlpro", PROJECT),
            (
                "a.awl",
                b"ORGANIZATION_BLOCK OB 1\nBEGIN\nEND_ORGANIZATION_BLOCK\n",
            ),
            ("a.sym", b""),
            ("picture.png", b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR"),
        ]);
        let paths: Vec<PathBuf> = ["s.toml", "gone.awl", "picture.png", "x.awlpro", "y.awlpro"]
            .into_iter()
            .map(PathBuf::from)
            .collect();
        assert_eq!(
            codes(read_program(&files, &paths, &[PathBuf::from("gone.sym")])),
            [
                "awl::cli::scenario_as_program",
                "awl::cli::read_file",
                "awl::cli::two_projects",
                "awl::cli::not_text",
                "awl::cli::read_file",
            ]
        );
    }

    #[test]
    fn a_binary_source_of_a_project_is_told_too() {
        let files = store(&[
            (
                "x.awlpro",
                b"[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nawl_file_0=a.s5d\n",
            ),
            ("a.s5d", b"\0\x01\x02S5D\0\0"),
        ]);
        assert_eq!(
            codes(read_program(&files, &[PathBuf::from("x.awlpro")], &[])),
            ["awl::cli::not_text"]
        );
    }
}
