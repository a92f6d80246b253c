//! The library FCs a STEP 7 program calls without writing them: the IEC functions FC 1 to
//! FC 40 ("System Software for S7-300/400 System and Standard Functions", IEC functions) and
//! the TI-S7 converting blocks FC 105 SCALE and FC 106 UNSCALE. Each block with values worked
//! out from the manual's description, its error cases (BR, the ENO of the boxes, 0), and the
//! compiler's checks of the calls.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use awl::runner::{self, NotRun, Ran, RunOptions};
use awl::source::Files;
use common::step7::run;

/// The data block every case works on, at these byte offsets: three STRING [20] (S1, S2, OUT),
/// a STRING [3], INT, DINT, REAL, the BR after the call (OK) and a BOOL result beside it, three DATE_AND_TIME, a TIME, a
/// WORD and two more REALs.
const DB: &str = "
DATA_BLOCK DB 1
STRUCT
  s1 : STRING [20];
  s2 : STRING [20];
  out : STRING [20];
  tiny : STRING [3];
  n : INT;
  d : DINT;
  r : REAL;
  ok : BOOL;
  flag : BOOL;
  t1 : DATE_AND_TIME;
  t2 : DATE_AND_TIME;
  t3 : DATE_AND_TIME;
  tm : TIME;
  w : WORD;
  r2 : REAL;
  r3 : REAL;
END_STRUCT;
BEGIN
";

const S1: usize = 0;
const S2: usize = 22;
const OUT: usize = 44;
const TINY: usize = 66;
const N: usize = 72;
const D: usize = 74;
const R: usize = 78;
const OK: usize = 82;
const T1: usize = 84;
const T3: usize = 100;
const TM: usize = 108;
const W: usize = 112;

/// DB 1 after one cycle of OB 1 running `body` (then `A BR`, `= DB1.ok`), the DB's members
/// first set by `init`.
fn after(init: &str, body: &str) -> Data {
    let program = format!(
        "{DB}{init}\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n{body}\n      A     BR;\n      \
         =     DB1.ok;\nEND_ORGANIZATION_BLOCK\n"
    );
    match run(&program, "run = { cycles = 1 }\n") {
        Ok(ran) => Data(ran.cpu.s7_db(1).expect("DB 1").to_vec()),
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

struct Data(Vec<u8>);

impl Data {
    fn text(&self, at: usize) -> String {
        let len = usize::from(self.0[at + 1]);
        String::from_utf8(self.0[at + 2..at + 2 + len].to_vec()).unwrap()
    }

    fn out(&self) -> String {
        self.text(OUT)
    }

    fn word(&self, at: usize) -> u16 {
        u16::from_be_bytes([self.0[at], self.0[at + 1]])
    }

    fn int(&self) -> i16 {
        self.word(N) as i16
    }

    fn double(&self, at: usize) -> u32 {
        u32::from_be_bytes(self.0[at..at + 4].try_into().unwrap())
    }

    fn dint(&self) -> i32 {
        self.double(D) as i32
    }

    fn real(&self, at: usize) -> f32 {
        f32::from_bits(self.double(at))
    }

    fn ok(&self) -> bool {
        self.0[OK] & 1 != 0
    }

    fn dt(&self, at: usize) -> [u8; 8] {
        self.0[at..at + 8].try_into().unwrap()
    }
}

/// The source errors of `program` (OB 1 running `body` on the DB), rendered.
fn errors(body: &str) -> String {
    let program = format!(
        "{DB}\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n{body}\nEND_ORGANIZATION_BLOCK\n"
    );
    let Err(NotRun::SourceErrors(reports, _)) = run(&program, "run = { cycles = 1 }\n") else {
        panic!("expected source errors");
    };
    reports
        .iter()
        .map(|report| format!("{report:?}"))
        .collect::<Vec<_>>()
        .join("\n")
}

const HELLO: &str = "  s1 := 'Hello World';\n  out := 'old';\n  tiny := 'abc';";

#[test]
fn the_data_block_lies_where_the_cases_read_it() {
    let data = after(
        "  s1 := 'a';\n  s2 := 'b';\n  tiny := 'c';\n  n := 1;\n  d := L#2;\n  r := 3.0;\n  \
         t1 := DT#1990-1-1-0:0:0.0;\n  t3 := DT#1990-1-1-0:0:0.0;\n  tm := T#4MS;\n  w := W#16#5;",
        "      SET;",
    );
    assert_eq!(
        (data.text(S1), data.text(S2), data.text(TINY)),
        ("a".into(), "b".into(), "c".into())
    );
    assert_eq!((data.int(), data.dint(), data.real(R)), (1, 2, 3.0));
    assert_eq!(data.dt(T1)[..3], [0x90, 0x01, 0x01]);
    assert_eq!(data.dt(T3)[..3], [0x90, 0x01, 0x01]);
    assert_eq!((data.double(TM), data.word(W)), (4, 5));
}

// FC 2 CONCAT, FC 4 DELETE, FC 17 INSERT, FC 31 REPLACE.

#[test]
fn concat_joins_and_cuts_to_the_destination() {
    let call = |to: &str| {
        format!("      CALL  \"CONCAT\" (IN1 := DB1.s1, IN2 := '!', RET_VAL := DB1.{to});")
    };
    let data = after(HELLO, &call("out"));
    assert_eq!(data.out(), "Hello World!");
    assert!(data.ok());
    let data = after(HELLO, &call("tiny"));
    assert_eq!(data.text(TINY), "Hel");
    assert!(!data.ok(), "too long for STRING [3]");
    // By number, the result written over an input.
    let data = after(
        HELLO,
        "      CALL  FC 2 (IN1 := DB1.s1, IN2 := DB1.s1, RET_VAL := DB1.s1);",
    );
    assert_eq!(data.text(S1), "Hello WorldHello Wor");
    assert!(!data.ok());
}

fn delete(l: i16, p: i16) -> Data {
    after(
        HELLO,
        &format!("      CALL  \"DELETE\" (IN := DB1.s1, L := {l}, P := {p}, RET_VAL := DB1.out);"),
    )
}

#[test]
fn delete_takes_out_l_characters_from_position_p() {
    let data = delete(6, 6);
    assert_eq!((data.out(), data.ok()), ("Hello".into(), true));
    let data = delete(3, 1);
    assert_eq!((data.out(), data.ok()), ("lo World".into(), true));
    // Past the end: to the end; L or P 0, or P past the end: IN as it is.
    assert_eq!(delete(50, 10).out(), "Hello Wor");
    assert_eq!(delete(0, 3).out(), "Hello World");
    assert_eq!(delete(3, 0).out(), "Hello World");
    assert_eq!(delete(3, 12).out(), "Hello World");
    let data = delete(-1, 3);
    assert_eq!((data.out(), data.ok()), (String::new(), false));
    let data = delete(1, -3);
    assert_eq!((data.out(), data.ok()), (String::new(), false));
}

#[test]
fn delete_cuts_a_long_result_to_ret_val_without_an_error() {
    // The manual's only error of DELETE is a negative L or P: a result longer than RET_VAL is
    // cut to its maximum length, BR stays 1.
    let data = after(
        HELLO,
        "      CALL  \"DELETE\" (IN := DB1.s1, L := 2, P := 2, RET_VAL := DB1.tiny);",
    );
    assert_eq!((data.text(TINY), data.ok()), ("Hlo".into(), true));
}

/// DB 2's number and DB 1's `n` with OB 1 running `call` with DB 2 open, then loading DBNO.
fn db_register_after(call: &str) -> (u16, i16) {
    let program = format!(
        "{DB}  s1 := 'Hello';\nEND_DATA_BLOCK\n\nDATA_BLOCK DB 2\nSTRUCT\n  x : INT;\nEND_STRUCT;\n\
         BEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      OPN   DB 2;\n{call}\n      \
         L     DBNO;\n      T     MW 0;\nEND_ORGANIZATION_BLOCK\n"
    );
    match run(&program, "run = { cycles = 1 }\n") {
        Ok(ran) => {
            let flags = 2 * usize::from(ran.cpu.program.layout.image_bytes);
            let dbno = u16::from_be_bytes([ran.cpu.image[flags], ran.cpu.image[flags + 1]]);
            (dbno, Data(ran.cpu.s7_db(1).expect("DB 1").to_vec()).int())
        }
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

#[test]
fn a_library_call_leaves_the_db_register_as_step7_s_call_does() {
    // A STRING actual of DB 1 travels in its DB pointer: DB 2 stays open.
    let (dbno, len) = db_register_after("      CALL  \"LEN\" (S := DB1.s1, RET_VAL := MW 2);");
    assert_eq!(dbno, 2);
    assert_eq!(len, 0, "the result went to MW 2");
    // An elementary actual of DB 1 is reached through the DB register: DB 1 is open after.
    let (dbno, len) = db_register_after("      CALL  \"LEN\" (S := DB1.s1, RET_VAL := DB1.n);");
    assert_eq!((dbno, len), (1, 5));
}

fn insert(p: i16) -> Data {
    after(
        "  s1 := 'Hello';\n  s2 := ' big';",
        &format!(
            "      CALL  \"INSERT\" (IN1 := DB1.s1, IN2 := DB1.s2, P := {p}, RET_VAL := DB1.out);"
        ),
    )
}

#[test]
fn insert_puts_in2_after_character_p() {
    assert_eq!(insert(5).out(), "Hello big");
    assert_eq!(insert(2).out(), "He bigllo");
    assert_eq!(insert(0).out(), " bigHello");
    let data = insert(9);
    assert_eq!((data.out(), data.ok()), ("Hello big".into(), true));
    let data = insert(-1);
    assert_eq!((data.out(), data.ok()), (String::new(), false));
    let data = after(
        HELLO,
        "      CALL  \"INSERT\" (IN1 := DB1.s1, IN2 := 'XYZXYZXYZX', P := 1, RET_VAL := DB1.out);",
    );
    assert_eq!(
        (data.out(), data.ok()),
        ("HXYZXYZXYZXello Worl".into(), false)
    );
}

fn replace(l: i16, p: i16) -> Data {
    after(
        HELLO,
        &format!(
            "      CALL  \"REPLACE\" (IN1 := DB1.s1, IN2 := 'There', L := {l}, P := {p}, \
             RET_VAL := DB1.out);"
        ),
    )
}

#[test]
fn replace_puts_in2_over_l_characters_from_p() {
    let data = replace(5, 7);
    assert_eq!((data.out(), data.ok()), ("Hello There".into(), true));
    assert_eq!(replace(5, 1).out(), "There World");
    assert_eq!(replace(0, 7).out(), "Hello ThereWorld");
    assert_eq!(replace(3, 20).out(), "Hello WorldThere");
    let data = replace(-1, 3);
    assert_eq!((data.out(), data.ok()), (String::new(), false));
    let data = replace(1, 0);
    assert_eq!((data.out(), data.ok()), (String::new(), false));
}

// FC 20 LEFT, FC 32 RIGHT, FC 26 MID, FC 21 LEN, FC 11 FIND.

fn side(name: &str, l: i16) -> Data {
    after(
        HELLO,
        &format!("      CALL  \"{name}\" (IN := DB1.s1, L := {l}, RET_VAL := DB1.out);"),
    )
}

#[test]
fn left_and_right_take_l_characters() {
    let data = side("LEFT", 5);
    assert_eq!((data.out(), data.ok()), ("Hello".into(), true));
    let data = side("RIGHT", 5);
    assert_eq!((data.out(), data.ok()), ("World".into(), true));
    assert_eq!(side("LEFT", 40).out(), "Hello World");
    assert_eq!(side("RIGHT", 0).out(), "");
    for name in ["LEFT", "RIGHT"] {
        let data = side(name, -2);
        assert_eq!((data.out(), data.ok()), (String::new(), false), "{name}");
    }
    let data = after(
        HELLO,
        "      CALL  FC 20 (IN := DB1.s1, L := 5, RET_VAL := DB1.tiny);",
    );
    assert_eq!((data.text(TINY), data.ok()), ("Hel".into(), false));
}

fn mid(l: i16, p: i16) -> Data {
    after(
        HELLO,
        &format!("      CALL  \"MID\" (IN := DB1.s1, L := {l}, P := {p}, RET_VAL := DB1.out);"),
    )
}

#[test]
fn mid_takes_l_characters_from_p() {
    let data = mid(3, 7);
    assert_eq!((data.out(), data.ok()), ("Wor".into(), true));
    assert_eq!(mid(20, 7).out(), "World");
    let data = mid(2, 12);
    assert_eq!((data.out(), data.ok()), (String::new(), true));
    for (l, p) in [(0, 1), (2, 0), (-1, 1), (1, -1)] {
        let data = mid(l, p);
        assert_eq!(
            (data.out(), data.ok()),
            (String::new(), false),
            "L {l} P {p}"
        );
    }
}

#[test]
fn len_and_find() {
    let data = after(
        HELLO,
        "      CALL  \"LEN\" (S := DB1.s1, RET_VAL := DB1.n);",
    );
    assert_eq!((data.int(), data.ok()), (11, true));
    let data = after(HELLO, "      CALL  FC 21 (S := '', RET_VAL := DB1.n);");
    assert_eq!(data.int(), 0);
    // LEN gives the current-length byte as it stands, even past the maximum length.
    let data = after(
        HELLO,
        &format!(
            "      L     9;\n      T     DB1.DBB {};\n      CALL  \"LEN\" (S := DB1.tiny, RET_VAL := DB1.n);",
            TINY + 1
        ),
    );
    assert_eq!((data.int(), data.ok()), (9, true));
    let find = |what: &str| {
        after(
            HELLO,
            &format!("      CALL  \"FIND\" (IN1 := DB1.s1, IN2 := '{what}', RET_VAL := DB1.n);"),
        )
    };
    assert_eq!(find("o").int(), 5);
    assert_eq!(find("World").int(), 7);
    assert_eq!(find("world").int(), 0, "case counts");
    assert_eq!(find("").int(), 0);
    assert!(find("xyz").ok());
}

// FC 10 EQ_STRNG … FC 29 NE_STRNG.

#[test]
fn strings_compare_by_character_codes() {
    let compare = |name: &str, s1: &str, s2: &str| {
        let data = after(
            &format!("  s1 := '{s1}';\n  s2 := '{s2}';"),
            &format!("      CALL  \"{name}\" (S1 := DB1.s1, S2 := DB1.s2, RET_VAL := DB1.flag);"),
        );
        assert!(data.ok());
        data.0[OK] & 2 != 0
    };
    let cases: [(&str, [bool; 3]); 6] = [
        // 'abc' against 'abd', 'abc', 'ab'.
        ("EQ_STRNG", [false, true, false]),
        ("NE_STRNG", [true, false, true]),
        ("LT_STRNG", [true, false, false]),
        ("LE_STRNG", [true, true, false]),
        ("GT_STRNG", [false, false, true]),
        ("GE_STRNG", [false, true, true]),
    ];
    for (name, expected) in cases {
        let found = ["abd", "abc", "ab"].map(|other| compare(name, "abc", other));
        assert_eq!(found, expected, "{name}");
    }
}

// FC 16 I_STRNG, FC 5 DI_STRNG, FC 30 R_STRNG and back.

#[test]
fn numbers_become_a_sign_and_digits() {
    let to_text = |call: &str| after(HELLO, call);
    let data = to_text("      CALL  \"I_STRNG\" (I := 123, RET_VAL := DB1.out);");
    assert_eq!((data.out(), data.ok()), ("+123".into(), true));
    let data = to_text("      CALL  \"I_STRNG\" (I := -32768, RET_VAL := DB1.out);");
    assert_eq!(data.out(), "-32768");
    let data = to_text("      CALL  \"DI_STRNG\" (I := L#-2147483648, RET_VAL := DB1.out);");
    assert_eq!((data.out(), data.ok()), ("-2147483648".into(), true));
    let data = to_text("      CALL  FC 5 (I := L#0, RET_VAL := DB1.out);");
    assert_eq!(data.out(), "+0");
    let data = to_text("      CALL  \"R_STRNG\" (IN := 1234.5, RET_VAL := DB1.out);");
    assert_eq!((data.out(), data.ok()), ("+1.2345000E+03".into(), true));
    let data = to_text("      CALL  \"R_STRNG\" (IN := -0.001, RET_VAL := DB1.out);");
    assert_eq!(data.out(), "-1.0000000E-03");
    // An output shorter than the longest result: nothing written, BR 0.
    for call in [
        "      CALL  \"I_STRNG\" (I := 1, RET_VAL := DB1.tiny);",
        "      CALL  \"DI_STRNG\" (I := L#1, RET_VAL := DB1.tiny);",
        "      CALL  \"R_STRNG\" (IN := 1.0, RET_VAL := DB1.tiny);",
    ] {
        let data = to_text(call);
        assert_eq!(
            (data.text(TINY), data.ok()),
            ("abc".into(), false),
            "{call}"
        );
    }
    // A REAL that is no number.
    let data = after(
        HELLO,
        "      L     DW#16#7FC00000;\n      T     MD 0;\n      \
         CALL  \"R_STRNG\" (IN := MD 0, RET_VAL := DB1.out);",
    );
    assert_eq!((data.out(), data.ok()), ("old".into(), false));
}

fn from_text(name: &str, text: &str) -> Data {
    let target = match name {
        "STRNG_I" => "n",
        "STRNG_DI" => "d",
        _ => "r",
    };
    after(
        &format!("  s1 := '{text}';\n  n := 7;\n  d := L#7;\n  r := 7.0;"),
        &format!("      CALL  \"{name}\" (S := DB1.s1, RET_VAL := DB1.{target});"),
    )
}

#[test]
fn strings_become_numbers() {
    let data = from_text("STRNG_I", "-123");
    assert_eq!((data.int(), data.ok()), (-123, true));
    assert_eq!(from_text("STRNG_I", "+0042").int(), 42);
    let data = from_text("STRNG_I", "40000");
    assert_eq!((data.int(), data.ok()), (32767, false), "limited");
    let data = from_text("STRNG_I", "-40000");
    assert_eq!((data.int(), data.ok()), (-32768, false));
    for bad in ["", "12a", "-", "1234567"] {
        let data = from_text("STRNG_I", bad);
        assert_eq!((data.int(), data.ok()), (7, false), "{bad:?}");
    }
    let data = from_text("STRNG_DI", "-1234567");
    assert_eq!((data.dint(), data.ok()), (-1234567, true));
    let data = from_text("STRNG_DI", "99999999999");
    assert_eq!((data.dint(), data.ok()), (i32::MAX, false));
    let data = from_text("STRNG_DI", "1.5");
    assert_eq!((data.dint(), data.ok()), (7, false));
    let data = from_text("STRNG_R", "+1.2345000E+03");
    assert_eq!((data.real(R), data.ok()), (1234.5, true));
    let data = from_text("STRNG_R", "-2.5000000E-01");
    assert_eq!(data.real(R), -0.25);
    let data = from_text("STRNG_R", "+9.9999999E+99");
    assert_eq!((data.real(R), data.ok()), (f32::MAX, false), "limited");
    for bad in ["1.5", "+1.2345000E+0", "+1,2345000E+03"] {
        let data = from_text("STRNG_R", bad);
        assert_eq!((data.real(R), data.ok()), (7.0, false), "{bad:?}");
    }
}

// FC 1 AD_DT_TM, FC 35 SB_DT_TM, FC 34 SB_DT_DT, FC 3 D_TOD_DT, FC 6–8.

/// The eight BCD bytes of a DATE_AND_TIME: year, month, day, hour, minute, second (whole),
/// weekday (1 Sunday).
fn bcd(parts: [u8; 6], weekday: u8) -> [u8; 8] {
    let b = |value: u8| ((value / 10) << 4) | (value % 10);
    [
        b(parts[0]),
        b(parts[1]),
        b(parts[2]),
        b(parts[3]),
        b(parts[4]),
        b(parts[5]),
        0,
        weekday,
    ]
}

#[test]
fn a_duration_is_added_to_and_taken_from_an_instant() {
    let data = after(
        "  t1 := DT#2024-2-28-23:00:00.000;",
        "      CALL  \"AD_DT_TM\" (T := DB1.t1, D := T#2H, RET_VAL := DB1.t3);",
    );
    // 2024 is a leap year: 2024-02-29, a Thursday (5).
    assert_eq!(
        (data.dt(T3), data.ok()),
        (bcd([24, 2, 29, 1, 0, 0], 5), true)
    );
    let data = after(
        "  t1 := DT#2024-3-1-0:0:0.0;",
        "      CALL  \"SB_DT_TM\" (IN1 := DB1.t1, IN2 := T#1D, RET_VAL := DB1.t3);",
    );
    assert_eq!(data.dt(T3), bcd([24, 2, 29, 0, 0, 0], 5));
    // Beyond 2089-12-31-23:59:59.999 and before 1990-01-01: the limit, BR 0.
    let data = after(
        "  t1 := DT#2089-12-31-23:00:00.000;",
        "      CALL  FC 1 (T := DB1.t1, D := T#2H, RET_VAL := DB1.t3);",
    );
    assert_eq!(
        data.dt(T3),
        [0x89, 0x12, 0x31, 0x23, 0x59, 0x59, 0x99, 0x97]
    );
    assert!(!data.ok(), "2089-12-31 was a Saturday (7)");
    let data = after(
        "  t1 := DT#1990-1-1-0:0:0.5;",
        "      CALL  FC 35 (IN1 := DB1.t1, IN2 := T#1S, RET_VAL := DB1.t3);",
    );
    assert_eq!(
        (data.dt(T3), data.ok()),
        (bcd([90, 1, 1, 0, 0, 0], 2), false)
    );
    // A DATE_AND_TIME that is none (month 13): BR 0, the result as it was.
    let data = after(
        "  t3 := DT#2000-1-1-0:0:0.0;",
        "      L     DW#16#24131200;\n      T     DB1.DBD 84;\n      \
         CALL  FC 1 (T := DB1.t1, D := T#1S, RET_VAL := DB1.t3);",
    );
    assert_eq!(
        (data.dt(T3), data.ok()),
        (bcd([0, 1, 1, 0, 0, 0], 7), false)
    );
}

#[test]
fn the_time_between_two_instants() {
    let data = after(
        "  t1 := DT#2024-3-1-0:0:0.0;\n  t2 := DT#2024-2-28-23:00:00.250;",
        "      CALL  \"SB_DT_DT\" (IN1 := DB1.t1, IN2 := DB1.t2, RET_VAL := DB1.tm);",
    );
    assert_eq!(
        (data.double(TM) as i32, data.ok()),
        (25 * 3_600_000 - 250, true)
    );
    let data = after(
        "  t1 := DT#2024-2-28-23:00:00.250;\n  t2 := DT#2024-3-1-0:0:0.0;",
        "      CALL  FC 34 (IN1 := DB1.t1, IN2 := DB1.t2, RET_VAL := DB1.tm);",
    );
    assert_eq!(data.double(TM) as i32, -(25 * 3_600_000 - 250));
    // Decades apart: beyond a TIME (24 days), limited, BR 0.
    let data = after(
        "  t1 := DT#2080-1-1-0:0:0.0;\n  t2 := DT#1990-1-1-0:0:0.0;",
        "      CALL  FC 34 (IN1 := DB1.t1, IN2 := DB1.t2, RET_VAL := DB1.tm);",
    );
    assert_eq!((data.double(TM) as i32, data.ok()), (i32::MAX, false));
    let data = after(
        "  t1 := DT#1990-1-1-0:0:0.0;\n  t2 := DT#2080-1-1-0:0:0.0;",
        "      CALL  FC 34 (IN1 := DB1.t1, IN2 := DB1.t2, RET_VAL := DB1.tm);",
    );
    assert_eq!((data.double(TM) as i32, data.ok()), (i32::MIN, false));
}

#[test]
fn dates_and_times_of_day_combine_and_split() {
    let data = after(
        "",
        "      CALL  \"D_TOD_DT\" (IN1 := D#2024-3-15, IN2 := TOD#12:30:00.000, RET_VAL := DB1.t3);",
    );
    // 2024-03-15 was a Friday (6).
    assert_eq!(
        (data.dt(T3), data.ok()),
        (bcd([24, 3, 15, 12, 30, 0], 6), true)
    );
    // A time of day past midnight: BR 0, nothing written.
    let data = after(
        "",
        "      L     L#86400000;\n      T     MD 0;\n      \
         CALL  FC 3 (IN1 := D#2024-3-15, IN2 := MD 0, RET_VAL := DB1.t3);",
    );
    assert_eq!((data.dt(T3), data.ok()), ([0; 8], false));
    let init = "  t1 := DT#2024-3-15-12:30:00.000;";
    let data = after(
        init,
        "      CALL  \"DT_DATE\" (IN := DB1.t1, RET_VAL := DB1.n);",
    );
    // 12492 days after 1990-01-01.
    assert_eq!((data.int(), data.ok()), (12492, true));
    let data = after(
        init,
        "      CALL  \"DT_DAY\" (IN := DB1.t1, RET_VAL := DB1.n);",
    );
    assert_eq!(data.int(), 6, "Friday");
    let data = after(
        "  t1 := DT#2024-3-17-0:0:0.0;",
        "      CALL  FC 7 (IN := DB1.t1, RET_VAL := DB1.n);",
    );
    assert_eq!(data.int(), 1, "Sunday");
    let data = after(
        init,
        "      CALL  \"DT_TOD\" (IN := DB1.t1, RET_VAL := DB1.tm);",
    );
    assert_eq!((data.double(TM), data.ok()), (45_000_000, true));
    // The all-zero DATE_AND_TIME is none (month 0).
    let data = after(
        "  n := 9;",
        "      CALL  FC 6 (IN := DB1.t1, RET_VAL := DB1.n);",
    );
    assert_eq!((data.int(), data.ok()), (9, false));
}

// FC 9 EQ_DT … FC 28 NE_DT.

#[test]
fn instants_compare() {
    let compare = |name: &str, t2: &str| {
        let data = after(
            &format!("  t1 := DT#2024-3-15-12:00:00.000;\n  t2 := {t2};"),
            &format!("      CALL  \"{name}\" (DT1 := DB1.t1, DT2 := DB1.t2, RET_VAL := DB1.flag);"),
        );
        assert!(data.ok());
        data.0[OK] & 2 != 0
    };
    let cases: [(&str, [bool; 3]); 6] = [
        // t1 against a later, the same and an earlier instant.
        ("EQ_DT", [false, true, false]),
        ("NE_DT", [true, false, true]),
        ("LT_DT", [true, false, false]),
        ("LE_DT", [true, true, false]),
        ("GT_DT", [false, false, true]),
        ("GE_DT", [false, true, true]),
    ];
    for (name, expected) in cases {
        let found = [
            "DT#2024-3-15-12:00:00.001",
            "DT#2024-3-15-12:00:00.000",
            "DT#1999-12-31-23:59:59.999",
        ]
        .map(|other| compare(name, other));
        assert_eq!(found, expected, "{name}");
    }
    // The orderings take any bytes but a year that is no BCD number (BR 0, RET_VAL as it
    // was); EQ_DT and NE_DT compare the bytes as they are and report no error.
    let t2 = T1 + 8;
    let with_bad_year = |call: &str| {
        after(
            "  t1 := DT#2024-3-15-12:00:00.000;\n  t2 := DT#2024-3-15-12:00:00.000;",
            &format!("      L     B#16#AF;\n      T     DB1.DBB {t2};\n{call}"),
        )
    };
    let data =
        with_bad_year("      CALL  FC 12 (DT1 := DB1.t1, DT2 := DB1.t2, RET_VAL := DB1.flag);");
    assert!(!data.ok());
    let data =
        with_bad_year("      CALL  FC 28 (DT1 := DB1.t1, DT2 := DB1.t2, RET_VAL := DB1.flag);");
    assert!(data.ok());
    assert!(data.0[OK] & 2 != 0, "not equal");
    let data = after(
        "  t1 := DT#2024-3-15-12:00:00.000;\n  t2 := DT#2024-3-15-12:00:00.000;",
        "      L     DW#16#FFFFFFFF;\n      T     DB1.DBD 88;\n      T     DB1.DBD 96;\n\
         \x20     CALL  FC 9 (DT1 := DB1.t1, DT2 := DB1.t2, RET_VAL := DB1.flag);",
    );
    assert!(data.ok());
    assert!(data.0[OK] & 2 != 0, "the same bytes, though no date");
}

// FC 33 S5TI_TIM, FC 40 TIM_S5TI.

#[test]
fn s5time_and_time_convert() {
    let data = after(
        "",
        "      CALL  \"S5TI_TIM\" (IN := S5T#2M30S, RET_VAL := DB1.tm);",
    );
    assert_eq!((data.double(TM), data.ok()), (150_000, true));
    let data = after(
        "",
        "      CALL  FC 33 (IN := W#16#3999, RET_VAL := DB1.tm);",
    );
    assert_eq!(data.double(TM), 9_990_000);
    let to_s5 = |time: &str| {
        after(
            "",
            &format!("      CALL  \"TIM_S5TI\" (IN := {time}, RET_VAL := DB1.w);"),
        )
    };
    // The finest base that holds the value (1 s for 150 s); what is finer is cut off.
    let data = to_s5("T#2M30S");
    assert_eq!((data.word(W), data.ok()), (0x2150, true));
    assert_eq!(to_s5("T#1S5MS").word(W), 0x0100);
    assert_eq!(to_s5("T#10S5MS").word(W), 0x1100);
    assert_eq!(to_s5("T#9S999MS").word(W), 0x0999);
    let data = to_s5("T#3H");
    assert_eq!((data.word(W), data.ok()), (0x3999, false), "beyond 9990 s");
    let data = to_s5("T#-1S");
    assert_eq!((data.word(W), data.ok()), (0, false), "negative");
}

// FC 22 LIMIT, FC 25 MAX, FC 27 MIN, FC 36 SEL.

#[test]
fn limit_keeps_in_within_mn_and_mx() {
    let limit = |mn: &str, input: &str, mx: &str, to: &str| {
        after(
            "  n := 7;\n  r := 7.0;",
            &format!(
                "      CALL  \"LIMIT\" (MN := {mn}, IN := {input}, MX := {mx}, RET_VAL := {to});"
            ),
        )
    };
    let data = limit("0", "150", "100", "DB1.n");
    assert_eq!((data.int(), data.ok()), (100, true));
    assert_eq!(limit("0", "-5", "100", "DB1.n").int(), 0);
    assert_eq!(limit("0", "42", "100", "DB1.n").int(), 42);
    let data = limit("L#-100000", "L#-200000", "L#100000", "DB1.d");
    assert_eq!((data.dint(), data.ok()), (-100_000, true));
    let data = limit("0.5", "2.5", "1.5", "DB1.r");
    assert_eq!((data.real(R), data.ok()), (1.5, true));
    // Addresses take the type of the others: MD 0 holds a REAL here.
    let data = after(
        "",
        "      L     3.5;\n      T     MD 0;\n      \
         CALL  FC 22 (MN := 0.0, IN := MD 0, MX := 2.0, RET_VAL := DB1.r);",
    );
    assert_eq!(data.real(R), 2.0);
    // MN above MX: IN, BR 0.
    let data = limit("100", "150", "0", "DB1.n");
    assert_eq!((data.int(), data.ok()), (150, false));
    // A REAL that is no number: BR 0, RET_VAL as it was.
    let data = after(
        "  r := 7.0;",
        "      L     DW#16#7FC00000;\n      T     MD 0;\n      \
         CALL  FC 22 (MN := 0.0, IN := MD 0, MX := 2.0, RET_VAL := DB1.r);",
    );
    assert_eq!((data.real(R), data.ok()), (7.0, false));
}

#[test]
fn max_and_min_of_three() {
    let extreme = |name: &str, values: [&str; 3], to: &str| {
        after(
            "",
            &format!(
                "      CALL  \"{name}\" (IN1 := {}, IN2 := {}, IN3 := {}, RET_VAL := {to});",
                values[0], values[1], values[2]
            ),
        )
    };
    let data = extreme("MAX", ["3", "7", "-5"], "DB1.n");
    assert_eq!((data.int(), data.ok()), (7, true));
    assert_eq!(extreme("MIN", ["3", "7", "-5"], "DB1.n").int(), -5);
    assert_eq!(
        extreme("MAX", ["L#70000", "L#-1", "L#3"], "DB1.d").dint(),
        70_000
    );
    assert_eq!(
        extreme("MIN", ["2.5", "-0.5", "1.0"], "DB1.r").real(R),
        -0.5
    );
    let data = after(
        "  r := 7.0;",
        "      L     DW#16#7FC00000;\n      T     MD 0;\n      \
         CALL  FC 25 (IN1 := 1.0, IN2 := MD 0, IN3 := 2.0, RET_VAL := DB1.r);",
    );
    assert_eq!((data.real(R), data.ok()), (7.0, false));
}

#[test]
fn sel_picks_in0_or_in1() {
    let data = after(
        "",
        "      CALL  \"SEL\" (G := TRUE, IN0 := 1, IN1 := 2, RET_VAL := DB1.n);",
    );
    assert_eq!((data.int(), data.ok()), (2, true));
    let data = after(
        "",
        "      CALL  FC 36 (G := FALSE, IN0 := W#16#A, IN1 := W#16#B, RET_VAL := DB1.w);",
    );
    assert_eq!(data.word(W), 0xA);
    let data = after(
        "",
        "      CALL  FC 36 (G := TRUE, IN0 := T#1S, IN1 := T#2S, RET_VAL := DB1.tm);",
    );
    assert_eq!(data.double(TM), 2000);
}

// FC 105 SCALE, FC 106 UNSCALE.

fn scale(input: i16, bipolar: bool, high: &str, low: &str) -> Data {
    after(
        "  w := W#16#FFFF;",
        &format!(
            "      CALL  \"SCALE\" (IN := {input}, HI_LIM := {high}, LO_LIM := {low}, \
             BIPOLAR := {}, RET_VAL := DB1.w, OUT := DB1.r);",
            if bipolar { "TRUE" } else { "FALSE" }
        ),
    )
}

#[test]
fn scale_maps_an_analog_value_to_its_range() {
    // Unipolar 0 … 27648 to 0.0 … 100.0: 13824 is the middle.
    let data = scale(13824, false, "100.0", "0.0");
    assert_eq!((data.real(R), data.word(W), data.ok()), (50.0, 0, true));
    assert_eq!(scale(0, false, "100.0", "0.0").real(R), 0.0);
    assert_eq!(scale(27648, false, "100.0", "0.0").real(R), 100.0);
    assert_eq!(scale(6912, false, "20.0", "4.0").real(R), 8.0);
    // Bipolar -27648 … 27648: 0 is the middle.
    assert_eq!(scale(0, true, "100.0", "-100.0").real(R), 0.0);
    assert_eq!(scale(-27648, true, "100.0", "-100.0").real(R), -100.0);
    assert_eq!(scale(13824, true, "100.0", "-100.0").real(R), 50.0);
    // LO_LIM above HI_LIM scales the other way.
    assert_eq!(scale(6912, false, "0.0", "100.0").real(R), 75.0);
    // Beyond the range: the limit on its side, RET_VAL 16#0008, BR 0.
    let data = scale(30000, false, "100.0", "0.0");
    assert_eq!((data.real(R), data.word(W), data.ok()), (100.0, 8, false));
    let data = scale(-1, false, "100.0", "0.0");
    assert_eq!((data.real(R), data.word(W), data.ok()), (0.0, 8, false));
    let data = scale(-27649, true, "100.0", "-100.0");
    assert_eq!((data.real(R), data.word(W)), (-100.0, 8));
}

fn unscale(input: &str, bipolar: bool, high: &str, low: &str) -> Data {
    after(
        "  w := W#16#FFFF;",
        &format!(
            "      CALL  FC 106 (IN := {input}, HI_LIM := {high}, LO_LIM := {low}, \
             BIPOLAR := {}, RET_VAL := DB1.w, OUT := DB1.n);",
            if bipolar { "TRUE" } else { "FALSE" }
        ),
    )
}

#[test]
fn unscale_maps_a_value_back_to_an_analog_value() {
    let data = unscale("50.0", false, "100.0", "0.0");
    assert_eq!((data.int(), data.word(W), data.ok()), (13824, 0, true));
    assert_eq!(unscale("100.0", false, "100.0", "0.0").int(), 27648);
    assert_eq!(unscale("8.0", false, "20.0", "4.0").int(), 6912);
    // 1.0 of 0 … 3.0 is 9216; 0.1 of 0 … 1.0 is 2764.8, rounded to 2765.
    assert_eq!(unscale("1.0", false, "3.0", "0.0").int(), 9216);
    assert_eq!(unscale("0.1", false, "1.0", "0.0").int(), 2765);
    assert_eq!(unscale("0.0", true, "100.0", "-100.0").int(), 0);
    assert_eq!(unscale("-100.0", true, "100.0", "-100.0").int(), -27648);
    // Beyond LO_LIM … HI_LIM: the end of the analog range on its side, RET_VAL 16#0008.
    let data = unscale("150.0", false, "100.0", "0.0");
    assert_eq!((data.int(), data.word(W), data.ok()), (27648, 8, false));
    let data = unscale("-10.0", false, "100.0", "0.0");
    assert_eq!((data.int(), data.word(W), data.ok()), (0, 8, false));
    let data = unscale("-150.0", true, "100.0", "-100.0");
    assert_eq!((data.int(), data.word(W)), (-27648, 8));
}

// Calls: checked parameters, the program's own blocks first.

#[test]
fn a_call_needs_every_parameter_of_its_type() {
    let missing =
        errors("      CALL  \"SCALE\" (IN := 5, HI_LIM := 1.0, LO_LIM := 0.0, OUT := MD 0);");
    assert!(missing.contains("awl::check::param_count"), "{missing}");
    assert!(missing.contains("BIPOLAR, RET_VAL"), "{missing}");
    let plain = errors("      UC    FC 105;");
    assert!(plain.contains("awl::check::param_count"), "{plain}");
    let unknown = errors("      CALL  FC 21 (S := DB1.s1, RET_VAL := DB1.n, X := 1);");
    assert!(unknown.contains("awl::check::unknown_param"), "{unknown}");
    assert!(unknown.contains("FC 21 (LEN) has S, RET_VAL"), "{unknown}");
    let twice = errors("      CALL  FC 21 (S := DB1.s1, S := DB1.s2, RET_VAL := DB1.n);");
    assert!(twice.contains("given twice"), "{twice}");
    let not_a_string = errors("      CALL  FC 21 (S := DB1.n, RET_VAL := DB1.n);");
    assert!(
        not_a_string.contains("awl::check::param_mismatch"),
        "{not_a_string}"
    );
    assert!(not_a_string.contains("a STRING"), "{not_a_string}");
    let constant_out = errors("      CALL  \"CONCAT\" (IN1 := 'a', IN2 := 'b', RET_VAL := 'c');");
    assert!(
        constant_out.contains("a STRING variable to write"),
        "{constant_out}"
    );
    let not_dt = errors("      CALL  FC 6 (IN := DB1.s1, RET_VAL := DB1.n);");
    assert!(not_dt.contains("DATE_AND_TIME"), "{not_dt}");
    let narrow = errors("      CALL  FC 21 (S := DB1.s1, RET_VAL := DB1.d);");
    assert!(narrow.contains("expected an INT to write to"), "{narrow}");
    let int_out = errors(
        "      CALL  FC 105 (IN := 5, HI_LIM := 1.0, LO_LIM := 0.0, BIPOLAR := FALSE, RET_VAL := 8, OUT := MD 0);",
    );
    assert!(int_out.contains("to write to"), "{int_out}");
}

#[test]
fn the_any_parameters_share_one_number_type() {
    let mixed = errors("      CALL  \"MAX\" (IN1 := 1, IN2 := 2.0, IN3 := 3, RET_VAL := DB1.n);");
    assert!(mixed.contains("awl::check::param_mismatch"), "{mixed}");
    assert!(
        mixed.contains("expected an INT as the other parameters (the first at p.awl:"),
        "{mixed}"
    );
    let word = errors("      CALL  \"LIMIT\" (MN := DB1.w, IN := 1, MX := 2, RET_VAL := DB1.n);");
    assert!(word.contains("an INT, a DINT or a REAL"), "{word}");
    let wide = errors("      CALL  \"MIN\" (IN1 := 1, IN2 := 2, IN3 := 3, RET_VAL := DB1.d);");
    assert!(wide.contains("awl::check::param_mismatch"), "{wide}");
    let sel = errors("      CALL  \"SEL\" (G := TRUE, IN0 := 1, IN1 := L#2, RET_VAL := DB1.n);");
    assert!(sel.contains("the same type as IN0"), "{sel}");
}

const OWN_FC: &str = "
FUNCTION FC 105 : VOID
VAR_INPUT
  IN : INT;
  HI_LIM : REAL;
  LO_LIM : REAL;
  BIPOLAR : BOOL;
END_VAR
VAR_OUTPUT
  RET_VAL : WORD;
  OUT : REAL;
END_VAR
BEGIN
      L     W#16#1234;
      T     #RET_VAL;
      L     0.0;
      T     #OUT;
END_FUNCTION
";

/// Runs `program` with the STEP 7 symbol table `symbols`, one cycle, and checks `expect`.
fn run_with_symbols(program: &str, symbols: &str, expect: &str) -> Ran {
    let mut files = BTreeMap::new();
    files.insert(PathBuf::from("p.awl"), program.as_bytes().to_vec());
    let listed = if symbols.is_empty() {
        ""
    } else {
        files.insert(PathBuf::from("s.sdf"), symbols.as_bytes().to_vec());
        "symbols = [\"s.sdf\"]\n"
    };
    let scenario = format!(
        "program = [\"p.awl\"]\ncpu = \"speed7\"\n{listed}run = {{ cycles = 1 }}\n\
         [expect]\n{expect}"
    );
    files.insert(PathBuf::from("s.toml"), scenario.into_bytes());
    match runner::run(&RunOptions {
        scenario: Some(PathBuf::from("s.toml")),
        store: Files::Memory(Arc::new(files)),
        ..RunOptions::default()
    }) {
        Ok(ran) => {
            assert!(!ran.failed(), "{:#?}", ran.mismatches);
            ran
        }
        Err(NotRun::SourceErrors(reports, _) | NotRun::Failed(reports)) => panic!("{reports:?}"),
        Err(NotRun::Usage(report)) => panic!("{report:?}"),
    }
}

fn notes_of(ran: &Ran) -> String {
    ran.warnings
        .iter()
        .map(|report| format!("{report:?}"))
        .collect::<Vec<_>>()
        .join("\n")
}

const SCALE_CALL: &str = "
ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  \"SCALE\" (IN := 13824, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 0, OUT := MD 2);
      CALL  FC 105 (IN := 13824, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 10, OUT := MD 12);
END_ORGANIZATION_BLOCK
";

#[test]
fn the_programs_own_fc_of_the_number_is_called_with_a_note() {
    let ran = run_with_symbols(
        &format!("{OWN_FC}{SCALE_CALL}"),
        "",
        "\"MW 0\" = 0x1234\n\"MW 10\" = 0x1234\n",
    );
    let notes = notes_of(&ran);
    assert!(
        notes.contains("awl::check::library_block_replaced"),
        "{notes}"
    );
    assert!(notes.contains("the program defines FC 105"), "{notes}");
    assert!(
        notes.contains("\"SCALE\" calls the program's own FC 105"),
        "{notes}"
    );
    // Once, and not for `CALL FC 105`, which names the program's block.
    assert_eq!(
        notes.matches("library_block_replaced").count(),
        1,
        "{notes}"
    );
    let program = "
ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  \"SCALE\" (IN := 13824, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 0, OUT := MD 2);
END_ORGANIZATION_BLOCK
";
    let ran = run_with_symbols(program, "", "\"MW 0\" = 0\n\"MD 2\" = 0x42480000\n");
    assert!(ran.warnings.is_empty(), "{}", notes_of(&ran));
}

#[test]
fn the_symbol_table_may_give_a_library_name_to_another_block() {
    let program = format!(
        "{}{}",
        OWN_FC.replace("FC 105", "FC 7"),
        "
ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  \"SCALE\" (IN := 13824, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 0, OUT := MD 2);
      CALL  \"Scaling\" (IN := 13824, HI_LIM := 100.0, LO_LIM := 0.0, BIPOLAR := FALSE,
        RET_VAL := MW 10, OUT := MD 12);
END_ORGANIZATION_BLOCK
"
    );
    let symbols = "126,SCALE                   FC      7   FC      7 Own scaling\n\
                   126,Scaling                 FC    105   FC    105 Library scaling\n";
    // "SCALE" runs FC 7 (RET_VAL 16#1234); "Scaling" names FC 105, which the library has.
    let ran = run_with_symbols(
        &program,
        symbols,
        "\"MW 0\" = 0x1234\n\"MW 10\" = 0\n\"MD 12\" = 0x42480000\n",
    );
    let notes = notes_of(&ran);
    assert!(
        notes.contains("the symbol table gives this name to FC 7"),
        "{notes}"
    );
}

/// The STRING and DATE_AND_TIME actuals may be an FC's own parameters and temporaries and an
/// FB's statics. A temporary STRING's maximum length is the program's to set (STL does not),
/// here for `#copy` at L 0.
#[test]
fn parameters_temporaries_and_statics_are_actuals() {
    let program = "
FUNCTION FC 50 : VOID
VAR_INPUT
  text : STRING [20];
  at : DATE_AND_TIME;
END_VAR
VAR_OUTPUT
  size : INT;
  part : INT;
  day : INT;
END_VAR
VAR_TEMP
  copy : STRING [20];
END_VAR
BEGIN
      L     20;
      T     LB 0;
      CALL  \"LEN\" (S := #text, RET_VAL := #size);
      CALL  \"LEFT\" (IN := #text, L := 2, RET_VAL := #copy);
      CALL  \"CONCAT\" (IN1 := #copy, IN2 := #copy, RET_VAL := #copy);
      CALL  \"FIND\" (IN1 := #copy, IN2 := 'eH', RET_VAL := #part);
      CALL  \"DT_DAY\" (IN := #at, RET_VAL := #day);
END_FUNCTION

FUNCTION_BLOCK FB 1
VAR
  name : STRING [10] := 'abc';
  n : INT;
END_VAR
BEGIN
      CALL  \"CONCAT\" (IN1 := #name, IN2 := 'd', RET_VAL := #name);
      CALL  \"LEN\" (S := #name, RET_VAL := #n);
      L     #n;
      T     MW 20;
END_FUNCTION_BLOCK

DATA_BLOCK DB 1
STRUCT
  s1 : STRING [20] := 'Hello World';
  t1 : DATE_AND_TIME := DT#2024-3-17-0:0:0.0;
END_STRUCT;
BEGIN
END_DATA_BLOCK

DATA_BLOCK DB 2 FB 1
BEGIN
END_DATA_BLOCK

ORGANIZATION_BLOCK OB 1
BEGIN
      CALL  FC 50 (text := DB1.s1, at := DB1.t1, size := MW 0, part := MW 2, day := MW 4);
      CALL  FB 1, DB 2;
END_ORGANIZATION_BLOCK
";
    // 'He' twice is 'HeHe', 'eH' from its second character; Sunday is 1; the static grows to
    // 'abcd'.
    run_with_symbols(
        program,
        "",
        "\"MW 0\" = 11\n\"MW 2\" = 2\n\"MW 4\" = 1\n\"MW 20\" = 4\n",
    );
}
