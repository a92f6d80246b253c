//! Symbolic operands: the assignment list (German: Zuordnungsliste) gives operands names, and
//! a program writes `-NAME` where the operand would stand (`U -START`, `SPA -FILL`). The list
//! is read from its files (`--symbols FILE`, a scenario's `symbols = [...]`), the program's
//! symbols are replaced by their operands before compiling, and the names are shown back
//! where operands are printed (`awl dump --symbols`, the text trace, the expectations).

mod error;
pub mod file;
mod resolve;

use std::collections::HashMap;

pub use error::SymbolError;
pub use file::Entry;
pub use resolve::{Uses, resolve};

use crate::ast::Operand;
use crate::mnemonics::{self, MnemonicSet};
use crate::source::{SourceSet, Span};

/// Every symbol of the program's assignment lists.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Symbols {
    entries: Vec<Entry>,
    /// Upper-case name → entry.
    by_name: HashMap<String, usize>,
    /// The operand as English and as German text (`I 1.0`, `E 1.0`, `PB 3`) → entry.
    by_operand: HashMap<String, usize>,
}

/// An operand as text in `set`: `E 1.0`, `FW 10`, `PB 3`.
pub fn operand_text(operand: &Operand, set: MnemonicSet) -> Option<String> {
    match operand {
        Operand::Address(address) => {
            let word = mnemonics::area_word(set, address.area);
            Some(if address.area.is_bit() {
                format!("{word} {}.{}", address.index, address.bit)
            } else {
                format!("{word} {}", address.index)
            })
        }
        Operand::Block(id) => Some(id.to_string()),
        _ => None,
    }
}

impl Symbols {
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// The symbol `name` (without `-`; case does not matter).
    pub fn get(&self, name: &str) -> Option<&Entry> {
        let name = name.strip_prefix('-').unwrap_or(name);
        self.by_name
            .get(&name.to_uppercase())
            .map(|&index| &self.entries[index])
    }

    /// The symbol of an operand written as text in either set (`I 1.0`, `E 1.0`, `PB 3`).
    pub fn name_of(&self, operand: &str) -> Option<&str> {
        self.by_operand
            .get(operand)
            .map(|&index| self.entries[index].name.as_str())
    }

    /// `E 1.0 (-START)` when the operand has a symbol, else the operand.
    pub fn decorate(&self, operand: &str) -> String {
        match self.name_of(operand) {
            Some(name) => format!("{operand} (-{name})"),
            None => operand.to_string(),
        }
    }

    /// An operand as a scenario wrote it, with its other name: `-START (E 1.0)` for a symbol,
    /// `E 1.0 (-START)` for an operand that has one.
    pub fn describe(&self, written: &str) -> String {
        match written.strip_prefix('-').and_then(|name| self.get(name)) {
            Some(entry) => match operand_text(&entry.operand, entry.set) {
                Some(operand) => format!("{written} ({operand})"),
                None => written.to_string(),
            },
            None => self.decorate(written),
        }
    }

    /// The symbol's operand as text in `set`, for `-NAME` written where an operand is read.
    pub fn operand_in(&self, name: &str, set: MnemonicSet) -> Option<String> {
        operand_text(&self.get(name)?.operand, set)
    }

    /// A close name for an unknown one, for a did-you-mean.
    pub fn suggest(&self, name: &str) -> Option<String> {
        let wanted = name.to_uppercase();
        self.entries
            .iter()
            .map(|entry| {
                let distance = strsim::damerau_levenshtein(&wanted, &entry.name.to_uppercase());
                (distance, &entry.name)
            })
            .filter(|(distance, candidate)| *distance <= 1 + candidate.len() / 4)
            .min_by_key(|(distance, _)| *distance)
            .map(|(_, candidate)| format!("did you mean `-{candidate}`?"))
    }

    /// Adds an entry; a name defined before is an error.
    fn add(&mut self, entry: Entry, sources: &SourceSet) -> Result<(), SymbolError> {
        let key = entry.name.to_uppercase();
        if let Some(&first) = self.by_name.get(&key) {
            let first = self.entries[first].name_span;
            return Err(SymbolError::Duplicate {
                name: entry.name,
                at: entry.name_span,
                first: (first.file == entry.name_span.file).then_some(first),
                first_place: place(sources, first),
            });
        }
        let index = self.entries.len();
        self.by_name.insert(key, index);
        for set in [MnemonicSet::English, MnemonicSet::German] {
            if let Some(text) = operand_text(&entry.operand, set) {
                self.by_operand.entry(text).or_insert(index);
            }
        }
        if let Some(block) = entry.block {
            self.by_operand.entry(block.to_string()).or_insert(index);
        }
        self.entries.push(entry);
        Ok(())
    }
}

/// `plant.seq line 3`.
fn place(sources: &SourceSet, span: Span) -> String {
    format!(
        "in {} line {}",
        sources.get(span.file).name,
        sources.line_of(span)
    )
}

/// Reads the assignment lists among `sources` (the files `files` names); the symbols and every
/// error in them. `default` is the set of operands a list does not show its own.
pub fn load(
    sources: &SourceSet,
    files: std::ops::Range<usize>,
    default: MnemonicSet,
    profile: &'static crate::profile::Profile,
) -> (Symbols, Vec<SymbolError>) {
    let mut symbols = Symbols::default();
    let mut errors = Vec::new();
    for id in files {
        let file = &sources.files[id];
        let (entries, _, mut file_errors) = file::read(id as u16, &file.text, default, profile);
        errors.append(&mut file_errors);
        for entry in entries {
            if let Err(error) = symbols.add(entry, sources) {
                errors.push(error);
            }
        }
    }
    (symbols, errors)
}
