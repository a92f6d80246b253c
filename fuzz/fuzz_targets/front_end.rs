//! Any bytes as a program file, on a CPU the first byte picks: the front end never panics,
//! and every diagnostic has a message and a code and points into the file; one input in 16
//! has its diagnostics rendered in full. Seeds: `programs/`, `tests/inputs/`.
#![no_main]

use awl::frontend;
use awl::source::{SourceFile, SourceSet};
use libfuzzer_sys::fuzz_target;

fuzz_target!(
    init: awl_fuzz::quiet_reports(),
    |bytes: &[u8]| {
        let bytes = awl_fuzz::bounded(bytes);
        let profile = awl_fuzz::cpu(bytes.first().copied().unwrap_or(0));
        let mut sources = SourceSet::default();
        sources.add(SourceFile::from_bytes("fuzz.awl", bytes.to_vec()));
        let built = frontend::build(sources, frontend::Language::default(), profile);
        awl_fuzz::check_diagnostics(&built, awl_fuzz::renders_in_full(bytes));
    }
);
