//! The SPEED7 samples of programs/s7/, STEP 7 programs as their users write them, keep every
//! rule of the VIPA SPEED7 operation list for hardware interrupts (OB 40/OB 41: "Function",
//! "Behavior on error", "Diagnostic interrupt"); each test names its rule and reads the trace.

mod common;

use awl::runner::Ran;
use common::{of, traced_scenario};
use serde_json::Value;

fn sample(name: &str) -> (Ran, Vec<Value>) {
    std::fs::create_dir_all("target/test-scenarios").unwrap();
    // A file per test thread: tests running at once read the same sample's trace.
    let thread = format!("{:?}", std::thread::current().id());
    let thread: String = thread.chars().filter(char::is_ascii_digit).collect();
    let trace = std::path::PathBuf::from("target/test-scenarios")
        .join(format!("s7-{name}-speed7_samples-{thread}.jsonl"));
    let (ran, events) = traced_scenario(
        &std::path::PathBuf::from(format!("programs/s7/{name}.toml")),
        &trace,
    );
    assert!(ran.mismatches.is_empty(), "{name}: {:?}", ran.mismatches);
    assert!(ran.expectations > 0, "{name}");
    (ran, events)
}

fn t(event: &Value) -> u64 {
    event["t_ns"].as_u64().unwrap()
}

/// The request a module's channel made at `at_ns`.
fn request(events: &[Value], module: u64, channel: u64, at_ns: u64) -> u64 {
    of(events, "irq_request")
        .into_iter()
        .find(|e| e["module"] == module && e["channel"] == channel && t(e) == at_ns)
        .unwrap_or_else(|| panic!("no request of module {module} channel {channel} at {at_ns}"))
        ["id"]
        .as_u64()
        .unwrap()
}

/// The event of `kind` for request `id`.
fn of_request<'a>(events: &'a [Value], kind: &str, id: u64) -> Option<&'a Value> {
    of(events, kind).into_iter().find(|e| e["id"] == id)
}

fn reason(events: &[Value], id: u64) -> String {
    of_request(events, "irq_lost", id).unwrap_or_else(|| panic!("request {id} is not lost"))
        ["reason"]
        .as_str()
        .unwrap()
        .to_string()
}

/// "If this OB has a higher priority than the currently active priority class, it will be
/// started": OB 41 (17) starts inside OB 40 (16), after an operation of OB 40; a second OB 40
/// request (module 4 channel 1) does not start inside OB 40, it waits for OB 40's end.
#[test]
fn an_ob_starts_only_above_the_active_priority_class() {
    let (_, events) = sample("speed7_lines");
    let first = request(&events, 4, 0, 1_000_000);
    let ob40_start = t(of_request(&events, "irq_service", first).unwrap());
    let ob40_end = t(of_request(&events, "irq_end", first).unwrap());
    let ob41 = of_request(&events, "irq_service", request(&events, 6, 0, 1_010_000)).unwrap();
    assert_eq!(ob41["point"], "operation");
    assert_eq!(ob41["block"], "OB 40");
    assert!(ob40_start < t(ob41) && t(ob41) < ob40_end);
    let line2 = request(&events, 4, 1, 1_020_000);
    assert_eq!(
        t(of_request(&events, "irq_service", line2).unwrap()),
        ob40_end
    );
}

/// "The channel-specific acknowledgement is sent after this hardware interrupt OB has been
/// executed": channel 0 loses an event while its OB 40 runs and starts OB 40 again once it
/// has been acknowledged.
#[test]
fn the_channel_is_acknowledged_after_its_ob() {
    let (_, events) = sample("speed7_lines");
    let bounce = request(&events, 4, 0, 1_015_000);
    assert!(reason(&events, bounce).contains("same channel"));
    let later = request(&events, 4, 0, 2_000_000);
    assert!(of_request(&events, "irq_service", later).is_some());
}

/// "If the event occurs on the channel that previously triggered the hardware interrupt, then
/// the new interrupt is lost" and "the loss of the hardware interrupt is announced by means of
/// a diagnostic interrupt": OB 82 runs at once (priority 26, inside OB 40) and its start
/// information names the module (MW 38 = 8, checked by the scenario).
#[test]
fn a_loss_on_the_same_channel_starts_ob82() {
    let (ran, events) = sample("speed7_lines");
    let bounce = request(&events, 4, 0, 1_015_000);
    let lost = of_request(&events, "irq_lost", bounce).unwrap();
    let ob82 = of(&events, "irq_request")
        .into_iter()
        .find(|e| e["ob"] == 82)
        .unwrap();
    assert_eq!(t(ob82), t(lost));
    let service = of_request(&events, "irq_service", ob82["id"].as_u64().unwrap()).unwrap();
    assert_eq!(service["block"], "OB 40");
    assert_eq!(ran.cpu.engine.stats(82).serviced, 1);
}

/// "If the event occurs on another channel of the same module ... This interrupt, however, is
/// not lost, but is triggered if just active after the acknowledgement of the currently active
/// hardware interrupt. Else it is lost." Neither kind of loss is announced by OB 82.
#[test]
fn another_channel_is_held_and_triggered_only_if_still_active() {
    let (_, events) = sample("speed7_lines");
    let held = request(&events, 4, 1, 1_020_000);
    assert!(of_request(&events, "irq_service", held).is_some());
    assert!(of_request(&events, "irq_lost", held).is_none());
    let (_, events) = sample("speed7_lines_modules");
    let glitch = request(&events, 4, 1, 2_035_000);
    assert!(reason(&events, glitch).contains("no longer active"));
    assert!(!of(&events, "irq_request").iter().any(|e| e["ob"] == 82));
}

/// "If a hardware interrupt is triggered and its OB is currently active due to a hardware
/// interrupt from another module, the new request can be processed only if it is still active
/// after acknowledgement."
#[test]
fn a_busy_ob_takes_another_module_only_if_still_active() {
    let (_, events) = sample("speed7_lines_modules");
    let first = request(&events, 4, 0, 1_000_000);
    let cap = request(&events, 5, 0, 1_010_000);
    assert_eq!(
        t(of_request(&events, "irq_service", cap).unwrap()),
        t(of_request(&events, "irq_end", first).unwrap())
    );
    let short = request(&events, 5, 0, 2_030_000);
    assert!(reason(&events, short).contains("no longer active"));
}

/// "During STARTUP there is no hardware interrupt produced. ... Hardware interrupts during
/// transition to RUN are lost."
#[test]
fn nothing_in_startup_and_a_loss_at_the_transition_to_run() {
    let (_, events) = sample("speed7_lines_modules");
    let run = t(of(&events, "mode")
        .into_iter()
        .find(|e| e["to"] == "RUN")
        .unwrap());
    let module_events = of(&events, "module_event");
    assert_eq!(module_events.len(), 1);
    assert!(t(module_events[0]) < run);
    assert!(
        module_events[0]["reason"]
            .as_str()
            .unwrap()
            .contains("STARTUP")
    );
    let still_active = request(&events, 4, 1, 20_000);
    assert!(reason(&events, still_active).contains("transition to RUN"));
    assert_eq!(
        t(of_request(&events, "irq_lost", still_active).unwrap()),
        run
    );
}

/// "If a hardware interrupt is generated for which there is no hardware interrupt OB in the
/// user program, OB 85 is called by the operating system. The hardware interrupt is
/// acknowledged. If OB 85 has not been programmed, the CPU goes to STOP".
#[test]
fn a_missing_ob_calls_ob85_and_without_ob85_the_cpu_stops() {
    let (ran, events) = sample("speed7_ob85");
    assert_eq!(of(&events, "irq_ignored").len(), 2);
    assert!(of(&events, "irq_lost").is_empty(), "acknowledged: no loss");
    assert_eq!(ran.cpu.engine.stats(85).serviced, 2);
    let (_, events) = sample("speed7_stop");
    let stop = of(&events, "stop");
    assert_eq!(stop.len(), 1);
    assert_eq!(stop[0]["cause"], "OB85");
}
