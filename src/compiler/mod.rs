//! Compiler: checked blocks of statements to per-block bytecode, with the static checks of the
//! front end (operand ranges, labels, FB parameters, operation sets, block existence).

mod add_constant;
pub mod arena;
mod brackets;
pub mod builtin;
pub mod bytecode;
mod calls;
pub mod cost;
pub mod error;
pub mod fuse;
pub mod lower;
pub mod needs;
mod ranges;
pub mod specialise;
pub mod step7;

use std::collections::HashMap;

use crate::address::{Layout, range};
pub use bytecode::Op;
pub use calls::describe_decl;
pub use error::CheckError;
pub use lower::Resolved;
pub use needs::{Need, Needs};

use crate::ast::{Block, BlockBody, BlockId, LogicBody, Operand, ParamDecl, SourceUnit, Statement};
use crate::mnemonics::{self, BlockKind, MnemonicSet, OpCode};
use crate::profile::{self, Profile};
use crate::source::{SourceSet, Span};
use builtin::{Builtin, IntegralFb};

/// One compiled logic block.
#[derive(Debug, Clone)]
pub struct CompiledBlock {
    pub id: BlockId,
    pub header: Span,
    pub mnemonics: MnemonicSet,
    pub params: Vec<ParamDecl>,
    pub code: Vec<Op>,
    /// Where each op was written, parallel to `code`.
    pub spans: Vec<Span>,
    /// Execution times as prefix sums: `elapsed[i]` is the time in ns of ops `0..i`, so the
    /// time of any straight run of ops is one subtraction (`code.len() + 1` entries).
    pub elapsed: Vec<u64>,
    /// Where the segments of a PG listing start: (first op, segment number), in order.
    pub segments: Vec<(u32, u16)>,
    /// STEP 7: the block's local data bytes on the L stack.
    pub local_bytes: u32,
}

impl CompiledBlock {
    /// The listing segment op `pc` is in, if the block has segments.
    pub fn segment_of(&self, pc: usize) -> Option<u16> {
        let after = self
            .segments
            .partition_point(|(first, _)| *first as usize <= pc);
        after
            .checked_sub(1)
            .map(|at| self.segments[at].1)
            .filter(|segment| *segment != 0)
    }

    /// The execution time of op `pc`.
    pub fn cost(&self, pc: usize) -> u64 {
        self.elapsed[pc + 1] - self.elapsed[pc]
    }
}

/// A data block's initial contents.
#[derive(Debug, Clone)]
pub struct DataBlockImage {
    pub id: BlockId,
    pub header: Span,
    pub words: Vec<u16>,
}

/// A compiled program: everything the VM needs, nothing it must look up by name.
#[derive(Debug, Clone)]
pub struct Program {
    pub profile: &'static Profile,
    pub layout: Layout,
    pub blocks: Vec<CompiledBlock>,
    pub data_blocks: Vec<DataBlockImage>,
    /// Actual parameters of each FB call, in declaration order.
    pub param_lists: Vec<Vec<Resolved>>,
    /// The operation after each `DO`, with its operand to be replaced at run time.
    pub indirect_templates: Vec<(OpCode, Resolved)>,
    /// The assignment list's symbols, to show operands by name.
    pub symbols: crate::symbols::Symbols,
    index: HashMap<BlockId, u16>,
    /// Every block's name, `"PB 3"`, made once: trace events share it without allocating.
    pub names: Vec<std::sync::Arc<str>>,
    /// The code as the VM runs it, with the FB bodies specialised for their actuals.
    pub arena: arena::Arena,
    /// Each block's bytes of local data on the L stack (STEP 7; 0 for STEP 5 blocks).
    pub local_bytes: Vec<u32>,
    /// The tables of the STEP 7 operations (empty for a STEP 5 program).
    pub s7: crate::step7::bytecode::S7Tables,
    /// What the STEP 5 program's checks asked of the CPU (empty for a STEP 7 program).
    pub needs: Needs,
}

/// An operand's places are the program's: the address model knows no compiled program.
impl<'a> crate::address::operand::Places<'a> {
    pub fn of(program: &'a Program) -> Self {
        Self {
            dialect: if program.s7.step7 {
                crate::dialect::Dialect::Step7
            } else {
                crate::dialect::Dialect::Step5
            },
            profile: program.profile,
            layout: program.layout,
            data_blocks: &program.s7.data_blocks,
            declared: &program.s7.declared_dbs,
        }
    }
}

impl Program {
    /// The blocks the program loads into the CPU: its code blocks and the data blocks of
    /// either dialect (a STEP 7 `TYPE` is no block of the CPU, only of the program's source).
    pub fn block_count(&self) -> usize {
        self.blocks.len() + self.data_blocks.len() + self.s7.data_blocks.len()
    }

    /// The program of compiled blocks: their names made once and the arena built.
    pub fn assemble(
        profile: &'static Profile,
        blocks: Vec<CompiledBlock>,
        data_blocks: Vec<DataBlockImage>,
        param_lists: Vec<Vec<Resolved>>,
        index: HashMap<BlockId, u16>,
        s7: crate::step7::bytecode::S7Tables,
    ) -> Program {
        let layout = Layout::new(&profile.sizes);
        let arena = arena::Arena::build(&blocks, &param_lists, (layout, &s7.places), true);
        let names = blocks
            .iter()
            .map(|block| std::sync::Arc::from(block.id.to_string()))
            .collect();
        let local_bytes = blocks.iter().map(|block| block.local_bytes).collect();
        Program {
            profile,
            layout,
            blocks,
            data_blocks,
            param_lists,
            indirect_templates: Vec::new(),
            symbols: crate::symbols::Symbols::default(),
            index,
            names,
            arena,
            local_bytes,
            s7,
            needs: Needs::default(),
        }
    }

    pub fn block_index(&self, id: BlockId) -> Option<u16> {
        self.index.get(&id).copied()
    }

    /// The program run op by op as compiled: no specialised bodies (every formal operand is
    /// resolved at run time, the path a parameter passed on from a calling FB takes) and no
    /// fused pairs. Tests compare the two.
    pub fn unoptimised(mut self) -> Self {
        let places = (self.layout, &self.s7.places[..]);
        self.arena = arena::Arena::build(&self.blocks, &self.param_lists, places, false);
        self
    }

    /// The program with every op interpreted: optimised, but no stretch runs as native code.
    /// Tests compare it with the native stretches.
    pub fn interpreted(mut self) -> Self {
        self.arena.native = false;
        self
    }

    /// The local data bytes of block `index`.
    pub fn local_bytes(&self, index: u16) -> u32 {
        self.local_bytes
            .get(usize::from(index))
            .copied()
            .unwrap_or(0)
    }

    /// The index of OB `number`, one of the OBs a CPU starts (their numbers fit a byte).
    pub fn ob(&self, number: u8) -> Option<u16> {
        self.block_index(BlockId {
            kind: BlockKind::Ob,
            number: u16::from(number),
        })
    }
}

/// The compiled program and every error and warning found. The program is only fit to run when
/// no error (as opposed to warning) was found.
#[derive(Debug)]
pub struct Compiled {
    pub program: Program,
    pub diagnostics: Vec<CheckError>,
}

pub fn compile(units: &[SourceUnit], sources: &SourceSet, profile: &'static Profile) -> Compiled {
    let mut compiler = Compiler {
        profile,
        layout: Layout::new(&profile.sizes),
        sources,
        index: HashMap::new(),
        data_numbers: Vec::new(),
        generated_dbs: Vec::new(),
        fb_params: HashMap::new(),
        param_lists: Vec::new(),
        templates: Vec::new(),
        diagnostics: Vec::new(),
        needs: Needs::default(),
    };
    let (logic, data) = compiler.collect(units);
    let blocks: Vec<CompiledBlock> = logic
        .iter()
        .map(|(block, set)| compiler.compile_block(block, *set))
        .collect();
    let data_blocks = data.iter().map(|block| data_image(block)).collect();
    compiler.diagnostics.sort_by_key(|diagnostic| {
        let span = diagnostic.span();
        (span.file, span.start)
    });
    let program = Program::assemble(
        profile,
        blocks,
        data_blocks,
        compiler.param_lists,
        compiler.index,
        crate::step7::bytecode::S7Tables::default(),
    );
    let mut program = program;
    program.indirect_templates = compiler.templates;
    program.needs = compiler.needs;
    Compiled {
        program,
        diagnostics: compiler.diagnostics,
    }
}

fn data_image(block: &Block) -> DataBlockImage {
    let mut words = Vec::new();
    if let BlockBody::Data(data) = &block.body {
        for word in data {
            let values = std::iter::once(word.constant.value)
                .chain(word.constant.extra_words.iter().map(|w| u32::from(*w)));
            let wide = word.constant.format.words() == 2;
            let mut at = usize::from(word.index);
            for value in values {
                let parts: &[u16] = if wide {
                    &[(value >> 16) as u16, value as u16]
                } else {
                    &[value as u16]
                };
                for part in parts {
                    if words.len() <= at {
                        words.resize(at + 1, 0);
                    }
                    words[at] = *part;
                    at += 1;
                }
            }
        }
    }
    DataBlockImage {
        id: block.id,
        header: block.header,
        words,
    }
}

struct Compiler<'a> {
    profile: &'static Profile,
    layout: Layout,
    sources: &'a SourceSet,
    index: HashMap<BlockId, u16>,
    data_numbers: Vec<BlockId>,
    /// DBs that a `G DB` may create at run time.
    generated_dbs: Vec<u16>,
    fb_params: HashMap<BlockId, Vec<ParamDecl>>,
    param_lists: Vec<Vec<Resolved>>,
    templates: Vec<(OpCode, Resolved)>,
    diagnostics: Vec<CheckError>,
    needs: Needs,
}

impl<'a> Compiler<'a> {
    fn where_is(&self, span: Span) -> String {
        let file = self.sources.get(span.file);
        format!("{}:{}", file.name, file.line_of(span.start))
    }

    /// Registers every block, reporting duplicates and blocks this CPU lacks.
    fn collect<'u>(
        &mut self,
        units: &'u [SourceUnit],
    ) -> (Vec<(&'u Block, MnemonicSet)>, Vec<&'u Block>) {
        let mut first_seen: HashMap<BlockId, Span> = HashMap::new();
        let mut logic = Vec::new();
        let mut data = Vec::new();
        for unit in units {
            for block in &unit.blocks {
                if let Some(first) = first_seen.get(&block.id) {
                    self.diagnostics.push(CheckError::DuplicateBlock {
                        id: block.id.to_string(),
                        at: block.header,
                        first: self.where_is(*first),
                    });
                    continue;
                }
                first_seen.insert(block.id, block.header);
                if matches!(block.id.kind, BlockKind::Fx | BlockKind::Dx)
                    && !self.needs.ask(Need::ExtendedBlocks, self.profile)
                {
                    self.diagnostics.push(CheckError::ExtendedBlock {
                        id: block.id.to_string(),
                        kind: block.id.kind.name(),
                        cpu: self.profile.name,
                        at: block.header,
                    });
                }
                match &block.body {
                    BlockBody::Logic(body) => {
                        self.index.insert(block.id, logic.len() as u16);
                        if block.id.kind.is_function() {
                            self.fb_params.insert(block.id, body.params.clone());
                        }
                        for statement in &body.statements {
                            if let (OpCode::GenerateDb, Operand::Block(id)) =
                                (statement.op, &statement.operand)
                            {
                                self.generated_dbs.push(id.number);
                            }
                        }
                        logic.push((block, unit.mnemonics));
                    }
                    BlockBody::Data(_) => {
                        self.data_numbers.push(block.id);
                        data.push(block);
                    }
                }
            }
        }
        self.declare_integral_fbs();
        (logic, data)
    }

    /// The integral FBs of the profile that the program does not define, so their calls are
    /// checked like calls of the program's own FBs.
    fn declare_integral_fbs(&mut self) {
        for &number in self.profile.integral_fbs {
            let id = BlockId {
                kind: BlockKind::Fb,
                number: u16::from(number),
            };
            if let (false, Some(fb)) = (self.index.contains_key(&id), IntegralFb::of(number)) {
                self.fb_params.insert(id, fb.declarations());
            }
        }
    }

    /// The built-in block a call of `id` runs: one of the profile's, not defined by the
    /// program.
    fn builtin(&self, id: BlockId) -> Option<Builtin> {
        if self.index.contains_key(&id) {
            return None;
        }
        match id.kind {
            BlockKind::Fb => u8::try_from(id.number)
                .ok()
                .filter(|&number| self.profile.has_integral_fb(number))
                .and_then(IntegralFb::of)
                .map(Builtin::Integral),
            BlockKind::Ob => u8::try_from(id.number)
                .ok()
                .and_then(|number| self.profile.system_ob(number))
                .map(|system| Builtin::SystemOb(system.ob)),
            _ => None,
        }
    }

    /// A call of a built-in block: its op, its parameters checked.
    fn builtin_call(
        &mut self,
        context: &BlockContext<'_>,
        statement: &Statement,
        id: BlockId,
        block: Builtin,
    ) -> Option<Op> {
        let params = match block {
            Builtin::Integral(_) => self.call_params(context, statement, id)?,
            Builtin::SystemOb(_) => bytecode::NO_PARAMS,
        };
        Some(Op::Builtin {
            block,
            conditional: statement.op == OpCode::JumpConditional,
            params,
        })
    }

    fn compile_block(&mut self, block: &Block, set: MnemonicSet) -> CompiledBlock {
        let BlockBody::Logic(body) = &block.body else {
            unreachable!("only logic blocks are compiled")
        };
        if body.end.is_none() {
            self.diagnostics.push(CheckError::MissingBlockEnd {
                id: block.id.to_string(),
                at: block.header,
            });
        }
        self.diagnostics
            .extend(brackets::check(body, set, self.profile, &mut self.needs));
        let labels = self.labels(body);
        let mut compiled = CompiledBlock {
            id: block.id,
            header: block.header,
            mnemonics: set,
            params: body.params.clone(),
            code: Vec::with_capacity(body.statements.len()),
            spans: Vec::with_capacity(body.statements.len()),
            elapsed: Vec::with_capacity(body.statements.len() + 1),
            segments: Vec::new(),
            local_bytes: 0,
        };
        compiled.elapsed.push(0);
        let context = BlockContext {
            id: block.id,
            set,
            params: &body.params,
            labels: &labels,
        };
        for (pc, statement) in body.statements.iter().enumerate() {
            let (op, cost_op) = self
                .statement(&context, statement, body.statements.get(pc + 1))
                .unwrap_or((Op::Nop, Op::Nop));
            compiled.code.push(op);
            compiled.spans.push(statement.span);
            if compiled.segments.last().map(|(_, segment)| *segment) != Some(statement.segment) {
                compiled.segments.push((pc as u32, statement.segment));
            }
            let before = *compiled.elapsed.last().expect("starts with 0");
            compiled
                .elapsed
                .push(before + u64::from(cost::cost(cost_op, &self.profile.timings)));
        }
        compiled
    }

    fn labels(&mut self, body: &LogicBody) -> HashMap<String, (u32, Span)> {
        let mut labels: HashMap<String, (u32, Span)> = HashMap::new();
        for (pc, statement) in body.statements.iter().enumerate() {
            let Some(label) = &statement.label else {
                continue;
            };
            let name = label.text.to_ascii_uppercase();
            if name.chars().count() > 4 {
                self.diagnostics.push(CheckError::LabelTooLong {
                    name: label.text.clone(),
                    at: label.span,
                    length: label.text.chars().count(),
                });
            }
            if let Some((_, first)) = labels.get(&name) {
                self.diagnostics.push(CheckError::DuplicateLabel {
                    name: label.text.clone(),
                    at: label.span,
                    first: *first,
                });
            } else {
                labels.insert(name, (pc as u32, label.span));
            }
        }
        labels
    }

    /// The op of one statement, and the op whose execution time it costs (they differ for
    /// formal operands, which cost what the substituted operation costs).
    fn statement(
        &mut self,
        context: &BlockContext<'_>,
        statement: &Statement,
        next: Option<&Statement>,
    ) -> Option<(Op, Op)> {
        let info = mnemonics::op_info(statement.op);
        let op_word = mnemonics::op_word(context.set, statement.op);
        if let Some(feature) = info
            .feature
            .filter(|feature| !self.needs.ask(Need::Feature(*feature), self.profile))
        {
            return self.fail(CheckError::OperationNotOnCpu {
                op: op_word.to_string(),
                at: statement.op_span,
                cpu: self.profile.name,
                feature: feature.name(),
                profiles: profile::having(feature).join(", "),
            });
        }
        if info.supplementary && !context.id.kind.is_function() {
            return self.fail(CheckError::Supplementary {
                op: op_word.to_string(),
                at: statement.op_span,
                block: context.id.to_string(),
                help: supplementary_help(context.set, statement),
            });
        }
        let resolved = self.resolve(context, statement)?;
        if let (Operand::Block(id), OpCode::JumpUnconditional | OpCode::JumpConditional) =
            (&statement.operand, statement.op)
            && let Some(block) = self.builtin(*id)
        {
            let op = self.builtin_call(context, statement, *id, block)?;
            return Some((op, op));
        }
        let params = match resolved {
            Resolved::Block {
                kind,
                index: Some(_),
                ..
            } if kind.is_function() => {
                let id = match statement.operand {
                    Operand::Block(id) => id,
                    _ => unreachable!("block operands resolve to blocks"),
                };
                self.call_params(context, statement, id)?
            }
            _ => bytecode::NO_PARAMS,
        };
        let lowered = if statement.op == OpCode::AddConstant {
            add_constant::lower(&statement.operand)
        } else {
            lower::lower(statement.op, resolved, self.layout, params)
        };
        let Some(mut op) = lowered else {
            return self.fail(self.not_allowed(context, statement, resolved));
        };
        let four_accumulators = self.profile.accumulators == 4;
        match op {
            Op::Arithmetic(kind) if four_accumulators => op = Op::ArithmeticStack(kind),
            Op::FloatArithmetic { kind, .. } if four_accumulators => {
                op = Op::FloatArithmetic { kind, stack: true }
            }
            Op::Enter if !self.needs.ask(Need::FourAccumulators, self.profile) => {
                return self.fail(CheckError::NotOnCpu {
                    op: op_word.to_string(),
                    at: statement.op_span,
                    cpu: self.profile.name,
                    reason: "it moves ACCU 2 to ACCU 3, and this CPU has two accumulators",
                });
            }
            _ => {}
        }
        let mut cost_op = op;
        if let Resolved::Formal(index) = resolved {
            let decl = &context.params[usize::from(index)];
            match calls::formal_op(statement.op, decl, self.layout) {
                Some(substituted) => cost_op = substituted,
                None => {
                    return self.fail(CheckError::OperandNotAllowed {
                        op: op_word.to_string(),
                        at: statement.operand_span,
                        help: Some(format!(
                            "parameter `{}` is of kind {}",
                            decl.name.text,
                            calls::describe_decl(decl, context.set)
                        )),
                    });
                }
            }
        }
        if let Op::Indirect { source, .. } = op {
            let template = self.indirect_template(context, statement, next)?;
            op = Op::Indirect { source, template };
        }
        Some((op, cost_op))
    }

    fn fail<T>(&mut self, error: CheckError) -> Option<T> {
        self.diagnostics.push(error);
        None
    }

    fn indirect_template(
        &mut self,
        context: &BlockContext<'_>,
        statement: &Statement,
        next: Option<&Statement>,
    ) -> Option<u16> {
        let op_word = mnemonics::op_word(context.set, statement.op).to_string();
        // The next operation must take an operand, and may not be another `DO`.
        let Some(next) = next.filter(|next| next.op != OpCode::Indirect) else {
            return self.fail(CheckError::IndirectTarget {
                op: op_word,
                at: statement.op_span,
            });
        };
        let resolved = match next.operand {
            Operand::Address(_) | Operand::Number(_) => self.resolve(context, next)?,
            _ => {
                return self.fail(CheckError::IndirectTarget {
                    op: op_word,
                    at: statement.op_span,
                });
            }
        };
        self.templates.push((next.op, resolved));
        Some((self.templates.len() - 1) as u16)
    }

    fn resolve(&mut self, context: &BlockContext<'_>, statement: &Statement) -> Option<Resolved> {
        let at = statement.operand_span;
        match &statement.operand {
            Operand::Block(id) => Some(self.resolve_block(statement.op, *id, at)),
            Operand::Symbol(name) => self.resolve_symbol(context, statement, name),
            value => self.resolve_value(context.set, value, at),
        }
    }

    /// An operand that names no block and no symbol: range-checked addresses, constants,
    /// numbers.
    fn resolve_value(&mut self, set: MnemonicSet, operand: &Operand, at: Span) -> Option<Resolved> {
        match operand {
            Operand::Number(value) => Some(Resolved::Number(*value)),
            Operand::Constant(constant) => Some(Resolved::Constant(constant.value)),
            Operand::Address(address) => {
                let need = Need::Address {
                    area: address.area,
                    index: address.index,
                };
                self.needs.ask(need, self.profile);
                if let Err(out) = range::check(*address, set, self.profile) {
                    let (what, range, cpu) = (out.what, out.range, self.profile.name);
                    return self.fail(CheckError::OperandRange {
                        what,
                        at,
                        range,
                        cpu,
                    });
                }
                Some(Resolved::Address(*address))
            }
            Operand::None | Operand::Block(_) | Operand::Symbol(_) => Some(Resolved::None),
            // A symbol left unresolved: the assignment list's check has reported it.
            Operand::Assigned(_) => None,
        }
    }

    fn resolve_block(&mut self, op: OpCode, id: BlockId, at: Span) -> Resolved {
        let index = self.index.get(&id).copied();
        let known_data = self.data_numbers.contains(&id) || self.generated_dbs.contains(&id.number);
        match op {
            OpCode::JumpUnconditional | OpCode::JumpConditional
                if index.is_none() && !id.kind.is_data() =>
            {
                let elsewhere = builtin::profiles_with(id);
                if elsewhere.is_empty() {
                    self.diagnostics.push(CheckError::UndefinedBlock {
                        id: id.to_string(),
                        at,
                    });
                } else if !self.needs.ask(Need::BuiltinBlock(id), self.profile) {
                    self.diagnostics.push(CheckError::BlockNotOnCpu {
                        id: id.to_string(),
                        at,
                        cpu: self.profile.name,
                        profiles: elsewhere.join(", "),
                    });
                }
            }
            OpCode::OpenDb if id.kind.is_data() && !known_data => {
                self.diagnostics.push(CheckError::UndefinedDb {
                    id: id.to_string(),
                    at,
                });
            }
            _ => {}
        }
        Resolved::Block {
            kind: id.kind,
            number: id.number,
            index,
        }
    }

    fn resolve_symbol(
        &mut self,
        context: &BlockContext<'_>,
        statement: &Statement,
        name: &str,
    ) -> Option<Resolved> {
        let at = statement.operand_span;
        let is_label_jump = matches!(
            statement.op,
            OpCode::JumpUnconditional | OpCode::JumpConditional
        );
        if !context.id.kind.is_function() {
            if is_label_jump {
                return self.fail(CheckError::LabelOutsideFb {
                    op: mnemonics::op_word(context.set, statement.op),
                    name: name.to_string(),
                    at,
                    block: context.id.to_string(),
                });
            }
            return self.fail(CheckError::FormalOutsideFb {
                name: name.to_string(),
                at,
            });
        }
        if let Some(index) = context
            .params
            .iter()
            .position(|param| param.name.text.eq_ignore_ascii_case(name))
        {
            return Some(Resolved::Formal(index as u8));
        }
        if let Some((pc, _)) = context.labels.get(&name.to_ascii_uppercase()) {
            return Some(Resolved::Label(*pc));
        }
        let candidates = context
            .params
            .iter()
            .map(|param| param.name.text.as_str())
            .chain(context.labels.keys().map(String::as_str));
        let help = crate::suggest::one_edit_from(name, candidates)
            .map(|close| format!("did you mean `={close}`?"));
        self.fail(CheckError::UndefinedSymbol {
            name: name.to_string(),
            block: context.id.to_string(),
            at,
            help,
        })
    }

    fn not_allowed(
        &self,
        context: &BlockContext<'_>,
        statement: &Statement,
        resolved: Resolved,
    ) -> CheckError {
        let set = context.set;
        let op_word = mnemonics::op_word(set, statement.op).to_string();
        if let (Some(range), Resolved::Number(value)) =
            (ranges::number_range(statement.op), resolved)
        {
            return CheckError::OperandRange {
                what: format!("{op_word} {value}"),
                at: statement.operand_span,
                range: range.to_string(),
                cpu: self.profile.name,
            };
        }
        let label_jump = matches!(
            statement.op,
            OpCode::JumpZero
                | OpCode::JumpNotZero
                | OpCode::JumpPositive
                | OpCode::JumpMinus
                | OpCode::JumpOverflow
        );
        let (ju, jc) = (
            mnemonics::op_word(set, OpCode::JumpUnconditional),
            mnemonics::op_word(set, OpCode::JumpConditional),
        );
        let help = match (statement.op, resolved) {
            (_, Resolved::Block { .. }) if label_jump => Some(format!(
                "`{op_word}` jumps to a label in this FB (`{op_word} =M001`); to call a block use `{ju} PB 3`, or `{jc} PB 3` when the RLO is 1"
            )),
            (OpCode::JumpUnconditional | OpCode::JumpConditional, Resolved::Block { kind, .. })
                if kind.is_data() =>
            {
                Some(format!(
                    "data blocks are opened, not called: `{} DB n`",
                    mnemonics::op_word(set, OpCode::OpenDb)
                ))
            }
            (OpCode::OpenDb, Resolved::Block { .. }) => Some(
                "`C DB n` opens a data block (DB); DX blocks are not opened by `C`".to_string(),
            ),
            _ => {
                let info = mnemonics::op_info(statement.op);
                let example = match set {
                    MnemonicSet::English => info.example_en,
                    MnemonicSet::German => info.example_de,
                };
                (!example.is_empty()).then(|| format!("for example `{op_word} {example}`"))
            }
        };
        CheckError::OperandNotAllowed {
            op: op_word,
            at: statement.operand_span,
            help,
        }
    }
}

/// What the checks of one statement need to know about its block.
struct BlockContext<'b> {
    id: BlockId,
    set: MnemonicSet,
    params: &'b [ParamDecl],
    labels: &'b HashMap<String, (u32, Span)>,
}

/// What to write instead of a supplementary operation outside an FB: a load of a constant with
/// `LW`/`LD` is what `L` does; anything else moves into an FB.
fn supplementary_help(set: MnemonicSet, statement: &Statement) -> String {
    let loads_constant = matches!(statement.op, OpCode::LoadBitPattern | OpCode::LoadDecimal)
        && matches!(statement.operand, Operand::Constant(_));
    if loads_constant {
        let load = mnemonics::op_word(set, OpCode::Load);
        format!(
            "`{}` loads a formal operand (`=NAME`) in an FB; to load a constant, write `{load}`",
            mnemonics::op_word(set, statement.op)
        )
    } else {
        "move this logic into an FB, or use a basic operation".to_string()
    }
}
