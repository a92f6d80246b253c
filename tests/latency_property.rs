//! Property: for random programs and one interrupt request at a random time of the cycle, the
//! request is taken exactly at the first interrupt point at or after it: in `block` mode the
//! next block change or the cycle boundary, in `operation` mode the end of the operation that
//! runs when it comes.

use std::sync::Arc;

use awl::frontend;
use awl::profile::{self, InterruptPoints};
use awl::trace::{TraceFormat, Tracer};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Happening, Scheduled};
use proptest::prelude::*;
use serde_json::Value;

mod common;

const OPS: &[&str] = &[
    "A  I 0.0", "AN F 1.0", "O  Q 4.0", "=  F 2.0", "L  FW 4", "L  KF +7", "T  FW 6", "X  F", ":F",
    "+F", ">F", "L  IW 2", "L  DW 1",
];

fn program(blocks: &[Vec<usize>]) -> String {
    let mut text = String::from("OB 1\n      C  DB 9\n");
    for (index, _) in blocks.iter().enumerate() {
        text.push_str(&format!("      JU PB {}\n", index + 1));
    }
    text.push_str("      BE\n");
    for (index, ops) in blocks.iter().enumerate() {
        text.push_str(&format!("PB {}\n", index + 1));
        for op in ops {
            text.push_str(&format!("      {}\n", OPS[*op]));
        }
        text.push_str("      BE\n");
    }
    text + "OB 3\n      L  KF +1\n      T  FW 8\n      BE\nDB 9\n 0: KF +1\n 1: KF +3\n"
}

fn run(source: &str, points: InterruptPoints, request_at: Option<u64>) -> (Vec<Value>, Cpu) {
    let cpu_profile = profile::find("sinumerik-840c").unwrap();
    let built = frontend::build_text("p.awl", source, cpu_profile);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    let schedule = request_at
        .map(|at_ns| Scheduled {
            at_ns,
            what: Happening::Interrupt { ob: 3 },
        })
        .into_iter()
        .collect();
    cpu.engine = Engine::new(
        EngineConfig {
            points,
            ..EngineConfig::default()
        },
        schedule,
    );
    let buffer = common::Buffer::default();
    cpu.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    cpu.run(RunLimit::Cycles(1));
    cpu.tracer.finish().unwrap();
    (buffer.events(), cpu)
}

fn times(events: &[Value], kinds: &[&str]) -> Vec<u64> {
    events
        .iter()
        .filter(|e| kinds.contains(&e["ev"].as_str().unwrap()))
        .map(|e| e["t_ns"].as_u64().unwrap())
        .collect()
}

/// When each op of a block ends, with the blocks it calls, running from `*t` on (the random
/// programs are straight code).
fn op_ends(program: &awl::compiler::Program, block: u16, t: &mut u64, ends: &mut Vec<u64>) {
    let code = &program.blocks[usize::from(block)];
    for pc in 0..code.code.len() {
        *t += code.cost(pc);
        ends.push(*t);
        if let awl::compiler::Op::Call { block: callee, .. } = code.code[pc] {
            op_ends(program, callee, t, ends);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    /// A request anywhere in the first cycle — the PII read, OB 1 and its blocks, the PIQ write
    /// and the operating-system time — is taken at the first interrupt point at or after it:
    /// in `block` mode the next block call or block end or the cycle boundary, in `operation`
    /// mode the end of the operation that runs when it comes.
    #[test]
    fn latency_is_bounded_by_the_stretch(blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..25), 1..6), fraction in 0.0f64..1.0) {
        let source = program(&blocks);
        let (dry, dry_cpu) = run(&source, InterruptPoints::Block, None);
        let read = dry.iter().find(|e| e["ev"] == "data_cycle").unwrap();
        let start = read["t_ns"].as_u64().unwrap() + read["duration_ns"].as_u64().unwrap();
        let cycle_end = times(&dry, &["cycle_end"])[0];
        let at = (cycle_end as f64 * fraction) as u64;

        let (events, _) = run(&source, InterruptPoints::Block, Some(at));
        let service = events.iter().find(|e| e["ev"] == "irq_service").expect("serviced");
        let latency = service["latency_ns"].as_u64().unwrap();
        let points = times(&dry, &["block_call", "block_end", "cycle_end"]);
        let next = *points.iter().find(|t| **t >= at).unwrap();
        prop_assert_eq!(latency, next - at, "taken at the first block change after the request");

        let (events, _) = run(&source, InterruptPoints::Operation, Some(at));
        let service = events.iter().find(|e| e["ev"] == "irq_service").expect("serviced");
        let latency = service["latency_ns"].as_u64().unwrap();
        let mut ends = Vec::new();
        op_ends(&dry_cpu.program, dry_cpu.program.ob(1).unwrap(), &mut { start }, &mut ends);
        ends.push(cycle_end);
        let next = *ends.iter().find(|t| **t >= at).unwrap();
        prop_assert_eq!(latency, next - at, "taken when the operation running at the request ends");
    }
}
