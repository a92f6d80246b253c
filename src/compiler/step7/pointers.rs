//! Parameters of the types POINTER and ANY ("Programming with STEP 7", parameter types): what
//! a call gives them, made into the bytes STEP 7 passes.
//!
//! A POINTER is a DB pointer of 6 bytes: the DB number (0 for none) and an area-crossing
//! pointer. An ANY is 10 bytes: 16#10 (S7), the element type's code, the repetition factor, the
//! DB number and the area-crossing pointer. A call passes either a pointer known when compiling
//! (`P#DB1.DBX 0.0 BYTE 10`, `MW 10`, `#temp`) or a variable of the parameter's own type (an
//! ANY the program built on its L stack), whose bytes then travel as they are.

use crate::ast::Name;
use crate::compiler::{CheckError, Resolved};
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, CallParam, ConstKind, DataType, PathPart, S7Address, S7Area, S7Operand,
};
use crate::step7::bytecode::{AnyActual, FcCall, ParamCopy, Place, Target};
use crate::symbols::S7Symbol;

use super::layout::Home;
use super::operand::Scope;

/// The first byte of an S7 ANY pointer.
pub const ANY_MAGIC: u8 = 0x10;

/// Where the actual's pointer is looked at from: a called FC or FB sees its caller's local
/// data as area V; a system function awl runs stands in its caller's place and sees them as L.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    Callee,
    SystemFunction,
}

/// A pointer known when compiling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Descriptor {
    pub type_code: u8,
    pub count: u16,
    pub db: u16,
    /// The area-crossing pointer: area code in bits 24 to 31, byte.bit below.
    pub pointer: u32,
}

impl Descriptor {
    pub fn any_bytes(self) -> [u8; 10] {
        let mut bytes = [0; 10];
        bytes[0] = ANY_MAGIC;
        bytes[1] = self.type_code;
        bytes[2..4].copy_from_slice(&self.count.to_be_bytes());
        bytes[4..6].copy_from_slice(&self.db.to_be_bytes());
        bytes[6..].copy_from_slice(&self.pointer.to_be_bytes());
        bytes
    }

    /// The (value, byte offset, width) pieces that write the parameter's bytes: the 6 of a
    /// DB pointer or the 10 of an ANY.
    pub fn pieces(self, ty: &DataType) -> Vec<(u32, u32, AccessWidth)> {
        if *ty == DataType::Pointer {
            return vec![
                (u32::from(self.db), 0, AccessWidth::Word),
                (self.pointer, 2, AccessWidth::Double),
            ];
        }
        let bytes = self.any_bytes();
        let double = |at: usize| {
            u32::from_be_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
        };
        vec![
            (double(0), 0, AccessWidth::Double),
            (double(4), 4, AccessWidth::Double),
            (
                u32::from(u16::from_be_bytes([bytes[8], bytes[9]])),
                8,
                AccessWidth::Word,
            ),
        ]
    }
}

/// A POINTER or ANY parameter as a call names it.
#[derive(Debug, Clone, Copy)]
pub struct Formal<'a> {
    /// `DataType::Pointer` or `DataType::Any`.
    pub ty: &'a DataType,
    pub name: &'a str,
    /// The called block, for messages.
    pub callee: &'a str,
    pub view: View,
}

/// What a POINTER or ANY parameter is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointerActual {
    Known(Descriptor),
    /// A variable of the parameter's own type: its bytes at run time.
    Variable(Place),
}

impl PointerActual {
    pub fn any(self) -> AnyActual {
        match self {
            PointerActual::Known(descriptor) => AnyActual::Bytes(descriptor.any_bytes()),
            PointerActual::Variable(place) => AnyActual::At(place),
        }
    }
}

/// Whether parameters of type `ty` are passed as a pointer built by the call.
pub fn is_pointer_type(ty: &DataType) -> bool {
    matches!(ty, DataType::Pointer | DataType::Any)
}

/// The ANY type code of an elementary type (the System Software manual, the ANY format).
fn elementary_code(ty: &DataType) -> Option<u8> {
    Some(match ty {
        DataType::Bool => 0x01,
        DataType::Byte => 0x02,
        DataType::Char => 0x03,
        DataType::Word => 0x04,
        DataType::Int => 0x05,
        DataType::Dword => 0x06,
        DataType::Dint => 0x07,
        DataType::Real => 0x08,
        DataType::Date => 0x09,
        DataType::TimeOfDay => 0x0A,
        DataType::Time => 0x0B,
        DataType::S5Time => 0x0C,
        DataType::DateAndTime => 0x0E,
        _ => return None,
    })
}

/// The element type and count of an ANY to something of `bits` bits with no type of its own
/// (a structure): the widest unit that divides it.
fn by_width(bits: u32) -> (u8, u16) {
    let (code, unit) = match bits {
        bits if bits % 32 == 0 => (0x06, 32),
        bits if bits % 16 == 0 => (0x04, 16),
        bits if bits % 8 == 0 => (0x02, 8),
        _ => (0x01, 1),
    };
    (code, (bits / unit).max(1) as u16)
}

fn width_code(width: AccessWidth) -> u8 {
    match width {
        AccessWidth::Bit => 0x01,
        AccessWidth::Byte => 0x02,
        AccessWidth::Word => 0x04,
        AccessWidth::Double => 0x06,
    }
}

impl super::Compiler<'_> {
    /// The type code and count of an ANY to a variable of type `ty`.
    fn type_and_count(&self, ty: &DataType) -> (u8, u16) {
        if let Some(code) = elementary_code(ty) {
            return (code, 1);
        }
        if let DataType::Array { dims, element } = ty
            && let Some(code) = elementary_code(element)
        {
            let count: i64 = dims
                .iter()
                .map(|(low, high)| i64::from(high - low + 1).max(0))
                .product();
            return (code, count.clamp(1, i64::from(u16::MAX)) as u16);
        }
        by_width(super::layout::size_bits(ty, self.types()))
    }

    /// The pointer a call of `callee` passes for `param`, a parameter of type `formal`, as the
    /// called block sees it.
    fn callee_pointer(
        &mut self,
        param: &CallParam,
        formal: &DataType,
        callee: &str,
        scope: &Scope<'_>,
    ) -> Result<PointerActual, CheckError> {
        let formal = Formal {
            ty: formal,
            name: &param.name.text,
            callee,
            view: View::Callee,
        };
        self.pointer_actual(&param.actual, formal, param.actual_span, scope)
    }

    /// The pointer the call passes to parameter `formal` for `actual`.
    pub(super) fn pointer_actual(
        &mut self,
        actual: &S7Operand,
        formal: Formal<'_>,
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<PointerActual, CheckError> {
        let Formal {
            ty: formal_ty,
            name,
            callee,
            view,
        } = formal;
        let any = *formal_ty == DataType::Any;
        let mismatch = || CheckError::ParamMismatch {
            name: name.to_string(),
            fb: callee.to_string(),
            at,
            expected: if any {
                "an ANY: an address, a variable, or `P#DB1.DBX 0.0 BYTE 10`".into()
            } else {
                "a POINTER: an address, a variable, or `P#DB1.DBX 0.0`".into()
            },
        };
        let known = |type_code: u8, count: u16, db: u16, pointer: u32| {
            Ok(PointerActual::Known(Descriptor {
                type_code,
                count,
                db,
                pointer,
            }))
        };
        match actual {
            S7Operand::Constant(constant) => match constant.kind {
                ConstKind::AnyPointer if any && constant.bytes.len() == 10 => {
                    let bytes = &constant.bytes;
                    known(
                        bytes[1],
                        u16::from_be_bytes([bytes[2], bytes[3]]),
                        u16::from_be_bytes([bytes[4], bytes[5]]),
                        constant.value,
                    )
                }
                // `P#DB50.DBX 10.0` carries its DB number; `P#M 99.7` and `P#7.1` none.
                ConstKind::Pointer if !any => {
                    let db = match constant.bytes.as_slice() {
                        [high, low, ..] => u16::from_be_bytes([*high, *low]),
                        _ => 0,
                    };
                    known(0, 0, db, constant.value)
                }
                _ => Err(mismatch()),
            },
            // `P#DB100.DBVAR3` (an awlsim extension) stands for what it points to.
            S7Operand::PointerTo(inner) => self.pointer_actual(inner, formal, at, scope),
            S7Operand::Address(address) => self.address_pointer(address, at, view, &mismatch),
            S7Operand::Local(path) => {
                let (variable, ty, offset) = self.resolve_local(path, at, scope)?;
                if ty == *formal_ty {
                    return Ok(PointerActual::Variable(self.local_place(path, at, scope)?));
                }
                let Home::Local(base) = variable.home else {
                    return Err(CheckError::NotSimulated {
                        what: format!(
                            "a pointer to `#{}` for the parameter `{name}`",
                            variable.declaration.name.text
                        ),
                        why: "awl passes pointers to the caller's temporaries, addresses and \
                              data block members so far; an FB's instance variable or an FC's \
                              parameter is not simulated as the actual of a POINTER or ANY"
                            .into(),
                        at,
                    });
                };
                let (type_code, count) = self.type_and_count(&ty);
                let area = match view {
                    View::Callee => 0x87,
                    View::SystemFunction => 0x86,
                };
                known(type_code, count, 0, area << 24 | (base.0 + offset))
            }
            S7Operand::DbMember { db, path } => self.db_member_pointer(*db, path, at),
            S7Operand::Symbol {
                name: symbol,
                members,
            } => self.symbol_pointer(symbol, members, at, view, &mismatch),
            _ => Err(mismatch()),
        }
    }

    fn address_pointer(
        &mut self,
        address: &S7Address,
        at: Span,
        view: View,
        mismatch: &dyn Fn() -> CheckError,
    ) -> Result<PointerActual, CheckError> {
        // Checked as any operand is: within the CPU's areas.
        self.address_place(address, at)?;
        let area: u32 = match address.area {
            S7Area::PeripheralInput | S7Area::PeripheralOutput => 0x80,
            S7Area::Input => 0x81,
            S7Area::Output => 0x82,
            S7Area::Flag => 0x83,
            S7Area::Data => 0x84,
            S7Area::Instance => 0x85,
            S7Area::Local if view == View::Callee => 0x87,
            S7Area::Local => 0x86,
            S7Area::PreviousLocal | S7Area::Timer | S7Area::Counter => return Err(mismatch()),
        };
        Ok(PointerActual::Known(Descriptor {
            type_code: width_code(address.width),
            count: 1,
            db: address.db.unwrap_or(0),
            pointer: area << 24 | address.byte << 3 | u32::from(address.bit),
        }))
    }

    fn db_member_pointer(
        &mut self,
        db: u16,
        path: &[PathPart],
        at: Span,
    ) -> Result<PointerActual, CheckError> {
        let (bits, ty) = self.db_member(db, path, at)?;
        let (type_code, count) = self.type_and_count(&ty);
        Ok(PointerActual::Known(Descriptor {
            type_code,
            count,
            db,
            pointer: 0x84 << 24 | bits,
        }))
    }

    fn symbol_pointer(
        &mut self,
        name: &Name,
        members: &[PathPart],
        at: Span,
        view: View,
        mismatch: &dyn Fn() -> CheckError,
    ) -> Result<PointerActual, CheckError> {
        match self.symbol(name)? {
            S7Symbol::Address(address) if members.is_empty() => {
                self.address_pointer(&address, at, view, mismatch)
            }
            S7Symbol::Block {
                kind: crate::step7::ast::S7BlockKind::Db,
                number,
            } if !members.is_empty() => self.db_member_pointer(number, members, at),
            _ => Err(mismatch()),
        }
    }

    /// `L P#DB42.member`, `L P#"Data".member` (an awlsim extension): the area pointer to a
    /// member of a global data block, as the DB's own `P#DBX` address.
    pub(super) fn db_member_area_pointer(
        &mut self,
        operand: &S7Operand,
        at: Span,
    ) -> Option<Result<u32, CheckError>> {
        let (db, path) = match operand {
            S7Operand::DbMember { db, path } => (*db, path.as_slice()),
            S7Operand::Symbol { name, members } if !members.is_empty() => match self.symbol(name) {
                Ok(S7Symbol::Block {
                    kind: crate::step7::ast::S7BlockKind::Db,
                    number,
                }) => (number, members.as_slice()),
                Ok(_) => return None,
                Err(error) => return Some(Err(error)),
            },
            _ => return None,
        };
        Some(
            self.db_member_pointer(db, path, at)
                .map(|actual| match actual {
                    PointerActual::Known(descriptor) => descriptor.pointer,
                    PointerActual::Variable(_) => 0,
                }),
        )
    }
}

/// A place `bytes` further on than `place`, for the pieces of a pointer variable; `None` for
/// a place that has no bytes of its own.
pub fn offset_place(place: Place, bytes: u32, width: AccessWidth) -> Option<Place> {
    let target = match place.target {
        Target::Local { byte, bit } => Target::Local {
            byte: byte + bytes,
            bit,
        },
        Target::PreviousLocal { byte, bit } => Target::PreviousLocal {
            byte: byte + bytes,
            bit,
        },
        Target::Data {
            instance,
            byte,
            bit,
        } => Target::Data {
            instance,
            byte: byte + bytes,
            bit,
        },
        Target::Instance { byte, bit } => Target::Instance {
            byte: byte + bytes,
            bit,
        },
        Target::NumberedData {
            db,
            slot,
            byte,
            bit,
        } => Target::NumberedData {
            db,
            slot,
            byte: byte + bytes,
            bit,
        },
        Target::Parameter { param, byte, bit } => Target::Parameter {
            param,
            byte: byte + bytes,
            bit,
        },
        _ => return None,
    };
    Some(Place { target, width })
}

impl super::Compiler<'_> {
    /// An FC's POINTER or ANY parameter: a pointer known when compiling is written onto the
    /// caller's L stack after its temporaries (`scratch_bits` of them used so far by the
    /// call), and the FC gets a pointer to it (area V), as STEP 7 does; a variable of the
    /// parameter's type is passed itself. `None` after an error.
    pub(super) fn fc_pointer_param(
        &mut self,
        param: &CallParam,
        formal: &DataType,
        callee: &str,
        scope: &Scope<'_>,
        scratch_bits: &mut u32,
        call: &mut FcCall,
    ) -> Option<Resolved> {
        let actual = self.callee_pointer(param, formal, callee, scope);
        let descriptor = match actual {
            Ok(PointerActual::Known(descriptor)) => descriptor,
            // An FC's own POINTER or ANY parameter lies on its caller's caller's L stack,
            // which no pointer of the called FC reaches.
            Ok(PointerActual::Variable(Place {
                target: Target::Parameter { .. },
                ..
            })) => {
                self.errors.push(CheckError::NotSimulated {
                    what: format!("passing on the parameter `{}`", param.name.text),
                    why: "an FC passes its POINTER or ANY parameter on to an FB, not to another \
                          FC, so far"
                        .into(),
                    at: param.actual_span,
                });
                return None;
            }
            Ok(PointerActual::Variable(place)) => {
                return Some(Resolved::S7(self.tables.place(place)));
            }
            Err(error) => {
                self.errors.push(error);
                return None;
            }
        };
        let start = scratch_bits.div_ceil(16) * 16;
        *scratch_bits = start + super::layout::size_bits(formal, self.types());
        let base = self.scratch_base + start / 8;
        for (value, byte, width) in descriptor.pieces(formal) {
            let constant = self.tables.place(Place {
                target: Target::Constant(value),
                width,
            });
            let copy = self.tables.place(Place {
                target: Target::Local {
                    byte: base + byte,
                    bit: 0,
                },
                width,
            });
            // Before the call whatever the parameter's direction: the FC reads the pointer
            // to find where to write an output.
            call.inputs.push((constant, copy));
        }
        Some(Resolved::S7(self.tables.place(Place {
            target: Target::Local { byte: base, bit: 0 },
            width: AccessWidth::Byte,
        })))
    }

    /// An FB's POINTER or ANY parameter at `offset` in its instance data: the pointer's bytes
    /// copied there before the call. `None` after an error.
    pub(super) fn fb_pointer_param(
        &mut self,
        param: &CallParam,
        formal: &DataType,
        offset: super::layout::BitOffset,
        callee: &str,
        scope: &Scope<'_>,
    ) -> Option<Vec<ParamCopy>> {
        let actual = self.callee_pointer(param, formal, callee, scope);
        let pieces: Vec<(Place, u32)> = match actual {
            Ok(PointerActual::Known(descriptor)) => descriptor
                .pieces(formal)
                .into_iter()
                .map(|(value, byte, width)| {
                    let place = Place {
                        target: Target::Constant(value),
                        width,
                    };
                    (place, byte)
                })
                .collect(),
            Ok(PointerActual::Variable(place)) => {
                let bytes = super::layout::size_bits(formal, self.types()) / 8;
                let mut pieces = Vec::new();
                let mut at = 0;
                while at < bytes {
                    let width = if bytes - at >= 4 {
                        AccessWidth::Double
                    } else {
                        AccessWidth::Word
                    };
                    let Some(piece) = offset_place(place, at, width) else {
                        self.errors.push(CheckError::NotSimulated {
                            what: format!("this actual of the parameter `{}`", param.name.text),
                            why: "a POINTER or ANY variable is passed from the caller's \
                                  temporaries or instance data"
                                .into(),
                            at: param.actual_span,
                        });
                        return None;
                    };
                    pieces.push((piece, at));
                    at += width.bytes();
                }
                pieces
            }
            Err(error) => {
                self.errors.push(error);
                return None;
            }
        };
        Some(
            pieces
                .into_iter()
                .map(|(place, byte)| ParamCopy {
                    actual: self.tables.place(place),
                    byte: offset.byte() + byte,
                    bit: 0,
                    width: place.width,
                })
                .collect(),
        )
    }
}
