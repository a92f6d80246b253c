//! VM speed on programs/bench: a bit-logic and word-arithmetic loop, block-call-heavy code, and
//! an FB with formal parameters called in a loop.
//! Each is measured as the bare execution loop ("vm_only": OB 1 run directly, no cycle, no
//! engine) and through the full cycle with the interrupt engine on and nothing pending, with
//! block and with operation interrupt points, and with a probe that looks at every operation
//! (the stepping loop of program status and the debugger). Targets (release, one core, engine
//! on): 500 M instr/s on the loop with block points, 400 M with operation points, 300 M on
//! block calls, 150 M on the FB with parameters.

use std::sync::Arc;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

use awl::compiler::Op;
use awl::frontend;
use awl::profile::{self, InterruptPoints};
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Happening, Scheduled};
use awl::vm::probe::{Flow, Probe};
use awl::vm::{Cpu, Exit};

/// Looks at every operation, as program status does, and lets the run go on.
struct Looking;

impl Probe for Looking {
    fn before(&mut self, _cpu: &mut Cpu) -> Flow {
        Flow::Go
    }

    fn after(&mut self, cpu: &Cpu, _block: u16, _pc: u32, _op: Op) -> Flow {
        std::hint::black_box(cpu.level.accu1);
        Flow::Go
    }
}

fn cpu_for(file: &str, points: InterruptPoints) -> Cpu {
    let source = std::fs::read_to_string(file).unwrap() + "OB 3\n      BE\n";
    let built = frontend::build_text(file, &source, profile::find("sinumerik-840c").unwrap());
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    // A request far in the future: the engine is armed, nothing is pending.
    let far = vec![Scheduled {
        at_ns: u64::MAX / 2,
        what: Happening::Interrupt { ob: 3 },
    }];
    let config = EngineConfig {
        points,
        watchdog_ns: 10_000_000_000,
        ..EngineConfig::default()
    };
    cpu.engine = Engine::new(cpu.profile, config, far);
    cpu
}

/// OB 1 once through the bare loop.
fn ob1_only(cpu: &mut Cpu) {
    let ob1 = cpu.program.ob(1).unwrap();
    cpu.enter_level(ob1)
        .expect("OB 1's local data fit the L stack");
    cpu.attention_at = u64::MAX;
    while !matches!(cpu.execute(false), Exit::LevelEnd) {}
}

fn bench_program(c: &mut Criterion, name: &str, file: &str, cycles: u64) {
    let mut probe = cpu_for(file, InterruptPoints::Block);
    probe.run(RunLimit::Cycles(cycles));
    let per_run = probe.instructions;
    let mut group = c.benchmark_group(name);
    group.throughput(Throughput::Elements(per_run));
    group.sample_size(20);
    group.bench_function("vm_only", |b| {
        let mut cpu = cpu_for(file, InterruptPoints::Block);
        b.iter(|| {
            for _ in 0..cycles {
                ob1_only(&mut cpu);
            }
        })
    });
    for (label, points) in [
        ("engine_block_points", InterruptPoints::Block),
        ("engine_operation_points", InterruptPoints::Operation),
    ] {
        group.bench_function(label, |b| {
            let mut cpu = cpu_for(file, points);
            b.iter(|| {
                let limit = RunLimit::Cycles(cpu.cycle + cycles);
                cpu.run(limit)
            })
        });
    }
    group.bench_function("stepping_probe", |b| {
        let mut cpu = cpu_for(file, InterruptPoints::Block);
        cpu.probe = Some(Box::new(Looking));
        b.iter(|| {
            let limit = RunLimit::Cycles(cpu.cycle + cycles);
            cpu.run(limit)
        })
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    bench_program(c, "logic_loop", "programs/bench/logic_loop.awl", 20);
    bench_program(c, "calls", "programs/bench/calls.awl", 2000);
    bench_program(c, "fb_params", "programs/bench/fb_params.awl", 20);
}

criterion_group!(vm, benches);
criterion_main!(vm);
