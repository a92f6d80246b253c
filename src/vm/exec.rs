//! What the execution loop ([`super::run_loop`]) hands off: the image and data memory, formal
//! operands and `DO`, and the operations it does not run inline.

use crate::ast::Address;
use crate::compiler::bytecode::*;
use crate::compiler::{Resolved, lower, specialise};

use super::io_trace::Modules;

use super::Cpu;
use super::arith;
use super::bytes::{read_bytes, write_bytes};
use super::float;
use super::interrupts::FamilyRules;
use super::interrupts::s5_95f::S595f;
use super::stop::{StopCause, StopDetail};
use super::system_ops;

impl Cpu {
    #[inline(always)]
    pub(super) fn image_bit(&self, bit: ImageBit) -> bool {
        self.image[usize::from(bit.byte)] >> bit.bit & 1 != 0
    }

    #[inline(always)]
    pub(super) fn write_image_bit(&mut self, bit: ImageBit, value: bool) {
        let byte = &mut self.image[usize::from(bit.byte)];
        let mask = 1u8 << bit.bit;
        if value { *byte |= mask } else { *byte &= !mask }
    }

    fn load(&mut self, value: u32) {
        self.level.accu2 = self.level.accu1;
        self.level.accu1 = value;
    }

    /// Image reads and writes index the fixed-size image with a `u16` offset: in bounds by type.
    #[inline(always)]
    pub(super) fn read_image(&self, width: Width, byte: u16) -> u32 {
        let at = usize::from(byte);
        let image = &*self.image;
        match width {
            Width::Byte => u32::from(image[at]),
            Width::Word => u32::from(u16::from_be_bytes([image[at], image[at + 1]])),
            Width::Double => {
                u32::from_be_bytes([image[at], image[at + 1], image[at + 2], image[at + 3]])
            }
        }
    }

    #[inline(always)]
    pub(super) fn write_image(&mut self, width: Width, byte: u16, value: u32) {
        let at = usize::from(byte);
        let image = &mut *self.image;
        match width {
            Width::Byte => image[at] = value as u8,
            Width::Word => [image[at], image[at + 1]] = (value as u16).to_be_bytes(),
            Width::Double => {
                [image[at], image[at + 1], image[at + 2], image[at + 3]] = value.to_be_bytes()
            }
        }
    }

    /// The op that a formal operand or a `DO` stands for; `DO` also consumes the next op.
    #[inline(never)]
    pub(super) fn concrete(&mut self, op: Op) -> Result<(Op, bool), (StopCause, StopDetail)> {
        match op {
            Op::Formal { op: code, param } => match self.formal(code, param) {
                Some(concrete) => Ok((concrete, false)),
                None => {
                    let text = format!("formal parameter {} cannot be substituted here", param + 1);
                    Err((StopCause::Bcf, StopDetail::Text(text)))
                }
            },
            Op::Indirect {
                source: IndirectSource::S7Block(place),
                template: flags,
            } => self.call_from(place, flags).map(|call| (call, false)),
            Op::Indirect { source, template } => {
                let value = match source {
                    IndirectSource::FlagWord(byte) => self.read_image(Width::Word, byte),
                    IndirectSource::DataWord(word) => match self.data_word(word) {
                        Some(value) => u32::from(value),
                        None => return Err(self.data_fault(word)),
                    },
                    IndirectSource::S7Block(_) => unreachable!("matched above"),
                };
                match self.substitute(template, value as u16) {
                    Some(concrete) => Ok((concrete, true)),
                    None => {
                        let text = format!("DO parameter {value} gives no valid operand");
                        Err((StopCause::Bcf, StopDetail::Text(text)))
                    }
                }
            }
            other => Ok((other, false)),
        }
    }

    /// The op an operation on a formal operand amounts to with the running FB's actual.
    fn formal(&self, code: crate::mnemonics::OpCode, param: u8) -> Option<Op> {
        let actual = self.actual(param)?;
        specialise::formal_op(code, actual, self.program.layout)
    }

    /// The op after `DO` with its parameter replaced by `value`: for bit operands the high byte
    /// is the bit and the low byte the byte; otherwise the value is the number.
    fn substitute(&self, template: u16, value: u16) -> Option<Op> {
        let (code, operand) = *self.program.indirect_templates.get(usize::from(template))?;
        let operand = match operand {
            Resolved::Address(address) => {
                let replaced = if address.area.is_bit() {
                    Address {
                        area: address.area,
                        index: value & 0xFF,
                        bit: (value >> 8) as u8,
                    }
                } else {
                    Address {
                        area: address.area,
                        index: value,
                        bit: 0,
                    }
                };
                let fits = crate::address::range::address_in_range(replaced, self.profile);
                fits.then_some(Resolved::Address(replaced))?
            }
            Resolved::Number(_) => Resolved::Number(value & 0xFF),
            _ => return None,
        };
        // Only operations the loop runs directly can be substituted.
        lower::lower(code, operand, self.program.layout, NO_PARAMS)
            .filter(|op| !op.resolved_at_run_time())
            .filter(|op| !matches!(op, Op::Indirect { .. } | Op::Formal { .. }))
    }

    pub fn data_word(&self, word: u16) -> Option<u16> {
        let db = self.data_blocks[usize::from(self.level.open_db?)].as_ref()?;
        db.get(usize::from(word)).copied()
    }

    /// Why data word `word` cannot be reached: no DB open, or past its end.
    pub(super) fn data_fault(&self, word: u16) -> (StopCause, StopDetail) {
        let problem = match self.level.open_db {
            None => format!("DW {word} accessed with no data block open"),
            Some(db) => {
                let length = self.data_blocks[usize::from(db)]
                    .as_ref()
                    .map_or(0, Vec::len);
                format!("DW {word} is past the end of DB {db} ({length} words)")
            }
        };
        (StopCause::LzfData, StopDetail::Text(problem))
    }

    pub(super) fn read_data(
        &self,
        part: DataPart,
        word: u16,
    ) -> Result<u32, (StopCause, StopDetail)> {
        let fault = || self.data_fault(word);
        let value = u32::from(self.data_word(word).ok_or_else(fault)?);
        Ok(match part {
            DataPart::Left => value >> 8,
            DataPart::Right => value & 0xFF,
            DataPart::Word => value,
            DataPart::Double => {
                value << 16 | u32::from(self.data_word(word + 1).ok_or_else(fault)?)
            }
        })
    }

    pub(super) fn write_data(
        &mut self,
        part: DataPart,
        word: u16,
        value: u32,
    ) -> Result<(), (StopCause, StopDetail)> {
        let last = if part == DataPart::Double {
            word + 1
        } else {
            word
        };
        if self.data_word(last).is_none() {
            return Err(self.data_fault(last));
        }
        let db = self.data_blocks[usize::from(self.level.open_db.unwrap_or(0))]
            .as_mut()
            .expect("checked above");
        let slot = &mut db[usize::from(word)];
        match part {
            DataPart::Left => *slot = *slot & 0x00FF | (value as u16 & 0xFF) << 8,
            DataPart::Right => *slot = *slot & 0xFF00 | value as u16 & 0xFF,
            DataPart::Word => *slot = value as u16,
            DataPart::Double => {
                *slot = (value >> 16) as u16;
                db[usize::from(word) + 1] = value as u16;
            }
        }
        Ok(())
    }

    pub(super) fn data_bit(&self, word: u16, bit: u8) -> Result<bool, (StopCause, StopDetail)> {
        Ok(self.read_data(DataPart::Word, word)? >> bit & 1 != 0)
    }

    pub(super) fn write_data_bit(
        &mut self,
        word: u16,
        bit: u8,
        value: bool,
    ) -> Result<(), (StopCause, StopDetail)> {
        let old = self.read_data(DataPart::Word, word)?;
        let mask = 1u32 << bit;
        let new = if value { old | mask } else { old & !mask };
        self.write_data(DataPart::Word, word, new)
    }

    fn bit_target(&self, target: BitTarget) -> Result<bool, (StopCause, StopDetail)> {
        match target {
            BitTarget::Image(bit) => Ok(self.image_bit(bit)),
            BitTarget::Data { word, bit } => self.data_bit(word, bit),
        }
    }

    fn write_bit_target(
        &mut self,
        target: BitTarget,
        value: bool,
    ) -> Result<(), (StopCause, StopDetail)> {
        match target {
            BitTarget::Image(bit) => {
                self.write_image_bit(bit, value);
                Ok(())
            }
            BitTarget::Data { word, bit } => self.write_data_bit(word, bit, value),
        }
    }

    /// The S5-95F interrupt images, when the running level is OB 13.
    fn interrupt_images(&mut self) -> Option<&mut S595f> {
        match &mut self.engine.rules {
            FamilyRules::S595f(rules) if self.level.interrupt_images => Some(rules),
            _ => None,
        }
    }

    /// The periphery a load reaches: in the S5-95F's OB 13, the interrupt PII.
    pub(super) fn read_periphery(&mut self, width: Width, byte: u16, extended: bool) -> u32 {
        let (at, count) = (usize::from(byte), width.bytes());
        if extended {
            return read_bytes(&self.extended_inputs, at, count);
        }
        let pii = usize::from(self.program.layout.input_base());
        if self.inputs_echo_pii && at + count <= usize::from(self.program.layout.image_bytes) {
            return read_bytes(&self.image[..], pii + at, count);
        }
        match self.interrupt_images() {
            Some(images) => images.read_interrupt_pii(at, count),
            None => read_bytes(&self.inputs, at, count),
        }
    }

    /// The periphery a transfer reaches: the output module, or in the S5-95F's OB 13 the
    /// interrupt PIQ; the normal PIQ follows a direct output to a digital module.
    pub(super) fn write_periphery(&mut self, width: Width, byte: u16, value: u32, extended: bool) {
        let (at, count) = (usize::from(byte), width.bytes());
        let before = self.modules_before(Modules::Outputs, extended, at, count);
        if extended {
            write_bytes(&mut self.extended_outputs, at, count, value);
        } else {
            match self.interrupt_images() {
                Some(images) => images.write_interrupt_piq(at, count, value),
                None => write_bytes(&mut self.outputs, at, count, value),
            }
        }
        if let Some(before) = before {
            self.trace_module_changes(Modules::Outputs, extended, at, &before);
        }
        if extended {
            return;
        }
        let image_bytes = usize::from(self.program.layout.image_bytes);
        let piq = usize::from(self.program.layout.output_base());
        if at + count <= image_bytes {
            write_bytes(&mut self.image[..], piq + at, count, value);
        }
    }

    /// The operations the loop does not handle inline.
    #[inline(never)]
    pub(super) fn execute_other(&mut self, op: Op, pc: u32) -> Result<(), (StopCause, StopDetail)> {
        let now = self.clock;
        let rlo = self.level.status.rlo();
        match op {
            Op::AndBracket | Op::OrBracket => {
                if !self.level.brackets.open(
                    &mut self.level.status,
                    op == Op::OrBracket,
                    self.profile.bracket_depth,
                ) {
                    return Err((
                        StopCause::Bcf,
                        StopDetail::Text(format!(
                            "more than {} nested brackets",
                            self.profile.bracket_depth
                        )),
                    ));
                }
            }
            Op::CloseBracket => {
                if !self.level.brackets.close(&mut self.level.status) {
                    return Err((
                        StopCause::Bcf,
                        StopDetail::Text("`)` without an open bracket".into()),
                    ));
                }
            }
            Op::LogicOther(logic, source) => {
                let value = match source {
                    BitSource::Data { word, bit } => self.data_bit(word, bit)?,
                    BitSource::Timer(n) => self.timers[usize::from(n)].bit(now),
                    BitSource::Counter(n) => self.counters[usize::from(n)].bit(),
                };
                self.level.status.scanned(logic, value);
            }
            Op::WriteData { write, word, bit } => {
                match write {
                    Write::Assign => self.write_data_bit(word, bit, rlo)?,
                    Write::Set if rlo => self.write_data_bit(word, bit, true)?,
                    Write::Reset if rlo => self.write_data_bit(word, bit, false)?,
                    _ => {}
                }
                self.level.status.end_string();
            }
            Op::LoadData(part, word) => {
                let value = self.read_data(part, word)?;
                self.load(value);
            }
            Op::TransferData(part, word) => self.write_data(part, word, self.level.accu1)?,
            Op::LoadPeripheral {
                width,
                byte,
                extended,
            } => {
                let value = self.read_periphery(width, byte, extended);
                self.load(value);
            }
            Op::TransferPeripheral {
                width,
                byte,
                extended,
            } => self.write_periphery(width, byte, self.level.accu1, extended),
            Op::LoadTimer(n) => {
                let timer = &mut self.timers[usize::from(n)];
                timer.settle(now);
                let value = u32::from(timer.value(now));
                self.load(value);
            }
            Op::LoadTimerCoded(n) => {
                let value = self.timers[usize::from(n)].coded(now);
                self.load(value);
            }
            Op::LoadCounter(n) => {
                let value = u32::from(self.counters[usize::from(n)].value);
                self.load(value);
            }
            Op::LoadCounterCoded(n) => {
                let value = self.counters[usize::from(n)].coded();
                self.load(value);
            }
            Op::StartTimer(kind, n) => {
                self.timers[usize::from(n)].start_op(kind, rlo, self.level.accu1, now);
                self.level.status.end_string();
            }
            Op::EnableTimer(n) => {
                self.timers[usize::from(n)].enable(rlo);
                self.level.status.end_string();
            }
            Op::ResetTimer(n) => {
                self.timers[usize::from(n)].reset(rlo);
                self.level.status.end_string();
            }
            Op::CountUp(n) => {
                self.counters[usize::from(n)].up(rlo);
                self.level.status.end_string();
            }
            Op::CountDown(n) => {
                self.counters[usize::from(n)].down(rlo);
                self.level.status.end_string();
            }
            Op::SetCounter(n) => {
                self.counters[usize::from(n)].set(rlo, self.level.accu1);
                self.level.status.end_string();
            }
            Op::ResetCounter(n) => {
                self.counters[usize::from(n)].reset(rlo);
                self.level.status.end_string();
            }
            Op::EnableCounter(n) => {
                self.counters[usize::from(n)].enable(rlo);
                self.level.status.end_string();
            }
            Op::CallMissing {
                kind,
                number,
                conditional,
            } => {
                if !conditional || rlo {
                    return Err((
                        StopCause::LzfBlock,
                        StopDetail::Text(format!("{} {number}", kind.name())),
                    ));
                }
                self.level.status.after_jump();
            }
            Op::Builtin {
                block,
                conditional,
                params,
            } => {
                if !conditional || rlo {
                    self.run_builtin(block, params)?;
                }
                self.level.status.after_jump();
            }
            Op::OpenDb(number) => {
                if self.data_blocks[usize::from(number)].is_none() {
                    return Err((
                        StopCause::LzfBlock,
                        StopDetail::Text(format!("DB {number}")),
                    ));
                }
                self.level.open_db = Some(number);
            }
            Op::GenerateDb(number) => {
                let words = self.level.accu1 as u16;
                if words > self.profile.sizes.data_words {
                    let text = format!(
                        "G DB {number} with {words} words: the CPU allows {}",
                        self.profile.sizes.data_words
                    );
                    return Err((StopCause::LzfData, StopDetail::Text(text)));
                }
                let slot = &mut self.data_blocks[usize::from(number)];
                if slot.is_none() {
                    *slot = Some(vec![0; usize::from(words)]);
                }
            }
            Op::Nop => {}
            Op::Stop => {
                self.stop_requested.get_or_insert((self.level.block, pc));
            }
            Op::WordLogic(kind) => arith::word_logic(
                kind,
                &mut self.level.accu1,
                self.level.accu2,
                &mut self.level.status,
            ),
            Op::ShiftLeft(n) => {
                arith::shift(true, n, &mut self.level.accu1, &mut self.level.status)
            }
            Op::ShiftRight(n) => {
                arith::shift(false, n, &mut self.level.accu1, &mut self.level.status)
            }
            Op::OnesComplement => arith::ones_complement(&mut self.level.accu1),
            Op::TwosComplement => {
                arith::twos_complement(&mut self.level.accu1, &mut self.level.status)
            }
            Op::Swap => std::mem::swap(&mut self.level.accu1, &mut self.level.accu2),
            Op::Enter => {
                self.level.accu4 = self.level.accu3;
                self.level.accu3 = self.level.accu2;
            }
            Op::FloatArithmetic { kind, stack } => {
                float::arithmetic(
                    kind,
                    &mut self.level.accu1,
                    self.level.accu2,
                    &mut self.level.status,
                );
                if stack {
                    self.level.accu2 = self.level.accu3;
                    self.level.accu3 = self.level.accu4;
                }
            }
            Op::FloatCompare(kind) => float::compare(
                kind,
                self.level.accu1,
                self.level.accu2,
                &mut self.level.status,
            ),
            Op::Convert(conversion) => {
                float::convert(conversion, &mut self.level.accu1, &mut self.level.status)
            }
            Op::Increment(n) => arith::increment(&mut self.level.accu1, i16::from(n)),
            Op::Decrement(n) => arith::increment(&mut self.level.accu1, -i16::from(n)),
            Op::SetUnconditional(target) => self.write_bit_target(target, true)?,
            Op::ResetUnconditional(target) => self.write_bit_target(target, false)?,
            Op::TestBit { negate, target } => {
                let value = self.bit_target(target)?;
                self.level.status.load(value != negate);
            }
            Op::AddConstant { value, double } => {
                system_ops::add_constant(&mut self.level.accu1, value, double)
            }
            Op::NotSimulated { op, operand } => return Err(system_ops::not_simulated(op, operand)),
            Op::S7(code) => {
                self.execute_s7(code, pc)?;
            }
            Op::S7Scan(combination, bit) => {
                let value = self.image_bit(bit);
                self.level.status.scanned_step7(combination, value);
            }
            Op::S7Write(write, bit) => {
                match write {
                    Write::Assign => self.write_image_bit(bit, rlo),
                    Write::Set if rlo => self.write_image_bit(bit, true),
                    Write::Reset if rlo => self.write_image_bit(bit, false),
                    _ => {}
                }
                super::s7::bit_logic::assigned(&mut self.level.status, rlo);
            }
            Op::Interrupts { enabled } => {
                self.level.interrupts_enabled = enabled;
                if enabled {
                    self.update_attention();
                }
            }
            image_bit_ops!(_)
            | Op::OrAlone
            | Op::LoadImageByte(_)
            | Op::LoadImageWord(_)
            | Op::LoadImageDouble(_)
            | Op::TransferImageByte(_)
            | Op::TransferImageWord(_)
            | Op::TransferImageDouble(_)
            | Op::LoadConstant(_)
            | Op::Arithmetic(_)
            | Op::ArithmeticStack(_)
            | Op::Compare(_)
            | Op::Jump(..)
            | Op::Call { .. }
            | Op::CallAt { .. }
            | Op::BlockEnd
            | Op::BlockEndConditional
            | Op::BlockEndUnconditional
            | Op::Indirect { .. }
            | Op::Formal { .. }
            | Op::End
            | Op::Native(_)
            | fused_pairs!() => {
                unreachable!("{op:?} is executed by the loop itself")
            }
        }
        Ok(())
    }
}
