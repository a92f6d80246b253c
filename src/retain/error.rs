//! What goes wrong with a retentive memory file or a snapshot: each error names the file and,
//! where the file does not fit the program, what does not and the ways on.

use std::path::PathBuf;

use miette::Diagnostic;
use thiserror::Error;

/// The options a file that does not fit leaves.
const WAYS_ON: &str = "start cold from the source's values with `--cold` (the file is then \
     written anew), or load what still fits with `--retain-what-fits`";

#[derive(Debug, Error, Diagnostic)]
pub enum RetainError {
    #[error("cannot read `{path}`: {reason}")]
    #[diagnostic(code(awl::retain::unreadable))]
    Unreadable { path: PathBuf, reason: String },

    #[error("`{path}` is damaged: {reason}")]
    #[diagnostic(
        code(awl::retain::damaged),
        help(
            "the file was changed or broken outside awl; start cold from the source's values with `--cold` (the file is then written anew)"
        )
    )]
    Damaged { path: PathBuf, reason: String },

    #[error("`{path}` is not {expected}: {reason}")]
    #[diagnostic(
        code(awl::retain::foreign),
        help(
            "name a file awl wrote with `--retain` (retentive memory) or as a snapshot (`--from`); for `--retain`, `--cold` starts from the source's values and writes the file anew"
        )
    )]
    Foreign {
        path: PathBuf,
        expected: &'static str,
        reason: String,
    },

    #[error("`{path}` does not fit the program: {}", misfits.join("; "))]
    #[diagnostic(code(awl::retain::out_of_date), help("{WAYS_ON}"))]
    OutOfDate { path: PathBuf, misfits: Vec<String> },

    #[error("cannot write `{path}`: {reason}")]
    #[diagnostic(
        code(awl::retain::write),
        help("the folder must exist and be writable; the file before stays as it was")
    )]
    Write { path: PathBuf, reason: String },
}
