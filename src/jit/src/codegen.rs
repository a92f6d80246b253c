//! One stretch as Cranelift IR: the registers are loaded once, every step works on SSA values,
//! and the registers a step changed are stored once at the end.

use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{Function, InstBuilder, MemFlagsData, Type, Value, types};
use cranelift_codegen::isa::TargetFrontendConfig;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext, Variable};

use super::{BitAction, Comparison, LoopBack, Memory, Registers, Spot, StatusBits, Step, Width};

/// Memory and register accesses: never trapping (offsets checked when compiling and before a
/// run), unaligned.
const MEMORY: MemFlagsData = MemFlagsData::new().with_notrap();

/// The byte offsets of the registers in [`Registers`].
const ACCU1: i32 = std::mem::offset_of!(Registers, accu1) as i32;
const ACCU2: i32 = std::mem::offset_of!(Registers, accu2) as i32;
const ACCU3: i32 = std::mem::offset_of!(Registers, accu3) as i32;
const ACCU4: i32 = std::mem::offset_of!(Registers, accu4) as i32;
const STATUS: i32 = std::mem::offset_of!(Registers, status) as i32;
const OFFSETS: [i32; 5] = [ACCU1, ACCU2, ACCU3, ACCU4, STATUS];

/// The registers as variables while the stretch is built, and which ones it changes.
struct State {
    variables: [Variable; 5],
    changed: [bool; 5],
}

const A1: usize = 0;
const A2: usize = 1;
const A3: usize = 2;
const A4: usize = 3;
const ST: usize = 4;

/// The function's result when the loop's jump was not taken (the passes in the low bits).
pub const NOT_TAKEN: u32 = 1 << 31;

pub fn build(
    function: &mut Function,
    context: &mut FunctionBuilderContext,
    config: TargetFrontendConfig,
    bits: StatusBits,
    steps: &[Step],
    loop_back: Option<LoopBack>,
) {
    let pointer = config.pointer_type();
    let mut b = FunctionBuilder::new(function, context);
    let entry = b.create_block();
    let body = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let [registers, image, data, most] = b.block_params(entry) else {
        unreachable!("the signature has four parameters");
    };
    let (registers, image, data, most) = (*registers, *image, *data, *most);
    let variables = OFFSETS.map(|offset| {
        let variable = b.declare_var(types::I32);
        let value = b.ins().load(types::I32, MEMORY, registers, offset);
        b.def_var(variable, value);
        variable
    });
    let passes = b.declare_var(types::I32);
    let zero = b.ins().iconst(types::I32, 0);
    b.def_var(passes, zero);
    b.ins().jump(body, &[]);
    b.switch_to_block(body);
    let mut state = State {
        variables,
        changed: [false; 5],
    };
    let mut emitter = Emitter {
        b: &mut b,
        pointer,
        image,
        data,
        bits,
        state: &mut state,
    };
    for step in steps {
        emitter.step(*step);
    }
    let Some(loop_back) = loop_back else {
        emitter.leave(registers, zero);
        finish(b, config);
        return;
    };
    // A pass is the body and the jump back; `most` passes at most, and none (the body alone)
    // when `most` is 0.
    let jump = emitter.b.create_block();
    let body_alone = emitter.b.create_block();
    emitter.b.ins().brif(most, jump, &[], body_alone, &[]);
    emitter.b.switch_to_block(body_alone);
    emitter.leave(registers, zero);
    emitter.b.switch_to_block(jump);
    let status = emitter.get(ST);
    let taken = emitter.lookup(loop_back.taken.as_ptr(), status);
    let after = emitter.lookup(loop_back.after.as_ptr(), status);
    emitter.set(ST, after);
    let not_taken = emitter.b.create_block();
    let again = emitter.b.create_block();
    emitter.b.ins().brif(taken, again, &[], not_taken, &[]);
    emitter.b.switch_to_block(not_taken);
    let done = emitter.b.use_var(passes);
    let result = emitter.b.ins().bor_imm_u(done, i64::from(NOT_TAKEN));
    emitter.leave(registers, result);
    emitter.b.switch_to_block(again);
    let done = emitter.b.use_var(passes);
    let done = emitter.b.ins().iadd_imm_u(done, 1);
    emitter.b.def_var(passes, done);
    let all_done = emitter.b.create_block();
    let finished = emitter.b.ins().icmp(IntCC::Equal, done, most);
    emitter.b.ins().brif(finished, all_done, &[], body, &[]);
    emitter.b.switch_to_block(all_done);
    emitter.leave(registers, done);
    finish(b, config);
}

fn finish(mut b: FunctionBuilder, config: TargetFrontendConfig) {
    b.seal_all_blocks();
    b.finalize(config);
}

struct Emitter<'a, 'b> {
    b: &'a mut FunctionBuilder<'b>,
    pointer: Type,
    image: Value,
    data: Value,
    bits: StatusBits,
    state: &'a mut State,
}

impl Emitter<'_, '_> {
    fn get(&mut self, register: usize) -> Value {
        self.b.use_var(self.state.variables[register])
    }

    fn set(&mut self, register: usize, value: Value) {
        self.b.def_var(self.state.variables[register], value);
        self.state.changed[register] = true;
    }

    /// Stores the registers the stretch changes and returns `result`.
    fn leave(&mut self, registers: Value, result: Value) {
        for (register, offset) in OFFSETS.iter().enumerate() {
            if self.state.changed[register] {
                let value = self.get(register);
                self.b.ins().store(MEMORY, value, registers, *offset);
            }
        }
        self.b.ins().return_(&[result]);
    }

    fn step(&mut self, step: Step) {
        match step {
            Step::Scan {
                memory,
                byte,
                bit,
                table,
            } => {
                let signal = self.bit(Spot { memory, byte, bit });
                let status = self.get(ST);
                let shifted = self.b.ins().ishl_imm_u(status, 1);
                let index = self.b.ins().bor(shifted, signal);
                let next = self.lookup(table.as_ptr(), index);
                self.set(ST, next);
            }
            Step::Write {
                memory,
                byte,
                bit,
                rlo_0,
                rlo_1,
                after,
            } => {
                let status = self.get(ST);
                let base = self.base(memory);
                let old = self
                    .b
                    .ins()
                    .uload8(types::I32, MEMORY, base, i32::from(byte));
                let when_0 = self.apply(rlo_0, old, bit);
                let when_1 = self.apply(rlo_1, old, bit);
                let rlo = self.b.ins().band_imm_u(status, i64::from(self.bits.rlo));
                let new = self.b.ins().select(rlo, when_1, when_0);
                self.b.ins().istore8(MEMORY, new, base, i32::from(byte));
                let next = self.lookup(after.as_ptr(), status);
                self.set(ST, next);
            }
            Step::Status(table) => {
                let status_now = self.get(ST);
                let next = self.lookup(table.as_ptr(), status_now);
                self.set(ST, next);
            }
            Step::Load {
                memory,
                width,
                byte,
            } => {
                let value = self.load(memory, width, byte);
                let moved = self.get(A1);
                self.set(A2, moved);
                self.set(A1, value);
            }
            Step::LoadConstant(constant) => {
                let value = self.b.ins().iconst(types::I32, i64::from(constant));
                let moved = self.get(A1);
                self.set(A2, moved);
                self.set(A1, value);
            }
            Step::Transfer {
                memory,
                width,
                byte,
            } => {
                let accu1 = self.get(A1);
                self.store(memory, width, byte, accu1);
            }
            Step::Copy {
                width: None,
                from,
                to,
            } => {
                let signal = self.bit(from);
                self.put_bit(to, signal);
            }
            Step::Copy {
                width: Some(width),
                from,
                to,
            } => {
                // Bytes as they are: big-endian on both sides.
                let kind = match width {
                    Width::Byte => types::I8,
                    Width::Word => types::I16,
                    Width::Double => types::I32,
                };
                let (from_base, to_base) = (self.base(from.memory), self.base(to.memory));
                let value = self
                    .b
                    .ins()
                    .load(kind, MEMORY, from_base, i32::from(from.byte));
                self.b
                    .ins()
                    .store(MEMORY, value, to_base, i32::from(to.byte));
            }
            Step::Put { width, to, value } => {
                let constant = self.b.ins().iconst(types::I32, i64::from(value));
                match width {
                    None => {
                        let signal = self.b.ins().band_imm_u(constant, 1);
                        self.put_bit(to, signal);
                    }
                    Some(width) => self.store(to.memory, width, to.byte, constant),
                }
            }
            Step::AddSub { subtract, stack } => self.add_sub(subtract, stack),
            Step::Compare(comparison) => self.compare(comparison),
            Step::Nop => {}
        }
    }

    fn base(&self, memory: Memory) -> Value {
        match memory {
            Memory::Image => self.image,
            Memory::Data => self.data,
        }
    }

    /// The signal state of a bit, 0 or 1.
    fn bit(&mut self, spot: Spot) -> Value {
        let base = self.base(spot.memory);
        let value = self
            .b
            .ins()
            .uload8(types::I32, MEMORY, base, i32::from(spot.byte));
        let shifted = self.b.ins().ushr_imm_u(value, i64::from(spot.bit));
        self.b.ins().band_imm_u(shifted, 1)
    }

    /// Writes `signal` (0 or 1) to the bit at `spot`.
    fn put_bit(&mut self, spot: Spot, signal: Value) {
        let base = self.base(spot.memory);
        let at = i32::from(spot.byte);
        let old = self.b.ins().uload8(types::I32, MEMORY, base, at);
        let cleared = self.b.ins().band_imm_u(old, i64::from(!(1u8 << spot.bit)));
        let moved = self.b.ins().ishl_imm_u(signal, i64::from(spot.bit));
        let new = self.b.ins().bor(cleared, moved);
        self.b.ins().istore8(MEMORY, new, base, at);
    }

    fn apply(&mut self, action: BitAction, byte: Value, bit: u8) -> Value {
        match action {
            BitAction::Keep => byte,
            BitAction::Clear => self.b.ins().band_imm_u(byte, i64::from(!(1u8 << bit))),
            BitAction::Set => self.b.ins().bor_imm_u(byte, 1i64 << bit),
        }
    }

    /// `table[index]`, the table at a fixed address.
    fn lookup(&mut self, table: *const u8, index: Value) -> Value {
        let base = self.b.ins().iconst(self.pointer, table as i64);
        let wide = self.b.ins().uextend(self.pointer, index);
        let address = self.b.ins().iadd(base, wide);
        self.b.ins().uload8(types::I32, MEMORY, address, 0)
    }

    fn load(&mut self, memory: Memory, width: Width, byte: u16) -> Value {
        let (base, at) = (self.base(memory), i32::from(byte));
        match width {
            Width::Byte => self.b.ins().uload8(types::I32, MEMORY, base, at),
            Width::Word => {
                let raw = self.b.ins().load(types::I16, MEMORY, base, at);
                let swapped = self.b.ins().bswap(raw);
                self.b.ins().uextend(types::I32, swapped)
            }
            Width::Double => {
                let raw = self.b.ins().load(types::I32, MEMORY, base, at);
                self.b.ins().bswap(raw)
            }
        }
    }

    fn store(&mut self, memory: Memory, width: Width, byte: u16, value: Value) {
        let (base, at) = (self.base(memory), i32::from(byte));
        match width {
            Width::Byte => {
                self.b.ins().istore8(MEMORY, value, base, at);
            }
            Width::Word => {
                let low = self.b.ins().ireduce(types::I16, value);
                let swapped = self.b.ins().bswap(low);
                self.b.ins().store(MEMORY, swapped, base, at);
            }
            Width::Double => {
                let swapped = self.b.ins().bswap(value);
                self.b.ins().store(MEMORY, swapped, base, at);
            }
        }
    }

    /// A register's low word as a signed 32-bit value.
    fn low_signed(&mut self, value: Value) -> Value {
        let low = self.b.ins().ireduce(types::I16, value);
        self.b.ins().sextend(types::I32, low)
    }

    /// `mask` where `condition` (an `icmp` result) holds, else 0.
    fn flag(&mut self, condition: Value, mask: u8) -> Value {
        let one = self.b.ins().uextend(types::I32, condition);
        self.b.ins().imul_imm_u(one, i64::from(mask))
    }

    fn add_sub(&mut self, subtract: bool, stack: bool) {
        let accu2_now = self.get(A2);
        let a = self.low_signed(accu2_now);
        let accu1_now = self.get(A1);
        let b = self.low_signed(accu1_now);
        let exact = if subtract {
            self.b.ins().isub(a, b)
        } else {
            self.b.ins().iadd(a, b)
        };
        let wrapped = self.low_signed(exact);
        let overflow = self.b.ins().icmp(IntCC::NotEqual, wrapped, exact);
        let positive = self
            .b
            .ins()
            .icmp_imm_s(IntCC::SignedGreaterThan, wrapped, 0);
        let negative = self.b.ins().icmp_imm_s(IntCC::SignedLessThan, wrapped, 0);
        let bits = self.bits;
        let kept = !(bits.cc1 | bits.cc0 | bits.ov);
        let status_now = self.get(ST);
        let status = self.b.ins().band_imm_u(status_now, i64::from(kept));
        let cc1 = self.flag(positive, bits.cc1);
        let cc0 = self.flag(negative, bits.cc0);
        let flow = self.flag(overflow, bits.ov | bits.os);
        let codes = self.b.ins().bor(cc1, cc0);
        let codes = self.b.ins().bor(codes, flow);
        let status = self.b.ins().bor(status, codes);
        self.set(ST, status);
        let accu1_now = self.get(A1);
        let high = self.b.ins().band_imm_u(accu1_now, 0xFFFF_0000);
        let low = self.b.ins().band_imm_u(exact, 0xFFFF);
        let accu1 = self.b.ins().bor(high, low);
        self.set(A1, accu1);
        if stack {
            let moved = self.get(A3);
            self.set(A2, moved);
            let moved = self.get(A4);
            self.set(A3, moved);
        }
    }

    fn compare(&mut self, comparison: Comparison) {
        let accu2_now = self.get(A2);
        let a = self.low_signed(accu2_now);
        let accu1_now = self.get(A1);
        let b = self.low_signed(accu1_now);
        let condition = match comparison {
            Comparison::Equal => IntCC::Equal,
            Comparison::NotEqual => IntCC::NotEqual,
            Comparison::Greater => IntCC::SignedGreaterThan,
            Comparison::GreaterOrEqual => IntCC::SignedGreaterThanOrEqual,
            Comparison::Less => IntCC::SignedLessThan,
            Comparison::LessOrEqual => IntCC::SignedLessThanOrEqual,
        };
        let holds = self.b.ins().icmp(condition, a, b);
        let greater = self.b.ins().icmp(IntCC::SignedGreaterThan, a, b);
        let less = self.b.ins().icmp(IntCC::SignedLessThan, a, b);
        let bits = self.bits;
        let kept = !(bits.rlo | bits.or | bits.cc1 | bits.cc0);
        let status_now = self.get(ST);
        let status = self.b.ins().band_imm_u(status_now, i64::from(kept));
        let status = self.b.ins().bor_imm_u(status, i64::from(bits.first_check));
        let rlo = self.flag(holds, bits.rlo);
        let cc1 = self.flag(greater, bits.cc1);
        let cc0 = self.flag(less, bits.cc0);
        let status = self.b.ins().bor(status, rlo);
        let status = self.b.ins().bor(status, cc1);
        let status = self.b.ins().bor(status, cc0);
        self.set(ST, status);
    }
}
