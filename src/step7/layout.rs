//! Where the variables of a block's interface lie: STEP 7's memory layout of its data types.
//! BOOLs are packed bit by bit; a BYTE or CHAR starts on a byte; everything wider, every
//! structure, array and section starts on an even byte, and structures and arrays take an even
//! number of bytes ("Programming with STEP 7", data types: memory layout).

use std::collections::HashMap;

use crate::step7::ast::{AccessWidth, DataType, PathPart, S7BlockKind, VarDecl, VarKind};

/// The length of an OB's start information, the first bytes of its local data (see
/// [`crate::vm::start_info`]).
pub const START_INFO_BYTES: u32 = 20;

/// The types a layout looks up by number: the UDTs, and the FBs and SFBs a multi-instance
/// (`motor : FB 2;`) embeds.
#[derive(Debug, Clone, Default)]
pub struct Types {
    pub udts: HashMap<u16, Vec<VarDecl>>,
    /// The instance data of each FB and SFB, section by section (inputs, outputs, in/outs,
    /// statics): each section starts on an even byte, as in its own instance DB.
    pub instances: HashMap<(S7BlockKind, u16), Vec<Vec<VarDecl>>>,
}

/// Instance data laid out: each section's start in bits with its variables.
pub type Sections<'t> = Vec<(u32, &'t [VarDecl])>;

impl Types {
    /// The instance data of `kind number` as `(offset of the section, its variables)`, and
    /// the size in bits; `None` for a block the program does not have.
    pub fn instance(&self, kind: S7BlockKind, number: u16) -> Option<(Sections<'_>, u32)> {
        let sections = self.instances.get(&(kind, number))?;
        let mut at = 0;
        let mut laid = Vec::with_capacity(sections.len());
        for section in sections {
            laid.push((at, section.as_slice()));
            at += struct_layout(section, self).1;
        }
        Some((laid, at))
    }
}

/// A position in bits from the start of an area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BitOffset(pub u32);

impl BitOffset {
    pub fn byte(self) -> u32 {
        self.0 / 8
    }
    pub fn bit(self) -> u8 {
        (self.0 % 8) as u8
    }
    fn align_byte(self) -> BitOffset {
        BitOffset(self.0.div_ceil(8) * 8)
    }
    fn align_word(self) -> BitOffset {
        BitOffset(self.0.div_ceil(16) * 16)
    }
}

/// The size of a type in bits (BOOL: 1).
pub fn size_bits(ty: &DataType, types: &Types) -> u32 {
    match ty {
        DataType::Bool => 1,
        DataType::DateAndTime => 64,
        DataType::Pointer => 48,
        DataType::Any => 80,
        DataType::String(length) => (u32::from(*length) + 2) * 8,
        DataType::Array { dims, element } => {
            let count: u32 = dims
                .iter()
                .map(|(low, high)| (high - low + 1).max(0) as u32)
                .product();
            let element_bits = element_stride(element, types);
            BitOffset(count * element_bits).align_word().0
        }
        DataType::Struct(members) => struct_layout(members, types).1,
        DataType::Udt(number) => types
            .udts
            .get(number)
            .map_or(0, |members| struct_layout(members, types).1),
        // A multi-instance: the FB's or SFB's instance data, inside the calling FB's.
        DataType::Instance(kind, number) => {
            types.instance(*kind, *number).map_or(0, |(_, size)| size)
        }
        // The compiler replaced every name that stands for a type; one left stands for
        // nothing and was reported.
        DataType::Named(_) => 0,
        elementary => width_of(elementary).map_or(0, |width| 8 * width.bytes()),
    }
}

/// The distance between two array elements in bits.
pub fn element_stride(element: &DataType, types: &Types) -> u32 {
    match element {
        DataType::Bool => 1,
        DataType::Byte | DataType::Char => 8,
        other => BitOffset(size_bits(other, types)).align_word().0,
    }
}

/// Where a value of type `ty` starts when the area is at `at`.
fn aligned(at: BitOffset, ty: &DataType) -> BitOffset {
    match ty {
        DataType::Bool => at,
        DataType::Byte | DataType::Char => at.align_byte(),
        _ => at.align_word(),
    }
}

/// The members' offsets and the structure's size in bits (even bytes).
pub fn struct_layout(members: &[VarDecl], types: &Types) -> (Vec<BitOffset>, u32) {
    let mut at = BitOffset(0);
    let mut offsets = Vec::with_capacity(members.len());
    for member in members {
        at = aligned(at, &member.ty);
        offsets.push(at);
        at = BitOffset(at.0 + size_bits(&member.ty, types));
    }
    (offsets, at.align_word().0)
}

/// The width an access to a value of type `ty` has.
pub fn width_of(ty: &DataType) -> Option<AccessWidth> {
    Some(match ty {
        DataType::Bool => AccessWidth::Bit,
        DataType::Byte | DataType::Char => AccessWidth::Byte,
        DataType::Word
        | DataType::Int
        | DataType::S5Time
        | DataType::Date
        | DataType::Timer
        | DataType::Counter
        | DataType::BlockDb
        | DataType::BlockFb
        | DataType::BlockFc => AccessWidth::Word,
        DataType::Dword
        | DataType::Dint
        | DataType::Real
        | DataType::Time
        | DataType::TimeOfDay => AccessWidth::Double,
        _ => return None,
    })
}

/// A variable of a block's interface and where it lies.
#[derive(Debug, Clone)]
pub struct Variable {
    pub kind: VarKind,
    pub ty: DataType,
    pub home: Home,
    pub declaration: VarDecl,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Home {
    /// In the instance DB (FB inputs, outputs, in/outs, statics) or a global DB.
    Instance(BitOffset),
    /// On the L stack.
    Local(BitOffset),
    /// An FC parameter, by its position in the call's list.
    Parameter(u8),
}

/// A block's interface laid out.
#[derive(Debug, Clone, Default)]
pub struct Interface {
    pub variables: HashMap<String, Variable>,
    /// FC parameters in order (inputs, outputs, in/outs, `RET_VAL` last).
    pub parameters: Vec<String>,
    /// Bytes on the L stack.
    pub local_bytes: u32,
    /// Bytes in the instance DB (FB).
    pub instance_bytes: u32,
}

impl Interface {
    /// The interface of an FB (`instance` true: inputs … statics in the instance DB) or of an
    /// FC or OB (parameters by position, temporaries on the L stack).
    pub fn build(sections: &[(VarKind, &[VarDecl])], instance: bool, types: &Types) -> Interface {
        let mut interface = Interface::default();
        let mut data = BitOffset(0);
        let mut local = BitOffset(0);
        for (kind, vars) in sections {
            let in_instance = instance && *kind != VarKind::Temp;
            for var in *vars {
                let home = match kind {
                    VarKind::Temp => {
                        local = aligned(local, &var.ty);
                        let home = Home::Local(local);
                        local = BitOffset(local.0 + size_bits(&var.ty, types));
                        home
                    }
                    _ if in_instance => {
                        data = aligned(data, &var.ty);
                        let home = Home::Instance(data);
                        let bits = instance_bits(*kind, &var.ty, types);
                        data = BitOffset(data.0 + bits);
                        home
                    }
                    _ => {
                        interface
                            .parameters
                            .push(var.name.text.to_ascii_uppercase());
                        Home::Parameter((interface.parameters.len() - 1) as u8)
                    }
                };
                interface.variables.insert(
                    var.name.text.to_ascii_uppercase(),
                    Variable {
                        kind: *kind,
                        ty: var.ty.clone(),
                        home,
                        declaration: var.clone(),
                    },
                );
            }
            if in_instance {
                data = data.align_word();
            }
        }
        interface.local_bytes = local.align_word().byte();
        interface.instance_bytes = data.align_word().byte();
        interface
    }
}

/// Where a section lies in an FB's instance data and an FC's parameter list.
pub fn section_rank(kind: VarKind) -> u8 {
    match kind {
        VarKind::Input => 0,
        VarKind::Output => 1,
        VarKind::InOut => 2,
        VarKind::Static => 3,
        VarKind::Temp => 4,
    }
}

/// A member path below a variable: the offset in bits and the member's type, or why not.
pub fn member(ty: &DataType, path: &[PathPart], types: &Types) -> Result<(u32, DataType), String> {
    let mut offset = 0u32;
    let mut ty = ty.clone();
    for part in path {
        match (part, &ty) {
            (PathPart::Member(name), DataType::Struct(_) | DataType::Udt(_)) => {
                let members = match &ty {
                    DataType::Struct(members) => members.clone(),
                    DataType::Udt(number) => types.udts.get(number).cloned().unwrap_or_default(),
                    _ => unreachable!("matched above"),
                };
                let (offsets, _) = struct_layout(&members, types);
                let Some(at) = members
                    .iter()
                    .position(|m| m.name.text.eq_ignore_ascii_case(&name.text))
                else {
                    return Err(format!("no member `{}`", name.text));
                };
                offset += offsets[at].0;
                ty = members[at].ty.clone();
            }
            (PathPart::Index(indexes), DataType::Array { dims, element }) => {
                if indexes.len() != dims.len() {
                    return Err(format!(
                        "{} indexes for {} dimensions",
                        indexes.len(),
                        dims.len()
                    ));
                }
                let mut linear = 0u32;
                for (index, (low, high)) in indexes.iter().zip(dims) {
                    if index < low || index > high {
                        return Err(format!("index {index} is outside {low}..{high}"));
                    }
                    linear = linear * ((high - low + 1) as u32) + (index - low) as u32;
                }
                offset += linear * element_stride(element, types);
                ty = (**element).clone();
            }
            // A STRING's characters, `text[1]` the first: after its maximum and actual length
            // bytes ("Programming with STEP 7", data types: STRING).
            (PathPart::Index(indexes), DataType::String(max)) => {
                let [index] = indexes.as_slice() else {
                    return Err(format!("a STRING takes 1 index, not {}", indexes.len()));
                };
                if *index < 1 || *index > i32::from(*max) {
                    return Err(format!("index {index} is outside the STRING's 1..{max}"));
                }
                offset += (1 + *index as u32) * 8;
                ty = DataType::Char;
            }
            (PathPart::Member(name), DataType::Instance(kind, number)) => {
                let Some((sections, _)) = types.instance(*kind, *number) else {
                    return Err(format!("{} {number} is not in the program", kind.name()));
                };
                let found = sections.iter().find_map(|(start, vars)| {
                    let at = vars
                        .iter()
                        .position(|v| v.name.text.eq_ignore_ascii_case(&name.text))?;
                    let (offsets, _) = struct_layout(vars, types);
                    Some((start + offsets[at].0, vars[at].ty.clone()))
                });
                let Some((at, member)) = found else {
                    return Err(format!("no member `{}`", name.text));
                };
                offset += at;
                ty = member;
            }
            (PathPart::Member(name), _) => return Err(format!("`{}`: not a structure", name.text)),
            (PathPart::Index(_), _) => return Err("not an array".into()),
        }
    }
    Ok((offset, ty))
}

/// Whether STEP 7 passes a parameter of type `ty` as a whole block of bytes (by DB pointer to
/// an FC): the complex types. POINTER and ANY are parameter types of their own.
pub fn is_complex(ty: &DataType) -> bool {
    matches!(
        ty,
        DataType::Array { .. }
            | DataType::Struct(_)
            | DataType::Udt(_)
            | DataType::String(_)
            | DataType::DateAndTime
    )
}

/// The bits a variable of type `ty` takes in an FB's instance data: an in/out of a complex
/// type is a 6-byte DB pointer to its actual.
fn instance_bits(kind: VarKind, ty: &DataType, types: &Types) -> u32 {
    if kind == VarKind::InOut && is_complex(ty) {
        48
    } else {
        size_bits(ty, types)
    }
}
