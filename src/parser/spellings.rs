//! Each spelling of printouts and posts reads as the canonical form does.

use super::parse_text;
use crate::ast::{BlockBody, Operand, Statement};
use crate::mnemonics::OpCode;

/// The statements of the one block in `source`, with no errors.
fn statements(source: &str) -> Vec<(OpCode, Operand, Option<String>)> {
    let parsed = parse_text(source);
    assert!(parsed.errors.is_empty(), "{source}\n{:?}", parsed.errors);
    let BlockBody::Logic(body) = &parsed.unit.blocks[0].body else {
        panic!("a logic block");
    };
    body.statements
        .iter()
        .map(|s: &Statement| {
            let label = s.label.as_ref().map(|l| l.text.clone());
            (s.op, s.operand.clone(), label)
        })
        .collect()
}

fn same(spelling: &str, canonical: &str) {
    let wrap = |line: &str| format!("FB 1\nNAME :X\n{line}\n      BE\n");
    assert_eq!(
        statements(&wrap(spelling)),
        statements(&wrap(canonical)),
        "`{spelling}` should read as `{canonical}`"
    );
}

#[test]
fn address_prefixes_with_or_without_a_blank() {
    same("0034 :A F 67.1", "      A F 67.1");
    same("0034: A F 67.1", "      A F 67.1");
}

#[test]
fn labels_with_or_without_a_blank() {
    same("M004 :L DW 10", "M004 :L DW 10");
    same("M004: L DW 10", "M004 :L DW 10");
}

#[test]
fn a_blank_after_the_equals_sign() {
    same("M001 :JC = M001", "M001 :JC =M001");
    same("      A = EIN", "      A =EIN");
}

#[test]
fn operands_without_their_blank() {
    same("      C DB105", "      C DB 105");
    same("      L DW10", "      L DW 10");
    same("      A T1", "      A T 1");
    same("      A C5", "      A C 5");
    same("      L KT050.0", "      L KT 050.0");
    same("      L KF+20", "      L KF +20");
    same("      A F67.1", "      A F 67.1");
}

#[test]
fn a_bit_area_without_its_bit_stays_an_error() {
    let parsed = parse_text("PB 1\n      A F1\n      BE\n");
    assert_eq!(parsed.errors.len(), 1);
    let help = crate::syntax::error::help_text(&parsed.errors[0]);
    assert!(help.contains("`F 1.0`"), "{help}");
}

#[test]
fn brackets_with_a_blank() {
    same("      O (", "      O(");
    same("      A (", "      A(");
}

#[test]
fn empty_statements_and_segment_ends_are_no_statements() {
    same("      :\n      A I 1.0\n      :***", "      A I 1.0");
    same("0004 :\n      A I 1.0\n***", "      A I 1.0");
}

#[test]
fn block_names_take_pg_characters() {
    for name in ["RAD:GP", "RLG:AE", "A/B-1.2"] {
        let parsed = parse_text(&format!("FB 1\nNAME :{name}\n      BE\n"));
        assert!(parsed.errors.is_empty(), "{name}: {:?}", parsed.errors);
        let BlockBody::Logic(body) = &parsed.unit.blocks[0].body else {
            panic!("a logic block");
        };
        assert_eq!(body.name.as_ref().unwrap().text, name);
    }
}

#[test]
fn declarations_as_the_pg_prints_them_with_their_legend() {
    let params = |declarations: &str| {
        let parsed = parse_text(&format!("FB 1\nNAME :X\n{declarations}      BE\n"));
        assert!(parsed.errors.is_empty(), "{:?}", parsed.errors);
        let BlockBody::Logic(body) = &parsed.unit.blocks[0].body else {
            panic!("a logic block");
        };
        body.params
            .iter()
            .map(|p| (p.name.text.clone(), p.kind, p.format))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        params(
            "BEZ :EIN   E/A/D/B/T/Z: E   BI/BY/W/D: BI\n\
             BEZ :ZEIT  E/A/D/B/T/Z: T\n\
             BEZ :WERT  E/A/D/B/T/Z: D   KM/KH/KY/KS/KF/KT/KZ/KG: KF\n"
        ),
        params("BEZ :EIN E BI\nBEZ :ZEIT T\nBEZ :WERT D KF\n")
    );
    assert_eq!(
        params("DES :IN    I/Q/D/B/T/C: I   BI/BY/W/D: W\n"),
        params("DES :IN I W\n")
    );
}
