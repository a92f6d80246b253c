//! FB calls: the actual parameters after `JU FB n` checked against the FB's declarations, and
//! operations on formal operands checked against the parameter's kind and format.

use crate::ast::BlockId;
use crate::ast::{Address, Operand, ParamDecl, ParamFormat, Statement};
use crate::mnemonics::{self, Area, BlockKind, MnemonicSet, OpCode, ParamKind};

use super::bytecode::{self, Op};
use super::error::CheckError;
use super::lower::{self, Resolved};
use super::{BlockContext, Compiler};
use crate::address::Layout;
use crate::suggest::one_edit_from;

/// `I BI`, `D KF`, `T` — a declaration's kind and format as written in the file's set.
pub fn describe_decl(decl: &ParamDecl, set: MnemonicSet) -> String {
    let kind = mnemonics::PARAM_KINDS
        .iter()
        .find(|info| info.kind == decl.kind)
        .expect("every kind has a row");
    let kind = match set {
        MnemonicSet::English => kind.en,
        MnemonicSet::German => kind.de,
    };
    match decl.format {
        None => kind.to_string(),
        Some(ParamFormat::Bit) => format!("{kind} BI"),
        Some(ParamFormat::Byte) => format!("{kind} BY"),
        Some(ParamFormat::Word) => format!("{kind} W"),
        Some(ParamFormat::Constant(format)) => {
            let info = mnemonics::CONSTANTS
                .iter()
                .find(|info| info.format == format)
                .expect("every format has a row");
            format!(
                "{kind} {}",
                if set == MnemonicSet::English {
                    info.en
                } else {
                    info.de
                }
            )
        }
    }
}

/// An operand standing for any actual of the declaration, for checks and execution times.
fn representative(decl: &ParamDecl) -> Resolved {
    let address = |area| {
        Resolved::Address(Address {
            area,
            index: 0,
            bit: 0,
        })
    };
    let input = decl.kind == ParamKind::Input;
    match (decl.kind, decl.format) {
        (ParamKind::Input | ParamKind::Output, Some(ParamFormat::Byte)) => address(if input {
            Area::InputByte
        } else {
            Area::OutputByte
        }),
        (ParamKind::Input | ParamKind::Output, Some(ParamFormat::Word)) => address(if input {
            Area::InputWord
        } else {
            Area::OutputWord
        }),
        (ParamKind::Input | ParamKind::Output, _) => {
            address(if input { Area::Input } else { Area::Output })
        }
        (ParamKind::Data, _) => Resolved::Constant(0),
        (ParamKind::Timer, _) => address(Area::Timer),
        (ParamKind::Counter, _) => address(Area::Counter),
        (ParamKind::Block, _) => Resolved::Block {
            kind: BlockKind::Pb,
            number: 0,
            index: Some(0),
        },
    }
}

/// The op that an operation on this formal parameter amounts to, or `None` when the operation
/// does not fit the parameter (`SP =EIN` on an input bit).
pub fn formal_op(op: OpCode, decl: &ParamDecl, layout: Layout) -> Option<Op> {
    if decl.kind == ParamKind::Block {
        return match op {
            OpCode::JumpUnconditional | OpCode::JumpConditional | OpCode::Indirect => {
                Some(Op::Call {
                    block: 0,
                    conditional: false,
                    params: bytecode::NO_PARAMS,
                })
            }
            OpCode::OpenDb => Some(Op::OpenDb(0)),
            _ => None,
        };
    }
    let actual = representative(decl);
    let op = super::specialise::formal_meaning(op, actual)?;
    lower::lower(op, actual, layout, bytecode::NO_PARAMS)
}

fn accepts(decl: &ParamDecl, actual: &Operand) -> bool {
    match (decl.kind, decl.format, actual) {
        (
            ParamKind::Input | ParamKind::Output,
            Some(ParamFormat::Bit),
            Operand::Address(address),
        ) => address.area.is_bit(),
        (
            ParamKind::Input | ParamKind::Output,
            Some(ParamFormat::Byte),
            Operand::Address(address),
        ) => matches!(
            address.area,
            Area::InputByte
                | Area::OutputByte
                | Area::FlagByte
                | Area::DataLeft
                | Area::DataRight
                | Area::PeripheralByte
        ),
        (
            ParamKind::Input | ParamKind::Output,
            Some(ParamFormat::Word),
            Operand::Address(address),
        ) => matches!(
            address.area,
            Area::InputWord
                | Area::OutputWord
                | Area::FlagWord
                | Area::DataWord
                | Area::PeripheralWord
        ),
        (ParamKind::Data, Some(ParamFormat::Constant(format)), Operand::Constant(constant)) => {
            constant.format == format
        }
        (ParamKind::Timer, _, Operand::Address(address)) => address.area == Area::Timer,
        (ParamKind::Counter, _, Operand::Address(address)) => address.area == Area::Counter,
        (ParamKind::Block, _, Operand::Block(_)) => true,
        _ => false,
    }
}

impl Compiler<'_> {
    /// Checks and resolves the actual parameters of a call of `fb`; returns the list's index.
    pub(super) fn call_params(
        &mut self,
        context: &BlockContext<'_>,
        statement: &Statement,
        fb: BlockId,
    ) -> Option<u16> {
        let decls = self.fb_params.get(&fb).cloned().unwrap_or_default();
        let given = &statement.call_params;
        let mut ok = true;
        for param in given {
            if !decls
                .iter()
                .any(|decl| decl.name.text.eq_ignore_ascii_case(&param.name.text))
            {
                let declared = decls.iter().map(|decl| decl.name.text.as_str());
                let help = one_edit_from(&param.name.text, declared)
                    .map(|close| format!("did you mean `{close}`?"))
                    .or_else(|| Some(format!("{fb} declares: {}", names(&decls))));
                self.diagnostics.push(CheckError::UnknownParam {
                    name: param.name.text.clone(),
                    fb: fb.to_string(),
                    at: param.name.span,
                    help,
                });
                ok = false;
            }
        }
        let missing: Vec<&str> = decls
            .iter()
            .filter(|decl| {
                !given
                    .iter()
                    .any(|param| param.name.text.eq_ignore_ascii_case(&decl.name.text))
            })
            .map(|decl| decl.name.text.as_str())
            .collect();
        if ok && (given.len() != decls.len() || !missing.is_empty()) {
            let help = if missing.is_empty() {
                Some(format!("{fb} declares: {}", names(&decls)))
            } else {
                Some(format!(
                    "missing: {}; write one line `NAME :operand` per parameter after the call",
                    missing.join(", ")
                ))
            };
            self.diagnostics.push(CheckError::ParamCount {
                fb: fb.to_string(),
                expected: decls.len(),
                found: given.len(),
                at: statement.span,
                help,
            });
            ok = false;
        }
        let mut list = Vec::with_capacity(decls.len());
        for decl in &decls {
            let Some(param) = given
                .iter()
                .find(|param| param.name.text.eq_ignore_ascii_case(&decl.name.text))
            else {
                continue;
            };
            let expected = describe_decl(decl, context.set);
            let mismatch = |compiler: &mut Self| {
                compiler.diagnostics.push(CheckError::ParamMismatch {
                    name: decl.name.text.clone(),
                    fb: fb.to_string(),
                    at: param.actual_span,
                    expected: expected.clone(),
                });
            };
            let resolved = match &param.actual {
                Operand::Symbol(name) => {
                    match context
                        .params
                        .iter()
                        .position(|own| own.name.text.eq_ignore_ascii_case(name))
                    {
                        Some(index)
                            if context.params[index].kind == decl.kind
                                && context.params[index].format == decl.format =>
                        {
                            Resolved::Formal(index as u8)
                        }
                        _ => {
                            mismatch(self);
                            ok = false;
                            continue;
                        }
                    }
                }
                actual if accepts(decl, actual) => match actual {
                    Operand::Block(id) => Resolved::Block {
                        kind: id.kind,
                        number: id.number,
                        index: self.index.get(id).copied(),
                    },
                    _ => match self.resolve_value(context.set, actual, param.actual_span) {
                        Some(resolved) => resolved,
                        None => {
                            ok = false;
                            continue;
                        }
                    },
                },
                _ => {
                    mismatch(self);
                    ok = false;
                    continue;
                }
            };
            list.push(resolved);
        }
        if !ok {
            return None;
        }
        self.param_lists.push(list);
        Some((self.param_lists.len() - 1) as u16)
    }
}

fn names(decls: &[ParamDecl]) -> String {
    if decls.is_empty() {
        return "no parameters".to_string();
    }
    decls
        .iter()
        .map(|decl| decl.name.text.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}
