//! Properties of the response (SINUMERIK 840C PLC manual, 5.3.2: "an interrupt is only serviced
//! on a block change"; "the maximum response time ... is therefore, in the worst case, the
//! processing time of the longest block"):
//! - a request at a random moment of the cycle — PII read, OB 1 and its blocks, PIQ write,
//!   operating-system time — is taken exactly at the first interrupt point at or after it: in
//!   `block` mode the next block change or point of the operating system, in `operation` mode
//!   the end of the operation that runs when it comes;
//! - on every CPU and in both modes, every request that did not wait for a reason the manuals
//!   give (a higher or equal priority running, `IA`, STARTUP) is serviced within the response
//!   bound the summary prints, and the trace is in time order.

use std::sync::Arc;

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
    "A  I 0.0", "AN F 1.0", "O  Q 4.0", "=  F 2.0", "L  FW 4", "L  KF +7", "T  FW 6", "X  F", ":F",
    "+F", ">F", "L  IW 2", "L  DW 1",
];

/// OB 1 calls a PB per entry of `blocks`; `loops` > 0 adds an FB counting down that often.
fn program(blocks: &[Vec<usize>], loops: u16) -> String {
    let mut text = String::from("OB 1\n      C  DB 9\n");
    for (index, _) in blocks.iter().enumerate() {
        text.push_str(&format!("      JU PB {}\n", index + 1));
    }
    if loops > 0 {
        text.push_str("      JU FB 1\nNAME :LOOP\n");
    }
    text.push_str("      BE\n");
    for (index, ops) in blocks.iter().enumerate() {
        text.push_str(&format!("PB {}\n", index + 1));
        for op in ops {
            text.push_str(&format!("      {}\n", OPS[*op]));
        }
        text.push_str("      BE\n");
    }
    text.push_str(&format!(
        "FB 1\nNAME :LOOP\n      L  KF +{loops}\n      T  FW 20\nM001 :L  FW 20\n      L  KF +1\n      -F\n      T  FW 20\n      JP =M001\n      BE\n"
    ));
    for ob in [2, 3, 4, 13, 40, 41] {
        text.push_str(&format!(
            "OB {ob}\n      L  KF +1\n      T  FW {ob}\n      JU PB 90\n      BE\n"
        ));
    }
    text + "PB 90\n      L  KF +2\n      BE\nDB 9\n 0: KF +1\n 1: KF +3\n"
}

fn run(
    source: &str,
    cpu_profile: &'static Profile,
    config: EngineConfig,
    schedule: Vec<Scheduled>,
    limit: RunLimit,
) -> (Vec<Value>, Cpu) {
    let built = frontend::build_text("p.awl", source, cpu_profile);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    cpu.engine = Engine::new(cpu_profile, config, schedule);
    let buffer = common::Buffer::default();
    cpu.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    let outcome = cpu.run(limit);
    assert!(outcome.stop.is_none(), "{:?}", outcome.stop);
    assert!(
        cpu.tracer
            .finish(cpu.clock)
            .iter()
            .all(|output| output.error.is_none())
    );
    (buffer.events(), cpu)
}

fn on_840c(source: &str, points: InterruptPoints, request_at: Option<u64>) -> (Vec<Value>, Cpu) {
    let schedule = request_at
        .map(|at_ns| Scheduled {
            at_ns,
            what: Happening::Interrupt { ob: 3 },
        })
        .into_iter()
        .collect();
    let config = EngineConfig {
        points,
        ..EngineConfig::default()
    };
    let cpu = profile::find("sinumerik-840c").unwrap();
    run(source, cpu, config, schedule, RunLimit::Cycles(1))
}

fn times(events: &[Value], kinds: &[&str]) -> Vec<u64> {
    events
        .iter()
        .filter(|e| kinds.contains(&e["ev"].as_str().unwrap()))
        .map(|e| e["t_ns"].as_u64().unwrap())
        .collect()
}

/// Where the data cycles end: points of the operating system.
fn data_cycle_ends(events: &[Value]) -> Vec<u64> {
    events
        .iter()
        .filter(|e| e["ev"] == "data_cycle")
        .map(|e| e["t_ns"].as_u64().unwrap() + e["duration_ns"].as_u64().unwrap())
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

fn latency(events: &[Value]) -> u64 {
    let service = events
        .iter()
        .find(|e| e["ev"] == "irq_service")
        .expect("serviced");
    service["latency_ns"].as_u64().unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn requests_are_taken_at_the_next_interrupt_point(
        blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..25), 1..6),
        fraction in 0.0f64..1.0,
    ) {
        let source = program(&blocks, 0);
        let (dry, dry_cpu) = on_840c(&source, InterruptPoints::Block, None);
        let cycle_end = times(&dry, &["cycle_end"])[0];
        let at = (cycle_end as f64 * fraction) as u64;
        let system_points: Vec<u64> = data_cycle_ends(&dry).into_iter().chain([cycle_end]).collect();

        let (events, _) = on_840c(&source, InterruptPoints::Block, Some(at));
        let mut points = times(&dry, &["block_call", "block_end"]);
        points.extend(&system_points);
        points.sort_unstable();
        let next = *points.iter().find(|t| **t >= at).unwrap();
        prop_assert_eq!(latency(&events), next - at, "block mode: the first point at or after {}", at);

        let (events, _) = on_840c(&source, InterruptPoints::Operation, Some(at));
        let start = data_cycle_ends(&dry)[0];
        let mut ends = Vec::new();
        op_ends(&dry_cpu.program, dry_cpu.program.ob(1).unwrap(), &mut { start }, &mut ends);
        ends.extend(&system_points);
        ends.sort_unstable();
        let next = *ends.iter().find(|t| **t >= at).unwrap();
        prop_assert_eq!(latency(&events), next - at, "operation mode: the end of the running operation");
    }
}

/// A request for every interrupt OB of the CPU, and on the S5-95F OB 13 every 5 ms.
fn requests(cpu: &Profile, picks: &[(u64, u8)]) -> (Vec<Scheduled>, Option<Ob13Timing>) {
    let obs = common::requestable_obs(cpu);
    let inputs = picks.iter().map(|&(at_ns, which)| Scheduled {
        at_ns: at_ns / 2,
        what: Happening::SetInputs(vec![InputChange {
            target: InputTarget::Process,
            byte: 0,
            bit: which % 8,
            bytes: 0,
            value: u32::from(which % 2),
        }]),
    });
    let schedule = picks
        .iter()
        .map(|&(at_ns, which)| Scheduled {
            at_ns,
            what: match cpu.family {
                Family::Speed7 => Happening::Hardware {
                    module: 1 + u16::from(which % 2),
                    channel: u16::from(which / 2 % 2),
                    active_for_ns: 2_000,
                },
                _ => Happening::Interrupt {
                    ob: obs[usize::from(which) % obs.len()],
                },
            },
        })
        .chain(inputs)
        .collect();
    let ob13 = (cpu.family == Family::S5_95f).then_some(Ob13Timing {
        interval_ns: 5_000_000,
        delay_ns: 0,
        max_delay_ns: None,
    });
    (schedule, ob13)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn latency_stays_within_the_bound_and_the_trace_in_time_order(
        blocks in prop::collection::vec(prop::collection::vec(0..OPS.len(), 1..25), 1..5),
        loops in prop::sample::select(vec![0u16, 3, 40]),
        picks in prop::collection::vec((0u64..12_000_000, any::<u8>()), 1..25),
    ) {
        let source = program(&blocks, loops);
        let mut checked = 0;
        for cpu in profile::PROFILES {
            for points in [InterruptPoints::Block, InterruptPoints::Operation] {
                let (schedule, ob13) = requests(cpu, &picks);
                let config = EngineConfig {
                    points,
                    special_mode: true,
                    ob13,
                    hw_modules: vec![(1, 40), (2, 41)],
                    ..EngineConfig::default()
                };
                let (events, machine) = run(&source, cpu, config, schedule, RunLimit::Duration(14_000_000));
                let bound = machine.response_bound().ns;
                let times: Vec<u64> = events.iter().map(|e| e["t_ns"].as_u64().unwrap()).collect();
                prop_assert!(times.windows(2).all(|pair| pair[0] <= pair[1]), "{} {:?}: the trace goes back in time", cpu.name, points);
                for service in events.iter().filter(|e| e["ev"] == "irq_service") {
                    let latency = service["latency_ns"].as_u64().unwrap();
                    if service.get("waited").is_none() {
                        checked += 1;
                        prop_assert!(
                            latency <= bound,
                            "{} {:?}: {} waited {} ns, bound {} ns", cpu.name, points, service, latency, bound
                        );
                    }
                }
            }
        }
        prop_assert!(checked > 0, "some requests did not wait");
    }
}
