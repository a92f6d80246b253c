//! The language server's re-check: the time from an edit of a 10,000-line document to its
//! diagnostics, as an editor sees it (the edit goes over the protocol as the whole text, the
//! diagnostics come back as a notification). Target: within 100 ms, in release mode. A STEP 5
//! program with the CPU set (a scenario or a setting names one), the same program without a
//! CPU (it is compiled for every profile to tell which ones take it), and a STEP 7 source.

use std::path::PathBuf;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::{Value, json};

mod generated;

const LINES: usize = 10_000;

/// A server on a memory connection with one document open.
struct Session {
    client: Connection,
    server: Option<std::thread::JoinHandle<Result<(), String>>>,
    uri: String,
    text: String,
    version: i32,
}

impl Session {
    fn open(name: &str, text: String, options: Value) -> Session {
        let folder = std::env::temp_dir().join(format!("awl-bench-lsp-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let path: PathBuf = folder.join(name);
        let uri = format!("file://{}", path.display());
        let (client, server) = Connection::memory();
        let server = std::thread::spawn(move || awl::lsp::serve(&server));
        let initialize = json!({"capabilities": {}, "initializationOptions": options});
        let request = Request::new(RequestId::from(1), "initialize".into(), initialize);
        client.sender.send(request.into()).unwrap();
        let session = Session {
            client,
            server: Some(server),
            uri,
            text,
            version: 1,
        };
        session.wait_for(|message| matches!(message, Message::Response(_)));
        session.notify("initialized", json!({}));
        let document = json!({"textDocument": {"uri": session.uri, "languageId": "awl", "version": 1, "text": session.text}});
        session.notify("textDocument/didOpen", document);
        session.wait_for_diagnostics();
        session
    }

    fn notify(&self, method: &str, params: Value) {
        let message = Notification::new(method.to_string(), params);
        self.client.sender.send(message.into()).unwrap();
    }

    fn wait_for(&self, wanted: impl Fn(&Message) -> bool) -> Message {
        loop {
            let message = self
                .client
                .receiver
                .recv_timeout(Duration::from_secs(60))
                .expect("the server answers");
            if wanted(&message) {
                return message;
            }
        }
    }

    /// The document's diagnostics (not those of other files), with the number of errors.
    fn wait_for_diagnostics(&self) -> usize {
        let message = self.wait_for(|message| {
            matches!(message, Message::Notification(notification)
                if notification.method == "textDocument/publishDiagnostics"
                    && notification.params["uri"] == self.uri.as_str())
        });
        let Message::Notification(notification) = message else {
            unreachable!()
        };
        let diagnostics = notification.params["diagnostics"]
            .as_array()
            .unwrap()
            .iter();
        diagnostics.filter(|found| found["severity"] == 1).count()
    }

    /// Types one character at the end of the document's middle line, or takes it away again.
    fn edit_and_recheck(&mut self) -> usize {
        self.version += 1;
        let middle = self.text.len() / 2;
        let line_end = middle + self.text[middle..].find('\n').unwrap();
        if self.version % 2 == 0 {
            self.text.insert(line_end, ' ');
        } else {
            self.text.remove(line_end - 1);
        }
        let change = json!({
            "textDocument": {"uri": self.uri, "version": self.version},
            "contentChanges": [{"text": self.text}]
        });
        self.notify("textDocument/didChange", change);
        self.wait_for_diagnostics()
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        let request = Request::new(RequestId::from(2), "shutdown".into(), Value::Null);
        self.client.sender.send(request.into()).unwrap();
        self.wait_for(|message| matches!(message, Message::Response(_)));
        self.notify("exit", Value::Null);
        self.server.take().unwrap().join().unwrap().unwrap();
    }
}

fn bench_recheck(c: &mut Criterion) {
    let step5 = generated::generate(LINES);
    let step7 = generated::generate_step7(LINES);
    let cases = [
        (
            "step5_cpu_set",
            "gen.awl",
            &step5,
            json!({"cpu": "sinumerik-840c"}),
        ),
        ("step5_without_cpu", "gen.awl", &step5, Value::Null),
        ("step7", "gen7.awl", &step7, json!({"cpu": "speed7"})),
    ];
    let mut group = c.benchmark_group("lsp_recheck_10k_lines");
    group.sample_size(20);
    for (name, file, text, options) in cases {
        let mut session = Session::open(file, text.clone(), options);
        assert_eq!(
            session.edit_and_recheck(),
            0,
            "{name}: the generated program has no errors"
        );
        group.bench_function(name, |b| b.iter(|| session.edit_and_recheck()));
    }
    group.finish();
}

criterion_group!(benches, bench_recheck);
criterion_main!(benches);
