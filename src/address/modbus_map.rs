//! Where the four Modbus tables lie in the CPU's memory. By default discrete inputs are the
//! input bits (`I 0.0` = 0, `I 1.0` = 8), coils the output bits, input registers the input words
//! (`IW 0` = 0, `IW 2` = 1) and holding registers the flag words (`MW 0`, STEP 5 `FW 0`); a
//! scenario's `[modbus]` table moves each to another area and start. A table runs from its start
//! to the end of its area: the CPU refuses what lies past it.

use super::MemoryArea as Area;
use crate::address::{ImageArea, Layout, Places, Target};
use crate::dialect::Dialect;

/// Where one table's address 0 lies: a bit table counts bits from bit 0 of byte 0 of `area`, a
/// register table bytes. The start is an operand's, so it lies within the CPU's ranges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Table {
    pub area: Area,
    pub start: u32,
}

/// The four tables of a Modbus server.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Map {
    pub discrete_inputs: Table,
    pub coils: Table,
    pub input_registers: Table,
    pub holding_registers: Table,
}

impl Default for Map {
    fn default() -> Self {
        let at = |area| Table { area, start: 0 };
        Map {
            discrete_inputs: at(Area::Inputs),
            coils: at(Area::Outputs),
            input_registers: at(Area::Inputs),
            holding_registers: at(Area::Flags),
        }
    }
}

/// Why an operand cannot start a table: what it is instead, and which operands can.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Misfit {
    pub found: &'static str,
    pub help: &'static str,
}

/// Which operands start a bit table, and a register table, in the program's dialect.
fn help(dialect: Dialect, bits: bool) -> &'static str {
    match (dialect, bits) {
        (Dialect::Step7, true) => {
            "a bit table starts at a bit of I, Q, M or a data block: `I 0.0`, `M 10.0`, `DB1.DBX 0.0`"
        }
        (Dialect::Step5, true) => "a bit table starts at a bit of I, Q or F: `I 0.0`, `F 10.0`",
        (Dialect::Step7, false) => {
            "a register table starts at a word of I, Q, M or a data block: `IW 0`, `MW 100`, `DB1.DBW 0`"
        }
        (Dialect::Step5, false) => {
            "a register table starts at a word of I, Q, F or a data block: `IW 0`, `FW 100`, `DB 10 DW 0`"
        }
    }
}

fn image_area(layout: Layout, byte: u16) -> Option<(Area, u32)> {
    let (area, byte) = layout.image_area_of(byte)?;
    let area = match area {
        ImageArea::Input => Area::Inputs,
        ImageArea::Output => Area::Outputs,
        ImageArea::Flag => Area::Flags,
    };
    Some((area, u32::from(byte)))
}

/// What an operand that starts no table is, in the words of the error.
fn kind(target: Target) -> &'static str {
    match target {
        Target::TimerBit(_) => "a timer",
        Target::CounterValue(_) => "a counter",
        Target::Periphery { .. } => "the periphery, which Modbus does not reach",
        _ => match target.bytes() {
            0 => "a bit",
            1 => "a byte",
            2 => "a word",
            _ => "a double word",
        },
    }
}

impl Table {
    /// The bit table (discrete inputs, coils) whose address 0 is the bit `target`.
    pub fn of_bits(target: Target, places: &Places) -> Result<Table, Misfit> {
        let layout = places.layout;
        let start = match target {
            Target::ImageBit { byte, bit } => {
                image_area(layout, byte).map(|(area, byte)| (area, byte, bit))
            }
            Target::S7Data {
                db,
                byte,
                bit,
                bytes: 0,
            } => Some((Area::DataBlock(db), byte, bit)),
            _ => None,
        };
        start
            .map(|(area, byte, bit)| Table {
                area,
                start: byte * 8 + u32::from(bit),
            })
            .ok_or(Misfit {
                found: kind(target),
                help: help(places.dialect, true),
            })
    }

    /// The register table (input, holding registers) whose register 0 is the word `target`.
    pub fn of_registers(target: Target, places: &Places) -> Result<Table, Misfit> {
        let layout = places.layout;
        let start = match target {
            Target::Image { byte, bytes: 2 } => image_area(layout, byte),
            Target::S7Data {
                db, byte, bytes: 2, ..
            } => Some((Area::DataBlock(db), byte)),
            Target::DataWord { db, word } => {
                Some((Area::DataBlock(u16::from(db)), 2 * u32::from(word)))
            }
            _ => None,
        };
        start
            .map(|(area, start)| Table { area, start })
            .ok_or(Misfit {
                found: kind(target),
                help: help(places.dialect, false),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::address::operand::{Places, parse};
    use crate::compiler::Program;
    use crate::frontend;
    use crate::mnemonics::MnemonicSet;
    use crate::profile;

    fn program(cpu: &str, text: &str) -> Program {
        let profile = profile::find(cpu).expect("the profile");
        let built = frontend::build_text("plant.awl", text, profile);
        assert!(!built.has_errors(), "the test program compiles");
        built.compiled.program.clone()
    }

    fn step7() -> Program {
        program(
            "speed7",
            "DATA_BLOCK DB 1\n  STRUCT\n    a : WORD;\n    b : WORD;\n  END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      L     DB1.DBW 2;\n      T     MW 10;\nEND_ORGANIZATION_BLOCK\n",
        )
    }

    fn step5() -> Program {
        program("s5-115u", "OB 1\n      L  FW 10\n      T  QW 4\n      BE\n")
    }

    fn target(program: &Program, set: MnemonicSet, text: &str) -> Target {
        parse(text, set, &Places::of(program)).expect(text)
    }

    fn bits(program: &Program, text: &str) -> Result<Table, Misfit> {
        Table::of_bits(
            target(program, MnemonicSet::English, text),
            &Places::of(program),
        )
    }

    fn registers(program: &Program, set: MnemonicSet, text: &str) -> Result<Table, Misfit> {
        Table::of_registers(target(program, set, text), &Places::of(program))
    }

    #[test]
    fn the_default_map_is_input_and_output_bits_input_and_flag_words() {
        let map = Map::default();
        let at = |area| Table { area, start: 0 };
        assert_eq!(map.discrete_inputs, at(Area::Inputs));
        assert_eq!(map.coils, at(Area::Outputs));
        assert_eq!(map.input_registers, at(Area::Inputs));
        assert_eq!(map.holding_registers, at(Area::Flags));
    }

    #[test]
    fn a_bit_table_starts_at_any_bit_of_i_q_m_or_a_data_block() {
        let program = step7();
        let at = |area, start| Ok(Table { area, start });
        assert_eq!(bits(&program, "I 0.0"), at(Area::Inputs, 0));
        assert_eq!(bits(&program, "I 1.3"), at(Area::Inputs, 11));
        assert_eq!(bits(&program, "Q 4.0"), at(Area::Outputs, 32));
        assert_eq!(bits(&program, "M 10.7"), at(Area::Flags, 87));
        assert_eq!(bits(&program, "DB1.DBX 2.1"), at(Area::DataBlock(1), 17));
    }

    #[test]
    fn a_register_table_starts_at_a_word_in_either_dialect() {
        let at = |area, start| Ok(Table { area, start });
        let program = step7();
        let english = MnemonicSet::English;
        assert_eq!(registers(&program, english, "IW 4"), at(Area::Inputs, 4));
        assert_eq!(registers(&program, english, "QW 2"), at(Area::Outputs, 2));
        assert_eq!(registers(&program, english, "MW 100"), at(Area::Flags, 100));
        assert_eq!(
            registers(&program, english, "DB1.DBW 2"),
            at(Area::DataBlock(1), 2)
        );
        let program = step5();
        assert_eq!(registers(&program, english, "FW 10"), at(Area::Flags, 10));
        assert_eq!(
            registers(&program, MnemonicSet::German, "MW 10"),
            at(Area::Flags, 10)
        );
        assert_eq!(registers(&program, english, "IW 2"), at(Area::Inputs, 2));
        assert_eq!(
            registers(&program, english, "DB 10 DW 3"),
            at(Area::DataBlock(10), 6),
            "a STEP 5 data word n is byte 2n"
        );
    }

    #[test]
    fn a_table_refuses_operands_of_the_other_width_and_other_areas() {
        let program = step7();
        let english = MnemonicSet::English;
        let found = |result: Result<Table, Misfit>| result.expect_err("refused").found;
        assert_eq!(found(bits(&program, "MW 0")), "a word");
        assert_eq!(found(bits(&program, "IB 0")), "a byte");
        assert_eq!(found(bits(&program, "T 1")), "a timer");
        assert_eq!(found(registers(&program, english, "I 0.0")), "a bit");
        assert_eq!(found(registers(&program, english, "MD 0")), "a double word");
        assert_eq!(found(registers(&program, english, "C 1")), "a counter");
        assert!(found(registers(&program, english, "PIW 256")).contains("periphery"));
        let misfit = registers(&program, english, "DB1.DBX 0.0").expect_err("a bit");
        assert!(misfit.help.contains("`DB1.DBW 0`"), "{}", misfit.help);
        assert!(
            bits(&program, "MW 0")
                .expect_err("a word")
                .help
                .contains("`I 0.0`")
        );
        let program = step5();
        let misfit = bits(&program, "FW 0").expect_err("a word");
        assert!(misfit.help.contains("`F 10.0`"), "{}", misfit.help);
        let misfit = registers(&program, english, "F 0.0").expect_err("a bit");
        assert!(misfit.help.contains("`DB 10 DW 0`"), "{}", misfit.help);
    }
}
