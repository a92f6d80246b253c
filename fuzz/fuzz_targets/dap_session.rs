//! A debug session against `awl dap`: the bytes before the first NUL are the program, the
//! bytes after it a script of requests and broken messages (see `awl_fuzz::debug_session`). Without a NUL
//! the program gets a fixed script that launches, sets breakpoints, steps and looks around.
#![no_main]

use libfuzzer_sys::fuzz_target;

/// initialize, launch (stop on entry), a line breakpoint with a condition, the filters,
/// configurationDone, threads, stackTrace, scopes, variables, evaluate, next, stepIn,
/// continue, disconnect.
const DEFAULT_SCRIPT: &[u8] = &[
    0, 0, 0, 1, 1, 0, 2, 8, 0, 4, 0, 0, 5, 0, 0, 6, 0, 0, 7, 1, 0, 8, 27, 7, 9, 108, 28, 10, 0, 1,
    13, 0, 0, 14, 0, 0, 12, 0, 0, 19, 0, 0,
];

fuzz_target!(
    init: awl_fuzz::quiet_reports(),
    |bytes: &[u8]| {
        let bytes = awl_fuzz::bounded(bytes);
        let (text, script) = match bytes.iter().position(|&byte| byte == 0) {
            Some(nul) => (&bytes[..nul], &bytes[nul + 1..]),
            None => (bytes, DEFAULT_SCRIPT),
        };
        awl_fuzz::debug_session(&String::from_utf8_lossy(text), script);
    }
);
