//! STEP 7 programs run end to end: parameters passed as a real CPU passes them (FC: pointers
//! to the actuals; FB: copies in and out of the instance DB), the L stack per call, data block
//! members, REAL values, and the errors a run can meet.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, RunOptions};
use awl::source::Files;
use common::step7::{passes, run};

const FC_OUTPUT_IS_A_POINTER: &str = "
FUNCTION FC 1 : VOID
VAR_INPUT
  in : INT;
END_VAR
VAR_OUTPUT
  out : INT;
END_VAR
BEGIN
      L     #in;
      T     #out;
      L     MW 10;   // the actual of #out, already written
      T     MW 12;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL FC 1 (in := 42, out := MW 10);
END_ORGANIZATION_BLOCK
";

#[test]
fn an_fc_writes_its_actual_at_once() {
    passes(
        FC_OUTPUT_IS_A_POINTER,
        "run = { cycles = 1 }\n[expect]\n\"MW 10\" = 42\n\"MW 12\" = 42\n",
    );
}

const TWO_INSTANCES: &str = "
FUNCTION_BLOCK FB 1
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

DATA_BLOCK DB 1
 FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
 FB 1
BEGIN
   sum := 1000;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL FB 1, DB 1 (add := 1, total := MW 20);
      CALL FB 1, DB 2 (add := 2, total := MW 22);
END_ORGANIZATION_BLOCK
";

#[test]
fn each_instance_db_keeps_its_own_statics() {
    // Three cycles: DB 1 counts 100 + 3 × 1, DB 2 (initial 1000) 1000 + 3 × 2. The statics
    // follow the input (word 0) and the output (word 2) at byte 4.
    passes(
        TWO_INSTANCES,
        "run = { cycles = 3 }\n[expect]\n\"MW 20\" = 103\n\"MW 22\" = 1006\n\
         \"DB1.DBW 4\" = 103\n\"DB2.DBW 4\" = 1006\n",
    );
}

const LOCALS: &str = "
FUNCTION FC 2 : INT
VAR_TEMP
  scratch : INT;
END_VAR
BEGIN
      L     7;
      T     #scratch;
      L     #scratch;
      T     #RET_VAL;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
VAR_TEMP
  mine : INT;
  result : INT;
END_VAR
BEGIN
      L     5;
      T     #mine;
      CALL FC 2 (RET_VAL := #result);
      L     #mine;
      T     MW 30;
      L     #result;
      T     MW 32;
END_ORGANIZATION_BLOCK
";

#[test]
fn a_callee_has_its_own_local_data() {
    passes(
        LOCALS,
        "run = { cycles = 1 }\n[expect]\n\"MW 30\" = 5\n\"MW 32\" = 7\n",
    );
}

const MEMBERS_AND_REALS: &str = "
DATA_BLOCK DB 5
STRUCT
  count : INT := 3;
  gain : REAL := 1.5;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB5.gain;
      L     2.0;
      *R    ;
      T     MD 40;
      L     DB5.count;
      T     MW 44;
END_ORGANIZATION_BLOCK
";

#[test]
fn data_block_members_and_reals() {
    passes(
        MEMBERS_AND_REALS,
        "run = { cycles = 1 }\n[expect]\n\"MD 40\" = 3.0\n\"MW 44\" = 3\n\"DB5.DBD 2\" = 1.5\n",
    );
}

#[test]
fn sfc_46_stops_the_cpu() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL SFC 46;\nEND_ORGANIZATION_BLOCK\n";
    passes(
        program,
        "run = { cycles = 3 }\n[expect]\nmode = \"STOP\"\nstop_cause = \"STP\"\n",
    );
}

#[test]
fn a_peripheral_address_past_the_modules_is_a_source_error() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L PIW 8192;\nEND_ORGANIZATION_BLOCK\n";
    let Err(NotRun::SourceErrors(reports, _)) = run(program, "run = { cycles = 1 }\n") else {
        panic!("a source error");
    };
    assert!(format!("{reports:?}").contains("operand_range"));
}

#[test]
fn an_indirect_address_past_the_modules_stops_the_cpu() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L L#65536;\n      T MD 4;\n      \
                   L PIW [MD 4];\nEND_ORGANIZATION_BLOCK\n";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\nmode = \"STOP\"\nstop_cause = \"BCF\"\n",
    );
}

#[test]
fn a_step7_program_on_a_step5_cpu_names_the_s7_profiles() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      NOP 0;\nEND_ORGANIZATION_BLOCK\n";
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.as_bytes().to_vec());
    let outcome = runner::run(&RunOptions {
        files: vec![PathBuf::from("p.awl")],
        cpu: awl::profile::find("sinumerik-840c"),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    });
    let Err(NotRun::SourceErrors(reports, _)) = outcome else {
        panic!("a source error");
    };
    let text = format!("{reports:?}");
    assert!(
        text.contains("step7_on_step5_cpu") && text.contains("speed7"),
        "{text}"
    );
}

#[test]
fn a_call_whose_local_data_do_not_fit_the_l_stack_stops_the_cpu() {
    // FC 1 calls itself with 20000 bytes of temporaries each time: the fourth call would need
    // more than the speed7 CPU's 64 KB L stack, long before the nesting depth of 16.
    let program = "FUNCTION FC 1 : VOID\nVAR_TEMP\n  big : ARRAY [1 .. 20000] OF BYTE;\nEND_VAR\n\
                   BEGIN\n      CALL FC 1;\nEND_FUNCTION\n\n\
                   ORGANIZATION_BLOCK OB 1\nBEGIN\n      CALL FC 1;\nEND_ORGANIZATION_BLOCK\n";
    let Ok(ran) = run(program, "run = { cycles = 1 }\n") else {
        panic!("the program runs");
    };
    let stop = ran.outcome.stop.as_ref().expect("a STOP");
    assert_eq!(stop.cause.code(), "LSTACK");
    assert_eq!(stop.stack.len(), 4, "OB 1 and three FC 1: {:?}", stop.stack);
    let report = awl::diagnostics::render_plain(&runner::stop_report(&ran, stop));
    assert!(report.contains("awl::stop::lstack"), "{report}");
    assert!(
        report.contains("the local data of FC 1 need 80020 bytes of the L stack, which has 65536"),
        "{report}"
    );
    assert!(report.contains("FC 1 is called here"), "{report}");
}

#[test]
fn a_data_access_without_a_data_block_stops_with_step7_help() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L DBW 0;\nEND_ORGANIZATION_BLOCK\n";
    let Ok(ran) = run(program, "run = { cycles = 1 }\n") else {
        panic!("the program runs");
    };
    let stop = ran.outcome.stop.as_ref().expect("a STOP");
    let report = awl::diagnostics::render_plain(&runner::stop_report(&ran, stop));
    assert!(report.contains("awl::stop::lzf_data"), "{report}");
    assert!(report.contains("`OPN DB n`"), "{report}");
    assert!(!report.contains("C DB"), "{report}");
}
