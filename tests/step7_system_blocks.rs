//! The system blocks of STEP 7 that awl runs itself ("System Software for S7-300/400 System and
//! Standard Functions"): the IEC counters SFB 0–2 and timers SFB 3–5 with instance DBs and as
//! multi-instances, SFC 0 SET_CLK and SFC 1 READ_CLK on the simulated clock, SFC 47 WAIT; and
//! the errors of their calls.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

fn ob1(body: &str) -> String {
    format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n{body}\nEND_ORGANIZATION_BLOCK\n")
}

fn instance_db(db: u16, sfb: u16) -> String {
    format!("DATA_BLOCK DB {db}\n  SFB {sfb}\nBEGIN\nEND_DATA_BLOCK\n")
}

#[test]
fn the_counters_count_edges_within_an_int_with_reset_and_load_first() {
    let program = ob1(
        "  CALL SFB 0, DB 1 (CU := TRUE, R := FALSE, PV := 2, Q := M 0.0, CV := MW 10)
  CALL SFB 0, DB 1 (CU := FALSE, R := FALSE, PV := 2, Q := M 0.1, CV := MW 10)
  CALL SFB 0, DB 1 (CU := TRUE, R := FALSE, PV := 2, Q := M 0.2, CV := MW 12)
  CALL SFB 0, DB 1 (CU := TRUE, R := FALSE, PV := 2, Q := M 0.3, CV := MW 14)
  L 32767
  T DB1.DBW 6
  CALL SFB 0, DB 1 (CU := FALSE, R := FALSE, PV := 2, Q := M 0.4, CV := MW 16)
  CALL SFB 0, DB 1 (CU := TRUE, R := FALSE, PV := 2, Q := M 0.4, CV := MW 16)
  CALL SFB 0, DB 1 (CU := TRUE, R := TRUE, PV := 2, Q := M 0.5, CV := MW 18)
  CALL SFB 1, DB 2 (CD := FALSE, LOAD := TRUE, PV := 1, Q := M 1.0, CV := MW 20)
  CALL SFB 1, DB 2 (CD := TRUE, LOAD := FALSE, PV := 1, Q := M 1.1, CV := MW 22)
  L -32768
  T DB2.DBW 6
  CALL SFB 1, DB 2 (CD := FALSE, LOAD := FALSE, PV := 1, Q := M 1.2, CV := MW 24)
  CALL SFB 1, DB 2 (CD := TRUE, LOAD := FALSE, PV := 1, Q := M 1.2, CV := MW 24)
  CALL SFB 2, DB 3 (CU := TRUE, CD := TRUE, R := FALSE, LOAD := FALSE, PV := 5, QU := M 2.0, QD := M 2.1, CV := MW 30)
  CALL SFB 2, DB 3 (CU := FALSE, CD := FALSE, R := FALSE, LOAD := TRUE, PV := 5, QU := M 2.2, QD := M 2.3, CV := MW 32)
  CALL SFB 2, DB 3 (CU := FALSE, CD := TRUE, R := FALSE, LOAD := FALSE, PV := 5, QU := M 2.4, QD := M 2.5, CV := MW 34)
  CALL SFB 2, DB 3 (CU := TRUE, CD := FALSE, R := TRUE, LOAD := TRUE, PV := 5, QU := M 2.6, QD := M 2.7, CV := MW 36)
  A BR
  = M 3.0",
    ) + &instance_db(1, 0)
        + &instance_db(2, 1)
        + &instance_db(3, 2);
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\
         \"MW 10\" = 1\n\"M 0.0\" = 0\n\"MW 12\" = 2\n\"M 0.2\" = 1\n\"MW 14\" = 2\n\
         \"MW 16\" = 32767\n\"MW 18\" = 0\n\"M 0.5\" = 0\n\
         \"MW 20\" = 1\n\"M 1.0\" = 0\n\"MW 22\" = 0\n\"M 1.1\" = 1\n\"MW 24\" = -32768\n\
         \"MW 30\" = 0\n\"M 2.0\" = 0\n\"M 2.1\" = 1\n\"MW 32\" = 5\n\"M 2.2\" = 1\n\"M 2.3\" = 0\n\
         \"MW 34\" = 4\n\"M 2.4\" = 0\n\"MW 36\" = 0\n\"M 2.7\" = 1\n\"M 3.0\" = 1\n\
         \"DB1.DBW 6\" = 0\n",
    );
}

/// OB 1 calls TP (DB 3) and TON (DB 4) with IN always 1, TOF (DB 5) with IN 1 in the first
/// cycle only, each with PT 100 ms.
fn timers() -> String {
    ob1("  UN M 20.0
  = M 20.1
  SET
  = M 20.0
  CALL SFB 3, DB 3 (IN := TRUE, PT := T#100MS, Q := M 0.3, ET := MD 30)
  CALL SFB 4, DB 4 (IN := TRUE, PT := T#100MS, Q := M 0.4, ET := MD 40)
  CALL SFB 5, DB 5 (IN := M 20.1, PT := T#100MS, Q := M 0.5, ET := MD 50)")
        + &instance_db(3, 3)
        + &instance_db(4, 4)
        + &instance_db(5, 5)
}

#[test]
fn the_timers_run_on_simulated_time() {
    // After 50 ms the pulse is on, the on-delay not yet, the off-delay still on.
    let Ok(ran) = run(
        &timers(),
        "run = { for = \"50ms\" }\n[expect]\n\"M 0.3\" = 1\n\"M 0.4\" = 0\n\"M 0.5\" = 1\n\
         \"DB3.DBB 12\" = 1\n\"DB4.DBB 12\" = 1\n\"DB5.DBB 12\" = 2\n",
    ) else {
        panic!("the program runs");
    };
    assert!(!ran.failed(), "{:#?}", ran.mismatches);
    // After 200 ms all three have run out: ET is PT.
    passes(
        &timers(),
        "run = { for = \"200ms\" }\n[expect]\n\"M 0.3\" = 0\n\"M 0.4\" = 1\n\"M 0.5\" = 0\n\
         \"MD 30\" = 100\n\"MD 40\" = 100\n\"MD 50\" = 100\n\
         \"DB3.DBB 12\" = 2\n\"DB4.DBB 12\" = 2\n\"DB5.DBB 12\" = 0\n",
    );
}

#[test]
fn a_timer_is_reset_by_pt_0_and_refuses_a_negative_pt_with_br_0() {
    let program = ob1(
        "  CALL SFB 4, DB 4 (IN := TRUE, PT := T#1S, Q := M 0.0, ET := MD 4)
  L DB4.DBB 12
  T MB 2
  CALL SFB 4, DB 4 (IN := TRUE, PT := T#-1S, Q := M 0.2, ET := MD 12)
  A BR
  = M 1.1
  L DB4.DBB 12
  T MB 3
  CALL SFB 4, DB 4 (IN := TRUE, PT := T#0S, Q := M 0.1, ET := MD 8)
  A BR
  = M 1.0",
    ) + &instance_db(4, 4);
    // Running (STATE 1), then reset by each; PT 0 clears IN too.
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"MB 2\" = 1\n\"M 1.1\" = 0\n\"MB 3\" = 0\n\
         \"M 1.0\" = 1\n\"DB4.DBX 0.0\" = 0\n\"DB4.DBB 12\" = 0\n\"M 0.2\" = 0\n",
    );
}

#[test]
fn counters_and_timers_run_as_multi_instances() {
    let program = "FUNCTION_BLOCK FB 1\nVAR\n  down : SFB 1;\n  delay : SFB 4;\nEND_VAR\nBEGIN\n\
                   CALL #down (CD := TRUE, LOAD := FALSE, PV := 0, Q := M 0.0, CV := MW 2)\n\
                   CALL #delay (IN := TRUE, PT := T#20MS, Q := M 0.1, ET := MD 4)\n\
                   END_FUNCTION_BLOCK\n\
                   DATA_BLOCK DB 1\n  FB 1\nBEGIN\nEND_DATA_BLOCK\n"
        .to_string()
        + &ob1("  CALL FB 1, DB 1");
    // The count falls once (one edge); the delay has run out.
    passes(
        &program,
        "run = { for = \"50ms\" }\n[expect]\n\"MW 2\" = -1\n\"M 0.0\" = 1\n\"M 0.1\" = 1\n\
         \"MD 4\" = 20\n",
    );
}

#[test]
fn wait_passes_wt_microseconds_of_simulated_time() {
    let program = ob1("  CALL SFC 64 (RET_VAL := MD 0)
  CALL SFC 47 (WT := 20000)
  A BR
  = M 20.0
  CALL SFC 64 (RET_VAL := MD 4)
  CALL SFC 47 (WT := -5)
  CALL SFC 64 (RET_VAL := MD 8)
  L MD 4
  L MD 0
  -D
  T MD 12
  L MD 8
  L MD 4
  -D
  T MD 16");
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"MD 12\" = 20\n\"MD 16\" = 0\n\"M 20.0\" = 1\n",
    );
}

/// A global DB with a DATE_AND_TIME to set the clock to and one that is none.
const CLOCK_DB: &str = "DATA_BLOCK DB 2\nSTRUCT\n  set : DATE_AND_TIME;\n  read : DATE_AND_TIME;\n\
                        END_STRUCT\nBEGIN\n  set := DT#2030-06-15-12:34:56.789;\nEND_DATA_BLOCK\n";

#[test]
fn read_clk_reads_the_clock_from_2024_and_set_clk_moves_it() {
    let program = "ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  info : ARRAY [0..19] OF BYTE;\n  \
                   now : DATE_AND_TIME;\nEND_VAR\nBEGIN\n\
                   CALL SFC 1 (RET_VAL := MW 0, CDT := #now)\n\
                   A BR\n= M 10.0\nL LD 20\nT MD 20\n\
                   CALL SFC 0 (PDT := DB2.set, RET_VAL := MW 2)\n\
                   A BR\n= M 10.1\n\
                   CALL SFC 1 (RET_VAL := MW 4, CDT := DB2.read)\n\
                   END_ORGANIZATION_BLOCK\n"
        .to_string()
        + CLOCK_DB;
    // 2024-01-01 00:00, then 2030-06-15 12:34:56 (a Saturday: weekday 7) as set.
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 0\n\"M 10.0\" = 1\n\
         \"MD 20\" = 0x24010100\n\"MW 2\" = 0\n\"M 10.1\" = 1\n\"MW 4\" = 0\n\
         \"DB2.DBD 8\" = 0x30061512\n\"DB2.DBB 12\" = 0x34\n\"DB2.DBB 13\" = 0x56\n\
         \"DB2.DBB 14\" = 0x78\n\"DB2.DBB 15\" = 0x97\n",
    );
}

#[test]
fn set_clk_refuses_a_wrong_date_or_time_with_its_error_code() {
    let program = ob1("  L DW#16#24023000
  T DB2.DBD 0
  CALL SFC 0 (PDT := DB2.set, RET_VAL := MW 0)
  A BR
  = M 10.0
  L DW#16#24010124
  T DB2.DBD 0
  CALL SFC 0 (PDT := DB2.set, RET_VAL := MW 2)
  CALL SFC 1 (RET_VAL := MW 4, CDT := DB2.read)")
        + CLOCK_DB;
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 0x8080\n\"M 10.0\" = 0\n\
         \"MW 2\" = 0x8081\n\"DB2.DBW 8\" = 0x2401\n",
    );
}

fn errors(program: &str) -> String {
    match run(program, "") {
        Err(NotRun::SourceErrors(reports, _)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        _ => panic!("`{program}` has errors"),
    }
}

#[test]
fn calls_of_system_blocks_awl_does_not_run_or_with_wrong_parameters_are_errors() {
    let unknown = errors(&(ob1("  CALL SFB 6, DB 1") + &instance_db(2, 0)));
    assert!(unknown.contains("awl::check::not_simulated"), "{unknown}");
    assert!(unknown.contains("SFB 0 to SFB 5"), "{unknown}");
    let no_db = errors(&ob1("  CALL SFB 4 (IN := TRUE, PT := T#1S)"));
    assert!(no_db.contains("awl::check::not_simulated"), "{no_db}");
    assert!(no_db.contains("CALL SFB 4, DB m"), "{no_db}");
    let unknown_db = errors(&(ob1("  NOP 0") + &instance_db(1, 7)));
    assert!(
        unknown_db.contains("an instance DB of SFB 7"),
        "{unknown_db}"
    );
    let param = errors(&(ob1("  CALL SFB 4, DB 1 (X := TRUE)") + &instance_db(1, 4)));
    assert!(param.contains("awl::check::unknown_param"), "{param}");
    let wt = errors(&ob1("  CALL SFC 47 (WT := MD 0)"));
    assert!(wt.contains("awl::check::param_mismatch"), "{wt}");
    assert!(wt.contains("an INT"), "{wt}");
    let twice = errors(&ob1("  CALL SFC 47 (WT := 1, WT := 2)"));
    assert!(twice.contains("is given twice"), "{twice}");
    let cdt = errors(&ob1("  CALL SFC 1 (RET_VAL := MW 0, CDT := MD 4)"));
    assert!(cdt.contains("a DATE_AND_TIME variable"), "{cdt}");
    let missing = errors(&ob1("  CALL SFC 0 (RET_VAL := MW 0)"));
    assert!(missing.contains("awl::check::param_count"), "{missing}");
    assert!(missing.contains("PDT := #now"), "{missing}");
}
