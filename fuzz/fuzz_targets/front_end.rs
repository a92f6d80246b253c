//! Any bytes as a program file, on a CPU the first byte picks: the front end never panics,
//! and every diagnostic points into the file and renders. Seeds: `programs/`.
#![no_main]

use awl::frontend;
use awl::source::{SourceFile, SourceSet};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let profile = awl_fuzz::cpu(bytes.first().copied().unwrap_or(0));
    let mut sources = SourceSet::default();
    sources.add(SourceFile::from_bytes("fuzz.awl", bytes.to_vec()));
    let built = frontend::build(sources, None, profile);
    awl_fuzz::check_diagnostics(&built);
});
