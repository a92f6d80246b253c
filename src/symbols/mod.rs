//! Symbolic operands: the assignment list (German: Zuordnungsliste) gives operands names, and
//! a program writes `-NAME` where the operand would stand (`U -START`, `SPA -FILL`). The list
//! is read from its files (`--symbols FILE`, a scenario's `symbols = [...]`), the program's
//! symbols are replaced by their operands before compiling, and the names are shown back
//! where operands are printed (`awl dump --symbols`, the text trace, the expectations).
//!
//! STEP 7 has the same in its symbol table: a program writes `"Motor"` for an address or a
//! block, `"Data".speed` for a member of a data block. Its table is read from the same files
//! (its format told by the content, [`step7::Format`]); the S7 compiler looks the names up.

mod error;
pub mod file;
mod resolve;
pub mod step7;

use std::collections::HashMap;

pub use error::SymbolError;
pub use file::Entry;
pub use resolve::{Uses, resolve};

use crate::ast::{BlockId, Operand};
use crate::mnemonics::{self, MnemonicSet};
use crate::source::{SourceSet, Span};
use crate::step7::ast::{S7Address, S7BlockKind};

/// What a symbol stands for.
#[derive(Debug, Clone, PartialEq)]
pub enum Stands {
    /// STEP 5: an operand, and the block a German `PB n` also names (it is a peripheral byte
    /// otherwise).
    Step5 {
        operand: Operand,
        block: Option<BlockId>,
    },
    Step7(S7Symbol),
}

/// What a STEP 7 symbol stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum S7Symbol {
    /// `I 0.0`, `MW 10`, `PIW 256`, `T 5`, `C 3`.
    Address(S7Address),
    /// `FC 1`, `DB 5`, `UDT 2`, `SFC 46`.
    Block { kind: S7BlockKind, number: u16 },
    /// `VAT 1`: a variable table, which the tables list but a program cannot use.
    VariableTable(u16),
}

impl S7Symbol {
    /// `I 0.0`/`E 0.0`, `FC 1`, `VAT 1`.
    pub fn text(&self, set: MnemonicSet) -> String {
        match self {
            S7Symbol::Address(address) => crate::step7::text::address(*address, set),
            S7Symbol::Block { kind, number } => format!("{} {number}", kind.name()),
            S7Symbol::VariableTable(number) => format!("VAT {number}"),
        }
    }
}

impl Entry {
    /// The symbol as a program writes it: `-START`, `"Motor"`.
    pub fn written(&self) -> String {
        match self.stands {
            Stands::Step5 { .. } => format!("-{}", self.name),
            Stands::Step7(_) => format!("\"{}\"", self.name),
        }
    }

    /// What the symbol stands for as text in `set`: `E 1.0`, `PB 3`, `MW 10`, `FC 1`.
    pub fn operand_text(&self, set: MnemonicSet) -> Option<String> {
        match &self.stands {
            Stands::Step5 { operand, .. } => operand_text(operand, set),
            Stands::Step7(symbol) => Some(symbol.text(set)),
        }
    }

    /// The STEP 5 operand it stands for.
    pub fn step5(&self) -> Option<(&Operand, Option<BlockId>)> {
        match &self.stands {
            Stands::Step5 { operand, block } => Some((operand, *block)),
            Stands::Step7(_) => None,
        }
    }
}

/// Every symbol of the program's assignment lists.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Symbols {
    entries: Vec<Entry>,
    /// Upper-case name → entry.
    by_name: HashMap<String, usize>,
    /// The operand as English and as German text (`I 1.0`, `E 1.0`, `PB 3`) → entry.
    by_operand: HashMap<String, usize>,
    /// Upper-case names of STEP 7 table lines that had errors → where the name is.
    rejected: HashMap<String, Span>,
    /// How many entries are blocks the source declared (see [`Symbols::declare`]).
    declared: usize,
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

    /// The addresses the STEP 5 symbols stand for: each had to be in the CPU's ranges.
    pub fn step5_addresses(&self) -> impl Iterator<Item = crate::ast::Address> + '_ {
        self.entries.iter().filter_map(|entry| match entry.step5() {
            Some((Operand::Address(address), _)) => Some(*address),
            _ => None,
        })
    }

    /// Whether no list or table gave a symbol (blocks the source declares by name aside).
    pub fn none_listed(&self) -> bool {
        self.entries.len() == self.declared
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// The symbol `name` (without `-` or quotes; case does not matter).
    pub fn get(&self, name: &str) -> Option<&Entry> {
        let name = unwritten(name);
        self.by_name
            .get(&name.to_uppercase())
            .map(|&index| &self.entries[index])
    }

    /// The symbol of an operand written as text in either set (`I 1.0`, `E 1.0`, `PB 3`).
    pub fn name_of(&self, operand: &str) -> Option<&str> {
        self.entry_of(operand).map(|entry| entry.name.as_str())
    }

    /// The same as a program writes it: `-START`, `"Motor"`.
    pub fn written_of(&self, operand: &str) -> Option<String> {
        self.entry_of(operand).map(Entry::written)
    }

    /// The symbol of an operand written as text in either set.
    pub fn entry_of(&self, operand: &str) -> Option<&Entry> {
        self.by_operand
            .get(operand)
            .map(|&index| &self.entries[index])
    }

    /// `E 1.0 (-START)`, `I 0.0 ("Start")` when the operand has a symbol, else the operand.
    pub fn decorate(&self, operand: &str) -> String {
        match self.written_of(operand) {
            Some(name) => format!("{operand} ({name})"),
            None => operand.to_string(),
        }
    }

    /// An operand as a scenario wrote it, with its other name: `-START (E 1.0)` for a symbol,
    /// `E 1.0 (-START)` for an operand that has one.
    pub fn describe(&self, written: &str) -> String {
        match symbol_written(written).and_then(|name| self.get(name)) {
            Some(entry) => match entry.operand_text(entry.set) {
                Some(operand) => format!("{written} ({operand})"),
                None => written.to_string(),
            },
            None => self.decorate(written),
        }
    }

    /// The symbol's operand as text in `set`, for `-NAME` written where an operand is read.
    pub fn operand_in(&self, name: &str, set: MnemonicSet) -> Option<String> {
        self.get(name)?.operand_text(set)
    }

    /// The close names for an unknown one (the closest first, at most three), for a
    /// did-you-mean.
    pub fn suggest(&self, name: &str) -> Option<String> {
        self.suggest_among(name, |_| true)
    }

    /// The block a symbol names (`-FUELLEN`, `"Valve"`), for the commands that take a block;
    /// `None` for a name that is not there or stands for no block awl files.
    pub fn block_of(&self, name: &str) -> Option<BlockId> {
        match &self.get(name)?.stands {
            Stands::Step5 {
                block: Some(id), ..
            }
            | Stands::Step5 {
                operand: Operand::Block(id),
                ..
            } => Some(*id),
            // A UDT, SFC or VAT is no block of the program: its text does not parse.
            Stands::Step7(symbol @ S7Symbol::Block { .. }) => {
                BlockId::parse(&symbol.text(MnemonicSet::English))
            }
            _ => None,
        }
    }

    /// The close names of blocks for an unknown one, as [`Symbols::suggest`].
    pub fn suggest_block(&self, name: &str) -> Option<String> {
        self.suggest_among(name, |entry| self.block_of(&entry.name).is_some())
    }

    fn suggest_among(&self, name: &str, fits: impl Fn(&Entry) -> bool) -> Option<String> {
        let wanted = unwritten(name).to_uppercase();
        let mut close: Vec<(usize, &Entry)> = self
            .entries
            .iter()
            .filter(|entry| fits(entry))
            .map(|entry| {
                let distance = strsim::damerau_levenshtein(&wanted, &entry.name.to_uppercase());
                (distance, entry)
            })
            .filter(|(distance, entry)| *distance <= 1 + entry.name.chars().count() / 4)
            .collect();
        close.sort_by_key(|(distance, _)| *distance);
        let names: Vec<String> = close
            .iter()
            .take(3)
            .map(|(_, entry)| format!("`{}`", entry.written()))
            .collect();
        match names.as_slice() {
            [] => None,
            [one] => Some(format!("did you mean {one}?")),
            [first @ .., last] => Some(format!("did you mean {} or {last}?", first.join(", "))),
        }
    }

    /// Why `name` is not a symbol although a table has a line for it: that line had an
    /// error (reported with the table).
    pub fn rejected(&self, name: &str, sources: &SourceSet) -> Option<String> {
        let at = self.rejected.get(&unwritten(name).to_uppercase())?;
        Some(format!(
            "the table's line for it ({}) has an error, reported there",
            place(sources, *at)
        ))
    }

    /// The entries, in the order the lists define them.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
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
        self.insert(entry);
        Ok(())
    }

    /// Adds an entry whose name is not defined yet.
    fn insert(&mut self, entry: Entry) {
        let key = entry.name.to_uppercase();
        let index = self.entries.len();
        self.by_name.insert(key, index);
        for set in [MnemonicSet::English, MnemonicSet::German] {
            if let Some(text) = entry.operand_text(set) {
                self.by_operand.entry(text).or_insert(index);
            }
        }
        if let Some((_, Some(block))) = entry.step5() {
            self.by_operand.entry(block.to_string()).or_insert(index);
        }
        self.entries.push(entry);
    }

    /// A STEP 7 block the source declares by a name no table lists, with the number the
    /// compiler gave it: named like a listed one from then on (`FB 1 ("Valve")`). `None` when
    /// the name is taken.
    pub fn declare(
        &mut self,
        name: &crate::ast::Name,
        kind: S7BlockKind,
        number: u16,
    ) -> Option<()> {
        if self.get(&name.text).is_some() {
            return None;
        }
        self.insert(Entry {
            name: name.text.clone(),
            stands: Stands::Step7(S7Symbol::Block { kind, number }),
            comment: "declared in the source, numbered by awl".into(),
            set: MnemonicSet::English,
            name_span: name.span,
            operand_span: name.span,
        });
        self.declared += 1;
        Some(())
    }
}

/// A symbol as a program or scenario writes it without its marks: `START` of `-START`,
/// `Motor` of `"Motor"`.
fn unwritten(written: &str) -> &str {
    symbol_written(written).unwrap_or(written)
}

/// The name of `-NAME` or `"Name"`; `None` for an operand.
pub fn symbol_written(written: &str) -> Option<&str> {
    let written = written.trim();
    written.strip_prefix('-').or_else(|| {
        written
            .strip_prefix('"')
            .and_then(|rest| rest.strip_suffix('"'))
    })
}

/// `plant.seq line 3`.
fn place(sources: &SourceSet, span: Span) -> String {
    format!(
        "in {} line {}",
        sources.get(span.file).name,
        sources.line_of(span)
    )
}

/// Reads the assignment lists or symbol tables among `sources` (the files `files` names) for a
/// program in STEP 7 (`step7`) or STEP 5; the symbols and every error in them. `default` is
/// the set of operands a STEP 5 list does not show its own.
pub fn load(
    sources: &SourceSet,
    files: std::ops::Range<usize>,
    default: MnemonicSet,
    profile: &'static crate::profile::Profile,
    step7: bool,
) -> (Symbols, Vec<SymbolError>) {
    let mut symbols = Symbols::default();
    let mut errors = Vec::new();
    for id in files {
        let file = &sources.files[id];
        let format = step7::Format::detect(&file.text);
        let is_step7 = format != step7::Format::Step5;
        if is_step7 != step7 {
            errors.push(wrong_dialect(id as u16, &file.text, step7));
            continue;
        }
        let (entries, mut file_errors) = if is_step7 {
            let read = step7::read(id as u16, &file.text, format, profile);
            for (name, at) in read.rejected {
                symbols.rejected.entry(name.to_uppercase()).or_insert(at);
            }
            (read.entries, read.errors)
        } else {
            let (entries, _, errors) = file::read(id as u16, &file.text, default, profile);
            (entries, errors)
        };
        errors.append(&mut file_errors);
        for entry in entries {
            if let Err(error) = symbols.add(entry, sources) {
                errors.push(error);
            }
        }
    }
    (symbols, errors)
}

/// A symbol file of the other dialect, said at its first line.
fn wrong_dialect(file: crate::source::FileId, text: &str, step7: bool) -> SymbolError {
    let start = text.len() - text.trim_start().len();
    let end = text[start..]
        .find('\n')
        .map_or(text.len(), |end| start + end);
    let at = Span {
        file,
        start: start as u32,
        end: text[..end].trim_end().len().max(start) as u32,
    };
    if step7 {
        SymbolError::WrongDialect {
            found: "STEP 5",
            program: "STEP 7",
            help: "a STEP 7 program takes a STEP 7 symbol table: the ASCII export (`126,` and fixed columns), the System Data Format export (`\"Start\",\"I 0.0\",\"BOOL\",\"\"`) or CSV `Symbol;Address;Data type;Comment`",
            at,
        }
    } else {
        SymbolError::WrongDialect {
            found: "STEP 7",
            program: "STEP 5",
            help: "a STEP 5 program takes an assignment list: `E 1.0   START   Start button`, or the same as CSV with commas",
            at,
        }
    }
}
