//! The start information of STEP 7 OBs on the speed7 CPU: the first 20 bytes of each OB's local
//! data ("System Software for S7-300/400 System and Standard Functions", Organization Blocks;
//! VIPA SPEED7 operation list), read by address and by the names an OB declares in VAR_TEMP.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

/// OB 1 by its default names: the first cycle's are kept in MB 0–MB 3 and MW 6–MW 10, the
/// latest cycle's in MB 20–MB 23 and MW 26–MW 30.
const OB1_NAMED: &str = "
ORGANIZATION_BLOCK OB 1
VAR_TEMP
  OB1_EV_CLASS : BYTE;
  OB1_SCAN_1 : BYTE;
  OB1_PRIORITY : BYTE;
  OB1_OB_NUMBR : BYTE;
  OB1_RESERVED_1 : BYTE;
  OB1_RESERVED_2 : BYTE;
  OB1_PREV_CYCLE : INT;
  OB1_MIN_CYCLE : INT;
  OB1_MAX_CYCLE : INT;
  OB1_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      L     MB 100;
      L     0;
      ==I;
      SPBN  late;
      L     #OB1_EV_CLASS;
      T     MB 0;
      L     #OB1_SCAN_1;
      T     MB 1;
      L     #OB1_PRIORITY;
      T     MB 2;
      L     #OB1_OB_NUMBR;
      T     MB 3;
      L     #OB1_PREV_CYCLE;
      T     MW 6;
      L     #OB1_MAX_CYCLE;
      T     MW 10;
      L     1;
      T     MB 100;
late: L     #OB1_SCAN_1;
      T     MB 21;
      L     #OB1_PREV_CYCLE;
      T     MW 26;
      L     #OB1_MIN_CYCLE;
      T     MW 28;
      L     #OB1_MAX_CYCLE;
      T     MW 30;
      L     LB 0;      // the same bytes by address
      T     MB 20;
      L     LW 6;
      T     MW 32;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob1_has_its_event_class_scan_type_priority_and_number() {
    passes(
        OB1_NAMED,
        "run = { cycles = 3 }\n[expect]\n\
         \"MB 0\" = 0x11\n\"MB 1\" = 1\n\"MB 2\" = 1\n\"MB 3\" = 1\n\
         \"MW 6\" = 0\n\"MW 10\" = 0\n\
         \"MB 20\" = 0x11\n\"MB 21\" = 3\n",
    );
}

#[test]
fn ob1_has_the_cycle_times_in_ms() {
    // The cycles take some microseconds: 0 ms each; LW 6 is OB1_PREV_CYCLE.
    passes(
        OB1_NAMED,
        "run = { cycles = 3 }\n[expect]\n\"MW 26\" = 0\n\"MW 28\" = 0\n\"MW 30\" = 0\n\"MW 32\" = 0\n",
    );
}

/// A cycle of 5 ms (a loop), then the previous cycle's time, the least and the most.
const SLOW_OB1: &str = "
ORGANIZATION_BLOCK OB 1
BEGIN
      L     LW 6;
      T     MW 0;
      L     LW 8;
      T     MW 2;
      L     LW 10;
      T     MW 4;
      __SLEEP 5;
END_ORGANIZATION_BLOCK
";

#[test]
fn the_cycle_times_are_the_previous_the_least_and_the_most() {
    passes(
        SLOW_OB1,
        "extended = true\nrun = { cycles = 3 }\n[expect]\n\"MW 0\" = 5\n\"MW 2\" = 5\n\"MW 4\" = 5\n",
    );
}

/// OB 100 keeps its start information in MB 0–MB 11, OB 1 its date and time in MB 20–MB 27.
const STARTUP: &str = "
ORGANIZATION_BLOCK OB 100
VAR_TEMP
  OB100_EV_CLASS : BYTE;
  OB100_STRTUP : BYTE;
  OB100_PRIORITY : BYTE;
  OB100_OB_NUMBR : BYTE;
  OB100_RESERVED_1 : BYTE;
  OB100_RESERVED_2 : BYTE;
  OB100_STOP : WORD;
  OB100_STRT_INFO : DWORD;
  OB100_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      L     #OB100_EV_CLASS;
      T     MB 0;
      L     #OB100_STRTUP;
      T     MB 1;
      L     #OB100_PRIORITY;
      T     MB 2;
      L     #OB100_OB_NUMBR;
      T     MB 3;
      L     #OB100_STOP;
      T     MW 4;
      L     #OB100_STRT_INFO;
      T     MD 8;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     LD 12;
      T     MD 20;
      L     LD 16;
      T     MD 24;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob100_is_a_manual_warm_restart() {
    passes(
        STARTUP,
        "run = { cycles = 1 }\n[expect]\n\
         \"MB 0\" = 0x13\n\"MB 1\" = 0x81\n\"MB 2\" = 27\n\"MB 3\" = 100\n\
         \"MW 4\" = 0\n\"MD 8\" = 0x00037703\n",
    );
}

#[test]
fn the_date_and_time_counts_from_the_start_date() {
    // The first cycle starts within a millisecond of 2024-01-01 00:00:00.000, a Monday (2).
    passes(
        STARTUP,
        "run = { cycles = 1 }\n[expect]\n\"MD 20\" = 0x24010100\n\"MD 24\" = 0x00000002\n",
    );
}

/// OB 102 alone: a cold restart, and OB 1's first cycle says so.
const COLD_RESTART: &str = "
ORGANIZATION_BLOCK OB 102
BEGIN
      L     LD 0;
      T     MD 0;
      L     LD 8;
      T     MD 4;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     LB 1;
      T     MB 8;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob102_alone_is_a_manual_cold_restart() {
    passes(
        COLD_RESTART,
        "run = { cycles = 1 }\n[expect]\n\"MD 0\" = 0x13851B66\n\"MD 4\" = 0x00077703\n\"MB 8\" = 4\n",
    );
}

/// OB 100 takes 3.723 s; OB 1 keeps its DATE_AND_TIME in MD 20 and MD 24.
const LATE_OB1: &str = "
ORGANIZATION_BLOCK OB 100
BEGIN
      __SLEEP 3723;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     LD 12;
      T     MD 20;
      L     LD 16;
      T     MD 24;
END_ORGANIZATION_BLOCK
";

#[test]
fn the_date_and_time_follows_the_simulated_clock() {
    // OB 1 starts some microseconds after 3.723 s: 00:00:03.723 on Monday (2).
    passes(
        LATE_OB1,
        "extended = true\nwatchdog = \"6s\"\nrun = { cycles = 1 }\n[expect]\n\
         \"MD 20\" = 0x24010100\n\"MD 24\" = 0x00037232\n",
    );
}

/// OB 40 keeps its start information in MB 0–MB 11, by name and by address.
const OB40: &str = "
ORGANIZATION_BLOCK OB 40
VAR_TEMP
  OB40_EV_CLASS : BYTE;
  OB40_STRT_INF : BYTE;
  OB40_PRIORITY : BYTE;
  OB40_OB_NUMBR : BYTE;
  OB40_RESERVED_1 : BYTE;
  OB40_IO_FLAG : BYTE;
  OB40_MDL_ADDR : WORD;
  OB40_POINT_ADDR : DWORD;
  OB40_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      L     #OB40_EV_CLASS;
      T     MB 0;
      L     #OB40_STRT_INF;
      T     MB 1;
      L     #OB40_PRIORITY;
      T     MB 2;
      L     #OB40_OB_NUMBR;
      T     MB 3;
      L     #OB40_IO_FLAG;
      T     MB 5;
      L     #OB40_MDL_ADDR;
      T     MW 6;
      L     #OB40_POINT_ADDR;
      T     MD 8;
      L     LD 8;
      T     MD 12;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 41
BEGIN
      L     LB 1;
      T     MB 21;
      L     LB 2;
      T     MB 22;
      L     LB 3;
      T     MB 23;
      L     LW 6;
      T     MW 24;
      L     LD 8;
      T     MD 26;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     LB 3;
      T     MB 30;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob40_has_the_module_address_and_the_channel_bit() {
    passes(
        OB40,
        "run = { for = \"10ms\" }\n\
         [[hw_module]]\nmodule = 1\nob = 40\naddress = 256\n\
         [[hw_module]]\nmodule = 2\nob = 41\n\
         [[event]]\nat = \"2ms\"\nhw_interrupt = { module = 1, channel = 3, active_for = \"1ms\" }\n\
         [[event]]\nat = \"5ms\"\nhw_interrupt = { module = 2, channel = 0, active_for = \"1ms\" }\n\
         [expect]\n\
         \"MB 0\" = 0x11\n\"MB 1\" = 0x41\n\"MB 2\" = 16\n\"MB 3\" = 40\n\"MB 5\" = 0x54\n\
         \"MW 6\" = 256\n\"MD 8\" = 8\n\"MD 12\" = 8\n\
         \"MB 21\" = 0x42\n\"MB 22\" = 17\n\"MB 23\" = 41\n\"MW 24\" = 2\n\"MD 26\" = 1\n\
         \"MB 30\" = 1\n",
    );
}

/// OB 85 for module 1, whose OB 40 is missing: its start information in MB 0–MB 11.
const OB85: &str = "
ORGANIZATION_BLOCK OB 85
BEGIN
      L     LD 0;
      T     MD 0;
      L     LW 6;
      T     MW 4;
      L     LD 8;
      T     MD 8;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     1;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob85_names_the_missing_obs_event_and_the_running_ob() {
    passes(
        OB85,
        "run = { for = \"10ms\" }\n\
         [[hw_module]]\nmodule = 1\nob = 40\naddress = 512\n\
         [[event]]\nat = \"2ms\"\nhw_interrupt = { module = 1, channel = 0, active_for = \"1ms\" }\n\
         [expect]\n\"MD 0\" = 0x35A11A55\n\"MW 4\" = 512\n\"MD 8\" = 0x11410101\n",
    );
}

/// OB 82 for a second event on module 3's channel while OB 40 still handles the first.
const OB82: &str = "
ORGANIZATION_BLOCK OB 82
BEGIN
      L     LD 0;
      T     MD 0;
      L     LD 4;
      T     MD 4;
      L     LD 8;
      T     MD 8;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 40
BEGIN
      __SLEEP 2;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     1;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob82_is_a_channel_fault_of_the_module() {
    passes(
        OB82,
        "extended = true\nrun = { for = \"10ms\" }\n\
         [[hw_module]]\nmodule = 3\nob = 40\n\
         [[event]]\nat = \"2ms\"\nhw_interrupt = { module = 3, channel = 1, active_for = \"100us\" }\n\
         [[event]]\nat = \"3ms\"\nhw_interrupt = { module = 3, channel = 1, active_for = \"100us\" }\n\
         [expect]\n\"MD 0\" = 0x39421A52\n\"MD 4\" = 0x00540003\n\"MD 8\" = 0x09000000\n",
    );
}

/// FC 1 called from OB 1 writes its own temporaries: they start after OB 1's 20 bytes.
const CALLEE_TEMPS: &str = "
FUNCTION FC 1 : VOID
VAR_TEMP
  scratch : DWORD;
END_VAR
BEGIN
      L     DW#16#FFFFFFFF;
      T     #scratch;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FC 1;
      L     LB 0;
      T     MB 0;
      L     LB 3;
      T     MB 1;
END_ORGANIZATION_BLOCK
";

#[test]
fn a_called_blocks_temporaries_leave_the_start_information_alone() {
    passes(
        CALLEE_TEMPS,
        "run = { cycles = 1 }\n[expect]\n\"MB 0\" = 0x11\n\"MB 1\" = 1\n",
    );
}

/// The source errors of `program` (with the test extensions), as text.
fn source_errors(program: &str) -> String {
    match run(program, "extended = true\nrun = { cycles = 1 }\n") {
        Err(NotRun::SourceErrors(reports, _)) => format!("{reports:?}"),
        Ok(_) => panic!("the program ran"),
        Err(NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

/// The STOP a run of `program` (with the test extensions) ends with, as text.
fn stop_of(program: &str) -> String {
    let ran = match run(program, "extended = true\nrun = { cycles = 1 }\n") {
        Ok(ran) => ran,
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    };
    format!("{:?}", ran.outcome.stop.expect("a STOP"))
}

/// `P##name` of a temporary is an area-crossing pointer to it on the L stack.
const POINTER_TO_TEMP: &str = "
ORGANIZATION_BLOCK OB 1
VAR_TEMP
  OB1_EV_CLASS : BYTE;
  OB1_SCAN_1 : BYTE;
  OB1_PRIORITY : BYTE;
  OB1_OB_NUMBR : BYTE;
  OB1_RESERVED_1 : BYTE;
  OB1_RESERVED_2 : BYTE;
  OB1_PREV_CYCLE : INT;
  OB1_MIN_CYCLE : INT;
  OB1_MAX_CYCLE : INT;
  OB1_DATE_TIME : DATE_AND_TIME;
END_VAR
BEGIN
      LAR1  P##OB1_DATE_TIME;
      L     B [AR1, P#0.0];     // the year
      T     MB 0;
      L     P##OB1_OB_NUMBR;
      T     MD 4;
      LAR2  P##OB1_SCAN_1;
      L     B [AR2, P#0.0];
      T     MB 1;
END_ORGANIZATION_BLOCK
";

#[test]
fn a_pointer_to_a_temporary_reads_the_start_information() {
    passes(
        POINTER_TO_TEMP,
        "run = { cycles = 1 }\n[expect]\n\"MB 0\" = 0x24\n\"MD 4\" = 0x86000018\n\"MB 1\" = 1\n",
    );
}

#[test]
fn a_pointer_to_an_fc_parameter_is_not_simulated() {
    let errors = source_errors(
        "FUNCTION FC 1 : VOID\nVAR_INPUT\n  x : INT;\nEND_VAR\nBEGIN\n      LAR1  P##x;\nEND_FUNCTION\n\n\
         ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL FC 1 (x := 1);\nEND_ORGANIZATION_BLOCK\n",
    );
    // `L P##x` is simulated; `LAR1 P##x` not yet.
    assert!(errors.contains("pointer to an FC parameter"), "{errors}");
}

#[test]
fn feature_1_says_the_start_information_is_written() {
    passes(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n      __FEATURE 1;\n      T     MB 0;\n      __FEATURE 1, 1;\n      T     MB 1;\nEND_ORGANIZATION_BLOCK\n",
        "extended = true\nrun = { cycles = 1 }\n[expect]\n\"MB 0\" = 1\n\"MB 1\" = 1\n",
    );
    let stop =
        stop_of("ORGANIZATION_BLOCK OB 1\nBEGIN\n      __FEATURE 1, 0;\nEND_ORGANIZATION_BLOCK\n");
    assert!(
        stop.contains("cannot switch the OBs' start information"),
        "{stop}"
    );
}

#[test]
fn awlsims_reboot_parses_with_the_extensions_and_stops_when_run() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL SFC -2 (REBOOT_TYPE := 1);\nEND_ORGANIZATION_BLOCK\n";
    let stop = stop_of(program);
    assert!(
        stop.contains("SFC -2 (__REBOOT) is not simulated"),
        "{stop}"
    );
    let other = source_errors(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL SFC -3 (X := 1);\nEND_ORGANIZATION_BLOCK\n",
    );
    assert!(other.contains("SFC -3"), "{other}");
    // Without the extensions, a negative number is no block.
    match run(program, "run = { cycles = 1 }\n") {
        Err(NotRun::SourceErrors(reports, _)) => {
            assert!(
                format!("{reports:?}").contains("block number -2"),
                "{reports:?}"
            )
        }
        _ => panic!("SFC -2 parsed without the extensions"),
    }
}

/// OB 86 keeps the start information of each call: the failure's in MD 0/4/8, the return's in
/// MD 12/16/20.
const OB86: &str = "
ORGANIZATION_BLOCK OB 86
BEGIN
      L     LB 0;
      L     B#16#39;
      ==I;
      JCN   back;
      L     LD 0;
      T     MD 0;
      L     LD 4;
      T     MD 4;
      L     LD 8;
      T     MD 8;
      BEU;
back: L     LD 0;
      T     MD 12;
      L     LD 4;
      T     MD 16;
      L     LD 8;
      T     MD 20;
END_ORGANIZATION_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     1;
END_ORGANIZATION_BLOCK
";

#[test]
fn ob86_has_the_station_s_failure_and_return() {
    passes(
        OB86,
        "run = { for = \"10ms\" }\n\
         [[event]]\nat = \"2ms\"\nstation = { number = 5, failed = true }\n\
         [[event]]\nat = \"6ms\"\nstation = { number = 5, failed = false }\n\
         [expect]\n\"MD 0\" = 0x39C41A56\n\"MD 4\" = 0x000007FF\n\"MD 8\" = 0x00000105\n\
         \"MD 12\" = 0x38C41A56\n\"MD 20\" = 0x00000105\n",
    );
}

#[test]
fn a_station_event_without_ob86_stops_the_cpu() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L     1;\nEND_ORGANIZATION_BLOCK\n";
    passes(
        program,
        "run = { for = \"10ms\" }\n\
         [[event]]\nat = \"2ms\"\nstation = { number = 5, failed = true }\n\
         [expect]\nmode = \"STOP\"\nstop_cause = \"OB86\"\n",
    );
    let Err(NotRun::Failed(reports)) = awl_station_on_s5() else {
        panic!("a scenario error");
    };
    assert!(format!("{reports:?}").contains("`station` belongs to the speed7 profile"));
}

/// A station event in a scenario for an S5 CPU.
fn awl_station_on_s5() -> Result<awl::runner::Ran, NotRun> {
    common::step7::run_on(
        "s5-115u",
        "PB 1\n      BE\n",
        "run = { cycles = 1 }\n[[event]]\nat = \"0ms\"\nstation = { number = 5, failed = true }\n",
    )
}
