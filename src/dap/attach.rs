//! Attaching to `awl serve --http`.

use serde_json::Value;

use super::Adapter;

pub fn attach(adapter: &mut Adapter, seq: i64, _arguments: &Value) {
    adapter.out.refuse(seq, "attach", "attach is not there yet");
}
