//! `awl serve`'s snapshot key: `s` and Enter on the terminal writes a snapshot of the whole
//! CPU beside the program, taken at the CPU's next control point.

use std::io::BufRead;
use std::path::PathBuf;

use crate::retain::file::write_durably;
use crate::retain::snapshot::beside;
use crate::serve::request::{Ask, Client, Protocol, Request, Requests};

/// Reads the terminal's lines on a thread of their own until its input ends.
pub fn listen(requests: Requests, program: PathBuf) {
    let spawned = std::thread::Builder::new()
        .name("snapshot key".into())
        .spawn(move || {
            for line in std::io::stdin().lock().lines() {
                let Ok(line) = line else { return };
                if line.trim().eq_ignore_ascii_case("s") && !take(&requests, &program) {
                    return;
                }
            }
        });
    // Without the thread the key does nothing; the server runs on.
    drop(spawned);
}

/// Asks the CPU for a snapshot and writes it; `false` once the CPU is gone.
fn take(requests: &Requests, program: &std::path::Path) -> bool {
    let (reply, answer) = tokio::sync::oneshot::channel();
    let client = Client {
        protocol: Protocol::Terminal,
        number: 1,
    };
    let ask = Ask::Snapshot { reply };
    if requests.send(Request::Online { client, ask }).is_err() {
        return false;
    }
    let Ok(text) = answer.blocking_recv() else {
        return false;
    };
    let path = beside(program);
    match write_durably(&path, &text) {
        Ok(()) => eprintln!("snapshot written to {}", path.display()),
        Err(error) => eprintln!("{:?}", miette::Report::new(error)),
    }
    true
}
