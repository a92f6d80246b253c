//! STEP 7 programs with a symbol table: `"Start"` for an address, `"Valve"` for a block,
//! `"Data".member`, blocks declared by a name the table does not list, and the errors of a
//! symbol that is not there.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::frontend::{self, Frontend, Language};
use awl::runner::{self, NotRun, RunOptions};
use awl::source::{Files, SourceFile, SourceSet};

fn profile() -> &'static awl::profile::Profile {
    awl::profile::find("speed7").unwrap()
}

/// Compiles `program` with the symbol table `table` (named `table_name`, whose content tells
/// its format).
fn build(program: &str, table_name: &str, table: &str) -> Frontend {
    let mut sources = SourceSet::default();
    sources.add(SourceFile::new("p.awl", program)).unwrap();
    let tables = if table.is_empty() {
        Vec::new()
    } else {
        vec![SourceFile::new(table_name, table)]
    };
    frontend::build_with_symbols(sources, tables, Language::default(), profile())
}

fn codes(built: &Frontend) -> Vec<String> {
    use miette::Diagnostic;
    built
        .diagnostics
        .iter()
        .map(|diagnostic| {
            diagnostic
                .code()
                .map(|code| code.to_string())
                .unwrap_or_default()
        })
        .collect()
}

/// Runs `program` with the table `table` and the scenario `scenario` (its `program`,
/// `symbols` and `cpu` keys are added), from memory.
fn run(program: &str, table: &str, scenario: &str) -> Result<runner::Ran, NotRun> {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.as_bytes().to_vec());
    files.insert(PathBuf::from("table.csv"), table.as_bytes().to_vec());
    let scenario =
        format!("program = [\"p.awl\"]\nsymbols = [\"table.csv\"]\ncpu = \"speed7\"\n{scenario}");
    files.insert(PathBuf::from("s.toml"), scenario.into_bytes());
    runner::run(&RunOptions {
        scenario: Some(PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    })
}

fn passes(program: &str, table: &str, scenario: &str) {
    match run(program, table, scenario) {
        Ok(ran) => assert!(
            !ran.failed() && ran.expectations > 0,
            "{:#?}",
            ran.mismatches
        ),
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

const TABLE: &str = "Symbol;Address;Data type;Comment
Start;I 0.0;BOOL;Start button
Motor;Q 4.0;BOOL;
Speed;MW 10;INT;
Valve;FB 5;FB 5;
ValveDB;DB 5;FB 5;
Settings;DB 7;DB 7;
";

const PROGRAM: &str = r#"
FUNCTION_BLOCK "Valve"
VAR_INPUT
  open : BOOL;
END_VAR
VAR_OUTPUT
  opened : BOOL;
END_VAR
BEGIN
      A     #open;
      =     #opened;
END_FUNCTION_BLOCK

DATA_BLOCK "ValveDB" "Valve"
BEGIN
END_DATA_BLOCK

DATA_BLOCK "Settings"
STRUCT
  speed : INT := 1500;
  limits : STRUCT
    low : INT := 10;
    high : INT := 90;
  END_STRUCT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

FUNCTION "Double" : VOID
BEGIN
      L     "Speed";
      L     2;
      *I;
      T     MW 20;
END_FUNCTION

ORGANIZATION_BLOCK OB 1
BEGIN
      A     "Start";
      =     "Motor";
      L     "Settings".speed;
      T     "Speed";
      L     "Settings".limits.high;
      T     MW 14;
      CALL  "Valve", "ValveDB" (open := "Motor", opened := Q 4.1);
      UC    "Double";
      OPN   "Settings";
      L     DBW 2;
      T     MW 16;
END_ORGANIZATION_BLOCK
"#;

#[test]
fn a_program_runs_with_its_symbols() {
    passes(
        PROGRAM,
        TABLE,
        r#"run = { for = "10ms" }
[[event]]
at = "1ms"
set = { '"Start"' = 1 }
[expect]
'"Motor"' = 1
"Q 4.1" = 1
'"Speed"' = 1500
"MW 14" = 90
"MW 16" = 10
"MW 20" = 3000
"#,
    );
}

#[test]
fn the_ascii_export_and_german_addresses_work_the_same() {
    let asc = [
        ("Start", "E       0.0", "BOOL"),
        ("Motor", "A       4.0", "BOOL"),
        ("Speed", "MW     10", "INT"),
        ("Valve", "FB      5", "FB      5"),
        ("ValveDB", "DB      5", "FB      5"),
        ("Settings", "DB      7", "DB      7"),
    ]
    .iter()
    .map(|(name, address, ty)| format!("126,{name:<24}{address:<12}{ty:<10}{:<80}\r\n", ""))
    .collect::<String>();
    let built = build(PROGRAM, "plant.asc", &asc);
    assert!(!built.has_errors(), "{:?}", built.diagnostics);
    let symbols = &built.compiled.program.symbols;
    assert_eq!(symbols.decorate("I 0.0"), "I 0.0 (\"Start\")");
    assert_eq!(symbols.decorate("E 0.0"), "E 0.0 (\"Start\")");
    assert_eq!(symbols.decorate("FB 5"), "FB 5 (\"Valve\")");
}

#[test]
fn a_block_the_table_does_not_list_gets_the_first_free_number() {
    // FC 1 is in the source, FC 2 in the table: "Double" becomes FC 3, "Half" FC 4; DB 1 is
    // free for "Data".
    let program = r#"
FUNCTION FC 1 : VOID
BEGIN
      NOP   0;
END_FUNCTION

FUNCTION "Double" : VOID
BEGIN
      L     MW 0;
      L     2;
      *I;
      T     MW 2;
END_FUNCTION

FUNCTION "Half" : VOID
BEGIN
      L     "Data".value;
      T     MW 4;
END_FUNCTION

DATA_BLOCK "Data"
STRUCT
  value : INT := 7;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     21;
      T     MW 0;
      CALL  "Double";
      UC    "Half";
      CALL  FC 3;
END_ORGANIZATION_BLOCK
"#;
    let built = build(program, "t.csv", "Taken;FC 2;FC 2;\n");
    let ids: Vec<String> = built
        .compiled
        .program
        .blocks
        .iter()
        .map(|block| block.id.to_string())
        .collect();
    assert!(ids.contains(&"FC 3".to_string()), "{ids:?}");
    assert!(ids.contains(&"FC 4".to_string()), "{ids:?}");
    let symbols = &built.compiled.program.symbols;
    assert_eq!(symbols.decorate("FC 3"), "FC 3 (\"Double\")");
    assert_eq!(symbols.decorate("DB 1"), "DB 1 (\"Data\")");
    // Without any table the same numbering holds (FC 2 is then free).
    let built = build(program, "", "");
    assert!(codes(&built).is_empty(), "{:?}", built.diagnostics);
    assert_eq!(
        built.compiled.program.symbols.decorate("FC 2"),
        "FC 2 (\"Double\")"
    );
    passes(
        program,
        "Taken;FC 2;FC 2;\n",
        "run = { cycles = 1 }\n[expect]\n\"MW 2\" = 42\n\"MW 4\" = 7\n",
    );
}

#[test]
fn an_unknown_symbol_names_the_closest_and_how_to_give_a_table() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      A     \"Strat\";\n      = \"Motor\";\nEND_ORGANIZATION_BLOCK\n";
    let built = build(
        program,
        "t.csv",
        "Start;I 0.0;BOOL;\nStart2;I 0.1;BOOL;\nMotor;Q 4.0;BOOL;\n",
    );
    assert_eq!(codes(&built), ["awl::symbols::unknown"]);
    let help = format!("{:?}", built.diagnostics[0]);
    assert!(
        help.contains(r#"did you mean `\"Start\"` or `\"Start2\"`?"#),
        "{help}"
    );
    let built = build(program, "", "");
    assert_eq!(
        codes(&built),
        ["awl::symbols::unknown", "awl::symbols::unknown"]
    );
    assert!(format!("{:?}", built.diagnostics[0]).contains("--symbols FILE"));
}

#[test]
fn a_symbol_of_the_wrong_kind_is_an_error_where_it_is_used() {
    let program = r#"
ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  "Motor";
      A     "Pump";
      L     "Motor".member;
      OPN   "Pump";
END_ORGANIZATION_BLOCK
"#;
    let built = build(program, "t.csv", "Motor;Q 4.0;BOOL;\nPump;FC 3;FC 3;\n");
    assert_eq!(
        codes(&built),
        [
            "awl::symbols::wrong_kind",
            "awl::symbols::wrong_kind",
            "awl::symbols::wrong_kind",
            "awl::symbols::wrong_kind",
        ]
    );
}

#[test]
fn a_pointer_to_a_symbol_of_an_address_is_not_simulated() {
    // `P#"Data".value` is a data block member's area pointer; `P#"Motor"`, an output bit's, is
    // not simulated: the error says which pointers are.
    let program = r#"
DATA_BLOCK "Data"
STRUCT
  value : INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      LAR1  P#"Data".value;
      LAR1  P#"Motor";
END_ORGANIZATION_BLOCK
"#;
    let built = build(program, "t.csv", "Data;DB 3;DB 3;\nMotor;Q 4.0;BOOL;\n");
    assert_eq!(codes(&built), ["awl::check::operand_not_allowed"]);
    let text = format!("{:?}", built.diagnostics);
    assert!(text.contains("P##name"), "{text}");
}

#[test]
fn a_member_the_data_block_does_not_declare_is_an_error() {
    let program = r#"
DATA_BLOCK "Data"
STRUCT
  value : INT;
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     "Data".valeu;
END_ORGANIZATION_BLOCK
"#;
    let built = build(program, "t.csv", "Data;DB 3;DB 3;\n");
    assert_eq!(codes(&built), ["awl::check::undeclared_local"]);
}

#[test]
fn the_table_lines_with_errors_are_reported_and_their_uses_point_there() {
    let program = "ORGANIZATION_BLOCK OB 1\nBEGIN\n      L \"Speed\";\nEND_ORGANIZATION_BLOCK\n";
    let built = build(program, "t.csv", "Speed;MW 10;BOOL;\n");
    assert_eq!(
        codes(&built),
        ["awl::symbols::unknown", "awl::symbols::type_mismatch"]
    );
    assert!(format!("{:?}", built.diagnostics[0]).contains("(in t.csv line 1) has an error"));
}

/// A UDT by its name: declared in the source (`TYPE "MotorData"`, numbered as no table lists
/// it), a static of an FB, the element of an array, a member of a global DB's structure.
const TYPED: &str = r#"
TYPE "MotorData"
STRUCT
  speed : INT := 5;
  on : BOOL;
END_STRUCT;
END_TYPE

TYPE "Line"
STRUCT
  first : "MotorData";
  motors : ARRAY [1..2] OF "MotorData";
END_STRUCT;
END_TYPE

FUNCTION_BLOCK "Drive"
VAR
  motor : "MotorData";
END_VAR
BEGIN
      L     #motor.speed;
      L     1;
      +I;
      T     #motor.speed;
      T     MW 0;
END_FUNCTION_BLOCK

DATA_BLOCK "DriveDB" "Drive"
BEGIN
END_DATA_BLOCK

DATA_BLOCK "Plant"
STRUCT
  pump : "MotorData";
  line : "Line";
  spare : ARRAY [1..3] OF "MotorData";
END_STRUCT;
BEGIN
  line.motors[2].speed := 42;
  spare[3].speed := 7;
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  "Drive", "DriveDB";
      L     "Plant".pump.speed;
      T     MW 2;
      L     "Plant".line.motors[2].speed;
      T     MW 4;
      L     "Plant".spare[3].speed;
      T     MW 6;
      L     "Plant".line.first.speed;
      T     MW 8;
END_ORGANIZATION_BLOCK
"#;

#[test]
fn a_type_written_by_its_name_is_laid_out_as_the_udt_it_stands_for() {
    passes(
        TYPED,
        "Unused;M 9.0;BOOL;\n",
        "run = { cycles = 3 }\n[expect]\n\"MW 0\" = 8\n\"MW 2\" = 5\n\"MW 4\" = 42\n\"MW 6\" = 7\n\"MW 8\" = 5\n",
    );
    // The same types by number give the same data block: the name is only another spelling.
    let numbered = TYPED
        .replace("TYPE \"MotorData\"", "TYPE UDT 1")
        .replace("TYPE \"Line\"", "TYPE UDT 2")
        .replace(": \"MotorData\"", ": UDT 1")
        .replace("OF \"MotorData\"", "OF UDT 1")
        .replace(": \"Line\"", ": UDT 2");
    let by_name = build(TYPED, "", "");
    let by_number = build(&numbered, "", "");
    assert!(codes(&by_name).is_empty(), "{:?}", by_name.diagnostics);
    assert!(codes(&by_number).is_empty(), "{:?}", by_number.diagnostics);
    assert_eq!(
        by_name.compiled.program.symbols.decorate("UDT 1"),
        "UDT 1 (\"MotorData\")"
    );
    assert_eq!(
        format!("{:?}", by_name.compiled.program.s7.data_blocks),
        format!("{:?}", by_number.compiled.program.s7.data_blocks)
    );
}

#[test]
fn a_type_the_table_lists_takes_its_number_from_there() {
    let program = r#"
TYPE UDT 7
STRUCT
  speed : INT := 9;
END_STRUCT;
END_TYPE

DATA_BLOCK "Plant"
STRUCT
  filler : INT;
  pump : "MotorData";
END_STRUCT;
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      L     "Plant".pump.speed;
      T     MW 0;
END_ORGANIZATION_BLOCK
"#;
    passes(
        program,
        "MotorData;UDT 7;UDT 7;\n",
        "run = { cycles = 1 }\n[expect]\n\"MW 0\" = 9\n",
    );
}

#[test]
fn a_multi_instance_by_name_is_taken_as_one_by_number() {
    let program = |ty: &str| {
        format!(
            r#"
FUNCTION_BLOCK "Function Block 2"
BEGIN
      NOP   0;
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB 1
VAR
  MULTI : {ty};
END_VAR
BEGIN
      CALL  #MULTI (speed := 1);
END_FUNCTION_BLOCK
"#
        )
    };
    let by_name = build(&program("\"Function Block 2\""), "", "");
    let by_number = build(&program("FB 2"), "", "");
    // Both resolve to FB 2, which has no parameter `speed`.
    assert_eq!(codes(&by_number), ["awl::check::unknown_param"]);
    assert_eq!(codes(&by_name), codes(&by_number));
}

#[test]
fn a_type_name_that_stands_for_no_type_is_an_error() {
    let program = r#"
TYPE "MotorData"
STRUCT
  speed : INT;
END_STRUCT;
END_TYPE

FUNCTION_BLOCK FB 1
VAR
  motor : "MotorDta";
  pump : "Start";
  motors : ARRAY [1..2] OF "Nothing";
END_VAR
BEGIN
      NOP   0;
END_FUNCTION_BLOCK
"#;
    let built = build(program, "t.csv", "Start;I 0.0;BOOL;\n");
    assert_eq!(
        codes(&built),
        [
            "awl::symbols::unknown",
            "awl::symbols::wrong_kind",
            "awl::symbols::unknown",
        ]
    );
    let first = format!("{:?}", built.diagnostics[0]);
    assert!(first.contains(r#"did you mean `\"MotorData\"`"#), "{first}");
    let built = build(
        "TYPE UDT 1\nSTRUCT\n  a : \"Other\";\nEND_STRUCT;\nEND_TYPE\n",
        "",
        "",
    );
    assert_eq!(codes(&built), ["awl::symbols::unknown"]);
    assert!(format!("{:?}", built.diagnostics[0]).contains("--symbols FILE"));
}
