//! The Python the real-client tests run: the one at `AWL_PYTHON`, else `python3`.

use std::path::PathBuf;
use std::process::{Command, Stdio};

/// That Python when it imports `modules` (`"snap7, pymodbus"`); otherwise `None`, and the
/// test says why it skips (`packages` names what to install).
pub fn with(modules: &str, packages: &str) -> Option<PathBuf> {
    let python =
        std::env::var_os("AWL_PYTHON").map_or_else(|| PathBuf::from("python3"), PathBuf::from);
    let found = Command::new(&python)
        .args(["-c", &format!("import {modules}")])
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|status| status.success());
    if !found {
        eprintln!(
            "skipped: {packages} not installed for {} (set AWL_PYTHON; .ci/run installs it)",
            python.display()
        );
    }
    found.then_some(python)
}
