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

/// Mutated scenario files never panic the scenario loader or resolver.
fn scenario_samples() -> Vec<(std::path::PathBuf, String)> {
    let mut files: Vec<_> = std::fs::read_dir("programs")
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|ext| ext == "toml"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).unwrap();
            (path, text)
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn mutated_scenarios(index in any::<usize>(), mutations in prop::collection::vec(mutation(), 1..8)) {
        let samples = scenario_samples();
        let (path, text) = &samples[index % samples.len()];
        let mutated = String::from_utf8_lossy(&apply(text.clone().into_bytes(), &mutations)).into_owned();
        if let Ok(scenario) = awl::scenario::Scenario::parse(path, &mutated) {
            let program_text = std::fs::read_to_string("programs/fig5_2_interrupt.awl").unwrap();
            let cpu = scenario.cpu.unwrap_or(profile::find("sinumerik-840c").unwrap());
            let built = frontend::build_text("p.awl", &program_text, cpu);
            let set = awl::mnemonics::MnemonicSet::English;
            if let Err(error) = scenario.schedule(&built.compiled.program, set) {
                let _ = render_plain(&scenario.report(error));
            }
            if let Err(error) = scenario.expectations(&built.compiled.program, set) {
                let _ = render_plain(&scenario.report(error));
            }
        }
    }
}

/// Random programs from the whole operation table run on every CPU without a panic: whatever
/// they do ends in RUN or in a STOP with a cause.
fn random_fb(picks: &[(usize, bool)]) -> String {
    let mut body = String::new();
    for (index, labelled) in picks {
        let info = &awl::mnemonics::OPERATIONS[index % awl::mnemonics::OPERATIONS.len()];
        if info.op == awl::mnemonics::OpCode::BlockEnd {
            continue;
        }
        let label = if *labelled { "M001 :" } else { "      " };
        body.push_str(&format!("{label}{} {}\n", info.en, info.example_en));
    }
    format!(
        "OB 1\n      C  DB 10\n      JU FB 1\nNAME :R\nX    :I 0.0\n      BE\nFB 1\nNAME :R\nDES  :X I BI\n{body}M001 :NOP 0\n      BE\nPB 3\n      BE\nFB 5\n      BE\nDB 10\n 0: KF +1\n 1: KF +2\n 2: KF +3\n"
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_programs_run_without_panic(picks in prop::collection::vec((any::<usize>(), prop::bool::weighted(0.05)), 1..40)) {
        let source = random_fb(&picks);
        for cpu in profile::PROFILES {
            let built = frontend::build_text("random.awl", &source, cpu);
            if built.has_errors() {
                continue;
            }
            let mut machine = awl::vm::Cpu::new(
                std::sync::Arc::new(built.compiled.program.clone()),
                std::sync::Arc::new(built.sources.clone()),
            );
            let outcome = machine.run(awl::vm::cycle::RunLimit::Cycles(3));
            prop_assert!(outcome.stop.is_some() || outcome.cycles == 3);
        }
    }
}
