//! STEP 7 pointers: POINTER parameters (a DB pointer of 6 bytes: DB number, area pointer) and
//! ANY parameters (10 bytes: 16#10, type, repetition factor, DB number, area pointer) as a call
//! builds them, taken apart through AR1 as STEP 7 programs do; SFC 20 BLKMOV and SFC 21 FILL
//! with their RET_VAL ("System Software for S7-300/400 System and Standard Functions");
//! `TAR1`, a block parameter given as `DB [MW 14]`, an area-crossing pointer to P.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

/// FC 1 copies the DB number and the area pointer of its two POINTER parameters to MW/MD;
/// FC 2 does the same for the type, count, DB and pointer of an ANY.
const POINTER_FCS: &str = "
FUNCTION FC 1 : VOID
VAR_INPUT
  first : POINTER;
  second : POINTER;
END_VAR
BEGIN
      L     P##first;
      T     MD 100;
      LAR1  ;
      L     W [AR1, P#0.0];
      T     MW 0;
      L     D [AR1, P#2.0];
      T     MD 2;
      L     P##second;
      LAR1  ;
      L     W [AR1, P#0.0];
      T     MW 6;
      L     D [AR1, P#2.0];
      T     MD 8;
END_FUNCTION

FUNCTION FC 2 : VOID
VAR_INPUT
  area : ANY;
END_VAR
BEGIN
      L     P##area;
      LAR1  ;
      L     B [AR1, P#0.0];
      T     MB 20;
      L     B [AR1, P#1.0];
      T     MB 21;
      L     W [AR1, P#2.0];
      T     MW 22;
      L     W [AR1, P#4.0];
      T     MW 24;
      L     D [AR1, P#6.0];
      T     MD 26;
END_FUNCTION

DATA_BLOCK DB 5
STRUCT
  a : INT;
  b : DWORD;
END_STRUCT
BEGIN
END_DATA_BLOCK
";

fn with_ob1(body: &str) -> String {
    format!(
        "{POINTER_FCS}\nORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  t0 : INT;\n  t1 : DWORD;\n  any : ANY;\nEND_VAR\nBEGIN\n{body}\nEND_ORGANIZATION_BLOCK\n"
    )
}

#[test]
fn an_fc_gets_db_pointers_on_its_callers_l_stack() {
    // The pointer to the parameter is area V; the DB pointers say DB 5 and P#DBX 2.0, then
    // none and P#M 3.1.
    passes(
        &with_ob1("      CALL FC 1 (first := P#DB5.DBX 2.0, second := M 3.1);"),
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 5\n\"MD 2\" = 0x84000010\n\
         \"MW 6\" = 0\n\"MD 8\" = 0x83000019\n",
    );
    passes(
        &with_ob1("      CALL FC 1 (first := DB5.b, second := #t1);"),
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 5\n\"MD 2\" = 0x84000010\n\"MW 6\" = 0\n",
    );
}

#[test]
fn a_callers_temporary_is_area_v_for_the_callee() {
    // OB 1's temporaries start at L 0 (over its start information): t0 is L 0.
    passes(
        &with_ob1("      CALL FC 1 (first := #t0, second := P#7.1);"),
        "run = { cycles = 1 }\n[expect]\n\"MD 2\" = 0x87000000\n\"MD 8\" = 0x00000039\n\
         \"MW 0\" = 0\n",
    );
}

#[test]
fn an_any_literal_and_an_operand_become_ten_bytes() {
    passes(
        &with_ob1("      CALL FC 2 (area := P#DB5.DBX 2.0 DWORD 3);"),
        "run = { cycles = 1 }\n[expect]\n\"MB 20\" = 0x10\n\"MB 21\" = 6\n\"MW 22\" = 3\n\
         \"MW 24\" = 5\n\"MD 26\" = 0x84000010\n",
    );
    passes(
        &with_ob1("      CALL FC 2 (area := DB5.a);"),
        "run = { cycles = 1 }\n[expect]\n\"MB 21\" = 5\n\"MW 22\" = 1\n\"MW 24\" = 5\n\
         \"MD 26\" = 0x84000000\n",
    );
    passes(
        &with_ob1("      CALL FC 2 (area := Q 1.2);"),
        "run = { cycles = 1 }\n[expect]\n\"MB 21\" = 1\n\"MW 22\" = 1\n\"MD 26\" = 0x8200000A\n",
    );
}

#[test]
fn an_any_variable_is_passed_as_it_is() {
    // The program builds the ANY on its L stack; the FC reads those bytes.
    let body = "      LAR1  P##any;
      L     B#16#10;
      T     B [AR1, P#0.0];
      L     B#16#04;
      T     B [AR1, P#1.0];
      L     9;
      T     W [AR1, P#2.0];
      L     0;
      T     W [AR1, P#4.0];
      L     P#M 40.0;
      T     D [AR1, P#6.0];
      CALL FC 2 (area := #any);";
    passes(
        &with_ob1(body),
        "run = { cycles = 1 }\n[expect]\n\"MB 20\" = 0x10\n\"MB 21\" = 4\n\"MW 22\" = 9\n\
         \"MW 24\" = 0\n\"MD 26\" = 0x83000140\n",
    );
}

#[test]
fn an_fb_keeps_its_pointers_in_the_instance_db() {
    let program = "
FUNCTION_BLOCK FB 1
VAR_INPUT
  target : POINTER;
  block : ANY;
END_VAR
BEGIN
      L     P##target;
      T     MD 0;
      L     DIW 0;
      T     MW 4;
      L     DID 2;
      T     MD 6;
      L     DIB 6;
      T     MB 10;
      L     DIW 8;
      T     MW 12;
      L     DID 12;
      T     MD 14;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL FB 1, DB 1 (target := P#DB7.DBX 1.0, block := P#M 10.0 BYTE 7);
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MD 0\" = 0x85000000\n\"MW 4\" = 7\n\
         \"MD 6\" = 0x84000008\n\"MB 10\" = 0x10\n\"MW 12\" = 7\n\"MD 14\" = 0x83000050\n",
    );
}

#[test]
fn load_pointer_to_a_data_block_member() {
    // `L`, `LAR1` and `LAR2` take the same area pointer (the DB number is no part of it); the
    // address registers then reach the member in the open DB.
    let program = "
DATA_BLOCK DB 3
STRUCT
  a : INT;
  b : DINT;
END_STRUCT
BEGIN
  b := L#77;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     P#DB3.b;
      T     MD 0;
      LAR1  P#DB3.b;
      TAR1  MD 4;
      LAR2  P#DB3.a;
      TAR2  MD 8;
      OPN   DB 3;
      L     D [AR1, P#0.0];
      T     MD 12;
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MD 0\" = 0x84000010\n\"MD 4\" = 0x84000010\n\
         \"MD 8\" = 0x84000000\n\"MD 12\" = 77\n",
    );
}

/// SFC 20 and SFC 21 on DB 1 (6 bytes) and DB 3 (12 bytes).
fn block_program(body: &str) -> String {
    format!(
        "DATA_BLOCK DB 1\nSTRUCT\n  w0 : WORD;\n  w1 : WORD;\n  w2 : WORD;\nEND_STRUCT\nBEGIN\n\
         w0 := W#16#ABCD;\n  w1 := W#16#1234;\n  w2 := W#16#9988;\nEND_DATA_BLOCK\n\
         DATA_BLOCK DB 3\nSTRUCT\n  d : ARRAY [0 .. 5] OF WORD;\nEND_STRUCT\nBEGIN\nEND_DATA_BLOCK\n\
         ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  ret : INT;\n  local : DWORD;\n  any : ANY;\nEND_VAR\nBEGIN\n\
         {body}\n      L #ret;\n      T MW 100;\n      L 0;\n      JC x;\n      L 1;\n\
         x:    T MW 102;\n      A BR;\n      = M 104.0;\nEND_ORGANIZATION_BLOCK\n"
    )
}

#[test]
fn fill_repeats_the_source_over_the_destination() {
    passes(
        &block_program(
            "      CALL SFC 21 (BVAL := P#DB1.DBX 0.0 WORD 3, RET_VAL := #ret, \
             BLK := P#DB3.DBX 0.0 WORD 6);",
        ),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0\n\"M 104.0\" = 1\n\
         \"DB3.DBW 0\" = 0xABCD\n\"DB3.DBW 4\" = 0x9988\n\"DB3.DBW 6\" = 0xABCD\n\
         \"DB3.DBW 10\" = 0x9988\n",
    );
    // Into a temporary double word: as much as it holds.
    passes(
        &block_program(
            "      CALL SFC 21 (BVAL := P#DB1.DBX 0.0 WORD 3, RET_VAL := #ret, BLK := #local);\n\
                   L #local;\n      T MD 0;",
        ),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0\n\"MD 0\" = 0xABCD1234\n",
    );
}

#[test]
fn blkmov_copies_as_much_as_both_areas_hold() {
    passes(
        &block_program(
            "      L DW#16#11223344;\n      T MD 10;\n\
                   CALL SFC 20 (SRCBLK := P#M 10.0 BYTE 4, RET_VAL := #ret, \
             DSTBLK := P#DB3.DBX 2.0 BYTE 8);",
        ),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0\n\"M 104.0\" = 1\n\
         \"DB3.DBD 2\" = 0x11223344\n\"DB3.DBW 6\" = 0\n",
    );
    passes(
        &block_program(
            "      CALL SFC 20 (SRCBLK := P#DB1.DBX 0.0 BYTE 6, RET_VAL := #ret, DSTBLK := MW 20);",
        ),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0\n\"MW 20\" = 0xABCD\n\"MW 22\" = 0\n",
    );
}

#[test]
fn the_error_codes_name_the_parameter_and_write_nothing() {
    let cases = [
        // A DB the program lacks: 8x3A.
        ("P#DB9.DBX 0.0 BYTE 2", "P#M 0.0 BYTE 2", 0x813A),
        ("P#M 0.0 BYTE 2", "P#DB9.DBX 0.0 BYTE 2", 0x833A),
        // Past the end of DB 1: area errors 8124 and 8325.
        ("P#DB1.DBX 4.0 BYTE 4", "P#M 0.0 BYTE 8", 0x8124),
        ("P#M 0.0 BYTE 4", "P#DB1.DBX 0.0 BYTE 8", 0x8325),
        // 15 bits is no whole number of bytes: 8122, 8323.
        ("P#M 0.0 BOOL 15", "P#M 10.0 BYTE 2", 0x8122),
        ("P#M 0.0 BYTE 2", "P#M 10.0 BOOL 3", 0x8323),
        // Not on a byte: 8128, 8329.
        ("P#M 0.1 BOOL 8", "P#M 10.0 BYTE 2", 0x8128),
        ("P#M 0.0 BOOL 8", "P#M 10.7 BOOL 8", 0x8329),
    ];
    for (source, destination, code) in cases {
        passes(
            &block_program(&format!(
                "      L DW#16#55555555;\n      T MD 10;\n\
                       CALL SFC 21 (BVAL := {source}, RET_VAL := #ret, BLK := {destination});"
            )),
            &format!(
                "run = {{ cycles = 1 }}\n[expect]\n\"MW 100\" = {code}\n\"M 104.0\" = 0\n\
                 \"MD 10\" = 0x55555555\n\"DB1.DBW 0\" = 0xABCD\n"
            ),
        );
    }
}

#[test]
fn an_any_variable_with_a_wrong_first_byte_is_an_area_error() {
    // The ANY built on the L stack starts with 16#01, not 16#10: 8124 for BVAL.
    let body = "      LAR1  P##any;
      L     B#16#01;
      T     B [AR1, P#0.0];
      L     B#16#02;
      T     B [AR1, P#1.0];
      L     1;
      T     W [AR1, P#2.0];
      L     0;
      T     W [AR1, P#4.0];
      L     P#M 50.0;
      T     D [AR1, P#6.0];
      CALL SFC 21 (BVAL := #any, RET_VAL := #ret, BLK := P#M 0.0 BYTE 1);";
    passes(
        &block_program(body),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0x8124\n\"M 104.0\" = 0\n",
    );
    // With 16#10 it fills MB 0 from MB 50.
    let good = body.replace("L     B#16#01;", "L     B#16#10;");
    passes(
        &block_program(&format!("      L 7;\n      T MB 50;\n{good}")),
        "run = { cycles = 1 }\n[expect]\n\"MW 100\" = 0\n\"MB 0\" = 7\n",
    );
}

#[test]
fn sfc_nop_sets_br() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      CLR;\n      SAVE;\n\
                   CALL SFC -1;\n      A BR;\n      = M 0.0;\nEND_ORGANIZATION_BLOCK\n";
    // awlsim's own SFCs come with its test operations.
    passes(
        program,
        "extended = true\nrun = { cycles = 1 }\n[expect]\n\"M 0.0\" = 1\n",
    );
}

fn errors(program: &str) -> String {
    match run(program, "") {
        Err(NotRun::SourceErrors(reports, _)) => {
            reports.iter().map(awl::diagnostics::render_plain).collect()
        }
        Err(_) => panic!("the program has source errors, not others"),
        Ok(_) => panic!("the program has errors"),
    }
}

fn ob1(body: &str) -> String {
    format!(
        "ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  ret : INT;\nEND_VAR\nBEGIN\n{body}\nEND_ORGANIZATION_BLOCK\n"
    )
}

#[test]
fn block_sfc_parameters_are_checked() {
    let missing = errors(&ob1("      CALL SFC 21;"));
    assert!(missing.contains("awl::check::param_count"), "{missing}");
    assert!(missing.contains("BVAL, RET_VAL, BLK"), "{missing}");
    let unknown = errors(&ob1(
        "      CALL SFC 20 (SRCBLK := MW 0, RET_VAL := #ret, DSTBLK := MW 2, X := MW 4);",
    ));
    assert!(unknown.contains("awl::check::unknown_param"), "{unknown}");
    assert!(unknown.contains("SRCBLK, RET_VAL, DSTBLK"), "{unknown}");
    let twice = errors(&ob1(
        "      CALL SFC 20 (SRCBLK := MW 0, RET_VAL := #ret, DSTBLK := MW 2, DSTBLK := MW 4);",
    ));
    assert!(twice.contains("is given twice"), "{twice}");
    let ret = errors(&ob1(
        "      CALL SFC 21 (BVAL := MW 0, RET_VAL := MD 4, BLK := MW 2);",
    ));
    assert!(ret.contains("awl::check::param_mismatch"), "{ret}");
    assert!(ret.contains("an INT to write to"), "{ret}");
    let constant = errors(&ob1(
        "      CALL SFC 21 (BVAL := 5, RET_VAL := #ret, BLK := MW 2);",
    ));
    assert!(
        constant.contains("awl::check::param_mismatch"),
        "{constant}"
    );
    assert!(constant.contains("an ANY"), "{constant}");
}

#[test]
fn pointer_actuals_are_checked() {
    let fc = "FUNCTION FC 1 : VOID\nVAR_INPUT\n  p : POINTER;\nEND_VAR\nBEGIN\nEND_FUNCTION\n";
    // An ANY literal is no POINTER.
    let any = errors(&format!(
        "{fc}{}",
        ob1("      CALL FC 1 (p := P#M 0.0 BYTE 2);")
    ));
    assert!(any.contains("awl::check::param_mismatch"), "{any}");
    assert!(any.contains("a POINTER"), "{any}");
    // An FB's own variable as the actual: where it is is known only when the FB runs.
    let instance = errors(&format!(
        "{fc}FUNCTION_BLOCK FB 1\nVAR\n  v : INT;\nEND_VAR\nBEGIN\n      CALL FC 1 (p := #v);\n\
         END_FUNCTION_BLOCK\nDATA_BLOCK DB 1\nFB 1\nBEGIN\nEND_DATA_BLOCK\n{}",
        ob1("      CALL FB 1, DB 1;")
    ));
    assert!(instance.contains("awl::check::not_simulated"), "{instance}");
    // An FC's POINTER parameter passed on to another FC.
    let forwarded = errors(&format!(
        "{fc}FUNCTION FC 2 : VOID\nVAR_INPUT\n  q : POINTER;\nEND_VAR\nBEGIN\n\
         CALL FC 1 (p := #q);\nEND_FUNCTION\n{}",
        ob1("      CALL FC 2 (q := M 0.0);")
    ));
    assert!(
        forwarded.contains("awl::check::not_simulated"),
        "{forwarded}"
    );
    assert!(
        forwarded.contains("passing on the parameter"),
        "{forwarded}"
    );
}

#[test]
fn tar1_saves_accu1_into_accu2() {
    let program = ob1(
        "      LAR1 P#12.3;\n      L 111;\n      L 222;\n      TAR1;\n      T MD 0;\n\
               POP;\n      T MW 4;",
    );
    passes(
        &program,
        "run = { cycles = 1 }\n[expect]\n\"MD 0\" = 0x63\n\"MW 4\" = 222\n",
    );
}

#[test]
fn a_block_parameter_takes_its_number_from_a_word() {
    let program = "
FUNCTION_BLOCK FB 1
VAR_INPUT
  data : BLOCK_DB;
END_VAR
BEGIN
      OPN   #data;
      L     DBW 0;
      T     MW 0;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
STRUCT
  w : WORD;
END_STRUCT
BEGIN
  w := W#16#4242;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     2;
      T     MW 14;
      CALL FB 1, DB 1 (data := DB [MW 14]);
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 0x4242\n",
    );
}

#[test]
fn an_area_crossing_pointer_to_p_writes_the_outputs() {
    let program = ob1(
        "      LAR1 P#P 2.0;\n      L B#16#5A;\n      T B [AR1, P#0.0];\n      L 1;\n      T MW 50;",
    );
    passes(&program, "run = { cycles = 1 }\n[expect]\n\"MW 50\" = 1\n");
}
