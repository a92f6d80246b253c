//! Calls of the library FCs (see [`crate::step7::library`]): `CALL FC 105 (…)` or
//! `CALL "SCALE" (…)` when the program defines no such FC and its symbol table does not give
//! the name to another block. Every parameter is given once, with an actual of its type; the
//! places go to the VM in the interface's order.

use crate::ast::BlockId;
use crate::compiler::CheckError;
use crate::mnemonics::BlockKind;
use crate::source::Span;
use crate::step7::ast::{
    AccessWidth, CallParam, CallSpec, ConstKind, DataType, S7BlockKind, S7BlockRef, S7Operand,
};
use crate::step7::bytecode::Target;
use crate::step7::library::{self, AnyType, LibraryCall, LibraryFc, Param, ParamType};
use crate::symbols::S7Symbol;

use super::operand::Scope;

/// What a call's block reference names, as far as the library goes.
pub(super) enum Target7 {
    /// The library's FC: the program has none of that number.
    Library(&'static LibraryFc),
    /// The block the program defines or the symbol table names (a symbolic library name the
    /// table lacks, made into the program's own FC of the library's number).
    Program(S7BlockRef),
}

impl super::Compiler<'_> {
    fn defines_fc(&self, number: u16) -> bool {
        self.index.contains_key(&BlockId {
            kind: BlockKind::Fc,
            number,
        })
    }

    /// Whether `reference` calls a library FC. A note when the library's usual name, which the
    /// symbol table does not list, or gives to another block, calls the program's own block
    /// (`CALL FC 20` of a program with an FC 20 is simply its own block).
    pub(super) fn library_target(&mut self, reference: &S7BlockRef, at: Span) -> Target7 {
        let program = Target7::Program(reference.clone());
        let (number, by_library_name) = match reference {
            S7BlockRef::Number {
                kind: S7BlockKind::Fc,
                number,
            } => (*number, None),
            S7BlockRef::Symbol(name) => {
                let written = format!("\"{}\"", name.text);
                match self.symbol(name) {
                    Ok(S7Symbol::Block {
                        kind: S7BlockKind::Fc,
                        number,
                    }) if library::by_name(&name.text).is_none_or(|fc| fc.number == number) => {
                        (number, None)
                    }
                    Ok(S7Symbol::Block { kind, number }) => {
                        if let Some(fc) = library::by_name(&name.text) {
                            self.errors.push(CheckError::LibraryReplaced {
                                called: written,
                                block: format!("{} {number}", kind.name()),
                                library: fc.label(),
                                at,
                                why: format!(
                                    "the symbol table gives this name to {} {number}",
                                    kind.name()
                                ),
                            });
                        }
                        return program;
                    }
                    Ok(_) => return program,
                    // A library name the table does not list stands for the library's number.
                    Err(_) => match library::by_name(&name.text) {
                        Some(fc) => (fc.number, Some(written)),
                        None => return program,
                    },
                }
            }
            _ => return program,
        };
        let Some(fc) = library::by_number(number) else {
            return program;
        };
        if !self.defines_fc(number) {
            return Target7::Library(fc);
        }
        if let Some(written) = by_library_name {
            self.note_own(written, fc, at);
        }
        Target7::Program(S7BlockRef::Number {
            kind: S7BlockKind::Fc,
            number,
        })
    }

    /// The note that the program's own FC replaces the library's: once, at its first call by
    /// the library's name.
    fn note_own(&mut self, called: String, fc: &LibraryFc, at: Span) {
        let block = format!("FC {}", fc.number);
        let noted = self.errors.iter().any(|error| {
            matches!(error, CheckError::LibraryReplaced { block: other, .. } if *other == block)
        });
        if noted {
            return;
        }
        self.errors.push(CheckError::LibraryReplaced {
            called,
            block,
            library: fc.label(),
            at,
            why: format!("the program defines FC {}", fc.number),
        });
    }

    /// `CALL FC 105 (…)` of the library's FC: its call's index in
    /// [`crate::step7::bytecode::S7Tables::library_calls`], `None` after errors.
    pub(super) fn library_call(
        &mut self,
        fc: &'static LibraryFc,
        call: &CallSpec,
        at: Span,
        scope: &Scope<'_>,
    ) -> Option<u16> {
        let label = fc.label();
        let names: Vec<&str> = fc.params.iter().map(|param| param.name).collect();
        let mut ok = true;
        for (index, param) in call.params.iter().enumerate() {
            let name = param.name.text.to_ascii_uppercase();
            let known = names.contains(&name.as_str());
            let twice = call.params[..index]
                .iter()
                .any(|other| other.name.text.eq_ignore_ascii_case(&name));
            if !known || twice {
                self.errors.push(CheckError::UnknownParam {
                    name: param.name.text.clone(),
                    fb: label.clone(),
                    at: param.name.span,
                    help: Some(if twice {
                        format!("`{name}` is given twice")
                    } else {
                        format!("{label} has {}", names.join(", "))
                    }),
                });
                ok = false;
            }
        }
        let missing: Vec<&str> = names
            .iter()
            .copied()
            .filter(|name| {
                !call
                    .params
                    .iter()
                    .any(|param| param.name.text.eq_ignore_ascii_case(name))
            })
            .collect();
        if !missing.is_empty() {
            self.errors.push(CheckError::ParamCount {
                fb: label.clone(),
                expected: names.len(),
                found: names.len() - missing.len(),
                at,
                help: Some(format!(
                    "a library FC needs every parameter; missing: {}",
                    missing.join(", ")
                )),
            });
            return None;
        }
        if !ok {
            return None;
        }
        let any_type = self.any_type(fc, call, scope)?;
        let mut library_call = LibraryCall {
            number: fc.number,
            params: Vec::new(),
            constants: Vec::new(),
            any_type,
        };
        let mut scratch_bits = 0;
        for formal in fc.params {
            let param = call
                .params
                .iter()
                .find(|param| param.name.text.eq_ignore_ascii_case(formal.name))
                .expect("every parameter is given");
            let place = match formal.ty {
                ParamType::String | ParamType::DateAndTime => self.complex_library_actual(
                    param,
                    formal,
                    &label,
                    scope,
                    &mut scratch_bits,
                    &mut library_call,
                ),
                _ => self.elementary_library_actual(param, formal, any_type, &label, scope),
            };
            match place {
                Ok(place) => library_call.params.push(place),
                Err(error) => {
                    self.errors.push(error);
                    ok = false;
                }
            }
        }
        self.scratch_bytes = self.scratch_bytes.max(scratch_bits.div_ceil(16) * 2);
        if !ok {
            return None;
        }
        self.tables.library_calls.push(library_call);
        Some((self.tables.library_calls.len() - 1) as u16)
    }

    /// A STRING or DATE_AND_TIME actual: a variable of the type, or for an input a constant,
    /// copied to the caller's L stack.
    fn complex_library_actual(
        &mut self,
        param: &CallParam,
        formal: &Param,
        label: &str,
        scope: &Scope<'_>,
        scratch_bits: &mut u32,
        call: &mut LibraryCall,
    ) -> Result<u16, CheckError> {
        let string = formal.ty == ParamType::String;
        let mismatch = |to_write: bool| CheckError::ParamMismatch {
            name: formal.name.into(),
            fb: label.into(),
            at: param.actual_span,
            expected: match (string, to_write) {
                (true, true) => "a STRING variable to write, such as #text or DB1.text".into(),
                (true, false) => "a STRING: a variable such as #text, or 'text'".into(),
                (false, true) => "a DATE_AND_TIME variable to write, such as #now".into(),
                (false, false) => {
                    "a DATE_AND_TIME: a variable such as #now, or DT#1990-1-1-0:0:0".into()
                }
            },
        };
        if let S7Operand::Constant(constant) = &param.actual {
            let ty = match constant.kind {
                ConstKind::String | ConstKind::Char if string => {
                    DataType::String(constant.bytes.len().min(254) as u8)
                }
                ConstKind::DateAndTime if !string => DataType::DateAndTime,
                _ => return Err(mismatch(formal.output)),
            };
            if formal.output {
                return Err(mismatch(true));
            }
            let bytes = super::complex::constant_bytes(&ty, constant).ok_or(mismatch(false))?;
            let place = self.scratch(scratch_bits, bytes.len() as u32);
            call.constants.push((place, bytes));
            return Ok(place);
        }
        let fits = match self.actual_type(&param.actual, param.actual_span, scope) {
            Some(DataType::String(_)) => string,
            Some(DataType::DateAndTime) => !string,
            _ => false,
        };
        if !fits {
            return Err(mismatch(formal.output));
        }
        let place = self.place(&param.actual, param.actual_span, scope)?;
        Ok(self.tables.place(place))
    }

    /// An elementary actual: of the parameter's width, and no constant for an output.
    fn elementary_library_actual(
        &mut self,
        param: &CallParam,
        formal: &Param,
        any_type: AnyType,
        label: &str,
        scope: &Scope<'_>,
    ) -> Result<u16, CheckError> {
        let place = self.place(&param.actual, param.actual_span, scope)?;
        let width = match formal.ty {
            ParamType::Bool => Some(AccessWidth::Bit),
            ParamType::Int | ParamType::Word | ParamType::S5Time | ParamType::Date => {
                Some(AccessWidth::Word)
            }
            ParamType::Number if any_type == AnyType::Int => Some(AccessWidth::Word),
            ParamType::Elementary => None,
            _ => Some(AccessWidth::Double),
        };
        let constant = matches!(place.target, Target::Constant(_));
        if width.is_some_and(|width| width != place.width) || (formal.output && constant) {
            let what = match formal.ty {
                ParamType::Number => any_type_name(any_type),
                other => other.name(),
            };
            return Err(CheckError::ParamMismatch {
                name: formal.name.into(),
                fb: label.into(),
                at: param.actual_span,
                expected: if formal.output {
                    format!("{} {what} to write to", article(what))
                } else {
                    format!("{} {what}", article(what))
                },
            });
        }
        Ok(self.tables.place(place))
    }

    /// The type the ANY parameters of LIMIT, MAX, MIN or SEL share: the declared type of the
    /// variables and the kind of the constants given to them; addresses take the others' type
    /// (an INT for a word and a DINT for a double word when nothing else says). `None` after
    /// an error: two types, a type the block does not take, or widths that differ (SEL).
    fn any_type(&mut self, fc: &LibraryFc, call: &CallSpec, scope: &Scope<'_>) -> Option<AnyType> {
        let anys: Vec<(&Param, &CallParam)> = fc
            .params
            .iter()
            .filter(|formal| matches!(formal.ty, ParamType::Number | ParamType::Elementary))
            .filter_map(|formal| {
                let param = call
                    .params
                    .iter()
                    .find(|param| param.name.text.eq_ignore_ascii_case(formal.name))?;
                Some((formal, param))
            })
            .collect();
        let Some((first, _)) = anys.first() else {
            return Some(AnyType::Int);
        };
        if first.ty == ParamType::Elementary {
            return self.same_width(fc, &anys, scope).then_some(AnyType::Bits);
        }
        let mut found: Option<(AnyType, Span)> = None;
        for (formal, param) in &anys {
            let Some(ty) = self.declared_any_type(&param.actual, param.actual_span, scope) else {
                continue;
            };
            let Some(ty) = ty else {
                self.errors.push(CheckError::ParamMismatch {
                    name: formal.name.into(),
                    fb: fc.label(),
                    at: param.actual_span,
                    expected: "an INT, a DINT or a REAL".into(),
                });
                return None;
            };
            match found {
                Some((other, at)) if other != ty => {
                    self.errors.push(CheckError::ParamMismatch {
                        name: formal.name.into(),
                        fb: fc.label(),
                        at: param.actual_span,
                        expected: format!(
                            "{} {} as the other parameters (the first at {})",
                            article(any_type_name(other)),
                            any_type_name(other),
                            self.where_is(at)
                        ),
                    });
                    return None;
                }
                _ => found = Some((ty, param.actual_span)),
            }
        }
        if let Some((ty, _)) = found {
            return Some(ty);
        }
        // Only addresses: their width says (a bad one is reported with its parameter).
        let (_, param) = anys[0];
        let width = self
            .place(&param.actual, param.actual_span, scope)
            .map(|place| place.width);
        Some(if width == Ok(AccessWidth::Double) {
            AnyType::Dint
        } else {
            AnyType::Int
        })
    }

    /// The type of an ANY actual that has one: `Some(None)` for a type LIMIT, MAX and MIN do
    /// not take, `None` for an address.
    fn declared_any_type(
        &self,
        actual: &S7Operand,
        at: Span,
        scope: &Scope<'_>,
    ) -> Option<Option<AnyType>> {
        if let S7Operand::Constant(constant) = actual {
            return Some(match constant.kind {
                ConstKind::Int => Some(AnyType::Int),
                ConstKind::Dint => Some(AnyType::Dint),
                ConstKind::Real => Some(AnyType::Real),
                _ => None,
            });
        }
        Some(match self.actual_type(actual, at, scope)? {
            DataType::Int => Some(AnyType::Int),
            DataType::Dint => Some(AnyType::Dint),
            DataType::Real => Some(AnyType::Real),
            _ => None,
        })
    }

    /// SEL: IN0, IN1 and RET_VAL of one width, none a STRING or DATE_AND_TIME.
    fn same_width(
        &mut self,
        fc: &LibraryFc,
        anys: &[(&Param, &CallParam)],
        scope: &Scope<'_>,
    ) -> bool {
        let mut width = None;
        for (formal, param) in anys {
            let complex = matches!(
                self.actual_type(&param.actual, param.actual_span, scope),
                Some(ty) if super::layout::is_complex(&ty)
            );
            let Ok(place) = self.place(&param.actual, param.actual_span, scope) else {
                continue;
            };
            if complex || width.is_some_and(|width| width != place.width) {
                self.errors.push(CheckError::ParamMismatch {
                    name: formal.name.into(),
                    fb: fc.label(),
                    at: param.actual_span,
                    expected: "an elementary value of the same type as IN0".into(),
                });
                return false;
            }
            width = Some(place.width);
        }
        true
    }
}

fn any_type_name(ty: AnyType) -> &'static str {
    match ty {
        AnyType::Int => "INT",
        AnyType::Dint => "DINT",
        AnyType::Real => "REAL",
        AnyType::Bits => "value",
    }
}

/// "an" before a type name that is spoken with a vowel first (INT, S5TIME), else "a".
fn article(name: &str) -> &'static str {
    if name.starts_with(['A', 'E', 'I', 'O', 'U']) || name.starts_with("S5") {
        "an"
    } else {
        "a"
    }
}
