//! STEP 7 multi-instances: an FB declares `name : FB n;` in its static section, the instance's
//! data lie inside the caller's instance DB, and `CALL #name (…)` runs FB n with the same DI and
//! AR2 at the instance's offset ("Programming with STEP 7", multiple instances; STL manual,
//! `CALL`). Also the FC calls around it: actuals copied to the L stack, `P##param`, AR2 back
//! after the call, `UC FC [MW n]`.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

/// FB 2 (a counter with an inner FB 3) twice inside FB 1; FB 1's instance DB 1 holds both.
/// FB 3 (2 bytes: `seen`) lies at 8 in FB 2, which takes 10 bytes: `add` 0, `total` 2,
/// `count` 4, `inner` 8. FB 1: `guard` 0, `left` 2, `right` 12, `ar2_left` 22.
const TWO_INSTANCES: &str = "
FUNCTION_BLOCK FB 3
VAR
  seen : INT;
END_VAR
BEGIN
      L     #seen;
      + 1;
      T     #seen;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB 2
VAR
  count : DINT;
  inner : FB 3;
END_VAR
VAR_INPUT
  add : INT;
END_VAR
VAR_OUTPUT
  total : INT;
END_VAR
BEGIN
      TAR2  MD 100;
      L     #count;
      L     #add;
      +D    ;
      T     #count;
      T     #total;
      CALL  #inner;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB 1
VAR
  guard : WORD;
  left : FB 2;
  right : FB 2;
  ar2_left : DWORD;
END_VAR
BEGIN
      L     W#16#BEEF;
      T     #guard;
      CALL  #left (add := 1, total := MW 20);
      L     MD 100;
      T     #ar2_left;
      CALL  #right (add := 10, total := MW 22);
      TAR2  MD 104;
      L     DINO;
      T     MW 30;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FB 1, DB 1;
END_ORGANIZATION_BLOCK
";

#[test]
fn two_multi_instances_of_one_fb_keep_their_own_data() {
    // Three cycles: left adds 1, right 10; each inner FB 3 counts its calls.
    passes(
        TWO_INSTANCES,
        "run = { cycles = 3 }\n[expect]\n\"MW 20\" = 3\n\"MW 22\" = 30\n\
         \"DB1.DBW 0\" = 0xBEEF\n\
         \"DB1.DBW 2\" = 1\n\"DB1.DBW 4\" = 3\n\"DB1.DBD 6\" = 3\n\"DB1.DBW 10\" = 3\n\
         \"DB1.DBW 12\" = 10\n\"DB1.DBW 14\" = 30\n\"DB1.DBD 16\" = 30\n\"DB1.DBW 20\" = 3\n\
         \"MW 30\" = 1\n",
    );
}

#[test]
fn ar2_points_at_the_instance_and_comes_back() {
    // Inside `left` AR2 is P#DBX 2.0; inside `right` P#DBX 12.0 (MD 100, the last); after
    // the calls FB 1's own P#DBX 0.0.
    passes(
        TWO_INSTANCES,
        "run = { cycles = 1 }\n[expect]\n\"DB1.DBD 22\" = 0x84000010\n\
         \"MD 100\" = 0x84000060\n\"MD 104\" = 0x84000000\n",
    );
}

#[test]
fn a_multi_instance_call_of_an_undeclared_name_suggests_the_close_one() {
    let program = TWO_INSTANCES.replace("CALL  #right", "CALL  #rigxt");
    let Err(NotRun::SourceErrors(reports, _)) = run(&program, "run = { cycles = 1 }\n") else {
        panic!("an undeclared multi-instance must be a source error");
    };
    let text = format!("{reports:?}");
    assert!(text.contains("undeclared_local"), "{text}");
    assert!(text.contains("did you mean `#right`?"), "{text}");
}

#[test]
fn calling_a_variable_that_is_no_instance_is_an_error() {
    let program = TWO_INSTANCES.replace("CALL  #right", "CALL  #guard");
    let Err(NotRun::SourceErrors(reports, _)) = run(&program, "run = { cycles = 1 }\n") else {
        panic!("CALL of a WORD must be a source error");
    };
    let text = format!("{reports:?}");
    assert!(text.contains("operand_not_allowed"), "{text}");
    assert!(text.contains("multi-instance"), "{text}");
}

#[test]
fn an_fb_embedding_itself_is_an_error() {
    let program = TWO_INSTANCES.replace("inner : FB 3;", "inner : FB 2;");
    let Err(NotRun::SourceErrors(reports, _)) = run(&program, "run = { cycles = 1 }\n") else {
        panic!("a recursive multi-instance must be a source error");
    };
    let text = format!("{reports:?}");
    assert!(text.contains("recursive_instance"), "{text}");
}

/// An FB passes its own data and a constant to an FC: the FC sees copies on the FB's L stack
/// (its pointers are area V), and after the call AR2 is the FB's again even though the FC
/// loaded it.
const FB_TO_FC: &str = "
FUNCTION FC 1 : INT
VAR_INPUT
  value : INT;
  flag : BOOL;
END_VAR
BEGIN
      L     P##value;
      T     MD 40;
      L     P##flag;
      T     MD 44;
      L     #value;
      T     #RET_VAL;
      LAR2  P#84.0;
END_FUNCTION

FUNCTION_BLOCK FB 1
VAR_INPUT
  start : INT;
END_VAR
VAR_OUTPUT
  result : INT;
END_VAR
BEGIN
      CALL  FC 1 (value := #start, flag := TRUE, RET_VAL := #result);
      TAR2  MD 48;
      L     #result;
      T     MW 52;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FB 1, DB 1 (start := 77);
      L     2;
      T     MW 60;
      UC    FC [MW 60];
END_ORGANIZATION_BLOCK

FUNCTION FC 2 : VOID
BEGIN
      L     5;
      T     MW 62;
END_FUNCTION
";

#[test]
fn an_fb_passes_its_data_to_an_fc_as_copies_and_keeps_its_ar2() {
    passes(
        FB_TO_FC,
        "run = { cycles = 1 }\n[expect]\n\"MD 40\" = 0x87000000\n\"MD 44\" = 0x87000010\n\
         \"MD 48\" = 0x84000000\n\"MW 52\" = 77\n\"MW 62\" = 5\n",
    );
}
