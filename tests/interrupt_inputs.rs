//! Interrupts raised by input changes (`[[interrupt_input]]`): an input bit's edge requests an
//! S5 CPU's interrupt OB or raises a SPEED7 module channel's hardware interrupt, whatever
//! changed the input; the other edge raises nothing.

mod common;

use std::sync::Arc;

use awl::frontend;
use awl::profile;
use awl::runner::NotRun;
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::inputs::{Edge, InterruptInput, Raises};
use awl::vm::interrupts::{Engine, EngineConfig, InputChange, InputTarget};
use common::{of, traced};

/// OB 2 counts its runs in FW 20.
const S5_PROGRAM: &str = "OB 1\n      L  FW 10\n      T  FW 10\n      BE\n\
                          OB 2\n      L  FW 20\n      L  KF +1\n      +F\n      T  FW 20\n      BE\n";

/// OB 40 counts its runs in MW 20.
const S7_PROGRAM: &str = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L MW 10;\n      T MW 10;\n\
                          END_ORGANIZATION_BLOCK\n\
                          ORGANIZATION_BLOCK OB 40\nBEGIN\n      L MW 20;\n      L 1;\n      +I;\n\
                          T MW 20;\nEND_ORGANIZATION_BLOCK\n";

/// I 8.0 goes 1 at 1 ms, 0 at 2 ms, 1 at 3 ms (written `input` in the program's notation).
fn pulses(input: &str) -> String {
    [("1ms", 1), ("2ms", 0), ("3ms", 1)]
        .iter()
        .map(|(at, value)| format!("[[event]]\nat = \"{at}\"\nset = {{ \"{input}\" = {value} }}\n"))
        .collect()
}

/// The times of the requests for `ob` in the trace, in ms.
fn requests(events: &[serde_json::Value], ob: u64) -> Vec<f64> {
    of(events, "irq_request")
        .iter()
        .filter(|event| event["ob"] == ob)
        .map(|event| event["t_ns"].as_u64().unwrap() as f64 / 1e6)
        .collect()
}

fn s5_run(name: &str, edge: &str) -> (awl::runner::Ran, Vec<serde_json::Value>) {
    let scenario = format!(
        "cpu = \"s5-115u-944\"\nrun = {{ for = \"5ms\" }}\n\
         [[interrupt_input]]\ninput = \"I 8.0\"\n{edge}ob = 2\n{}",
        pulses("I 8.0")
    );
    traced(name, S5_PROGRAM, &scenario)
}

#[test]
fn a_rising_edge_requests_the_s5_interrupt_ob_and_the_falling_one_does_not() {
    // Rising is the default edge.
    let (ran, events) = s5_run("interrupt_input_s5_rising", "");
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    assert_eq!(requests(&events, 2), [1.0, 3.0]);
    assert_eq!(of(&events, "irq_service").len(), 2);
    let (_, events) = s5_run("interrupt_input_s5_rising_named", "edge = \"rising\"\n");
    assert_eq!(requests(&events, 2), [1.0, 3.0]);
}

#[test]
fn a_falling_edge_requests_the_ob_on_the_change_to_0_only() {
    let (_, events) = s5_run("interrupt_input_s5_falling", "edge = \"falling\"\n");
    assert_eq!(requests(&events, 2), [2.0]);
}

#[test]
fn both_edges_request_the_ob_on_every_change() {
    let (_, events) = s5_run("interrupt_input_s5_both", "edge = \"both\"\n");
    assert_eq!(requests(&events, 2), [1.0, 2.0, 3.0]);
}

#[test]
fn the_ob_runs_and_a_byte_write_counts_as_well() {
    let scenario = "cpu = \"s5-115u-944\"\nrun = { for = \"5ms\" }\n\
         [[interrupt_input]]\ninput = \"I 8.3\"\nob = 2\n\
         [[event]]\nat = \"1ms\"\nset = { \"IB 8\" = 8 }\n\
         [[event]]\nat = \"2ms\"\nset = { \"IB 8\" = 9 }\n\
         [expect]\n\"FW 20\" = 1\n";
    let (ran, events) = traced("interrupt_input_s5_byte", S5_PROGRAM, scenario);
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    assert_eq!(requests(&events, 2), [1.0]);
}

fn speed7_run(name: &str, edge: &str) -> (awl::runner::Ran, Vec<serde_json::Value>) {
    let scenario = format!(
        "cpu = \"speed7\"\nrun = {{ for = \"5ms\" }}\n\
         [[hw_module]]\nmodule = 4\nob = 40\n\
         [[interrupt_input]]\ninput = \"E 8.0\"\n{edge}module = 4\nchannel = 2\n{}",
        pulses("E 8.0")
    );
    traced(name, S7_PROGRAM, &scenario)
}

#[test]
fn an_input_s_edge_raises_the_speed7_hardware_interrupt_of_its_channel() {
    let (ran, events) = speed7_run("interrupt_input_speed7_rising", "");
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    assert_eq!(requests(&events, 40), [1.0, 3.0]);
    for request in of(&events, "irq_request") {
        assert_eq!(request["module"], 4, "{request}");
        assert_eq!(request["channel"], 2, "{request}");
    }
    assert_eq!(of(&events, "irq_service").len(), 2);
    let (_, events) = speed7_run("interrupt_input_speed7_falling", "edge = \"falling\"\n");
    assert_eq!(requests(&events, 40), [2.0]);
    let (_, events) = speed7_run("interrupt_input_speed7_both", "edge = \"both\"\n");
    assert_eq!(requests(&events, 40), [1.0, 2.0, 3.0]);
}

#[test]
fn a_held_speed7_event_is_lost_when_its_input_changed_back_before_the_acknowledgement() {
    // Channel 0's event keeps the module busy until OB 40 has run; channel 2's input rises
    // meanwhile (held) and falls again before the acknowledgement: no longer active, lost.
    let scenario = "cpu = \"speed7\"\nrun = { for = \"3ms\" }\ninterrupt_points = \"block\"\n\
         [[hw_module]]\nmodule = 4\nob = 40\n\
         [[interrupt_input]]\ninput = \"E 8.0\"\nmodule = 4\nchannel = 0\n\
         [[interrupt_input]]\ninput = \"E 8.2\"\nmodule = 4\nchannel = 2\n\
         [[event]]\nat = \"1ms\"\nset = { \"E 8.0\" = 1 }\n\
         [[event]]\nat = \"1.000001ms\"\nset = { \"E 8.2\" = 1 }\n\
         [[event]]\nat = \"1.000002ms\"\nset = { \"E 8.2\" = 0 }\n\
         [expect]\n\"MW 20\" = 1\n";
    let (ran, events) = traced("interrupt_input_speed7_held", S7_PROGRAM, scenario);
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    let lost = of(&events, "irq_lost");
    assert_eq!(lost.len(), 1, "{lost:?}");
    assert!(
        lost[0]["reason"]
            .as_str()
            .unwrap()
            .contains("no longer active"),
        "{}",
        lost[0]
    );
}

/// Every error of a scenario with `table` as its `[[interrupt_input]]`, rendered.
fn errors(cpu: &str, program: &str, table: &str) -> String {
    let scenario = format!(
        "cpu = \"{cpu}\"\nrun = {{ cycles = 1 }}\n[[hw_module]]\nmodule = 4\nob = 40\n\
         [[interrupt_input]]\n{table}"
    );
    let scenario = if cpu == "speed7" {
        scenario
    } else {
        scenario.replace("[[hw_module]]\nmodule = 4\nob = 40\n", "")
    };
    match common::run_scenario("interrupt_input_errors", program, &scenario) {
        Err(NotRun::Failed(reports)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        Err(NotRun::SourceErrors(..) | NotRun::Usage(_)) => panic!("not a scenario error"),
        Ok(_) => panic!("{table}: the scenario ran"),
    }
}

#[test]
fn each_key_s_error_is_told_at_its_place() {
    let s5 = |table: &str| errors("s5-115u-944", S5_PROGRAM, table);
    let s7 = |table: &str| errors("speed7", S7_PROGRAM, table);
    for (text, says) in [
        (
            s5("input = \"I 8.0\"\nob = 2\nedg = \"rising\"\n"),
            "did you mean `edge`?",
        ),
        (
            s5("input = \"I 8.0\"\nob = \"OB 2\"\n"),
            "`ob` in [[interrupt_input]] takes",
        ),
        (
            s5("input = 8\nob = 2\n"),
            "`input` in [[interrupt_input]] takes an input bit",
        ),
        (s5("ob = 2\n"), "[[interrupt_input]] has no `input`"),
        (s5("input = \"Q 4.0\"\nob = 2\n"), "not an input bit"),
        (s5("input = \"IW 8\"\nob = 2\n"), "not an input bit"),
        (
            s5("input = \"I 8.0\"\nob = 2\nedge = \"up\"\n"),
            "unknown edge `up`",
        ),
        (
            s5("input = \"I 8.0\"\nob = 9\n"),
            "unknown OB `OB 9` for the s5-115u-944 CPU",
        ),
        (
            s5("input = \"I 8.0\"\nmodule = 4\nchannel = 0\n"),
            "`module` in [[interrupt_input]] belongs to the speed7 profile",
        ),
        (
            s7("input = \"E 8.0\"\nob = 40\n"),
            "give `module` and `channel`",
        ),
        (
            s7("input = \"E 8.0\"\nmodule = 5\nchannel = 0\n"),
            "module 5 has no [[hw_module]] entry",
        ),
        (
            s7("input = \"E 8.0\"\nob = 40\nmodule = 4\nchannel = 0\n"),
            "not both",
        ),
        (s7("input = \"E 8.0\"\n"), "has no `ob` and no `module`"),
        (
            s7("input = \"E 8.0\"\nmodule = 4\n"),
            "`module` needs `channel`",
        ),
    ] {
        assert!(text.contains(says), "`{says}` in {text}");
    }
}

/// A CPU running `source` on `cpu` with `config`, as a server drives it: slices of cycles, input
/// writes between them.
fn machine(source: &str, cpu: &str, config: EngineConfig) -> Cpu {
    let profile = profile::find(cpu).unwrap();
    let built = frontend::build_text("p.awl", source, profile);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let mut machine = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    machine.engine = Engine::new(profile, config, Vec::new());
    machine
}

fn i_8_0(value: u32) -> InputChange {
    InputChange {
        target: InputTarget::Process,
        byte: 8,
        bit: 0,
        bytes: 0,
        value,
    }
}

#[test]
fn an_input_written_between_runs_raises_its_interrupt_in_the_next_one() {
    let config = EngineConfig {
        interrupt_inputs: vec![InterruptInput {
            byte: 8,
            bit: 0,
            edge: Edge::Falling,
            raises: Raises::Ob(2),
        }],
        ..EngineConfig::default()
    };
    let mut cpu = machine(S5_PROGRAM, "s5-115u-944", config);
    assert!(cpu.run(RunLimit::Cycles(1)).stop.is_none());
    cpu.deliver_inputs(i_8_0(1));
    assert!(cpu.run(RunLimit::Cycles(2)).stop.is_none());
    assert_eq!(cpu.engine.stats(2).requested, 0, "a rising edge");
    cpu.deliver_inputs(i_8_0(0));
    assert!(cpu.run(RunLimit::Cycles(3)).stop.is_none());
    assert_eq!(cpu.engine.stats(2).serviced, 1);
}

#[test]
fn a_stop_an_input_write_brings_comes_at_the_next_interrupt_point() {
    // Module 4 starts OB 40, which the program lacks, and there is no OB 85: STOP `OB85`.
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L MW 10;\n      T MW 10;\n\
                   END_ORGANIZATION_BLOCK\n";
    let config = EngineConfig {
        hw_modules: vec![(4, 40)],
        interrupt_inputs: vec![InterruptInput {
            byte: 8,
            bit: 0,
            edge: Edge::Rising,
            raises: Raises::Hardware {
                module: 4,
                channel: 0,
            },
        }],
        ..EngineConfig::default()
    };
    let mut cpu = machine(program, "speed7", config);
    assert!(cpu.run(RunLimit::Cycles(1)).stop.is_none());
    cpu.deliver_inputs(i_8_0(1));
    let outcome = cpu.run(RunLimit::Cycles(5));
    let stop = outcome.stop.expect("STOP OB85");
    assert_eq!(stop.cause.code(), "OB85");
    assert_eq!(outcome.cycles, 2, "stopped in the cycle after the write");
}
