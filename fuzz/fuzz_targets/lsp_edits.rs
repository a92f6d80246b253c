//! An editor session against `awl lsp`: the bytes before the first NUL are the document, the
//! bytes after it a script of edits, requests, cancellations and setting changes (see
//! `src/editor.rs`). Without a NUL the document gets a fixed script that asks everything once
//! and types into it, so the sample programs seed it as they are.
#![no_main]

use libfuzzer_sys::fuzz_target;

/// Hover, definition, references and completion at four places, a quick fix, the four
/// document requests, an insertion, a deletion and a cancelled hover.
const DEFAULT_SCRIPT: &[u8] = &[
    0, 1, 7, 0, 1, 2, 9, 0, 2, 3, 2, 0, 3, 4, 12, 0, 4, 1, 0, 0, 5, 0, 0, 0, 5, 0, 0, 1, 5, 0,
    0, 2, 5, 1, 0, 3, 6, 2, 0, 0, 8, 3, 2, 5, 9, 1, 6, 0,
];

fuzz_target!(
    init: awl_fuzz::quiet_reports(),
    |bytes: &[u8]| {
        let bytes = awl_fuzz::bounded(bytes);
        let (text, script) = match bytes.iter().position(|&byte| byte == 0) {
            Some(nul) => (&bytes[..nul], &bytes[nul + 1..]),
            None => (bytes, DEFAULT_SCRIPT),
        };
        awl_fuzz::edit_session(&String::from_utf8_lossy(text), script);
    }
);
