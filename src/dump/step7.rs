//! `awl dump` of a STEP 7 program: each op as the STEP 7 statement it came from, in the file's
//! mnemonic set (`A #start`, `SPBN skip`), with where a block-local name or a symbol is
//! (`DIX 0.0`, `parameter 1`) and where a jump goes. `CALL FB` is three ops — copy the inputs
//! into the instance DB, run the FB, copy the outputs back — and each says which it is.

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::address::ImageArea;
use crate::compiler::{CompiledBlock, Op, Program};
use crate::frontend::Frontend;
use crate::mnemonics::MnemonicSet;
use crate::source::{SourceSet, Span};
use crate::step7::ast::{
    S7Address, S7Area, S7Block, S7BlockKind, S7BlockRef, S7Body, S7Operand, S7Statement, S7Unit,
    VarKind,
};
use crate::step7::bytecode::{Place, S7Code, Target};
use crate::step7::text;
use crate::symbols::{S7Symbol, Stands};

/// The STEP 7 statements of every file, by where they start.
pub(crate) fn statements(built: &Frontend) -> HashMap<Span, &S7Statement> {
    built
        .s7_units
        .iter()
        .flat_map(S7Unit::statements)
        .map(|statement| (statement.span, statement))
        .collect()
}

/// The mnemonic set of the file `span` is in.
pub(crate) fn set_of(built: &Frontend, span: Span) -> MnemonicSet {
    built
        .mnemonics
        .get(usize::from(span.file))
        .copied()
        .unwrap_or(MnemonicSet::English)
}

/// What one block's ops are shown with.
struct BlockContext<'a> {
    program: &'a Program,
    sources: &'a SourceSet,
    blocks: &'a [&'a S7Block],
    statements: &'a HashMap<Span, &'a S7Statement>,
    block: &'a CompiledBlock,
    set: MnemonicSet,
}

/// The whole dump of a STEP 7 program.
pub fn dump(built: &Frontend) -> String {
    let program = &built.compiled.program;
    let statements = statements(built);
    let blocks: Vec<&S7Block> = built
        .s7_units
        .iter()
        .flat_map(|unit| &unit.blocks)
        .collect();
    let mut out = String::new();
    for block in &program.blocks {
        super::header(
            &mut out,
            &built.sources,
            program.symbols.decorate(&block.id.to_string()),
            block.header,
            block.code.len(),
            "ops",
        );
        let context = BlockContext {
            program,
            sources: &built.sources,
            blocks: &blocks,
            statements: &statements,
            block,
            set: set_of(built, block.header),
        };
        context.write(&mut out);
        out.push('\n');
    }
    for block in blocks.iter().filter(|block| block.kind == S7BlockKind::Db) {
        data_block(&mut out, built, block);
    }
    out
}

impl BlockContext<'_> {
    fn write(&self, out: &mut String) {
        for (pc, (op, span)) in self.block.code.iter().zip(&self.block.spans).enumerate() {
            if let Some(&(_, network)) = self
                .block
                .segments
                .iter()
                .find(|(first, _)| *first as usize == pc)
                && network != 0
            {
                let _ = writeln!(out, "  network {network}");
            }
            let line = self.sources.line_of(*span);
            let (shown, detail) = self.op(*op, *span);
            let row = format!("  {pc:>4}  line {line:>4}  {shown:<28} {detail}");
            let _ = writeln!(out, "{}", row.trim_end());
        }
    }

    /// The statement an op came from (with its label), and what to add about the op.
    fn op(&self, op: Op, span: Span) -> (String, String) {
        let Some(statement) = self.statements.get(&span) else {
            // The block end STEP 7 places after the last network, on the `END_…` line.
            let written = self.sources.get(span.file).slice(span).trim().to_string();
            return (written, "block end".to_string());
        };
        let mut shown = text::statement(statement, self.set, self.sources);
        if let Some(label) = &statement.label {
            shown = format!("{}: {shown}", label.text);
        }
        let detail = match op {
            Op::S7(S7Code::FbEnter { call }) => self.fb_inputs(statement, call),
            Op::S7(S7Code::FbLeave { call }) => self.fb_outputs(statement, call),
            Op::S7(S7Code::FcEnter { call }) => self.fc_copies(call, true),
            Op::S7(S7Code::FcLeave { call }) => self.fc_copies(call, false),
            Op::Indirect { .. } => "call the block numbered in the word".to_string(),
            Op::Call { .. } if statement.call.is_some() => self.call(statement),
            Op::S7(S7Code::Jump { target, .. } | S7Code::Loop { target }) => {
                format!("to {}", self.target(u32::from(target)))
            }
            Op::Jump(_, target) => format!("to {}", self.target(target)),
            Op::S7(S7Code::JumpList { entries, target }) => format!(
                "the next {entries} ops are the list; past it to {}",
                self.target(u32::from(target))
            ),
            Op::S7(S7Code::Mem { place, .. }) => self.where_is(statement, place),
            _ => String::new(),
        };
        let detail = match self.symbol(statement) {
            Some(symbol) if detail.is_empty() => symbol,
            _ => detail,
        };
        (shown, detail)
    }

    /// `op 12`, or `skip (op 12)` when a label is there.
    fn target(&self, pc: u32) -> String {
        let label = self
            .block
            .spans
            .get(pc as usize)
            .and_then(|span| self.statements.get(span))
            .and_then(|statement| statement.label.as_ref());
        match label {
            Some(label) => format!("{} (op {pc})", label.text),
            None => format!("op {pc}"),
        }
    }

    /// Where a name (`#start`, `"Motor".speed`) or an indirect address is; nothing for an
    /// address written out.
    fn where_is(&self, statement: &S7Statement, place: u16) -> String {
        let named = matches!(
            statement.operand,
            S7Operand::Local(_) | S7Operand::Symbol { .. }
        );
        let place = self.program.s7.places.get(usize::from(place));
        match place.and_then(|place| place_text(self.program, *place, self.set)) {
            Some(text) if named => format!("= {text}"),
            _ => String::new(),
        }
    }

    /// What the symbol table says of the operand: the address or block a symbol stands for
    /// (`= I 0.0`), the symbol of an absolute operand (`("Start")`).
    fn symbol(&self, statement: &S7Statement) -> Option<String> {
        let symbols = &self.program.symbols;
        match &statement.operand {
            S7Operand::Symbol { name, members } if members.is_empty() => symbols
                .get(&name.text)
                .and_then(|entry| entry.operand_text(self.set))
                .map(|text| format!("= {text}")),
            S7Operand::Block(reference @ S7BlockRef::Symbol(_)) => self
                .number(reference)
                .map(|(kind, number)| format!("= {} {number}", kind.name())),
            S7Operand::Address(address) => symbols
                .written_of(&text::address(*address, self.set))
                .map(|name| format!("({name})")),
            S7Operand::Block(S7BlockRef::Number { kind, number }) => symbols
                .written_of(&format!("{} {number}", kind.name()))
                .map(|name| format!("({name})")),
            _ => None,
        }
    }

    /// The kind and number of a block reference, by the program's symbols for a name.
    fn number(&self, reference: &S7BlockRef) -> Option<(S7BlockKind, u16)> {
        block_number(self.program, reference)
    }

    /// A called block or instance DB by number, with its symbol: `FB 5 ("Valve")`.
    fn block_shown(&self, reference: &S7BlockRef) -> String {
        match self.number(reference) {
            Some((kind, number)) => self
                .program
                .symbols
                .decorate(&format!("{} {number}", kind.name())),
            None => text::block_ref(reference, self.sources),
        }
    }

    /// `CALL FC 1`: the parameter list as written.
    fn call(&self, statement: &S7Statement) -> String {
        let Some(call) = &statement.call else {
            return String::new();
        };
        match &call.instance {
            Some(instance) => format!(
                "run {} (instance {})",
                self.block_shown(&call.block),
                self.block_shown(instance)
            ),
            None if call.params.is_empty() => String::new(),
            None => format!("with {}", self.parameters(statement, None)),
        }
    }

    /// `a := MW 10, b := 5`: the parameters of a call, those of `kinds` only when given.
    fn parameters(&self, statement: &S7Statement, kinds: Option<&[VarKind]>) -> String {
        let Some(call) = &statement.call else {
            return String::new();
        };
        let declared = kinds.and_then(|kinds| self.declared(&call.block, kinds));
        call.params
            .iter()
            .filter(|param| {
                declared.as_ref().is_none_or(|names| {
                    names
                        .iter()
                        .any(|name| name.eq_ignore_ascii_case(&param.name.text))
                })
            })
            .map(|param| {
                let written = self.sources.get(param.span.file).slice(param.span);
                written.split_whitespace().collect::<Vec<_>>().join(" ")
            })
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The names an FB declares in the sections `kinds`.
    fn declared(&self, fb: &S7BlockRef, kinds: &[VarKind]) -> Option<Vec<String>> {
        let wanted = self.number(fb)?;
        let block = self
            .blocks
            .iter()
            .find(|block| self.number(&block.name) == Some(wanted))?;
        Some(
            block
                .interface
                .iter()
                .filter(|section| kinds.contains(&section.kind))
                .flat_map(|section| &section.vars)
                .map(|var| var.name.text.clone())
                .collect(),
        )
    }

    fn instance_db(&self, call: u16) -> String {
        self.program.s7.fb_calls.get(usize::from(call)).map_or(
            "the instance DB".to_string(),
            |call| match call.multi_instance {
                Some(offset) => format!(
                    "the caller's instance DB at AR2 + P#{}.{}",
                    offset / 8,
                    offset % 8
                ),
                None => format!("DB {}", call.instance_db),
            },
        )
    }

    /// `CALL FC n (…)`: the actuals passed as copies on the L stack, and AR2 saved or back.
    fn fc_copies(&self, call: u16, entering: bool) -> String {
        let Some(call) = self.program.s7.fc_calls.get(usize::from(call)) else {
            return String::new();
        };
        let copies = if entering {
            &call.inputs
        } else {
            &call.outputs
        };
        let shown = |place: u16| {
            self.program
                .s7
                .places
                .get(usize::from(place))
                .and_then(|place| place_text(self.program, *place, self.set))
                .unwrap_or_else(|| "?".into())
        };
        let list: Vec<String> = copies
            .iter()
            .map(|&(actual, copy)| {
                if entering {
                    format!("{} to {}", shown(actual), shown(copy))
                } else {
                    format!("{} to {}", shown(copy), shown(actual))
                }
            })
            .collect();
        match (entering, list.is_empty()) {
            (true, true) => "save AR2".into(),
            (true, false) => format!("copy {} onto the L stack, save AR2", list.join(", ")),
            (false, true) => "restore AR2".into(),
            (false, false) => format!("restore AR2, copy back {}", list.join(", ")),
        }
    }

    /// The call's parameters of `kinds` as ` (A, B)`; empty when it passes none.
    fn bracketed(&self, statement: &S7Statement, kinds: &[VarKind]) -> String {
        let params = self.parameters(statement, Some(kinds));
        if params.is_empty() {
            String::new()
        } else {
            format!(" ({params})")
        }
    }

    fn fb_inputs(&self, statement: &S7Statement, call: u16) -> String {
        let db = self.instance_db(call);
        let params = self.bracketed(statement, &[VarKind::Input, VarKind::InOut]);
        let opened = if db.starts_with("DB") {
            "open it as the instance DB"
        } else {
            "AR2 to the instance"
        };
        format!("copy the inputs into {db}{params}, {opened}")
    }

    fn fb_outputs(&self, statement: &S7Statement, call: u16) -> String {
        let db = self.instance_db(call);
        let params = self.bracketed(statement, &[VarKind::Output, VarKind::InOut]);
        format!("copy the outputs back from {db}{params}, restore the DB registers")
    }
}

/// The kind and number of a block reference, a name looked up in the program's symbols.
fn block_number(program: &Program, reference: &S7BlockRef) -> Option<(S7BlockKind, u16)> {
    match reference {
        S7BlockRef::Number { kind, number } => Some((*kind, *number)),
        S7BlockRef::Symbol(name) => match program.symbols.get(&name.text)?.stands {
            Stands::Step7(S7Symbol::Block { kind, number }) => Some((kind, number)),
            _ => None,
        },
    }
}

/// A compiled place as an address (`DIX 0.0`, `LW 2`, `parameter 2`), when it is one.
pub(crate) fn place_text(program: &Program, place: Place, set: MnemonicSet) -> Option<String> {
    let address = |area, byte, bit, db| {
        text::address(
            S7Address {
                area,
                width: place.width,
                byte,
                bit,
                db,
            },
            set,
        )
    };
    Some(match place.target {
        Target::Image { byte, bit } => {
            let (area, number) = program.layout.image_area_of(byte)?;
            let area = match area {
                ImageArea::Input => S7Area::Input,
                ImageArea::Output => S7Area::Output,
                ImageArea::Flag => S7Area::Flag,
            };
            address(area, u32::from(number), bit, None)
        }
        Target::Local { byte, bit } => address(S7Area::Local, byte, bit, None),
        Target::PreviousLocal { byte, bit } => address(S7Area::PreviousLocal, byte, bit, None),
        Target::Data {
            instance,
            byte,
            bit,
        } => {
            let area = if instance {
                S7Area::Instance
            } else {
                S7Area::Data
            };
            address(area, byte, bit, None)
        }
        Target::NumberedData { db, byte, bit, .. } => address(S7Area::Data, byte, bit, Some(db)),
        Target::Instance { byte, bit } => {
            // The FB's own variable: DI at AR2's offset (`DIW [AR2, P#2.0]`).
            let written = address(S7Area::Instance, byte, bit, None);
            let area = written.split_whitespace().next().unwrap_or("DIX");
            format!("{area} [AR2, P#{byte}.{bit}]")
        }
        Target::Parameter { param, byte, bit } if byte == 0 && bit == 0 => {
            format!("parameter {}", u16::from(param) + 1)
        }
        Target::Parameter { param, byte, bit } => {
            format!("parameter {}, at {byte}.{bit} in it", u16::from(param) + 1)
        }
        Target::Through { param, byte, bit } => {
            format!(
                "parameter {} (by DB pointer), at {byte}.{bit} in it",
                u16::from(param) + 1
            )
        }
        Target::InstanceThrough { pointer, byte, bit } => {
            format!("the DB pointer at DIX [AR2, P#{pointer}.0], at {byte}.{bit} in it")
        }
        Target::Timer(n) => address(S7Area::Timer, u32::from(n), 0, None),
        Target::Counter(n) => address(S7Area::Counter, u32::from(n), 0, None),
        _ => return None,
    })
}

/// A data block: its header, what it is an instance of, its initial bytes.
fn data_block(out: &mut String, built: &Frontend, block: &S7Block) {
    let Some((_, number)) = block_number(&built.compiled.program, &block.name) else {
        return;
    };
    let Some((_, bytes)) = built
        .compiled
        .program
        .s7
        .data_blocks
        .iter()
        .find(|(db, _)| *db == number)
    else {
        return;
    };
    let file = built.sources.get(block.header.file);
    let _ = writeln!(
        out,
        "{}  ({}:{}, {} bytes)",
        built
            .compiled
            .program
            .symbols
            .decorate(&format!("DB {number}")),
        file.name,
        file.line_of(block.header.start),
        bytes.len()
    );
    if let S7Body::Data {
        instance_of: Some(fb),
        ..
    } = &block.body
    {
        let fb = match block_number(&built.compiled.program, fb) {
            Some((kind, number)) => built
                .compiled
                .program
                .symbols
                .decorate(&format!("{} {number}", kind.name())),
            None => text::block_ref(fb, &built.sources),
        };
        let _ = writeln!(out, "  instance DB of {fb}");
    }
    for (row, chunk) in bytes.chunks(8).enumerate() {
        let hex: Vec<String> = chunk.iter().map(|byte| format!("{byte:02X}")).collect();
        let _ = writeln!(out, "  DBB {:>4}  {}", row * 8, hex.join(" "));
    }
    out.push('\n');
}
