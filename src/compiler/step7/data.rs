//! The initial bytes of STEP 7 data blocks: the declared initial values (`:= 5` in the
//! interface or `STRUCT`), then the assignments after `BEGIN`.

use crate::compiler::CheckError;
use crate::step7::ast::{DataType, InitialValue, PathPart, S7Constant, VarDecl};

use super::layout::{self, BitOffset, Interface, Types, struct_layout};

/// Writes `value` as a value of `ty` at bit `at` of `bytes`, growing them as needed.
pub fn put(bytes: &mut Vec<u8>, at: u32, ty: &DataType, value: &S7Constant) {
    let start = (at / 8) as usize;
    let size = (layout::size_bits(ty, &Types::default()).max(1)).div_ceil(8) as usize;
    if bytes.len() < start + size {
        bytes.resize(start + size, 0);
    }
    match layout::width_of(ty) {
        Some(crate::step7::ast::AccessWidth::Bit) => {
            let mask = 1u8 << (at % 8);
            if value.value & 1 != 0 {
                bytes[start] |= mask;
            } else {
                bytes[start] &= !mask;
            }
        }
        Some(width) => {
            let count = match width {
                crate::step7::ast::AccessWidth::Byte => 1,
                crate::step7::ast::AccessWidth::Word => 2,
                _ => 4,
            };
            let all = value.value.to_be_bytes();
            bytes[start..start + count].copy_from_slice(&all[4 - count..]);
        }
        None => match ty {
            DataType::String(max) => {
                let text = &value.bytes;
                let length = text.len().min(usize::from(*max));
                bytes[start] = *max;
                bytes[start + 1] = length as u8;
                // A shorter value replaces a declared one entirely: the rest reads as zeros.
                bytes[start + 2..start + size].fill(0);
                bytes[start + 2..start + 2 + length].copy_from_slice(&text[..length]);
            }
            _ => {
                let length = value.bytes.len().min(size);
                bytes[start..start + length].copy_from_slice(&value.bytes[..length]);
            }
        },
    }
}

/// The declared initial values of `members` laid out from bit `base`.
fn put_declared(
    bytes: &mut Vec<u8>,
    base: u32,
    members: &[VarDecl],
    offsets: &[BitOffset],
    types: &Types,
) {
    for (member, offset) in members.iter().zip(offsets) {
        put_initial(bytes, base + offset.0, &member.ty, &member.initial, types);
    }
}

/// A value of type `ty` at bit `at` as declared: `initial` (one value per array element), the
/// declared values of a structure's or UDT's members, and every STRING's maximum length.
fn put_initial(bytes: &mut Vec<u8>, at: u32, ty: &DataType, initial: &[S7Constant], types: &Types) {
    match ty {
        DataType::Struct(inner) => {
            let (inner_offsets, _) = struct_layout(inner, types);
            put_declared(bytes, at, inner, &inner_offsets, types);
        }
        DataType::Udt(number) => {
            if let Some(inner) = types.udts.get(number) {
                let (inner_offsets, _) = struct_layout(inner, types);
                put_declared(bytes, at, inner, &inner_offsets, types);
            }
        }
        DataType::Array { dims, element } => {
            let count: u32 = dims
                .iter()
                .map(|(low, high)| (high - low + 1).max(0) as u32)
                .product();
            let stride = layout::element_stride(element, types);
            for index in 0..count {
                let value = initial.get(index as usize..=index as usize).unwrap_or(&[]);
                put_initial(bytes, at + index * stride, element, value, types);
            }
        }
        DataType::String(max) => {
            // A STRING's first byte is its maximum length, whether it has a value or not.
            let empty = S7Constant {
                kind: crate::step7::ast::ConstKind::String,
                value: 0,
                bytes: Vec::new(),
            };
            let value = initial.first().unwrap_or(&empty);
            put(bytes, at, &DataType::String(*max), value);
        }
        ty => {
            if let Some(value) = initial.first() {
                put(bytes, at, ty, value);
            }
        }
    }
}

/// A global DB: its `STRUCT`, then the assignments after `BEGIN`.
pub fn global_image(
    members: &[VarDecl],
    initial: &[InitialValue],
    types: &Types,
    errors: &mut Vec<CheckError>,
) -> Vec<u8> {
    let (offsets, size) = struct_layout(members, types);
    let mut bytes = vec![0u8; (size / 8) as usize];
    put_declared(&mut bytes, 0, members, &offsets, types);
    let as_struct = DataType::Struct(members.to_vec());
    assign(&mut bytes, &as_struct, initial, types, errors);
    bytes
}

/// An instance DB of an FB with the interface `interface` (its declared initial values), then
/// the assignments after `BEGIN`.
pub fn instance_image(
    interface: &Interface,
    initial: &[InitialValue],
    types: &Types,
    errors: &mut Vec<CheckError>,
) -> Vec<u8> {
    let mut bytes = vec![0u8; interface.instance_bytes as usize];
    let mut members = Vec::new();
    for variable in interface.variables.values() {
        // An in/out of a complex type holds the DB pointer its call writes, no value.
        let pointer = variable.kind == crate::step7::ast::VarKind::InOut
            && super::layout::is_complex(&variable.ty);
        if let (layout::Home::Instance(at), false) = (variable.home, pointer) {
            put_declared(
                &mut bytes,
                at.0,
                std::slice::from_ref(&variable.declaration),
                &[BitOffset(0)],
                types,
            );
            members.push((at, variable));
        }
    }
    for value in initial {
        let Some(PathPart::Member(first)) = value.path.first() else {
            continue;
        };
        let Some(variable) = interface.variables.get(&first.text.to_ascii_uppercase()) else {
            errors.push(unknown_member(&first.text, value));
            continue;
        };
        let layout::Home::Instance(at) = variable.home else {
            continue;
        };
        if variable.kind == crate::step7::ast::VarKind::InOut
            && super::layout::is_complex(&variable.ty)
        {
            let problem = "an in/out of a complex type holds the pointer its call passes";
            errors.push(bad_member(problem.into(), value));
            continue;
        }
        match layout::member(&variable.ty, &value.path[1..], types) {
            Ok((offset, ty)) => put(&mut bytes, at.0 + offset, &ty, &value.value),
            Err(problem) => errors.push(bad_member(problem, value)),
        }
    }
    bytes
}

fn assign(
    bytes: &mut Vec<u8>,
    whole: &DataType,
    initial: &[InitialValue],
    types: &Types,
    errors: &mut Vec<CheckError>,
) {
    for value in initial {
        match layout::member(whole, &value.path, types) {
            Ok((offset, ty)) => put(bytes, offset, &ty, &value.value),
            Err(problem) => errors.push(bad_member(problem, value)),
        }
    }
}

fn unknown_member(name: &str, value: &InitialValue) -> CheckError {
    CheckError::UndeclaredLocal {
        name: name.to_string(),
        block: "the data block".into(),
        at: value.span,
        help: None,
    }
}

fn bad_member(problem: String, value: &InitialValue) -> CheckError {
    CheckError::OperandNotAllowed {
        op: ":=".into(),
        at: value.span,
        help: Some(problem),
    }
}
