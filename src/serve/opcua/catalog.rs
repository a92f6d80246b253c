//! What the OPC UA server offers of the program: the folders a client browses (the image
//! areas, the data blocks with their declared members, timers, counters, the symbols) and the
//! resolution of a node id, which is an operand in the command line's notation
//! ([`runner::watch_target`]), so anything `--watch` reads is a node even where it is not
//! browsed.

use std::collections::HashMap;
use std::sync::Arc;

use crate::address::Target;
use crate::address::declared::{self, DeclaredValue, Format};
use crate::compiler::Program;
use crate::mnemonics::MnemonicSet;
use crate::runner;

use super::super::request::{Area, Range};
use super::value::Kind;

/// The most operands one area's folder lists; the others are read by their node ids.
const LISTED_PER_FOLDER: u16 = 1024;

/// The `PLC` object's own variables.
pub const STATE: &str = "PLC.State";
pub const CYCLE: &str = "PLC.Cycle";
pub const CYCLE_TIME: &str = "PLC.CycleTime";

/// What a variable reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reads {
    /// One operand.
    One(Target),
    /// A STRING's bytes: its maximum and current length, then the characters.
    Text(Range),
    /// An array's elements in storage order.
    Many(Vec<Target>),
}

/// A variable: what it reads and the type its value has (of each element for an array).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Variable {
    pub reads: Reads,
    pub kind: Kind,
}

/// A node of the browsed tree below the `PLC` object.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Node {
    /// The node id's string.
    pub id: String,
    pub browse_name: String,
    /// The id of the node it is organised by (`PLC` for the folders).
    pub parent: String,
    /// `None` for a folder.
    pub variable: Option<Variable>,
}

pub struct Catalog {
    program: Arc<Program>,
    mnemonics: MnemonicSet,
    /// The browsed tree, parents before their children.
    pub nodes: Vec<Node>,
    /// The browsed variables by id, for ids no operand is (an array, a STRING).
    variables: HashMap<String, Variable>,
}

impl Catalog {
    pub fn new(program: Arc<Program>, mnemonics: MnemonicSet) -> Catalog {
        let mut catalog = Catalog {
            program,
            mnemonics,
            nodes: Vec::new(),
            variables: HashMap::new(),
        };
        catalog.images();
        catalog.data_blocks();
        catalog.timers_and_counters();
        catalog.symbols();
        catalog.variables = catalog
            .nodes
            .iter()
            .filter_map(|node| Some((node.id.clone(), node.variable.clone()?)))
            .collect();
        catalog
    }

    /// The variable a node id names: a browsed one, or any operand the command line reads.
    pub fn resolve(&self, id: &str) -> Option<Variable> {
        if let Some(variable) = self.variables.get(id) {
            return Some(variable.clone());
        }
        let target = self.operand(id)?;
        Some(Variable {
            reads: Reads::One(target),
            kind: self.kind_of(target),
        })
    }

    /// Where the program's image areas lie.
    pub fn layout(&self) -> crate::address::Layout {
        self.program.layout
    }

    fn operand(&self, text: &str) -> Option<Target> {
        runner::watch_target(text, self.mnemonics, &self.program).ok()
    }

    /// The type of an operand: a data block member's declared one, else by its width.
    fn kind_of(&self, target: Target) -> Kind {
        let declared = match target {
            Target::S7Data {
                db,
                byte,
                bit,
                bytes,
            } => self
                .program
                .s7
                .declared_dbs
                .iter()
                .find(|(number, _)| *number == db)
                .and_then(|(_, values)| declared::at(values, byte, bit, bytes)),
            _ => None,
        };
        match (declared, target) {
            (Some(value), _) => Kind::declared(value.format),
            (None, Target::TimerBit(_)) => Kind::S5Time,
            (None, _) => Kind::by_width(target.bytes()),
        }
    }

    fn folder(&mut self, id: &str, browse_name: &str, parent: &str) {
        self.nodes.push(Node {
            id: id.to_string(),
            browse_name: browse_name.to_string(),
            parent: parent.to_string(),
            variable: None,
        });
    }

    /// A variable for `id` under `parent`, when `id` is an operand.
    fn operand_node(&mut self, id: &str, browse_name: &str, parent: &str) -> bool {
        let Some(target) = self.operand(id) else {
            return false;
        };
        let kind = self.kind_of(target);
        self.nodes.push(Node {
            id: id.to_string(),
            browse_name: browse_name.to_string(),
            parent: parent.to_string(),
            variable: Some(Variable {
                reads: Reads::One(target),
                kind,
            }),
        });
        true
    }

    /// The bytes of the inputs, outputs and flags, in the program's mnemonics.
    fn images(&mut self) {
        let sizes = self.program.profile.sizes;
        let german = self.mnemonics == MnemonicSet::German;
        let areas: [(&str, &[&str], u16); 3] = [
            (
                "Inputs",
                if german { &["EB"] } else { &["IB"] },
                sizes.image_bytes,
            ),
            (
                "Outputs",
                if german { &["AB"] } else { &["QB"] },
                sizes.image_bytes,
            ),
            (
                "Flags",
                if german { &["MB"] } else { &["MB", "FY"] },
                sizes.flag_bytes,
            ),
        ];
        for (folder, words, bytes) in areas {
            let folder_id = format!("PLC.{folder}");
            self.folder(&folder_id, folder, "PLC");
            for byte in 0..bytes.min(LISTED_PER_FOLDER) {
                words.iter().any(|word| {
                    let name = format!("{word} {byte}");
                    self.operand_node(&name, &name, &folder_id)
                });
            }
        }
    }

    fn timers_and_counters(&mut self) {
        let sizes = self.program.profile.sizes;
        let counter = if self.mnemonics == MnemonicSet::German {
            "Z"
        } else {
            "C"
        };
        for (folder, word, count) in [
            ("Timers", "T", sizes.timers),
            ("Counters", counter, sizes.counters),
        ] {
            let folder_id = format!("PLC.{folder}");
            self.folder(&folder_id, folder, "PLC");
            for number in 0..count.min(LISTED_PER_FOLDER) {
                let name = format!("{word} {number}");
                self.operand_node(&name, &name, &folder_id);
            }
        }
    }

    /// A node per data block: a STEP 7 block's declared members (structs and arrays as
    /// nodes of their own), a STEP 5 block's data words.
    fn data_blocks(&mut self) {
        self.folder("PLC.DataBlocks", "DataBlocks", "PLC");
        let program = Arc::clone(&self.program);
        if program.s7.step7 {
            for (number, _) in &program.s7.data_blocks {
                let id = format!("DB{number}");
                self.folder(&id, &id, "PLC.DataBlocks");
                let declared = program.s7.declared_dbs.iter();
                if let Some((_, values)) = declared.clone().find(|(db, _)| db == number) {
                    self.members(*number, values);
                }
            }
        } else {
            for block in &program.data_blocks {
                let number = block.id.number;
                let id = format!("DB{number}");
                self.folder(&id, &id, "PLC.DataBlocks");
                for word in 0..(block.words.len() as u16).min(LISTED_PER_FOLDER) {
                    let name = format!("DB {number} DW {word}");
                    self.operand_node(&name, &format!("DW {word}"), &id);
                }
            }
        }
    }

    /// The declared values of STEP 7 data block `db`, each under its struct's or array's node.
    fn members(&mut self, db: u16, values: &[DeclaredValue]) {
        let block = format!("DB{db}");
        let mut arrays: HashMap<String, Vec<(Target, Kind)>> = HashMap::new();
        for value in values {
            let path = split_path(&value.name);
            let mut parent = block.clone();
            for (depth, part) in path.iter().enumerate() {
                let id = format!("{block}.{}", path[..=depth].concat());
                let last = depth + 1 == path.len();
                if !last && !self.nodes.iter().rev().any(|node| node.id == id) {
                    self.folder(&id, part.trim_start_matches('.'), &parent);
                }
                if last {
                    self.member(&id, part.trim_start_matches('.'), &parent, db, value);
                    if let (true, Some(target)) = (is_element(part), member_target(db, value)) {
                        let elements = arrays.entry(parent.clone()).or_default();
                        elements.push((target, Kind::declared(value.format)));
                    }
                }
                parent = id;
            }
        }
        // An array's node reads its elements at once, as an array of their type.
        for node in &mut self.nodes {
            if let Some(elements) = arrays.remove(&node.id) {
                let kind = elements[0].1;
                if elements.iter().all(|(_, each)| *each == kind) {
                    node.variable = Some(Variable {
                        reads: Reads::Many(elements.into_iter().map(|(at, _)| at).collect()),
                        kind,
                    });
                }
            }
        }
    }

    fn member(
        &mut self,
        id: &str,
        browse_name: &str,
        parent: &str,
        db: u16,
        value: &DeclaredValue,
    ) {
        let variable = match (member_target(db, value), value.format) {
            (Some(target), format) => Variable {
                reads: Reads::One(target),
                kind: Kind::declared(format),
            },
            (None, Format::String(length)) => Variable {
                reads: Reads::Text(Range::new(
                    Area::DataBlock(db),
                    value.byte,
                    u32::from(length) + 2,
                )),
                kind: Kind::String,
            },
            // A DATE_AND_TIME, POINTER or ANY: no value of one OPC UA type.
            (None, _) => return,
        };
        self.nodes.push(Node {
            id: id.to_string(),
            browse_name: browse_name.to_string(),
            parent: parent.to_string(),
            variable: Some(variable),
        });
    }

    /// The assignment list's or symbol table's operands, by name.
    fn symbols(&mut self) {
        self.folder("PLC.Symbols", "Symbols", "PLC");
        let program = Arc::clone(&self.program);
        for entry in program.symbols.entries() {
            let written = entry.written();
            self.operand_node(&written, &entry.name, "PLC.Symbols");
        }
    }
}

/// The operand reading a declared value whole; `None` for a STRING or a longer value.
fn member_target(db: u16, value: &DeclaredValue) -> Option<Target> {
    Some(Target::S7Data {
        db,
        byte: value.byte,
        bit: value.bit,
        bytes: value.format.operand_bytes()?,
    })
}

/// `motor.speed` → `motor`, `.speed`; `table[2]` → `table`, `[2]`; `grid[1,2].x` → `grid`,
/// `[1,2]`, `.x`: each a level of the tree, the id of a level the parts up to it.
fn split_path(name: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let mut start = 0;
    for (at, character) in name.char_indices() {
        if (character == '.' || character == '[') && at > start {
            parts.push(&name[start..at]);
            start = at;
        }
    }
    parts.push(&name[start..]);
    parts
}

fn is_element(part: &str) -> bool {
    part.starts_with('[')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_split_at_members_and_elements() {
        assert_eq!(split_path("setpoint"), ["setpoint"]);
        assert_eq!(split_path("motor.speed"), ["motor", ".speed"]);
        assert_eq!(split_path("grid[1,2].x"), ["grid", "[1,2]", ".x"]);
    }
}
