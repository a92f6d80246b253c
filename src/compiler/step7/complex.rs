//! Parameters of the complex data types — ARRAY, STRUCT, UDT, STRING and DATE_AND_TIME — as
//! STEP 7 passes them ("Programming with STEP 7", parameter passing): an FB's inputs and
//! outputs are copied whole into and out of its instance DB; an FC receives a 6-byte DB pointer
//! (DB number, then an area pointer) on its caller's L stack, to the actual or to a copy of a
//! constant.

use crate::compiler::CheckError;
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, CallParam, ConstKind, DataType, S7Constant, S7Operand, VarKind,
};
use crate::step7::bytecode::{BlockCopy, CopySource, FbCall, FcCall, Place, Target};

use super::layout::{self, Home, Variable, is_complex};
use super::operand::Scope;

/// A type as STEP 7 writes it, for messages.
pub fn type_name(ty: &DataType) -> String {
    match ty {
        DataType::Array { dims, element } => {
            let dims: Vec<String> = dims
                .iter()
                .map(|(low, high)| format!("{low}..{high}"))
                .collect();
            format!("ARRAY [{}] OF {}", dims.join(", "), type_name(element))
        }
        DataType::Struct(_) => "STRUCT".into(),
        DataType::Udt(number) => format!("UDT {number}"),
        DataType::String(max) => format!("STRING [{max}]"),
        DataType::DateAndTime => "DATE_AND_TIME".into(),
        DataType::Instance(kind, number) => format!("{} {number}", kind.name()),
        DataType::Named(name) => format!("\"{}\"", name.text),
        DataType::Bool => "BOOL".into(),
        DataType::Byte => "BYTE".into(),
        DataType::Word => "WORD".into(),
        DataType::Dword => "DWORD".into(),
        DataType::Int => "INT".into(),
        DataType::Dint => "DINT".into(),
        DataType::Real => "REAL".into(),
        DataType::S5Time => "S5TIME".into(),
        DataType::Time => "TIME".into(),
        DataType::Date => "DATE".into(),
        DataType::TimeOfDay => "TIME_OF_DAY".into(),
        DataType::Char => "CHAR".into(),
        DataType::Timer => "TIMER".into(),
        DataType::Counter => "COUNTER".into(),
        DataType::Pointer => "POINTER".into(),
        DataType::Any => "ANY".into(),
        DataType::BlockDb => "BLOCK_DB".into(),
        DataType::BlockFb => "BLOCK_FB".into(),
        DataType::BlockFc => "BLOCK_FC".into(),
    }
}

/// The bytes a value of type `ty` takes.
fn size_bytes(ty: &DataType, types: &layout::Types) -> u32 {
    layout::size_bits(ty, types).div_ceil(8)
}

/// A constant as the bytes of a parameter of type `ty`: a STRING's maximum and actual length
/// then its characters, a DATE_AND_TIME's eight BCD bytes; `None` when it is not of the type.
pub(super) fn constant_bytes(ty: &DataType, constant: &S7Constant) -> Option<Vec<u8>> {
    match (ty, constant.kind) {
        (DataType::String(max), ConstKind::String | ConstKind::Char) => {
            let text = &constant.bytes;
            let length = text.len().min(usize::from(*max));
            let mut bytes = vec![0u8; usize::from(*max) + 2];
            bytes[0] = *max;
            bytes[1] = length as u8;
            bytes[2..2 + length].copy_from_slice(&text[..length]);
            Some(bytes)
        }
        (DataType::DateAndTime, ConstKind::DateAndTime) => Some(constant.bytes.clone()),
        _ => None,
    }
}

impl super::Compiler<'_> {
    /// The type of an actual that names a variable (`#local.member`, `DB5.values`), if it does.
    pub(super) fn actual_type(
        &self,
        actual: &S7Operand,
        at: Span,
        scope: &Scope<'_>,
    ) -> Option<DataType> {
        match actual {
            S7Operand::Local(path) => self
                .resolve_local(path, at, scope)
                .ok()
                .map(|(_, ty, _)| ty),
            S7Operand::DbMember { db, path } => {
                let layout = self.db_layouts.get(db)?;
                let scope = Scope {
                    interface: layout,
                    block: format!("DB {db}"),
                };
                self.resolve_local(path, at, &scope)
                    .ok()
                    .map(|(_, ty, _)| ty)
            }
            _ => None,
        }
    }

    /// Where the bytes of the actual of the complex parameter `formal` come from and how many
    /// to copy, or why the actual does not fit: a variable of the same size (a STRING of any
    /// length for a STRING: the shorter length counts), or a constant of the type.
    fn complex_source(
        &mut self,
        param: &CallParam,
        formal: &DataType,
        block: &str,
        scope: &Scope<'_>,
    ) -> Result<(CopySource, u32), CheckError> {
        let size = size_bytes(formal, self.types());
        let mismatch = || CheckError::ParamMismatch {
            name: param.name.text.clone(),
            fb: block.to_string(),
            at: param.actual_span,
            expected: format!("a variable of type {}", type_name(formal)),
        };
        if let S7Operand::Constant(constant) = &param.actual {
            let bytes = constant_bytes(formal, constant).ok_or_else(mismatch)?;
            return Ok((CopySource::Bytes(bytes), size));
        }
        let actual = self
            .actual_type(&param.actual, param.actual_span, scope)
            .ok_or_else(mismatch)?;
        let size = match (formal, &actual) {
            (DataType::String(_), DataType::String(_)) => {
                size.min(size_bytes(&actual, self.types()))
            }
            _ if is_complex(&actual) && size_bytes(&actual, self.types()) == size => size,
            _ => return Err(mismatch()),
        };
        let place = self.place(&param.actual, param.actual_span, scope)?;
        Ok((CopySource::Place(self.tables.place(place)), size))
    }

    /// An FB parameter of a complex type, into `fb_call`: an input or output copied into or
    /// out of the instance data, an in/out passed as a DB pointer there.
    pub(super) fn complex_fb_param(
        &mut self,
        param: &CallParam,
        variable: &Variable,
        block: &str,
        scope: &Scope<'_>,
        fb_call: &mut FbCall,
    ) -> Result<(), CheckError> {
        let Home::Instance(offset) = variable.home else {
            return Err(CheckError::UnknownParam {
                name: param.name.text.clone(),
                fb: block.to_string(),
                at: param.name.span,
                help: None,
            });
        };
        let (source, size) = self.complex_source(param, &variable.ty, block, scope)?;
        let (CopySource::Place(place), VarKind::InOut) = (&source, variable.kind) else {
            if variable.kind != VarKind::Input && matches!(source, CopySource::Bytes(_)) {
                return Err(CheckError::ParamMismatch {
                    name: param.name.text.clone(),
                    fb: block.to_string(),
                    at: param.actual_span,
                    expected: format!("a variable of type {} to write", type_name(&variable.ty)),
                });
            }
            let copy = BlockCopy {
                source,
                byte: offset.byte(),
                size,
            };
            match variable.kind {
                VarKind::Input => fb_call.blocks_in.push(copy),
                _ => fb_call.blocks_out.push(copy),
            }
            return Ok(());
        };
        fb_call.pointers.push((*place, offset.byte()));
        Ok(())
    }

    /// An FC parameter of a complex type: the DB pointer to its actual, on the caller's L stack
    /// after its temporaries from bit `scratch_bits` on (a constant is copied there first).
    /// Gives the place of the pointer, the parameter's actual.
    pub(super) fn complex_fc_actual(
        &mut self,
        param: &CallParam,
        formal: &DataType,
        block: &str,
        scratch_bits: &mut u32,
        fc_call: &mut FcCall,
        scope: &Scope<'_>,
    ) -> Result<u16, CheckError> {
        let (source, _) = self.complex_source(param, formal, block, scope)?;
        let source = match source {
            CopySource::Place(place) => place,
            CopySource::Bytes(bytes) => {
                let place = self.scratch(scratch_bits, bytes.len() as u32);
                fc_call.constants.push((place, bytes));
                place
            }
        };
        let pointer = self.scratch(scratch_bits, 6);
        fc_call.pointers.push((source, pointer));
        Ok(pointer)
    }

    /// `bytes` bytes of the caller's L stack after its temporaries, from an even byte.
    pub(super) fn scratch(&mut self, scratch_bits: &mut u32, bytes: u32) -> u16 {
        let start = scratch_bits.div_ceil(16) * 16;
        *scratch_bits = start + bytes * 8;
        self.tables.place(Place {
            target: Target::Local {
                byte: self.scratch_base + start / 8,
                bit: 0,
            },
            width: AccessWidth::Byte,
        })
    }
}

/// The number of a UDT that `ty` names, or a member or element of it names, and that the
/// program does not define.
fn missing_udt(ty: &DataType, types: &layout::Types) -> Option<u16> {
    match ty {
        DataType::Udt(number) => (!types.udts.contains_key(number)).then_some(*number),
        DataType::Array { element, .. } => missing_udt(element, types),
        DataType::Struct(members) => members.iter().find_map(|m| missing_udt(&m.ty, types)),
        _ => None,
    }
}

impl super::Compiler<'_> {
    /// Reports each declaration that names a UDT the program does not define: it would take no
    /// room, and its members none.
    pub(super) fn check_udts(&mut self, units: &[crate::step7::ast::S7Unit]) {
        use crate::step7::ast::S7Body;
        for block in units.iter().flat_map(|unit| &unit.blocks) {
            let members: &[crate::step7::ast::VarDecl] = match &block.body {
                S7Body::Type(members) | S7Body::Data { members, .. } => members,
                S7Body::Logic(_) => &[],
            };
            let declarations = block
                .interface
                .iter()
                .flat_map(|section| &section.vars)
                .chain(members)
                .map(|declaration| (&declaration.ty, declaration.span))
                .chain(block.return_type.iter().map(|ty| (ty, block.header)));
            let missing: Vec<(u16, Span)> = declarations
                .filter_map(|(ty, at)| Some((missing_udt(ty, &self.types)?, at)))
                .collect();
            for (number, at) in missing {
                self.errors.push(CheckError::UndefinedType {
                    id: format!("UDT {number}"),
                    at,
                });
            }
        }
    }
}
