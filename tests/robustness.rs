//! No input makes the front end panic or hang: random bytes, STL-like noise and mutated sample
//! programs all go through lexing, parsing, compiling and rendering of every diagnostic.

mod common;

use awl::diagnostics::{render_plain, report};
use awl::dialect::Dialect;
use awl::frontend;
use awl::profile;
use awl::source::{SourceFile, SourceSet};
use proptest::prelude::*;

fn run_front_end(bytes: Vec<u8>) {
    for cpu in profile::PROFILES {
        let mut sources = SourceSet::default();
        sources.add(SourceFile::from_bytes("fuzz.awl", bytes.clone()));
        let built = frontend::build(sources, frontend::Language::default(), cpu);
        for diagnostic in &built.diagnostics {
            let span = diagnostic.span();
            assert!(span.end as usize <= built.sources.get(span.file).text.len());
            let _ = render_plain(&report(&built.sources, diagnostic));
        }
    }
}

fn samples() -> Vec<Vec<u8>> {
    common::sample_files("awl")
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
    fn assignment_lists_never_panic(bytes in prop::collection::vec(prop::sample::select(ALPHABET), 0..400)) {
        let text = String::from_utf8_lossy(&bytes).to_string();
        let cpu = profile::find("sinumerik-840c").unwrap();
        let program = "PB 3\n      A  -START\n      SPA -B\n      BE\n";
        let mut sources = SourceSet::default();
        sources.add(SourceFile::new("p.awl", program));
        let built = frontend::build_with_symbols(sources, vec![SourceFile::new("s.seq", text)], frontend::Language::default(), cpu);
        for diagnostic in &built.diagnostics {
            let _ = awl::diagnostics::render_plain(&awl::diagnostics::report(&built.sources, diagnostic));
        }
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
    let built = frontend::build(
        sources,
        frontend::Language::default(),
        profile::find("sinumerik-840c").unwrap(),
    );
    assert!(built.diagnostics.is_empty(), "{:#?}", built.diagnostics);
    assert_eq!(built.compiled.program.blocks[0].code.len(), 3);
}

/// Mutated scenario files never panic the scenario loader or resolver.
fn scenario_samples() -> Vec<(std::path::PathBuf, String)> {
    common::sample_scenarios()
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
        // Every error is a rendered diagnostic with a scenario code.
        let is_scenario_diagnostic = |rendered: &str| rendered.contains("awl::scenario::");
        let (mut scenario, mut reports) = awl::scenario::Scenario::parse(path, &mutated);
        let profile = scenario.cpu.unwrap_or(profile::default_for(Dialect::Step5));
        reports.extend(scenario.settle_cpu(profile));
        let program_text = std::fs::read_to_string("programs/fig5_2_interrupt.awl").unwrap();
        let built = frontend::build_text("p.awl", &program_text, profile);
        let set = awl::mnemonics::MnemonicSet::English;
        reports.extend(scenario.schedule(&built.compiled.program, set).err().into_iter().flatten());
        reports.extend(scenario.expectations(&built.compiled.program, set).err().into_iter().flatten());
        for report in &reports {
            let rendered = render_plain(report);
            prop_assert!(is_scenario_diagnostic(&rendered), "{}", rendered);
        }
    }
}

/// Random programs from the whole operation table run on every CPU without a panic: whatever
/// they do ends in RUN after the cycles asked for, or in STOP with a cause at a real op.
/// Labels are numbered so none is defined twice; a `DO` is always followed by a load it can
/// modify, so every generated program compiles.
fn random_fb(picks: &[(usize, bool)], cpu: &profile::Profile) -> String {
    use awl::mnemonics::OpCode;
    let mut body = String::new();
    // Brackets are balanced in the text (the compiler rejects anything else); jumps may still
    // unbalance them at run time, which must end in a STOP, not a panic.
    let mut open = 0;
    for (line, (index, labelled)) in picks.iter().enumerate() {
        let info = &awl::mnemonics::OPERATIONS[index % awl::mnemonics::OPERATIONS.len()];
        let two_accumulators = cpu.accumulators == 2;
        if info.op == awl::mnemonics::OpCode::BlockEnd
            || (info.op == awl::mnemonics::OpCode::Enter && two_accumulators)
            || info.feature.is_some_and(|feature| !cpu.has(feature))
        {
            continue;
        }
        let label = if *labelled {
            format!("L{line:03} :")
        } else {
            "      ".to_string()
        };
        match info.op {
            OpCode::AndBracket | OpCode::OrBracket if open == cpu.bracket_depth => {
                body.push_str("      )\n");
                open -= 1;
            }
            OpCode::CloseBracket if open == 0 => {
                body.push_str("      A(\n");
                open += 1;
            }
            _ => {}
        }
        match info.op {
            OpCode::AndBracket | OpCode::OrBracket => open += 1,
            OpCode::CloseBracket => open -= 1,
            _ => {}
        }
        body.push_str(&format!("{label}{} {}\n", info.en, info.example_en));
        if info.op == awl::mnemonics::OpCode::Indirect {
            body.push_str("      L  DW 0\n");
        }
    }
    body.push_str(&"      )\n".repeat(usize::from(open)));
    format!(
        "OB 1\n      C  DB 10\n      JU FB 1\nNAME :R\nX    :I 0.0\nTIM  :T 1\nKON  :KF +5\n      BE\nFB 1\nNAME :R\nDES  :X I BI\nDES  :TIM T\nDES  :KON D KF\n{body}M001 :NOP 0\n      BE\nPB 3\n      BE\nFB 5\n      BE\nDB 10\n 0: KF +1\n 1: KF +2\n 2: KF +3\n"
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_programs_run_without_panic(picks in prop::collection::vec((any::<usize>(), prop::bool::weighted(0.05)), 1..40)) {
        for cpu in profile::PROFILES {
            let source = random_fb(&picks, cpu);
            let built = frontend::build_text("random.awl", &source, cpu);
            prop_assert!(!built.has_errors(), "{}: {:?}\n{}", cpu.name, built.diagnostics, source);
            let mut machine = awl::vm::Cpu::new(
                std::sync::Arc::new(built.compiled.program.clone()),
                std::sync::Arc::new(built.sources.clone()),
            );
            let outcome = machine.run(awl::vm::cycle::RunLimit::Cycles(3));
            prop_assert!(outcome.instructions > 0);
            match &outcome.stop {
                None => {
                    prop_assert_eq!(outcome.mode, awl::vm::Mode::Run);
                    prop_assert_eq!(outcome.cycles, 3);
                }
                Some(stop) => {
                    prop_assert_eq!(outcome.mode, awl::vm::Mode::Stop);
                    let block = &machine.program.blocks[usize::from(stop.block.expect("OB 1 exists"))];
                    prop_assert!((stop.pc as usize) < block.code.len(), "STOP at a real op");
                    prop_assert_eq!(&stop.stack[0].block, &block.id.to_string());
                    prop_assert!(outcome.cycles <= 3);
                }
            }
        }
    }
}

/// Random programs with random interrupt OBs present or not, and random requests and hardware
/// events, on every CPU: the engine never panics, and a run ends in RUN or with a STOP cause.
fn engine_program(with_ob1: bool, obs: &[u8]) -> String {
    let mut text = String::new();
    if with_ob1 {
        text.push_str("OB 1\n      JU PB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n");
    }
    text.push_str("PB 1\n      L  FW 0\n      L  KF +1\n      +F\n      T  FW 0\n      BE\n");
    for ob in obs {
        text.push_str(&format!(
            "OB {ob}\n      JU PB 1\n      L  PY 0\n      T  PY 1\n      BE\n"
        ));
    }
    text
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn random_interrupts_never_panic(
        with_ob1 in any::<bool>(),
        obs in prop::collection::vec(prop::sample::select(vec![2u8, 3, 4, 5, 6, 7, 13, 40, 41, 82, 85, 100, 21]), 0..6),
        events in prop::collection::vec((0u64..5_000_000, 0u8..12, 0u16..3, 0u64..400_000), 0..12),
        points_operation in any::<bool>(),
        special in any::<bool>(),
    ) {
        use awl::vm::interrupts::{Engine, EngineConfig, Happening, Scheduled};
        let mut obs = obs;
        obs.sort_unstable();
        obs.dedup();
        let source = engine_program(with_ob1, &obs);
        for cpu in profile::PROFILES {
            let built = frontend::build_text("engine.awl", &source, cpu);
            prop_assert!(!built.has_errors(), "{:?}", built.diagnostics);
            let interrupt_obs: Vec<u8> = cpu.interrupt_obs.iter().map(|entry| entry.ob).collect();
            let schedule = events
                .iter()
                .map(|&(at_ns, which, channel, active_for_ns)| {
                    let what = if cpu.family == profile::Family::Speed7 {
                        Happening::Hardware { module: u16::from(which % 3), channel, active_for_ns }
                    } else {
                        Happening::Interrupt { ob: interrupt_obs[usize::from(which) % interrupt_obs.len()] }
                    };
                    Scheduled { at_ns, what }
                })
                .collect();
            let config = EngineConfig {
                points: if points_operation { profile::InterruptPoints::Operation } else { profile::InterruptPoints::Block },
                special_mode: special,
                ob13: (cpu.family == profile::Family::S5_95f).then_some(
                    awl::vm::interrupts::Ob13Timing {
                        interval_ns: 1_000_000,
                        delay_ns: 0,
                        max_delay_ns: None,
                    },
                ),
                hw_modules: vec![(0, 40), (1, 41)],
                hw_addresses: Vec::new(),
                ob35_interval_ns: awl::vm::interrupts::OB35_DEFAULT_NS,
                watchdog_ns: 150_000_000,
                interrupt_inputs: Vec::new(),
                min_cycle_ns: 0,
            };
            let mut machine = awl::vm::Cpu::new(
                std::sync::Arc::new(built.compiled.program.clone()),
                std::sync::Arc::new(built.sources.clone()),
            );
            machine.engine = Engine::new(cpu, config, schedule);
            let outcome = machine.run(awl::vm::cycle::RunLimit::Duration(6_000_000));
            prop_assert_eq!(outcome.stop.is_some(), outcome.mode == awl::vm::Mode::Stop);
            if outcome.stop.is_none() {
                prop_assert!(outcome.clock_ns >= 6_000_000, "ran to the end");
            }
            // Every request is accounted for: serviced, lost, ignored, or still waiting.
            for (ob, stats) in machine.engine.requested_obs() {
                let waiting = machine.engine.waiting(ob);
                prop_assert_eq!(
                    stats.requested,
                    stats.serviced + stats.lost + stats.ignored + waiting,
                    "OB {}: {:?}, {} waiting", ob, stats, waiting
                );
                prop_assert!(stats.latency_min <= stats.latency_max);
            }
        }
    }
}

/// Found by the `scenario` fuzz target: a string cut off by the end of the file (`"RUN` and two
/// bytes that are no UTF-8, read as two replacement characters) used as an operand was labelled
/// as if it had its closing quote, so the label split the last character.
#[test]
fn an_operand_cut_off_by_the_end_of_the_file_is_labelled_on_whole_characters() {
    let bytes = std::fs::read("tests/inputs/fuzz_cut_off_string.toml").unwrap();
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let (mut scenario, mut reports) =
        awl::scenario::Scenario::parse(std::path::Path::new("cut.toml"), &text);
    let profile = scenario.cpu.unwrap_or(profile::default_for(Dialect::Step5));
    reports.extend(scenario.settle_cpu(profile));
    let built = frontend::build_text("p.awl", "OB 1\n      BE\n", profile);
    let set = awl::mnemonics::MnemonicSet::English;
    let program = &built.compiled.program;
    reports.extend(scenario.schedule(program, set).err().into_iter().flatten());
    reports.extend(
        scenario
            .expectations(program, set)
            .err()
            .into_iter()
            .flatten(),
    );
    assert!(!reports.is_empty());
    for report in &reports {
        for label in report.labels().into_iter().flatten() {
            let (start, end) = (label.offset(), label.offset() + label.len());
            assert!(
                text.is_char_boundary(start) && text.is_char_boundary(end),
                "{report:?}: {start}..{end}"
            );
        }
    }
}
