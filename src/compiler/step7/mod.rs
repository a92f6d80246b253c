//! The STEP 7 compiler: parsed S7 units to the same [`Program`] the STEP 5 compiler makes.
//! Blocks are registered first (so calls find their callees' interfaces), the interfaces laid
//! out, the data blocks' initial bytes made, then each logic block's statements lowered.

mod block_sfcs;
pub(crate) mod complex;
mod data;
pub(crate) mod interrupt_sfcs;
pub(crate) use crate::step7::layout;
mod library;
pub(super) mod lower;
mod operand;
mod pointers;
mod symbols;
mod system;
mod system_functions;

use std::collections::HashMap;

use crate::address::declared;
use crate::ast::BlockId;
use crate::compiler::{CheckError, Compiled, Program, Resolved};
use crate::mnemonics::BlockKind;
use crate::profile::Profile;
use crate::source::{SourceSet, Span};
use crate::step7::ast::{
    S7Block, S7BlockKind, S7BlockRef, S7Body, S7Op, S7Operand, S7Unit, VarDecl, VarKind,
};
use crate::step7::bytecode::S7Tables;
use crate::symbols::Symbols;

use layout::{Interface, Types};

/// The number of accumulators the first `__FEATURE 0, N` of the program asks for.
fn asked_accumulators(units: &[S7Unit]) -> Option<u8> {
    units
        .iter()
        .flat_map(S7Unit::statements)
        .filter(|statement| statement.op == S7Op::Feature)
        .find_map(|statement| match &statement.operand {
            S7Operand::Pair(target, value) if lower::feature_number(target) == Some(0) => {
                lower::feature_number(value)
            }
            _ => None,
        })
}

/// Compiles every STEP 7 unit of a program together with the symbol table `symbols`;
/// `extensions` allows awlsim's test instructions. The program keeps the symbols, with the
/// blocks the source declares by a name the table does not list.
pub fn compile(
    units: &[S7Unit],
    sources: &SourceSet,
    profile: &'static Profile,
    extensions: bool,
    symbols: Symbols,
) -> Compiled {
    // awlsim's `__FEATURE 0, 4` sets the number of accumulators; the compiled operations
    // depend on it, so the program runs on the CPU set that way from its start.
    let profile = asked_accumulators(units)
        .filter(|_| extensions)
        .and_then(|count| crate::profile::with_accumulators(profile, count))
        .unwrap_or(profile);
    let mut compiler = Compiler {
        profile,
        sources,
        symbols,
        index: HashMap::new(),
        interfaces: HashMap::new(),
        types: Types::default(),
        data_blocks: HashMap::new(),
        db_layouts: HashMap::new(),
        db_slots: HashMap::new(),
        tables: S7Tables {
            extensions,
            step7: true,
            ..S7Tables::default()
        },
        param_lists: Vec::new(),
        errors: Vec::new(),
        mcr_block: false,
        scratch_base: 0,
        scratch_bytes: 0,
    };
    compiler.number_blocks(units);
    let units = compiler.named_types(units);
    let units: &[S7Unit] = &units;
    let logic = compiler.collect(units);
    compiler.check_udts(units);
    compiler.make_data_blocks(units);
    compiler.number_data_blocks();
    compiler.tables.declared_dbs = compiler
        .db_layouts
        .iter()
        .map(|(&number, layout)| (number, declared::values(layout, &compiler.types)))
        .filter(|(_, values)| !values.is_empty())
        .collect();
    compiler
        .tables
        .declared_dbs
        .sort_by_key(|(number, _)| *number);
    let blocks = logic
        .iter()
        .map(|(block, id, set)| compiler.compile_block(block, *id, *set))
        .collect();
    compiler.tables.block_locals = logic
        .iter()
        .filter_map(|(_, id, _)| {
            let interface = compiler.interfaces.get(id)?;
            let index = *compiler.index.get(id)?;
            Some((index, declared::locals(interface, &compiler.types)))
        })
        .collect();
    compiler.errors.sort_by_key(|error| {
        let span = error.span();
        (span.file, span.start)
    });
    let mut data: Vec<(u16, Vec<u8>)> = compiler.data_blocks.into_iter().collect();
    data.sort_by_key(|(number, _)| *number);
    compiler.tables.data_blocks = data;
    let mut program = Program::assemble(
        profile,
        blocks,
        Vec::new(),
        compiler.param_lists,
        compiler.index,
        compiler.tables,
    );
    program.symbols = compiler.symbols;
    Compiled {
        program,
        diagnostics: compiler.errors,
    }
}

struct Compiler<'a> {
    profile: &'static Profile,
    sources: &'a SourceSet,
    /// The symbol table, and the blocks declared by a name it does not list.
    symbols: Symbols,
    index: HashMap<BlockId, u16>,
    interfaces: HashMap<BlockId, Interface>,
    types: Types,
    data_blocks: HashMap<u16, Vec<u8>>,
    /// Each data block's members and where they lie (for `DB5.speed`).
    db_layouts: HashMap<u16, Interface>,
    /// Each data block number's slot in [`S7Tables::db_numbers`].
    db_slots: HashMap<u16, u16>,
    tables: S7Tables,
    param_lists: Vec<Vec<Resolved>>,
    errors: Vec<CheckError>,
    /// The block being compiled has `MCRA`: its writes are MCR-aware.
    mcr_block: bool,
    /// Where the block's copies of FC actuals start on its L stack (after its own local
    /// data), and how many bytes its largest call needs.
    scratch_base: u32,
    scratch_bytes: u32,
}

/// The block kind awl files an S7 block under.
fn block_kind(kind: S7BlockKind) -> Option<BlockKind> {
    Some(match kind {
        S7BlockKind::Ob => BlockKind::Ob,
        S7BlockKind::Fc => BlockKind::Fc,
        S7BlockKind::Fb => BlockKind::Fb,
        S7BlockKind::Db => BlockKind::Db,
        _ => return None,
    })
}

impl<'a> Compiler<'a> {
    fn where_is(&self, span: Span) -> String {
        let file = self.sources.get(span.file);
        format!("{}:{}", file.name, file.line_of(span.start))
    }

    /// The block id of a reference, or `None` after an error.
    fn block_id(&mut self, reference: &S7BlockRef) -> Option<BlockId> {
        match reference {
            S7BlockRef::Number { kind, number } => Some(BlockId {
                kind: block_kind(*kind)?,
                number: *number,
            }),
            S7BlockRef::Symbol(name) => {
                let (kind, number) = self.symbol_block(name, &[], "")?;
                self.block_id(&S7BlockRef::Number { kind, number })
            }
        }
    }

    /// Registers every block; lays out the interfaces of the logic blocks.
    fn collect<'u>(
        &mut self,
        units: &'u [S7Unit],
    ) -> Vec<(&'u S7Block, BlockId, crate::mnemonics::MnemonicSet)> {
        for block in units.iter().flat_map(|unit| &unit.blocks) {
            if let (S7BlockKind::Udt, S7Body::Type(members)) = (block.kind, &block.body)
                && let Some(number) = self.declaration(block)
            {
                self.types.udts.insert(number, members.clone());
            }
        }
        self.instance_types(units);
        let mut first_seen: HashMap<BlockId, Span> = HashMap::new();
        let mut logic = Vec::new();
        let blocks = units
            .iter()
            .flat_map(|unit| unit.blocks.iter().map(move |block| (block, unit.mnemonics)));
        for (block, set) in blocks {
            if block.kind == S7BlockKind::Udt {
                continue;
            }
            let Some(number) = self.declaration(block) else {
                continue;
            };
            let name = S7BlockRef::Number {
                kind: block.kind,
                number,
            };
            let Some(id) = self.block_id(&name) else {
                continue;
            };
            if let Some(first) = first_seen.get(&id) {
                self.errors.push(CheckError::DuplicateBlock {
                    id: id.to_string(),
                    at: block.header,
                    first: self.where_is(*first),
                });
                continue;
            }
            first_seen.insert(id, block.header);
            if let S7Body::Logic(_) = block.body {
                self.index.insert(id, logic.len() as u16);
                self.interfaces.insert(id, self.interface(block));
                logic.push((block, id, set));
            }
        }
        logic
    }

    /// Registers the instance data of every FB (and of the system FBs awl runs) for the
    /// multi-instances that embed them; an FB that embeds itself, directly or through others,
    /// is reported and left out, so it takes no room.
    fn instance_types(&mut self, units: &[S7Unit]) {
        for block in units.iter().flat_map(|unit| &unit.blocks) {
            if block.kind != S7BlockKind::Fb {
                continue;
            }
            let S7BlockRef::Number { number, .. } = block.name else {
                // `number_blocks` declared it: its number is in the symbol table.
                let S7BlockRef::Symbol(name) = &block.name else {
                    unreachable!("matched above")
                };
                let Some(crate::symbols::Stands::Step7(crate::symbols::S7Symbol::Block {
                    number,
                    ..
                })) = self
                    .symbols
                    .get(&name.text)
                    .map(|entry| entry.stands.clone())
                else {
                    continue;
                };
                self.register_instance(block, number);
                continue;
            };
            self.register_instance(block, number);
        }
        for (number, sections) in system::instances() {
            self.types
                .instances
                .insert((S7BlockKind::Sfb, number), sections);
        }
        // Each FB on a cycle of multi-instances is left out until none is left.
        loop {
            let mut keys: Vec<(S7BlockKind, u16)> = self.types.instances.keys().copied().collect();
            keys.sort_unstable();
            let Some((key, at)) = keys.iter().find_map(|key| {
                self.embeds(*key, *key, &mut Vec::new())
                    .map(|at| (*key, at))
            }) else {
                break;
            };
            self.types.instances.remove(&key);
            self.errors.push(CheckError::RecursiveInstance {
                id: format!("{} {}", key.0.name(), key.1),
                at,
            });
        }
    }

    fn register_instance(&mut self, block: &S7Block, number: u16) {
        let mut sections: Vec<(VarKind, Vec<VarDecl>)> = block
            .interface
            .iter()
            .filter(|section| section.kind != VarKind::Temp)
            .map(|section| (section.kind, section.vars.clone()))
            .collect();
        // A multi-instance's in/out of a complex type is the DB pointer to its actual, as in
        // the FB's own instance DB: as big as a POINTER.
        for (_, vars) in sections
            .iter_mut()
            .filter(|(kind, _)| *kind == VarKind::InOut)
        {
            for var in vars.iter_mut().filter(|var| layout::is_complex(&var.ty)) {
                var.ty = crate::step7::ast::DataType::Pointer;
            }
        }
        sections.sort_by_key(|(kind, _)| layout::section_rank(*kind));
        let sections = sections.into_iter().map(|(_, vars)| vars).collect();
        self.types
            .instances
            .insert((S7BlockKind::Fb, number), sections);
    }

    /// Where the instance data of `from` embed `target`, directly or through other
    /// multi-instances (`seen`: the blocks already walked).
    fn embeds(
        &self,
        from: (S7BlockKind, u16),
        target: (S7BlockKind, u16),
        seen: &mut Vec<(S7BlockKind, u16)>,
    ) -> Option<Span> {
        if seen.contains(&from) {
            return None;
        }
        seen.push(from);
        let sections = self.types.instances.get(&from)?;
        for declaration in sections.iter().flatten() {
            let mut ty = &declaration.ty;
            while let crate::step7::ast::DataType::Array { element, .. } = ty {
                ty = element;
            }
            if let crate::step7::ast::DataType::Instance(kind, number) = *ty
                && ((kind, number) == target || self.embeds((kind, number), target, seen).is_some())
            {
                return Some(declaration.span);
            }
        }
        None
    }

    fn interface(&self, block: &S7Block) -> Interface {
        let mut sections: Vec<(VarKind, &[VarDecl])> = block
            .interface
            .iter()
            .map(|section| (section.kind, section.vars.as_slice()))
            .collect();
        // STEP 7 lays the sections out in this order whatever order the source writes them in
        // (inputs, outputs, in/outs, statics; temporaries on the L stack).
        sections.sort_by_key(|(kind, _)| layout::section_rank(*kind));
        let return_value;
        if let Some(ty) = &block.return_type {
            return_value = [VarDecl {
                name: crate::ast::Name {
                    text: "RET_VAL".into(),
                    span: block.header,
                },
                ty: ty.clone(),
                initial: Vec::new(),
                span: block.header,
            }];
            sections.push((VarKind::Output, &return_value));
            return Interface::build(&sections, block.kind == S7BlockKind::Fb, &self.types);
        }
        Interface::build(&sections, block.kind == S7BlockKind::Fb, &self.types)
    }

    fn make_data_blocks(&mut self, units: &[S7Unit]) {
        for block in units.iter().flat_map(|unit| &unit.blocks) {
            let S7Body::Data {
                instance_of,
                members,
                initial,
            } = &block.body
            else {
                continue;
            };
            let Some(number) = self.declared_number(block) else {
                continue;
            };
            let mut errors = Vec::new();
            let bytes = match instance_of {
                None => {
                    let sections = [(VarKind::Static, members.as_slice())];
                    let layout = Interface::build(&sections, true, &self.types);
                    self.db_layouts.insert(number, layout);
                    data::global_image(members, initial, &self.types, &mut errors)
                }
                Some(fb) => {
                    let Some(fb) = self.numbered(fb, "DATA_BLOCK") else {
                        continue;
                    };
                    if let S7BlockRef::Number {
                        kind: S7BlockKind::Sfb,
                        number: sfb,
                    } = fb
                    {
                        let Some(interface) = system::interface(sfb, &self.types) else {
                            self.errors.push(CheckError::NotSimulated {
                                what: format!("an instance DB of {}", system::label(sfb)),
                                why: system::WHICH.into(),
                                at: block.header,
                            });
                            continue;
                        };
                        let bytes =
                            data::instance_image(&interface, initial, &self.types, &mut errors);
                        self.db_layouts.insert(number, interface);
                        self.errors.extend(errors);
                        self.data_blocks.insert(number, bytes);
                        continue;
                    }
                    // `DATA_BLOCK DB 5` / `UDT 1`: a global DB whose structure is the UDT's.
                    if let S7BlockRef::Number {
                        kind: S7BlockKind::Udt,
                        number: udt,
                    } = fb
                    {
                        let Some(members) = self.types.udts.get(&udt).cloned() else {
                            self.errors.push(CheckError::UndefinedType {
                                id: format!("UDT {udt}"),
                                at: block.header,
                            });
                            continue;
                        };
                        let sections = [(VarKind::Static, members.as_slice())];
                        let layout = Interface::build(&sections, true, &self.types);
                        self.db_layouts.insert(number, layout);
                        let bytes = data::global_image(&members, initial, &self.types, &mut errors);
                        self.errors.extend(errors);
                        self.data_blocks.insert(number, bytes);
                        continue;
                    }
                    let Some(id) = self.block_id(&fb) else {
                        continue;
                    };
                    match self.interfaces.get(&id) {
                        Some(interface) => {
                            self.db_layouts.insert(number, interface.clone());
                            data::instance_image(interface, initial, &self.types, &mut errors)
                        }
                        None => {
                            self.errors.push(CheckError::UndefinedBlock {
                                id: id.to_string(),
                                at: block.header,
                            });
                            Vec::new()
                        }
                    }
                }
            };
            self.errors.extend(errors);
            self.data_blocks.insert(number, bytes);
        }
    }

    /// The slots of the defined data blocks: 0 (no data block), then the others by number.
    fn number_data_blocks(&mut self) {
        let mut defined: Vec<u16> = self
            .data_blocks
            .keys()
            .copied()
            .filter(|&n| n != 0)
            .collect();
        defined.sort_unstable();
        self.tables.defined_dbs = defined.len();
        self.tables.db_numbers = std::iter::once(0).chain(defined).collect();
        for (slot, &number) in self.tables.db_numbers.iter().enumerate() {
            self.db_slots.insert(number, slot as u16);
        }
    }

    /// The slot of data block `number`, named at `at`: a new one after the defined ones for a
    /// data block the program does not define, with a warning.
    fn db_slot(&mut self, number: u16, at: Span) -> u16 {
        if !self.data_blocks.contains_key(&number) {
            self.errors.push(CheckError::UndefinedDb {
                id: format!("DB {number}"),
                at,
            });
        }
        if let Some(&slot) = self.db_slots.get(&number) {
            return slot;
        }
        // At most 65536 numbers, so a slot fits 16 bits.
        let slot = self.tables.db_numbers.len() as u16;
        self.tables.db_numbers.push(number);
        self.db_slots.insert(number, slot);
        slot
    }

    fn types(&self) -> &Types {
        &self.types
    }
}
