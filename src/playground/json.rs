//! The playground's functions with JSON in and out, as the page's WebAssembly module hands
//! them on: a request the page could not have meant (malformed JSON, an unknown field) is
//! answered with an outcome that says so, like any other refused run.

use serde::Serialize;
use serde_json::json;

use super::{Live, Outcome, Pulse, Request};

/// The example files (name, text), the CPU profiles and the words the editor colours.
pub fn catalogue(files: &[(&str, &str)]) -> String {
    let files: serde_json::Map<String, serde_json::Value> = files
        .iter()
        .map(|(name, text)| ((*name).to_string(), json!(text)))
        .collect();
    let cpus: Vec<_> = super::cpus()
        .into_iter()
        .map(|(name, title)| json!({ "name": name, "title": title }))
        .collect();
    json!({ "files": files, "cpus": cpus, "words": super::words() }).to_string()
}

/// The request in `json`, or the outcome (as JSON) that says it is malformed.
fn request(json: &str) -> Result<Request, String> {
    serde_json::from_str(json).map_err(|error| {
        to_json(&Outcome {
            summary: format!("not run: the page sent a malformed request ({error})\n"),
            ..Outcome::default()
        })
    })
}

pub fn to_json(value: &impl Serialize) -> String {
    serde_json::to_string(value).expect("plain data")
}

/// [`super::run_reporting`]: the outcome as JSON.
pub fn run(json: &str, pulse: Pulse) -> String {
    request(json).map_or_else(
        |refused| refused,
        |request| to_json(&super::run_reporting(&request, pulse)),
    )
}

/// [`super::debug_reporting`] with these commands, one per line: the outcome as JSON.
pub fn debug(json: &str, commands: &str, pulse: Pulse) -> String {
    request(json).map_or_else(
        |refused| refused,
        |request| to_json(&super::debug_reporting(&request, commands, pulse)),
    )
}

/// [`Live::start`], or the outcome (as JSON) that says why it cannot start.
pub fn start_live(json: &str) -> Result<Live, String> {
    let request = request(json)?;
    Live::start(&request).map_err(|outcome| to_json(&*outcome))
}
