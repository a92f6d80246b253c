//! STEP 7 statements and operands as text in a mnemonic set: what `awl dump` and program
//! status show for an S7 operation (`A #start`, `L DB1.DBW 2`, `CALL FB 1, DB 1`, `SPBN skip`).
//! Addresses are written in their regular form (`M 0.0`, `DB1.DBW 2`); constants, symbols,
//! labels and indirect addresses as the user wrote them.

use crate::mnemonics::MnemonicSet;
use crate::source::{SourceSet, Span};

use super::ast::{
    AccessWidth, Condition, S7Address, S7Area, S7BlockRef, S7Op, S7Operand, S7Statement,
};
use super::mnemonics;

/// The word of `op` in `set`, with the operations the mnemonic table files under another
/// word (`O` alone, `OPN DI`, `L STW`).
pub fn op_word(op: S7Op, set: MnemonicSet) -> &'static str {
    match op {
        S7Op::OrAlone => "O",
        S7Op::OpenInstanceDb => mnemonics::op_word(set, S7Op::OpenDb),
        S7Op::LoadStatusWord => "L STW",
        S7Op::TransferStatusWord => "T STW",
        other => mnemonics::op_word(set, other),
    }
}

/// The letters of an area at a width in `set`: `I`/`E`, `QW`/`AW`, `DBX`, `PIW`/`PEW`.
pub fn area_word(area: S7Area, width: AccessWidth, set: MnemonicSet) -> String {
    let german = set == MnemonicSet::German;
    let base = match area {
        S7Area::Input if german => "E",
        S7Area::Input => "I",
        S7Area::Output if german => "A",
        S7Area::Output => "Q",
        S7Area::Flag => "M",
        S7Area::Local => "L",
        S7Area::PreviousLocal => "V",
        S7Area::Data => "DB",
        S7Area::Instance => "DI",
        S7Area::PeripheralInput if german => "PE",
        S7Area::PeripheralInput => "PI",
        S7Area::PeripheralOutput if german => "PA",
        S7Area::PeripheralOutput => "PQ",
        S7Area::Timer => return "T".into(),
        S7Area::Counter if german => return "Z".into(),
        S7Area::Counter => return "C".into(),
    };
    let suffix = match (area, width) {
        (S7Area::Data | S7Area::Instance, AccessWidth::Bit) => "X",
        (_, AccessWidth::Bit) => "",
        (_, AccessWidth::Byte) => "B",
        (_, AccessWidth::Word) => "W",
        (_, AccessWidth::Double) => "D",
    };
    format!("{base}{suffix}")
}

/// `M 0.0`, `MW 10`, `DB1.DBW 2`, `T 5`.
pub fn address(address: S7Address, set: MnemonicSet) -> String {
    let word = area_word(address.area, address.width, set);
    let at = match address.area {
        S7Area::Timer | S7Area::Counter => address.byte.to_string(),
        _ if address.width == AccessWidth::Bit => format!("{}.{}", address.byte, address.bit),
        _ => address.byte.to_string(),
    };
    match address.db {
        Some(db) => format!("DB{db}.{word} {at}"),
        None => format!("{word} {at}"),
    }
}

/// `==0`, `OV`, `BR` (German `BIE`).
pub fn condition(condition: Condition, set: MnemonicSet) -> &'static str {
    match condition {
        Condition::Zero => "==0",
        Condition::NotZero => "<>0",
        Condition::Positive => ">0",
        Condition::Negative => "<0",
        Condition::PositiveOrZero => ">=0",
        Condition::NegativeOrZero => "<=0",
        Condition::Unordered => "UO",
        Condition::Overflow => "OV",
        Condition::StoredOverflow => "OS",
        Condition::BinaryResult if set == MnemonicSet::German => "BIE",
        Condition::BinaryResult => "BR",
    }
}

/// Source text with its runs of blanks (line breaks in a long operand) made one blank.
fn written(sources: &SourceSet, span: Span) -> String {
    let text = sources.get(span.file).slice(span);
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `FB 1`, or a symbol as written.
pub fn block_ref(reference: &S7BlockRef, sources: &SourceSet) -> String {
    match reference {
        S7BlockRef::Number { kind, number } => format!("{} {number}", kind.name()),
        S7BlockRef::Symbol(name) => written(sources, name.span),
    }
}

/// The operand of a statement.
pub fn operand(statement: &S7Statement, set: MnemonicSet, sources: &SourceSet) -> String {
    match &statement.operand {
        S7Operand::None => String::new(),
        S7Operand::Address(at) => address(*at, set),
        S7Operand::Condition(status) => condition(*status, set).to_string(),
        // `OPN DI 2` is filed as the open of DB 2 into the DI register.
        S7Operand::Block(S7BlockRef::Number { number, .. })
            if statement.op == S7Op::OpenInstanceDb =>
        {
            format!("DI {number}")
        }
        S7Operand::Block(reference) => block_ref(reference, sources),
        _ => written(sources, statement.operand_span),
    }
}

/// `CALL FB 1, DB 1`, `CALL FC 1`, `CALL #motor`: a call without its parameter list.
fn call_head(statement: &S7Statement, set: MnemonicSet, sources: &SourceSet) -> Option<String> {
    let call = statement.call.as_ref()?;
    let word = op_word(statement.op, set);
    Some(match (&call.multi_instance, &call.instance) {
        (Some(name), _) => format!("{word} #{}", name.text.trim_start_matches('#')),
        (None, Some(instance)) => format!(
            "{word} {}, {}",
            block_ref(&call.block, sources),
            block_ref(instance, sources)
        ),
        (None, None) => format!("{word} {}", block_ref(&call.block, sources)),
    })
}

/// The statement in `set`: `A #start`, `L DB1.DBW 2`, `CALL FB 1, DB 1`, `+I`; a label is
/// not part of it.
pub fn statement(statement: &S7Statement, set: MnemonicSet, sources: &SourceSet) -> String {
    if let Some(head) = call_head(statement, set, sources) {
        return head;
    }
    let word = op_word(statement.op, set);
    let operand = operand(statement, set, sources);
    if operand.is_empty() {
        word.to_string()
    } else {
        format!("{word} {operand}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(area: S7Area, width: AccessWidth, byte: u32, bit: u8, db: Option<u16>) -> S7Address {
        S7Address {
            area,
            width,
            byte,
            bit,
            db,
        }
    }

    #[test]
    fn addresses_take_the_set_s_letters() {
        use AccessWidth::*;
        let en = MnemonicSet::English;
        let de = MnemonicSet::German;
        assert_eq!(address(at(S7Area::Input, Bit, 0, 1, None), en), "I 0.1");
        assert_eq!(address(at(S7Area::Input, Bit, 0, 1, None), de), "E 0.1");
        assert_eq!(address(at(S7Area::Output, Word, 4, 0, None), de), "AW 4");
        assert_eq!(address(at(S7Area::Flag, Word, 10, 0, None), en), "MW 10");
        assert_eq!(
            address(at(S7Area::Data, Word, 2, 0, Some(1)), en),
            "DB1.DBW 2"
        );
        assert_eq!(
            address(at(S7Area::Instance, Bit, 0, 3, None), en),
            "DIX 0.3"
        );
        assert_eq!(
            address(at(S7Area::PeripheralInput, Word, 256, 0, None), de),
            "PEW 256"
        );
        assert_eq!(address(at(S7Area::Counter, Word, 3, 0, None), de), "Z 3");
    }

    #[test]
    fn operations_the_table_files_elsewhere_have_words() {
        assert_eq!(op_word(S7Op::OrAlone, MnemonicSet::German), "O");
        assert_eq!(op_word(S7Op::OpenInstanceDb, MnemonicSet::German), "AUF");
        assert_eq!(op_word(S7Op::JumpIfNotRlo, MnemonicSet::German), "SPBN");
        assert_eq!(op_word(S7Op::LoadStatusWord, MnemonicSet::English), "L STW");
    }
}
