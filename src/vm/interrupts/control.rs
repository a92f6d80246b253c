//! The STEP 7 system functions that disable and delay interrupts ("System Software for
//! S7-300/400 System and Standard Functions", 12 SFCs for Handling Interrupts and Asynchronous
//! Errors; the VIPA SPEED7 operation list has the same SFCs):
//!
//! - SFC 39 DIS_IRT (12.2) disables the processing of new interrupt and asynchronous error
//!   events: MODE 0 all of them, MODE 1 those of one class (OB_NR 10, 20, …, 80: the class's
//!   first OB number), MODE 2 those of one OB (OB_NR). A disabled event is discarded, not kept
//!   for later. SFC 40 EN_IRT (12.3) enables them again with the same MODE and OB_NR.
//!   RET_VAL 0; 16#8090 OB_NR invalid; 16#8091 MODE invalid.
//! - SFC 41 DIS_AIRT (12.4) delays the interrupt and asynchronous error OBs of a higher
//!   priority than the running OB's: they are taken in and run later. The calls are counted;
//!   each stays in force until an SFC 42 EN_AIRT call (12.5) or until the OB that called it
//!   has ended. RET_VAL: the number of delays in force; EN_AIRT's 16#8080 when no delay was in
//!   force.
//!
//! An error sets the binary result BR to 0, no error to 1 (the same manual, "Evaluating Errors
//! with Output Parameter RET_VAL").

use crate::trace::Event;
use crate::vm::Cpu;
use crate::vm::s7::memory::Fault;

use super::Request;

pub use crate::compiler::step7::interrupt_sfcs::{
    DIS_AIRT, DIS_IRT, EN_AIRT, EN_IRT, name, parameters,
};

/// RET_VAL: OB_NR names no interrupt or asynchronous error OB (no class in MODE 1).
pub const OB_NR_INVALID: u16 = 0x8090;
/// RET_VAL: MODE is not 0, 1 or 2.
pub const MODE_INVALID: u16 = 0x8091;
/// RET_VAL of EN_AIRT: no delay was in force.
pub const NOT_DELAYED: u16 = 0x8080;

/// The interrupt and asynchronous error OBs MODE 0 and MODE 2 reach: OB 10 (time-of-day
/// interrupts) to OB 88 (the last asynchronous error OB) of the STEP 7 numbering. The cyclic
/// program, the startup OBs and the synchronous error OBs (OB 121, OB 122) are none of them:
/// SFC 39 does not disable synchronous errors.
const FIRST: u8 = 10;
const LAST: u8 = 88;

/// The OBs SFC 39 has disabled, one bit per OB number.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Disabled([u128; 2]);

impl Disabled {
    /// The OBs disabled, by number.
    pub fn obs(&self) -> Vec<u8> {
        (0..=u8::MAX).filter(|ob| self.has(*ob)).collect()
    }

    /// The OBs `obs` disabled.
    pub fn of(obs: &[u8]) -> Disabled {
        let mut disabled = Disabled::default();
        for ob in obs {
            disabled.set(*ob..=*ob, true);
        }
        disabled
    }

    pub fn has(&self, ob: u8) -> bool {
        self.0[usize::from(ob / 128)] >> (ob % 128) & 1 == 1
    }

    fn set(&mut self, obs: std::ops::RangeInclusive<u8>, disabled: bool) {
        for ob in obs {
            let (word, bit) = (usize::from(ob / 128), ob % 128);
            if disabled {
                self.0[word] |= 1 << bit;
            } else {
                self.0[word] &= !(1 << bit);
            }
        }
    }
}

/// The OBs a MODE and OB_NR name, or the RET_VAL error.
fn obs_of(mode: u8, ob_nr: i16) -> Result<std::ops::RangeInclusive<u8>, u16> {
    let ob = u8::try_from(ob_nr).ok();
    match mode {
        0 => Ok(FIRST..=LAST),
        // A class is named by its first OB number: 10, 20, … 80; the asynchronous errors'
        // class ends with OB 88.
        1 => match ob {
            Some(first @ (10 | 20 | 30 | 40 | 50 | 60 | 70)) => Ok(first..=first + 9),
            Some(80) => Ok(80..=LAST),
            _ => Err(OB_NR_INVALID),
        },
        2 => match ob {
            Some(ob @ FIRST..=LAST) => Ok(ob..=ob),
            _ => Err(OB_NR_INVALID),
        },
        _ => Err(MODE_INVALID),
    }
}

impl Cpu {
    /// Runs SFC 39 to SFC 42, call `call` of the program's SFC calls.
    pub(crate) fn interrupt_sfc(&mut self, number: u16, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let places = &program.s7.sfc_calls[usize::from(call)].params;
        let mut value = |index: usize| -> Result<u32, Fault> {
            let (located, width) = self.locate_index(places[index].1)?;
            self.fetch(located, width)
        };
        let (mode, ob_nr) = match number {
            DIS_IRT | EN_IRT => (Some(value(0)? as u8), Some(value(1)? as u16 as i16)),
            _ => (None, None),
        };
        let ret_val = match (number, mode, ob_nr) {
            (DIS_IRT | EN_IRT, Some(mode), Some(ob_nr)) => match obs_of(mode, ob_nr) {
                Ok(obs) => {
                    self.engine.disabled.set(obs, number == DIS_IRT);
                    0
                }
                Err(code) => code,
            },
            (DIS_AIRT, ..) => {
                self.level.airt_delays = self.level.airt_delays.saturating_add(1);
                if self.level.airt_delays == 1 {
                    self.delay_pending();
                }
                self.level.airt_delays
            }
            _ if self.level.airt_delays == 0 => NOT_DELAYED,
            _ => {
                self.level.airt_delays -= 1;
                if self.level.airt_delays == 0 {
                    let ob = self.active_ob().0;
                    self.emit(self.clock, |_| Event::DelayEnd { ob, by: "EN_AIRT" });
                }
                self.level.airt_delays
            }
        };
        let (located, width) = self.locate_index(places[places.len() - 1].1)?;
        self.store(located, width, u32::from(ret_val))?;
        self.level.br = ret_val & 0x8000 == 0;
        let ob = self.active_ob().0;
        self.emit(self.clock, |_| Event::IrtCall {
            sfc: number,
            name: name(number),
            mode,
            ob_nr,
            ret_val: ret_val as i16,
            ob,
        });
        self.update_attention();
        Ok(())
    }

    /// DIS_AIRT took effect: the pending requests that outrank the running level wait.
    fn delay_pending(&mut self) {
        let running = self.running_priority();
        let delays = self.level.airt_delays;
        for index in 0..self.engine.pending.len() {
            let Request { id, ob, .. } = self.engine.pending[index];
            if self.priority_of(ob) > running {
                self.engine.pending[index].waited = Some(super::Wait::Delayed);
                self.emit(self.clock, |_| Event::IrqDelayed { id, ob, delays });
            }
        }
    }

    /// The level of OB `ob` ends: the delays its DIS_AIRT calls left in force end with it.
    pub(in crate::vm) fn end_delays(&mut self, ob: u8) {
        if self.level.airt_delays > 0 {
            self.level.airt_delays = 0;
            self.emit(self.clock, |_| Event::DelayEnd { ob, by: "OB end" });
        }
    }

    /// Counts and traces a request SFC 39 had disabled: it is discarded.
    pub(super) fn discard(&mut self, at: u64, request: Request) {
        let (id, ob) = (request.id, request.ob);
        self.engine.stats_mut(ob).discarded += 1;
        self.emit(at, |_| Event::IrqDiscarded {
            id,
            ob,
            reason: "disabled by SFC 39 DIS_IRT",
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_name_all_a_class_or_one_ob() {
        assert_eq!(obs_of(0, -5), Ok(10..=88));
        assert_eq!(obs_of(1, 40), Ok(40..=49));
        assert_eq!(obs_of(1, 80), Ok(80..=88));
        assert_eq!(obs_of(1, 35), Err(OB_NR_INVALID));
        assert_eq!(obs_of(2, 35), Ok(35..=35));
        assert_eq!(obs_of(2, 1), Err(OB_NR_INVALID));
        assert_eq!(obs_of(2, 121), Err(OB_NR_INVALID));
        assert_eq!(obs_of(3, 35), Err(MODE_INVALID));
    }

    #[test]
    fn the_disabled_set_keeps_one_bit_per_ob() {
        let mut disabled = Disabled::default();
        disabled.set(40..=49, true);
        disabled.set(41..=41, false);
        assert!(disabled.has(40) && !disabled.has(41) && disabled.has(49));
        assert!(!disabled.has(35) && !disabled.has(200));
    }
}
