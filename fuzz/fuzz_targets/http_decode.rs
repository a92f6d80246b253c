//! Any bytes as what the online page's server is sent: a method, a path with its query, a
//! body, the `Host` and `Origin` headers, a live connection's message. The decoders never
//! panic; every refusal is a diagnostic with an `awl::online::` code and a 4xx or 503 status
//! that serializes as the API's error; what decodes is a request the API has.
#![no_main]

use awl::serve::http::api::{self, Call};
use awl::serve::http::guard;
use libfuzzer_sys::fuzz_target;

const METHODS: [&str; 5] = ["GET", "POST", "DELETE", "PUT", "HEAD"];

fuzz_target!(|bytes: &[u8]| {
    let bytes = awl_fuzz::bounded(bytes);
    let Some((&first, rest)) = bytes.split_first() else {
        return;
    };
    let method = METHODS[usize::from(first) % METHODS.len()];
    let (target, body) = match rest.iter().position(|&byte| byte == 0) {
        Some(nul) => (&rest[..nul], &rest[nul + 1..]),
        None => (rest, &[][..]),
    };
    let target = String::from_utf8_lossy(target);
    let (path, query) = match target.split_once('?') {
        Some((path, query)) => (path, Some(query)),
        None => (target.as_ref(), None),
    };
    match api::decode(method, path, query, body) {
        Ok(call) => check_call(&call),
        Err(error) => check_refusal(error.refusal()),
    }
    let text = String::from_utf8_lossy(body);
    if let Err(error) = api::subscription(&text) {
        check_refusal(error.refusal());
    }
    let listening = "127.0.0.1:8102".parse().expect("an address");
    if let Err(error) = guard::check_host(Some(&target), listening) {
        check_refusal(error.refusal());
    }
    if let Err(error) = guard::check_origin(Some(&text), &target) {
        check_refusal(error.refusal());
    }
});

/// A decoded request names what the API serves: operands are never empty, the timeline's
/// seconds lie in its range.
fn check_call(call: &Call) {
    match call {
        Call::Values(rows) => assert!(rows.iter().all(|(operand, _)| !operand.trim().is_empty())),
        Call::Unforce(Some(operand)) => assert!(!operand.trim().is_empty()),
        Call::Status { block, level } => {
            assert!(!block.trim().is_empty());
            assert!(level.as_ref().is_none_or(|level| !level.trim().is_empty()));
        }
        Call::Timeline(seconds) => assert!(*seconds > 0.0 && *seconds <= 60.0),
        _ => {}
    }
}

/// A refusal is answered as the API's error, with a code and a 4xx (or 503) status.
fn check_refusal(refusal: awl::serve::request::Refusal) {
    let status = refusal.kind.status();
    assert!((400..500).contains(&status) || status == 503, "{status}");
    assert!(refusal.code.as_deref().is_some_and(|code| code.starts_with("awl::")));
    assert!(!refusal.error.is_empty());
    let json = serde_json::to_value(&refusal).expect("a refusal serializes");
    assert!(json["error"].is_string() && json["code"].is_string());
}
