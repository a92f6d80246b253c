//! The execution loop and the interrupt engine allocate nothing: after a warm-up, running many
//! cycles of a program with calls, FB parameters, timers, counters and data blocks performs no
//! allocation — nor does servicing interrupts of every kind on every CPU (requests that are
//! serviced, lost and ignored; OB 13 with its data cycles; SPEED7 hardware interrupts that are
//! held, lost with OB 82, or go to OB 85), nor input changes. Only writing a trace allocates.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;

use awl::frontend;
use awl::profile::{self, InterruptPoints};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{
    Engine, EngineConfig, Happening, InputChange, InputTarget, Ob13Timing, ObStats, Scheduled,
};

struct Counting;

thread_local! {
    /// Allocations of this thread: the tests run in parallel, each counts its own.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn allocations_so_far() -> usize {
    ALLOCATIONS.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|count| count.set(count.get() + 1));
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn machine(source: &str, cpu: &str) -> Cpu {
    let built = frontend::build_text("alloc.awl", source, profile::find(cpu).unwrap());
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    )
}

/// Runs `limit` after a warm-up and returns the allocations made in it.
fn allocations(cpu: &mut Cpu, warm_up: RunLimit, limit: RunLimit) -> usize {
    let warm = cpu.run(warm_up);
    assert!(warm.stop.is_none(), "{:?}", warm.stop);
    let before = allocations_so_far();
    let outcome = cpu.run(limit);
    let after = allocations_so_far();
    assert!(outcome.stop.is_none(), "{:?}", outcome.stop);
    after - before
}

#[test]
fn running_cycles_allocates_nothing() {
    let source = std::fs::read_to_string("programs/two_motors.awl").unwrap()
        + "PB 1\n      C  DB 5\n      L  DW 0\n      L  KF +1\n      +F\n      T  DW 0\n      A  I 0.0\n      CU C 1\n      BE\nDB 5\n 0: KF +0\nOB 3\n      BE\n";
    let source = source.replacen("      BE\n", "      JU PB 1\n      BE\n", 1);
    let mut cpu = machine(&source, "sinumerik-840c");
    let count = allocations(&mut cpu, RunLimit::Cycles(1), RunLimit::Cycles(2000));
    assert!(cpu.instructions > 50_000);
    assert_eq!(count, 0, "allocations while running");
}

/// An interrupt OB that calls a block, reads the periphery and writes it.
fn interrupt_ob(ob: u8) -> String {
    format!(
        "OB {ob}\n      JU PB 9\n      L  PY 0\n      T  PY 1\n      L  FW {ob}\n      L  KF +1\n      +F\n      T  FW {ob}\n      BE\n"
    )
}

const CYCLIC: &str = "OB 1\n      JU PB 9\n      A  I 0.0\n      =  Q 4.0\n      BE\nPB 9\n      L  IW 2\n      T  FW 100\n      BE\n";

/// Events every `every` ns from `from` to `to`: the kinds `kinds` makes, in turn.
fn schedule(from: u64, to: u64, every: u64, kinds: &[Happening]) -> Vec<Scheduled> {
    (0..)
        .map(|i| (from + i * every, &kinds[i as usize % kinds.len()]))
        .take_while(|(at, _)| *at < to)
        .map(|(at_ns, what)| Scheduled {
            at_ns,
            what: what.clone(),
        })
        .collect()
}

fn input(byte: u16, value: u32) -> Happening {
    Happening::SetInputs(vec![InputChange {
        target: InputTarget::Process,
        byte,
        bit: 0,
        bytes: 2,
        value,
    }])
}

fn total(cpu: &Cpu) -> ObStats {
    cpu.engine
        .requested_obs()
        .fold(ObStats::default(), |sum, (_, stats)| ObStats {
            requested: sum.requested + stats.requested,
            serviced: sum.serviced + stats.serviced,
            lost: sum.lost + stats.lost,
            ignored: sum.ignored + stats.ignored,
            ..sum
        })
}

const MS: u64 = 1_000_000;

#[test]
fn servicing_interrupts_allocates_nothing_on_the_840c() {
    for points in [InterruptPoints::Block, InterruptPoints::Operation] {
        let source = [3, 4, 6, 7, 2, 5]
            .map(interrupt_ob)
            .into_iter()
            .fold(CYCLIC.to_string(), |text, ob| text + &ob);
        let mut cpu = machine(&source, "sinumerik-840c");
        // OB 2 and OB 5 are ignored in normal mode; OB 3 twice in a row is lost once.
        let kinds = [2, 3, 3, 4, 5, 6, 7].map(|ob| Happening::Interrupt { ob });
        let mut events = schedule(0, 200 * MS, 37_000, &kinds);
        events.extend(schedule(
            5_000,
            200 * MS,
            410_000,
            &[input(2, 7), input(2, 9)],
        ));
        cpu.engine = Engine::new(
            cpu.profile,
            EngineConfig {
                points,
                ..EngineConfig::default()
            },
            events,
        );
        let count = allocations(
            &mut cpu,
            RunLimit::Duration(5 * MS),
            RunLimit::Duration(200 * MS),
        );
        let stats = total(&cpu);
        assert!(stats.serviced > 1000 && stats.lost > 0 && stats.ignored > 1000);
        assert_eq!(count, 0, "allocations while servicing ({points:?})");
    }
}

#[test]
fn servicing_ob13_and_process_interrupts_allocates_nothing_on_the_s5_95f() {
    let source = CYCLIC.to_string() + &interrupt_ob(13) + &interrupt_ob(3);
    let mut cpu = machine(&source, "s5-95f");
    let mut events = schedule(0, 300 * MS, 2_300_000, &[Happening::Interrupt { ob: 3 }]);
    events.extend(schedule(
        100_000,
        300 * MS,
        1_700_000,
        &[input(0, 5), input(0, 6)],
    ));
    cpu.engine = Engine::new(
        cpu.profile,
        EngineConfig {
            ob13: Some(Ob13Timing {
                interval_ns: 5 * MS,
                delay_ns: 0,
                max_delay_ns: None,
            }),
            ..EngineConfig::default()
        },
        events,
    );
    let count = allocations(
        &mut cpu,
        RunLimit::Duration(11 * MS),
        RunLimit::Duration(300 * MS),
    );
    assert!(cpu.engine.stats(13).serviced > 50 && cpu.engine.stats(3).serviced > 100);
    assert_eq!(count, 0, "allocations while servicing");
}

#[test]
fn hardware_interrupts_allocate_nothing_on_the_speed7() {
    // Module 1 → OB 40 (programmed), module 2 → OB 40 too (busy-OB hold), module 3 → OB 41
    // (not programmed: OB 85). Same-channel events are lost and start OB 82; other channels
    // are held until the acknowledgement.
    let source = CYCLIC.to_string()
        + &interrupt_ob(40)
        + &interrupt_ob(82)
        + &interrupt_ob(85)
        + "FB 1\nNAME :WAIT\n      L  KF +300\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n";
    let source = source.replacen("OB 40\n", "OB 40\n      JU FB 1\nNAME :WAIT\n", 1);
    let mut cpu = machine(&source, "speed7");
    let hardware = |module, channel, active_for_ns| Happening::Hardware {
        module,
        channel,
        active_for_ns,
    };
    let kinds = [
        hardware(1, 0, 5_000),
        hardware(1, 0, 5_000),
        hardware(1, 1, 400_000),
        hardware(2, 0, 400_000),
        hardware(1, 2, 1_000),
        hardware(3, 0, 1_000),
    ];
    let mut events = schedule(0, 100 * MS, 3_000, &kinds);
    events.extend(schedule(
        1_000,
        100 * MS,
        90_000,
        &[input(2, 1), input(2, 2)],
    ));
    cpu.engine = Engine::new(
        cpu.profile,
        EngineConfig {
            points: InterruptPoints::Operation,
            hw_modules: vec![(1, 40), (2, 40), (3, 41)],
            ..EngineConfig::default()
        },
        events,
    );
    let count = allocations(
        &mut cpu,
        RunLimit::Duration(2 * MS),
        RunLimit::Duration(100 * MS),
    );
    let stats = total(&cpu);
    assert!(stats.serviced > 1000 && stats.lost > 1000 && stats.ignored > 1000);
    assert!(cpu.engine.stats(82).serviced > 0 && cpu.engine.stats(85).serviced > 0);
    assert_eq!(count, 0, "allocations while servicing");
}

#[test]
fn library_fcs_allocate_nothing() {
    // String, date and scaling blocks, with constants copied in and results cut (BR 0).
    let source = "
DATA_BLOCK DB 1
STRUCT
  text : STRING [20] := 'Hello';
  short : STRING [3];
  at : DATE_AND_TIME := DT#2024-3-15-12:00:00.000;
  later : DATE_AND_TIME;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  \"CONCAT\" (IN1 := DB1.text, IN2 := ' World', RET_VAL := DB1.short);
      CALL  \"R_STRNG\" (IN := 1234.5, RET_VAL := DB1.text);
      CALL  \"STRNG_R\" (S := DB1.text, RET_VAL := MD 0);
      CALL  \"AD_DT_TM\" (T := DB1.at, D := T#1H, RET_VAL := DB1.later);
      CALL  \"SCALE\" (IN := MW 4, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 6, OUT := MD 8);
      CALL  \"MAX\" (IN1 := MW 4, IN2 := 7, IN3 := -1, RET_VAL := MW 12);
END_ORGANIZATION_BLOCK
";
    let mut cpu = machine(source, "speed7");
    let count = allocations(&mut cpu, RunLimit::Cycles(1), RunLimit::Cycles(2000));
    assert!(cpu.instructions > 10_000);
    assert_eq!(count, 0, "allocations while running");
}

#[test]
fn interrupts_raised_by_input_edges_allocate_nothing() {
    use awl::vm::interrupts::inputs::{Edge, InterruptInput, Raises};
    // `input(2, 1)` and `input(2, 2)` in turn toggle I 3.0 and I 3.1.
    let tied = |bit, edge, raises| InterruptInput {
        byte: 3,
        bit,
        edge,
        raises,
    };
    let hardware = |module, channel| Raises::Hardware { module, channel };
    for (cpu_name, obs, inputs, modules) in [
        (
            "speed7",
            vec![40, 85],
            vec![
                tied(0, Edge::Both, hardware(1, 0)),
                tied(1, Edge::Rising, hardware(1, 1)),
                tied(1, Edge::Falling, hardware(3, 0)),
            ],
            vec![(1, 40), (3, 41)],
        ),
        (
            "s5-115u-944",
            vec![2, 3],
            vec![
                tied(0, Edge::Both, Raises::Ob(2)),
                tied(1, Edge::Falling, Raises::Ob(3)),
            ],
            Vec::new(),
        ),
    ] {
        let source = obs
            .iter()
            .fold(CYCLIC.to_string(), |text, &ob| text + &interrupt_ob(ob));
        let mut cpu = machine(&source, cpu_name);
        let events = schedule(1_000, 100 * MS, 7_000, &[input(2, 1), input(2, 2)]);
        cpu.engine = Engine::new(
            cpu.profile,
            EngineConfig {
                points: InterruptPoints::Operation,
                hw_modules: modules,
                interrupt_inputs: inputs,
                ..EngineConfig::default()
            },
            events,
        );
        let count = allocations(
            &mut cpu,
            RunLimit::Duration(2 * MS),
            RunLimit::Duration(100 * MS),
        );
        let stats = total(&cpu);
        assert!(stats.serviced > 1000, "{cpu_name}: {stats:?}");
        assert_eq!(count, 0, "allocations while raising ({cpu_name})");
    }
}
