//! Property: for random programs and one interrupt request at a random time, the latency in
//! `block` mode never exceeds the stretch between interrupt points that contains the request
//! (and the request is taken at the first point after it); in `operation` mode it never
//! exceeds the longest single operation.

use std::io::Write;
use std::sync::{Arc, Mutex};

use awl::frontend;
use awl::profile::{self, InterruptPoints};
use awl::trace::{TraceFormat, Tracer};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Happening, Scheduled};
use proptest::prelude::*;
use serde_json::Value;

#[derive(Clone, Default)]
struct Buffer(Arc<Mutex<Vec<u8>>>);

impl Write for Buffer {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(bytes);
        Ok(bytes.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

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
    let buffer = Buffer::default();
    cpu.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    cpu.run(RunLimit::Cycles(1));
    cpu.tracer.finish().unwrap();
    let text = String::from_utf8(buffer.0.lock().unwrap().clone()).unwrap();
    (
        text.lines()
            .map(|line| serde_json::from_str(line).unwrap())
            .collect(),
        cpu,
    )
}

fn times(events: &[Value], kinds: &[&str]) -> Vec<u64> {
    events
        .iter()
        .filter(|e| kinds.contains(&e["ev"].as_str().unwrap()))
        .map(|e| e["t_ns"].as_u64().unwrap())
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn latency_is_bounded_by_the_stretch(blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..25), 1..6), fraction in 0.0f64..1.0) {
        let source = program(&blocks);
        // Where OB 1 runs in the first cycle, from a run without interrupts.
        let (dry, _) = run(&source, InterruptPoints::Block, None);
        let start = times(&dry, &["data_cycle"])[0] + 12_800;
        let end = *times(&dry, &["block_end"]).last().unwrap();
        let at = start + ((end - start) as f64 * fraction) as u64;

        let (events, _) = run(&source, InterruptPoints::Block, Some(at));
        let service = events.iter().find(|e| e["ev"] == "irq_service").expect("serviced");
        let latency = service["latency_ns"].as_u64().unwrap();
        let points = times(&dry, &["block_call", "block_end", "cycle_end"]);
        let next = *points.iter().find(|t| **t >= at).unwrap();
        let previous = points.iter().rev().find(|t| **t < at).copied().unwrap_or(start);
        prop_assert_eq!(latency, next - at, "taken at the first block change after the request");
        prop_assert!(latency <= next - previous);

        let (events, cpu) = run(&source, InterruptPoints::Operation, Some(at));
        let service = events.iter().find(|e| e["ev"] == "irq_service").expect("serviced");
        let latency = service["latency_ns"].as_u64().unwrap();
        let longest_op = cpu.program.blocks.iter().flat_map(|b| (0..b.code.len()).map(move |pc| b.cost(pc))).max().unwrap();
        prop_assert!(latency <= longest_op, "{} > {}", latency, longest_op);
    }
}
