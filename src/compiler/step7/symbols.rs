//! Names of the symbol table in a STEP 7 program: `"Start"` for an address, `"Valve"` for a
//! block, `"Data".speed` for a member of a data block. A block the source declares by a name
//! the table does not list gets a number of its own (see [`Compiler::number_blocks`]).

use std::borrow::Cow;
use std::collections::{BTreeSet, HashMap};

use crate::ast::Name;
use crate::compiler::CheckError;
use crate::mnemonics::MnemonicSet;
use crate::source::Span;
use crate::step7::ast::{
    CallSpec, DataType, PathPart, S7Block, S7BlockKind, S7BlockRef, S7Body, S7Op, S7Operand,
    S7Statement, S7Unit, VarDecl,
};
use crate::step7::bytecode::{Place, Target};
use crate::step7::text;
use crate::symbols::{S7Symbol, Stands, SymbolError};

use super::Compiler;

impl Compiler<'_> {
    /// Numbers the blocks the source declares by a name the symbol table does not list, as
    /// STEP 7 gives a new block the first free number of its kind: in source order, the lowest
    /// number from 1 up that neither a block of the source nor the table uses. An OB is not
    /// numbered (its number says when the CPU runs it), so an OB's name must be listed.
    pub(super) fn number_blocks(&mut self, units: &[S7Unit]) {
        let blocks = || units.iter().flat_map(|unit| &unit.blocks);
        let mut taken: HashMap<S7BlockKind, BTreeSet<u16>> = HashMap::new();
        for block in blocks() {
            if let S7BlockRef::Number { kind, number } = block.name {
                taken.entry(kind).or_default().insert(number);
            }
        }
        for entry in self.symbols.entries() {
            if let Stands::Step7(S7Symbol::Block { kind, number }) = entry.stands {
                taken.entry(kind).or_default().insert(number);
            }
        }
        for block in blocks() {
            let S7BlockRef::Symbol(name) = &block.name else {
                continue;
            };
            if block.kind == S7BlockKind::Ob || self.symbols.get(&name.text).is_some() {
                continue;
            }
            let used = taken.entry(block.kind).or_default();
            let Some(number) = (1..=u16::MAX).find(|number| !used.contains(number)) else {
                continue;
            };
            used.insert(number);
            self.symbols.declare(name, block.kind, number);
        }
    }

    /// The units with every type written by its symbol (`motor : "MotorData";`) replaced by
    /// the UDT or FB it stands for, as if written `UDT 5` or `FB 2`, so the layout sees only
    /// numbered types. Borrowed when no declaration names a type by its symbol; a name that
    /// stands for no UDT or FB is reported and kept (it takes no room).
    pub(super) fn named_types<'u>(&mut self, units: &'u [S7Unit]) -> Cow<'u, [S7Unit]> {
        let blocks = units.iter().flat_map(|unit| &unit.blocks);
        if !blocks.flat_map(declared).any(names_type) {
            return Cow::Borrowed(units);
        }
        let mut units = units.to_vec();
        for block in units.iter_mut().flat_map(|unit| &mut unit.blocks) {
            if let Some(ty) = &mut block.return_type {
                let op = format!("{} : …", declaration_word(block.kind));
                self.resolve_type(ty, &op);
            }
            let members = match &mut block.body {
                S7Body::Type(members) | S7Body::Data { members, .. } => members.as_mut_slice(),
                S7Body::Logic(_) => &mut [],
            };
            let sections = block
                .interface
                .iter_mut()
                .flat_map(|section| &mut section.vars);
            for declaration in sections.chain(members) {
                let op = format!("{} : …", declaration.name.text);
                self.resolve_type(&mut declaration.ty, &op);
            }
        }
        Cow::Owned(units)
    }

    /// Replaces the names in `ty` (and its members and elements) by the types they stand for;
    /// `op` is the declaration, for the error of a name that stands for something else.
    fn resolve_type(&mut self, ty: &mut DataType, op: &str) {
        match ty {
            DataType::Named(name) => {
                let kinds = [S7BlockKind::Udt, S7BlockKind::Fb, S7BlockKind::Sfb];
                *ty = match self.symbol_block(&name.clone(), &kinds, op) {
                    Some((S7BlockKind::Udt, number)) => DataType::Udt(number),
                    Some((kind, number)) => DataType::Instance(kind, number),
                    None => return,
                };
            }
            DataType::Struct(members) => {
                for member in members {
                    let op = format!("{} : …", member.name.text);
                    self.resolve_type(&mut member.ty, &op);
                }
            }
            DataType::Array { element, .. } => self.resolve_type(element, op),
            _ => {}
        }
    }

    /// What `name` stands for: its table entry, or the number a block declared by that name
    /// was given.
    pub(super) fn symbol(&self, name: &Name) -> Result<S7Symbol, CheckError> {
        match self.symbols.get(&name.text).map(|entry| &entry.stands) {
            Some(Stands::Step7(symbol)) => Ok(*symbol),
            // The loader reads only STEP 7 tables for a STEP 7 program.
            Some(Stands::Step5 { .. }) | None => Err(self.unknown(name)),
        }
    }

    /// The number of a block the source declares; an error when its name stands for
    /// something else.
    pub(super) fn declaration(&mut self, block: &crate::step7::ast::S7Block) -> Option<u16> {
        match &block.name {
            S7BlockRef::Number { number, .. } => Some(*number),
            S7BlockRef::Symbol(name)
                if block.kind == S7BlockKind::Ob && self.symbols.get(&name.text).is_none() =>
            {
                self.errors
                    .push(CheckError::Symbol(Box::new(SymbolError::Unknown {
                        written: format!("\"{}\"", name.text),
                        list: "symbol table",
                        at: name.span,
                        help: Some(
                            "an OB's number says when the CPU runs it, so awl does not number one: list the name in the symbol table (`--symbols FILE`) or write `ORGANIZATION_BLOCK OB 1`"
                                .into(),
                        ),
                    })));
                None
            }
            S7BlockRef::Symbol(name) => {
                let word = declaration_word(block.kind);
                self.symbol_block(name, &[block.kind], word)
                    .map(|(_, number)| number)
            }
        }
    }

    /// The number of a block the source declares, without reporting (the registration did).
    pub(super) fn declared_number(&self, block: &crate::step7::ast::S7Block) -> Option<u16> {
        match &block.name {
            S7BlockRef::Number { number, .. } => Some(*number),
            S7BlockRef::Symbol(name) => match self.symbol(name) {
                Ok(S7Symbol::Block { kind, number }) if kind == block.kind => Some(number),
                _ => None,
            },
        }
    }

    fn unknown(&self, name: &Name) -> CheckError {
        let help = self
            .symbols
            .rejected(&name.text, self.sources)
            .or_else(|| self.symbols.suggest(&name.text))
            .or_else(|| {
                self.symbols.none_listed().then(|| {
                    "give the symbol table with `--symbols FILE` or a scenario's `symbols = [...]`"
                        .to_string()
                })
            });
        // As written: `"Start"`, or a bare `Start`.
        let span = name.span;
        let written =
            self.sources.get(span.file).text[span.start as usize..span.end as usize].to_string();
        CheckError::Symbol(Box::new(SymbolError::Unknown {
            written,
            list: "symbol table",
            at: span,
            help,
        }))
    }

    /// `"Name"` used where its kind does not fit; `op` is filled in by the statement's
    /// operation when empty (see [`Compiler::name_operation`]).
    fn wrong_kind(&self, name: &Name, symbol: S7Symbol, op: &str, at: Span) -> CheckError {
        let stands_for = symbol.text(MnemonicSet::English);
        let place = match self.symbols.get(&name.text) {
            Some(entry) => format!(
                "is defined in {} line {} as {stands_for}",
                self.sources.get(entry.name_span.file).name,
                self.sources.line_of(entry.name_span)
            ),
            None => format!("stands for {stands_for}"),
        };
        CheckError::Symbol(Box::new(SymbolError::WrongKind {
            written: format!("\"{}\"", name.text),
            stands_for,
            op: op.to_string(),
            at,
            help: Some(format!("`\"{}\"` {place}", name.text)),
        }))
    }

    /// The block `"Name"` stands for; an error when it stands for something else.
    pub(super) fn symbol_block(
        &mut self,
        name: &Name,
        kinds: &[S7BlockKind],
        op: &str,
    ) -> Option<(S7BlockKind, u16)> {
        let found = match self.symbol(name) {
            Ok(S7Symbol::Block { kind, number }) if kinds.is_empty() || kinds.contains(&kind) => {
                return Some((kind, number));
            }
            Ok(symbol) => self.wrong_kind(name, symbol, op, name.span),
            Err(error) => error,
        };
        self.errors.push(found);
        None
    }

    /// A block reference with its symbol replaced by the block's number; `None` (the error
    /// reported) when the symbol names no block.
    pub(super) fn numbered(&mut self, reference: &S7BlockRef, op: &str) -> Option<S7BlockRef> {
        match reference {
            S7BlockRef::Number { .. } => Some(reference.clone()),
            S7BlockRef::Symbol(name) => self
                .symbol_block(name, &[], op)
                .map(|(kind, number)| S7BlockRef::Number { kind, number }),
        }
    }

    /// A call with its block and instance DB by number.
    pub(super) fn numbered_call(&mut self, call: &CallSpec) -> Option<CallSpec> {
        let block = self.numbered(&call.block, "CALL")?;
        let instance = match &call.instance {
            Some(instance) => Some(self.numbered(instance, "CALL")?),
            None => None,
        };
        Some(CallSpec {
            block,
            instance,
            ..call.clone()
        })
    }

    /// A symbol written as an operand, as the absolute operand it stands for (`A "Start"`
    /// compiles as `A I 0.0`, `UC "Valve"` as `UC FC 1`); `None` for other operands and for
    /// a symbol that does not resolve (the place it is used reports it). A block stands only
    /// where the operation `op` takes one.
    pub(super) fn resolved_operand(
        &self,
        operand: &S7Operand,
        op: S7Op,
        at: Span,
    ) -> Result<Option<S7Operand>, CheckError> {
        let name = match operand {
            S7Operand::Symbol { name, members } if members.is_empty() => name,
            S7Operand::Block(S7BlockRef::Symbol(name)) => name,
            _ => return Ok(None),
        };
        let Ok(symbol) = self.symbol(name) else {
            return Ok(None);
        };
        let takes_block = matches!(
            op,
            S7Op::OpenDb
                | S7Op::OpenInstanceDb
                | S7Op::Call
                | S7Op::CallUnconditional
                | S7Op::CallConditional
        );
        match symbol {
            S7Symbol::Address(address) => Ok(Some(S7Operand::Address(address))),
            S7Symbol::Block { kind, number } if takes_block => {
                Ok(Some(S7Operand::Block(S7BlockRef::Number { kind, number })))
            }
            _ => Err(self.wrong_kind(name, symbol, "", at)),
        }
    }

    /// Reports a symbol where a block must stand that does not stand for one; `true` when
    /// `operand` was such a symbol.
    pub(super) fn not_a_block(&mut self, operand: &S7Operand, op: &str) -> bool {
        let S7Operand::Symbol { name, .. } = operand else {
            return false;
        };
        self.symbol_block(name, &[], op);
        true
    }

    /// The place of `"Start"` (an address) or `"Data".speed` (a member of a data block).
    pub(super) fn symbol_place(
        &mut self,
        name: &Name,
        members: &[PathPart],
        at: Span,
    ) -> Result<Place, CheckError> {
        let symbol = self.symbol(name)?;
        match (symbol, members.is_empty()) {
            (S7Symbol::Address(address), true) => self.address_place(&address, at),
            (
                S7Symbol::Block {
                    kind: S7BlockKind::Db,
                    number,
                },
                false,
            ) => self.db_member_place(number, members, at),
            // A block as a parameter value (BLOCK_DB, BLOCK_FC): its number.
            (S7Symbol::Block { number, .. }, true) => Ok(Place {
                target: Target::Constant(u32::from(number)),
                width: crate::step7::ast::AccessWidth::Word,
            }),
            (symbol, _) => Err(self.wrong_kind(name, symbol, "", at)),
        }
    }

    /// Gives the symbol errors of `statement` (those from `first` on) the statement's
    /// operation word.
    pub(super) fn name_operation(
        &mut self,
        first: usize,
        statement: &S7Statement,
        set: MnemonicSet,
    ) {
        for error in &mut self.errors[first..] {
            if let CheckError::Symbol(symbol) = error
                && let SymbolError::WrongKind { op, .. } = symbol.as_mut()
                && op.is_empty()
            {
                *op = text::op_word(statement.op, set).to_string();
            }
        }
    }
}

/// The declarations of a block: its interface, a UDT's or global DB's members, a function's
/// return type (as `RET_VAL`).
fn declared(block: &S7Block) -> impl Iterator<Item = &DataType> {
    let members: &[VarDecl] = match &block.body {
        S7Body::Type(members) | S7Body::Data { members, .. } => members,
        S7Body::Logic(_) => &[],
    };
    block
        .interface
        .iter()
        .flat_map(|section| &section.vars)
        .chain(members)
        .map(|declaration| &declaration.ty)
        .chain(&block.return_type)
}

/// Whether `ty` or a member or element of it is written by a symbol.
fn names_type(ty: &DataType) -> bool {
    match ty {
        DataType::Named(_) => true,
        DataType::Struct(members) => members.iter().any(|member| names_type(&member.ty)),
        DataType::Array { element, .. } => names_type(element),
        _ => false,
    }
}

/// The keyword that declares a block of `kind`.
fn declaration_word(kind: S7BlockKind) -> &'static str {
    match kind {
        S7BlockKind::Ob => "ORGANIZATION_BLOCK",
        S7BlockKind::Fc => "FUNCTION",
        S7BlockKind::Fb => "FUNCTION_BLOCK",
        S7BlockKind::Db => "DATA_BLOCK",
        S7BlockKind::Udt => "TYPE",
        S7BlockKind::Sfc => "SFC",
        S7BlockKind::Sfb => "SFB",
    }
}
