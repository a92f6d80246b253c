//! Retentive memory and snapshots with `awl serve`: a data block an S7 client (python-snap7)
//! wrote survives a restart, a SIGTERM and a SIGKILL; a client's cold restart puts the source's
//! values back; SIGKILL at random moments, again and again, never tears the file nor loses more
//! than the interval; the online API's and the terminal's snapshots continue in `awl run`.

mod common;

use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::online::Online;
use common::serve::Serving;

const AWL: &str = env!("CARGO_BIN_EXE_awl");
const COUNTER: &str = "tests/inputs/retain/counter.awl";

fn folder(name: &str) -> PathBuf {
    common::scratch("retain-serve", name)
}

/// Sends `signal` to the serve and waits for it to end.
fn end(serving: &mut Serving, signal: &str) {
    common::end_with(&mut serving.child, signal);
}

/// The S7 client's answer: DB 1's setpoint after `action`.
fn s7(port: u16, action: &[&str]) -> i64 {
    let port = port.to_string();
    let args: Vec<&str> = std::iter::once(port.as_str())
        .chain(action.iter().copied())
        .collect();
    let printed = common::python::client("snap7", "retain_s7.py", &args);
    printed.lines().next().unwrap().trim().parse().unwrap()
}

fn serve_s7(retain: &Path) -> (Serving, u16) {
    let args = [
        COUNTER,
        "--s7",
        "127.0.0.1:0",
        "--retain",
        retain.to_str().unwrap(),
        "--retain-every",
        "100ms",
    ];
    let (serving, ports) = Serving::start(&args, &["S7 server listening on "]);
    (serving, ports[0])
}

#[test]
fn a_data_block_an_s7_client_wrote_survives_restarts_and_a_cold_restart_clears_it() {
    let retain = folder("s7").join("memory.json");
    let (mut serving, port) = serve_s7(&retain);
    assert_eq!(
        s7(port, &["read"]),
        500,
        "the source's value at a first start"
    );
    assert_eq!(s7(port, &["write", "1234"]), 1234);
    end(&mut serving, "-TERM");
    // A SIGTERM ends the serve with the memory written.
    let (mut serving, port) = serve_s7(&retain);
    assert_eq!(s7(port, &["read"]), 1234);
    assert_eq!(s7(port, &["write", "-4321"]), -4321);
    // A SIGKILL loses at most the interval (100 ms).
    std::thread::sleep(Duration::from_millis(400));
    end(&mut serving, "-KILL");
    let (mut serving, port) = serve_s7(&retain);
    assert_eq!(s7(port, &["read"]), -4321);
    // A client's cold restart: the source's values, written at once.
    assert_eq!(s7(port, &["cold"]), 500);
    end(&mut serving, "-KILL");
    let (mut serving, port) = serve_s7(&retain);
    assert_eq!(s7(port, &["read"]), 500);
    end(&mut serving, "-TERM");
}

/// DB1.count of the file, as the next run starts from it (one cycle later); the run fails on a
/// torn or damaged file.
fn count_in(retain: &Path) -> i64 {
    let output = common::awl_run(&[
        COUNTER,
        "--cycles",
        "1",
        "--retain",
        retain.to_str().unwrap(),
        "--watch",
        "DB1.count",
    ]);
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{printed}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let last = printed
        .lines()
        .nth(2)
        .expect("the row after the first cycle");
    let cell = last.split_whitespace().last().unwrap();
    cell.trim_start_matches("L#").parse::<i64>().unwrap() - 1
}

fn count_now(online: &Online) -> i64 {
    let row = online.values("DB1.count", "").remove(0);
    row["raw"].as_i64().expect("a count")
}

#[test]
fn sigkill_at_random_moments_never_tears_the_file_nor_loses_more_than_the_interval() {
    let retain = folder("sigkill").join("memory.json");
    let path = retain.to_str().unwrap();
    let every = Duration::from_millis(200);
    // Writing and syncing the file takes a little after the control point it was taken at.
    let slack = Duration::from_millis(300);
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut last_saved = 0;
    for round in 0..12 {
        let online = Online::start(&[COUNTER, "--retain", path, "--retain-every", "200ms"]);
        let first = count_now(&online);
        assert!(
            first >= last_saved,
            "round {round}: started from {first}, the file held {last_saved}"
        );
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let run_for = Duration::from_millis(250 + seed % 750);
        let started = Instant::now();
        let mut seen = Vec::new();
        while started.elapsed() < run_for {
            seen.push((Instant::now(), count_now(&online)));
            std::thread::sleep(Duration::from_millis(15));
        }
        let mut online = online;
        let pid = online.child.id().to_string();
        let killed_at = Instant::now();
        assert!(
            Command::new("kill")
                .args(["-KILL", &pid])
                .status()
                .unwrap()
                .success()
        );
        let _ = online.child.wait();
        let saved = count_in(&retain);
        let surely_saved = seen
            .iter()
            .filter(|(at, _)| *at + every + slack <= killed_at)
            .map(|(_, count)| *count)
            .max()
            .unwrap_or(first);
        assert!(
            saved >= surely_saved,
            "round {round}: the file holds {saved}, the CPU had counted {surely_saved} more than \
             {every:?} before the kill"
        );
        last_saved = saved;
    }
}

#[test]
fn a_snapshot_of_the_online_api_or_the_terminal_continues_in_awl_run() {
    let folder = folder("snapshot");
    let online = Online::start(&[COUNTER]);
    std::thread::sleep(Duration::from_millis(200));
    let (status, snapshot) = online.post("/api/snapshot", &serde_json::json!({}));
    assert_eq!(status, 200, "{snapshot}");
    assert_eq!(snapshot["format"], "awl-snapshot");
    let cycle = snapshot["body"]["state"]["cycle"]
        .as_u64()
        .expect("a cycle");
    let count = snapshot["body"]["state"]["memory"]["data_blocks"][0]["bytes"]
        .as_str()
        .map(|hex| i64::from_str_radix(&hex[..8], 16).unwrap())
        .expect("DB 1's bytes");
    assert!(
        cycle > 0 && count as u64 == cycle,
        "cycle {cycle}, count {count}"
    );
    let file = folder.join("online.json");
    std::fs::write(&file, serde_json::to_string(&snapshot).unwrap()).unwrap();
    let more = (cycle + 5).to_string();
    let output = common::awl_run(&[
        COUNTER,
        "--from",
        file.to_str().unwrap(),
        "--cycles",
        &more,
        "--watch",
        "DB1.count",
    ]);
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{printed}");
    assert!(printed.contains(&format!("L#{more}")), "{printed}");
    drop(online);

    // The terminal's key writes one beside the program.
    let program = folder.join("counter.awl");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join(COUNTER),
        &program,
    )
    .unwrap();
    let mut child = Command::new(AWL)
        .args(["serve", program.to_str().unwrap(), "--http", "127.0.0.1:0"])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("awl starts");
    let mut keys = child.stdin.take().unwrap();
    let mut errors = BufReader::new(child.stderr.take().unwrap()).lines();
    std::thread::sleep(Duration::from_millis(300));
    keys.write_all(b"s\n").unwrap();
    keys.flush().unwrap();
    let line = errors
        .find_map(|line| {
            line.ok()
                .filter(|line| line.starts_with("snapshot written to "))
        })
        .expect("the snapshot's line");
    let written = PathBuf::from(line.trim_start_matches("snapshot written to "));
    assert_eq!(written, folder.join("counter.snapshot-1.json"));
    let _ = child.kill();
    let _ = child.wait();
    let output = common::awl_run(&[
        COUNTER,
        "--from",
        written.to_str().unwrap(),
        "--cycles",
        "1",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    // `awl serve --from` continues from it too.
    let online = Online::start(&[COUNTER, "--from", written.to_str().unwrap()]);
    assert!(count_now(&online) > 0);
}
