//! The STEP 7 source form: blocks, interfaces, data, statements, calls, and the errors with
//! their recovery.

use super::*;
use crate::step7::ast::{
    AccessWidth, CallSpec, Cmp, Combination, Condition, ConstKind, Extension, PathPart, S7Address,
    S7Area, S7Op, S7Operand, VarKind,
};
use crate::syntax::error::help_text;

fn parse_with(text: &str, options: ParseOptions) -> Parsed {
    parse(0, text, options)
}

fn parse_ok(text: &str) -> S7Unit {
    let parsed = parse_with(
        text,
        ParseOptions {
            mnemonics: None,
            extensions: true,
        },
    );
    assert!(parsed.errors.is_empty(), "{text}\n{:#?}", parsed.errors);
    parsed.unit
}

fn codes(text: &str) -> Vec<String> {
    error_codes(&parse_with(text, ParseOptions::default()).errors)
}

fn error_codes(errors: &[S7ParseError]) -> Vec<String> {
    errors.iter().map(S7ParseError::stable_code).collect()
}

fn statements(block: &S7Block) -> &[S7Statement] {
    match &block.body {
        S7Body::Logic(statements) => statements,
        other => panic!("not a logic block: {other:?}"),
    }
}

fn ops(text: &str) -> Vec<S7Op> {
    let unit = parse_ok(text);
    statements(&unit.blocks[0]).iter().map(|s| s.op).collect()
}

fn number(kind: S7BlockKind, number: u16) -> S7BlockRef {
    S7BlockRef::Number { kind, number }
}

const PROGRAM: &str = "\
ORGANIZATION_BLOCK OB 1
TITLE = Main cycle
{ S7_language := '7(1) English (USA)  15.04.2008  15:42:54' }
AUTHOR : Teacher
FAMILY : Demo
NAME : Main
VERSION : 0.1
KNOW_HOW_PROTECT

VAR_TEMP
  OB1_EV_CLASS : BYTE ;
  info : ARRAY [1..10, 0..3] OF INT ;
END_VAR
BEGIN
NETWORK
TITLE = Motor
      A     I      0.1; // start
      AN    I      0.2;
      =     Q      4.0;
NETWORK
TITLE =
      CALL FC 1 (
           SPEED := MW 10,
           DONE  := M 0.0);
END_ORGANIZATION_BLOCK

FUNCTION FC 1 : INT
VAR_INPUT
  SPEED : INT ;
END_VAR
VAR_OUTPUT
  DONE : BOOL ;
END_VAR
BEGIN
      L     #SPEED;
      T     #RET_VAL;
END_FUNCTION
";

#[test]
fn blocks_with_headers_interfaces_and_networks() {
    let unit = parse_ok(PROGRAM);
    assert_eq!(unit.mnemonics, MnemonicSet::English);
    assert_eq!(unit.blocks.len(), 2);
    let ob = &unit.blocks[0];
    assert_eq!(
        (ob.kind, &ob.name),
        (S7BlockKind::Ob, &number(S7BlockKind::Ob, 1))
    );
    assert!(ob.end.is_some());
    assert_eq!(ob.interface.len(), 1);
    assert_eq!(ob.interface[0].kind, VarKind::Temp);
    assert_eq!(
        ob.interface[0].vars[1].ty,
        DataType::Array {
            dims: vec![(1, 10), (0, 3)],
            element: Box::new(DataType::Int)
        }
    );
    let body = statements(ob);
    assert_eq!(body.len(), 4);
    assert_eq!(body[0].network, 1);
    assert_eq!(body[3].network, 2);
    assert_eq!(body[3].op, S7Op::Call);
    let call = body[3].call.as_ref().unwrap();
    assert_eq!(call.params.len(), 2);
    assert_eq!(call.params[0].name.text, "SPEED");
    let fc = &unit.blocks[1];
    assert_eq!(fc.return_type, Some(DataType::Int));
    assert_eq!(
        fc.interface.iter().map(|s| s.kind).collect::<Vec<_>>(),
        [VarKind::Input, VarKind::Output]
    );
    let S7Operand::Local(path) = &statements(fc)[0].operand else {
        panic!()
    };
    assert!(matches!(&path[0], PathPart::Member(name) if name.text == "SPEED"));
}

#[test]
fn function_blocks_data_blocks_and_types() {
    let unit = parse_ok(
        "TYPE UDT 5
  STRUCT
    on : BOOL ;
    speed : INT := 100 ;
  END_STRUCT ;
END_TYPE

FUNCTION_BLOCK \"Valve\"
VAR_INPUT
  open {S7_m_c := 'true'} : BOOL := TRUE;
END_VAR
VAR
  state : UDT 5 ;
  inner : FB 7 ;
  tim : SFB 4 ;
  name : STRING [16] := 'valve';
  text : STRING ;
  list : ARRAY [0..4] OF DINT := 1, 2, 3 (0);
  nested : STRUCT
     a : WORD := W#16#00FF;
     b : ARRAY [1..2] OF STRUCT
        c : REAL := 1.5;
     END_STRUCT ;
  END_STRUCT ;
  t : TIMER ;
  c : COUNTER ;
  p : POINTER ;
  any : ANY ;
  db : BLOCK_DB ;
  fb : BLOCK_FB ;
  fc : BLOCK_FC ;
  when : DATE_AND_TIME ;
  day : TOD ;
END_VAR
BEGIN
      NOP 0
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
  STRUCT
    speeds : ARRAY [1..3] OF INT ;
    motor : STRUCT
       on : BOOL ;
    END_STRUCT ;
  END_STRUCT ;
BEGIN
  speeds[1] := 5;
  motor.on := TRUE;
END_DATA_BLOCK

DATA_BLOCK DB 2
  FB 1
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 3
  \"Valve\"
BEGIN
  open := FALSE;
END_DATA_BLOCK

DATA_BLOCK DB 4
  SFB 3
BEGIN
END_DATA_BLOCK
",
    );
    let [udt, fb, db1, db2, db3, db4] = unit.blocks.as_slice() else {
        panic!("{} blocks", unit.blocks.len())
    };
    let S7Body::Type(members) = &udt.body else {
        panic!()
    };
    assert_eq!(members[1].initial[0].value, 100);
    assert!(matches!(&fb.name, S7BlockRef::Symbol(name) if name.text == "Valve"));
    let statics = &fb.interface[1].vars;
    let types: Vec<&DataType> = statics.iter().map(|v| &v.ty).collect();
    assert_eq!(types[0], &DataType::Udt(5));
    assert_eq!(types[1], &DataType::Instance(S7BlockKind::Fb, 7));
    assert_eq!(types[2], &DataType::Instance(S7BlockKind::Sfb, 4));
    assert_eq!(types[3], &DataType::String(16));
    assert_eq!(types[4], &DataType::String(254));
    assert_eq!(statics[3].initial[0].bytes, b"valve");
    assert_eq!(
        statics[5]
            .initial
            .iter()
            .map(|c| c.value)
            .collect::<Vec<_>>(),
        [1, 2, 0, 0, 0]
    );
    let DataType::Struct(nested) = types[6] else {
        panic!()
    };
    assert!(
        matches!(&nested[1].ty, DataType::Array { element, .. } if matches!(**element, DataType::Struct(_)))
    );
    assert_eq!(
        &types[7..],
        [
            &DataType::Timer,
            &DataType::Counter,
            &DataType::Pointer,
            &DataType::Any,
            &DataType::BlockDb,
            &DataType::BlockFb,
            &DataType::BlockFc,
            &DataType::DateAndTime,
            &DataType::TimeOfDay
        ]
    );
    assert_eq!(fb.interface[0].vars[0].initial[0].kind, ConstKind::Bool);
    let S7Body::Data {
        instance_of,
        members,
        initial,
    } = &db1.body
    else {
        panic!()
    };
    assert!(instance_of.is_none());
    assert_eq!(members.len(), 2);
    assert_eq!(initial[0].path[1], PathPart::Index(vec![1]));
    assert_eq!(initial[1].path.len(), 2);
    let instance = |block: &S7Block| match &block.body {
        S7Body::Data { instance_of, .. } => instance_of.clone(),
        _ => None,
    };
    assert_eq!(instance(db2), Some(number(S7BlockKind::Fb, 1)));
    assert!(matches!(instance(db3), Some(S7BlockRef::Symbol(_))));
    assert_eq!(instance(db4), Some(number(S7BlockKind::Sfb, 3)));
}

#[test]
fn statements_with_labels_brackets_and_special_operands() {
    let unit = parse_ok(
        "FUNCTION FC 2 : VOID
BEGIN
M1:   A(
      O     I 0.0
      O     I 0.1
      )
      JC    M1
LOOP:
      L     STW
      T     STW
      OPN   DI 2
      OPN   DB [MW 2]
      LAR1  AR2
      L     DBNO
      RND+
      + 5
      +AR1  P#2.0
      ==I
      A     ==0
      O     OV
      MCR(
      )MCR
      JL    END
      JU    M1
      JU    LOOP
END:  NOP 0
      BE
END_FUNCTION
",
    );
    let body = statements(&unit.blocks[0]);
    let ops: Vec<S7Op> = body.iter().map(|s| s.op).collect();
    use S7Op::*;
    assert_eq!(
        ops,
        [
            Bracket(Combination::And),
            Logic(Combination::Or),
            Logic(Combination::Or),
            CloseBracket,
            JumpIfRlo,
            LoadStatusWord,
            TransferStatusWord,
            OpenInstanceDb,
            OpenDb,
            LoadAr1,
            Load,
            RoundUp,
            AddConstant,
            AddAr1,
            CmpInt(Cmp::Eq),
            Logic(Combination::And),
            Logic(Combination::Or),
            McrOpen,
            McrClose,
            JumpList,
            JumpAlways,
            JumpAlways,
            Nop,
            BlockEnd
        ]
    );
    assert_eq!(body[0].label.as_ref().unwrap().text, "M1");
    // A label alone on its line belongs to the next statement.
    assert_eq!(body[5].label.as_ref().unwrap().text, "LOOP");
    assert_eq!(body[9].operand, S7Operand::AddressRegister(2));
    assert_eq!(body[15].operand, S7Operand::Condition(Condition::Zero));
    assert_eq!(body[16].operand, S7Operand::Condition(Condition::Overflow));
    assert!(matches!(&body[19].operand, S7Operand::Label(name) if name.text == "END"));
}

#[test]
fn calls_with_instances_and_parameter_lists() {
    let unit = parse_ok(
        "ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FB     1 , DB     1 (
           Start := #x,
           Time  := S5T#7S,
           Tim   := T 12,
           Area  := P#M 0.0 BYTE 2
      );
      CALL  SFC 46
      CALL  SFB 4, DB 4
      CALL  \"Valve\"
      CALL  #motor (IN := TRUE)
      CALL  FC 3 ()
END_ORGANIZATION_BLOCK
",
    );
    let body = statements(&unit.blocks[0]);
    let call = |index: usize| -> &CallSpec { body[index].call.as_ref().unwrap() };
    assert_eq!(call(0).block, number(S7BlockKind::Fb, 1));
    assert_eq!(call(0).instance, Some(number(S7BlockKind::Db, 1)));
    assert_eq!(call(0).params.len(), 4);
    assert!(matches!(
        &call(0).params[1].actual,
        S7Operand::Constant(c) if c.kind == ConstKind::S5Time && c.value == 0x0700
    ));
    assert!(matches!(
        &call(0).params[2].actual,
        S7Operand::Address(S7Address {
            area: S7Area::Timer,
            byte: 12,
            ..
        })
    ));
    assert!(matches!(
        &call(0).params[3].actual,
        S7Operand::Constant(c) if c.kind == ConstKind::AnyPointer
    ));
    assert_eq!(
        body[0].operand,
        S7Operand::Block(number(S7BlockKind::Fb, 1))
    );
    assert_eq!(call(1).block, number(S7BlockKind::Sfc, 46));
    assert_eq!(call(2).instance, Some(number(S7BlockKind::Db, 4)));
    assert!(matches!(&call(3).block, S7BlockRef::Symbol(name) if name.text == "Valve"));
    assert_eq!(call(4).multi_instance.as_ref().unwrap().text, "motor");
    assert_eq!(call(4).params.len(), 1);
    assert!(call(5).params.is_empty());
}

#[test]
fn a_flat_file_is_ob_1() {
    let unit = parse_ok("\n  L 5\n  T MW 0\n");
    assert_eq!(unit.blocks.len(), 1);
    let ob = &unit.blocks[0];
    assert_eq!(ob.name, number(S7BlockKind::Ob, 1));
    assert_eq!(statements(ob).len(), 2);
    assert_eq!(ob.header, statements(ob)[0].span);
    assert!(parse_ok("// nothing\n").blocks.is_empty());
}

#[test]
fn semicolons_are_optional_at_line_ends_and_may_join_statements() {
    assert_eq!(
        ops("L 1; T MW 0;\nL 2\nT MW 2"),
        [S7Op::Load, S7Op::Transfer, S7Op::Load, S7Op::Transfer]
    );
}

#[test]
fn german_files_are_detected() {
    let unit = parse_ok(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n  U E 0.0\n  SPB M1\n  L EW 2\n  T AW 4\nM1: BEA\nEND_ORGANIZATION_BLOCK\n",
    );
    assert_eq!(unit.mnemonics, MnemonicSet::German);
    let body = statements(&unit.blocks[0]);
    assert_eq!(body[0].op, S7Op::Logic(Combination::And));
    assert!(matches!(
        body[0].operand,
        S7Operand::Address(S7Address {
            area: S7Area::Input,
            ..
        })
    ));
    assert!(matches!(
        body[3].operand,
        S7Operand::Address(S7Address {
            area: S7Area::Output,
            width: AccessWidth::Word,
            ..
        })
    ));
    assert_eq!(body[4].op, S7Op::BlockEndUnconditional);
}

#[test]
fn a_block_of_calls_only_is_detected_by_its_actual_parameters() {
    let unit = parse_ok(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n  CALL FC 1 (\n    fault := E 10.0,\n    lamp := A 10.0)\nEND_ORGANIZATION_BLOCK\n",
    );
    assert_eq!(unit.mnemonics, MnemonicSet::German);
}

#[test]
fn the_forced_set_reads_ambiguous_words() {
    let text = "SE T 1\n";
    let english = parse_with(text, ParseOptions::default());
    let german = parse_with(
        text,
        ParseOptions {
            mnemonics: Some(MnemonicSet::German),
            extensions: false,
        },
    );
    let op = |parsed: &Parsed| statements(&parsed.unit.blocks[0])[0].op;
    assert_eq!(op(&english), S7Op::TimerExtendedPulse);
    assert_eq!(op(&german), S7Op::TimerOnDelay);
}

#[test]
fn mixing_the_sets_is_one_error_at_the_first_foreign_word() {
    let parsed = parse_with(
        "A I 0.0\nA I 0.1\nU E 0.2\nSPA M1\nM1: NOP 0\n",
        ParseOptions::default(),
    );
    assert_eq!(parsed.errors.len(), 1, "{:#?}", parsed.errors);
    let S7ParseError::MixedMnemonics {
        word,
        help,
        decided_by,
        ..
    } = &parsed.errors[0]
    else {
        panic!("{:?}", parsed.errors[0])
    };
    assert_eq!(word, "U");
    assert!(help.as_ref().unwrap().contains("`A`"));
    assert!(decided_by.is_some());
    // The foreign lines are still understood.
    assert_eq!(statements(&parsed.unit.blocks[0]).len(), 5);
}

#[test]
fn awlsims_sfb_minus_1_is_a_block_and_its_instance_dbs_fb_with_the_extensions() {
    let unit = parse_ok(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\nCALL SFB -1, DB 1\nEND_ORGANIZATION_BLOCK\n\
         DATA_BLOCK DB 1\nSFB -1\nBEGIN\nEND_DATA_BLOCK\n",
    );
    let sfb = S7BlockRef::Number {
        kind: S7BlockKind::Sfb,
        number: u16::MAX,
    };
    let call = statements(&unit.blocks[0])[0]
        .call
        .as_ref()
        .expect("a call");
    assert_eq!(call.block, sfb);
    let S7Body::Data { instance_of, .. } = &unit.blocks[1].body else {
        panic!("a DB")
    };
    assert_eq!(instance_of.as_ref(), Some(&sfb));
    // awlsim has no other negative SFB.
    let parsed = parse_with(
        "CALL SFB -2, DB 1\n",
        ParseOptions {
            mnemonics: None,
            extensions: true,
        },
    );
    assert_eq!(parsed.errors.len(), 1, "{:#?}", parsed.errors);
}

#[test]
fn test_extensions_only_when_enabled() {
    let text = "__STWRST\n__ASSERT== __ACCU 1, 5\n__ASSERT>= MW 0, L#3\n__SLEEP 10\n__FEATURE 1, 2\nL __CNST_PI\n";
    let unit = parse_ok(text);
    let body = statements(&unit.blocks[0]);
    assert_eq!(body[0].op, S7Op::ResetStatusWord);
    assert_eq!(body[1].op, S7Op::Assert(Cmp::Eq));
    assert!(matches!(
        &body[1].operand,
        S7Operand::Pair(a, _) if **a == S7Operand::Extension(Extension::Accu(1))
    ));
    assert_eq!(body[2].op, S7Op::Assert(Cmp::Ge));
    assert_eq!(body[3].operand, S7Operand::Number(10));
    assert_eq!(
        body[4].operand,
        S7Operand::Pair(
            Box::new(S7Operand::Number(1)),
            Box::new(S7Operand::Number(2))
        )
    );
    assert_eq!(body[5].operand, S7Operand::Extension(Extension::Pi));
    let off = codes(text);
    assert_eq!(off.len(), 6);
    assert!(
        off.iter()
            .all(|code| code == "awl::s7::extension_not_enabled")
    );
}

#[test]
fn crlf_and_latin1_text() {
    let unit = parse_ok(
        "FUNCTION FC 1 : VOID\r\nVAR_TEMP\r\n  Größe : INT;\r\nEND_VAR\r\nBEGIN\r\n  L #Größe\r\nEND_FUNCTION\r\n",
    );
    assert_eq!(statements(&unit.blocks[0]).len(), 1);
}

#[test]
fn no_prefix_of_a_program_panics() {
    for end in (0..PROGRAM.len()).filter(|end| PROGRAM.is_char_boundary(*end)) {
        let _ = parse_with(&PROGRAM[..end], ParseOptions::default());
    }
}

// Errors, each with its code, and recovery.

#[test]
fn every_bad_line_is_reported_and_the_rest_still_parses() {
    let parsed = parse_with(
        "ORGANIZATION_BLOCK OB 1\nBEGIN\n  A I 0.0\n  JUU M1\n  L W#16#XYZ\n  A I 9.9\n  = Q 4.0\nEND_ORGANIZATION_BLOCK\n",
        ParseOptions::default(),
    );
    assert_eq!(
        error_codes(&parsed.errors),
        [
            "awl::s7::unknown_operation",
            "awl::s7::bad_constant",
            "awl::s7::bad_address"
        ]
    );
    let body = statements(&parsed.unit.blocks[0]);
    assert_eq!(
        body.iter().map(|s| s.op).collect::<Vec<_>>(),
        [S7Op::Logic(Combination::And), S7Op::Assign]
    );
    let help = help_text(&parsed.errors[0]);
    assert!(help.contains("`JU`"), "{help}");
}

#[test]
fn bad_declarations_are_dropped_one_by_one() {
    let parsed = parse_with(
        "FUNCTION_BLOCK FB 1\nVAR\n  a : INT;\n  b : INTT;\n  c INT;\n  d : ARRAY [5..1] OF INT;\n  e : STRING [300];\n  f : BOOL;\nEND_VAR\nBEGIN\nEND_FUNCTION_BLOCK\n",
        ParseOptions::default(),
    );
    assert_eq!(
        error_codes(&parsed.errors),
        [
            "awl::s7::unknown_type",
            "awl::s7::unexpected_token",
            "awl::s7::bad_declaration",
            "awl::s7::bad_declaration"
        ]
    );
    let vars = &parsed.unit.blocks[0].interface[0].vars;
    assert_eq!(
        vars.iter()
            .map(|v| v.name.text.as_str())
            .collect::<Vec<_>>(),
        ["a", "f"]
    );
    let help = help_text(&parsed.errors[0]);
    assert!(help.contains("`INT`"), "{help}");
}

#[test]
fn a_missing_end_is_one_error_and_the_next_block_still_parses() {
    let parsed = parse_with(
        "FUNCTION FC 1 : VOID\nBEGIN\n  NOP 0\nFUNCTION FC 2 : VOID\nBEGIN\n  NOP 0\nEND_FUNCTION\n",
        ParseOptions::default(),
    );
    assert_eq!(parsed.errors.len(), 1);
    assert_eq!(parsed.errors[0].stable_code(), "awl::s7::unclosed_block");
    assert_eq!(parsed.unit.blocks.len(), 2);
    assert!(parsed.unit.blocks[0].end.is_none());
    assert_eq!(
        codes("FUNCTION_BLOCK FB 1\nVAR\n  a : INT;\nBEGIN\nEND_FUNCTION_BLOCK\n"),
        ["awl::s7::unclosed_block"]
    );
}

#[test]
fn block_level_errors() {
    assert_eq!(
        codes("FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION_BLOCK\n"),
        ["awl::s7::mismatched_end"]
    );
    assert_eq!(
        codes("stray text\nmore\nFUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION\n"),
        ["awl::s7::outside_block"]
    );
    assert_eq!(
        codes("FUNCTION FC 70000 : VOID\nBEGIN\nEND_FUNCTION\n"),
        ["awl::s7::block_number"]
    );
    assert_eq!(
        codes("FUNCTION FB 1 : VOID\nBEGIN\nEND_FUNCTION\n"),
        ["awl::s7::unexpected_token"]
    );
}

#[test]
fn statement_errors() {
    assert_eq!(codes("LOOPS: NOP 0\n"), ["awl::s7::bad_label"]);
    assert_eq!(codes("CALL SFC -1\n"), ["awl::s7::block_number"]);
    assert_eq!(codes("CALL SFB -1, DB 1\n"), ["awl::s7::block_number"]);
    assert_eq!(codes("L\n"), ["awl::s7::missing_operand"]);
    assert_eq!(codes("A X 1.0\n"), ["awl::s7::unknown_operand"]);
    assert_eq!(codes("L 5 6\n"), ["awl::s7::unexpected_token"]);
    assert_eq!(codes("A § 1\n"), ["awl::s7::unexpected_character"]);
    assert_eq!(codes("L 99999999999\n"), ["awl::s7::constant_range"]);
    assert_eq!(codes("L S5T#3H\n"), ["awl::s7::constant_range"]);
    assert_eq!(codes("L S5T#3X\n"), ["awl::s7::bad_constant"]);
}

#[test]
fn step5_spellings_are_named_with_the_step7_form() {
    let help = |text: &str| {
        let parsed = parse_with(text, ParseOptions::default());
        assert_eq!(parsed.errors.len(), 1, "{text}: {:#?}", parsed.errors);
        assert_eq!(
            parsed.errors[0].stable_code(),
            "awl::s7::step5_spelling",
            "{text}"
        );
        help_text(&parsed.errors[0])
    };
    assert!(help("JU PB 3\n").contains("`CALL FC 3`"));
    assert!(help("SPA PB 3\nU E 0.0\n").contains("`CALL FC 3`"));
    assert!(help("L KF +5\n").contains("`5`"));
    assert!(help("L KH 00FF\n").contains("`W#16#00FF`"));
    assert!(help("L KT 50.1\n").contains("`S5T#5S`"));
    assert!(help("L DW 4\n").contains("`DBW 8`"));
    assert!(help("A D 0.1\n").contains("`DBX 1.1`"));
    assert!(help("A F 1.0\n").contains("`M 1.0`"));
    assert!(help("DES :EIN I BI\n").contains("VAR_INPUT"));
    assert!(help("BEZ :EIN E BI\n").contains("VAR_INPUT"));
    // `BEB` and `BEA` are STEP 7 too.
    assert!(codes("U E 0.0\nBEB\nBEA\n").is_empty());
}

#[test]
fn a_type_written_by_its_symbol_keeps_its_name_for_the_compiler() {
    let unit = parse_ok(
        "FUNCTION_BLOCK FB 1\nVAR\n  motor : \"MotorData\";\n  motors : ARRAY [1..4] OF \"Motor Data\";\n  MULTI : \"Function Block 2\";\nEND_VAR\nBEGIN\nEND_FUNCTION_BLOCK\n",
    );
    let types: Vec<&DataType> = unit.blocks[0].interface[0]
        .vars
        .iter()
        .map(|v| &v.ty)
        .collect();
    let name = |ty: &DataType| match ty {
        DataType::Named(name) => name.text.clone(),
        DataType::Array { element, .. } => match &**element {
            DataType::Named(name) => name.text.clone(),
            other => panic!("{other:?}"),
        },
        other => panic!("{other:?}"),
    };
    assert_eq!(
        types.into_iter().map(name).collect::<Vec<_>>(),
        ["MotorData", "Motor Data", "Function Block 2"]
    );
}
