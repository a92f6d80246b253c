//! Every trace is in time order, events of one time in the order they happened: on every CPU,
//! in both interrupt-point modes and both SINUMERIK 840C modes, with requests, hardware events
//! and input changes at any moment, during the startup OB too (the SPEED7 judges the events of
//! STARTUP only at the transition to RUN, and must not write them after what came later).

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
    "A  I 0.0", "AN F 1.0", "O  I 0.3", "=  Q 4.0", "L  FW 4", "L  KF +7", "T  FW 6", "T  QW 6",
    "+F", "L  IW 2", "L  DW 1", "JU PB 90",
];

/// A startup OB and OB 1 of random straight code, each ending in a count-down loop of
/// `loops` passes (so STARTUP can last long), and every interrupt OB of every CPU.
fn program(startup: &[usize], cyclic: &[usize], loops: u16) -> String {
    let block = |name: &str, ops: &[usize]| {
        let body: String = ops
            .iter()
            .map(|op| format!("      {}\n", OPS[*op]))
            .collect();
        format!("{name}\n      C  DB 9\n{body}      JU FB 1\nNAME :LOOP\n      BE\n")
    };
    let mut text = block("OB 1", cyclic);
    for ob in [21, 22, 100] {
        text += &block(&format!("OB {ob}"), startup);
    }
    text += &format!(
        "FB 1\nNAME :LOOP\n      L  KF +{loops}\n      T  FW 20\nM001 :L  FW 20\n      L  KF +1\n      -F\n      T  FW 20\n      JP =M001\n      BE\n"
    );
    for ob in [2, 3, 4, 5, 6, 7, 13, 40, 41, 82, 85] {
        text += &format!("OB {ob}\n      L  KF +1\n      T  FW {ob}\n      JU PB 90\n      BE\n");
    }
    text + "PB 90\n      L  KF +2\n      =  Q 5.1\n      BE\nDB 9\n 0: KF +1\n 1: KF +3\n"
}

/// The requests of `picks` (time, which) as `cpu` takes them: S5 interrupt requests for its
/// interrupt OBs, SPEED7 hardware events on two modules; an input change beside each.
fn schedule(cpu: &Profile, picks: &[(u64, u8)]) -> Vec<Scheduled> {
    let obs = common::requestable_obs(cpu);
    let mut schedule = Vec::new();
    for &(at_ns, which) in picks {
        let what = match cpu.family {
            Family::Speed7 => Happening::Hardware {
                module: 1 + u16::from(which % 3),
                channel: u16::from(which / 3 % 2),
                active_for_ns: 500 + u64::from(which) * 40,
            },
            _ => Happening::Interrupt {
                ob: obs[usize::from(which) % obs.len()],
            },
        };
        schedule.push(Scheduled { at_ns, what });
        let change = InputChange {
            target: InputTarget::Process,
            byte: 0,
            bit: which % 8,
            bytes: 0,
            value: u32::from(which % 2),
        };
        schedule.push(Scheduled {
            at_ns: at_ns / 3,
            what: Happening::SetInputs(vec![change]),
        });
    }
    schedule
}

/// The jsonl trace of a run.
fn trace(
    source: &str,
    cpu: &'static Profile,
    config: EngineConfig,
    picks: &[(u64, u8)],
) -> Vec<Value> {
    let built = frontend::build_text("p.awl", source, cpu);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut machine = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    machine.engine = Engine::new(cpu, config, schedule(cpu, picks));
    let buffer = common::Buffer::default();
    machine.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    machine.run(RunLimit::Duration(2_000_000));
    assert!(
        machine
            .tracer
            .finish(machine.clock)
            .iter()
            .all(|output| output.error.is_none())
    );
    buffer.events()
}

/// Where the trace first goes back in time, if it does.
fn first_step_back(events: &[Value]) -> Option<(&Value, &Value)> {
    events
        .windows(2)
        .find(|pair| pair[0]["t_ns"].as_u64() > pair[1]["t_ns"].as_u64())
        .map(|pair| (&pair[0], &pair[1]))
}

/// Every CPU, both point modes, and both modes of the SINUMERIK 840C.
fn configurations() -> Vec<(&'static Profile, InterruptPoints, bool)> {
    let mut all = Vec::new();
    for cpu in profile::PROFILES {
        for points in [InterruptPoints::Block, InterruptPoints::Operation] {
            all.push((cpu, points, false));
            if cpu.family == Family::Sinumerik840c {
                all.push((cpu, points, true));
            }
        }
    }
    all
}

fn config(cpu: &Profile, points: InterruptPoints, special_mode: bool) -> EngineConfig {
    EngineConfig {
        points,
        special_mode,
        ob13: (cpu.family == Family::S5_95f).then_some(Ob13Timing {
            interval_ns: 300_000,
            delay_ns: 0,
            max_delay_ns: None,
        }),
        hw_modules: vec![(1, 40), (2, 41), (3, 42)],
        ..EngineConfig::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 40, ..ProptestConfig::default() })]

    #[test]
    fn every_trace_is_in_time_order(
        startup in prop::collection::vec(0..OPS.len(), 0..30),
        cyclic in prop::collection::vec(0..OPS.len(), 1..30),
        loops in prop::sample::select(vec![1u16, 20, 400]),
        // Many events fall in the first 20 µs, in the startup OB.
        early in prop::collection::vec((0u64..20_000, any::<u8>()), 0..12),
        late in prop::collection::vec((0u64..1_500_000, any::<u8>()), 0..12),
    ) {
        let source = program(&startup, &cyclic, loops);
        let picks: Vec<(u64, u8)> = early.into_iter().chain(late).collect();
        for (cpu, points, special) in configurations() {
            let events = trace(&source, cpu, config(cpu, points, special), &picks);
            let back = first_step_back(&events);
            prop_assert!(back.is_none(), "{} {:?} special {}: {:?}", cpu.name, points, special, back);
        }
    }
}

/// The case that went back in time: a SPEED7 module event at 2 µs, while OB 100 runs for
/// longer, was written after OB 100's block events. Still active at the transition to RUN, it
/// is a lost request; over before it, no request at all.
#[test]
fn a_speed7_event_in_startup_is_written_at_its_time() {
    let startup: Vec<usize> = [4, 6].repeat(30);
    let source = program(&startup, &[0, 3], 40);
    let cpu = profile::find("speed7").unwrap();
    let config = || config(cpu, InterruptPoints::Operation, false);
    for (which, kind) in [(255, "irq_request"), (0, "module_event")] {
        let events = trace(&source, cpu, config(), &[(2_000, which)]);
        assert_eq!(first_step_back(&events), None);
        let event = events.iter().position(|e| e["ev"] == kind).unwrap();
        let run = events
            .iter()
            .position(|e| e["ev"] == "mode" && e["to"] == "RUN")
            .unwrap();
        assert!(event < run, "{events:#?}");
        assert!(
            events[run]["t_ns"].as_u64() > Some(2_000),
            "OB 100 runs past the event"
        );
        assert_eq!(events[event]["t_ns"], 2_000);
    }
    let events = trace(&source, cpu, config(), &[(2_000, 255)]);
    let request = events.iter().find(|e| e["ev"] == "irq_request").unwrap();
    assert_eq!(
        request["block"], "FB 1",
        "where the CPU was when it came: OB 100's loop"
    );
}
