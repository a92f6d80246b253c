//! Bare names in a block's statements (`L position1;`, `CALL FC 1 (IN := start)`). STEP 7's
//! source compiler takes a name the block declares as that variable, as if written
//! `#position1`, and any other as a symbol of the symbol table, as if written `"start"`. The
//! operand parser reads every bare name as a symbol; here those the block declares become its
//! variables.

use crate::step7::ast::{PathPart, S7Operand, S7Statement, VarSection};

/// Turns each bare name that `interface` declares into the block's variable; `RET_VAL` too in
/// a function that `returns` a value.
pub fn declared_as_locals(
    source: &str,
    interface: &[VarSection],
    returns: bool,
    statements: &mut [S7Statement],
) {
    let declared = |name: &str| {
        (returns && name.eq_ignore_ascii_case("RET_VAL"))
            || interface
                .iter()
                .flat_map(|section| &section.vars)
                .any(|var| var.name.text.eq_ignore_ascii_case(name))
    };
    let resolve = |operand: &mut S7Operand| {
        let S7Operand::Symbol { name, members } = operand else {
            return;
        };
        // A quoted symbol (`"start"`) stays the symbol even where a variable has its name.
        let quoted = source.as_bytes().get(name.span.start as usize) == Some(&b'"');
        if quoted || !declared(&name.text) {
            return;
        }
        let mut path = vec![PathPart::Member(name.clone())];
        path.append(members);
        *operand = S7Operand::Local(path);
    };
    for statement in statements {
        resolve(&mut statement.operand);
        if let Some(call) = &mut statement.call {
            for param in &mut call.params {
                resolve(&mut param.actual);
            }
        }
    }
}
