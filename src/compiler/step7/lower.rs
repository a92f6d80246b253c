//! One STEP 7 logic block's statements to ops. What STEP 5 has too runs as the shared op; the
//! rest as [`S7Code`]s.

use std::collections::HashMap;

use crate::ast::BlockId;
use crate::compiler::bytecode::{
    Arith, CALL_FROM_CONDITIONAL, CALL_FROM_FB, ImageBit, IndirectSource, JumpCondition, NO_PARAMS,
    Op, TimerKind, Width, Write,
};
use crate::compiler::{CheckError, CompiledBlock, Resolved, cost};
use crate::mnemonics::{BlockKind, MnemonicSet};
use crate::rules::jump::Jump;
use crate::rules::status::Combination;
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, CallParam, CallSpec, ConstKind, DataType, S7Address, S7Area, S7Block, S7BlockKind,
    S7BlockRef, S7Body, S7Op, S7Operand, S7Statement, VarKind,
};
use crate::step7::bytecode::{
    AWLSIM_SFC_CLOCK_RESET, AWLSIM_SFC_NOP, AWLSIM_SFC_REBOOT, AWLSIM_SFC_SHUTDOWN, BLKMOV, FILL,
    FbCall, FcCall, McrCode, MemOp, ParamCopy, Place, READ_CLK, S7Code, SET_CLK, SfcCall, TIME_TCK,
    Target, WAIT,
};
use crate::suggest::one_edit_from;

use super::layout::{Home, START_INFO_BYTES};
use super::operand::{Scope, constant_value, not_an_operand};

/// A called FC or FB: its id, its index in the program, its interface.
#[derive(Clone, Copy)]
struct Callee<'i> {
    id: BlockId,
    block: u16,
    interface: &'i super::layout::Interface,
}

/// The code of a block as it is emitted.
struct Emitter {
    code: Vec<Op>,
    spans: Vec<Span>,
    elapsed: Vec<u64>,
    segments: Vec<(u32, u16)>,
    labels: HashMap<String, u32>,
    /// Jumps to patch: (op, label, where it was written).
    fixups: Vec<(usize, String, Span)>,
}

impl Emitter {
    fn emit(&mut self, op: Op, span: Span, timings: &crate::profile::Timings) {
        let before = *self.elapsed.last().unwrap_or(&0);
        self.code.push(op);
        self.spans.push(span);
        self.elapsed
            .push(before + u64::from(cost::cost(op, timings)));
    }
}

pub(crate) fn width_of(width: AccessWidth) -> Width {
    match width {
        AccessWidth::Bit | AccessWidth::Byte => Width::Byte,
        AccessWidth::Word => Width::Word,
        AccessWidth::Double => Width::Double,
    }
}

fn timer_kind(op: S7Op) -> Option<TimerKind> {
    Some(match op {
        S7Op::TimerPulse => TimerKind::Pulse,
        S7Op::TimerExtendedPulse => TimerKind::ExtendedPulse,
        S7Op::TimerOnDelay => TimerKind::OnDelay,
        S7Op::TimerRetentiveOnDelay => TimerKind::StoredOnDelay,
        S7Op::TimerOffDelay => TimerKind::OffDelay,
        _ => return None,
    })
}

/// `A AN O ON X XN`: how the scanned bit combines with the RLO.
fn scan(op: S7Op) -> Option<Combination> {
    match op {
        S7Op::Logic(combination) => Some(combination),
        _ => None,
    }
}

/// A conditional jump STEP 5 does not have (`JC` … `JUO`), as the VM runs it.
fn step7_jump(op: S7Op) -> Jump {
    match op {
        S7Op::JumpIfRlo => Jump::Rlo,
        S7Op::JumpIfNotRlo => Jump::NotRlo,
        S7Op::JumpIfRloSave => Jump::RloSavingBr,
        S7Op::JumpIfNotRloSave => Jump::NotRloSavingBr,
        S7Op::JumpIfBr => Jump::Br,
        S7Op::JumpIfNotBr => Jump::NotBr,
        S7Op::JumpIfStoredOverflow => Jump::StoredOverflow,
        S7Op::JumpIfPositiveOrZero => Jump::PositiveOrZero,
        S7Op::JumpIfMinusOrZero => Jump::MinusOrZero,
        _ => Jump::Unordered,
    }
}

fn mem_op(op: S7Op) -> Option<MemOp> {
    if let Some(combination) = scan(op) {
        return Some(MemOp::Scan(combination));
    }
    Some(match op {
        S7Op::Assign => MemOp::Assign,
        S7Op::Set => MemOp::Set,
        S7Op::Reset => MemOp::Reset,
        S7Op::EdgePositive => MemOp::EdgePositive,
        S7Op::EdgeNegative => MemOp::EdgeNegative,
        S7Op::Load => MemOp::Load,
        S7Op::LoadCoded => MemOp::LoadCoded,
        S7Op::Transfer => MemOp::Transfer,
        S7Op::TimerPulse => MemOp::TimerPulse,
        S7Op::TimerExtendedPulse => MemOp::TimerExtendedPulse,
        S7Op::TimerOnDelay => MemOp::TimerOnDelay,
        S7Op::TimerRetentiveOnDelay => MemOp::TimerRetentiveOnDelay,
        S7Op::TimerOffDelay => MemOp::TimerOffDelay,
        S7Op::Enable => MemOp::Enable,
        S7Op::CountUp => MemOp::CountUp,
        S7Op::CountDown => MemOp::CountDown,
        S7Op::LoadAr1 => MemOp::LoadAr1,
        S7Op::LoadAr2 => MemOp::LoadAr2,
        S7Op::TransferAr1 => MemOp::TransferAr1,
        S7Op::TransferAr2 => MemOp::TransferAr2,
        _ => return None,
    })
}

/// Operations on the accumulators and the status word alone.
fn accumulator_only(op: S7Op) -> bool {
    use S7Op::*;
    matches!(
        op,
        SetRlo
            | ClearRlo
            | Not
            | Save
            | LoadStatusWord
            | TransferStatusWord
            | AddInt
            | SubInt
            | MulInt
            | DivInt
            | AddDint
            | SubDint
            | MulDint
            | DivDint
            | ModDint
            | AddReal
            | SubReal
            | MulReal
            | DivReal
            | Abs
            | Real(_)
            | NegInt
            | NegDint
            | NegReal
            | InvInt
            | InvDint
            | CmpInt(_)
            | CmpDint(_)
            | CmpReal(_)
            | IntToDint
            | IntToBcd
            | BcdToInt
            | BcdToDint
            | DintToBcd
            | DintToReal
            | Round
            | RoundUp
            | RoundDown
            | Truncate
            | SwapBytesWord
            | SwapBytesDouble
            | SwapAccus
            | Push
            | Pop
            | Enter
            | Leave
            | Increment
            | Decrement
    )
}

fn is_word_logic(op: S7Op) -> bool {
    matches!(
        op,
        S7Op::AndWord
            | S7Op::OrWord
            | S7Op::XorWord
            | S7Op::AndDouble
            | S7Op::OrDouble
            | S7Op::XorDouble
    )
}

impl super::Compiler<'_> {
    pub(super) fn compile_block(
        &mut self,
        block: &S7Block,
        id: BlockId,
        set: MnemonicSet,
    ) -> CompiledBlock {
        let interface = self.interfaces.get(&id).cloned().unwrap_or_default();
        // An OB's local data hold its 20 bytes of start information, declared or not
        // (see `vm::start_info`): the blocks it calls start after them.
        let declared = if id.kind == BlockKind::Ob {
            interface.local_bytes.max(START_INFO_BYTES)
        } else {
            interface.local_bytes
        };
        let S7Body::Logic(statements) = &block.body else {
            unreachable!("only logic blocks are compiled")
        };
        // The local data also cover what the block addresses absolutely (`T LB 0` with no
        // temporaries): a block it calls starts after them, so neither overwrites the other.
        let declared = statements
            .iter()
            .flat_map(|statement| {
                let params = statement.call.iter().flat_map(|call| &call.params);
                std::iter::once(&statement.operand).chain(params.map(|param| &param.actual))
            })
            .map(absolute_local_end)
            .fold(declared, u32::max);
        self.scratch_base = declared;
        self.scratch_bytes = 0;
        let scope = Scope {
            interface: &interface,
            block: id.to_string(),
        };
        let mut out = Emitter {
            code: Vec::new(),
            spans: Vec::new(),
            elapsed: vec![0],
            segments: Vec::new(),
            labels: HashMap::new(),
            fixups: Vec::new(),
        };
        // A block with `MCRA` has the MCR-aware writes, and starts without the dependency
        // (see `vm::s7::mcr`); no other block pays for the MCR.
        self.mcr_block = statements.iter().any(|s| s.op == S7Op::McrActivate);
        if self.mcr_block {
            let start = Op::S7(S7Code::Mcr(McrCode::Activate(false)));
            out.emit(start, block.header, &self.profile.timings);
        }
        let mut network = 0;
        let mut label_spans = HashMap::new();
        for (index, statement) in statements.iter().enumerate() {
            if statement.network != network {
                network = statement.network;
                out.segments.push((out.code.len() as u32, network));
            }
            if let Some(label) = &statement.label {
                let name = label.text.to_ascii_uppercase();
                if let Some(first) = label_spans.insert(name.clone(), label.span) {
                    self.errors.push(CheckError::DuplicateLabel {
                        name: label.text.clone(),
                        at: label.span,
                        first,
                    });
                }
                out.labels.insert(name, out.code.len() as u32);
            }
            let following_jumps = statements[index + 1..]
                .iter()
                .take_while(|s| s.op == S7Op::JumpAlways && s.label.is_none())
                .count();
            let first_error = self.errors.len();
            if let Err(error) = self.lower(statement, &scope, &mut out, following_jumps) {
                self.errors.push(error);
            }
            self.name_operation(first_error, statement, set);
        }
        // The block's end: `BE` as STEP 7 places it after the last network.
        let end = block.end.unwrap_or(block.header);
        out.emit(Op::BlockEnd, end, &self.profile.timings);
        for (at, label, span) in std::mem::take(&mut out.fixups) {
            let Some(&target) = out.labels.get(&label.to_ascii_uppercase()) else {
                let labels = statements.iter().filter_map(|s| s.label.as_ref());
                let help = match one_edit_from(&label, labels.map(|l| l.text.as_str())) {
                    Some(close) => format!("did you mean `{close}`?"),
                    None => "labels are written `NAME:` before a statement of the same block"
                        .to_string(),
                };
                self.errors.push(CheckError::UndefinedLabel {
                    name: label,
                    block: id.to_string(),
                    at: span,
                    help,
                });
                continue;
            };
            out.code[at] = match out.code[at] {
                Op::Jump(condition, _) => Op::Jump(condition, target),
                Op::S7(S7Code::Jump { jump, .. }) => Op::S7(S7Code::Jump {
                    jump,
                    target: target as u16,
                }),
                Op::S7(S7Code::Loop { .. }) => Op::S7(S7Code::Loop {
                    target: target as u16,
                }),
                Op::S7(S7Code::JumpList { entries, .. }) => Op::S7(S7Code::JumpList {
                    entries,
                    target: target as u16,
                }),
                other => other,
            };
        }
        CompiledBlock {
            id,
            header: block.header,
            mnemonics: set,
            params: Vec::new(),
            code: out.code,
            spans: out.spans,
            elapsed: out.elapsed,
            segments: out.segments,
            // The copies of its calls' actuals follow its own local data.
            local_bytes: declared + self.scratch_bytes,
        }
    }

    /// A call written without its parameters (`UC FC 105`, `UC SFC 20`), checked by `check`
    /// as a `CALL` that gives none: each missing parameter is an error that names it.
    fn without_params(
        &mut self,
        reference: &S7BlockRef,
        check: impl FnOnce(&mut Self, &CallSpec, &Scope<'_>),
    ) {
        let call = CallSpec {
            block: reference.clone(),
            instance: None,
            multi_instance: None,
            params: Vec::new(),
        };
        let empty = super::layout::Interface::default();
        let scope = Scope {
            interface: &empty,
            block: String::new(),
        };
        check(self, &call, &scope);
    }

    fn emit(&self, out: &mut Emitter, op: Op, span: Span) {
        out.emit(op, span, &self.profile.timings);
    }

    fn mem(&mut self, out: &mut Emitter, op: MemOp, place: Place, span: Span) {
        let place = self.tables.place(place);
        self.emit(out, Op::S7(S7Code::Mem { op, place }), span);
    }

    fn jump(&self, out: &mut Emitter, op: Op, statement: &S7Statement) -> Result<(), CheckError> {
        let S7Operand::Label(label) = &statement.operand else {
            return Err(not_an_operand(
                statement.operand_span,
                "a jump needs a label; this",
            ));
        };
        out.fixups
            .push((out.code.len(), label.text.clone(), label.span));
        self.emit(out, op, statement.span);
        Ok(())
    }

    fn lower(
        &mut self,
        statement: &S7Statement,
        scope: &Scope<'_>,
        out: &mut Emitter,
        following_jumps: usize,
    ) -> Result<(), CheckError> {
        let span = statement.span;
        let at = statement.operand_span;
        let op = statement.op;
        let resolved = self.resolved_operand(&statement.operand, op, at)?;
        let operand = resolved.as_ref().unwrap_or(&statement.operand);
        match op {
            S7Op::Logic(Combination::Or) if *operand == S7Operand::None => {
                self.emit(out, Op::S7(S7Code::Accu(S7Op::OrAlone)), span);
                Ok(())
            }
            S7Op::Logic(_) | S7Op::Assign | S7Op::Set | S7Op::Reset => {
                if let S7Operand::Condition(condition) = operand {
                    let combination = scan(op).unwrap_or(Combination::And);
                    self.emit(
                        out,
                        Op::S7(S7Code::Condition {
                            combination,
                            condition: *condition,
                        }),
                        span,
                    );
                    return Ok(());
                }
                if let S7Operand::Address(address) = operand
                    && !(self.mcr_block && matches!(op, S7Op::Assign | S7Op::Set | S7Op::Reset))
                    && let Some(shared) = self.image_bit_op(op, address)
                {
                    self.emit(out, shared, span);
                    return Ok(());
                }
                if let (S7Op::Set | S7Op::Reset, S7Operand::Address(address)) = (op, operand)
                    && matches!(address.area, S7Area::Timer | S7Area::Counter)
                {
                    let place = self.address_place(address, at)?;
                    let shared = match (op, place.target) {
                        (S7Op::Reset, Target::Timer(n)) => Op::ResetTimer(n),
                        (S7Op::Reset, Target::Counter(n)) => Op::ResetCounter(n),
                        (S7Op::Set, Target::Counter(n)) => Op::SetCounter(n),
                        _ => return Err(not_an_operand(at, "a timer")),
                    };
                    self.emit(out, shared, span);
                    return Ok(());
                }
                self.memory(out, op, operand, at, span, scope)
            }
            S7Op::EdgePositive | S7Op::EdgeNegative => {
                self.memory(out, op, operand, at, span, scope)
            }
            S7Op::Bracket(combination) => {
                self.emit(out, Op::S7(S7Code::Bracket(combination)), span);
                Ok(())
            }
            S7Op::CloseBracket => {
                self.emit(out, Op::S7(S7Code::CloseBracket), span);
                Ok(())
            }
            S7Op::OrAlone => {
                self.emit(out, Op::S7(S7Code::Accu(S7Op::OrAlone)), span);
                Ok(())
            }
            S7Op::Load => self.load(out, operand, at, span, scope),
            S7Op::Transfer => {
                if let S7Operand::Address(address) = operand
                    && !self.mcr_block
                    && address.width != AccessWidth::Bit
                    && let Some(byte) = self.image_byte(address)
                {
                    self.emit(out, Op::transfer_image(width_of(address.width), byte), span);
                    return Ok(());
                }
                self.memory(out, op, operand, at, span, scope)
            }
            S7Op::LoadCoded => self.memory(out, op, operand, at, span, scope),
            S7Op::TimerPulse
            | S7Op::TimerExtendedPulse
            | S7Op::TimerOnDelay
            | S7Op::TimerRetentiveOnDelay
            | S7Op::TimerOffDelay => {
                if let S7Operand::Address(address) = operand
                    && address.area == S7Area::Timer
                {
                    let place = self.address_place(address, at)?;
                    if let (Target::Timer(n), Some(kind)) = (place.target, timer_kind(op)) {
                        self.emit(out, Op::StartTimer(kind, n), span);
                        return Ok(());
                    }
                }
                self.memory(out, op, operand, at, span, scope)
            }
            S7Op::Enable | S7Op::CountUp | S7Op::CountDown => {
                self.memory(out, op, operand, at, span, scope)
            }
            S7Op::LoadAr1 | S7Op::LoadAr2 => {
                let ar = if op == S7Op::LoadAr1 { 1 } else { 2 };
                let code = match operand {
                    S7Operand::None => S7Code::LoadAr(ar),
                    S7Operand::AddressRegister(2) if ar == 1 => S7Code::LoadAr1FromAr2,
                    S7Operand::Constant(constant) => S7Code::LoadArConstant {
                        ar,
                        constant: self.tables.constant(constant.value),
                    },
                    S7Operand::PointerTo(inner) => {
                        let pointer = self.pointer_constant(inner, at, scope)?;
                        S7Code::LoadArConstant {
                            ar,
                            constant: self.tables.constant(pointer),
                        }
                    }
                    _ => return self.memory(out, op, operand, at, span, scope),
                };
                self.emit(out, Op::S7(code), span);
                Ok(())
            }
            S7Op::TransferAr1 | S7Op::TransferAr2 => {
                let ar = if op == S7Op::TransferAr1 { 1 } else { 2 };
                let code = match operand {
                    S7Operand::None => S7Code::TransferAr(ar),
                    S7Operand::AddressRegister(2) if ar == 1 => S7Code::TransferAr1ToAr2,
                    _ => return self.memory(out, op, operand, at, span, scope),
                };
                self.emit(out, Op::S7(code), span);
                Ok(())
            }
            S7Op::SwapAr => {
                self.emit(out, Op::S7(S7Code::SwapAr), span);
                Ok(())
            }
            S7Op::AddAr1 | S7Op::AddAr2 => {
                let ar = if op == S7Op::AddAr1 { 1 } else { 2 };
                let constant = match operand {
                    S7Operand::Constant(constant) => Some(self.tables.constant(constant.value)),
                    _ => None,
                };
                self.emit(out, Op::S7(S7Code::AddAr { ar, constant }), span);
                Ok(())
            }
            S7Op::AddConstant => {
                let S7Operand::Constant(constant) = operand else {
                    return Err(not_an_operand(at, "`+` needs a constant; this"));
                };
                let shared = match constant.kind {
                    ConstKind::Dint => Op::S7(S7Code::AddDouble {
                        constant: self.tables.constant(constant.value),
                    }),
                    _ => Op::AddConstant {
                        value: constant_value(constant),
                        double: false,
                    },
                };
                self.emit(out, shared, span);
                Ok(())
            }
            op if op.is_shift() => {
                let code = match operand {
                    S7Operand::Number(count) => S7Code::Shift {
                        op,
                        count: (*count).clamp(0, 255) as u8,
                    },
                    S7Operand::Constant(constant) => S7Code::Shift {
                        op,
                        count: constant.value.min(255) as u8,
                    },
                    _ => S7Code::Accu(op),
                };
                self.emit(out, Op::S7(code), span);
                Ok(())
            }
            S7Op::RotateLeftViaCc1 | S7Op::RotateRightViaCc1 => {
                self.emit(out, Op::S7(S7Code::Accu(op)), span);
                Ok(())
            }
            op if is_word_logic(op) => {
                let code = match operand {
                    S7Operand::Constant(constant) => S7Code::WordConstant {
                        op,
                        constant: self.tables.constant(constant.value),
                    },
                    _ => S7Code::Accu(op),
                };
                self.emit(out, Op::S7(code), span);
                Ok(())
            }
            S7Op::Increment | S7Op::Decrement => {
                let count = match operand {
                    S7Operand::Number(n) => (*n).clamp(0, 255) as u8,
                    S7Operand::Constant(constant) => constant.value as u8,
                    _ => 1,
                };
                let shared = Op::S7(S7Code::Shift { op, count });
                self.emit(out, shared, span);
                Ok(())
            }
            // `+I`/`-I` mean what STEP 5's `+F`/`-F` mean (16 bits wrapped, CC1/CC0 by the
            // wrapped result, OV and OS): the shared op, inline. Four accumulators move after.
            S7Op::AddInt | S7Op::SubInt if self.profile.accumulators == 2 => {
                let kind = if op == S7Op::AddInt {
                    Arith::Add
                } else {
                    Arith::Sub
                };
                self.emit(out, Op::Arithmetic(kind), span);
                Ok(())
            }
            op if accumulator_only(op) => {
                self.emit(out, Op::S7(S7Code::Accu(op)), span);
                Ok(())
            }
            S7Op::JumpAlways => self.jump(out, Op::Jump(JumpCondition::Always, 0), statement),
            // The jumps on the condition codes and OV change no status bit in either dialect.
            S7Op::JumpIfZero => self.jump(out, Op::Jump(JumpCondition::Zero, 0), statement),
            S7Op::JumpIfNotZero => self.jump(out, Op::Jump(JumpCondition::NotZero, 0), statement),
            S7Op::JumpIfPositive => self.jump(out, Op::Jump(JumpCondition::Positive, 0), statement),
            S7Op::JumpIfMinus => self.jump(out, Op::Jump(JumpCondition::Minus, 0), statement),
            S7Op::JumpIfOverflow => self.jump(out, Op::Jump(JumpCondition::Overflow, 0), statement),
            S7Op::JumpIfRlo
            | S7Op::JumpIfNotRlo
            | S7Op::JumpIfRloSave
            | S7Op::JumpIfNotRloSave
            | S7Op::JumpIfBr
            | S7Op::JumpIfNotBr
            | S7Op::JumpIfStoredOverflow
            | S7Op::JumpIfPositiveOrZero
            | S7Op::JumpIfMinusOrZero
            | S7Op::JumpIfUnordered => {
                let jump = step7_jump(op);
                self.jump(out, Op::S7(S7Code::Jump { jump, target: 0 }), statement)
            }
            S7Op::Loop => self.jump(out, Op::S7(S7Code::Loop { target: 0 }), statement),
            S7Op::JumpList => self.jump(
                out,
                Op::S7(S7Code::JumpList {
                    entries: following_jumps as u16,
                    target: 0,
                }),
                statement,
            ),
            S7Op::OpenDb | S7Op::OpenInstanceDb => {
                let instance = op == S7Op::OpenInstanceDb;
                if let (
                    S7Operand::Symbol { name, .. },
                    S7Operand::Block(S7BlockRef::Number { kind, .. }),
                ) = (&statement.operand, operand)
                    && *kind != S7BlockKind::Db
                {
                    self.symbol_block(name, &[S7BlockKind::Db], "");
                    return Ok(());
                }
                let code = match operand {
                    S7Operand::Block(S7BlockRef::Number { number, .. }) => S7Code::OpenDb {
                        instance,
                        slot: self.db_slot(*number, at),
                    },
                    S7Operand::BlockFrom { word, .. } => {
                        let place = self.place(word, at, scope)?;
                        S7Code::OpenDbFrom {
                            instance,
                            place: self.tables.place(Place {
                                width: AccessWidth::Word,
                                ..place
                            }),
                        }
                    }
                    other => {
                        let place = self.place(other, at, scope)?;
                        S7Code::OpenDbFrom {
                            instance,
                            place: self.tables.place(Place {
                                width: AccessWidth::Word,
                                ..place
                            }),
                        }
                    }
                };
                self.emit(out, Op::S7(code), span);
                Ok(())
            }
            S7Op::ExchangeDbRegisters => {
                self.emit(out, Op::S7(S7Code::ExchangeDbRegisters), span);
                Ok(())
            }
            S7Op::Call | S7Op::CallUnconditional | S7Op::CallConditional if self.mcr_block => {
                // The callee starts without the caller's MCR dependency; the caller has it
                // back after the call.
                self.emit(out, Op::S7(S7Code::Mcr(McrCode::Call(true))), span);
                self.mcr_block = false;
                let lowered = self.lower(statement, scope, out, following_jumps);
                self.mcr_block = true;
                self.emit(out, Op::S7(S7Code::Mcr(McrCode::Call(false))), span);
                lowered
            }
            S7Op::Call => {
                let Some(call) = &statement.call else {
                    return match operand {
                        S7Operand::Block(reference) => {
                            self.plain_call(out, reference, false, at, span)
                        }
                        _ if self.not_a_block(operand, "CALL") => Ok(()),
                        _ => Err(not_an_operand(at, "`CALL` needs a block; this")),
                    };
                };
                self.call(out, call, at, span, scope)
            }
            S7Op::CallUnconditional | S7Op::CallConditional => {
                if let S7Operand::BlockFrom {
                    kind: kind @ (S7BlockKind::Fc | S7BlockKind::Fb),
                    word,
                } = operand
                {
                    let place = self.place(word, at, scope)?;
                    let place = self.tables.place(Place {
                        width: AccessWidth::Word,
                        ..place
                    });
                    let mut flags = 0;
                    if *kind == S7BlockKind::Fb {
                        flags |= CALL_FROM_FB;
                    }
                    if op == S7Op::CallConditional {
                        flags |= CALL_FROM_CONDITIONAL;
                    }
                    let call = Op::Indirect {
                        source: IndirectSource::S7Block(place),
                        template: flags,
                    };
                    self.emit(out, call, span);
                    return Ok(());
                }
                let S7Operand::Block(reference) = operand else {
                    if self.not_a_block(operand, "") {
                        return Ok(());
                    }
                    return Err(not_an_operand(at, "`UC`/`CC` need an FC or FB; this"));
                };
                self.plain_call(out, reference, op == S7Op::CallConditional, at, span)
            }
            S7Op::BlockEnd => {
                self.emit(out, Op::BlockEndUnconditional, span);
                Ok(())
            }
            S7Op::BlockEndUnconditional => {
                self.emit(out, Op::BlockEndUnconditional, span);
                Ok(())
            }
            S7Op::BlockEndConditional => {
                self.emit(out, Op::BlockEndConditional, span);
                Ok(())
            }
            S7Op::McrActivate | S7Op::McrDeactivate | S7Op::McrOpen | S7Op::McrClose => {
                let code = match op {
                    S7Op::McrActivate => McrCode::Activate(true),
                    S7Op::McrDeactivate => McrCode::Activate(false),
                    S7Op::McrOpen => McrCode::Open,
                    _ => McrCode::Close,
                };
                self.emit(out, Op::S7(S7Code::Mcr(code)), span);
                Ok(())
            }
            S7Op::Nop | S7Op::Display => {
                self.emit(out, Op::Nop, span);
                Ok(())
            }
            S7Op::Assert(cmp) => {
                let S7Operand::Pair(left, right) = operand else {
                    return Err(not_an_operand(at, "`__ASSERT` needs two operands; this"));
                };
                let left = self.place(left, at, scope)?;
                let right = self.place(right, at, scope)?;
                let index = self.tables.place(left);
                self.tables.place(right);
                self.emit(out, Op::S7(S7Code::Assert { cmp, left: index }), span);
                Ok(())
            }
            S7Op::ResetStatusWord => {
                self.emit(out, Op::S7(S7Code::ResetStatusWord), span);
                Ok(())
            }
            S7Op::Sleep => {
                let ms = match operand {
                    S7Operand::Number(n) => *n,
                    S7Operand::Constant(constant) => i64::from(constant.value),
                    _ => 0,
                };
                self.emit(
                    out,
                    Op::S7(S7Code::Sleep {
                        ms: ms.clamp(0, i64::from(u16::MAX)) as u16,
                    }),
                    span,
                );
                Ok(())
            }
            S7Op::Feature => {
                let (target, value) = match operand {
                    S7Operand::Pair(a, b) => (feature_number(a).unwrap_or(0), feature_number(b)),
                    other => (feature_number(other).unwrap_or(0), None),
                };
                self.emit(out, Op::S7(S7Code::Feature { target, value }), span);
                Ok(())
            }
            other => Err(CheckError::NotSimulated {
                what: format!("`{other:?}`"),
                why: "this STEP 7 operation is not simulated yet".into(),
                at: statement.op_span,
            }),
        }
    }

    /// A bit operation on an `I`/`Q`/`M` bit, run inline.
    fn image_bit_op(&self, op: S7Op, address: &S7Address) -> Option<Op> {
        if address.width != AccessWidth::Bit {
            return None;
        }
        let bit = ImageBit {
            byte: self.image_byte(address)?,
            bit: address.bit,
        };
        if let Some(combination) = scan(op) {
            return Some(Op::S7Scan(combination, bit));
        }
        Some(match op {
            S7Op::Assign => Op::S7Write(Write::Assign, bit),
            S7Op::Set => Op::S7Write(Write::Set, bit),
            S7Op::Reset => Op::S7Write(Write::Reset, bit),
            _ => return None,
        })
    }

    /// An operation on the place its operand names.
    fn memory(
        &mut self,
        out: &mut Emitter,
        op: S7Op,
        operand: &S7Operand,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let Some(mut mem) = mem_op(op) else {
            return Err(not_an_operand(at, "this operand"));
        };
        if self.mcr_block {
            mem = match mem {
                MemOp::Assign => MemOp::McrAssign,
                MemOp::Set => MemOp::McrSet,
                MemOp::Reset => MemOp::McrReset,
                MemOp::Transfer => MemOp::McrTransfer,
                other => other,
            };
        }
        let place = self.place(operand, at, scope)?;
        self.mem(out, mem, place, span);
        Ok(())
    }

    /// `P##name`: an area-crossing pointer to a variable of the block's interface: area L
    /// (16#86) for a temporary, DI (16#85) for an FB's variable in its instance DB.
    fn pointer_to(
        &self,
        inner: &S7Operand,
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<u32, CheckError> {
        let S7Operand::Local(path) = inner else {
            return Err(not_an_operand(
                at,
                "a pointer to a variable of the block (`P##name`) is simulated; this",
            ));
        };
        let (variable, _, offset) = self.resolve_local(path, at, scope)?;
        let (area, base) = match variable.home {
            Home::Local(base) => (0x86, base.0),
            Home::Instance(base) => (0x85, base.0),
            Home::Parameter(_) => {
                return Err(CheckError::NotSimulated {
                    what: "this pointer to an FC parameter".into(),
                    why: "awl loads `P##parameter` of a whole parameter with `L`; a member's, \
                          or one loaded by `LAR1`/`LAR2`, is not simulated yet"
                        .into(),
                    at,
                });
            }
        };
        Ok(area << 24 | (base + offset))
    }

    /// The area pointer `P#…` gives to `L`, `LAR1` and `LAR2`: to a member of a data block
    /// (`P#DB1.text`, area DB; the DB number is not part of it) or to a variable of the block.
    fn pointer_constant(
        &mut self,
        inner: &S7Operand,
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<u32, CheckError> {
        match self.db_member_area_pointer(inner, at) {
            Some(pointer) => pointer,
            None => self.pointer_to(inner, at, scope),
        }
    }

    fn load(
        &mut self,
        out: &mut Emitter,
        operand: &S7Operand,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        match operand {
            S7Operand::Constant(constant) if constant.bytes.len() <= 4 => {
                self.emit(out, Op::LoadConstant(constant_value(constant)), span);
                Ok(())
            }
            S7Operand::Address(address)
                if address.width != AccessWidth::Bit && self.image_byte(address).is_some() =>
            {
                let byte = self.image_byte(address).expect("checked");
                self.emit(out, Op::load_image(width_of(address.width), byte), span);
                Ok(())
            }
            S7Operand::DbRegister(register) => {
                self.emit(out, Op::S7(S7Code::LoadDbRegister(*register)), span);
                Ok(())
            }
            S7Operand::PointerTo(inner) => {
                if let S7Operand::Local(path) = &**inner
                    && path.len() == 1
                    && let (variable, _, _) = self.resolve_local(path, at, scope)?
                    && let Home::Parameter(param) = variable.home
                {
                    // Where the actual is, known when the FC runs: the pointer its caller
                    // passed.
                    self.emit(out, Op::S7(S7Code::LoadParamPointer { param }), span);
                    return Ok(());
                }
                let pointer = self.pointer_constant(inner, at, scope)?;
                self.emit(out, Op::LoadConstant(pointer), span);
                Ok(())
            }
            other => self.memory(out, S7Op::Load, other, at, span, scope),
        }
    }

    /// `UC FC 1`, `CC FB 2`, `CALL FC 1` without parameters.
    fn plain_call(
        &mut self,
        out: &mut Emitter,
        reference: &S7BlockRef,
        conditional: bool,
        at: Span,
        span: Span,
    ) -> Result<(), CheckError> {
        let reference = &match self.library_target(reference, at) {
            super::library::Target7::Library(fc) => {
                self.without_params(reference, |compiler, call, scope| {
                    compiler.library_call(fc, call, at, scope);
                });
                return Ok(());
            }
            super::library::Target7::Program(block) => block,
        };
        if let S7BlockRef::Number {
            kind: S7BlockKind::Sfc,
            number,
        } = reference
        {
            if super::interrupt_sfcs::is_interrupt_sfc(*number) {
                return Err(super::interrupt_sfcs::missing_all(*number, at));
            }
            if matches!(*number, BLKMOV | FILL) {
                self.without_params(reference, |compiler, call, scope| {
                    compiler.block_sfc(*number, call, at, scope);
                });
                return Ok(());
            }
            super::system_functions::given_all(*number, 0, at)?;
            let call = self.sfc(*number, Vec::new());
            self.emit(out, Op::S7(S7Code::Sfc { call }), span);
            return Ok(());
        }
        let Some(id) = self.block_id(reference) else {
            return Ok(());
        };
        if let Some(block) = self.loaded_or_missing(out, id, conditional, at, span) {
            let call = Op::Call {
                block,
                conditional,
                params: NO_PARAMS,
            };
            self.emit(out, call, span);
        }
        Ok(())
    }

    /// The arena index of block `id`; for a block the program lacks, the error and a call
    /// that stops the CPU when taken, and `None`.
    fn loaded_or_missing(
        &mut self,
        out: &mut Emitter,
        id: BlockId,
        conditional: bool,
        at: Span,
        span: Span,
    ) -> Option<u16> {
        if let Some(&block) = self.index.get(&id) {
            return Some(block);
        }
        self.errors.push(CheckError::UndefinedBlock {
            id: id.to_string(),
            at,
        });
        let missing = Op::CallMissing {
            kind: id.kind,
            number: id.number,
            conditional,
        };
        self.emit(out, missing, span);
        None
    }

    fn sfc(&mut self, number: u16, params: Vec<(String, u16)>) -> u16 {
        self.tables.sfc_calls.push(SfcCall {
            number,
            params,
            anys: Vec::new(),
        });
        (self.tables.sfc_calls.len() - 1) as u16
    }

    /// `CALL SFC 39 (…)` to `CALL SFC 42 (…)`: the parameters checked and laid out in the
    /// order the VM reads them.
    fn interrupt_sfc(
        &mut self,
        out: &mut Emitter,
        number: u16,
        call: &CallSpec,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let mut errors = Vec::new();
        let ordered =
            super::interrupt_sfcs::ordered(number, &call.params, at, &mut errors, |param| {
                self.place(&param.actual, param.actual_span, scope)
            });
        self.errors.extend(errors);
        let Some(ordered) = ordered else {
            return Ok(());
        };
        let params = ordered
            .into_iter()
            .map(|(name, place)| (name, self.tables.place(place)))
            .collect();
        let index = self.sfc(number, params);
        self.emit(out, Op::S7(S7Code::Sfc { call: index }), span);
        Ok(())
    }

    /// `CALL FC n (…)`, `CALL FB n, DB m (…)`, `CALL SFC n (…)`.
    fn call(
        &mut self,
        out: &mut Emitter,
        call: &CallSpec,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        if let Some(name) = &call.multi_instance {
            return self.call_multi_instance(out, call, name, at, span, scope);
        }
        let call = &match self.library_target(&call.block, at) {
            super::library::Target7::Library(fc) => {
                if let Some(call) = self.library_call(fc, call, at, scope) {
                    self.emit(out, Op::S7(S7Code::Library { call }), span);
                }
                return Ok(());
            }
            super::library::Target7::Program(block) => CallSpec {
                block,
                ..call.clone()
            },
        };
        let Some(call) = &self.numbered_call(call) else {
            return Ok(());
        };
        if let S7BlockRef::Number {
            kind: S7BlockKind::Sfb,
            number,
        } = call.block
        {
            return self.call_system_fb(out, call, number, at, span, scope);
        }
        if let S7BlockRef::Number {
            kind: S7BlockKind::Sfc,
            number,
        } = call.block
        {
            if super::interrupt_sfcs::is_interrupt_sfc(number) {
                return self.interrupt_sfc(out, number, call, at, span, scope);
            }
            if matches!(number, BLKMOV | FILL) {
                if let Some(call) = self.block_sfc(number, call, at, scope) {
                    self.emit(out, Op::S7(S7Code::Sfc { call }), span);
                }
                return Ok(());
            }
            let mut params = Vec::new();
            let mut widths = Vec::new();
            for param in &call.params {
                let place = self.place(&param.actual, param.actual_span, scope)?;
                widths.push(place.width);
                params.push((
                    param.name.text.to_ascii_uppercase(),
                    self.tables.place(place),
                ));
            }
            self.system_function_params(number, &call.params, &widths, span, scope)?;
            let index = self.sfc(number, params);
            if !matches!(
                number,
                SET_CLK
                    | READ_CLK
                    | 46
                    | WAIT
                    | TIME_TCK
                    | AWLSIM_SFC_NOP
                    | AWLSIM_SFC_REBOOT
                    | AWLSIM_SFC_SHUTDOWN
                    | AWLSIM_SFC_CLOCK_RESET
            ) {
                // awlsim's own system functions are numbered below 0.
                let number = if number >= AWLSIM_SFC_REBOOT - 2 {
                    i32::from(number as i16)
                } else {
                    i32::from(number)
                };
                return Err(CheckError::NotSimulated {
                    what: format!("SFC {number}"),
                    why: "of the system functions, awl runs SFC 0 (SET_CLK), SFC 1 \
                          (READ_CLK), SFC 20 (BLKMOV), SFC 21 (FILL), SFC 39 to SFC 42, SFC 46 \
                          (STP), SFC 47 (WAIT), SFC 64 (TIME_TCK) and awlsim's SFC -1, SFC -3 \
                          and SFC -4 so far"
                        .into(),
                    at,
                });
            }
            self.emit(out, Op::S7(S7Code::Sfc { call: index }), span);
            return Ok(());
        }
        let Some(id) = self.block_id(&call.block) else {
            return Ok(());
        };
        let Some(block) = self.loaded_or_missing(out, id, false, at, span) else {
            return Ok(());
        };
        let interface = self.interfaces.get(&id).cloned().unwrap_or_default();
        let callee = Callee {
            id,
            block,
            interface: &interface,
        };
        match id.kind {
            BlockKind::Fb => self.call_fb(out, call, callee, at, span, scope),
            _ => self.call_fc(out, call, callee, span, scope),
        }
    }

    /// `CALL SFB n, DB m`: the system FB runs on its instance DB between the copies in and
    /// out, as a multi-instance of it does.
    fn call_system_fb(
        &mut self,
        out: &mut Emitter,
        call: &CallSpec,
        number: u16,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let (label, interface) = super::system::called(number, self.types(), at)?;
        let Some(S7BlockRef::Number { number: db, .. }) = &call.instance else {
            return Err(CheckError::NotSimulated {
                what: format!("a call of {label} without an instance DB"),
                why: format!("write `CALL {label}, DB m`"),
                at,
            });
        };
        let instance_slot = self.db_slot(*db, at);
        let mut fb_call = FbCall::on(*db, instance_slot, None, Some(number));
        self.fb_param_copies(call, &label, &interface, scope, &mut fb_call);
        self.emit_fb_call(out, fb_call, None, span);
        Ok(())
    }

    fn call_fc(
        &mut self,
        out: &mut Emitter,
        call: &CallSpec,
        callee: Callee<'_>,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let Callee {
            id,
            block,
            interface,
        } = callee;
        let mut actuals = vec![None; interface.parameters.len()];
        // A parameter written with a bad actual is not missing too: each has its own error.
        let mut given = vec![false; interface.parameters.len()];
        let mut fc_call = FcCall::default();
        let mut scratch_bits = 0u32;
        for param in &call.params {
            let name = param.name.text.to_ascii_uppercase();
            let Some(position) = interface.parameters.iter().position(|p| *p == name) else {
                self.errors.push(CheckError::UnknownParam {
                    name: param.name.text.clone(),
                    fb: id.to_string(),
                    at: param.name.span,
                    help: Some(format!("{id} has {}", interface.parameters.join(", "))),
                });
                continue;
            };
            given[position] = true;
            let formal = &interface.variables[&name];
            if super::pointers::is_pointer_type(&formal.ty) {
                actuals[position] = self.fc_pointer_param(
                    param,
                    &formal.ty,
                    &id.to_string(),
                    scope,
                    &mut scratch_bits,
                    &mut fc_call,
                );
                continue;
            }
            if super::layout::is_complex(&formal.ty) {
                let block = id.to_string();
                match self.complex_fc_actual(
                    param,
                    &formal.ty,
                    &block,
                    &mut scratch_bits,
                    &mut fc_call,
                    scope,
                ) {
                    Ok(pointer) => actuals[position] = Some(Resolved::S7(pointer)),
                    Err(error) => self.errors.push(error),
                }
                continue;
            }
            let place = match &param.actual {
                S7Operand::Constant(constant) if !copied(&formal.ty) => {
                    actuals[position] = Some(Resolved::Constant(constant_value(constant)));
                    continue;
                }
                actual => match self.place(actual, param.actual_span, scope) {
                    Ok(place) => place,
                    Err(error) => {
                        self.errors.push(error);
                        continue;
                    }
                },
            };
            if let Some(error) = width_mismatch(param, &id.to_string(), &formal.ty, &place) {
                self.errors.push(error);
                continue;
            }
            let copy = matches!(place.target, Target::Constant(_) | Target::Instance { .. })
                && copied(&formal.ty);
            let Some(width) = super::layout::width_of(&formal.ty).filter(|_| copy) else {
                actuals[position] = Some(Resolved::S7(self.tables.place(place)));
                continue;
            };
            // STEP 7 passes a constant or the caller's instance data as a copy on the caller's
            // L stack, after its temporaries: the FC's pointer is to the copy (area V).
            let bits = if width == AccessWidth::Bit {
                1
            } else {
                8 * width.bytes()
            };
            let start = if width == AccessWidth::Bit {
                scratch_bits
            } else {
                scratch_bits.div_ceil(16) * 16
            };
            scratch_bits = start + bits;
            let at_bits = self.scratch_base * 8 + start;
            let local = self.tables.place(Place {
                target: Target::Local {
                    byte: at_bits / 8,
                    bit: (at_bits % 8) as u8,
                },
                width,
            });
            let actual = self.tables.place(place);
            if matches!(formal.kind, VarKind::Input | VarKind::InOut) {
                fc_call.inputs.push((actual, local));
            }
            if matches!(formal.kind, VarKind::Output | VarKind::InOut) {
                fc_call.outputs.push((actual, local));
            }
            actuals[position] = Some(Resolved::S7(local));
        }
        let missing: Vec<&str> = interface
            .parameters
            .iter()
            .zip(&given)
            .filter(|(_, given)| !**given)
            .map(|(name, _)| name.as_str())
            .collect();
        if !missing.is_empty() {
            return Err(CheckError::ParamCount {
                fb: id.to_string(),
                expected: interface.parameters.len(),
                found: interface.parameters.len() - missing.len(),
                at: span,
                help: Some(format!(
                    "an FC needs every parameter; missing: {}",
                    missing.join(", ")
                )),
            });
        }
        let list = actuals
            .into_iter()
            .map(|actual| actual.unwrap_or(Resolved::None))
            .collect();
        self.param_lists.push(list);
        let params = (self.param_lists.len() - 1) as u16;
        self.scratch_bytes = self.scratch_bytes.max(scratch_bits.div_ceil(16) * 2);
        self.tables.fc_calls.push(fc_call);
        let index = (self.tables.fc_calls.len() - 1) as u16;
        self.emit(out, Op::S7(S7Code::FcEnter { call: index }), span);
        self.emit(
            out,
            Op::Call {
                block,
                conditional: false,
                params,
            },
            span,
        );
        self.emit(out, Op::S7(S7Code::FcLeave { call: index }), span);
        Ok(())
    }

    fn call_fb(
        &mut self,
        out: &mut Emitter,
        call: &CallSpec,
        callee: Callee<'_>,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let Callee {
            id,
            block,
            interface,
        } = callee;
        let Some(S7BlockRef::Number { number: db, .. }) = &call.instance else {
            return Err(CheckError::NotSimulated {
                what: format!("a call of {id} without an instance DB"),
                why: "write `CALL FB n, DB m`".into(),
                at,
            });
        };
        let instance_slot = self.db_slot(*db, at);
        let mut fb_call = FbCall::on(*db, instance_slot, None, None);
        self.fb_param_copies(call, &id.to_string(), interface, scope, &mut fb_call);
        self.emit_fb_call(out, fb_call, Some(block), span);
        Ok(())
    }

    /// The copies of a call's actuals into an FB's instance data (inputs, in/outs) and back
    /// (outputs, in/outs), into `fb_call`; `fb` names the block for messages.
    fn fb_param_copies(
        &mut self,
        call: &CallSpec,
        fb: &str,
        interface: &super::layout::Interface,
        scope: &Scope<'_>,
        fb_call: &mut FbCall,
    ) {
        for param in &call.params {
            let name = param.name.text.to_ascii_uppercase();
            let variable = interface.variables.get(&name).filter(|variable| {
                matches!(
                    variable.kind,
                    VarKind::Input | VarKind::Output | VarKind::InOut
                )
            });
            let Some(variable) = variable else {
                self.errors.push(CheckError::UnknownParam {
                    name: param.name.text.clone(),
                    fb: fb.to_string(),
                    at: param.name.span,
                    help: None,
                });
                continue;
            };
            if let (Home::Instance(offset), true) = (
                variable.home,
                super::pointers::is_pointer_type(&variable.ty),
            ) {
                let copies = self.fb_pointer_param(param, &variable.ty, offset, fb, scope);
                fb_call.inputs.extend(copies.unwrap_or_default());
                continue;
            }
            if super::layout::is_complex(&variable.ty) {
                if let Err(error) = self.complex_fb_param(param, variable, fb, scope, fb_call) {
                    self.errors.push(error);
                }
                continue;
            }
            let (Home::Instance(offset), Some(width)) =
                (variable.home, super::layout::width_of(&variable.ty))
            else {
                self.errors.push(CheckError::NotSimulated {
                    what: format!(
                        "the parameter `{}` of type {}",
                        param.name.text,
                        super::complex::type_name(&variable.ty)
                    ),
                    why: "FB parameters of elementary and complex types are simulated so far"
                        .into(),
                    at: param.span,
                });
                continue;
            };
            let place = match self.place(&param.actual, param.actual_span, scope) {
                Ok(place) => place,
                Err(error) => {
                    self.errors.push(error);
                    continue;
                }
            };
            if let Some(error) = width_mismatch(param, fb, &variable.ty, &place) {
                self.errors.push(error);
                continue;
            }
            let copy = ParamCopy {
                actual: self.tables.place(place),
                byte: offset.byte(),
                bit: offset.bit(),
                width,
            };
            if matches!(variable.kind, VarKind::Input | VarKind::InOut) {
                fb_call.inputs.push(copy);
            }
            if matches!(variable.kind, VarKind::Output | VarKind::InOut) {
                fb_call.outputs.push(copy);
            }
        }
    }

    /// `CALL #motor (…)`: the FB or SFB of the calling FB's multi-instance `motor`, with the
    /// caller's instance DB and AR2 moved on to the instance's data.
    fn call_multi_instance(
        &mut self,
        out: &mut Emitter,
        call: &CallSpec,
        name: &crate::ast::Name,
        at: Span,
        span: Span,
        scope: &Scope<'_>,
    ) -> Result<(), CheckError> {
        let path = [crate::step7::ast::PathPart::Member(name.clone())];
        let (variable, ty, _) = self
            .resolve_local(&path, name.span, scope)
            .map_err(|error| {
                match error {
                    // The names that are multi-instances are the ones to suggest.
                    CheckError::UndeclaredLocal {
                        name, block, at, ..
                    } => {
                        let mut instances: Vec<&str> = scope
                            .interface
                            .variables
                            .values()
                            .filter(|v| matches!(v.ty, DataType::Instance(..)))
                            .map(|v| v.declaration.name.text.as_str())
                            .collect();
                        instances.sort_unstable();
                        let close = one_edit_from(&name, instances.iter().copied())
                            .map(|known| format!("did you mean `#{known}`?"))
                            .or_else(|| {
                                (!instances.is_empty()).then(|| {
                                    format!(
                                        "the multi-instances of {block}: #{}",
                                        instances.join(", #")
                                    )
                                })
                            })
                            .or_else(|| {
                                Some(format!(
                                    "declare it in the static section of {block}: `{name} : FB n;`"
                                ))
                            });
                        CheckError::UndeclaredLocal {
                            name,
                            block,
                            at,
                            help: close,
                        }
                    }
                    other => other,
                }
            })?;
        let (Home::Instance(offset), DataType::Instance(kind, number)) = (variable.home, &ty)
        else {
            return Err(CheckError::OperandNotAllowed {
                op: "CALL".into(),
                at,
                help: Some(format!(
                    "`CALL #{}` calls a multi-instance, a variable declared `{} : FB n;` in the \
                     static section (VAR) of an FB",
                    name.text, name.text
                )),
            });
        };
        let (kind, number) = (*kind, *number);
        if kind == S7BlockKind::Sfb {
            let (label, interface) = super::system::called(number, self.types(), at)?;
            let mut fb_call = FbCall::on(0, 0, Some(offset.0), Some(number));
            self.fb_param_copies(call, &label, &interface, scope, &mut fb_call);
            self.emit_fb_call(out, fb_call, None, span);
            return Ok(());
        }
        let label = format!("{} {number}", kind.name());
        let id = BlockId {
            kind: BlockKind::Fb,
            number,
        };
        let interface = self.interfaces.get(&id).cloned().unwrap_or_default();
        let mut fb_call = FbCall::on(0, 0, Some(offset.0), None);
        self.fb_param_copies(call, &label, &interface, scope, &mut fb_call);
        let Some(block) = self.loaded_or_missing(out, id, false, at, span) else {
            return Ok(());
        };
        self.emit_fb_call(out, fb_call, Some(block), span);
        Ok(())
    }

    /// An FB call as its ops: copy in and open the instance, run FB `block` (none for a system
    /// FB, which the copy-in op runs itself), copy out.
    fn emit_fb_call(&mut self, out: &mut Emitter, call: FbCall, block: Option<u16>, span: Span) {
        self.tables.fb_calls.push(call);
        let index = (self.tables.fb_calls.len() - 1) as u16;
        self.emit(out, Op::S7(S7Code::FbEnter { call: index }), span);
        if let Some(block) = block {
            let call = Op::Call {
                block,
                conditional: false,
                params: NO_PARAMS,
            };
            self.emit(out, call, span);
        }
        self.emit(out, Op::S7(S7Code::FbLeave { call: index }), span);
    }
}

/// Where the absolute `L` addresses of an operand end, in bytes rounded to a word (0: none).
fn absolute_local_end(operand: &S7Operand) -> u32 {
    match operand {
        S7Operand::Address(address) if address.area == S7Area::Local => {
            (address.byte + address.width.bytes()).div_ceil(2) * 2
        }
        S7Operand::Pair(first, second) => absolute_local_end(first).max(absolute_local_end(second)),
        _ => 0,
    }
}

/// Whether STEP 7 passes an actual of an FC parameter of type `ty` as a copy when it is a
/// constant or the caller's instance data: the elementary types (a TIMER, COUNTER or block
/// parameter passes the number itself).
fn copied(ty: &DataType) -> bool {
    super::layout::width_of(ty).is_some()
        && !matches!(
            ty,
            DataType::Timer
                | DataType::Counter
                | DataType::BlockDb
                | DataType::BlockFb
                | DataType::BlockFc
        )
}

/// A `__FEATURE` operand's number.
pub(super) fn feature_number(operand: &S7Operand) -> Option<u8> {
    match operand {
        S7Operand::Number(n) => Some(*n as u8),
        S7Operand::Constant(constant) => Some(constant.value as u8),
        _ => None,
    }
}

/// An actual of another width than its elementary parameter (`MW 4` for a BOOL): STEP 7 takes
/// an address for a parameter of its width only. Constants are checked by their type.
fn width_mismatch(
    param: &CallParam,
    block: &str,
    ty: &DataType,
    place: &Place,
) -> Option<CheckError> {
    let expected = super::layout::width_of(ty)?;
    if place.width == expected || matches!(place.target, Target::Constant(_)) {
        return None;
    }
    let example = match expected {
        AccessWidth::Bit => "`M 0.0`",
        AccessWidth::Byte => "`MB 0`",
        AccessWidth::Word => "`MW 0`",
        AccessWidth::Double => "`MD 0`",
    };
    Some(CheckError::ParamMismatch {
        name: param.name.text.clone(),
        fb: block.to_string(),
        at: param.actual_span,
        expected: format!(
            "{}: an operand like {example}",
            super::complex::type_name(ty)
        ),
    })
}
