//! Attaching to `awl serve --http`: not yet supported, so the request is refused with the reason.

use serde_json::Value;

use super::Adapter;

pub fn attach(adapter: &mut Adapter, seq: i64, _arguments: &Value) {
    adapter.out.refuse(
        seq,
        "attach",
        "awl dap cannot attach to a running `awl serve` yet: launch the program instead",
    );
}
