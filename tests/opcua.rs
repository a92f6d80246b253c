//! `awl serve --opcua` with two independent clients: asyncua (Python, in the environment
//! tests/common/python.rs makes) and node-opcua (JavaScript, installed by npm into target/ from
//! tests/clients/node/package.json), on 127.0.0.1 and ports the system picks. The server's
//! certificate is made once in target/opcua-data (`AWL_DATA_DIR`), shared by the tests.

mod common;

use std::fs::{self, File};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const AWL: &str = env!("CARGO_BIN_EXE_awl");

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// A running `awl serve --opcua 127.0.0.1:0` and the port it printed; killed when dropped
/// unless it was terminated.
struct Served {
    child: Option<Child>,
    port: u16,
    stdout: mpsc::Receiver<String>,
}

impl Drop for Served {
    fn drop(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Starts `awl serve ARGS --opcua 127.0.0.1:0` with the tests' data folder. One start at a
/// time: the first makes the server's certificate, which the others then read.
fn serve(args: &[&str]) -> Served {
    let data = repo("target/opcua-data");
    fs::create_dir_all(&data).expect("target/ is writable");
    let lock = File::create(repo("target/opcua-data.lock")).expect("the lock file");
    lock.lock().expect("the lock");
    let mut child = Command::new(AWL)
        .arg("serve")
        .args(args)
        .args(["--opcua", "127.0.0.1:0"])
        .env("AWL_DATA_DIR", &data)
        .current_dir(repo("."))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("awl starts");
    let stdout = common::lines(child.stdout.take().expect("piped"));
    // The first start makes an RSA key, which takes a while in a debug build.
    let deadline = Instant::now() + Duration::from_secs(180);
    let port = loop {
        let line = common::next_line(&mut child, &stdout, deadline, "the listening line");
        if let Some(address) = line.strip_prefix("OPC UA server listening on opc.tcp://") {
            break address
                .rsplit(':')
                .next()
                .and_then(|port| port.parse().ok())
                .expect("a port");
        }
    };
    drop(lock);
    Served {
        child: Some(child),
        port,
        stdout,
    }
}

impl Served {
    /// Runs an asyncua script of tests/clients with the port and `more`; it must succeed.
    fn python(&self, script: &str, more: &[&str]) -> String {
        let python = common::python::with("asyncua");
        let output = common::python::command(&python)
            .arg(repo("tests/clients").join(script))
            .arg(self.port.to_string())
            .args(more)
            .current_dir(repo("tests/clients"))
            .output()
            .expect("python runs");
        succeeded(script, &output)
    }

    /// Runs the node-opcua client with the port and `more`; it must succeed.
    fn node(&self, more: &[&str]) -> String {
        let folder = node_clients();
        let output = Command::new("node")
            .arg(repo("tests/clients/node/opcua_client.js"))
            .arg(self.port.to_string())
            .args(more)
            .env("NODE_PATH", folder.join("node_modules"))
            .output()
            .expect("node runs");
        succeeded("opcua_client.js", &output)
    }

    /// Ends the serve with SIGTERM; its exit code, standard output and error.
    fn terminate(mut self) -> (Option<i32>, String, String) {
        let child = self.child.take().expect("not yet terminated");
        let pid = child.id().to_string();
        let sent = Command::new("kill").args(["-TERM", &pid]).status();
        assert!(sent.is_ok_and(|status| status.success()), "kill -TERM");
        let output = child.wait_with_output().expect("awl ends");
        let stdout: Vec<String> = self.stdout.iter().collect();
        (
            output.status.code(),
            stdout.join("\n"),
            String::from_utf8_lossy(&output.stderr).into_owned(),
        )
    }
}

fn succeeded(script: &str, output: &Output) -> String {
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{script} failed:\n{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    stdout
}

/// node-opcua, installed once into target/opcua-node from tests/clients/node/package.json
/// (again when the file changes), under a lock for the tests that ask at once.
fn node_clients() -> PathBuf {
    let folder = repo("target/opcua-node");
    let install = "`npm install --prefix target/opcua-node tests/clients/node` (needs Node.js \
                   with npm, on Debian `apt-get install npm`, and the network)";
    fs::create_dir_all(&folder).expect("target/ is writable");
    let lock = File::create(repo("target/opcua-node.lock")).expect("the lock file");
    lock.lock().expect("the lock");
    let package = fs::read_to_string(repo("tests/clients/node/package.json")).expect("package");
    let stamp = folder.join("package.json.installed");
    if fs::read_to_string(&stamp).ok().as_ref() != Some(&package) {
        fs::copy(
            repo("tests/clients/node/package.json"),
            folder.join("package.json"),
        )
        .expect("the package file copied");
        let installed = Command::new("npm")
            .args(["install", "--no-audit", "--no-fund", "--silent"])
            .current_dir(&folder)
            .output()
            .unwrap_or_else(|error| {
                panic!("npm does not run ({error}); install node-opcua with {install}")
            });
        assert!(
            installed.status.success(),
            "npm could not install node-opcua: {}\nInstall it with {install}",
            String::from_utf8_lossy(&installed.stderr)
        );
        fs::write(&stamp, &package).expect("the stamp");
    }
    drop(lock);
    folder
}

#[test]
fn asyncua_browses_reads_writes_subscribes_and_calls_the_methods_of_a_step7_program() {
    let served = serve(&["tests/inputs/serve/opcua.awl"]);
    let said = served.python("opcua_s7.py", &[]);
    assert!(said.contains("STEP 7: ok"), "{said}");
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("served: "), "{stdout}");
}

#[test]
fn asyncua_reads_and_writes_a_step5_program_s_data_words() {
    let served = serve(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    served.python("opcua_s5.py", &[]);
}

#[test]
fn a_read_only_serve_refuses_writes_and_methods_with_bad_user_access_denied() {
    let served = serve(&["tests/inputs/serve/opcua.awl", "--read-only"]);
    served.python("opcua_read_only.py", &[]);
}

#[test]
fn basic256sha256_sign_and_encrypt_with_a_user_and_password_from_the_users_file() {
    let folder = std::env::temp_dir().join(format!("awl-opcua-{}", std::process::id()));
    fs::create_dir_all(&folder).expect("a temporary folder");
    let users = folder.join("users.toml");
    fs::write(&users, "[users]\noperator = \"secret\"\n").expect("the users file");
    let users = users.display().to_string();
    let served = serve(&["tests/inputs/serve/opcua.awl", "--opcua-users", &users]);
    served.python("opcua_secure.py", &[&folder.display().to_string()]);
    let _ = fs::remove_dir_all(&folder);
}

#[test]
fn an_input_written_over_opc_ua_raises_ob_40_and_is_traced() {
    let trace = std::env::temp_dir().join(format!("awl-opcua-{}.jsonl", std::process::id()));
    let trace_arg = trace.display().to_string();
    let served = serve(&[
        "--scenario",
        "tests/inputs/serve/tank_alarm.toml",
        "--trace",
        &trace_arg,
    ]);
    served.python("opcua_interrupt.py", &[]);
    let (code, _, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    let trace = fs::read_to_string(&trace).expect("the trace is written");
    common::assert_write_raises(&trace, "I 8.0", 40);
    assert!(
        trace.contains("\"client\":\"opcua #"),
        "named by its client"
    );
}

#[test]
fn node_opcua_browses_reads_writes_subscribes_and_calls_in_both_dialects() {
    let served = serve(&["tests/inputs/serve/opcua.awl"]);
    let said = served.node(&["s7"]);
    assert!(said.contains("node-opcua, STEP 7: ok"), "{said}");
    let s5 = serve(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    let said = s5.node(&["s5"]);
    assert!(said.contains("node-opcua, STEP 5: ok"), "{said}");
    let read_only = serve(&["tests/inputs/serve/opcua.awl", "--read-only"]);
    let said = read_only.node(&["read-only"]);
    assert!(said.contains("node-opcua, read-only: ok"), "{said}");
}

#[test]
fn hundreds_of_monitored_items_across_four_clients_keep_arriving() {
    let served = serve(&["tests/inputs/serve/opcua.awl"]);
    let said = served.python("opcua_load.py", &["4", "100", "3"]);
    assert!(said.contains("4 clients x 100 items"), "{said}");
    let (code, stdout, stderr) = served.terminate();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stdout.contains("over 4 connections"), "{stdout}");
}

#[test]
fn malformed_messages_are_answered_and_the_cpu_keeps_its_cycle() {
    use std::io::{Read, Write};
    let served = serve(&["tests/inputs/serve/opcua.awl"]);
    for garbage in [
        &b"HELF\x08\x00\x00\x00"[..],
        b"HELF\xff\xff\xff\x7f\x00\x00\x00\x00",
        b"MSGF\x10\x00\x00\x00\x01\x00\x00\x00\x00\x00\x00\x00",
        &[0u8; 64],
    ] {
        let mut stream =
            std::net::TcpStream::connect(("127.0.0.1", served.port)).expect("connects");
        stream
            .set_read_timeout(Some(Duration::from_secs(5)))
            .expect("a timeout");
        stream.write_all(garbage).expect("sent");
        let mut answer = Vec::new();
        let _ = stream.read_to_end(&mut answer);
    }
    let said = served.python("opcua_load.py", &["1", "2", "1"]);
    assert!(said.contains("1 clients x 2 items"), "{said}");
}

#[test]
fn the_readme_s_opc_ua_snippet_runs_as_printed() {
    let served = serve(&["--scenario", "programs/s7/tank_hmi_serve.toml"]);
    // The README serves on port 4840; here the system picked the port.
    let snippet = common::readme_snippet("opcua").replace("4840", &served.port.to_string());
    let python = common::python::with("asyncua");
    let output = common::python::command(&python)
        .args(["-c", &snippet])
        .output()
        .expect("python runs");
    let stdout = succeeded("the README's snippet", &output);
    assert_eq!(stdout, "500\nthe pump runs\nSTOP\n");
}

#[test]
fn a_users_file_without_users_is_refused_before_the_serve_starts() {
    let users = std::env::temp_dir().join(format!("awl-no-users-{}.toml", std::process::id()));
    fs::write(&users, "[users]\n").expect("the users file");
    let output = Command::new(AWL)
        .args([
            "serve",
            "tests/inputs/serve/opcua.awl",
            "--opcua",
            "127.0.0.1:0",
        ])
        .arg("--opcua-users")
        .arg(&users)
        .current_dir(repo("."))
        .output()
        .expect("awl runs");
    let _ = fs::remove_file(&users);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("awl::serve::opcua_users"), "{stderr}");
    // The report wraps where the path's length puts it: its words are checked unwrapped.
    let words = stderr.replace('│', " ");
    let words: Vec<&str> = words.split_whitespace().collect();
    assert!(words.join(" ").contains("it names no user"), "{stderr}");
    assert!(output.stdout.is_empty(), "no listening line");
}
