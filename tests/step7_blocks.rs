//! STEP 7 block numbers up to 65535: a UDT, an FC, an FB with its instance DB and data blocks
//! numbered past 255 compile and run; data blocks opened by a constant and by a number read at
//! run time; what lies past 65535 (and, in STEP 5, past 255) is a diagnostic.

mod common;

use awl::runner::{self, NotRun, Ran};

fn run(program: &str, cpu: &str, scenario: &str) -> Result<Ran, NotRun> {
    common::step7::run_on(cpu, program, scenario)
}

fn passes(program: &str, scenario: &str) -> Ran {
    match run(program, "speed7", scenario) {
        Ok(ran) => {
            assert!(
                !ran.failed() && ran.expectations > 0,
                "{:#?}",
                ran.mismatches
            );
            ran
        }
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => {
            panic!("{reports:?}")
        }
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

/// The codes of the source errors of `program` on `cpu`.
fn source_errors(program: &str, cpu: &str) -> Vec<String> {
    let Err(NotRun::SourceErrors(reports, _)) = run(program, cpu, "run = { cycles = 1 }\n") else {
        panic!("a source error");
    };
    reports
        .iter()
        .filter_map(|report| report.code().map(|code| code.to_string()))
        .collect()
}

const HIGH_NUMBERS: &str = "
TYPE UDT 65535
  STRUCT
    low : INT;
    high : INT;
  END_STRUCT;
END_TYPE

DATA_BLOCK DB 300
STRUCT
  first : INT := 7;
  second : INT;
  pair : UDT 65535;
END_STRUCT;
BEGIN
  pair.high := 33;
END_DATA_BLOCK

DATA_BLOCK DB 4000
STRUCT
  value : INT := 11;
END_STRUCT;
BEGIN
END_DATA_BLOCK

FUNCTION_BLOCK FB 65535
VAR_INPUT
  add : INT;
END_VAR
VAR_OUTPUT
  total : INT;
END_VAR
VAR
  sum : INT := 100;
END_VAR
BEGIN
      L     #sum;
      L     #add;
      +I    ;
      T     #sum;
      T     #total;
END_FUNCTION_BLOCK

DATA_BLOCK DB 65535
 FB 65535
BEGIN
END_DATA_BLOCK

FUNCTION FC 1000 : VOID
BEGIN
      L     MW 0;       // counts the calls
      +     1;
      T     MW 0;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FC 1000;
      UC    FC 1000;
      CALL  FB 65535, DB 65535 (add := 5, total := MW 2);
      OPN   DB 300;
      L     DBW 0;      // first: 7
      T     MW 4;
      L     DBW 6;      // pair.high: 33
      T     MW 6;
      L     DBW 2;      // second counts up
      +     1;
      T     DBW 2;
      L     DBNO;       // 300
      T     MW 8;
      L     4000;
      T     MW 10;
      OPN   DB [MW 10];
      L     DBW 0;      // value: 11
      T     MW 12;
      L     DBNO;
      T     MW 14;      // 4000
      L     DB300.pair.low;
      +     2;
      T     DB300.pair.low;
      OPN   DI 65535;
      L     DINO;
      T     MW 16;
      L     DILG;       // the instance DB: add, total, sum
      T     MW 18;
END_ORGANIZATION_BLOCK
";

#[test]
fn blocks_numbered_past_255_compile_and_run() {
    // Three cycles: two FC calls per cycle; the FB's sum 100 + 3 × 5 in DB 65535 word 4.
    passes(
        HIGH_NUMBERS,
        "run = { cycles = 3 }\n[expect]\nmode = \"RUN\"\n\
         \"MW 0\" = 6\n\"MW 2\" = 115\n\"DB65535.DBW 4\" = 115\n\
         \"MW 4\" = 7\n\"MW 6\" = 33\n\"DB300.DBW 2\" = 3\n\"MW 8\" = 300\n\
         \"MW 12\" = 11\n\"MW 14\" = 4000\n\"DB300.DBW 4\" = 6\n\
         \"MW 16\" = 65535\n\"MW 18\" = 6\n",
    );
}

#[test]
fn a_scenario_writes_a_data_block_numbered_past_255() {
    let program = "
DATA_BLOCK DB 40000
STRUCT
  value : INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB40000.DBW 0;
      T     MW 0;
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 2 }\n[[event]]\nat = \"0ms\"\nset = { \"DB40000.DBW 0\" = 1234 }\n\
         [expect]\n\"MW 0\" = 1234\n",
    );
}

/// The STOP of a run of `program`, as the report renders it.
fn stop_report(program: &str) -> String {
    let Ok(ran) = run(program, "speed7", "run = { cycles = 1 }\n") else {
        panic!("the program runs");
    };
    let stop = ran.outcome.stop.as_ref().expect("a STOP");
    awl::diagnostics::render_plain(&runner::stop_report(&ran, stop))
}

#[test]
fn opening_a_missing_data_block_by_a_run_time_number_stops() {
    let program = "
DATA_BLOCK DB 4000
STRUCT
  value : INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     4001;
      T     MW 10;
      OPN   DB [MW 10];
END_ORGANIZATION_BLOCK
";
    let report = stop_report(program);
    assert!(report.contains("awl::stop::lzf_block"), "{report}");
    assert!(report.contains("DB 4001"), "{report}");
}

#[test]
fn opening_a_named_data_block_the_program_lacks_stops_naming_it() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      OPN DB 5000;\nEND_ORGANIZATION_BLOCK\n";
    let report = stop_report(program);
    assert!(report.contains("awl::stop::lzf_block"), "{report}");
    assert!(report.contains("DB 5000"), "{report}");
}

#[test]
fn a_step7_block_number_past_65535_is_a_diagnostic() {
    let program = "FUNCTION FC 65536 : VOID\nBEGIN\n      NOP 0;\nEND_FUNCTION\n\
                   ORGANIZATION_BLOCK OB 1\nBEGIN\n      NOP 0;\nEND_ORGANIZATION_BLOCK\n";
    assert!(
        source_errors(program, "speed7").contains(&"awl::s7::block_number".to_string()),
        "FC 65536"
    );
    for operand in [
        "OPN DB 65536",
        "CALL FC 70000",
        "UC FC70000",
        "CALL FB 1, DB 65536",
    ] {
        let program =
            format!("ORGANIZATION_BLOCK OB 1\nBEGIN\n      {operand};\nEND_ORGANIZATION_BLOCK\n");
        assert_eq!(
            source_errors(&program, "speed7"),
            ["awl::s7::block_number"],
            "{operand}"
        );
    }
}

#[test]
fn a_step5_block_number_past_255_stays_a_diagnostic() {
    let program = "OB 1\n      BE\nPB 256\n      BE\n";
    assert_eq!(
        source_errors(program, "sinumerik-840c"),
        ["awl::parse::block_number"]
    );
}
