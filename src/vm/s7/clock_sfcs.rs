//! SFC 0 SET_CLK, SFC 1 READ_CLK and SFC 47 WAIT on simulated time ("System Software for
//! S7-300/400 System and Standard Functions", SFCs for handling the time of day, and SFC 47
//! WAIT). The compiler checked every parameter is given with an operand of its type.

use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{READ_CLK, SET_CLK};
use crate::step7::literal::{BadDateAndTime, date_and_time_from_bytes};
use crate::vm::Cpu;

use super::memory::Fault;

/// SET_CLK's RET_VAL for a DATE_AND_TIME whose date is wrong.
const DATE_ERROR: u32 = 0x8080;
/// SET_CLK's RET_VAL for a DATE_AND_TIME whose time of day is wrong.
const TIME_ERROR: u32 = 0x8081;

impl Cpu {
    /// The place of parameter `name` of SFC call `call`.
    fn sfc_param(&self, call: u16, name: &str) -> Option<u16> {
        self.program.s7.sfc_calls[usize::from(call)]
            .params
            .iter()
            .find(|(param, _)| param == name)
            .map(|&(_, place)| place)
    }

    /// The eight bytes of the DATE_AND_TIME at `place`.
    pub(super) fn fetch_date_and_time(&mut self, place: u16) -> Result<[u8; 8], Fault> {
        let (at, _) = self.locate_index(place)?;
        let high = self.fetch(at, AccessWidth::Double)?;
        let low = self.fetch(at.offset(4, 0), AccessWidth::Double)?;
        let mut bytes = [0; 8];
        bytes[..4].copy_from_slice(&high.to_be_bytes());
        bytes[4..].copy_from_slice(&low.to_be_bytes());
        Ok(bytes)
    }

    pub(super) fn store_date_and_time(&mut self, place: u16, bytes: [u8; 8]) -> Result<(), Fault> {
        let (at, _) = self.locate_index(place)?;
        let [a, b, c, d, e, f, g, h] = bytes;
        self.store(at, AccessWidth::Double, u32::from_be_bytes([a, b, c, d]))?;
        self.store(
            at.offset(4, 0),
            AccessWidth::Double,
            u32::from_be_bytes([e, f, g, h]),
        )
    }

    fn store_ret_val(&mut self, call: u16, value: u32) -> Result<(), Fault> {
        if let Some(place) = self.sfc_param(call, "RET_VAL") {
            let (to, width) = self.locate_index(place)?;
            self.store(to, width, value)?;
        }
        Ok(())
    }

    /// SET_CLK or READ_CLK (`number`): RET_VAL 0 and BR 1, or SET_CLK's error code for a
    /// date (16#8080) or time of day (16#8081) that is none, and BR 0; the clock unchanged.
    pub(super) fn clock_sfc(&mut self, number: u16, call: u16) -> Result<(), Fault> {
        let result = match number {
            SET_CLK => {
                let Some(place) = self.sfc_param(call, "PDT") else {
                    return Err(super::exec::fault("SFC 0 without PDT"));
                };
                match date_and_time_from_bytes(self.fetch_date_and_time(place)?) {
                    Ok((days, ms)) => {
                        let wanted = i64::from(days) * 86_400_000 + i64::from(ms);
                        self.clock_set_ms += wanted - self.clock_ms() as i64;
                        0
                    }
                    Err(BadDateAndTime::Date) => DATE_ERROR,
                    Err(BadDateAndTime::Time) => TIME_ERROR,
                }
            }
            READ_CLK => {
                if let Some(place) = self.sfc_param(call, "CDT") {
                    self.store_date_and_time(place, self.date_and_time())?;
                }
                0
            }
            other => return Err(super::exec::fault(format!("SFC {other} is not simulated"))),
        };
        self.store_ret_val(call, result)?;
        self.level.br = result == 0;
        Ok(())
    }

    /// WAIT: WT microseconds of simulated time pass; none for a WT of 0 or below.
    pub(super) fn wait(&mut self, call: u16) -> Result<(), Fault> {
        if let Some(place) = self.sfc_param(call, "WT") {
            let (from, _) = self.locate_index(place)?;
            let micros = self.fetch(from, AccessWidth::Word)? as u16 as i16;
            if micros > 0 {
                self.clock += micros as u64 * 1_000;
            }
        }
        self.level.br = true;
        Ok(())
    }
}
