//! `[modbus]`: where the Modbus server's four tables start, resolved against the compiled
//! program like the scenario's other operands; a key left out keeps its table's default.

use miette::Report;
use toml::Spanned;

use super::error::ScenarioError;
use super::operand::parse_target;
use super::{Errors, Scenario};
use crate::address::Places;
use crate::address::modbus_map::{Map, Misfit, Table};
use crate::compiler::Program;
use crate::mnemonics::MnemonicSet;

/// How a table is placed by the operand it starts at.
type Place = fn(crate::address::Target, &Places) -> Result<Table, Misfit>;

impl Scenario {
    /// The Modbus map: the defaults, each table `[modbus]` names moved to its operand.
    pub fn modbus_map(&self, program: &Program, set: MnemonicSet) -> Result<Map, Vec<Report>> {
        let mut map = Map::default();
        let mut errors = Errors::default();
        let raw = &self.modbus;
        let bits: (&str, Place) = ("a bit", Table::of_bits);
        let words: (&str, Place) = ("a word", Table::of_registers);
        for (key, operand, (takes, place), table) in [
            (
                "discrete_inputs",
                &raw.discrete_inputs,
                bits,
                &mut map.discrete_inputs,
            ),
            ("coils", &raw.coils, bits, &mut map.coils),
            (
                "input_registers",
                &raw.input_registers,
                words,
                &mut map.input_registers,
            ),
            (
                "holding_registers",
                &raw.holding_registers,
                words,
                &mut map.holding_registers,
            ),
        ] {
            let Some(operand) = operand else {
                continue;
            };
            if let Some(placed) =
                errors.keep(self.place(key, operand, (takes, place), program, set))
            {
                *table = placed;
            }
        }
        self.unless_errors(map, errors)
    }

    fn place(
        &self,
        key: &'static str,
        operand: &Spanned<String>,
        (takes, place): (&'static str, Place),
        program: &Program,
        set: MnemonicSet,
    ) -> Result<Table, ScenarioError> {
        let at = self.key_span(operand);
        let target = parse_target(operand.get_ref(), at, set, program)?;
        place(target, &Places::of(program)).map_err(|misfit| ScenarioError::ModbusTable {
            key,
            takes,
            operand: operand.get_ref().trim().to_string(),
            at,
            found: misfit.found,
            help: misfit.help,
        })
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::address::MemoryArea as Area;
    use crate::frontend;
    use crate::profile;

    const STEP7: &str = "DATA_BLOCK DB 1\n  STRUCT\n    a : WORD;\n    b : WORD;\n  END_STRUCT;\nBEGIN\nEND_DATA_BLOCK\n\nORGANIZATION_BLOCK OB 1\nBEGIN\n      L     DB1.DBW 2;\n      T     MW 10;\nEND_ORGANIZATION_BLOCK\n";
    const STEP5: &str = "OB 1\n      L  FW 10\n      T  QW 4\n      BE\n";

    fn program(cpu: &str, text: &str) -> Program {
        let built = frontend::build_text("plant.awl", text, profile::find(cpu).expect("a CPU"));
        assert!(!built.has_errors(), "the test program compiles");
        built.compiled.program.clone()
    }

    /// The map of a scenario for a program, or its errors rendered.
    fn map(scenario: &str, program: &Program, set: MnemonicSet) -> Result<Map, Vec<String>> {
        let (scenario, errors) = Scenario::parse(Path::new("plant.toml"), scenario);
        assert!(errors.is_empty(), "{errors:?}");
        scenario.modbus_map(program, set).map_err(|reports| {
            reports
                .iter()
                .map(crate::diagnostics::render_plain)
                .collect()
        })
    }

    fn at(area: Area, start: u32) -> Table {
        Table { area, start }
    }

    #[test]
    fn without_modbus_the_map_is_the_default() {
        let program = program("speed7", STEP7);
        let found = map("run = { cycles = 1 }\n", &program, MnemonicSet::English);
        assert_eq!(found, Ok(Map::default()));
    }

    #[test]
    fn each_key_moves_its_table_in_step7_notation() {
        let program = program("speed7", STEP7);
        let text = "[modbus]\ndiscrete_inputs = \"M 2.1\"\ncoils = \"I 0.0\"\ninput_registers = \"QW 4\"\nholding_registers = \"DB1.DBW 2\"\n";
        let found = map(text, &program, MnemonicSet::English).expect("a map");
        assert_eq!(found.discrete_inputs, at(Area::Flags, 17));
        assert_eq!(found.coils, at(Area::Inputs, 0));
        assert_eq!(found.input_registers, at(Area::Outputs, 4));
        assert_eq!(found.holding_registers, at(Area::DataBlock(1), 2));
        let german = "[modbus]\ncoils = \"E 1.0\"\ninput_registers = \"AW 2\"\n";
        let found = map(german, &program, MnemonicSet::German).expect("a map");
        assert_eq!(found.coils, at(Area::Inputs, 8));
        assert_eq!(found.input_registers, at(Area::Outputs, 2));
        assert_eq!(found.holding_registers, at(Area::Flags, 0), "the default");
    }

    #[test]
    fn step5_notation_and_data_words() {
        let program = program("s5-115u", STEP5);
        let text = "[modbus]\ncoils = \"F 4.0\"\nholding_registers = \"DB 10 DW 3\"\ninput_registers = \"FW 20\"\n";
        let found = map(text, &program, MnemonicSet::English).expect("a map");
        assert_eq!(found.coils, at(Area::Flags, 32));
        assert_eq!(found.holding_registers, at(Area::DataBlock(10), 6));
        assert_eq!(found.input_registers, at(Area::Flags, 20));
        assert_eq!(found.discrete_inputs, at(Area::Inputs, 0), "the default");
    }

    #[test]
    fn a_bit_for_a_register_table_and_a_word_for_a_bit_table_are_errors() {
        let program = program("speed7", STEP7);
        let text = "[modbus]\ncoils = \"MW 0\"\nholding_registers = \"M 0.0\"\ninput_registers = \"T 3\"\n";
        let errors = map(text, &program, MnemonicSet::English).expect_err("errors");
        assert_eq!(errors.len(), 3, "{errors:#?}");
        let coils = &errors[0];
        assert!(coils.contains("awl::scenario::modbus_table"), "{coils}");
        assert!(
            coils.contains("`coils` in [modbus] starts at a bit, not at `MW 0`"),
            "{coils}"
        );
        assert!(coils.contains("a word"), "the label: {coils}");
        assert!(coils.contains("`DB1.DBX 0.0`"), "the help: {coils}");
        assert!(
            errors[1].contains("`holding_registers` in [modbus] starts at a word, not at `M 0.0`"),
            "{}",
            errors[1]
        );
        assert!(errors[2].contains("a timer"), "{}", errors[2]);
    }

    #[test]
    fn an_operand_that_is_none_is_an_unknown_operand() {
        let program = program("speed7", STEP7);
        let text = "[modbus]\ncoils = \"X 0.0\"\nholding_registers = \"DB9.DBW 0\"\n";
        let errors = map(text, &program, MnemonicSet::English).expect_err("errors");
        assert_eq!(errors.len(), 2, "{errors:#?}");
        assert!(
            errors[0].contains("awl::scenario::unknown_operand"),
            "{}",
            errors[0]
        );
        assert!(
            errors[1].contains("DB 9 is not in the program"),
            "{}",
            errors[1]
        );
        let program = self::program("s5-115u", STEP5);
        let errors = map(
            "[modbus]\nholding_registers = \"MW 0\"\n",
            &program,
            MnemonicSet::English,
        )
        .expect_err("no M in the English set of STEP 5");
        assert!(errors[0].contains("`MW 0`"), "{}", errors[0]);
    }
}
