//! STEP 7 complex data types: ARRAY, STRUCT, UDT, STRING and DATE_AND_TIME variables laid out
//! as STEP 7 lays them out (word alignment, a STRING's maximum and actual length bytes), their
//! elements and members by name, data blocks made from a UDT, and parameters of these types
//! ("Programming with STEP 7", data types and parameter passing): an FB's inputs and outputs
//! copied into and out of its instance DB, its in/outs and an FC's parameters passed as a
//! 6-byte DB pointer.

mod common;

use awl::runner::NotRun;
use common::step7::{passes, run};

/// The source errors of `program`, rendered.
fn errors(program: &str) -> String {
    let Err(NotRun::SourceErrors(reports, _)) = run(program, "run = { cycles = 1 }\n") else {
        panic!("expected source errors");
    };
    reports
        .iter()
        .map(|report| format!("{report:?}"))
        .collect::<Vec<_>>()
        .join("\n")
}

const LAYOUT: &str = "
TYPE UDT 2
STRUCT
  id : INT := 7;
  on : BOOL := TRUE;
END_STRUCT;
END_TYPE

DATA_BLOCK DB 1
STRUCT
  flag : BOOL;
  grid : ARRAY [1 .. 2, 0 .. 1] OF INT := 1, 2, 3, 4;
  bits : ARRAY [1 .. 10] OF BOOL;
  rows : ARRAY [4 .. 5] OF STRUCT
    w : WORD := W#16#AA;
    b : BYTE;
  END_STRUCT;
  part : UDT 2;
  name : STRING [4] := 'abc';
  text : STRING [3];
  last : INT;
END_STRUCT;
BEGIN
  bits[2] := TRUE;
  bits[10] := TRUE;
  rows[5].b := B#16#55;
  name := 'x';
  last := 99;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB1.grid[2, 1];
      T     MW 0;
      L     DB1.rows[5].w;
      T     MW 2;
      L     DB1.name[1];
      T     MB 4;
      A     DB1.bits[10];
      =     M 5.0;
      L     DB1.part.id;
      T     MW 6;
      L     99;
      T     DB1.grid[1, 0];
      OPN   DB 1;
      L     DBLG;
      T     MW 8;
END_ORGANIZATION_BLOCK
";

/// BOOL 0.0, the INT array from 2 (row by row), the BOOL array packed from 10.0 (two bytes),
/// the array of structures from 12 (4 bytes each), the UDT at 20, the STRINGs at 24 and 30
/// (their first byte the maximum length; a shorter value clears the rest), the INT at 36.
#[test]
fn arrays_structures_and_strings_lie_as_step7_lays_them_out() {
    passes(
        LAYOUT,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 4\n\"MW 2\" = 0xAA\n\"MB 4\" = 0x78\n\
         \"M 5.0\" = 1\n\"MW 6\" = 7\n\"MW 8\" = 38\n\"DB1.DBW 2\" = 99\n\"DB1.DBW 8\" = 4\n\
         \"DB1.DBW 10\" = 0x0202\n\"DB1.DBW 12\" = 0xAA\n\"DB1.DBW 16\" = 0xAA\n\
         \"DB1.DBB 18\" = 0x55\n\"DB1.DBW 20\" = 7\n\"DB1.DBB 22\" = 1\n\
         \"DB1.DBD 24\" = 0x04017800\n\"DB1.DBW 28\" = 0\n\"DB1.DBW 30\" = 0x0300\n\
         \"DB1.DBW 36\" = 99\n",
    );
}

/// `DATA_BLOCK DB n` followed by `UDT m` (or the UDT's symbol), on the next line or the same,
/// is a global DB laid out as the UDT, with its declared values.
#[test]
fn a_data_block_is_made_from_a_udt_by_number_or_name() {
    let program = "
TYPE UDT 3
STRUCT
  a : INT := 5;
  s : STRING [4] := 'ab';
  arr : ARRAY [1 .. 3] OF BYTE;
END_STRUCT;
END_TYPE

TYPE \"Motor\"
STRUCT
  speed : DINT := L#1000;
END_STRUCT;
END_TYPE

DATA_BLOCK DB 5
UDT 3
BEGIN
  arr[2] := B#16#7;
END_DATA_BLOCK

DATA_BLOCK DB 6
\"Motor\"
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 7 UDT 3
BEGIN
  a := 8;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB5.a;
      T     MW 0;
      L     DB5.arr[2];
      T     MB 2;
      L     DB5.s[2];
      T     MB 3;
      L     DB6.speed;
      T     MD 4;
      L     DB7.a;
      T     MW 8;
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 5\n\"MB 2\" = 7\n\"MB 3\" = 0x62\n\
         \"MD 4\" = 1000\n\"MW 8\" = 8\n\"DB5.DBW 2\" = 0x0402\n",
    );
}

/// An FB's ARRAY and STRING inputs are copied into its instance DB before it runs (a STRING
/// constant as a STRING of the parameter's length), its STRUCT output back after it; the DB
/// register then holds the instance DB.
#[test]
fn fb_inputs_and_outputs_of_complex_types_are_copied() {
    let program = "
FUNCTION_BLOCK FB 1
VAR_INPUT
  values : ARRAY [1 .. 3] OF INT;
  label : STRING [6];
END_VAR
VAR_OUTPUT
  result : STRUCT
    sum : INT;
    first : CHAR;
  END_STRUCT;
END_VAR
BEGIN
      L     #values[1];
      L     #values[2];
      +I    ;
      L     #values[3];
      +I    ;
      T     #result.sum;
      L     #label[1];
      T     #result.first;
      L     DIW 6;
      T     MW 10;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
STRUCT
  input : ARRAY [1 .. 3] OF INT := 10, 20, 30;
  output : STRUCT
    total : INT;
    letter : CHAR;
  END_STRUCT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FB 1, DB 1 (
        values := DB2.input,
        label := 'hello',
        result := DB2.output);
      L     DBNO;
      T     MW 0;
      L     DB2.output.total;
      T     MW 2;
      L     DB2.output.letter;
      T     MB 4;
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 1\n\"MW 2\" = 60\n\"MB 4\" = 0x68\n\
         \"MW 10\" = 0x0605\n\"DB1.DBW 2\" = 20\n",
    );
}

/// An FC's complex parameter is a DB pointer on the caller's L stack: `P##values` points there
/// (area V), the pointer holds the DB number and an area pointer; the FC reads and writes the
/// actual through it, a STRING constant lies in a copy on the caller's L stack (DB number 0,
/// area V).
#[test]
fn fc_parameters_of_complex_types_are_passed_by_db_pointer() {
    let program = "
FUNCTION FC 1 : VOID
VAR_INPUT
  values : ARRAY [1 .. 2] OF INT;
  label : STRING [8];
END_VAR
VAR_OUTPUT
  doubled : ARRAY [1 .. 2] OF INT;
END_VAR
BEGIN
      L     #values[2];
      T     MW 0;
      L     #values[1];
      L     2;
      *I    ;
      T     #doubled[1];
      L     #label[2];
      T     MB 2;
      L     P##values;
      T     MD 4;
      LAR1  ;
      L     W [AR1, P#0.0];
      T     MW 8;
      L     D [AR1, P#2.0];
      T     MD 10;
      L     P##label;
      LAR1  ;
      L     W [AR1, P#0.0];
      T     MW 14;
      L     D [AR1, P#2.0];
      LAR1  ;
      L     W [AR1, P#0.0];
      T     MW 16;
END_FUNCTION

DATA_BLOCK DB 3
STRUCT
  pad : WORD;
  input : ARRAY [1 .. 2] OF INT := 21, 22;
  output : ARRAY [1 .. 2] OF INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FC 1 (
        values := DB3.input,
        label := 'xyz',
        doubled := DB3.output);
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 22\n\"MB 2\" = 0x79\n\
         \"MD 4\" = 0x870000A0\n\"MW 8\" = 3\n\"MD 10\" = 0x84000010\n\"MW 14\" = 0\n\
         \"MW 16\" = 0x0803\n\"DB3.DBW 6\" = 42\n",
    );
}

/// An FB's in/out of a complex type is a DB pointer in its instance DB (6 bytes): the FB writes
/// the actual through it, and an FB passes its own complex parameter on to an FC.
#[test]
fn fb_in_outs_of_complex_types_are_passed_by_db_pointer() {
    let program = "
FUNCTION FC 2 : VOID
VAR_IN_OUT
  stamp : DATE_AND_TIME;
END_VAR
VAR_TEMP
  nr : WORD;
END_VAR
BEGIN
      L     P##stamp;
      LAR1  ;
      L     W [AR1, P#0.0];
      T     #nr;
      OPN   DB [#nr];
      L     D [AR1, P#2.0];
      LAR1  ;
      L     DW#16#01020304;
      T     D [AR1, P#4.0];
END_FUNCTION

FUNCTION_BLOCK FB 1
VAR_IN_OUT
  pair : ARRAY [1 .. 2] OF INT;
  stamp : DATE_AND_TIME;
END_VAR
VAR
  after : INT;
END_VAR
BEGIN
      L     #pair[1];
      L     #pair[2];
      +I    ;
      T     #pair[2];
      L     P##after;
      T     MD 0;
      CALL  FC 2 (stamp := #stamp);
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 4
STRUCT
  pair : ARRAY [1 .. 2] OF INT := 5, 6;
  stamp : DATE_AND_TIME;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FB 1, DB 1 (pair := DB4.pair, stamp := DB4.stamp);
END_ORGANIZATION_BLOCK
";
    passes(
        program,
        "run = { cycles = 1 }\n[expect]\n\"MD 0\" = 0x85000060\n\"DB4.DBW 2\" = 11\n\
         \"DB4.DBD 8\" = 0x01020304\n\"DB1.DBW 0\" = 4\n\"DB1.DBD 2\" = 0x84000000\n",
    );
}

/// The actual of a complex parameter must be a variable of the same size (any STRING for a
/// STRING) or a constant of the type; an output's actual a variable.
#[test]
fn a_complex_parameter_refuses_an_actual_of_another_type() {
    let program = "
FUNCTION FC 1 : VOID
VAR_INPUT
  values : ARRAY [1 .. 2] OF INT;
END_VAR
BEGIN
END_FUNCTION

FUNCTION_BLOCK FB 1
VAR_OUTPUT
  text : STRING [4];
END_VAR
BEGIN
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2
STRUCT
  small : ARRAY [1 .. 3] OF INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FC 1 (values := DB2.small);
      CALL  FC 1 (values := MW 0);
      CALL  FB 1, DB 1 (text := 'abc');
END_ORGANIZATION_BLOCK
";
    let text = errors(program);
    assert_eq!(text.matches("param_mismatch").count(), 3, "{text}");
    assert!(
        text.contains("a variable of type ARRAY [1..2] OF INT"),
        "{text}"
    );
    assert!(text.contains("to write"), "{text}");
}

/// A STRING's characters are indexed from 1 to its maximum length.
#[test]
fn a_string_index_past_its_length_is_an_error() {
    let program = "
DATA_BLOCK DB 1
STRUCT
  s : STRING [4];
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     DB1.s[5];
      L     DB1.s[1, 1];
END_ORGANIZATION_BLOCK
";
    let text = errors(program);
    assert!(
        text.contains("index 5 is outside the STRING's 1..4"),
        "{text}"
    );
    assert!(text.contains("a STRING takes 1 index, not 2"), "{text}");
}

/// A UDT no `TYPE` block defines, named by a declaration or a data block.
#[test]
fn an_undefined_udt_is_an_error() {
    let program = "
DATA_BLOCK DB 5
UDT 9
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 6
STRUCT
  x : ARRAY [1 .. 2] OF UDT 8;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
END_ORGANIZATION_BLOCK
";
    let text = errors(program);
    assert_eq!(text.matches("undefined_type").count(), 2, "{text}");
    assert!(text.contains("UDT 9 is not in the program"), "{text}");
    assert!(text.contains("UDT 8 is not in the program"), "{text}");
}

/// An instance DB cannot give an FB's in/out of a complex type a value: it holds the pointer
/// the call passes.
#[test]
fn an_instance_value_for_a_complex_in_out_is_an_error() {
    let program = "
FUNCTION_BLOCK FB 1
VAR_IN_OUT
  pair : ARRAY [1 .. 2] OF INT;
END_VAR
BEGIN
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
FB 1
BEGIN
  pair[1] := 3;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
END_ORGANIZATION_BLOCK
";
    let text = errors(program);
    assert!(text.contains("holds the pointer its call passes"), "{text}");
}
