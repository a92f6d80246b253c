//! The server on an in-memory connection: a client thread's requests and what comes back.

use std::path::{Path, PathBuf};

use lsp_server::{Connection, Message, Notification, Request, RequestId, Response};
use serde_json::{Value, json};

/// A STEP 5 plant: OB 1 calls FB 5 with parameters; the FB jumps to a label.
const PLANT: &str = include_str!("../../tests/inputs/lsp/plant.awl");

const LIST: &str = "I 0.0     START     start button (green)\nQ 4.0     LAMP      running lamp\n";

const SCENARIO: &str = "program = [\"plant.awl\"]\nsymbols = [\"plant.seq\"]\ncpu = \"s5-115u\"\n";

/// An empty folder of this test run's own.
fn scratch_folder(name: &str) -> PathBuf {
    let folder = std::env::temp_dir().join(format!("awl-lsp-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// The sample program that needs its CPU said.
fn analog_program() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("programs/analog_115u.awl");
    std::fs::read_to_string(path).unwrap()
}

/// A folder with the plant program, its assignment list and its scenario.
fn plant_folder(name: &str) -> PathBuf {
    let folder = scratch_folder(name);
    std::fs::write(folder.join("plant.awl"), PLANT).unwrap();
    std::fs::write(folder.join("plant.seq"), LIST).unwrap();
    std::fs::write(folder.join("plant.toml"), SCENARIO).unwrap();
    folder
}

/// A client of a server on a plant folder of its own, and the plant program's path.
fn plant_client(name: &str) -> (Client, PathBuf) {
    let folder = plant_folder(name);
    (
        Client::start(&folder, Value::Null),
        folder.join("plant.awl"),
    )
}

fn uri(path: &Path) -> String {
    format!("file://{}", path.display())
}

/// A client on one end of a memory connection, the server on the other.
struct Client {
    connection: Connection,
    server: Option<std::thread::JoinHandle<Result<(), String>>>,
    next: i32,
}

impl Client {
    fn start(root: &Path, options: Value) -> Client {
        let (client, server) = Connection::memory();
        let thread = std::thread::spawn(move || super::serve(&server));
        let mut client = Client {
            connection: client,
            server: Some(thread),
            next: 0,
        };
        let params =
            json!({"capabilities": {}, "rootUri": uri(root), "initializationOptions": options});
        let response = client.request("initialize", params);
        assert!(
            response.result.unwrap()["capabilities"]["hoverProvider"]
                .as_bool()
                .unwrap()
        );
        client.notify("initialized", json!({}));
        client
    }

    fn notify(&self, method: &str, params: Value) {
        let message = Notification::new(method.to_string(), params);
        self.connection.sender.send(message.into()).unwrap();
    }

    /// Sends a request; the notifications before its answer are dropped.
    fn request(&mut self, method: &str, params: Value) -> Response {
        self.next += 1;
        let id = RequestId::from(self.next);
        let request = Request::new(id.clone(), method.to_string(), params);
        self.connection.sender.send(request.into()).unwrap();
        loop {
            match self.receive() {
                Message::Response(response) if response.id == id => return response,
                _ => {}
            }
        }
    }

    fn receive(&self) -> Message {
        self.connection
            .receiver
            .recv_timeout(std::time::Duration::from_secs(30))
            .expect("the server answers")
    }

    /// The next diagnostics published for `path`.
    fn diagnostics(&self, path: &Path) -> Value {
        loop {
            if let Message::Notification(notification) = self.receive()
                && notification.method == "textDocument/publishDiagnostics"
                && notification.params["uri"] == uri(path)
            {
                return notification.params;
            }
        }
    }

    fn open(&self, path: &Path, text: &str) -> Value {
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri(path), "languageId": "awl", "version": 1, "text": text}}),
        );
        self.diagnostics(path)
    }

    fn at(&mut self, method: &str, path: &Path, line: u32, character: u32) -> Value {
        let params = json!({
            "textDocument": {"uri": uri(path)},
            "position": {"line": line, "character": character},
            "context": {"includeDeclaration": true}
        });
        self.request(method, params).result.unwrap_or(Value::Null)
    }

    /// The hover's text at a position (empty where there is none).
    fn hover(&mut self, path: &Path, line: u32, character: u32) -> String {
        let hover = self.at("textDocument/hover", path, line, character);
        hover["contents"]["value"]
            .as_str()
            .unwrap_or("")
            .to_string()
    }

    /// Asserts that the hover at a position says each of `texts`.
    fn assert_hover(&mut self, path: &Path, line: u32, character: u32, texts: &[&str]) {
        let hover = self.hover(path, line, character);
        assert!(texts.iter().all(|text| hover.contains(text)), "{hover}");
    }

    /// The document's symbols.
    fn outline(&mut self, path: &Path) -> Value {
        self.request(
            "textDocument/documentSymbol",
            json!({"textDocument": {"uri": uri(path)}}),
        )
        .result
        .unwrap()
    }

    fn finish(mut self) {
        let response = self.request("shutdown", Value::Null);
        assert!(response.error.is_none());
        self.notify("exit", Value::Null);
        let server = self.server.take().unwrap();
        assert_eq!(server.join().unwrap(), Ok(()));
    }
}

#[test]
fn errors_come_with_their_code_and_help_and_go_when_fixed() {
    let (client, path) = plant_client("errors");
    let broken = PLANT.replace("      R  =AUS", "      XYZ  =AUS");
    let published = client.open(&path, &broken);
    let diagnostics = published["diagnostics"].as_array().unwrap();
    let error = &diagnostics[0];
    assert_eq!(error["severity"], 1);
    assert!(
        error["code"].as_str().unwrap().starts_with("awl::"),
        "{error}"
    );
    assert_eq!(error["range"]["start"]["line"], 14, "{error}");
    // The code leads to its page, as `awl help error` prints it.
    let page = error["codeDescription"]["href"].as_str().unwrap();
    let page = super::workspace::path_of(&page.parse().unwrap()).unwrap();
    let text = std::fs::read_to_string(page).unwrap();
    assert!(text.contains(error["code"].as_str().unwrap()), "{text}");
    client.notify(
        "textDocument/didChange",
        json!({"textDocument": {"uri": uri(&path), "version": 2}, "contentChanges": [{"text": PLANT}]}),
    );
    assert_eq!(client.diagnostics(&path)["diagnostics"], json!([]));
    client.finish();
}

#[test]
fn an_assignment_list_s_errors_are_its_own() {
    let folder = plant_folder("list");
    std::fs::write(
        folder.join("plant.seq"),
        "I 0.0     START     start button\nQ 99999.0 LAMP\n",
    )
    .unwrap();
    let path = folder.join("plant.awl");
    let client = Client::start(&folder, Value::Null);
    client.open(&path, PLANT);
    let list = client.diagnostics(&folder.join("plant.seq"));
    let error = &list["diagnostics"][0];
    assert!(
        error["code"]
            .as_str()
            .unwrap()
            .starts_with("awl::symbols::"),
        "{list}"
    );
    assert_eq!(error["range"]["start"]["line"], 1, "{list}");
    client.finish();
}

#[test]
fn a_missing_assignment_list_is_told_at_the_top() {
    let folder = plant_folder("missing");
    std::fs::remove_file(folder.join("plant.seq")).unwrap();
    let path = folder.join("plant.awl");
    let client = Client::start(&folder, Value::Null);
    let published = client.open(&path, PLANT);
    let codes: Vec<&str> = published["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|diagnostic| diagnostic["code"].as_str())
        .collect();
    assert!(codes.contains(&"awl::cli::read_file"), "{published}");
    client.finish();
}

#[test]
fn hover_tells_the_operation_the_symbol_and_the_block() {
    let (mut client, path) = plant_client("hover");
    client.open(&path, PLANT);
    client.assert_hover(
        &path,
        1,
        6,
        // The status bits a STEP 5 CPU has: CC 1, CC 0, OV, OR, RLO, /FC.
        &[
            "`U`",
            "s5-115u",
            "| reads | - | - | - | x | x | x |",
            "| writes | - | - | - | x | x | 1 |",
        ],
    );
    client.assert_hover(&path, 1, 13, &["I 0.0", "start button"]);
    client.assert_hover(&path, 2, 13, &["DES  :EIN  I BI"]);
    client.assert_hover(
        &path,
        13,
        6,
        &["`SPB`", "RLO", "µs", "| writes | - | - | - | 0 | 1 | 0 |"],
    );
    let call = client.hover(&path, 2, 6);
    assert!(!call.contains("Status word"), "{call}");
    client.assert_hover(&path, 13, 10, &["line 17"]);
    client.finish();
}

#[test]
fn definitions_references_and_symbols() {
    let (mut client, path) = plant_client("navigate");
    client.open(&path, PLANT);
    let label = client.at("textDocument/definition", &path, 13, 10);
    assert_eq!(label["range"]["start"]["line"], 16, "{label}");
    let block = client.at("textDocument/definition", &path, 2, 12);
    assert_eq!(block["range"]["start"]["line"], 8, "{block}");
    let symbol = client.at("textDocument/definition", &path, 1, 13);
    assert!(
        symbol["uri"].as_str().unwrap().ends_with("plant.seq"),
        "{symbol}"
    );
    let uses = client.at("textDocument/references", &path, 13, 10);
    assert_eq!(uses.as_array().unwrap().len(), 2, "{uses}");
    let calls = client.at("textDocument/references", &path, 8, 3);
    assert_eq!(calls.as_array().unwrap().len(), 2, "{calls}");
    let outline = client.outline(&path);
    let names: Vec<&str> = outline
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["OB 1", "FB 5"]);
    let found = client
        .request("workspace/symbol", json!({"query": "fb"}))
        .result
        .unwrap();
    assert_eq!(found.as_array().unwrap().len(), 1, "{found}");
    client.finish();
}

#[test]
fn bad_requests_are_answered_and_the_server_stays() {
    let folder = plant_folder("bad");
    let path = folder.join("plant.awl");
    let mut client = Client::start(&folder, json!({"cpu": "no-such-cpu"}));
    let Message::Notification(message) = client.receive() else {
        panic!("a message about the setting comes first");
    };
    assert!(
        message.params["message"]
            .as_str()
            .unwrap()
            .contains("awl::lsp::unknown_cpu")
    );
    let unknown = client.request("textDocument/rename", json!({}));
    assert_eq!(
        unknown.error.unwrap().code,
        lsp_server::ErrorCode::MethodNotFound as i32
    );
    let bad = client.request("textDocument/hover", json!({"nonsense": true}));
    assert_eq!(
        bad.error.unwrap().code,
        lsp_server::ErrorCode::InvalidParams as i32
    );
    let not_open = client.at("textDocument/hover", &path, 0, 0);
    assert_eq!(not_open, Value::Null);
    client.open(&path, "\u{0}\u{1}FB \"\n((((");
    client.open(&path, "");
    let far = client.at("textDocument/hover", &path, 99, 99);
    assert_eq!(far, Value::Null);
    client.finish();
}

#[test]
fn a_client_that_vanishes_ends_the_server() {
    let folder = plant_folder("vanish");
    let mut client = Client::start(&folder, Value::Null);
    let server = client.server.take().unwrap();
    drop(client);
    assert_eq!(server.join().unwrap(), Ok(()));
}

const MOTOR: &str = "FUNCTION_BLOCK FB 1
VAR_INPUT
  start : BOOL;  // start button
END_VAR
BEGIN
NETWORK
TITLE = switch on
      U     #start;
      =     A 4.0;
END_FUNCTION_BLOCK
";

#[test]
fn a_step7_variable_shows_its_declaration_and_leads_to_it() {
    let folder = scratch_folder("step7");
    let path = folder.join("motor.awl");
    let mut client = Client::start(&folder, Value::Null);
    assert_eq!(client.open(&path, MOTOR)["diagnostics"], json!([]));
    client.assert_hover(&path, 7, 14, &["start : BOOL"]);
    client.assert_hover(
        &path,
        7,
        6,
        &[
            "English (SIMATIC) mnemonics: `A`",
            "| | BR | CC 1 | CC 0 | OV | OS | OR | STA | RLO | /FC |\n|---|---|---|---|---|---|---|---|---|---|\n| reads | - | - | - | - | - | x | - | x | x |\n| writes | - | - | - | - | - | x | x | x | 1 |",
        ],
    );
    let definition = client.at("textDocument/definition", &path, 7, 14);
    assert_eq!(definition["range"]["start"]["line"], 2, "{definition}");
    let outline = client.outline(&path);
    assert_eq!(outline[0]["name"], "FB 1", "{outline}");
    assert_eq!(outline[0]["children"][0]["name"], "network 1", "{outline}");
    client.finish();
}

#[test]
fn without_a_cpu_the_errors_say_which_cpus_compile_it() {
    let folder = scratch_folder("cpus");
    let program = analog_program();
    let path = folder.join("analog.awl");
    let client = Client::start(&folder, Value::Null);
    let published = client.open(&path, &program);
    let note = published["diagnostics"]
        .as_array()
        .unwrap()
        .iter()
        .find(|diagnostic| diagnostic["severity"] == 3)
        .cloned()
        .unwrap_or_default();
    assert!(
        note["message"]
            .as_str()
            .unwrap_or("")
            .contains("--cpu s5-115u-941"),
        "{published}"
    );
    client.finish();
    let client = Client::start(&folder, json!({"cpu": "s5-115u-944"}));
    assert_eq!(client.open(&path, &program)["diagnostics"], json!([]));
    client.finish();
}

#[test]
fn settings_sent_later_count_and_an_exit_alone_ends_the_server() {
    let folder = scratch_folder("later");
    let program = analog_program();
    let path = folder.join("analog.awl");
    let mut client = Client::start(&folder, Value::Null);
    assert_ne!(client.open(&path, &program)["diagnostics"], json!([]));
    client.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"awl": {"cpu": "s5-115u-944"}}}),
    );
    assert_eq!(client.diagnostics(&path)["diagnostics"], json!([]));
    client.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": null}),
    );
    client.notify("exit", Value::Null);
    let server = client.server.take().unwrap();
    assert_eq!(server.join().unwrap(), Ok(()));
}

#[test]
fn a_german_listing_finds_its_scenario_s_assignment_list() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("programs");
    let path = folder.join("filling_de.awl");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut client = Client::start(&folder, Value::Null);
    assert_eq!(client.open(&path, &text)["diagnostics"], json!([]));
    client.assert_hover(&path, 10, 18, &["Taster Fuellen ein"]);
    client.assert_hover(&path, 10, 11, &["English (SIMATIC) mnemonics: `A`"]);
    let call = client.at("textDocument/definition", &path, 6, 18);
    assert_eq!(call["range"]["start"]["line"], 8, "{call}");
    let outline = client.outline(&path);
    assert_eq!(
        outline[1]["children"].as_array().unwrap().len(),
        3,
        "{outline}"
    );
    client.finish();
}

fn complete(client: &mut Client, path: &Path, line: u32, character: u32) -> Value {
    let params = json!({
        "textDocument": {"uri": uri(path)},
        "position": {"line": line, "character": character},
        "context": {"triggerKind": 1}
    });
    let response = client.request("textDocument/completion", params);
    response
        .result
        .unwrap_or_else(|| panic!("{:?}", response.error))
}

/// `text` with the edits of a `TextEdit[]` in JSON made.
fn edited(text: &str, edits: &Value) -> String {
    let edits: Vec<lsp_types::TextEdit> = serde_json::from_value(edits.clone()).unwrap();
    let position = |at: lsp_types::Position| super::text::Position {
        line: at.line,
        character: at.character,
    };
    let edits: Vec<super::text::TextEdit> = edits
        .into_iter()
        .map(|edit| super::text::TextEdit {
            range: super::text::Range {
                start: position(edit.range.start),
                end: position(edit.range.end),
            },
            new_text: edit.new_text,
        })
        .collect();
    super::text::apply(text, &edits)
}

#[test]
fn completion_offers_the_symbols_and_the_operations() {
    let (mut client, path) = plant_client("complete");
    client.open(&path, &PLANT.replace("-START", "-ST"));
    let symbols = complete(&mut client, &path, 1, 15);
    let start = symbols
        .as_array()
        .unwrap()
        .iter()
        .find(|item| item["label"] == "-START")
        .unwrap_or_else(|| panic!("no -START in {symbols}"));
    assert_eq!(start["kind"], 21, "a constant: {start}");
    assert!(
        start["detail"].as_str().unwrap().contains("I 0.0"),
        "{start}"
    );
    let operations = complete(&mut client, &path, 16, 7);
    let set = operations
        .as_array()
        .unwrap()
        .iter()
        .find(|item| item["label"] == "S")
        .unwrap_or_else(|| panic!("no S in {operations}"));
    assert_eq!(set["kind"], 14, "a keyword: {set}");
    assert!(!set["detail"].as_str().unwrap().is_empty());
    client.finish();
}

#[test]
fn a_quick_fix_puts_the_blank_between_operation_and_operand() {
    let folder = plant_folder("fix");
    let path = folder.join("alone.awl");
    let text = "PB 1\n      L KF +5\n      T1\n      BE\n";
    let mut client = Client::start(&folder, Value::Null);
    client.open(&path, text);
    let params = json!({
        "textDocument": {"uri": uri(&path)},
        "range": {"start": {"line": 2, "character": 6}, "end": {"line": 2, "character": 6}},
        "context": {"diagnostics": []}
    });
    let actions = client
        .request("textDocument/codeAction", params)
        .result
        .unwrap();
    let action = &actions[0];
    assert_eq!(action["kind"], "quickfix", "{actions}");
    let fixed = edited(text, &action["edit"]["changes"][uri(&path)]);
    assert_eq!(fixed, "PB 1\n      L KF +5\n      T 1\n      BE\n");
    let elsewhere = json!({
        "textDocument": {"uri": uri(&path)},
        "range": {"start": {"line": 1, "character": 0}, "end": {"line": 1, "character": 0}},
        "context": {"diagnostics": []}
    });
    let none = client
        .request("textDocument/codeAction", elsewhere)
        .result
        .unwrap();
    assert_eq!(none, json!([]));
    client.finish();
}

#[test]
fn semantic_tokens_follow_the_legend_and_formatting_aligns_the_columns() {
    let folder = plant_folder("tokens");
    let path = folder.join("alone.awl");
    let text = "PB 1\nA I 0.0 ; start\n= Q 4.0\nBE\n";
    let (client_end, server_end) = Connection::memory();
    let server = std::thread::spawn(move || super::serve(&server_end));
    let mut client = Client {
        connection: client_end,
        server: Some(server),
        next: 0,
    };
    let params = json!({"capabilities": {}, "rootUri": uri(&folder)});
    let capabilities = client.request("initialize", params).result.unwrap()["capabilities"].clone();
    let legend = &capabilities["semanticTokensProvider"]["legend"]["tokenTypes"];
    assert_eq!(legend, &json!(super::tokens::LEGEND), "{capabilities}");
    assert_eq!(capabilities["documentFormattingProvider"], true);
    client.notify("initialized", json!({}));
    client.open(&path, text);
    let document = json!({"textDocument": {"uri": uri(&path)}});
    let tokens = client
        .request("textDocument/semanticTokens/full", document.clone())
        .result
        .unwrap();
    let data = tokens["data"].as_array().unwrap();
    let language = super::text::FileLanguage::of_text(text);
    let expected = super::tokens::semantic_tokens(text, language);
    assert_eq!(data.len(), expected.len() * 5);
    let comment = super::tokens::LEGEND
        .iter()
        .position(|name| *name == "comment");
    assert!(
        data.chunks(5)
            .any(|token| token[3] == json!(comment.unwrap())),
        "{tokens}"
    );
    let params = json!({
        "textDocument": {"uri": uri(&path)},
        "options": {"tabSize": 4, "insertSpaces": true}
    });
    let edits = client
        .request("textDocument/formatting", params)
        .result
        .unwrap();
    let formatted = edited(text, &edits);
    assert_ne!(formatted, text);
    assert_eq!(formatted, super::format::formatted(text, language));
    client.finish();
}

#[test]
fn a_waiting_request_is_cancelled_and_a_burst_of_edits_is_checked_once() {
    let folder = plant_folder("cancel");
    let path = folder.join("plant.awl");
    let (client, server) = Connection::memory();
    let send = |message: Message| client.sender.send(message).unwrap();
    let hover = |id: i32| {
        let params =
            json!({"textDocument": {"uri": uri(&path)}, "position": {"line": 1, "character": 6}});
        Request::new(
            RequestId::from(id),
            "textDocument/hover".to_string(),
            params,
        )
        .into()
    };
    let notification =
        |method: &str, params: Value| Notification::new(method.to_string(), params).into();
    // Everything is waiting before the server reads its first message.
    send(
        Request::new(
            RequestId::from(1),
            "initialize".to_string(),
            json!({"capabilities": {}, "rootUri": uri(&folder)}),
        )
        .into(),
    );
    send(notification("initialized", json!({})));
    send(notification(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": uri(&path), "languageId": "awl", "version": 1, "text": PLANT}}),
    ));
    send(hover(2));
    send(notification("$/cancelRequest", json!({"id": 2})));
    send(hover(3));
    for (version, text) in [
        (2, "      A I 0.0\n"),
        (3, "      A I 0.\n"),
        (4, "      A I 0.1\n      BE\n"),
    ] {
        send(notification(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri(&path), "version": version}, "contentChanges": [{"text": text}]}),
        ));
    }
    let thread = std::thread::spawn(move || super::serve(&server));
    let mut answers = Vec::new();
    let mut published = Vec::new();
    let mut shut_down = false;
    while answers.len() < 4 {
        if answers.len() == 3 && published.len() == 1 && !shut_down {
            shut_down = true;
            send(Request::new(RequestId::from(4), "shutdown".to_string(), Value::Null).into());
        }
        match client
            .receiver
            .recv_timeout(std::time::Duration::from_secs(30))
            .unwrap()
        {
            Message::Response(response) => answers.push(response),
            Message::Notification(notification) if notification.params["uri"] == uri(&path) => {
                published.push(notification.params)
            }
            Message::Notification(_) => {}
            Message::Request(_) => {}
        }
    }
    let ids: Vec<RequestId> = answers.iter().map(|answer| answer.id.clone()).collect();
    assert_eq!(ids, [1, 2, 3, 4].map(RequestId::from));
    assert_eq!(
        answers[1].error.as_ref().unwrap().code,
        lsp_server::ErrorCode::RequestCanceled as i32
    );
    assert!(
        answers[2].result.as_ref().unwrap()["contents"]["value"]
            .as_str()
            .unwrap()
            .contains("AND")
    );
    assert_eq!(published.len(), 1, "{published:?}");
    let errors = published[0]["diagnostics"].as_array().unwrap().iter();
    assert_eq!(
        errors.filter(|found| found["severity"] == 1).count(),
        0,
        "the last text, without the error of the one before, is the one checked"
    );
    client
        .sender
        .send(notification("exit", Value::Null))
        .unwrap();
    assert_eq!(thread.join().unwrap(), Ok(()));
}

const INSTANCES: &str = "FUNCTION_BLOCK FB 1
VAR_INPUT
  start : BOOL;
END_VAR
BEGIN
NETWORK
      A     #start;
      =     Q 4.0;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB 2
VAR
  pump : FB 1;
END_VAR
BEGIN
NETWORK
      CALL  #pump (start := I 0.1);
END_FUNCTION_BLOCK

DATA_BLOCK DB 10
FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 20
FB 2
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
NETWORK
      CALL  FB 1, DB 10 (start := I 0.0);
      CALL  FB 2, DB 20;
END_ORGANIZATION_BLOCK
";

#[test]
fn fb_instances_lead_to_their_data_block_their_declaration_and_their_fb() {
    let folder = scratch_folder("instances");
    let path = folder.join("instances.awl");
    let mut client = Client::start(&folder, json!({"cpu": "speed7"}));
    assert_eq!(client.open(&path, INSTANCES)["diagnostics"], json!([]));
    let line_of = |client: &mut Client, line: u32, character: u32| {
        let found = client.at("textDocument/definition", &path, line, character);
        found["range"]["start"]["line"].clone()
    };
    // `CALL FB 1, DB 10`: the FB, and the instance data block.
    assert_eq!(line_of(&mut client, 32, 13), 0);
    assert_eq!(line_of(&mut client, 32, 19), 19);
    // A parameter of the call: its declaration in the FB.
    assert_eq!(line_of(&mut client, 32, 25), 2);
    assert_eq!(line_of(&mut client, 16, 20), 2);
    client.assert_hover(&path, 32, 25, &["start : BOOL"]);
    // A multi-instance: `CALL #pump` leads to its declaration, `pump : FB 1` to the FB.
    assert_eq!(line_of(&mut client, 16, 15), 12);
    assert_eq!(line_of(&mut client, 12, 10), 0);
    // The instance data block's own `FB 2` line leads to the FB.
    assert_eq!(line_of(&mut client, 25, 1), 10);
    client.finish();
}
