//! The online page's JSON API (`awl serve --http`) with a plain HTTP client written by others
//! (ureq), in both dialects, and its security cases, on 127.0.0.1 with a port the system picks.
//! Requests that no well-behaved client sends (a foreign `Host`, a request of a single line) go
//! over a plain TCP socket.

mod common;

use common::online::Online;

use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

const AWL: &str = env!("CARGO_BIN_EXE_awl");

#[test]
fn a_step7_program_on_speed7_is_watched_modified_stopped_and_restarted() {
    let online = Online::start(&["programs/s7/tank_hmi.awl", "--cpu", "speed7"]);
    let deadline = Instant::now() + Duration::from_secs(10);
    let cpu = loop {
        let (status, cpu) = online.get("/api/cpu");
        assert_eq!(status, 200);
        if cpu["cycle"].as_u64() > Some(2) || Instant::now() > deadline {
            break cpu;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    assert_eq!(cpu["mode"], "RUN", "{cpu}");
    assert_eq!(cpu["profile"], "speed7");
    assert_eq!(cpu["dialect"], "s7");
    assert_eq!(cpu["mnemonics"], "en");
    assert_eq!(cpu["read_only"], false);
    assert_eq!(cpu["stop"], Value::Null);
    assert!(
        cpu["cycle_time_ms"]["mean"].as_f64().unwrap() > 0.0,
        "{cpu}"
    );

    let rows = online.values("DB1.DBW 0,Q 0.0,MW 20,DB1.DBW 0", "HEX,,,BIN");
    assert_eq!(
        rows[0],
        json!({"operand": "DB1.DBW 0", "format": "HEX", "value": "W#16#01F4", "raw": 500})
    );
    assert_eq!(
        rows[1],
        json!({"operand": "Q 0.0", "format": "BOOL", "value": "0", "raw": false})
    );
    assert_eq!(rows[2]["format"], "DEC");
    assert_eq!(rows[3]["value"], "2#0000_0001_1111_0100");
    // Every name `--state` prints: a data block's declared members, in their types.
    let declared = online.values("DB1.setpoint,DB1.run", "");
    assert_eq!(declared[0]["value"], "500");
    assert_eq!(
        (&declared[1]["value"], &declared[1]["raw"]),
        (&json!("FALSE"), &json!(false))
    );

    let (status, modified) = online.post(
        "/api/modify",
        &json!({"operand": "DB1.DBW 0", "value": "600"}),
    );
    assert_eq!(status, 200, "{modified}");
    assert_eq!(
        modified,
        json!({"operand": "DB1.DBW 0", "value": "600", "raw": 600})
    );
    online.wait_for("DB1.DBW 0", "600");

    let (status, mode) = online.post("/api/mode", &json!({"mode": "stop"}));
    assert_eq!((status, mode), (200, json!({"mode": "STOP"})));
    assert_eq!(online.get("/api/cpu").1["mode"], "STOP");
    let (status, mode) = online.post("/api/mode", &json!({"mode": "warm"}));
    assert_eq!((status, mode), (200, json!({"mode": "RUN"})));
    let (status, refused) = online.post("/api/mode", &json!({"mode": "cold"}));
    assert_eq!(status, 409, "{refused}");
    assert_eq!(refused["code"], "awl::online::running");
    // A warm restart keeps the data block; OB 100 counts the restart in MW 20.
    online.wait_for("DB1.DBW 0", "600");
    online.wait_for("MW 20", "2");

    let (status, buffer) = online.get("/api/diagnostics");
    assert_eq!(status, 200);
    let kinds: Vec<&str> = buffer["entries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|entry| entry["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["mode", "mode", "modify"], "{buffer}");
    let texts = &buffer["entries"];
    assert_eq!(texts[0]["text"], "STARTUP: warm restart");
    assert!(
        texts[1]["text"]
            .as_str()
            .unwrap()
            .starts_with("STOP, asked for by http #")
    );
    assert!(
        texts[2]["text"]
            .as_str()
            .unwrap()
            .starts_with("DB1.DBW 0 := 600 (http #")
    );
}

#[test]
fn a_step5_program_on_an_s5_115u_is_watched_and_modified_in_its_own_notation() {
    let online = Online::start(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    let (_, cpu) = online.get("/api/cpu");
    assert_eq!(cpu["dialect"], "s5", "{cpu}");
    assert_eq!(cpu["profile"], "s5-115u-944");
    let rows = online.values("DB 1 DW 0,DB 1 DW 0,FW 20,Q 0.0", ",HEX,,");
    assert_eq!(rows[0]["value"], "KF +500");
    assert_eq!(rows[0]["format"], "DEC");
    assert_eq!(rows[1]["value"], "KH 01F4");
    assert_eq!(rows[2]["raw"], 1, "one restart: {rows:?}");
    assert_eq!(rows[3]["raw"], false);

    let (status, modified) = online.post(
        "/api/modify",
        &json!({"operand": "DB 1 DW 0", "value": 700}),
    );
    assert_eq!(status, 200, "{modified}");
    assert_eq!(modified["value"], "KF +700");
    // The level sensor, written as a scenario's `set` writes an input: the program copies it.
    let (status, _) = online.post("/api/modify", &json!({"operand": "IW 0", "value": 321}));
    assert_eq!(status, 200);
    online.wait_for("FW 10", "KF +321");
}

#[test]
fn a_bad_operand_value_or_format_gets_the_words_the_command_line_uses() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let (status, refused) = online.get("/api/values?operands=XYZ%2099");
    assert_eq!(status, 400);
    assert!(
        refused["error"]
            .as_str()
            .unwrap()
            .starts_with("cannot watch `XYZ 99`: not a STEP 7 operand"),
        "{refused}"
    );
    assert_eq!(refused["code"], "awl::cli::watch_operand");
    assert!(refused["help"].as_str().unwrap().contains("`MW 10`"));

    let (status, refused) = online.post("/api/modify", &json!({"operand": "MB 10", "value": 1000}));
    assert_eq!(status, 400);
    assert_eq!(refused["error"], "`1000` does not fit `MB 10`");
    assert_eq!(refused["code"], "awl::scenario::bad_value");
    assert_eq!(refused["help"], "allowed: -128…255");

    let (status, refused) = online.get("/api/values?operands=MW%2010&formats=REAL");
    assert_eq!(status, 400);
    assert_eq!(refused["error"], "`MW 10` cannot be shown as REAL");
    assert_eq!(refused["code"], "awl::cli::watch_format");
    let (status, refused) = online.get("/api/values?operands=MW%2010&formats=OCT");
    assert_eq!(
        (status, &refused["code"]),
        (400, &json!("awl::online::format"))
    );
    let (status, refused) = online.get("/api/values");
    assert_eq!(
        (status, &refused["code"]),
        (400, &json!("awl::online::missing"))
    );
}

#[test]
fn the_page_is_served_from_the_binary() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let mut response = online.agent.get(&online.url("/")).call().unwrap();
    assert_eq!(response.status().as_u16(), 200);
    let kind = response.headers()["content-type"]
        .to_str()
        .unwrap()
        .to_string();
    assert!(kind.starts_with("text/html"), "{kind}");
    let page = response.body_mut().read_to_string().unwrap();
    assert!(page.contains("id=\"mode\""), "{page}");
    assert!(
        !page.contains("https://"),
        "the page fetches nothing from the network"
    );
}

#[test]
fn foreign_hosts_and_origins_are_refused() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let port = online.port;
    let get = |host: &str| {
        online.raw(&format!(
            "GET /api/cpu HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n"
        ))
    };
    for host in [
        format!("localhost:{port}"),
        format!("127.0.0.1:{port}"),
        format!("[::1]:{port}"),
    ] {
        assert_eq!(get(&host).0, 200, "{host}");
    }
    let (status, body) = get(&format!("attacker.example:{port}"));
    assert_eq!(status, 403);
    assert!(body.contains("awl::online::host"), "{body}");
    assert_eq!(get(&format!("localhost:{}", port.wrapping_add(1))).0, 403);
    let (status, _) = online.raw("GET /api/cpu HTTP/1.0\r\n\r\n");
    assert_eq!(status, 403, "a request without a Host");

    let post = |origin: &str| {
        let body = r#"{"operand": "MW 10", "value": 1}"#;
        online.raw(&format!(
            "POST /api/modify HTTP/1.1\r\nHost: localhost:{port}\r\nOrigin: {origin}\r\n\
             Content-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        ))
    };
    assert_eq!(post(&format!("http://localhost:{port}")).0, 200);
    let (status, body) = post("http://attacker.example");
    assert_eq!(status, 403);
    assert!(body.contains("awl::online::origin"), "{body}");
    assert_eq!(post("null").0, 403);
    // A read needs no origin check: the browser keeps the answer from a foreign page.
    let (status, _) = online.raw(&format!(
        "GET /api/cpu HTTP/1.1\r\nHost: localhost:{port}\r\nOrigin: http://attacker.example\r\n\
         Connection: close\r\n\r\n"
    ));
    assert_eq!(status, 200);
}

#[test]
fn read_only_refuses_changes_and_serves_reads() {
    let online = Online::start(&["programs/s7/tank_hmi.awl", "--read-only"]);
    assert_eq!(online.get("/api/cpu").1["read_only"], true);
    for (path, body) in [
        ("/api/modify", json!({"operand": "MW 10", "value": 1})),
        ("/api/mode", json!({"mode": "stop"})),
    ] {
        let (status, refused) = online.post(path, &body);
        assert_eq!(status, 403, "{path}");
        assert_eq!(refused["code"], "awl::online::read_only");
    }
    assert_eq!(online.get("/api/cpu").1["mode"], "RUN");
    assert_eq!(online.values("MW 10", "")[0]["raw"], 0);
}

#[test]
fn malformed_and_oversized_requests_get_a_4xx() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let (status, refused) = online.post("/api/mode", &Value::String("{mode".into()));
    assert_eq!(status, 400);
    assert_eq!(refused["code"], "awl::online::bad_json");
    let bad_json = online
        .agent
        .post(&online.url("/api/modify"))
        .send("{\"operand\": \"MW 10\", \"value\": ");
    assert_eq!(Online::answer(bad_json).0, 400);
    let port = online.port;
    let (status, refused) = online.raw(&format!(
        "POST /api/modify HTTP/1.1\r\nHost: localhost:{port}\r\nContent-Length: {}\r\n\
         Connection: close\r\n\r\n",
        70 * 1024
    ));
    assert_eq!(status, 413);
    assert!(refused.contains("awl::online::too_large"), "{refused}");
    // Without a length, the body is read up to the limit.
    let chunk = "x".repeat(70 * 1024);
    let (status, _) = online.raw(&format!(
        "POST /api/modify HTTP/1.1\r\nHost: localhost:{port}\r\nTransfer-Encoding: chunked\r\n\
         Connection: close\r\n\r\n{:x}\r\n{chunk}\r\n0\r\n\r\n",
        chunk.len()
    ));
    assert_eq!(status, 413);
    let (status, refused) = online.get("/api/nothing");
    assert_eq!(
        (status, &refused["code"]),
        (404, &json!("awl::online::not_found"))
    );
    let (status, refused) = online.post("/api/cpu", &json!({}));
    assert_eq!(
        (status, &refused["code"]),
        (405, &json!("awl::online::method"))
    );
    let (status, _) = online.raw("GARBAGE\r\n\r\n");
    assert_eq!(status, 400, "hyper refuses a request line it cannot read");
    assert_eq!(online.get("/api/cpu").0, 200, "and the server goes on");
}

#[test]
fn connections_past_the_limit_are_closed_at_once() {
    let online = Online::start(&["programs/s7/tank_hmi.awl", "--max-connections", "2"]);
    let held: Vec<TcpStream> = (0..2)
        .map(|_| TcpStream::connect(("127.0.0.1", online.port)).unwrap())
        .collect();
    std::thread::sleep(Duration::from_millis(300));
    let mut third = TcpStream::connect(("127.0.0.1", online.port)).unwrap();
    third
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    let _ = third.write_all(b"GET /api/cpu HTTP/1.1\r\nHost: localhost\r\n\r\n");
    let mut answer = Vec::new();
    let read = third.read_to_end(&mut answer);
    assert!(
        read.is_err() || answer.is_empty(),
        "the third connection was served: {}",
        String::from_utf8_lossy(&answer)
    );
    drop(held);
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(
        online.get("/api/cpu").0,
        200,
        "served again once they closed"
    );
}

#[test]
fn only_the_named_servers_start() {
    let output = Command::new(AWL)
        .args([
            "serve",
            "programs/s7/tank_hmi.awl",
            "--http",
            "127.0.0.1:0",
            "--cycles",
            "3",
        ])
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("Online page at http://127.0.0.1:"),
        "{stdout}"
    );
    assert!(!stdout.contains("S7 server"), "{stdout}");
    assert!(!stdout.contains("Modbus"), "{stdout}");
}

#[test]
fn a_forced_input_holds_against_writes_until_it_is_unforced() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let (status, forced) = online.post("/api/force", &json!({"operand": "IW 0", "value": 100}));
    assert_eq!(status, 200, "{forced}");
    assert_eq!(
        forced,
        json!({"operand": "IW 0", "value": "100", "raw": 100})
    );
    // A modify writes the modules and the PII once; the force puts the PII back at once, and
    // the program copies the level sensor IW 0 into DB1.DBW 2.
    let (status, _) = online.post("/api/modify", &json!({"operand": "IW 0", "value": 700}));
    assert_eq!(status, 200);
    online.wait_for("DB1.DBW 2", "100");
    std::thread::sleep(Duration::from_millis(100));
    online.wait_for("DB1.DBW 2", "100");
    assert_eq!(online.get("/api/cpu").1["forces"], 1);
    assert_eq!(
        online.get("/api/forces").1,
        json!({"forces": [{"operand": "IW 0", "value": "100", "raw": 100}]})
    );

    let (status, refused) = online.delete("/api/force?operand=Q%200.0");
    assert_eq!(status, 404);
    assert_eq!(refused["code"], "awl::online::not_forced");
    assert_eq!(refused["help"], "forced are: IW 0");
    let (status, unforced) = online.delete("/api/force?operand=IW%200");
    assert_eq!((status, unforced), (200, json!({"operand": "IW 0"})));
    online.wait_for("DB1.DBW 2", "700");

    online.post("/api/force", &json!({"operand": "Q 0.0", "value": true}));
    // The program writes the pump Q 0.0 = 0 in every cycle (no run): the force holds it at 1
    // in the PIQ and at the output module.
    std::thread::sleep(Duration::from_millis(100));
    assert_eq!(online.values("Q 0.0,PQB 0", "")[0]["raw"], true);
    assert_eq!(online.values("PQB 0", "BIN")[0]["value"], "2#0000_0001");
    let (status, all) = online.delete("/api/force");
    assert_eq!((status, all), (200, json!({"operands": ["Q 0.0"]})));
    online.wait_for("Q 0.0", "0");

    let kinds: Vec<Value> = online.get("/api/diagnostics").1["entries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|entry| entry["kind"].clone())
        .collect();
    assert_eq!(
        kinds,
        [
            "force_cleared",
            "force_set",
            "force_cleared",
            "modify",
            "force_set"
        ],
    );
}

#[test]
fn only_inputs_and_outputs_are_forced_and_read_only_forces_nothing() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    for operand in ["MW 10", "ID 0", "PIW 0", "T 1", "DB1.DBW 0"] {
        let (status, refused) = online.post("/api/force", &json!({"operand": operand, "value": 1}));
        assert_eq!(status, 400, "{operand}");
        assert_eq!(refused["code"], "awl::online::not_forceable", "{operand}");
    }
    let (status, refused) = online.post("/api/force", &json!({"operand": "QB 0", "value": 256}));
    assert_eq!(
        (status, &refused["help"]),
        (400, &json!("allowed: -128…255"))
    );
    drop(online);

    let online = Online::start(&["programs/s7/tank_hmi.awl", "--read-only"]);
    let (status, refused) = online.post("/api/force", &json!({"operand": "I 0.0", "value": 1}));
    assert_eq!(
        (status, &refused["code"]),
        (403, &json!("awl::online::read_only"))
    );
    assert_eq!(online.delete("/api/force").0, 403);
}

#[test]
fn a_trace_records_the_page_s_modifies_forces_and_mode_changes() {
    let trace = std::env::temp_dir().join(format!("awl-online-{}.jsonl", std::process::id()));
    let trace_arg = trace.display().to_string();
    let online = Online::start(&["programs/s7/tank_hmi.awl", "--trace", &trace_arg]);
    online.post("/api/modify", &json!({"operand": "MW 10", "value": 5}));
    online.post("/api/force", &json!({"operand": "I 0.1", "value": 1}));
    online.delete("/api/force?operand=I%200.1");
    online.post("/api/mode", &json!({"mode": "stop"}));
    let stderr = online.terminate();
    let text = std::fs::read_to_string(&trace).unwrap_or_else(|_| panic!("a trace: {stderr}"));
    let _ = std::fs::remove_file(&trace);
    let events: Vec<Value> = text
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .filter(|event: &Value| {
            ["modify", "force", "unforce", "mode"].contains(&event["ev"].as_str().unwrap())
        })
        .collect();
    let modify = events.iter().find(|event| event["ev"] == "modify").unwrap();
    let client = modify["client"].as_str().unwrap().to_string();
    assert!(client.starts_with("http #"), "{events:?}");
    let kinds: Vec<(&str, &str)> = events
        .iter()
        .map(|event| {
            let what = event["operand"]
                .as_str()
                .or(event["cause"].as_str())
                .unwrap_or("");
            (event["ev"].as_str().unwrap(), what)
        })
        .collect();
    assert_eq!(
        kinds[kinds.len() - 4..],
        [
            ("modify", "MW 10"),
            ("force", "I 0.1"),
            ("unforce", "I 0.1"),
            ("mode", "online")
        ],
        "{events:?}"
    );
    assert_eq!(events[events.len() - 4]["value"], "5");
}

#[test]
fn program_status_shows_the_latest_invocation_in_each_dialect() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let (status, view) = online.get("/api/status?block=OB%201&level=OB%201");
    assert_eq!(status, 200, "{view}");
    assert_eq!(
        (&view["block"], &view["level"]),
        (&json!("OB 1"), &json!("OB 1"))
    );
    assert!(view["cycle"].as_u64().unwrap() >= 1);
    let rows = view["rows"].as_array().unwrap();
    let load = rows
        .iter()
        .find(|row| row["statement"] == "L     DB1.DBW 0")
        .unwrap_or_else(|| panic!("{view}"));
    assert_eq!(load["executed"], true);
    assert_eq!(load["accu1"], "W#16#01F4");
    assert_eq!(load["operand"], "500");
    assert_eq!(load["passes"], 1);
    assert!(
        rows.iter()
            .all(|row| row["rlo"] == 0 || row["rlo"] == 1 || row["rlo"].is_null())
    );
    let (status, refused) = online.get("/api/status?block=FC%2099");
    assert_eq!(
        (status, &refused["code"]),
        (404, &json!("awl::status::unknown_block"))
    );
    let (status, refused) = online.get("/api/status?block=OB%2040");
    assert_eq!(
        (status, &refused["code"]),
        (404, &json!("awl::online::did_not_run"))
    );
    drop(online);

    let online = Online::start(&["programs/tank_hmi_115u.awl", "--cpu", "s5-115u-944"]);
    let (status, view) = online.get("/api/status?block=FB%201");
    assert_eq!(status, 200, "{view}");
    let rows = view["rows"].as_array().unwrap();
    let first = &rows[0];
    assert_eq!(first["statement"], ":C    DB 1");
    assert!(
        first["accu1"].as_str().unwrap().starts_with("KH "),
        "{first}"
    );
}

/// A live connection to `online`, with `origin` sent if given.
fn live(
    online: &Online,
    origin: Option<&str>,
) -> Result<
    tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>,
    tungstenite::Error,
> {
    use tungstenite::client::IntoClientRequest;
    let mut request = format!("ws://127.0.0.1:{}/api/live", online.port)
        .into_client_request()
        .unwrap();
    if let Some(origin) = origin {
        request
            .headers_mut()
            .insert("Origin", origin.parse().unwrap());
    }
    tungstenite::connect(request).map(|(socket, _)| socket)
}

/// The next message of `socket` as JSON.
fn next(
    socket: &mut tungstenite::WebSocket<tungstenite::stream::MaybeTlsStream<TcpStream>>,
) -> Value {
    loop {
        match socket.read().expect("a message") {
            tungstenite::Message::Text(text) => return serde_json::from_str(&text).unwrap(),
            _ => continue,
        }
    }
}

#[test]
fn the_live_view_pushes_what_was_subscribed_and_refuses_a_bad_subscription() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let mut socket = live(&online, Some(&format!("http://127.0.0.1:{}", online.port))).unwrap();
    let subscribe = json!({"subscribe": {
        "cpu": true,
        "values": [{"operand": "MW 20", "format": "HEX"}, {"operand": "Q 0.0"}],
        "status": {"block": "OB 1", "level": null},
        "timeline": true,
        "diagnostics": true,
    }});
    socket.send(subscribe.to_string().into()).unwrap();
    let mut seen = std::collections::BTreeMap::new();
    let deadline = Instant::now() + Duration::from_secs(20);
    while seen.len() < 5 && Instant::now() < deadline {
        let message = next(&mut socket);
        let kind = message["type"].as_str().unwrap().to_string();
        seen.entry(kind).or_insert(message);
    }
    assert_eq!(seen["cpu"]["mode"], "RUN", "{seen:?}");
    assert_eq!(seen["values"]["values"][0]["value"], "W#16#0001");
    assert_eq!(seen["values"]["values"][1]["raw"], false);
    assert_eq!(seen["status"]["block"], "OB 1");
    assert!(seen["status"]["rows"].as_array().unwrap().len() > 5);
    let svg = seen["timeline"]["svg"].as_str().unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("OB 1"), "{svg}");
    assert!(seen["diagnostics"]["entries"].is_array());

    // A second subscription replaces the first; an operand it cannot watch is an error.
    let bad = json!({"subscribe": {"values": [{"operand": "XYZ 99"}]}});
    socket.send(bad.to_string().into()).unwrap();
    let error = loop {
        let message = next(&mut socket);
        if message["type"] == "error" {
            break message;
        }
    };
    assert_eq!(error["code"], "awl::cli::watch_operand", "{error}");
    assert!(
        error["error"]
            .as_str()
            .unwrap()
            .starts_with("cannot watch `XYZ 99`")
    );
    socket.send("{not json".into()).unwrap();
    let error = loop {
        let message = next(&mut socket);
        if message["type"] == "error" {
            break message;
        }
    };
    assert_eq!(error["code"], "awl::online::bad_json");
    socket.close(None).unwrap();
}

#[test]
fn a_live_connection_from_a_foreign_page_or_without_an_upgrade_is_refused() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    match live(&online, Some("http://attacker.example")) {
        Err(tungstenite::Error::Http(response)) => assert_eq!(response.status().as_u16(), 403),
        other => panic!("a foreign page's live connection was opened: {other:?}"),
    }
    assert!(
        live(&online, None).is_ok(),
        "a program (no Origin) may open one"
    );
    let (status, refused) = online.get("/api/live");
    assert_eq!(
        (status, &refused["code"]),
        (400, &json!("awl::online::websocket"))
    );
}

#[test]
fn the_timeline_draws_the_last_seconds_of_the_levels() {
    let online = Online::start(&["programs/s7/tank_hmi.awl"]);
    let (status, answer) = online.get("/api/timeline?seconds=1");
    assert_eq!(status, 200);
    let svg = answer["svg"].as_str().unwrap();
    assert!(svg.starts_with("<svg"), "{svg}");
    assert!(svg.contains("class=\"run\""), "OB 1's level runs: {svg}");
    assert!(svg.contains("the last 1 s"), "{svg}");
    let (status, refused) = online.get("/api/timeline?seconds=often");
    assert_eq!(
        (status, &refused["code"]),
        (400, &json!("awl::online::seconds"))
    );
    // The recording leaves the CPU with the serve: the summary names no trace written.
    let stderr = online.terminate();
    assert!(!stderr.contains("online timeline"), "{stderr}");
}

#[test]
fn live_connections_count_against_the_connection_limit() {
    let online = Online::start(&["programs/s7/tank_hmi.awl", "--max-connections", "1"]);
    let first = live(&online, None).expect("the first live connection opens");
    std::thread::sleep(Duration::from_millis(200));
    match live(&online, None) {
        Err(tungstenite::Error::Http(response)) => assert_eq!(response.status().as_u16(), 503),
        Err(tungstenite::Error::Io(_) | tungstenite::Error::Protocol(_)) => {}
        other => panic!("a second live connection was opened: {other:?}"),
    }
    drop(first);
}
