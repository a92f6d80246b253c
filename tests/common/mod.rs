//! Helpers shared by the integration tests: run STL text on a CPU and look at the result.
#![allow(dead_code)]

pub mod browser;
pub mod fake_memory;
pub mod online;
pub mod python;
pub mod serve;
pub mod step7;

use std::io::Read;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdout};
use std::sync::{Arc, mpsc};
use std::time::Instant;

use awl::frontend;
use awl::profile;
use awl::runner::{self, NotRun, Ran, RunOptions};
use awl::vm::Cpu;
use awl::vm::cycle::{RunLimit, RunOutcome};
use awl::vm::interrupts::{Engine, EngineConfig, Scheduled};

/// The interrupt OBs a test requests on `cpu`: not the S5-95F's OB 13, which its own timing
/// drives, nor the error OBs 82 and 85, which the CPU starts itself.
pub fn requestable_obs(cpu: &profile::Profile) -> Vec<u8> {
    cpu.interrupt_obs
        .iter()
        .map(|entry| entry.ob)
        .filter(|ob| ![13, 82, 85].contains(ob))
        .collect()
}

/// Compiles `source` for `cpu` (it must be free of errors) and runs it.
pub fn run_with(
    source: &str,
    cpu: &str,
    limit: RunLimit,
    config: EngineConfig,
    schedule: Vec<Scheduled>,
) -> (Cpu, RunOutcome) {
    let profile = profile::find(cpu).expect("known profile");
    let built = frontend::build_text("test.awl", source, profile);
    assert!(!built.has_errors(), "{:#?}", built.diagnostics);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    cpu.engine = Engine::new(profile, config, schedule);
    let outcome = cpu.run(limit);
    (cpu, outcome)
}

/// One cycle on the default CPU.
pub fn run_once(source: &str) -> (Cpu, RunOutcome) {
    run_with(
        source,
        "sinumerik-840c",
        RunLimit::Cycles(1),
        EngineConfig::default(),
        Vec::new(),
    )
}

/// Flag word `n` as a signed number.
pub fn fw(cpu: &Cpu, n: usize) -> i16 {
    let base = 2 * usize::from(cpu.program.layout.image_bytes) + n;
    i16::from_be_bytes([cpu.image[base], cpu.image[base + 1]])
}

pub fn fd(cpu: &Cpu, n: usize) -> u32 {
    let base = 2 * usize::from(cpu.program.layout.image_bytes) + n;
    u32::from_be_bytes([
        cpu.image[base],
        cpu.image[base + 1],
        cpu.image[base + 2],
        cpu.image[base + 3],
    ])
}

pub fn flag(cpu: &Cpu, byte: usize, bit: u8) -> bool {
    cpu.image[2 * usize::from(cpu.program.layout.image_bytes) + byte] >> bit & 1 == 1
}

pub fn output(cpu: &Cpu, byte: usize, bit: u8) -> bool {
    cpu.image[usize::from(cpu.program.layout.image_bytes) + byte] >> bit & 1 == 1
}

/// Writes a program and a scenario under `target/test-scenarios/<name>/` and runs it as
/// `awl run --scenario` would; paths are relative so rendered reports are stable.
pub fn run_scenario(name: &str, program: &str, scenario: &str) -> Result<Ran, NotRun> {
    runner::run(&RunOptions {
        scenario: Some(write_scenario(name, program, scenario)),
        ..RunOptions::default()
    })
}

/// Writes `program.awl` and `scenario.toml` (naming it) under `target/test-scenarios/<name>/`;
/// the scenario's path.
pub fn write_scenario(name: &str, program: &str, scenario: &str) -> PathBuf {
    let dir = PathBuf::from("target/test-scenarios").join(name);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("program.awl"), program).unwrap();
    let path = dir.join("scenario.toml");
    std::fs::write(&path, format!("program = [\"program.awl\"]\n{scenario}")).unwrap();
    path
}

/// Runs a program and scenario (written as [`write_scenario`] does) with a jsonl trace; the
/// run and the trace's events.
pub fn traced(name: &str, program: &str, scenario: &str) -> (Ran, Vec<serde_json::Value>) {
    let path = write_scenario(name, program, scenario);
    traced_scenario(&path, &path.with_file_name("trace.jsonl"))
}

/// Runs a scenario file with a jsonl trace written to `trace`.
pub fn traced_scenario(
    scenario: &std::path::Path,
    trace: &std::path::Path,
) -> (Ran, Vec<serde_json::Value>) {
    let options = RunOptions {
        scenario: Some(scenario.into()),
        trace: Some(trace.into()),
        ..RunOptions::default()
    };
    let ran = ran(runner::run(&options));
    let events = std::fs::read_to_string(trace)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect();
    (ran, events)
}

/// The trace events of one kind (`"irq_service"`, …).
pub fn of<'a>(events: &'a [serde_json::Value], kind: &str) -> Vec<&'a serde_json::Value> {
    events.iter().filter(|event| event["ev"] == kind).collect()
}

pub fn ran(result: Result<Ran, NotRun>) -> Ran {
    match result {
        Ok(ran) => ran,
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

/// A trace written to memory, shared with the tracer that writes it.
#[derive(Clone, Default)]
pub struct Buffer(pub std::sync::Arc<std::sync::Mutex<Vec<u8>>>);

impl std::io::Write for Buffer {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(bytes);
        Ok(bytes.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Buffer {
    /// The jsonl events written so far.
    pub fn events(&self) -> Vec<serde_json::Value> {
        let bytes = self.0.lock().unwrap().clone();
        String::from_utf8(bytes)
            .unwrap()
            .lines()
            .map(|line| serde_json::from_str(line).unwrap())
            .collect()
    }
}

/// The folders of sample programs with their scenarios: the STEP 5 samples and the STEP 7 ones
/// (not programs/bench/).
pub const SAMPLE_DIRS: [&str; 2] = ["programs", "programs/s7"];

/// The files of the sample folders whose names end in `.extension`, in name order.
pub fn sample_files(extension: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = SAMPLE_DIRS
        .iter()
        .flat_map(|dir| std::fs::read_dir(dir).expect("a sample folder"))
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.extension().is_some_and(|ext| ext == extension))
        .collect();
    files.sort();
    files
}

/// The sample scenarios of programs/ and programs/s7/ (not programs/bench/), in name order.
pub fn sample_scenarios() -> Vec<PathBuf> {
    sample_files("toml")
}

/// Every file of `programs/` and `web/examples/`, named as the playground names them
/// (`fig5_2.awl`, `bench/calls.toml`, `mistakes.awl`).
pub fn playground_files() -> std::collections::BTreeMap<String, String> {
    let mut files = std::collections::BTreeMap::new();
    for root in ["programs", "web/examples"] {
        add_files(Path::new(root), Path::new(root), &mut files);
    }
    files
}

fn add_files(root: &Path, dir: &Path, files: &mut std::collections::BTreeMap<String, String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            add_files(root, &path, files);
        } else if let Ok(text) = std::fs::read_to_string(&path) {
            let name = path.strip_prefix(root).unwrap().to_string_lossy();
            files.insert(name.replace('\\', "/"), text);
        }
    }
}

/// What `awl run --scenario programs/NAME` prints on stdout, the wall time and rate cut from
/// its last line.
pub fn cli_summary(scenario: &str) -> String {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["run", "--scenario"])
        .arg(Path::new("programs").join(scenario))
        .output()
        .unwrap();
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .map(|line| line.split("   wall:").next().unwrap())
        .map(|line| format!("{line}\n"))
        .collect()
}

/// A child's standard output, line by line as it comes (a server's listening lines).
pub fn lines(stdout: ChildStdout) -> mpsc::Receiver<String> {
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if send.send(line).is_err() {
                return;
            }
        }
    });
    receive
}

/// The next line of `lines` before `deadline`; without one the child is killed and the test
/// fails with its stderr, saying `what` it waited for.
pub fn next_line(
    child: &mut Child,
    lines: &mpsc::Receiver<String>,
    deadline: Instant,
    what: &str,
) -> String {
    let left = deadline.saturating_duration_since(Instant::now());
    lines.recv_timeout(left).unwrap_or_else(|_| {
        let _ = child.kill();
        let mut stderr = String::new();
        let _ = child
            .stderr
            .take()
            .map(|mut err| err.read_to_string(&mut stderr));
        panic!("awl serve printed no {what}: {stderr}");
    })
}

/// A fresh folder `target/test-files/GROUP/NAME` for a test's files.
pub fn scratch(group: &str, name: &str) -> PathBuf {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target/test-files")
        .join(group)
        .join(name);
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// `awl run ARGS` in the repository.
pub fn awl_run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_awl"))
        .arg("run")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("awl runs")
}

/// Sends `signal` (`-TERM`, `-KILL`) to `child` and waits until it has ended.
pub fn end_with(child: &mut Child, signal: &str) {
    let pid = child.id().to_string();
    let sent = std::process::Command::new("kill")
        .args([signal, &pid])
        .status();
    assert!(sent.is_ok_and(|status| status.success()), "kill {signal}");
    let deadline = Instant::now() + std::time::Duration::from_secs(30);
    while child.try_wait().expect("waits").is_none() {
        assert!(Instant::now() < deadline, "the child did not end");
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
}

/// The code block after `<!-- serve-snippet: NAME -->` in the README.
pub fn readme_snippet(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("README.md");
    let readme = std::fs::read_to_string(path).expect("the README");
    let marker = format!("<!-- serve-snippet: {name} -->\n```python\n");
    let start = readme.find(&marker).expect("the snippet's marker") + marker.len();
    let end = readme[start..].find("```").expect("the snippet's end") + start;
    readme[start..end].to_string()
}

/// Asserts that a JSON-lines trace has a client's write of `operand` and, after it, the request
/// of OB `ob` it raised.
pub fn assert_write_raises(trace: &str, operand: &str, ob: u8) {
    let write = trace
        .lines()
        .position(|line| {
            line.contains("\"client_write\"") && line.contains(&format!("\"{operand}\""))
        })
        .unwrap_or_else(|| panic!("the client's write of {operand} is traced"));
    let request = trace
        .lines()
        .position(|line| line.contains("\"irq_request\"") && line.contains(&format!("\"ob\":{ob}")))
        .unwrap_or_else(|| panic!("OB {ob} is requested"));
    assert!(write < request, "the write comes first");
}
