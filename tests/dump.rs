//! `awl dump` speaks the user's language: every annotation names its operand with the area in
//! the file's mnemonic set (`count up C 1`, `count up Z 1`), constants appear as written
//! (`load constant KF -100`), jumps name their label and FB calls their actual parameters.

use std::process::Command;

/// `awl dump FILE`'s output.
fn dump(file: &str) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(["dump", file])
        .output()
        .expect("awl runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).unwrap()
}

/// Each pair is a statement as the dump's source column shows it and the annotation it must
/// end with.
fn assert_annotations(dump: &str, expected: &[(&str, &str)]) {
    let missing: Vec<String> = expected
        .iter()
        .filter(|(statement, annotation)| {
            !dump.lines().any(|line| {
                line.contains(&format!("  {statement}  ")) && line.ends_with(annotation)
            })
        })
        .map(|(statement, annotation)| format!("{statement:<28} {annotation}"))
        .collect();
    assert!(
        missing.is_empty(),
        "missing in the dump:\n{}\n\n{dump}",
        missing.join("\n")
    );
}

#[test]
fn every_operation_names_its_operand_in_the_english_set() {
    let dump = dump("tests/inputs/every_op_en.awl");
    assert_annotations(
        &dump,
        &[
            ("C  DB 10", "open DB 10"),
            ("JU FB 5", "call FB 5 with EIN = I 0.0, AUS = Q 4.0"),
            ("JC FB 6", "call if RLO 1 FB 6"),
            ("JC PB 3", "call if RLO 1 PB 3"),
            ("AN I 0.1", "and not I 0.1"),
            ("O  T 1", "or T 1"),
            ("ON C 2", "or not C 2"),
            ("A  D 1.0", "and D 1.0"),
            ("O ", "or: the AND strings before and after"),
            ("=  D 2.0", "assign D 2.0"),
            ("L  IB 0", "load IB 0"),
            ("L  QW 6", "load QW 6"),
            ("L  FD 14", "load FD 14"),
            ("L  DL 1", "load DL 1"),
            ("L  DD 4", "load DD 4"),
            ("L  PY 128", "load PY 128"),
            ("L  OW 6", "load OW 6"),
            ("T  DR 2", "transfer DR 2"),
            ("T  PW 130", "transfer PW 130"),
            ("T  OY 4", "transfer OY 4"),
            ("L  KB 10", "load constant KB 10"),
            ("L  KF -100", "load constant KF -100"),
            ("L  KH 00FF", "load constant KH 00FF"),
            (
                "L  KM 0000000011110000",
                "load constant KM 0000000011110000",
            ),
            ("L  KY 12,34", "load constant KY 12,34"),
            ("L  KT 050.1", "load constant KT 050.1"),
            ("L  KC 500", "load constant KC 500"),
            ("L  KS 'AB'", "load constant KS 'AB'"),
            ("L  KG +1234567+02", "load constant KG +1234567+02"),
            ("L  DH 0000FFFF", "load constant DH 0000FFFF"),
            ("L  T 1", "load T 1"),
            ("LC T 1", "load BCD-coded T 1"),
            ("L  C 2", "load C 2"),
            ("LC C 2", "load BCD-coded C 2"),
            ("SP T 1", "start pulse timer T 1"),
            ("SE T 2", "start extended pulse timer T 2"),
            ("SD T 3", "start on-delay timer T 3"),
            ("SS T 4", "start stored on-delay timer T 4"),
            ("SF T 5", "start off-delay timer T 5"),
            ("FR T 1", "enable T 1"),
            ("R  T 1", "reset T 1"),
            ("CU C 1", "count up C 1"),
            ("CD C 1", "count down C 1"),
            ("S  C 1", "set C 1"),
            ("R  C 1", "reset C 1"),
            ("FR C 1", "enable C 1"),
            ("><F", "compare ACCU 2 <> ACCU 1 (fixed-point)"),
            ("BLD 130", "display construction for the PG, no operation"),
            ("STP", "stop at the end of the cycle"),
            ("A  =EIN", "and =EIN (parameter 1)"),
            ("JC =M001", "jump if RLO 1 to M001 (op 4)"),
            ("JU =M002", "jump to M002 (op 5)"),
            ("JO =M001", "jump on overflow to M001 (op 4)"),
            ("SLW 3", "shift ACCU 1 left by 3 bits"),
            ("D  2", "decrement ACCU 1 by 2"),
            (
                "DO FW 20",
                "do the next operation with the parameter in FW 20",
            ),
            (
                "DO DW 3",
                "do the next operation with the parameter in DW 3",
            ),
            ("SU D 1.0", "set unconditionally D 1.0"),
            ("TBN D 1.3", "test bit for 0 D 1.3"),
            ("SU F 1.0", "set unconditionally F 1.0"),
            ("G  DB 20", "generate DB 20"),
        ],
    );
}

#[test]
fn every_operand_area_is_named_in_the_german_set() {
    let dump = dump("tests/inputs/every_op_de.awl");
    assert_annotations(
        &dump,
        &[
            ("A  DB 10", "open DB 10"),
            ("SPA FB 5", "call FB 5 with EIN = E 0.0, AUS = A 4.0"),
            ("UN A 4.0", "and not A 4.0"),
            ("O  M 10.0", "or M 10.0"),
            ("U  Z 2", "and Z 2"),
            ("L  EB 0", "load EB 0"),
            ("L  AW 6", "load AW 6"),
            ("L  MB 10", "load MB 10"),
            ("L  MD 14", "load MD 14"),
            ("L  PB 128", "load PB 128"),
            ("L  QB 4", "load QB 4"),
            ("L  QW 6", "load QW 6"),
            ("L  KZ 500", "load constant KZ 500"),
            ("L  KS 'AB'", "load constant KS 'AB'"),
            ("L  Z 1", "load Z 1"),
            ("LC Z 1", "load BCD-coded Z 1"),
            ("SI T 1", "start pulse timer T 1"),
            ("SV T 2", "start extended pulse timer T 2"),
            ("SE T 3", "start on-delay timer T 3"),
            ("SA T 5", "start off-delay timer T 5"),
            ("ZV Z 1", "count up Z 1"),
            ("ZR Z 1", "count down Z 1"),
            ("S  Z 1", "set Z 1"),
            ("FR Z 1", "enable Z 1"),
            ("BEB", "block end if RLO 1"),
            ("BEA", "block end unconditionally"),
            ("SPB =M001", "jump if RLO 1 to M001 (op 3)"),
            (
                "B  MW 20",
                "do the next operation with the parameter in MW 20",
            ),
            ("P  D 1.2", "test bit for 1 D 1.2"),
            ("E  DB 20", "generate DB 20"),
        ],
    );
}

/// A data word is shown as written, a 32-bit constant or a long string covers the words after
/// it.
#[test]
fn data_words_are_shown_as_written() {
    let shown = |dump: &str, word: &str, text: &str| {
        dump.lines()
            .any(|line| line.starts_with(&format!("  DW {word:>4}  ")) && line.ends_with(text))
    };
    let english = dump("tests/inputs/every_op_en.awl");
    for (word, text) in [
        ("0", "KF +100"),
        ("3", "KG +1234567+02"),
        ("4", "(continues DW 3)"),
        ("5", "KS 'ABCDE'"),
        ("7", "(continues DW 5)"),
        ("9", "(continues DW 8)"),
        ("12", "KC 999"),
    ] {
        assert!(
            shown(&english, word, text),
            "DW {word}: {text}\n\n{english}"
        );
    }
    let german = dump("tests/inputs/every_op_de.awl");
    assert!(shown(&german, "0", "KZ 500"), "{german}");
}

/// The README's `awl dump` examples are what the binary prints: each block after a
/// `cargo run --release -- dump …` command is a part of that command's output.
#[test]
fn the_readme_s_dump_examples_are_true() {
    let readme = std::fs::read_to_string("README.md").unwrap();
    let blocks: Vec<&str> = readme.split("```").skip(1).step_by(2).collect();
    let mut checked = 0;
    for pair in blocks.windows(2) {
        let Some(args) = pair[0].trim().strip_prefix("cargo run --release -- dump") else {
            continue;
        };
        let output = Command::new(env!("CARGO_BIN_EXE_awl"))
            .arg("dump")
            .args(args.split_whitespace())
            .output()
            .expect("awl runs");
        let stdout = String::from_utf8(output.stdout).unwrap();
        let example = pair[1].trim_start_matches('\n');
        assert!(
            stdout.contains(example),
            "README example of `dump{args}` is not its output:\n{example}\n\nactual:\n{stdout}"
        );
        checked += 1;
    }
    assert!(checked >= 2, "{checked} examples");
}

#[test]
fn a_step7_open_names_the_register_it_opens_into() {
    let dump = dump("tests/inputs/s7/open_di.awl");
    assert!(dump.contains("line    4  OPN DI 2"), "{dump}");
    assert!(dump.contains("line    5  OPN DB 2"), "{dump}");
}
