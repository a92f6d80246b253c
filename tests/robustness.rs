//! No input makes the front end panic or hang: random bytes, STL-like noise and mutated sample
//! programs all go through lexing, parsing, compiling and rendering of every diagnostic.

use awl::diagnostics::{render_plain, report};
use awl::frontend;
use awl::profile;
use awl::source::{SourceFile, SourceSet};
use proptest::prelude::*;

fn run_front_end(bytes: Vec<u8>) {
    for cpu in profile::PROFILES {
        let mut sources = SourceSet::default();
        sources.add(SourceFile::from_bytes("fuzz.awl", bytes.clone()));
        let built = frontend::build(sources, None, cpu);
        for diagnostic in &built.diagnostics {
            let span = diagnostic.span();
            assert!(span.end as usize <= built.sources.get(span.file).text.len());
            let _ = render_plain(&report(&built.sources, diagnostic));
        }
    }
}

fn samples() -> Vec<Vec<u8>> {
    let mut files: Vec<_> = std::fs::read_dir("programs")
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "awl"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|path| std::fs::read(path).unwrap())
        .collect()
}

/// Characters STL is made of, so that noise often gets past the lexer.
const ALPHABET: &[u8] = b"ABCDEFGIJKLMNOPQRSTUWXYZabcdf0123456789 .:;=+-()!<>,'\n\r\t/FBDH";

#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize, usize),
    Insert(usize, Vec<u8>),
    Replace(usize, u8),
    DuplicateLine(usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1usize..8).prop_map(|(at, len)| Mutation::Delete(at, len)),
        (
            any::<usize>(),
            prop::collection::vec(prop::sample::select(ALPHABET), 1..8)
        )
            .prop_map(|(at, bytes)| Mutation::Insert(at, bytes)),
        (any::<usize>(), any::<u8>()).prop_map(|(at, byte)| Mutation::Replace(at, byte)),
        any::<usize>().prop_map(Mutation::DuplicateLine),
    ]
}

fn apply(mut text: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for mutation in mutations {
        let len = text.len().max(1);
        match mutation {
            Mutation::Delete(at, n) => {
                let start = at % len;
                let end = (start + n).min(text.len());
                if start < end {
                    text.drain(start..end);
                }
            }
            Mutation::Insert(at, bytes) => {
                let at = at % (text.len() + 1);
                text.splice(at..at, bytes.iter().copied());
            }
            Mutation::Replace(at, byte) => {
                if !text.is_empty() {
                    let at = at % text.len();
                    text[at] = *byte;
                }
            }
            Mutation::DuplicateLine(at) => {
                let lines: Vec<&[u8]> = text.split(|b| *b == b'\n').collect();
                let line = lines[at % lines.len()].to_vec();
                text.extend_from_slice(b"\n");
                text.extend_from_slice(&line);
            }
        }
    }
    text
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        run_front_end(bytes);
    }

    #[test]
    fn stl_like_noise(bytes in prop::collection::vec(prop::sample::select(ALPHABET), 0..600)) {
        run_front_end(bytes);
    }

    #[test]
    fn mutated_samples(index in any::<usize>(), mutations in prop::collection::vec(mutation(), 1..12)) {
        let samples = samples();
        let sample = samples[index % samples.len()].clone();
        run_front_end(apply(sample, &mutations));
    }
}

#[test]
fn crlf_and_latin1_files_parse() {
    let text = "PB 1\r\n      A  I 0.0 ; Z\u{e4}hler\r\n      =  Q 4.0\r\n      BE\r\n";
    let latin1: Vec<u8> = text.chars().map(|c| c as u32 as u8).collect();
    let mut sources = SourceSet::default();
    sources.add(SourceFile::from_bytes("crlf.awl", latin1));
    let built = frontend::build(sources, None, profile::find("sinumerik-840c").unwrap());
    assert!(built.diagnostics.is_empty(), "{:#?}", built.diagnostics);
    assert_eq!(built.compiled.program.blocks[0].code.len(), 3);
}
