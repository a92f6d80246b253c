//! `awl analyze` against runs: for random programs without loops, on every CPU,
//! - each block's static `stretch_ns` is at least the longest stretch between two interrupt
//!   points measured in it on runs with random inputs, and equal for straight-line code;
//! - each interrupt OB's static response bound is at least every latency measured in runs
//!   with random interrupt requests (a millisecond apart, so each OB can come first once).

use std::collections::BTreeMap;
use std::sync::Arc;

use awl::analyze::{self, Analysis, Config};
use awl::frontend;
use awl::profile::{self, Family, InterruptPoints, Profile};
use awl::trace::{TraceFormat, Tracer};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{
    Engine, EngineConfig, Happening, InputChange, InputTarget, Ob13Timing, Scheduled,
};
use proptest::prelude::*;
use serde_json::Value;

mod common;

const OPS: &[&str] = &[
    "A  I 0.0", "AN I 0.1", "O  Q 4.0", "=  F 2.0", "L  FW 4", "L  KF +7", "T  FW 6", "X  F", ":F",
    "+F", ">F", "L  IW 2", "L  DW 1", "S  F 3.0",
];

/// OB 1 calls a PB per entry of `blocks`; with `branches`, an FB whose jumps and `BEB` depend
/// on the inputs.
fn program(blocks: &[Vec<usize>], branches: bool) -> String {
    let mut text = String::from("OB 1\n      C  DB 9\n");
    for (index, _) in blocks.iter().enumerate() {
        text.push_str(&format!("      JU PB {}\n", index + 1));
    }
    if branches {
        text.push_str("      JU FB 1\nNAME :BRANCH\n");
    }
    text.push_str("      BE\n");
    for (index, ops) in blocks.iter().enumerate() {
        text.push_str(&format!("PB {}\n", index + 1));
        for op in ops {
            text.push_str(&format!("      {}\n", OPS[*op]));
        }
        text.push_str("      BE\n");
    }
    text.push_str(
        "FB 1\nNAME :BRANCH\n      A  I 0.0\n      JC =M001\n      L  FW 4\n      L  FW 6\n      X  F\n      T  FW 8\nM001 :A  I 0.1\n      BEC\n      L  KF +3\n      JU PB 90\n      BE\n",
    );
    for ob in [2, 3, 4, 13, 40, 41] {
        text.push_str(&format!(
            "OB {ob}\n      L  KF +1\n      T  FW {ob}\n      JU PB 90\n      BE\n"
        ));
    }
    text + "PB 90\n      L  KF +2\n      BE\nDB 9\n 0: KF +1\n 1: KF +3\n"
}

fn inputs(picks: &[(u64, u8)]) -> impl Iterator<Item = Scheduled> + '_ {
    picks.iter().map(|&(at_ns, which)| Scheduled {
        at_ns,
        what: Happening::SetInputs(vec![InputChange {
            target: InputTarget::Process,
            byte: 0,
            bit: which % 2,
            bytes: 0,
            value: u32::from(which / 2 % 2),
        }]),
    })
}

fn run(
    source: &str,
    cpu: &'static Profile,
    config: EngineConfig,
    schedule: Vec<Scheduled>,
) -> (Vec<Value>, Analysis) {
    let built = frontend::build_text("p.awl", source, cpu);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let analysis = analyze::analyze(
        &built.compiled.program,
        &built.sources,
        Config {
            profile: cpu,
            points: config.points,
            special_mode: config.special_mode,
            ob13_interval_ns: config.ob13.map(|timing| timing.interval_ns),
            watchdog_ns: config.watchdog_ns,
        },
    );
    let mut machine = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    machine.engine = Engine::new(cpu, config, schedule);
    let buffer = common::Buffer::default();
    machine.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    let outcome = machine.run(RunLimit::Duration(12_000_000));
    assert!(outcome.stop.is_none(), "{:?}", outcome.stop);
    assert!(
        machine
            .tracer
            .finish(machine.clock)
            .iter()
            .all(|output| output.error.is_none())
    );
    (buffer.events(), analysis)
}

/// The longest stretch between two points measured in each block (a run without interrupts):
/// a stretch ends at a call (the caller's) or a block end (the ending block's) and starts at
/// the point before it or at the end of the PII read.
fn measured_stretches(events: &[Value]) -> BTreeMap<String, u64> {
    let mut longest: BTreeMap<String, u64> = BTreeMap::new();
    let mut last = 0;
    for event in events {
        let t = event["t_ns"].as_u64().unwrap();
        let block = match event["ev"].as_str().unwrap() {
            "data_cycle" if event["direction"] == "input" => {
                last = t + event["duration_ns"].as_u64().unwrap();
                continue;
            }
            "block_call" => event["from"].as_str().unwrap(),
            "block_end" => event["block"].as_str().unwrap(),
            _ => continue,
        };
        let entry = longest.entry(block.to_string()).or_default();
        *entry = (*entry).max(t - last);
        last = t;
    }
    longest
}

fn static_stretch(analysis: &Analysis, block: &str) -> u64 {
    let figures = analysis
        .blocks
        .iter()
        .find(|figures| figures.block == block)
        .unwrap_or_else(|| panic!("{block} analysed"));
    figures.stretch_ns.expect("no loops: bounded")
}

fn config(cpu: &Profile, points: InterruptPoints) -> EngineConfig {
    EngineConfig {
        points,
        special_mode: true,
        ob13: (cpu.family == Family::S5_95f).then_some(Ob13Timing {
            interval_ns: 5_000_000,
            delay_ns: 0,
            max_delay_ns: None,
        }),
        hw_modules: vec![(1, 40), (2, 41)],
        ..EngineConfig::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 32, ..ProptestConfig::default() })]

    #[test]
    fn static_stretches_bound_the_measured_ones(
        blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..20), 1..5),
        branches in any::<bool>(),
        picks in prop::collection::vec((0u64..12_000_000, any::<u8>()), 0..20),
    ) {
        let source = program(&blocks, branches);
        for cpu in profile::PROFILES {
            let mut config = config(cpu, InterruptPoints::Block);
            config.ob13 = None;
            let (events, analysis) = run(&source, cpu, config, inputs(&picks).collect());
            for (block, measured) in measured_stretches(&events) {
                let bound = static_stretch(&analysis, &block);
                prop_assert!(measured <= bound, "{} {}: measured {} > static {}", cpu.name, block, measured, bound);
                // Straight-line code: one path, the same every cycle.
                let straight = block != "FB 1" && !(branches && block == "OB 1");
                if straight {
                    prop_assert_eq!(measured, bound, "{} {}: straight-line code", cpu.name, block);
                }
            }
        }
    }

    #[test]
    fn static_response_bounds_hold_every_latency(
        blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..20), 1..4),
        branches in any::<bool>(),
        slots in prop::collection::btree_set(1u64..11, 1..8),
        picks in prop::collection::vec((0u64..900_000, any::<u8>()), 8),
    ) {
        let source = program(&blocks, branches);
        let mut checked = 0;
        for cpu in profile::PROFILES {
            for points in [InterruptPoints::Block, InterruptPoints::Operation] {
                let obs = common::requestable_obs(cpu);
                // One request a millisecond at most, at a random moment of it.
                let requests = slots.iter().zip(&picks).map(|(slot, &(offset, which))| Scheduled {
                    at_ns: slot * 1_000_000 + offset,
                    what: match cpu.family {
                        Family::Speed7 => Happening::Hardware {
                            module: 1 + u16::from(which % 2),
                            channel: 0,
                            active_for_ns: 2_000,
                        },
                        _ => Happening::Interrupt { ob: obs[usize::from(which) % obs.len()] },
                    },
                });
                let schedule = requests.chain(inputs(&picks)).collect();
                let (events, analysis) = run(&source, cpu, config(cpu, points), schedule);
                for service in events.iter().filter(|e| e["ev"] == "irq_service") {
                    let ob = service["ob"].as_u64().unwrap() as u8;
                    let latency = service["latency_ns"].as_u64().unwrap();
                    let Some(figures) = analysis.obs.iter().find(|figures| figures.ob == ob) else {
                        continue;
                    };
                    let bound = figures.response_bound_ns.expect("no loops: bounded");
                    checked += 1;
                    prop_assert!(
                        latency <= bound,
                        "{} {:?}: OB {} waited {} ns, static bound {} ns: {}", cpu.name, points, ob, latency, bound, service
                    );
                }
            }
        }
        prop_assert!(checked > 0, "some requests were serviced");
    }
}
