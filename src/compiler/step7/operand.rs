//! STEP 7 operands to places: absolute addresses, locals and parameters by name, indirect
//! addresses, constants and awlsim's test operands.

use crate::compiler::CheckError;
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, ConstKind, DataType, IndirectPointer, S7Address, S7Area, S7Constant, S7Operand,
    VarKind,
};
use crate::step7::bytecode::{Place, Target};
use crate::suggest::one_edit_from;
use crate::symbols::SymbolError;

use super::layout::{self, Home, Interface};

/// What the block compiles against: its interface, its name for messages.
pub struct Scope<'i> {
    pub interface: &'i Interface,
    pub block: String,
}

/// The value a constant loads into ACCU 1: awl, like awlsim, loads a 16-bit constant into
/// ACCU 1-L with ACCU 1-H 0.
pub fn constant_value(constant: &S7Constant) -> u32 {
    match constant.kind {
        ConstKind::Int
        | ConstKind::Word
        | ConstKind::S5Time
        | ConstKind::Counter
        | ConstKind::Date => constant.value & 0xFFFF,
        ConstKind::Byte | ConstKind::Char => constant.value & 0xFF,
        _ => constant.value,
    }
}

impl super::Compiler<'_> {
    /// The image memory offset of an `I`/`Q`/`M` address (any width), when in range.
    pub fn image_byte(&self, address: &S7Address) -> Option<u16> {
        let layout = crate::address::Layout::new(&self.profile.sizes);
        let (base, size) = match address.area {
            S7Area::Input => (layout.input_base(), layout.image_bytes),
            S7Area::Output => (layout.output_base(), layout.image_bytes),
            S7Area::Flag => (layout.flag_base(), layout.flag_bytes),
            _ => return None,
        };
        let end = address.byte + address.width.bytes();
        (end <= u32::from(size)).then(|| base + address.byte as u16)
    }

    fn range_error(&self, address: &S7Address, at: Span) -> CheckError {
        let layout = crate::address::Layout::new(&self.profile.sizes);
        let (name, size) = match address.area {
            S7Area::Input => ("I", layout.image_bytes),
            S7Area::Output => ("Q", layout.image_bytes),
            _ => ("M", layout.flag_bytes),
        };
        CheckError::OperandRange {
            what: format!("{name} byte {}", address.byte),
            at,
            range: format!("{name} bytes 0 to {}", size.saturating_sub(1)),
            cpu: self.profile.name,
        }
    }

    /// The place of an absolute address.
    pub fn address_place(&mut self, address: &S7Address, at: Span) -> Result<Place, CheckError> {
        let width = address.width;
        let target = match address.area {
            S7Area::Input | S7Area::Output | S7Area::Flag => match self.image_byte(address) {
                Some(byte) => Target::Image {
                    byte,
                    bit: address.bit,
                },
                None => return Err(self.range_error(address, at)),
            },
            S7Area::PeripheralInput | S7Area::PeripheralOutput => {
                let size = self.profile.sizes.peripheral_bytes;
                if address.byte + width.bytes() > u32::from(size) {
                    let name = if address.area == S7Area::PeripheralInput {
                        "PI"
                    } else {
                        "PQ"
                    };
                    return Err(CheckError::OperandRange {
                        what: format!("{name} byte {}", address.byte),
                        at,
                        range: format!("{name} bytes 0 to {}", size.saturating_sub(1)),
                        cpu: self.profile.name,
                    });
                }
                Target::Peripheral {
                    output: address.area == S7Area::PeripheralOutput,
                    byte: address.byte as u16,
                }
            }
            S7Area::Local => Target::Local {
                byte: address.byte,
                bit: address.bit,
            },
            S7Area::PreviousLocal => Target::PreviousLocal {
                byte: address.byte,
                bit: address.bit,
            },
            S7Area::Data | S7Area::Instance => match address.db {
                Some(db) => Target::NumberedData {
                    db,
                    slot: self.db_slot(db, at),
                    byte: address.byte,
                    bit: address.bit,
                },
                None => Target::Data {
                    instance: address.area == S7Area::Instance,
                    byte: address.byte,
                    bit: address.bit,
                },
            },
            S7Area::Timer | S7Area::Counter => {
                let (count, name) = if address.area == S7Area::Timer {
                    (self.profile.sizes.timers, "T")
                } else {
                    (self.profile.sizes.counters, "C")
                };
                if address.byte >= u32::from(count) {
                    return Err(CheckError::OperandRange {
                        what: format!("{name} {}", address.byte),
                        at,
                        range: format!("{name} 0 to {}", count.saturating_sub(1)),
                        cpu: self.profile.name,
                    });
                }
                if address.area == S7Area::Timer {
                    Target::Timer(address.byte as u16)
                } else {
                    Target::Counter(address.byte as u16)
                }
            }
        };
        Ok(Place { target, width })
    }

    /// The place of any operand that names one.
    pub fn place(
        &mut self,
        operand: &S7Operand,
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<Place, CheckError> {
        match operand {
            S7Operand::Address(address) => self.address_place(address, at),
            S7Operand::Local(path) => self.local_place(path, at, scope),
            S7Operand::Constant(constant) => Ok(Place {
                target: Target::Constant(constant_value(constant)),
                width: match constant.kind {
                    ConstKind::Bool => AccessWidth::Bit,
                    ConstKind::Byte | ConstKind::Char => AccessWidth::Byte,
                    ConstKind::Int
                    | ConstKind::Word
                    | ConstKind::S5Time
                    | ConstKind::Counter
                    | ConstKind::Date => AccessWidth::Word,
                    _ => AccessWidth::Double,
                },
            }),
            S7Operand::Indirect {
                area,
                width,
                pointer,
            } => {
                let target = match *pointer {
                    IndirectPointer::Memory(address) => {
                        let pointer_place = self.address_place(&address, at)?;
                        Target::MemoryIndirect {
                            area: *area,
                            pointer: self.tables.place(pointer_place),
                        }
                    }
                    IndirectPointer::Register { ar, offset } => Target::RegisterIndirect {
                        area: Some(*area),
                        ar,
                        offset,
                    },
                };
                Ok(Place {
                    target,
                    width: *width,
                })
            }
            S7Operand::Extension(extension) => Ok(Place {
                target: Target::Extension(*extension),
                width: AccessWidth::Double,
            }),
            S7Operand::Condition(condition) => Ok(Place {
                target: Target::Condition(*condition),
                width: AccessWidth::Bit,
            }),
            S7Operand::DbRegister(register) => Ok(Place {
                target: Target::DbRegister(*register),
                width: AccessWidth::Word,
            }),
            S7Operand::Block(reference) => match reference {
                crate::step7::ast::S7BlockRef::Number { number, .. } => Ok(Place {
                    target: Target::Constant(u32::from(*number)),
                    width: AccessWidth::Word,
                }),
                crate::step7::ast::S7BlockRef::Symbol(name) => self.symbol_place(name, &[], at),
            },
            // A block parameter's actual `DB [MW 14]`: the word that holds the number.
            S7Operand::BlockFrom { word, .. } => Ok(Place {
                width: AccessWidth::Word,
                ..self.place(word, at, scope)?
            }),
            S7Operand::AreaCrossing { width, ar, offset } => Ok(Place {
                target: Target::RegisterIndirect {
                    area: None,
                    ar: *ar,
                    offset: *offset,
                },
                width: *width,
            }),
            S7Operand::IndirectLocal {
                area,
                width,
                pointer,
            } => {
                let pointer_place = self.local_place(pointer, at, scope)?;
                let pointer = self.tables.place(Place {
                    width: AccessWidth::Double,
                    ..pointer_place
                });
                Ok(Place {
                    target: Target::MemoryIndirect {
                        area: *area,
                        pointer,
                    },
                    width: *width,
                })
            }
            S7Operand::DbMember { db, path } => self.db_member_place(*db, path, at),
            S7Operand::Symbol { name, members } => self
                .symbol_place(name, members, at)
                .map_err(|error| close_variable(error, scope)),
            _ => Err(not_an_operand(at, "this operand")),
        }
    }

    /// `DB5.speed`: a member of a data block declared in the program.
    pub(super) fn db_member_place(
        &mut self,
        db: u16,
        path: &[crate::step7::ast::PathPart],
        at: Span,
    ) -> Result<Place, CheckError> {
        let (bits, ty) = self.db_member(db, path, at)?;
        Ok(Place {
            target: Target::NumberedData {
                db,
                slot: self.db_slot(db, at),
                byte: bits / 8,
                bit: (bits % 8) as u8,
            },
            width: layout::width_of(&ty).unwrap_or(AccessWidth::Byte),
        })
    }

    /// Where a member of data block `db` lies (in bits from the block's start) and its type.
    pub(super) fn db_member(
        &self,
        db: u16,
        path: &[crate::step7::ast::PathPart],
        at: Span,
    ) -> Result<(u32, DataType), CheckError> {
        let Some(layout) = self.db_layouts.get(&db) else {
            return Err(CheckError::UndefinedDb {
                id: format!("DB {db}"),
                at,
            });
        };
        let scope = Scope {
            interface: layout,
            block: format!("DB {db}"),
        };
        let (variable, ty, offset) = self.resolve_local(path, at, &scope)?;
        let Home::Instance(base) = variable.home else {
            return Err(not_an_operand(at, "this member"));
        };
        Ok((base.0 + offset, ty))
    }

    /// `#name.member[3]`: a variable of the block's interface.
    pub fn local_place(
        &mut self,
        path: &[crate::step7::ast::PathPart],
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<Place, CheckError> {
        let (variable, ty, offset) = self.resolve_local(path, at, scope)?;
        let width = layout::width_of(&ty).unwrap_or(AccessWidth::Byte);
        let (byte, bit) = (offset / 8, (offset % 8) as u8);
        let target = match variable.home {
            Home::Instance(base)
                if variable.kind == VarKind::InOut && super::layout::is_complex(&variable.ty) =>
            {
                Target::InstanceThrough {
                    pointer: base.byte(),
                    byte,
                    bit,
                }
            }
            Home::Instance(base) => {
                let at_bits = base.0 + offset;
                Target::Instance {
                    byte: at_bits / 8,
                    bit: (at_bits % 8) as u8,
                }
            }
            Home::Local(base) => {
                let at_bits = base.0 + offset;
                Target::Local {
                    byte: at_bits / 8,
                    bit: (at_bits % 8) as u8,
                }
            }
            Home::Parameter(param) if super::layout::is_complex(&variable.ty) => {
                Target::Through { param, byte, bit }
            }
            Home::Parameter(param) => Target::Parameter { param, byte, bit },
        };
        // An FB keeps a TIMER or COUNTER parameter as its number in the instance DB.
        let target = match (&ty, variable.home) {
            (DataType::Timer, Home::Instance(_) | Home::Local(_)) => Target::TimerFrom {
                place: self.tables.place(Place {
                    target,
                    width: AccessWidth::Word,
                }),
            },
            (DataType::Counter, Home::Instance(_) | Home::Local(_)) => Target::CounterFrom {
                place: self.tables.place(Place {
                    target,
                    width: AccessWidth::Word,
                }),
            },
            _ => target,
        };
        Ok(Place { target, width })
    }

    pub fn resolve_local(
        &self,
        path: &[crate::step7::ast::PathPart],
        at: Span,
        scope: &Scope<'_>,
    ) -> Result<(layout::Variable, DataType, u32), CheckError> {
        let Some(crate::step7::ast::PathPart::Member(first)) = path.first() else {
            return Err(not_an_operand(at, "this name"));
        };
        let Some(variable) = scope
            .interface
            .variables
            .get(&first.text.to_ascii_uppercase())
        else {
            let known: Vec<&str> = scope
                .interface
                .variables
                .values()
                .map(|v| v.declaration.name.text.as_str())
                .collect();
            let close = one_edit_from(&first.text, known.iter().copied())
                .map(|name| format!("did you mean `#{name}`?"));
            return Err(CheckError::UndeclaredLocal {
                name: first.text.clone(),
                block: scope.block.clone(),
                at,
                help: close,
            });
        };
        let (offset, ty) = layout::member(&variable.ty, &path[1..], self.types())
            .map_err(|problem| not_an_operand(at, &problem))?;
        Ok((variable.clone(), ty, offset))
    }
}

pub fn not_an_operand(at: Span, what: &str) -> CheckError {
    CheckError::OperandNotAllowed {
        op: "this operation".into(),
        at,
        help: Some(format!("{what} cannot be used here")),
    }
}

/// An unknown bare name (`L positon1;`) close to a variable of the block: the help names the
/// variable, the likelier meaning than a symbol.
fn close_variable(error: CheckError, scope: &Scope<'_>) -> CheckError {
    let CheckError::Symbol(mut symbol) = error else {
        return error;
    };
    if let SymbolError::Unknown { written, help, .. } = symbol.as_mut()
        && !written.starts_with('"')
    {
        let upper = written.to_ascii_uppercase();
        let closest = scope
            .interface
            .variables
            .iter()
            .map(|(name, variable)| (strsim::damerau_levenshtein(&upper, name), variable))
            .filter(|(distance, _)| *distance <= 2 && upper.len() > 3)
            .min_by_key(|(distance, _)| *distance);
        if let Some((_, variable)) = closest {
            let named = format!(
                "did you mean `{}`, a variable of {}?",
                variable.declaration.name.text, scope.block
            );
            *help = Some(match help.take() {
                Some(table) => format!("{named} ({table})"),
                None => named,
            });
        }
    }
    CheckError::Symbol(symbol)
}
