//! The optimised program (FB bodies specialised for their actual parameters, pairs of ops
//! fused) runs exactly as the ops as compiled, whose formal operands the VM resolves at run
//! time: same image, accumulators, time and operation count, for every sample program, the
//! benchmarks, and FBs that pass parameters on.

use std::sync::Arc;

use awl::compiler::Program;
use awl::frontend;
use awl::profile;
use awl::profile::InterruptPoints;
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Happening, Scheduled};

/// Runs `program` for `cycles` cycles with inputs set, interrupt points `points` and a request
/// for each of its interrupt OBs every 37 µs of the first 5 ms; what the run left behind.
fn run(
    program: Program,
    sources: &awl::source::SourceSet,
    cycles: u64,
    points: InterruptPoints,
) -> String {
    let schedule = (1..=135u64)
        .flat_map(|step| {
            [2u8, 3, 4, 5, 13]
                .into_iter()
                .filter(|ob| program.ob(*ob).is_some())
                .map(move |ob| Scheduled {
                    at_ns: step * 37_000 + u64::from(ob),
                    what: Happening::Interrupt { ob },
                })
        })
        .collect();
    let profile = program.profile;
    let mut cpu = Cpu::new(Arc::new(program), Arc::new(sources.clone()));
    let config = EngineConfig {
        points,
        special_mode: true,
        ..EngineConfig::default()
    };
    cpu.engine = Engine::new(profile, config, schedule);
    for byte in cpu.inputs.iter_mut() {
        *byte = 0b0101_0011;
    }
    let outcome = cpu.run(RunLimit::Cycles(cycles));
    format!(
        "{:?} {:?} clock {} ops {} accus {} {} image {:?}",
        outcome.mode,
        outcome.stop.map(|stop| stop.cause),
        cpu.clock,
        cpu.instructions,
        cpu.level.accu1,
        cpu.level.accu2,
        &cpu.image[..1024],
    )
}

fn assert_same(name: &str, source: &str, cpu: &str, cycles: u64) {
    let built = frontend::build_text(name, source, profile::find(cpu).unwrap());
    assert!(!built.has_errors(), "{name}: {:#?}", built.diagnostics);
    let program = built.compiled.program;
    for points in [InterruptPoints::Block, InterruptPoints::Operation] {
        let optimised = run(program.clone(), &built.sources, cycles, points);
        let unoptimised = run(
            program.clone().unoptimised(),
            &built.sources,
            cycles,
            points,
        );
        assert_eq!(optimised, unoptimised, "{name} {points:?}");
    }
}

#[test]
fn every_sample_program_runs_the_same_optimised() {
    let samples = ["programs", "programs/s7", "programs/bench"]
        .iter()
        .flat_map(|dir| std::fs::read_dir(dir).unwrap());
    for entry in samples {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|ext| ext == "awl") {
            let source = std::fs::read_to_string(&path).unwrap();
            let name = path.display().to_string();
            for cpu in ["sinumerik-840c", "s5-95f", "speed7"] {
                if frontend::build_text(&name, &source, profile::find(cpu).unwrap()).has_errors() {
                    continue;
                }
                assert_same(&name, &source, cpu, 20);
            }
        }
    }
}

#[test]
fn parameters_passed_on_and_of_every_kind_run_the_same_optimised() {
    let source = "
OB 1
      JU FB 1
NAME :OUTER
A    :I 0.0
B    :I 0.1
W    :FW 10
K    :KF +7
BLK  :PB 9
TIM  :T 3
RES  :FW 12
      JU FB 2
NAME :INNER
X    :I 0.4
Y    :Q 5.0
V    :IW 0
      BE

FB 1
NAME :OUTER
DES  :A    I BI
DES  :B    I BI
DES  :W    I W
DES  :K    D KF
DES  :BLK  B
DES  :TIM  T
DES  :RES  Q W
      JU FB 2
NAME :INNER
X    :=A
Y    :Q 4.0
V    :=W
      A  =A
      AN =B
      L  KT 010.1
      SD =TIM
      L  =W
      L  =K
      +F
      T  =RES
      JU =BLK
      BE

FB 2
NAME :INNER
DES  :X    I BI
DES  :Y    Q BI
DES  :V    I W
      A  =X
      =  =Y
      L  =V
      I  1
      T  FW 20
      L  FW 30
M002 :L  KF +1
      +F
      T  FW 30
      A  I 0.1
      ON F 3.3
      O  I 0.4
M003 :AN F 3.1
      =  F 3.2
      L  FW 30
      L  FW 32
      -F
      T  FW 32
      L  FW 30
      L  KF +9
      <F
      JC =M002
      A  F 3.2
      JC =M003
      BE

PB 9
      L  FW 20
      T  FW 22
      BE

OB 3
      L  FW 30
      L  FW 40
      +F
      T  FW 40
      BE
";
    assert_same("passing.awl", source, "sinumerik-840c", 50);
}

#[test]
fn conditional_calls_taken_or_not_and_nesting_to_its_limit_run_the_same_optimised() {
    // `JC` taken and not taken, `JU` of blocks with and without parameters; from the 20th
    // cycle on, PB 4 calls itself until the nesting limit stops the CPU (STUEB).
    let source = "
OB 1
      A  I 0.0
      JC PB 1
      A  I 0.2
      JC PB 2
      JU FB 1
NAME :ADD
IN   :KF +3
      L  FW 10
      L  KF +20
      >=F
      JC PB 4
      BE

PB 1
      L  FW 10
      L  KF +1
      +F
      T  FW 10
      A  I 0.1
      JC SB 1
      BE

PB 2
      S  F 2.0
      BE

SB 1
      L  FW 12
      L  KF +2
      +F
      T  FW 12
      BE

FB 1
NAME :ADD
DES  :IN   D KF
      L  FW 14
      L  =IN
      +F
      T  FW 14
      BE

PB 4
      L  FW 16
      L  KF +1
      +F
      T  FW 16
      JU PB 4
      BE
";
    // `run` sets every input byte to 0101_0011: I 0.0 and I 0.1 are 1, I 0.2 is 0.
    for cpu in ["sinumerik-840c", "s5-95f"] {
        assert_same("conditional_calls.awl", source, cpu, 30);
        let built =
            frontend::build_text("conditional_calls.awl", source, profile::find(cpu).unwrap());
        let outcome = run(
            built.compiled.program,
            &built.sources,
            30,
            InterruptPoints::Block,
        );
        assert!(outcome.contains("Some(Stueb)"), "{cpu}: {outcome}");
    }
}
