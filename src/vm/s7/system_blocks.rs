//! The system FBs awl runs itself: the IEC counters SFB 0 to 2 and the IEC timers SFB 3 to 5
//! ("System Software for S7-300/400 System and Standard Functions", IEC counters and IEC
//! timers), and awlsim's SFB -1, on their instance data. The timers count simulated time in
//! the milliseconds of SFC 64 (TIME_TCK).

use crate::step7::ast::AccessWidth;
use crate::vm::Cpu;

use super::exec::fault;
use super::memory::{Fault, Located};

/// awlsim's SFB -1 (`__SFB_NOP`) as a 16-bit number.
const AWLSIM_SFB_NOP: u16 = -1i16 as u16;

/// The bit offsets of a timer's instance data (IN 0.0, PT 2, Q 6.0, ET 8, STATE 12,
/// STIME 14, ATIME 18).
const IN: u32 = 0;
const PT: u32 = 2 * 8;
const Q: u32 = 6 * 8;
const ET: u32 = 8 * 8;
const STATE: u32 = 12 * 8;
const STIME: u32 = 14 * 8;
const ATIME: u32 = 18 * 8;

/// STATE of TP and TON: the time runs, or it has run out and waits for IN to fall.
const RUNNING: u8 = 1;
const FINISHED: u8 = 2;
/// STATE of TOF: IN was 1 at the last call, or the delay after its falling edge runs.
const PREVIOUS_IN: u8 = 1;
const DELAYING: u8 = 2;

/// The instance data of one call: `slot`, from `base` bits on.
#[derive(Clone, Copy)]
struct Instance {
    slot: u16,
    base: u32,
}

impl Instance {
    fn at(self, offset: u32) -> Located {
        let bits = self.base + offset;
        Located::Data {
            slot: self.slot,
            byte: (bits >> 3) as usize,
            bit: (bits & 7) as u8,
        }
    }
}

impl Cpu {
    /// A system FB awl runs itself, on its instance data at `base` bits into `slot`. BR says
    /// whether it ran without error.
    pub(super) fn system_fb(&mut self, number: u16, slot: u16, base: u32) -> Result<(), Fault> {
        let data = Instance { slot, base };
        self.level.br = match number {
            0..=2 => self.iec_counter(number, data)?,
            3..=5 => self.iec_timer(number, data)?,
            AWLSIM_SFB_NOP => true,
            other => return Err(fault(format!("SFB {other} is not simulated"))),
        };
        Ok(())
    }

    fn word(&mut self, located: Located) -> Result<i16, Fault> {
        Ok(self.fetch(located, AccessWidth::Word)? as u16 as i16)
    }

    /// SFB 0 CTU (CU 0.0, R 0.1, PV 2, Q 4.0, CV 6, CUO 8.0), SFB 1 CTD (CD 0.0, LOAD 0.1,
    /// PV 2, Q 4.0, CV 6, CDO 8.0), SFB 2 CTUD (CU 0.0, CD 0.1, R 0.2, LOAD 0.3, PV 2, QU 4.0,
    /// QD 4.1, CV 6, CUO 8.0, CDO 8.1): each counts on a rising edge of its count input, R
    /// clears and LOAD loads PV before any edge counts, the count stays within an INT.
    fn iec_counter(&mut self, number: u16, data: Instance) -> Result<bool, Fault> {
        let preset = self.word(data.at(16))?;
        let mut count = self.word(data.at(48))?;
        // The edge of each count input against the value the last call kept.
        let edge = |cpu: &mut Self, input: u32, previous: u32| -> Result<bool, Fault> {
            let now = cpu.fetch_bit(data.at(input))?;
            let before = cpu.fetch_bit(data.at(previous))?;
            cpu.store_bit(data.at(previous), now)?;
            Ok(now && !before)
        };
        let (up, down, reset, load) = match number {
            0 => (
                edge(self, 0, 64)?,
                false,
                self.fetch_bit(data.at(1))?,
                false,
            ),
            1 => (
                false,
                edge(self, 0, 64)?,
                false,
                self.fetch_bit(data.at(1))?,
            ),
            _ => {
                let up = edge(self, 0, 64)?;
                let down = edge(self, 1, 65)?;
                let reset = self.fetch_bit(data.at(2))?;
                (up, down, reset, self.fetch_bit(data.at(3))?)
            }
        };
        if reset {
            count = 0;
        } else if load {
            count = preset;
        } else if up && !down {
            count = count.saturating_add(1);
        } else if down && !up {
            count = count.saturating_sub(1);
        }
        self.store(data.at(48), AccessWidth::Word, count as u16 as u32)?;
        match number {
            0 => self.store_bit(data.at(32), count >= preset)?,
            1 => self.store_bit(data.at(32), count <= 0)?,
            _ => {
                self.store_bit(data.at(32), count >= preset)?;
                self.store_bit(data.at(33), count <= 0)?;
            }
        }
        Ok(true)
    }

    /// SFB 3 TP, SFB 4 TON, SFB 5 TOF on simulated time. PT 0 resets the timer (and IN, as
    /// S7 does); a negative PT resets it too and is an error (BR 0).
    fn iec_timer(&mut self, number: u16, data: Instance) -> Result<bool, Fault> {
        let preset = self.fetch(data.at(PT), AccessWidth::Double)? as i32;
        if preset <= 0 {
            if preset == 0 {
                self.store_bit(data.at(IN), false)?;
            }
            self.store_bit(data.at(Q), false)?;
            self.store(data.at(ET), AccessWidth::Double, 0)?;
            self.store(data.at(STATE), AccessWidth::Byte, 0)?;
            return Ok(preset == 0);
        }
        let preset = preset as u32;
        let now = self.time_tick();
        let input = self.fetch_bit(data.at(IN))?;
        let mut state = self.fetch(data.at(STATE), AccessWidth::Byte)? as u8;
        match number {
            3 => self.pulse(data, input, &mut state, preset, now)?,
            4 => self.on_delay(data, input, &mut state, preset, now)?,
            _ => self.off_delay(data, input, &mut state, preset, now)?,
        }
        self.store(data.at(STATE), AccessWidth::Byte, u32::from(state))?;
        Ok(true)
    }

    /// The time since STIME, at most `preset`, into ET and ATIME; whether it has run out.
    fn elapse(&mut self, data: Instance, preset: u32, now: u32) -> Result<bool, Fault> {
        let start = self.fetch(data.at(STIME), AccessWidth::Double)?;
        self.store(data.at(ATIME), AccessWidth::Double, now)?;
        let elapsed = now.wrapping_sub(start) & 0x7FFF_FFFF;
        let done = elapsed >= preset;
        self.store(
            data.at(ET),
            AccessWidth::Double,
            if done { preset } else { elapsed },
        )?;
        Ok(done)
    }

    /// TP: a rising IN starts a pulse of PT (Q 1 while it runs, whatever IN does); ET stays
    /// at PT until IN falls.
    fn pulse(
        &mut self,
        data: Instance,
        input: bool,
        state: &mut u8,
        preset: u32,
        now: u32,
    ) -> Result<(), Fault> {
        if input && *state & (RUNNING | FINISHED) == 0 {
            self.store(data.at(STIME), AccessWidth::Double, now)?;
            *state |= RUNNING;
        }
        if *state & RUNNING != 0 {
            let done = self.elapse(data, preset, now)?;
            if done {
                *state = *state & !RUNNING | FINISHED;
            }
            self.store_bit(data.at(Q), !done)?;
        }
        if !input && *state & FINISHED != 0 {
            *state &= !FINISHED;
            self.store(data.at(ET), AccessWidth::Double, 0)?;
        }
        Ok(())
    }

    /// TON: Q rises PT after IN rose, while IN stays 1; IN 0 clears Q and ET.
    fn on_delay(
        &mut self,
        data: Instance,
        input: bool,
        state: &mut u8,
        preset: u32,
        now: u32,
    ) -> Result<(), Fault> {
        if input {
            if *state & (RUNNING | FINISHED) == 0 {
                self.store(data.at(STIME), AccessWidth::Double, now)?;
                *state |= RUNNING;
            }
        } else {
            *state &= !(RUNNING | FINISHED);
            self.store(data.at(ET), AccessWidth::Double, 0)?;
            self.store_bit(data.at(Q), false)?;
        }
        if *state & RUNNING != 0 {
            let done = self.elapse(data, preset, now)?;
            if done {
                *state = *state & !RUNNING | FINISHED;
            }
            self.store_bit(data.at(Q), done)?;
        }
        Ok(())
    }

    /// TOF: Q follows a rising IN at once and falls PT after IN fell.
    fn off_delay(
        &mut self,
        data: Instance,
        input: bool,
        state: &mut u8,
        preset: u32,
        now: u32,
    ) -> Result<(), Fault> {
        if input {
            *state = *state & !DELAYING | PREVIOUS_IN;
            self.store(data.at(ET), AccessWidth::Double, 0)?;
            self.store_bit(data.at(Q), true)?;
        } else {
            if *state & PREVIOUS_IN != 0 {
                self.store(data.at(STIME), AccessWidth::Double, now)?;
                *state |= DELAYING;
            }
            *state &= !PREVIOUS_IN;
        }
        if *state & DELAYING != 0 {
            let done = self.elapse(data, preset, now)?;
            if done {
                *state &= !DELAYING;
            }
            self.store_bit(data.at(Q), !done)?;
        }
        Ok(())
    }
}
