//! One test per rule of each seed. Each names its seed and sentence; most read the jsonl trace.

mod common;

use awl::runner::Ran;
use common::*;
use serde_json::Value;

/// A scenario of programs/, traced into a file of this test's own (`tag`).
fn sample(name: &str, tag: &str) -> (Ran, Vec<Value>) {
    let trace =
        std::path::PathBuf::from("target/test-scenarios").join(format!("{name}-{tag}.jsonl"));
    std::fs::create_dir_all("target/test-scenarios").unwrap();
    traced_scenario(
        &std::path::PathBuf::from(format!("programs/{name}.toml")),
        &trace,
    )
}

fn services(events: &[Value]) -> Vec<(u64, String)> {
    of(events, "irq_service")
        .iter()
        .map(|e| {
            (
                e["ob"].as_u64().unwrap(),
                e["point"].as_str().unwrap().to_string(),
            )
        })
        .collect()
}

fn expectations_met(ran: &Ran) {
    assert!(ran.mismatches.is_empty(), "{:?}", ran.mismatches);
}

// ---- seed 000: SINUMERIK 840C PLC, 5.3.1 Normal mode and 5.3.2 Response time ----

/// Seed 000: "In normal mode the cyclically processed program can only be interrupted at the
/// block limits by interrupt-controlled processing."
#[test]
fn seed000_normal_mode_interrupts_only_at_block_limits() {
    let (ran, events) = sample("fig5_2_interrupt", "1");
    expectations_met(&ran);
    assert_eq!(services(&events), [(3, "block_end".to_string())]);
    let service = of(&events, "irq_service")[0];
    let pb3_end = of(&events, "block_end")
        .into_iter()
        .find(|e| e["block"] == "PB 3")
        .unwrap();
    assert_eq!(
        service["t_ns"], pb3_end["t_ns"],
        "serviced exactly at PB 3's block end"
    );
}

/// Seed 000: "Only when a change is made from one block to another - either by calling a new
/// block or by returning to a higher-order block after a block end statement".
#[test]
fn seed000_both_kinds_of_block_change_are_interrupt_points() {
    // OB 1's first op runs from 12.8 us; the request at 13 us comes before the call of PB 3.
    let program = "OB 1\n      L  KF +1\n      L  KF +2\n      +F\n      JU PB 3\n      BE\nPB 3\n      L  KF +1\n      L  KF +2\n      X  F\n      BE\nOB 3\n      ON F 99.0\n      S  F 1.0\n      BE\n";
    let (_, events) = traced(
        "s000_call",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 3\"\n",
    );
    assert_eq!(services(&events), [(3, "block_call".to_string())]);
    let call = time_of(&events, "block_call", "to", "PB 3");
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["t_ns"], call, "taken at the call of PB 3");
    assert_eq!(service["latency_ns"], call - 13_000);
    let (_, events) = traced(
        "s000_end",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"24us\"\ninterrupt = \"OB 3\"\n",
    );
    assert_eq!(services(&events), [(3, "block_end".to_string())]);
    let end = time_of(&events, "block_end", "block", "PB 3");
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["t_ns"], end, "taken at the end of PB 3");
    assert_eq!(service["latency_ns"], end - 24_000);
}

/// The time of the first event of a kind whose `field` is `value`.
fn time_of(events: &[Value], kind: &str, field: &str, value: &str) -> u64 {
    of(events, kind)
        .into_iter()
        .find(|event| event[field] == value)
        .unwrap_or_else(|| panic!("no {kind} with {field} {value}"))["t_ns"]
        .as_u64()
        .unwrap()
}

/// Seed 000: "Organization blocks OB 2 and OB 5 cannot be called up in normal mode. If these
/// blocks are available in the user program ... they are nevertheless not processed."
#[test]
fn seed000_ob2_and_ob5_are_ignored_in_normal_mode_and_run_in_special_mode() {
    let (ran, events) = sample("ob2_ob5_normal", "2");
    expectations_met(&ran);
    let ignored: Vec<u64> = of(&events, "irq_ignored")
        .iter()
        .map(|e| e["ob"].as_u64().unwrap())
        .collect();
    assert_eq!(ignored, [2, 5]);
    assert!(
        of(&events, "irq_ignored")[0]["reason"]
            .as_str()
            .unwrap()
            .contains("normal mode")
    );
    let (ran, events) = sample("ob2_ob5_special", "3");
    expectations_met(&ran);
    assert!(of(&events, "irq_ignored").is_empty());
    let order: Vec<u64> = services(&events).into_iter().map(|(ob, _)| ob).collect();
    assert_eq!(order, [2, 3, 5], "OB 2 > OB 3 > OB 5");
}

/// Seed 000: "The maximum response time between an interrupt occurring and being serviced is
/// therefore, in the worst case, the processing time of the longest block."
#[test]
fn seed000_latency_is_bounded_by_the_longest_block() {
    let (ran, events) = sample("fig5_2_interrupt", "4");
    let service = of(&events, "irq_service")[0];
    let requested = of(&events, "irq_request")[0]["t_ns"].as_u64().unwrap();
    let pb3_end = time_of(&events, "block_end", "block", "PB 3");
    assert_eq!(
        service["latency_ns"],
        pb3_end - requested,
        "the request waits for the end of the block that runs"
    );
    // The longest block is PB 13: the bound is its processing time, from its call to its end.
    let pb13 = time_of(&events, "block_end", "block", "PB 13")
        - time_of(&events, "block_call", "to", "PB 13");
    assert_eq!(ran.cpu.longest_block.ns, pb13);
    assert!(service["latency_ns"].as_u64().unwrap() <= pb13);
    let summary = awl::report::summary(&ran);
    assert!(summary.contains("longest block: PB 13"), "{summary}");
}

/// Seed 000: "If two alarms occur simultaneously, the response time for the interrupt
/// increases for the interrupt with lower priority ... First ... the highest priority. Once
/// [it] has been completed, the [one] with lower priority is then processed."
#[test]
fn seed000_simultaneous_interrupts_by_priority() {
    let (ran, events) = sample("priorities", "5");
    expectations_met(&ran);
    let order: Vec<u64> = services(&events).into_iter().map(|(ob, _)| ob).collect();
    assert_eq!(order, [3, 4]);
    let ob3_end = of(&events, "irq_end")
        .into_iter()
        .find(|e| e["ob"] == 3)
        .unwrap()["t_ns"]
        .as_u64()
        .unwrap();
    let ob4_service = of(&events, "irq_service")
        .into_iter()
        .find(|e| e["ob"] == 4)
        .unwrap()["t_ns"]
        .as_u64()
        .unwrap();
    assert_eq!(ob4_service, ob3_end, "OB 4 waits for OB 3 to finish");
}

/// Seed 000: "If several interrupts occur simultaneously, the interrupt with the lowest
/// priority is only serviced when all higher-priority interrupts have been serviced."
#[test]
fn seed000_lowest_priority_last() {
    let program = "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      BE\nOB 3\n      BE\nOB 4\n      BE\nOB 7\n      BE\n";
    let scenario = "run = { cycles = 1 }\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 7\"\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 4\"\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 3\"\n";
    let (_, events) = traced("s000_lowest", program, scenario);
    let order: Vec<u64> = services(&events).into_iter().map(|(ob, _)| ob).collect();
    assert_eq!(order, [3, 4, 7]);
}

/// Seed 000: "The priorities of an interrupt-controlled processing can be shifted if an
/// interrupt occurs while an interrupt-controlled program is being processed. After
/// completion of the servicing of the higher-priority interrupt, the priorities are
/// reassigned".
#[test]
fn seed000_priorities_are_reassigned_after_an_interrupt_ob() {
    let (ran, events) = sample("nested", "6");
    expectations_met(&ran);
    assert_eq!(
        services(&events),
        [(4, "block_end".to_string()), (3, "block_call".to_string())]
    );
    // While OB 4 runs, OB 6 (lower than OB 4) and OB 3 (higher) arrive: OB 3 interrupts OB 4,
    // OB 4 then finishes, and only then OB 6 runs.
    let program = std::fs::read_to_string("programs/nested.awl").unwrap() + "OB 6\n      BE\n";
    let scenario = "run = { cycles = 1 }\n[[event]]\nat = \"22us\"\ninterrupt = \"OB 4\"\n[[event]]\nat = \"46us\"\ninterrupt = \"OB 6\"\n[[event]]\nat = \"47us\"\ninterrupt = \"OB 3\"\n";
    let (_, events) = traced("s000_reassigned", &program, scenario);
    let order: Vec<u64> = services(&events).into_iter().map(|(ob, _)| ob).collect();
    assert_eq!(order, [4, 3, 6]);
    let ob4_end = of(&events, "irq_end")
        .into_iter()
        .find(|e| e["ob"] == 4)
        .unwrap()["t_ns"]
        .as_u64()
        .unwrap();
    let ob6 = of(&events, "irq_service")
        .into_iter()
        .find(|e| e["ob"] == 6)
        .unwrap()["t_ns"]
        .as_u64()
        .unwrap();
    assert!(ob6 >= ob4_end);
}

/// SPEC §5: on entry the interrupted level's ACCU 1/2, RLO and status are saved and restored;
/// flags are shared.
#[test]
fn interrupted_level_gets_its_accumulators_and_rlo_back() {
    // OB 3 comes during `L KF +22` and runs at the call of PB 1; OB 1 then adds its own ACCUs.
    let program = "OB 1\n      L  KF +11\n      L  KF +22\n      JU PB 1\n      +F\n      T  FW 0\n      BE\nPB 1\n      BE\nOB 3\n      L  KF +99\n      L  KF +98\n      ON I 0.0\n      =  F 6.0\n      BE\n";
    let (ran, events) = traced(
        "context",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 3\"\n[expect]\n\"FW 0\" = 33\n\"F 6.0\" = 1\n",
    );
    expectations_met(&ran);
    assert_eq!(services(&events).len(), 1);
}

/// SPEC §5: each interrupt OB holds at most one pending request; on the 840C a second one is
/// lost.
#[test]
fn second_request_for_a_pending_ob_is_lost() {
    let program = "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      L  KF +1\n      X  F\n      BE\nOB 3\n      BE\n";
    let scenario = "run = { cycles = 1 }\n[[event]]\nat = \"20us\"\ninterrupt = \"OB 3\"\n[[event]]\nat = \"21us\"\ninterrupt = \"OB 3\"\n";
    let (ran, events) = traced("lost", program, scenario);
    assert_eq!(of(&events, "irq_lost").len(), 1);
    let stats = ran.cpu.engine.stats(3);
    assert_eq!((stats.requested, stats.serviced, stats.lost), (2, 1, 1));
}

/// `IA` (disable interrupts) holds requests until `RA`.
#[test]
fn disabled_interrupts_wait_for_enable() {
    let program = "OB 1\n      JU FB 1\nNAME :X\n      BE\nFB 1\nNAME :X\n      IA\n      JU PB 1\n      JU PB 1\n      RA\n      JU PB 2\n      BE\nPB 1\n      L  KF +1\n      BE\nPB 2\n      BE\nOB 3\n      BE\n";
    let (_, events) = traced(
        "disabled",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"25us\"\ninterrupt = \"OB 3\"\n",
    );
    let service = of(&events, "irq_service")[0];
    let pb2 = of(&events, "block_call")
        .into_iter()
        .find(|e| e["to"] == "PB 2")
        .unwrap();
    assert_eq!(service["t_ns"], pb2["t_ns"], "the first point after RA");
}

// ---- seed 002: S5-95F, OB 13 and the interrupt process images ----

/// Seed 002: "When OB13 is called, the signals of the external input modules are read into
/// the interrupt PII ... Before time-controlled program processing an interrupt input data
/// cycle is carried out." And T PY writes "the interrupt PIQ" and "at the same time the
/// normal PIQ".
#[test]
fn seed002_interrupt_pii_is_read_at_ob13_start_and_piq_written() {
    let (ran, events) = sample("ob13_images", "7");
    expectations_met(&ran);
    let inputs = of(&events, "data_cycle")
        .into_iter()
        .filter(|e| e["kind"] == "interrupt_input")
        .count();
    assert_eq!(inputs, 2, "one interrupt input data cycle per OB 13");
}

/// Seed 002: "In OB13 the interrupt PII is read with the load operations L PY x": an input
/// change while OB 13 runs is not seen by L PY in OB 13 (it reads the image taken at its
/// start); outside OB 13 L PY reads the module directly.
#[test]
fn seed002_l_py_in_ob13_reads_the_image_outside_the_module() {
    let program = "OB 1\n      L  PY 0\n      T  FY 60\n      BE\nOB 13\n      L  KF +1\n      L  KF +1\n      X  F\n      L  PY 0\n      T  FY 40\n      BE\n";
    // OB 13 starts at 10 ms; the input changes 100 us later, during its multiplication.
    let scenario = "cpu = \"s5-95f\"\nrun = { for = \"12ms\" }\n[ob13]\ninterval = \"10ms\"\n[[event]]\nat = \"10.35ms\"\nset = { \"IB 0\" = 7 }\n[expect]\n\"FY 40\" = 0\n\"FY 60\" = 7\n";
    let (ran, _) = traced("s002_image", program, scenario);
    expectations_met(&ran);
}

/// Seed 002: "The data transferred into the interrupt PIQ are output to the peripheral
/// modules after OB13 has finished, in an interrupt output data cycle" ... "carried out only
/// if the interrupt PIQ was written".
#[test]
fn seed002_interrupt_output_cycle_only_after_ob13_and_only_if_written() {
    let (_, events) = sample("ob13_images", "8");
    let outputs: Vec<&Value> = of(&events, "data_cycle")
        .into_iter()
        .filter(|e| e["kind"] == "interrupt_output")
        .collect();
    assert_eq!(outputs.len(), 2);
    let ends: Vec<&Value> = of(&events, "irq_end");
    for (output, end) in outputs.iter().zip(&ends) {
        assert!(
            output["t_ns"].as_u64() >= end["t_ns"].as_u64(),
            "after OB 13 has finished"
        );
    }
    let program = "OB 1\n      BE\nOB 13\n      L  PY 0\n      T  FY 40\n      BE\n";
    let (_, events) = traced(
        "s002_not_written",
        program,
        "cpu = \"s5-95f\"\nrun = { for = \"25ms\" }\n[ob13]\ninterval = \"10ms\"\n",
    );
    assert!(
        of(&events, "data_cycle")
            .iter()
            .all(|e| e["kind"] != "interrupt_output")
    );
    assert_eq!(
        of(&events, "data_cycle")
            .iter()
            .filter(|e| e["kind"] == "interrupt_input")
            .count(),
        2
    );
}

/// Seed 002: "The response time of cyclic program processing is extended by the interrupt
/// data cycle time": the cycle in which OB 13 runs is longer by its data cycles.
#[test]
fn seed002_data_cycles_lengthen_the_cycle() {
    let (_, events) = sample("ob13_images", "9");
    // What OB 13 takes: from its service (the interrupt input data cycle starts there) to the
    // end of the interrupt output data cycle after it.
    let services = of(&events, "irq_service");
    let outputs: Vec<&Value> = of(&events, "data_cycle")
        .into_iter()
        .filter(|e| e["kind"] == "interrupt_output")
        .collect();
    assert_eq!(services.len(), 2);
    let spans: Vec<u64> = services
        .iter()
        .zip(&outputs)
        .map(|(service, output)| {
            output["t_ns"].as_u64().unwrap() + output["duration_ns"].as_u64().unwrap()
                - service["t_ns"].as_u64().unwrap()
        })
        .collect();
    assert_eq!(spans[0], spans[1]);
    assert!(
        spans[0] > 2 * 300_000,
        "two data cycles of 0.3 ms and OB 13"
    );
    let mut times: Vec<u64> = of(&events, "cycle_end")
        .iter()
        .map(|e| e["cycle_time_ns"].as_u64().unwrap())
        .collect();
    times.sort_unstable();
    times.dedup();
    assert_eq!(
        times,
        [times[0], times[0] + spans[0]],
        "a cycle with OB 13 is longer by exactly OB 13 and its data cycles"
    );
}

/// Seed 002: "Wake-up error ... (OB13 is called again before it has finished). On a wake-up
/// error the S5-95F goes to STOP."
#[test]
fn seed002_wake_up_error_when_ob13_overruns() {
    let (ran, events) = sample("weck", "10");
    expectations_met(&ran);
    let stop = of(&events, "stop")[0];
    assert_eq!(stop["cause"], "WECK");
    assert_eq!(stop["block"], "FB 13", "OB 13's FB was still running");
}

/// Seed 002: "The same error can occur if OB13 is frequently interrupted by interrupt calls."
#[test]
fn seed002_wake_up_error_when_interrupts_keep_ob13_from_finishing() {
    let program = "OB 1\n      BE\nOB 13\n      JU PB 1\n      JU PB 1\n      JU PB 1\n      BE\nPB 1\n      BE\nOB 3\n      JU FB 3\nNAME :LONG\n      BE\nFB 3\nNAME :LONG\n      L  KF +500\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n";
    let mut scenario =
        String::from("cpu = \"s5-95f\"\nrun = { for = \"40ms\" }\n[ob13]\ninterval = \"10ms\"\n");
    for at in [10.4, 14.6, 18.8] {
        scenario.push_str(&format!(
            "[[event]]\nat = \"{at}ms\"\ninterrupt = \"OB 3\"\n"
        ));
    }
    scenario.push_str("[expect]\nmode = \"STOP\"\nstop_cause = \"WECK\"\n");
    let (ran, events) = traced("s002_interrupted", program, &scenario);
    expectations_met(&ran);
    // Follow the levels: each OB 3 starts while OB 13 is the running level.
    let mut running: Vec<u64> = Vec::new();
    let mut interrupted_ob13 = 0;
    for event in &events {
        match event["ev"].as_str().unwrap() {
            "irq_service" => {
                let ob = event["ob"].as_u64().unwrap();
                if ob == 3 {
                    assert_eq!(running.last(), Some(&13), "OB 3 interrupts OB 13");
                    interrupted_ob13 += 1;
                }
                running.push(ob);
            }
            "irq_end" => assert_eq!(running.pop(), event["ob"].as_u64()),
            _ => {}
        }
    }
    assert!(interrupted_ob13 >= 2);
    assert!(running.contains(&13), "OB 13 had not finished at the STOP");
}

// ---- seed 001: VIPA SPEED7, OB 40/OB 41 hardware interrupts ----

const SPEED7_OBS: &str = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n\
OB 40\n      JU FB 1\nNAME :WORK\n      L  FW 40\n      L  KF +1\n      +F\n      T  FW 40\n      BE\n\
OB 41\n      JU FB 1\nNAME :WORK\n      L  FW 41\n      L  KF +1\n      +F\n      T  FW 41\n      BE\n\
FB 1\nNAME :WORK\n      L  KF +1000\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n\
OB 82\n      L  FW 82\n      L  KF +1\n      +F\n      T  FW 82\n      BE\n";

fn speed7(events: &[(&str, u16, u16, &str)], extra: &str) -> String {
    let mut scenario = format!(
        "cpu = \"speed7\"\nrun = {{ for = \"3ms\" }}\n[[hw_module]]\nmodule = 4\nob = 40\n[[hw_module]]\nmodule = 5\nob = 40\n[[hw_module]]\nmodule = 6\nob = 41\n{extra}"
    );
    for (at, module, channel, active) in events {
        scenario.push_str(&format!("[[event]]\nat = \"{at}\"\nhw_interrupt = {{ module = {module}, channel = {channel}, active_for = \"{active}\" }}\n"));
    }
    scenario
}

/// Seed 001: "If this OB has a higher priority than the currently active priority class, it
/// will be started": OB 41 (17) interrupts OB 40 (16), not the other way round. (The 1 ms
/// event is taken at the cycle boundary at 1.026 ms; OB 40 then runs until 1.077 ms.)
#[test]
fn seed001_ob_starts_only_above_the_active_priority_class() {
    let (_, events) = traced(
        "s001_priority",
        SPEED7_OBS,
        &speed7(&[("1ms", 4, 1, "5us"), ("1.05ms", 6, 1, "5us")], ""),
    );
    let order: Vec<u64> = services(&events).into_iter().map(|(ob, _)| ob).collect();
    assert_eq!(order, [40, 41]);
    let ob41_end = of(&events, "irq_end")
        .into_iter()
        .find(|e| e["ob"] == 41)
        .unwrap()["t_ns"]
        .as_u64();
    let ob40_end = of(&events, "irq_end")
        .into_iter()
        .find(|e| e["ob"] == 40)
        .unwrap()["t_ns"]
        .as_u64();
    assert!(ob41_end < ob40_end, "OB 41 ran inside OB 40");
    let (_, events) = traced(
        "s001_priority_low",
        SPEED7_OBS,
        &speed7(&[("1ms", 6, 1, "5us"), ("1.05ms", 4, 1, "5us")], ""),
    );
    let ob41_end = of(&events, "irq_end")
        .into_iter()
        .find(|e| e["ob"] == 41)
        .unwrap()["t_ns"]
        .as_u64();
    let ob40_service = of(&events, "irq_service")
        .into_iter()
        .find(|e| e["ob"] == 40)
        .unwrap()["t_ns"]
        .as_u64();
    assert!(ob40_service >= ob41_end, "OB 40 waits for OB 41");
}

/// Seed 001: "The channel-specific acknowledgement is sent after this hardware interrupt OB
/// has been executed": a second event on the same channel up to the moment OB 40 ends is
/// lost (the channel is not yet acknowledged), one just after it starts OB 40 again.
#[test]
fn seed001_acknowledgement_after_the_ob() {
    let (_, events) = traced(
        "s001_ack_once",
        SPEED7_OBS,
        &speed7(&[("1ms", 4, 1, "5us")], ""),
    );
    let end = of(&events, "irq_end")[0]["t_ns"].as_u64().unwrap();
    for (at, runs, lost) in [(end - 1, 1, 1), (end, 1, 1), (end + 1, 2, 0)] {
        let second = format!("{at}ns");
        let (ran, events) = traced(
            &format!("s001_ack_{at}"),
            SPEED7_OBS,
            &speed7(
                &[("1ms", 4, 1, "5us"), (second.as_str(), 4, 1, "5us")],
                &format!("[expect]\n\"FW 40\" = {runs}\n\"FW 82\" = {lost}\n"),
            ),
        );
        expectations_met(&ran);
        assert_eq!(
            of(&events, "irq_lost").len(),
            lost as usize,
            "second event at {at}"
        );
    }
}

/// Seed 001: "If the event occurs on the channel that previously triggered the hardware
/// interrupt, then the new interrupt is lost" and "the loss of the hardware interrupt is
/// announced by means of a diagnostic interrupt".
#[test]
fn seed001_same_channel_loss_starts_ob82() {
    let (ran, events) = sample("speed7_lost", "11");
    expectations_met(&ran);
    assert_eq!(of(&events, "irq_lost").len(), 1);
    assert!(services(&events).iter().any(|(ob, _)| *ob == 82));
}

/// Seed 001: "If the event occurs on another channel of the same module ... This interrupt,
/// however, is not lost, but is triggered if just active after the acknowledgement of the
/// currently active hardware interrupt. Else it is lost."
#[test]
fn seed001_other_channel_is_held_until_acknowledgement() {
    let (ran, _) = traced(
        "s001_hold",
        SPEED7_OBS,
        &speed7(
            &[("1ms", 4, 1, "5us"), ("1.05ms", 4, 2, "500us")],
            "[expect]\n\"FW 40\" = 2\n\"FW 82\" = 0\n",
        ),
    );
    expectations_met(&ran);
    let (ran, events) = traced(
        "s001_hold_gone",
        SPEED7_OBS,
        &speed7(
            &[("1ms", 4, 1, "5us"), ("1.05ms", 4, 2, "5us")],
            "[expect]\n\"FW 40\" = 1\n",
        ),
    );
    expectations_met(&ran);
    assert!(
        of(&events, "irq_lost")[0]["reason"]
            .as_str()
            .unwrap()
            .contains("no longer active")
    );
}

/// Seed 001: "If a hardware interrupt is triggered and its OB is currently active due to a
/// hardware interrupt from another module, the new request can be processed only if it is
/// still active after acknowledgement."
#[test]
fn seed001_busy_ob_for_another_module() {
    let (ran, _) = traced(
        "s001_busy",
        SPEED7_OBS,
        &speed7(
            &[("1ms", 4, 1, "5us"), ("1.05ms", 5, 1, "500us")],
            "[expect]\n\"FW 40\" = 2\n",
        ),
    );
    expectations_met(&ran);
    let (ran, events) = traced(
        "s001_busy_gone",
        SPEED7_OBS,
        &speed7(
            &[("1ms", 4, 1, "5us"), ("1.05ms", 5, 1, "5us")],
            "[expect]\n\"FW 40\" = 1\n",
        ),
    );
    expectations_met(&ran);
    assert_eq!(of(&events, "irq_lost").len(), 1);
}

/// Seed 001: "During STARTUP there is no hardware interrupt produced. ... Hardware interrupts
/// during transition to RUN are lost."
#[test]
fn seed001_nothing_in_startup_and_loss_at_the_transition() {
    let program = format!(
        "{SPEED7_OBS}OB 100\n      JU FB 1\nNAME :WORK\n      JU FB 1\nNAME :WORK\n      BE\n"
    );
    // OB 100 runs about 100 us; one event ends during STARTUP, one is still active at RUN.
    let (ran, events) = traced(
        "s001_startup",
        &program,
        &speed7(
            &[("10us", 4, 1, "5us"), ("20us", 4, 2, "1ms")],
            "[expect]\n\"FW 40\" = 0\n",
        ),
    );
    expectations_met(&ran);
    // The event inside STARTUP is no request: a module event with the reason.
    let module_events = of(&events, "module_event");
    assert_eq!(module_events.len(), 1);
    assert!(
        module_events[0]["reason"]
            .as_str()
            .unwrap()
            .contains("STARTUP")
    );
    assert!(of(&events, "irq_ignored").is_empty());
    assert_eq!(of(&events, "irq_lost").len(), 1);
    assert!(services(&events).is_empty());
    let stats = ran.cpu.engine.stats(40);
    assert_eq!((stats.requested, stats.lost), (1, 1));
}

/// Seed 001: "If a hardware interrupt is generated for which there is no hardware interrupt
/// OB in the user program, OB 85 is called by the operating system. The hardware interrupt is
/// acknowledged. If OB 85 has not been programmed, the CPU goes to STOP".
#[test]
fn seed001_missing_ob_calls_ob85_and_without_ob85_stops() {
    let (ran, events) = sample("speed7_ob85", "12");
    expectations_met(&ran);
    assert_eq!(
        services(&events).iter().filter(|(ob, _)| *ob == 85).count(),
        2,
        "acknowledged: the second event is not lost"
    );
    let (ran, events) = sample("speed7_stop", "13");
    expectations_met(&ran);
    assert_eq!(of(&events, "stop")[0]["cause"], "OB85");
}

/// Seed 000: "An interrupt is only serviced on a block change, i.e. when a block is called or
/// terminated": OB 3 runs at the cycle boundary; OB 2 (higher) comes while OB 3 runs without
/// a block change, so it waits for OB 3's block end and runs after OB 3 has ended.
#[test]
fn seed000_a_higher_request_during_an_interrupt_ob_waits_for_its_end() {
    let program = "OB 1\n      BE\nOB 3\n      L  KF +1\n      L  KF +2\n      X  F\n      X  F\n      X  F\n      BE\nOB 2\n      L  KF +9\n      BE\n";
    let scenario = |events: &str| {
        format!(
            "mode = \"special\"\nrun = {{ cycles = 2 }}\n[[event]]\nat = \"100us\"\ninterrupt = \"OB 3\"\n{events}"
        )
    };
    let (_, events) = traced("s000_during_ob3_dry", program, &scenario(""));
    let start = of(&events, "irq_service")[0]["t_ns"].as_u64().unwrap();
    let end = of(&events, "irq_end")[0]["t_ns"].as_u64().unwrap();
    let at = start + (end - start) / 2;
    let (_, events) = traced(
        "s000_during_ob3",
        program,
        &scenario(&format!(
            "[[event]]\nat = \"{at}ns\"\ninterrupt = \"OB 2\"\n"
        )),
    );
    let order: Vec<(String, u64)> = events
        .iter()
        .filter(|e| e["ev"] == "irq_service" || e["ev"] == "irq_end")
        .map(|e| {
            (
                e["ev"].as_str().unwrap().to_string(),
                e["ob"].as_u64().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        order,
        [
            ("irq_service".to_string(), 3),
            ("irq_end".to_string(), 3),
            ("irq_service".to_string(), 2),
            ("irq_end".to_string(), 2)
        ]
    );
    let ob2 = of(&events, "irq_service")[1];
    assert_eq!(ob2["latency_ns"].as_u64().unwrap(), end - at);
}

/// The nesting limit counts an interrupt OB's own blocks (840C: 32 a level): OB 3, entered at
/// OB 1's call of PB 1, may nest 31 blocks below itself; one more is STOP STUEB.
#[test]
fn nesting_depth_counts_from_the_interrupt_obs_level() {
    let chain = |last: u8| {
        let mut text = String::from(
            "OB 1\n      JU PB 1\n      BE\nPB 1\n      BE\nOB 3\n      JU PB 10\n      BE\n",
        );
        for pb in 10..last {
            text.push_str(&format!("PB {pb}\n      JU PB {}\n      BE\n", pb + 1));
        }
        text + &format!("PB {last}\n      BE\n")
    };
    let scenario = "run = { cycles = 1 }\n[[event]]\nat = \"0ms\"\ninterrupt = \"OB 3\"\n";
    let (ran, events) = traced("nesting_ok", &chain(40), scenario);
    assert!(ran.outcome.stop.is_none(), "{:?}", ran.outcome.stop);
    let deepest = of(&events, "block_call")
        .iter()
        .map(|e| e["depth"].as_u64().unwrap())
        .max();
    assert_eq!(
        deepest,
        Some(32),
        "OB 3 is depth 1 of its level, PB 40 depth 32"
    );
    let (ran, _) = traced("nesting_stueb", &chain(41), scenario);
    let stop = ran.outcome.stop.expect("STOP");
    assert_eq!(stop.cause.code(), "STUEB");
    assert_eq!(stop.stack[0].block, "PB 40");
}

/// Seed 002: the interrupt output data cycle outputs what OB 13 wrote into the interrupt PIQ:
/// both bytes of a word, and nothing it did not write.
#[test]
fn seed002_interrupt_output_cycle_writes_the_bytes_ob13_wrote() {
    let program = "OB 1\n      BE\nOB 13\n      L  KH 1234\n      T  PW 2\n      BE\n";
    let scenario = "cpu = \"s5-95f\"\nrun = { for = \"12ms\" }\n[ob13]\ninterval = \"10ms\"\n[expect]\n\"PW 2\" = 4660\n\"PY 1\" = 0\n\"PY 4\" = 0\n";
    let (ran, _) = traced("s002_word", program, scenario);
    expectations_met(&ran);
}

/// Seed 002: what OB 13 transferred reaches the modules in the interrupt output data cycle
/// right after OB 13, "before 'normal' program processing resumes": a digital byte there and
/// not only at the cycle's PIQ write (T PY wrote the normal PIQ too), and a byte beyond the
/// process image, which only that data cycle outputs, at all.
#[test]
fn seed002_what_ob13_wrote_reaches_the_modules_right_after_ob13() {
    let program = "OB 1\n      BE\nOB 13\n      L  KH 0081\n      T  PY 1\n      L  KB 77\n      T  PY 130\n      BE\n";
    let scenario = "cpu = \"s5-95f\"\nrun = { for = \"12ms\" }\n[ob13]\ninterval = \"10ms\"\n[expect]\n\"PY 130\" = 77\n";
    let (ran, events) = traced("s002_output_cycle", program, scenario);
    expectations_met(&ran);
    let end = of(&events, "irq_end")[0]["t_ns"].as_u64().unwrap();
    let outputs_at_end: Vec<&str> = of(&events, "output")
        .into_iter()
        .filter(|e| e["t_ns"].as_u64() == Some(end))
        .map(|e| e["operand"].as_str().unwrap())
        .collect();
    assert_eq!(
        outputs_at_end,
        ["Q 1.0", "Q 1.7", "PY 130"],
        "at OB 13's end"
    );
    let cycle = of(&events, "data_cycle")
        .into_iter()
        .find(|e| e["kind"] == "interrupt_output")
        .unwrap();
    assert_eq!(cycle["t_ns"].as_u64(), Some(end));
}

/// A request noticed inside a loop (block points: not an interrupt point) is serviced at the
/// next block change, the loop's block end, not later.
#[test]
fn seed000_a_request_noticed_in_a_loop_waits_only_for_the_next_block_change() {
    let program = "OB 1\n      JU FB 1\nNAME :LOOP\n      JU PB 2\n      BE\nFB 1\nNAME :LOOP\n      L  KF +100\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\nPB 2\n      BE\nOB 3\n      BE\n";
    let (_, events) = traced(
        "loop_request",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"100us\"\ninterrupt = \"OB 3\"\n",
    );
    let end = time_of(&events, "block_end", "block", "FB 1");
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["t_ns"], end);
    assert_eq!(service["point"], "block_end");
}

/// Seed 002: OB 13 due while its interrupt output data cycle still runs is the wake-up error
/// (OB 13 "called again before OB 13 processing is completed"); and without OB 13 nothing is
/// requested at all ("cyclical program processing continues").
#[test]
fn seed002_wake_up_error_inside_the_output_data_cycle_and_no_ob13() {
    // OB 1 loops for a while; with operation points OB 13 starts right when it is due. A dry
    // run measures OB 13 from its due time to the end of its output data cycle (about
    // 0.64 ms); an interval 0.15 ms shorter falls due inside that output data cycle.
    let program = "OB 1\n      JU FB 1\nNAME :LOOP\n      BE\nFB 1\nNAME :LOOP\n      L  KF +2000\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\nOB 13\n      L  KH 1234\n      T  PW 2\n      BE\n";
    let scenario = |interval: u64| {
        format!(
            "cpu = \"s5-95f\"\ninterrupt_points = \"operation\"\nrun = {{ cycles = 1 }}\nwatchdog = \"1s\"\n[ob13]\ninterval = \"{interval}ns\"\n"
        )
    };
    let (_, events) = traced("s002_weck_output_dry", program, &scenario(5_000_000));
    let output = of(&events, "data_cycle")
        .into_iter()
        .find(|e| e["kind"] == "interrupt_output")
        .unwrap();
    let done = output["t_ns"].as_u64().unwrap() + output["duration_ns"].as_u64().unwrap();
    let interval = done - 5_000_000 - 150_000;
    let (ran, events) = traced("s002_weck_output", program, &scenario(interval));
    assert_eq!(
        ran.outcome.stop.as_ref().map(|s| s.cause.code()),
        Some("WECK")
    );
    assert_eq!(of(&events, "irq_service").len(), 1, "the first OB 13 ran");
    let (ran, _) = traced(
        "s002_no_ob13",
        "OB 1\n      BE\n",
        "cpu = \"s5-95f\"\nrun = { for = \"30ms\" }\n[ob13]\ninterval = \"10ms\"\n[expect]\nmode = \"RUN\"\n",
    );
    expectations_met(&ran);
    assert_eq!(ran.cpu.engine.stats(13).requested, 0);
}

/// An OB does not interrupt itself: a second OB 3 request made while OB 3 runs waits for its
/// end, even across OB 3's block changes.
#[test]
fn an_ob_is_not_interrupted_by_its_own_request() {
    let program = "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      X  F\n      BE\nOB 3\n      L  KF +1\n      X  F\n      JU PB 2\n      JU PB 2\n      BE\nPB 2\n      BE\n";
    let scenario = "run = { cycles = 1 }\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 3\"\n[[event]]\nat = \"22us\"\ninterrupt = \"OB 3\"\n";
    let (_, events) = traced("own_request", program, scenario);
    let order: Vec<String> = events
        .iter()
        .filter(|e| e["ev"] == "irq_service" || e["ev"] == "irq_end")
        .map(|e| format!("{} {}", e["ev"].as_str().unwrap(), e["id"]))
        .collect();
    assert_eq!(
        order,
        ["irq_service 1", "irq_end 1", "irq_service 2", "irq_end 2"]
    );
}

/// With operation points the service names the block whose operation it followed.
#[test]
fn operation_point_services_name_the_interrupted_block() {
    let (_, events) = sample("fig5_2_operation", "op_block");
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["point"], "operation");
    assert_eq!(service["block"], "PB 3");
}

/// Seed 001: a held event that is no longer active at the acknowledgement is lost and counted
/// so.
#[test]
fn seed001_a_held_event_gone_at_the_acknowledgement_is_counted_lost() {
    let (ran, _) = traced(
        "s001_hold_count",
        SPEED7_OBS,
        &speed7(&[("1ms", 4, 1, "5us"), ("1.05ms", 4, 2, "5us")], ""),
    );
    let stats = ran.cpu.engine.stats(40);
    assert_eq!((stats.requested, stats.serviced, stats.lost), (2, 1, 1));
}

/// Seed 001: STARTUP ends and RUN begins at one instant: an event at that instant is in RUN
/// and starts its OB; one a nanosecond earlier that is still active then is lost at the
/// transition; one that ended by then was in STARTUP and produced no request at all.
#[test]
fn seed001_the_transition_to_run_is_an_instant() {
    let program = format!("{SPEED7_OBS}OB 100\n      L  KF +1\n      BE\n");
    let (_, events) = traced("s001_startup_len", &program, &speed7(&[], ""));
    let run = of(&events, "mode")
        .into_iter()
        .find(|e| e["to"] == "RUN")
        .unwrap()["t_ns"]
        .as_u64()
        .unwrap();
    assert!(run > 0);
    for (at, active, requested, serviced, lost) in [
        (run, 5, 1, 1, 0),
        (run - 1, 5, 1, 0, 1),
        (run - 2, 1, 0, 0, 0),
        (run - 2, 2, 0, 0, 0),
    ] {
        let (ran, _) = traced(
            &format!("s001_transition_{at}_{active}"),
            &program,
            &speed7(&[(&format!("{at}ns"), 4, 1, &format!("{active}ns"))], ""),
        );
        let stats = ran.cpu.engine.stats(40);
        assert_eq!(
            (stats.requested, stats.serviced, stats.lost),
            (requested, serviced, lost),
            "event at {at} ns active {active} ns, RUN at {run} ns"
        );
    }
}

/// The S5-135U calls the time-controlled OBs the program has at their intervals from the start
/// of RUN (OB 10 every 10 ms, OB 13 every 100 ms); OB 11, which the program lacks, is never
/// requested; a process interrupt OB still runs only on request.
#[test]
fn s5_time_controlled_obs_are_called_at_their_intervals() {
    let program = "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      BE\nOB 10\n      L  FW 2\n      L  KF +1\n      +F\n      T  FW 2\n      BE\nOB 13\n      BE\nOB 2\n      BE\n";
    let scenario = "cpu = \"s5-135u\"\nrun = { for = \"1s\" }\n[expect]\nmode = \"RUN\"\n";
    let (ran, events) = traced("s5_timed", program, scenario);
    expectations_met(&ran);
    let requested = |ob| ran.cpu.engine.stats(ob).requested;
    assert_eq!((requested(10), requested(13)), (100, 10));
    assert_eq!((requested(11), requested(2)), (0, 0));
    assert_eq!(fw(&ran.cpu, 2), 100);
    let first_ob10 = of(&events, "irq_request")
        .into_iter()
        .find(|event| event["ob"] == 10)
        .expect("OB 10 requested")["t_ns"]
        .as_u64();
    assert_eq!(first_ob10, Some(10_000_000), "10 ms after RUN began");
}
