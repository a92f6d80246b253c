//! The Python the real-client tests run their clients with. Each set of clients is pinned in a
//! requirements file under tests/clients/; the first test that needs a set makes a virtual
//! environment of it under `target/` (`python3 -m venv`, then pip), once for all the test
//! threads and processes that ask at the same time (they wait on a lock file), and later runs
//! reuse it until the file changes. `AWL_PYTHON` names a Python to use instead of the main set's
//! environment. Where the clients cannot be had the test fails, naming the command that
//! installs them: a test that did not run never passes.

use std::fs::{self, File};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

/// A set of clients: its requirements file and the environment the tests make of it.
pub struct Clients {
    /// The requirements file, under tests/clients/.
    requirements: &'static str,
    /// The environment's folder under target/.
    folder: &'static str,
    /// The variable naming a Python to use instead of the environment.
    variable: Option<&'static str>,
    /// The environment's Python once made (or why it could not be), for every test thread.
    made: OnceLock<Result<PathBuf, String>>,
}

/// python-snap7 3.x, pymodbus and pytest-lsp.
pub static MAIN: Clients = Clients::new("requirements.txt", "clients", Some("AWL_PYTHON"));

/// python-snap7 1.x, whose wheel bundles Snap7's C library.
pub static SNAP7_1: Clients = Clients::new("requirements-snap7-1.txt", "clients-snap7-1", None);

/// The Python of the main clients, which must import `modules` (`"snap7, pymodbus"`).
pub fn with(modules: &str) -> PathBuf {
    MAIN.python(modules)
}

/// A command that runs `python`, writing no `__pycache__` beside the scripts it imports.
pub fn command(python: &Path) -> Command {
    let mut command = Command::new(python);
    command.env("PYTHONDONTWRITEBYTECODE", "1");
    command
}

/// Runs the client script `tests/clients/SCRIPT` with `args` on the Python that imports
/// `modules`; what it printed (it must succeed).
pub fn client(modules: &str, script: &str, args: &[&str]) -> String {
    let clients = repo().join("tests/clients");
    let output = command(&with(modules))
        .arg(clients.join(script))
        .args(args)
        .current_dir(&clients)
        .output()
        .expect("python runs");
    let printed = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{printed}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    printed
}

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

impl Clients {
    const fn new(
        requirements: &'static str,
        folder: &'static str,
        variable: Option<&'static str>,
    ) -> Clients {
        Clients {
            requirements,
            folder,
            variable,
            made: OnceLock::new(),
        }
    }

    /// The Python to run the clients with, which imports `modules`; panics, saying how to
    /// install them, where there is none.
    pub fn python(&self, modules: &str) -> PathBuf {
        let chosen = self.variable.and_then(std::env::var_os).map(PathBuf::from);
        let python = match &chosen {
            Some(python) => python.clone(),
            None => match self.made.get_or_init(|| self.make()) {
                Ok(python) => python.clone(),
                Err(why) => panic!("{why}"),
            },
        };
        if let Err(why) = imports(&python, modules) {
            let remedy = match (self.variable, chosen) {
                (Some(variable), Some(_)) => format!(
                    "install them with `{} -m pip install -r tests/clients/{}`, or unset \
                     {variable} to let the tests make their own environment",
                    python.display(),
                    self.requirements
                ),
                _ => format!(
                    "remove target/{} for the tests to make it again, or make it yourself: {}",
                    self.folder,
                    self.command()
                ),
            };
            panic!(
                "{} cannot import {modules}: {why}\n{remedy}",
                python.display()
            );
        }
        python
    }

    /// The command that makes the environment by hand, from the repository's folder.
    fn command(&self) -> String {
        format!(
            "`python3 -m venv target/{folder} && target/{folder}/bin/pip install -r tests/clients/{}`",
            self.requirements,
            folder = self.folder
        )
    }

    /// Makes the environment unless it holds this requirements file's packages; its Python.
    fn make(&self) -> Result<PathBuf, String> {
        let target = repo().join("target");
        fs::create_dir_all(&target).map_err(|error| self.failed("target/", error))?;
        // Held until the environment is made: other test processes wait for it.
        let lock = File::create(target.join(format!("{}.lock", self.folder)))
            .and_then(|lock| lock.lock().map(|()| lock))
            .map_err(|error| self.failed("its lock file", error))?;
        let requirements = fs::read_to_string(self.requirements_path())
            .map_err(|error| self.failed(self.requirements, error))?;
        let folder = target.join(self.folder);
        let python = folder.join(if cfg!(windows) {
            "Scripts/python.exe"
        } else {
            "bin/python"
        });
        // The copy of the requirements the environment was made from, written last.
        let made_from = folder.join(self.requirements);
        if fs::read_to_string(&made_from).ok().as_ref() != Some(&requirements) {
            let _ = fs::remove_dir_all(&folder);
            run(Command::new("python3").args(["-m", "venv"]).arg(&folder))
                .map_err(|why| self.failed("python3 -m venv", why))?;
            run(Command::new(&python)
                .args([
                    "-m",
                    "pip",
                    "install",
                    "--quiet",
                    "--disable-pip-version-check",
                ])
                .arg("-r")
                .arg(self.requirements_path()))
            .map_err(|why| self.failed("pip install", why))?;
            fs::write(&made_from, &requirements)
                .map_err(|error| self.failed("writing its stamp", error))?;
        }
        drop(lock);
        Ok(python)
    }

    fn requirements_path(&self) -> PathBuf {
        repo().join("tests/clients").join(self.requirements)
    }

    /// Why the environment could not be made, and how to make it by hand.
    fn failed(&self, what: &str, why: impl std::fmt::Display) -> String {
        format!(
            "the tests could not make the clients' environment in target/{}: {what}: {why}\n\
             Make it with {} (this needs python3 with its venv module, on Debian \
             `apt-get install python3-venv`, and the network for pip)",
            self.folder,
            self.command()
        )
    }
}

/// Whether `python` imports `modules`; the exception's line (not the traceback above it) where
/// it does not.
fn imports(python: &Path, modules: &str) -> Result<(), String> {
    let output = Command::new(python)
        .args(["-c", &format!("import {modules}")])
        .stdout(Stdio::null())
        .output()
        .map_err(|error| error.to_string())?;
    if output.status.success() {
        return Ok(());
    }
    let stderr = String::from_utf8_lossy(&output.stderr);
    Err(stderr.trim().lines().last().unwrap_or_default().to_string())
}

/// Runs a command to its end; what it said when it failed.
fn run(command: &mut Command) -> Result<(), String> {
    let output = command
        .current_dir(repo())
        .stdin(Stdio::null())
        .output()
        .map_err(|error| format!("cannot run {}: {error}", command.get_program().display()))?;
    if output.status.success() {
        return Ok(());
    }
    Err(format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
    .trim()
    .to_string())
}
