//! Runs the STEP 7 operations the loop does not run inline.

use crate::compiler::bytecode::{Op, TimerKind};
use crate::step7::ast::{AccessWidth, Cmp, DbRegister, Extension};
use crate::step7::bytecode::{
    AWLSIM_SFC_CLOCK_RESET, AWLSIM_SFC_NOP, AWLSIM_SFC_REBOOT, AWLSIM_SFC_SHUTDOWN, BLKMOV, FILL,
    McrCode, MemOp, READ_CLK, S7Code, SET_CLK, TIME_TCK, Target, WAIT,
};
use crate::vm::Cpu;
use crate::vm::interrupts::control::{DIS_IRT, EN_AIRT};
use crate::vm::stop::{StopCause, StopDetail};

use super::bit_logic;
use super::bridge;
use super::mcr::StackFault;
use super::memory::{Fault, Located};

/// What the loop does after an S7 operation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    Next,
    /// Go on at op `target` of the running block.
    Jump(u32),
}

pub(super) fn fault(text: impl Into<String>) -> Fault {
    (StopCause::Bcf, StopDetail::Text(text.into()))
}

/// The STOP for a data block the program does not have.
#[cold]
fn missing_db(number: u16) -> Fault {
    (
        StopCause::LzfBlock,
        StopDetail::Text(format!("DB {number}")),
    )
}

impl Cpu {
    /// Runs `code`, op `pc` of the running block; ACCU 1/2 and the status are in `self.level`.
    #[inline(never)]
    pub(crate) fn execute_s7(&mut self, code: S7Code, pc: u32) -> Result<Flow, Fault> {
        match code {
            S7Code::Mem { op, place } => self.memory_op(op, place, pc)?,
            S7Code::Accu(op) => {
                bridge::accumulator(&mut self.level, op, self.profile.accumulators)?
            }
            S7Code::Shift { op, count } => bridge::shift(&mut self.level, op, count),
            S7Code::WordConstant { op, constant } => {
                let value = self.program.s7.constants[usize::from(constant)];
                bridge::word_logic(&mut self.level, op, value);
            }
            S7Code::AddDouble { constant } => {
                let value = self.program.s7.constants[usize::from(constant)];
                self.level.accu1 = self.level.accu1.wrapping_add(value);
            }
            S7Code::Jump { jump, target } => {
                if bridge::jump_taken(&mut self.level, jump) {
                    return Ok(Flow::Jump(u32::from(target)));
                }
            }
            S7Code::Loop { target } => {
                if bridge::loop_taken(&mut self.level.accu1) {
                    return Ok(Flow::Jump(u32::from(target)));
                }
            }
            S7Code::JumpList { entries, target } => {
                let index = self.level.accu1 & 0xFF;
                return Ok(Flow::Jump(if index < u32::from(entries) {
                    pc + 1 + index
                } else {
                    u32::from(target)
                }));
            }
            S7Code::Bracket(combination) => {
                let depth = self.profile.bracket_depth;
                if !bridge::open_bracket(&mut self.level, combination, depth) {
                    return Err(fault(format!("more than {depth} nested brackets")));
                }
            }
            S7Code::CloseBracket => {
                if !bridge::close_bracket(&mut self.level) {
                    return Err(fault("`)` without an open bracket"));
                }
            }
            S7Code::Condition {
                combination,
                condition,
            } => {
                let value = bridge::condition(&self.level, condition);
                bridge::combine(&mut self.level.status, combination, value);
            }
            S7Code::OpenDb { instance, slot } => self.open_s7_db(instance, slot)?,
            S7Code::OpenDbFrom { instance, place } => {
                let (located, _) = self.locate_index(place)?;
                let number = self.fetch(located, AccessWidth::Word)? as u16;
                let Some(slot) = self.program.s7.db_slot(number) else {
                    return Err(missing_db(number));
                };
                self.open_s7_db(instance, slot)?;
            }
            S7Code::ExchangeDbRegisters => {
                std::mem::swap(&mut self.level.db, &mut self.level.di);
            }
            S7Code::LoadDbRegister(register) => {
                let value = self.db_register(register);
                self.load_s7(value);
            }
            S7Code::LoadAr(ar) => self.set_ar(ar, self.level.accu1),
            S7Code::LoadArConstant { ar, constant } => {
                let value = self.program.s7.constants[usize::from(constant)];
                self.set_ar(ar, value);
            }
            S7Code::LoadAr1FromAr2 => self.level.ar1 = self.level.ar2,
            S7Code::TransferAr(ar) => {
                // Statement List manual, TAR1/TAR2: ACCU 1 is saved into ACCU 2 first.
                let value = if ar == 1 {
                    self.level.ar1
                } else {
                    self.level.ar2
                };
                self.load_s7(value);
            }
            S7Code::TransferAr1ToAr2 => self.level.ar2 = self.level.ar1,
            S7Code::SwapAr => std::mem::swap(&mut self.level.ar1, &mut self.level.ar2),
            S7Code::AddAr { ar, constant } => {
                let offset = match constant {
                    Some(index) => self.program.s7.constants[usize::from(index)],
                    // ACCU 1-L as a signed bit offset.
                    None => self.level.accu1 as u16 as i16 as i32 as u32,
                };
                let register = if ar == 1 {
                    &mut self.level.ar1
                } else {
                    &mut self.level.ar2
                };
                let address = (*register & 0x00FF_FFFF).wrapping_add(offset) & 0x00FF_FFFF;
                *register = *register & 0xFF00_0000 | address;
            }
            S7Code::FcEnter { call } => self.fc_enter(call)?,
            S7Code::FcLeave { call } => self.fc_leave(call)?,
            S7Code::LoadParamPointer { param } => {
                let pointer = self.param_pointer(param)?;
                self.load_s7(pointer);
            }
            S7Code::FbEnter { call } => self.fb_enter(call)?,
            S7Code::FbLeave { call } => self.fb_leave(call)?,
            S7Code::Sfc { call } => self.system_function(call)?,
            S7Code::Library { call } => self.library_fc(call)?,
            S7Code::Assert { cmp, left } => self.assert(cmp, left)?,
            S7Code::Mcr(code) => self.mcr(code)?,
            S7Code::ResetStatusWord => bridge::reset_status_word(&mut self.level),
            S7Code::Sleep { ms } => self.clock += u64::from(ms) * 1_000_000,
            S7Code::Feature { target, value } => {
                let current = match (target, value) {
                    (0, Some(accus)) if accus == self.profile.accumulators => u32::from(accus),
                    (0, Some(accus)) => {
                        return Err(fault(format!(
                            "this CPU has {} accumulators, not {accus}",
                            self.profile.accumulators
                        )));
                    }
                    (0, None) => u32::from(self.profile.accumulators),
                    // awlsim's switch for writing the OBs' start information: awl writes it
                    // unless the run switched it off (an awlsim project file's
                    // `ob_startinfo_enable`), and the program cannot switch it.
                    (1, None) => u32::from(self.writes_start_info),
                    (1, Some(value)) if (value != 0) == self.writes_start_info => u32::from(value),
                    (1, Some(_)) => {
                        return Err(fault(
                            "`__FEATURE 1` cannot switch the OBs' start information: awl \
                             writes it unless the awlsim project file switches it off"
                                .to_string(),
                        ));
                    }
                    (_, Some(value)) => u32::from(value),
                    (_, None) => 0,
                };
                self.level.accu1 = current;
            }
        }
        Ok(Flow::Next)
    }

    /// `MCRA`, `MCRD`, `MCR(`, `)MCR` and a block with `MCRA` around its calls.
    fn mcr(&mut self, code: McrCode) -> Result<(), Fault> {
        let mcr = &mut self.level.mcr;
        match code {
            McrCode::Activate(on) => mcr.active = on,
            McrCode::Call(true) => mcr.call(),
            McrCode::Call(false) => mcr.called(),
            McrCode::Open | McrCode::Close => {
                let changed = if code == McrCode::Open {
                    mcr.open(self.level.status.rlo())
                } else {
                    mcr.close()
                };
                changed.map_err(|stack| {
                    fault(match stack {
                        StackFault::Overflow => {
                            "MCR stack fault (MCRF): a ninth nested MCR(, \
                                                 the MCR stack holds 8 entries"
                        }
                        StackFault::Underflow => "MCR stack fault (MCRF): )MCR with no MCR( open",
                    })
                })?;
                // Both end the logic string and set STA (STL manual, status of MCR( and )MCR).
                let status = &mut self.level.status;
                status.set_or_bit(false);
                status.set_sta(true);
                status.set_first_check(false);
            }
        }
        Ok(())
    }

    fn load_s7(&mut self, value: u32) {
        self.level.accu2 = self.level.accu1;
        self.level.accu1 = value;
    }

    fn set_ar(&mut self, ar: u8, value: u32) {
        if ar == 1 {
            self.level.ar1 = value;
        } else {
            self.level.ar2 = value;
        }
    }

    /// Opens the data block in `slot` (0: none) as the DB or the instance DB.
    fn open_s7_db(&mut self, instance: bool, slot: u16) -> Result<(), Fault> {
        if slot != 0 && !matches!(self.s7_data.get(usize::from(slot)), Some(Some(_))) {
            return Err(missing_db(self.program.s7.db_number(slot)));
        }
        if instance {
            self.level.di = slot;
        } else {
            self.level.db = slot;
        }
        Ok(())
    }

    fn db_register(&self, register: DbRegister) -> u32 {
        let length = |slot: u16| {
            self.s7_data
                .get(usize::from(slot))
                .and_then(Option::as_ref)
                .map_or(0, |bytes| bytes.len() as u32)
        };
        let number = |slot: u16| u32::from(self.program.s7.db_number(slot));
        match register {
            DbRegister::DbNumber => number(self.level.db),
            DbRegister::DbLength => length(self.level.db),
            DbRegister::DiNumber => number(self.level.di),
            DbRegister::DiLength => length(self.level.di),
        }
    }

    /// An area-crossing pointer with area P (code 0) names the peripheral inputs when read
    /// and the peripheral outputs when written (Statement List manual, area-crossing
    /// register-indirect addressing).
    fn written_peripheral(&self, located: Located, place: u16) -> Located {
        match located {
            Located::Peripheral {
                output: false,
                byte,
            } if matches!(
                self.program.s7.places[usize::from(place)].target,
                Target::RegisterIndirect { area: None, .. }
            ) =>
            {
                Located::Peripheral { output: true, byte }
            }
            other => other,
        }
    }

    fn memory_op(&mut self, op: MemOp, place: u16, pc: u32) -> Result<(), Fault> {
        let (located, width) = self.locate_index(place)?;
        let rlo = self.level.status.rlo();
        match op {
            MemOp::Scan(combination) => {
                let value = match located {
                    Located::Special(_) => self.special_value(located)? & 1 != 0,
                    other => self.fetch_bit(other)?,
                };
                bridge::combine(&mut self.level.status, combination, value);
            }
            MemOp::Assign => {
                self.store_bit(located, rlo)?;
                bridge::after_assignment(&mut self.level.status);
            }
            MemOp::Set | MemOp::Reset => {
                match located {
                    Located::Timer(_) | Located::Counter(_) if op == MemOp::Reset => {
                        return self.timer_counter_op(located, MemOp::ResetTimerCounter, pc);
                    }
                    Located::Counter(_) => {
                        return self.timer_counter_op(located, MemOp::SetCounter, pc);
                    }
                    _ => {}
                }
                if rlo {
                    self.store_bit(located, op == MemOp::Set)?;
                }
                bridge::after_assignment(&mut self.level.status);
            }
            MemOp::McrAssign => {
                let written = rlo && self.level.mcr.writes();
                self.store_bit(located, written)?;
                bit_logic::assigned(&mut self.level.status, written);
            }
            MemOp::McrSet | MemOp::McrReset => {
                if rlo && self.level.mcr.writes() {
                    self.store_bit(located, op == MemOp::McrSet)?;
                }
                bridge::after_assignment(&mut self.level.status);
            }
            MemOp::McrTransfer => {
                let value = if self.level.mcr.writes() {
                    self.level.accu1
                } else {
                    0
                };
                self.store(located, width, value)?;
            }
            MemOp::EdgePositive | MemOp::EdgeNegative => {
                let memory = self.fetch_bit(located)?;
                let stored =
                    bridge::edge(&mut self.level.status, op == MemOp::EdgePositive, memory);
                self.store_bit(located, stored)?;
            }
            MemOp::Load | MemOp::LoadCoded => match located {
                Located::Timer(_) | Located::Counter(_) => {
                    return self.timer_counter_op(located, op, pc);
                }
                Located::Special(Target::Extension(extension)) => {
                    let value = self.extension_value(extension);
                    self.load_s7(value);
                }
                Located::Special(Target::DbRegister(register)) => {
                    let value = self.db_register(register);
                    self.load_s7(value);
                }
                other => {
                    let value = self.fetch(other, width)?;
                    self.load_s7(value);
                }
            },
            MemOp::Transfer => {
                let located = self.written_peripheral(located, place);
                self.store(located, width, self.level.accu1)?;
            }
            MemOp::TimerPulse
            | MemOp::TimerExtendedPulse
            | MemOp::TimerOnDelay
            | MemOp::TimerRetentiveOnDelay
            | MemOp::TimerOffDelay
            | MemOp::Enable
            | MemOp::CountUp
            | MemOp::CountDown
            | MemOp::SetCounter
            | MemOp::ResetTimerCounter => return self.timer_counter_op(located, op, pc),
            MemOp::LoadAr1 | MemOp::LoadAr2 => {
                let value = self.fetch(located, AccessWidth::Double)?;
                self.set_ar(if op == MemOp::LoadAr1 { 1 } else { 2 }, value);
            }
            MemOp::TransferAr1 | MemOp::TransferAr2 => {
                let value = if op == MemOp::TransferAr1 {
                    self.level.ar1
                } else {
                    self.level.ar2
                };
                self.store(located, AccessWidth::Double, value)?;
            }
            MemOp::CallFrom => return Err(fault("a call through a block parameter")),
        }
        Ok(())
    }

    /// A timer or counter operation on a located timer or counter: the STEP 5 op runs it.
    fn timer_counter_op(&mut self, located: Located, op: MemOp, pc: u32) -> Result<(), Fault> {
        let shared = match (located, op) {
            (Located::Timer(n), MemOp::Load) => Op::LoadTimer(n),
            (Located::Timer(n), MemOp::LoadCoded) => Op::LoadTimerCoded(n),
            (Located::Counter(n), MemOp::Load) => Op::LoadCounter(n),
            (Located::Counter(n), MemOp::LoadCoded) => Op::LoadCounterCoded(n),
            (Located::Timer(n), MemOp::TimerPulse) => Op::StartTimer(TimerKind::Pulse, n),
            (Located::Timer(n), MemOp::TimerExtendedPulse) => {
                Op::StartTimer(TimerKind::ExtendedPulse, n)
            }
            (Located::Timer(n), MemOp::TimerOnDelay) => Op::StartTimer(TimerKind::OnDelay, n),
            (Located::Timer(n), MemOp::TimerRetentiveOnDelay) => {
                Op::StartTimer(TimerKind::StoredOnDelay, n)
            }
            (Located::Timer(n), MemOp::TimerOffDelay) => Op::StartTimer(TimerKind::OffDelay, n),
            (Located::Timer(n), MemOp::Enable) => Op::EnableTimer(n),
            (Located::Timer(n), MemOp::ResetTimerCounter) => Op::ResetTimer(n),
            (Located::Counter(n), MemOp::Enable) => Op::EnableCounter(n),
            (Located::Counter(n), MemOp::CountUp) => Op::CountUp(n),
            (Located::Counter(n), MemOp::CountDown) => Op::CountDown(n),
            (Located::Counter(n), MemOp::SetCounter) => Op::SetCounter(n),
            (Located::Counter(n), MemOp::ResetTimerCounter) => Op::ResetCounter(n),
            (other, op) => return Err(fault(format!("{op:?} on {other:?}"))),
        };
        let (number, count) = match located {
            Located::Timer(n) => (n, self.timers.len()),
            Located::Counter(n) => (n, self.counters.len()),
            _ => (0, 0),
        };
        if usize::from(number) >= count {
            return Err(fault(format!(
                "timer or counter {number} is past the CPU's {count}"
            )));
        }
        self.execute_other(shared, pc)
    }

    /// Where the instance data of `call` start: its instance DB's slot and the bit offset in
    /// it (a multi-instance's inside the caller's instance DB, after the caller's AR2).
    fn instance_base(&self, call: &crate::step7::bytecode::FbCall) -> (u16, u32) {
        match call.multi_instance {
            Some(offset) => (self.level.di, (self.level.ar2 & 0x0007_FFFF) + offset),
            None => (call.instance_slot, 0),
        }
    }

    /// `CALL FB n, DB m` and `CALL #instance`, before the call: the inputs into the instance
    /// data, the registers saved, DB the caller's DI, DI the instance DB and AR2 the instance's
    /// start (STL manual, `CALL`: AR2 holds the multi-instance offset).
    fn fb_enter(&mut self, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.fb_calls[usize::from(call)];
        let (slot, base) = self.instance_base(call);
        if !matches!(self.s7_data.get(usize::from(slot)), Some(Some(_))) {
            if call.multi_instance.is_some() {
                return Err(fault(
                    "a multi-instance call with no instance DB open (DI)".to_string(),
                ));
            }
            return Err(missing_db(call.instance_db));
        }
        for copy in &call.inputs {
            let (from, _) = self.locate_index(copy.actual)?;
            let value = self.fetch(from, copy.width)?;
            self.store(instance_at(slot, base, copy), copy.width, value)?;
        }
        self.copy_blocks_in(&call.blocks_in, |byte| bytes_at(slot, base, byte))?;
        self.write_instance_pointers(&call.pointers, |byte| bytes_at(slot, base, byte))?;
        self.fb_saves
            .push((self.level.db, self.level.di, self.level.ar2));
        self.level.db = self.level.di;
        self.level.di = slot;
        // P#DBX base: the area bits say DB, STEP 7's own choice; FB code adds only the offset.
        self.level.ar2 = 0x8400_0000 | base;
        if let Some(number) = call.system {
            self.system_fb(number, slot, base)?;
        }
        Ok(())
    }

    /// After the FB: the registers restored, the outputs copied to their actuals, the instance
    /// DB left open as the DB.
    fn fb_leave(&mut self, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.fb_calls[usize::from(call)];
        let Some((db, di, ar2)) = self.fb_saves.pop() else {
            return Err(fault("an FB's return without its call"));
        };
        // The registers first: an actual may be the caller's own instance data. The outputs are
        // read from the instance data where the call put them, whatever DI holds now.
        self.level.db = db;
        self.level.di = di;
        self.level.ar2 = ar2;
        let (slot, base) = self.instance_base(call);
        for copy in &call.outputs {
            let value = self.fetch(instance_at(slot, base, copy), copy.width)?;
            let (to, _) = self.locate_index(copy.actual)?;
            self.store(to, copy.width, value)?;
        }
        self.copy_blocks_out(&call.blocks_out, |byte| bytes_at(slot, base, byte))?;
        // STEP 7's `CALL FB` exchanges DB and DI around the call (`TDB`, `OPN DI`, `UC`, `TDB`):
        // afterwards the DB register holds the instance DB and DI the caller's own again.
        self.level.db = slot;
        Ok(())
    }

    /// `CALL FC n (…)`, before the call: the copied actuals onto the L stack, AR2 saved.
    fn fc_enter(&mut self, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.fc_calls[usize::from(call)];
        for &(actual, copy) in &call.inputs {
            let (from, width) = self.locate_index(actual)?;
            let value = self.fetch(from, width)?;
            let (to, width) = self.locate_index(copy)?;
            self.store(to, width, value)?;
        }
        self.write_db_pointers(call)?;
        self.fb_saves
            .push((self.level.db, self.level.di, self.level.ar2));
        Ok(())
    }

    /// After the FC: AR2 back (an FB's instance data stay where they were whatever the FC
    /// did with AR2), the copies of outputs and in/outs to their actuals.
    fn fc_leave(&mut self, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.fc_calls[usize::from(call)];
        let Some((_, _, ar2)) = self.fb_saves.pop() else {
            return Err(fault("an FC's return without its call"));
        };
        self.level.ar2 = ar2;
        for &(actual, copy) in &call.outputs {
            let (from, width) = self.locate_index(copy)?;
            let value = self.fetch(from, width)?;
            let (to, width) = self.locate_index(actual)?;
            self.store(to, width, value)?;
        }
        Ok(())
    }

    /// `UC FC [MW 50]`, `CC FB [MW 50]`: the call of the block numbered in the word.
    pub(crate) fn call_from(&mut self, place: u16, flags: u16) -> Result<Op, Fault> {
        use crate::compiler::bytecode::{CALL_FROM_CONDITIONAL, CALL_FROM_FB};
        let conditional = flags & CALL_FROM_CONDITIONAL != 0;
        let (located, _) = self.locate_index(place)?;
        let number = self.fetch(located, AccessWidth::Word)? as u16;
        let kind = if flags & CALL_FROM_FB != 0 {
            crate::mnemonics::BlockKind::Fb
        } else {
            crate::mnemonics::BlockKind::Fc
        };
        let id = crate::ast::BlockId { kind, number };
        Ok(match self.program.block_index(id) {
            Some(block) => Op::Call {
                block,
                conditional,
                params: crate::compiler::bytecode::NO_PARAMS,
            },
            None => Op::CallMissing {
                kind,
                number,
                conditional,
            },
        })
    }

    /// `P##param`: the pointer the FC's caller passed for parameter `param`, an area-crossing
    /// pointer to where the actual is (area V for the caller's local data).
    fn param_pointer(&mut self, param: u8) -> Result<u32, Fault> {
        let context = self.running_context();
        let Some(crate::compiler::Resolved::S7(index)) = self.passed(context.params, param) else {
            return Err(fault(format!(
                "parameter {} has no actual to point to",
                param + 1
            )));
        };
        let place = self.program.s7.places[usize::from(index)];
        let Some(caller) = self.caller_context(context) else {
            return Err(fault("a parameter outside a called block".to_string()));
        };
        let located = self.locate(place, caller)?;
        let layout = self.program.layout;
        let (area, byte, bit) = match located {
            Located::Local { byte, bit } if byte >= caller.local_base as usize => {
                (0x87, byte - caller.local_base as usize, bit)
            }
            Located::Data { slot, byte, bit } => {
                (if slot == caller.di { 0x85 } else { 0x84 }, byte, bit)
            }
            Located::Image { byte, bit } => {
                let flag = usize::from(layout.flag_base());
                let output = usize::from(layout.output_base());
                let input = usize::from(layout.input_base());
                if byte >= flag {
                    (0x83, byte - flag, bit)
                } else if byte >= output {
                    (0x82, byte - output, bit)
                } else {
                    (0x81, byte - input, bit)
                }
            }
            Located::Peripheral { byte, .. } => (0x80, usize::from(byte), 0),
            other => {
                return Err(fault(format!(
                    "parameter {} is {other:?}, which no pointer reaches",
                    param + 1
                )));
            }
        };
        Ok(area << 24 | (byte as u32) << 3 | u32::from(bit))
    }

    fn system_function(&mut self, call: u16) -> Result<(), Fault> {
        let number = self.program.s7.sfc_calls[usize::from(call)].number;
        match number {
            SET_CLK | READ_CLK => self.clock_sfc(number, call),
            46 => Err((StopCause::Stp, StopDetail::Text("CALL SFC 46 (STP)".into()))),
            // The simulation ends as a test does at `CALL SFC 46`.
            AWLSIM_SFC_SHUTDOWN => Err((
                StopCause::Stp,
                StopDetail::Text("awlsim's CALL SFC -3 (__SHUTDOWN)".into()),
            )),
            WAIT => self.wait(call),
            BLKMOV | FILL => self.block_move(number, call),
            DIS_IRT..=EN_AIRT => self.interrupt_sfc(number, call),
            TIME_TCK => {
                // The compiler checked RET_VAL is given, a double word.
                let program = std::sync::Arc::clone(&self.program);
                let params = &program.s7.sfc_calls[usize::from(call)].params;
                if let Some(&(_, place)) = params.iter().find(|(name, _)| name == "RET_VAL") {
                    let (to, width) = self.locate_index(place)?;
                    self.store(to, width, self.time_tick())?;
                }
                self.level.br = true;
                Ok(())
            }
            AWLSIM_SFC_NOP => {
                self.level.br = true;
                Ok(())
            }
            AWLSIM_SFC_CLOCK_RESET => {
                self.restart_clocks();
                self.level.br = true;
                Ok(())
            }
            AWLSIM_SFC_REBOOT => Err(fault(
                "awlsim's SFC -2 (__REBOOT) is not simulated: awl writes the OBs' start \
                 information always (`__FEATURE 1` is 1), there is nothing to reboot for"
                    .to_string(),
            )),
            other if other >= AWLSIM_SFC_CLOCK_RESET => Err(fault(format!(
                "awlsim's SFC {} is not simulated",
                other as i16
            ))),
            other => Err(fault(format!("SFC {other} is not simulated"))),
        }
    }

    /// The value of an operand of `__ASSERT`.
    fn assert_operand(&mut self, place: u16) -> Result<u32, Fault> {
        let (located, width) = self.locate_index(place)?;
        match located {
            Located::Special(_) => self.special_value(located),
            Located::Timer(_) | Located::Counter(_) => Ok(u32::from(self.fetch_bit(located)?)),
            other => self.fetch(other, width),
        }
    }

    /// The value of a test operand, a DB register or a status condition.
    fn special_value(&self, located: Located) -> Result<u32, Fault> {
        match located {
            Located::Special(Target::Extension(extension)) => Ok(self.extension_value(extension)),
            Located::Special(Target::DbRegister(register)) => Ok(self.db_register(register)),
            Located::Special(Target::Condition(condition)) => {
                Ok(u32::from(bridge::condition(&self.level, condition)))
            }
            other => Err(fault(format!("{other:?} has no value"))),
        }
    }

    fn extension_value(&self, extension: Extension) -> u32 {
        match extension {
            Extension::StatusBit(bit) => bridge::status_word(&self.level) >> bit & 1,
            Extension::StatusWord => bridge::status_word(&self.level),
            Extension::Accu(1) => self.level.accu1,
            Extension::Accu(2) => self.level.accu2,
            Extension::Accu(3) => self.level.accu3,
            Extension::Accu(_) => self.level.accu4,
            Extension::AddressRegister(1) => self.level.ar1,
            Extension::AddressRegister(_) => self.level.ar2,
            Extension::DbRegister(1) => u32::from(self.program.s7.db_number(self.level.db)),
            Extension::DbRegister(_) => u32::from(self.program.s7.db_number(self.level.di)),
            Extension::Pi => std::f32::consts::PI.to_bits(),
            Extension::E => std::f32::consts::E.to_bits(),
            Extension::PositiveInfinity => f32::INFINITY.to_bits(),
            Extension::NegativeInfinity => f32::NEG_INFINITY.to_bits(),
            Extension::PositiveNan => 0x7FFF_FFFF,
            Extension::NegativeNan => 0xFFFF_FFFF,
        }
    }

    /// `__ASSERT`: both operands compared as unsigned bit patterns, as awlsim's harness does.
    fn assert(&mut self, cmp: Cmp, left: u16) -> Result<(), Fault> {
        let a = self.assert_operand(left)?;
        let b = self.assert_operand(left + 1)?;
        if cmp.holds(&a, &b) {
            bridge::after_assert(&mut self.level.status);
            return Ok(());
        }
        let sign = match cmp {
            Cmp::Eq => "==",
            Cmp::Ne => "<>",
            Cmp::Gt => ">",
            Cmp::Lt => "<",
            Cmp::Ge => ">=",
            Cmp::Le => "<=",
        };
        Err((
            StopCause::Assert,
            StopDetail::Text(format!(
                "__ASSERT{sign} failed: left is {a} ({a:#X}), right is {b} ({b:#X})"
            )),
        ))
    }
}

/// Where a parameter copy lies in instance data that start `base` bits into `slot`.
fn instance_at(slot: u16, base: u32, copy: &crate::step7::bytecode::ParamCopy) -> Located {
    let bits = base + (copy.byte << 3 | u32::from(copy.bit));
    Located::Data {
        slot,
        byte: (bits >> 3) as usize,
        bit: (bits & 7) as u8,
    }
}

/// Byte `byte` of instance data that start `base` bits into `slot`.
fn bytes_at(slot: u16, base: u32, byte: u32) -> Located {
    Located::Data {
        slot,
        byte: ((base >> 3) + byte) as usize,
        bit: 0,
    }
}
