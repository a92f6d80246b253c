//! The manuals' figures on every run: the response bound covers the cycle-end work, the S5-95F
//! interrupt images belong to OB 13's level, the S5-95F's own interrupt rules and OB 13 timing,
//! STARTUP events on the SPEED7, where a request came, and the S5 status rules. Each test names
//! the manual sentence it checks.

mod common;

use awl::runner::{self, Ran};
use common::*;

fn summary(ran: &Ran) -> String {
    awl::report::summary(ran)
}

// ---- 1. The response bound covers the cycle-end work ----

/// SINUMERIK 840C PLC manual, 5.3.2: "The maximum response time between an interrupt occurring
/// and being serviced is therefore, in the worst case, the processing time of the longest
/// block." The operating system's work at the cycle end (PIQ write, operating-system time, PII
/// read) has no block change inside it: it is a stretch of its own, in the trace and in the
/// bound. A request just after OB 1's block end is taken after the PIQ write.
#[test]
fn the_cycle_end_work_is_in_the_trace_and_in_the_bound() {
    let program = "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      BE\nOB 3\n      BE\n";
    let (ran, events) = traced(
        "cycle_end_bound",
        program,
        "run = { cycles = 2 }\n[[event]]\nat = \"30us\"\ninterrupt = \"OB 3\"\n",
    );
    let piq = of(&events, "data_cycle")
        .into_iter()
        .find(|e| e["direction"] == "output")
        .unwrap();
    let piq_end = piq["t_ns"].as_u64().unwrap() + piq["duration_ns"].as_u64().unwrap();
    assert!(piq["t_ns"].as_u64().unwrap() < 30_000 && 30_000 < piq_end);
    let service = of(&events, "irq_service")[0];
    assert_eq!(service["t_ns"], piq_end, "taken right after the PIQ write");
    assert_eq!(service["point"], "cycle");
    let os = of(&events, "os_time")[0];
    assert_eq!(os["duration_ns"], 400_000);
    let bound = ran.cpu.response_bound().ns;
    assert_eq!(
        bound, 400_000,
        "the operating-system time is the longest stretch"
    );
    assert!(service["latency_ns"].as_u64().unwrap() <= bound);
    let text = summary(&ran);
    assert!(
        text.contains("response bound: 0.400 ms, the longest stretch without an interrupt point: the operating-system time at the cycle end"),
        "{text}"
    );
}

/// The SPEED7's 50 µs operating-system time bounds a request made in it, with operation points.
#[test]
fn the_speed7_operating_system_time_bounds_its_requests() {
    let program = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\nOB 40\n      L  KF +1\n      T  FW 40\n      BE\n";
    let (ran, events) = traced(
        "speed7_os",
        program,
        "cpu = \"speed7\"\nrun = { cycles = 3 }\n[[hw_module]]\nmodule = 4\nob = 40\n[[event]]\nat = \"20us\"\nhw_interrupt = { module = 4, channel = 1, active_for = \"5us\" }\n",
    );
    let os = of(&events, "os_time")[0];
    let os_start = os["t_ns"].as_u64().unwrap();
    assert!(
        os_start < 20_000 && 20_000 < os_start + 50_000,
        "the event came in the OS time"
    );
    let latency = of(&events, "irq_service")[0]["latency_ns"]
        .as_u64()
        .unwrap();
    assert_eq!(latency, os_start + 50_000 - 20_000);
    assert!(latency <= ran.cpu.response_bound().ns);
}

/// SINUMERIK 840C PLC manual, 5.3.2: "The response time of this lower-priority program has
/// thus been increased by the processing time of the higher-priority program": the summary says
/// so instead of contradicting the bound.
#[test]
fn the_summary_explains_requests_that_waited_for_a_higher_priority() {
    let (ran, events) = traced(
        "waited_priority",
        "OB 1\n      JU PB 1\n      BE\nPB 1\n      L  KF +1\n      BE\nOB 3\n      L  KF +1\n      X  F\n      X  F\n      BE\nOB 4\n      BE\n",
        "run = { cycles = 1 }\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 4\"\n[[event]]\nat = \"13us\"\ninterrupt = \"OB 3\"\n",
    );
    let ob4 = of(&events, "irq_service")
        .into_iter()
        .find(|e| e["ob"] == 4)
        .unwrap();
    assert_eq!(ob4["waited"], "priority");
    let text = summary(&ran);
    assert!(
        text.contains("OB 4: waited beyond the response bound: 1 because a level of the same or a higher priority ran first"),
        "{text}"
    );
}

// ---- 2. The S5-95F interrupt images belong to OB 13's level ----

/// S5-95F manual, 7.4.4: "In OB13 the interrupt PII is read with L PY"; the interrupt PIQ is
/// output "after OB13 has finished ... only if the interrupt PIQ was written". An OB 3 that
/// interrupts OB 13 is no OB 13: its `L PY 0` reads the module (2, not OB 13's image 1), its
/// `T PY 70` goes to the module at once, and no interrupt output data cycle follows OB 13,
/// which wrote nothing.
#[test]
fn the_interrupt_images_do_not_leak_into_ob3() {
    let program = format!(
        "{}OB 13\n      L  PY 0\n      T  FY 40\n      JU PB 1\n      BE\nPB 1\n      BE\nOB 3\n      L  PY 0\n      T  FY 80\n      L  KB 7\n      T  PY 70\n      BE\n",
        long_fb(1000)
    );
    // A cycle of about 11 ms, so OB 13 runs once. It starts right at 10 ms (operation points) and reads module byte 0 = 1 into its
    // interrupt PII in the 0.3 ms input data cycle; then the module changes to 2 and OB 3 is
    // requested, which runs after OB 13's first operation.
    let scenario = "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"10ms\"\n[[event]]\nat = \"1ms\"\nset = { \"PY 0\" = 1 }\n[[event]]\nat = \"10.305ms\"\nset = { \"PY 0\" = 2 }\n[[event]]\nat = \"10.305ms\"\ninterrupt = \"OB 3\"\n[expect]\n\"FY 40\" = 1\n\"FY 80\" = 2\n\"PY 70\" = 7\nmode = \"RUN\"\n";
    let (ran, events) = traced("images_per_level", &program, scenario);
    assert!(ran.mismatches.is_empty(), "{:?}", ran.mismatches);
    let ob3 = of(&events, "irq_service")
        .into_iter()
        .find(|e| e["ob"] == 3)
        .unwrap();
    assert_eq!(ob3["block"], "OB 13", "OB 3 interrupted OB 13");
    assert!(
        of(&events, "data_cycle")
            .iter()
            .all(|e| e["kind"] != "interrupt_output"),
        "no interrupt output data cycle: OB 13 wrote nothing"
    );
}

// ---- 3. The S5-95F's interrupt points, OB 2 and OB 13 timing ----

/// OB 1 calls FB 1, a loop of `passes` passes of about 11 µs each on the S5-95F.
fn long_fb(passes: u16) -> String {
    format!(
        "OB 1\n      JU FB 1\nNAME :LONG\n      BE\nFB 1\nNAME :LONG\n      L  KF +{passes}\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n"
    )
}

const LONG_FB: &str = "OB 1\n      JU FB 1\nNAME :LONG\n      BE\nFB 1\nNAME :LONG\n      L  KF +3000\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\n";

/// S5-95F manual, 7.4.4: "OB13 can interrupt the cyclic program after any STEP 5 statement": a
/// cyclic FB running about 25 ms without a block change does not keep OB 13 (every 10 ms)
/// waiting into a wake-up error.
#[test]
fn ob13_interrupts_the_cyclic_program_after_any_statement() {
    let program = format!(
        "{LONG_FB}OB 13\n      L  FW 2\n      L  KF +1\n      +F\n      T  FW 2\n      BE\n"
    );
    let (ran, events) = traced(
        "ob13_operation_points",
        &program,
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"10ms\"\n[expect]\nmode = \"RUN\"\n",
    );
    assert!(ran.mismatches.is_empty(), "{:?}", ran.mismatches);
    let services = of(&events, "irq_service");
    assert!(services.len() >= 2);
    assert!(
        services
            .iter()
            .all(|e| e["point"] == "operation" && e["block"] == "FB 1")
    );
}

/// S5-95F manual, 12 (interrupt processing): OB 3 "can be interrupted by an OB2 interrupt";
/// "the OB2 interrupt processing routine cannot be interrupted"; 7.4.4: OB 13 "can not
/// interrupt ... interrupt-driven program processing (OB2, OB3)".
#[test]
fn ob2_interrupts_ob3_and_ob13_waits_for_both() {
    let program = format!(
        "{LONG_FB}OB 2\n      L  KF +1\n      X  F\n      BE\nOB 3\n      L  KF +1\n      X  F\n      X  F\n      BE\nOB 13\n      BE\n"
    );
    // OB 3 at 9.9 ms runs about 120 us; OB 2 comes 30 us into it; OB 13 is due at 10 ms.
    let (_, events) = traced(
        "s595f_priorities",
        &program,
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"10ms\"\n[[event]]\nat = \"9.9ms\"\ninterrupt = \"OB 3\"\n[[event]]\nat = \"9.93ms\"\ninterrupt = \"OB 2\"\n",
    );
    let order: Vec<(String, u64)> = events
        .iter()
        .filter(|e| e["ev"] == "irq_service" || e["ev"] == "irq_end")
        .take(6)
        .map(|e| {
            (
                e["ev"].as_str().unwrap().to_string(),
                e["ob"].as_u64().unwrap(),
            )
        })
        .collect();
    let pairs: Vec<(&str, u64)> = order.iter().map(|(ev, ob)| (ev.as_str(), *ob)).collect();
    assert_eq!(
        pairs,
        [
            ("irq_service", 3),
            ("irq_service", 2),
            ("irq_end", 2),
            ("irq_end", 3),
            ("irq_service", 13),
            ("irq_end", 13)
        ]
    );
}

/// S5-95F manual, 7.4.4: "Use the IA command in the control program to disable the OB13
/// call-up and the RA command to enable it. A call-up request can be stored during a call-up
/// disable."
#[test]
fn ia_stores_the_ob13_call_until_ra() {
    let program = "OB 1\n      JU FB 1\nNAME :HOLD\n      BE\nFB 1\nNAME :HOLD\n      IA\n      L  KF +500\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      RA\n      L  KF +5\n      BE\nOB 13\n      BE\n";
    let (_, events) = traced(
        "ia_ob13",
        program,
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"3ms\"\n",
    );
    let request = of(&events, "irq_request")[0]["t_ns"].as_u64().unwrap();
    let service = of(&events, "irq_service")[0];
    let ra = of(&events, "block_end")[0]["t_ns"].as_u64().unwrap();
    assert_eq!(request, 3_000_000);
    assert_eq!(service["waited"], "disabled");
    let at = service["t_ns"].as_u64().unwrap();
    assert!(
        at > 5_000_000 && at < ra,
        "after the loop, right after RA: {at}"
    );
}

/// S5-95F manual, 7.4.4: "When processing OB13, you may not exceed the block nesting depth of
/// 16 levels" — and 12: "The block nesting depth of 16 may never be exceeded, even during
/// interrupt processing": the blocks of the interrupted level count.
#[test]
fn the_s5_95f_nesting_limit_counts_every_level() {
    let mut program = String::from("OB 1\n      JU PB 1\n      BE\n");
    for pb in 1..10 {
        program.push_str(&format!("PB {pb}\n      JU PB {}\n      BE\n", pb + 1));
    }
    program.push_str("PB 10\n");
    program.push_str(&"      X  F\n".repeat(20));
    program.push_str("      BE\nOB 13\n      JU PB 20\n      BE\n");
    for pb in 20..26 {
        program.push_str(&format!("PB {pb}\n      JU PB {}\n      BE\n", pb + 1));
    }
    program.push_str("PB 26\n      BE\n");
    // OB 13 is due at 1 ms while PB 10 runs, the 11th block with OB 1: OB 13 is the 12th,
    // PB 20…PB 23 the 13th to 16th, and PB 23's call of PB 24 would be the 17th.
    let scenario = "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"1ms\"\n";
    let (ran, _) = traced("nesting_95f", &program, scenario);
    let stop = ran.outcome.stop.as_ref().expect("STUEB");
    assert_eq!(stop.cause.code(), "STUEB");
    assert_eq!(
        stop.stack[0].block, "PB 23",
        "the 17th block was not called"
    );
}

/// S5-95F manual, 7.4.4: "In the ideal case, OB13 is processed directly when the previous
/// OB13 time has elapsed (t = 0)" — the default; a scenario may give the delay t of each call.
#[test]
fn ob13_calls_come_at_the_interval_plus_the_delay() {
    let program = format!("{LONG_FB}OB 13\n      BE\n");
    for (delay, first) in [("", 10_000_000u64), ("delay = \"2ms\"\n", 12_000_000)] {
        let (_, events) = traced(
            &format!("ob13_delay_{first}"),
            &program,
            &format!(
                "cpu = \"s5-95f\"\nrun = {{ cycles = 1 }}\n[ob13]\ninterval = \"10ms\"\n{delay}"
            ),
        );
        let requests: Vec<u64> = of(&events, "irq_request")
            .iter()
            .map(|e| e["t_ns"].as_u64().unwrap())
            .collect();
        assert_eq!(requests[..2], [first, first + 10_000_000]);
    }
}

/// S5-95F manual, 7.4.4: "OB13 call-up interval > maximum delay t of OB13 processing ... If you
/// have programmed an OB13 call-up interval that does not fulfill the above equation, this
/// results in a time interrupt error. In this case, the S5-95F goes into STOP."
#[test]
fn an_interval_not_above_the_maximum_delay_is_the_time_interrupt_error() {
    let program = format!("{LONG_FB}OB 13\n      BE\n");
    let (ran, _) = traced(
        "ob13_max_delay",
        &program,
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"20ms\"\nmax_delay = \"20ms\"\n",
    );
    let stop = ran.outcome.stop.as_ref().expect("STOP");
    assert_eq!(stop.cause.code(), "WECK");
    let report = awl::diagnostics::render_plain(&runner::stop_report(&ran, stop));
    assert!(report.contains("awl::stop::weck_interval"), "{report}");
    assert!(
        report.contains("not above the maximum delay 20.000 ms"),
        "{report}"
    );
    let (ran, _) = traced(
        "ob13_max_delay_ok",
        &program,
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"30ms\"\ndelay = \"20ms\"\nmax_delay = \"20ms\"\n",
    );
    assert!(ran.outcome.stop.is_none(), "{:?}", ran.outcome.stop);
}

// ---- 4. The S5-95F's maximum response of time-controlled processing ----

/// S5-95F manual, 7.4.5: the maximum response "depends on the OB13 call-up interval set, the
/// delay time t, the execution time T of OB13, the delay time of the input module, the data
/// cycle".
#[test]
fn the_summary_gives_the_time_controlled_response() {
    let (ran, _) = traced(
        "time_controlled_response",
        &format!("{LONG_FB}OB 13\n      L  PY 0\n      T  PY 1\n      BE\n"),
        "cpu = \"s5-95f\"\nrun = { cycles = 1 }\n[ob13]\ninterval = \"10ms\"\ndelay = \"1ms\"\nmax_delay = \"5ms\"\n",
    );
    let text = summary(&ran);
    let line = text
        .lines()
        .find(|line| line.contains("time-controlled response"))
        .unwrap_or_else(|| panic!("{text}"));
    for part in [
        "OB 13 interval 10.000",
        "delay t 5.000",
        "(longest run)",
        "data cycles 0.600",
        "input module 3.000 (estimate)",
        "(S5-95F manual, 7.4.5)",
    ] {
        assert!(line.contains(part), "{part}: {line}");
    }
    assert!(!text.contains("longest block"), "operation points: {text}");
}

// ---- 7. Where a request came ----

/// A request made while a block with a loop runs names the block and the line; one made while
/// the startup OB runs names it too.
#[test]
fn requests_name_the_running_block_and_line() {
    let program = "OB 21\n      L  KF +1\n      L  KF +2\n      X  F\n      BE\nOB 1\n      JU FB 1\nNAME :LOOP\n      BE\nFB 1\nNAME :LOOP\n      L  KF +100\n      T  FW 0\nM001 :L  FW 0\n      L  KF +1\n      -F\n      T  FW 0\n      JP =M001\n      BE\nOB 3\n      BE\n";
    let (_, events) = traced(
        "place_loop",
        program,
        "run = { cycles = 1 }\n[[event]]\nat = \"4us\"\ninterrupt = \"OB 3\"\n[[event]]\nat = \"100us\"\ninterrupt = \"OB 4\"\n",
    );
    let requests = of(&events, "irq_request");
    assert_eq!(requests[0]["block"], "OB 21");
    assert_eq!(requests[0]["line"], 4, "the X F running at 4 us");
    assert_eq!(requests[1]["block"], "FB 1");
    assert!(
        requests[1]["line"]
            .as_u64()
            .is_some_and(|line| (13..=17).contains(&line))
    );
}

// ---- 8. The S5 status rules ----

fn fb(body: &str) -> String {
    format!("OB 1\n      JU FB 1\nNAME :T\n      BE\nFB 1\nNAME :T\n{body}\n      BE\n")
}

/// S5-101U manual, 5.2.5: digital logic and shift operations set CC 1 and CC 0 and do not
/// affect the overflow bit.
#[test]
fn word_logic_and_shifts_leave_the_overflow_bit() {
    let body = "      L  KF +30000\n      L  KF +30000\n      +F\n      L  KH 00FF\n      L  KH 0F0F\n      AW\n      SLW 1\n      JO =OVF\n      BEU\nOVF  :L  KF +1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(
        fw(&cpu, 10),
        1,
        "the overflow of +F is still there after AW and SLW"
    );
}

/// CPU 928B programming guide, table 3-7: `:F` "quotient in ACCU-1-L, remainder in ACCU-1-H";
/// arithmetic moves ACCU 3 into ACCU 2 and ACCU 4 into ACCU 3; `ENT` loads ACCU 3 and 4.
#[test]
fn division_remainder_and_the_four_accumulators() {
    let body = "      L  KF +23\n      L  KF +5\n      :F\n      T  FD 10\n      L  KF +7\n      L  KF +8\n      ENT\n      L  KF +1\n      L  KF +2\n      +F\n      T  FW 20\n      TAK\n      T  FW 22";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(
        fd(&cpu, 10),
        3 << 16 | 4,
        "remainder 3 in ACCU 1-H, quotient 4 in ACCU 1-L"
    );
    assert_eq!(fw(&cpu, 20), 3);
    assert_eq!(
        fw(&cpu, 22),
        7,
        "ENT pushed ACCU 2 (7) into ACCU 3, +F moved it up"
    );
    let built = awl::frontend::build_text(
        "ent.awl",
        &fb("      ENT"),
        awl::profile::find("s5-95f").unwrap(),
    );
    assert!(built.has_errors(), "the S5-95F has two accumulators");
}

/// The label jumps leave the RLO (CPU 928B programming guide, table 3-19, for JZ/JN/JP/JM/JO;
/// JU = works the same way); JC = sets it to 1 whether it jumps or not.
#[test]
fn label_jumps_and_the_rlo() {
    let body = "      A  F 9.0\n      JU =M1\nM1   :=  F 1.0\n      ON F 9.0\n      A  F 9.0\n      JC =M2\nM2   :=  F 1.1";
    let (cpu, _) = run_once(&fb(body));
    assert!(!flag(&cpu, 1, 0), "JU = keeps the RLO 0");
    assert!(flag(&cpu, 1, 1), "JC = not taken leaves RLO 1");
}

/// `X F` overflowing: OV and OS set, CC1 CC0 from the sign of the true product (the STEP 7
/// status-word table the VIPA SPEED7 follows): 300 × 300 = 90000 is positive although its low
/// word is negative.
#[test]
fn multiplication_overflow_condition_codes_follow_the_true_product() {
    let body = "      L  KF +300\n      L  KF +300\n      X  F\n      JP =POS\n      BEU\nPOS  :JO =OVF\n      BEU\nOVF  :L  KF +1\n      T  FW 10";
    let (cpu, _) = run_once(&fb(body));
    assert_eq!(fw(&cpu, 10), 1);
}

/// SINUMERIK 840C PLC manual, 5.3.1: "Organization blocks OB 2 and OB 5 cannot be called up in
/// normal mode": a program call of OB 2 runs it as a block, with a warning.
#[test]
fn calling_ob2_in_normal_mode_is_warned() {
    let exe = env!("CARGO_BIN_EXE_awl");
    let dir = std::path::PathBuf::from("target/test-scenarios/ob2_call");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("p.awl"),
        "OB 1\n      JU OB 2\n      BE\nOB 2\n      BE\n",
    )
    .unwrap();
    let output = std::process::Command::new(exe)
        .args(["run", "--cycles", "1"])
        .arg(dir.join("p.awl"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("awl::run::ob_call_normal_mode") && stderr.contains("5.3.1"),
        "{stderr}"
    );
    assert!(output.status.success());
    let output = std::process::Command::new(exe)
        .args(["run", "--cycles", "1", "--mode", "special"])
        .arg(dir.join("p.awl"))
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&output.stderr).contains("ob_call_normal_mode"));
}
