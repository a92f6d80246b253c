//! `awl serve` for the tests that talk to it: started in the repository on ports the system
//! picks, its standard output read line by line as it comes, ended when dropped.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

/// A running `awl serve`.
pub struct Serving {
    pub child: Child,
    /// Standard output's lines, as they come.
    pub stdout: Receiver<String>,
}

impl Serving {
    /// Starts `awl serve ARGS` and waits until it has printed a line that starts with each of
    /// `announcements` (`"S7 server listening on "`, `"Online page at "`); the ports those
    /// lines name, in the order of `announcements`.
    pub fn start(args: &[&str], announcements: &[&str]) -> (Serving, Vec<u16>) {
        let mut child = Command::new(env!("CARGO_BIN_EXE_awl"))
            .arg("serve")
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("awl starts");
        let stdout = child.stdout.take().expect("piped");
        let (send, lines) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                if send.send(line).is_err() {
                    return;
                }
            }
        });
        let mut ports = vec![0; announcements.len()];
        let deadline = Instant::now() + Duration::from_secs(60);
        while ports.contains(&0) {
            let left = deadline.saturating_duration_since(Instant::now());
            let Ok(line) = lines.recv_timeout(left) else {
                let _ = child.kill();
                let ended = child.wait_with_output().expect("awl ends");
                let stderr = String::from_utf8_lossy(&ended.stderr);
                panic!("awl serve printed no listening lines: {stderr}");
            };
            for (port, announcement) in ports.iter_mut().zip(announcements) {
                if let Some(address) = line.strip_prefix(announcement) {
                    *port = port_of(address);
                }
            }
        }
        let serving = Serving {
            child,
            stdout: lines,
        };
        (serving, ports)
    }
}

/// The port of `127.0.0.1:41234` or `http://127.0.0.1:41234/`.
fn port_of(address: &str) -> u16 {
    address
        .trim()
        .trim_end_matches('/')
        .rsplit(':')
        .next()
        .and_then(|port| port.parse().ok())
        .unwrap_or_else(|| panic!("no port in {address:?}"))
}

impl Drop for Serving {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
