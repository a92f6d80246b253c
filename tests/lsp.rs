//! `awl lsp` with a real client: the Python package pytest-lsp (in the environment
//! tests/common/python.rs makes under target/, or the Python at `AWL_PYTHON`) starts the binary
//! and talks to it over stdio. Where the package cannot be had the test fails, naming the command
//! that installs it.

mod common;

use std::path::{Path, PathBuf};

fn python() -> PathBuf {
    common::python::with("pytest_lsp")
}

const PLANT: &str = include_str!("inputs/lsp/plant.awl");

#[test]
fn a_real_client_gets_diagnostics_hover_and_definitions() {
    let python = python();
    let folder = std::env::temp_dir().join(format!("awl-lsp-client-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("plant.awl"), PLANT).unwrap();
    std::fs::write(
        folder.join("plant.seq"),
        "I 0.0     START     start button\nQ 4.0     LAMP      running lamp\n",
    )
    .unwrap();
    std::fs::write(
        folder.join("plant.toml"),
        "program = [\"plant.awl\"]\nsymbols = [\"plant.seq\"]\ncpu = \"s5-115u\"\n",
    )
    .unwrap();
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/lsp_client/test_lsp.py");
    let output = common::python::command(&python)
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
        .args(["-o", "asyncio_default_fixture_loop_scope=function"])
        .arg(tests)
        .env("AWL_BIN", env!("CARGO_BIN_EXE_awl"))
        .env("AWL_LSP_FOLDER", &folder)
        .output()
        .expect("python runs");
    let _ = std::fs::remove_dir_all(&folder);
    assert!(
        output.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}
