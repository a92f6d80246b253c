//! The date and time functions of the IEC library: FC 1 AD_DT_TM, FC 3 D_TOD_DT, FC 6 DT_DATE,
//! FC 7 DT_DAY, FC 8 DT_TOD, the comparisons FC 9, 12, 14, 18, 23, 28 (EQ_DT … NE_DT), FC 33
//! S5TI_TIM, FC 34 SB_DT_DT, FC 35 SB_DT_TM and FC 40 TIM_S5TI. A DATE_AND_TIME is counted as
//! the day after 1990-01-01 and the milliseconds after midnight; one that is none (a byte that
//! is no BCD digit of the calendar) is an error and the result stays as it was.

use crate::step7::library::LibraryCall;
use crate::step7::literal::{
    DATE_AND_TIME_DAYS as DAYS, DATE_AND_TIME_LAST_MS as LAST_MS, DAY_MS, date_and_time_from_bytes,
    date_and_time_of_instant, date_and_time_year, s5time_word,
};
use crate::vm::Cpu;
use crate::vm::timers::decode_time;

use super::super::memory::Fault;

/// The longest S5TIME, 999 × 10 s.
const S5TIME_MS: i32 = 9_990_000;
/// The milliseconds of the S5TIME bases 0 to 3.
const BASE_MS: [u32; 4] = [10, 100, 1_000, 10_000];

impl Cpu {
    /// A DATE_AND_TIME parameter as milliseconds since 1990-01-01; `None` when it is none.
    fn read_dt(&mut self, call: &LibraryCall, index: usize) -> Result<Option<i64>, Fault> {
        let bytes = self.fetch_date_and_time(call.params[index])?;
        Ok(date_and_time_from_bytes(bytes)
            .ok()
            .map(|(days, ms)| i64::from(days) * DAY_MS + i64::from(ms)))
    }

    /// Writes the instant `ms` milliseconds after 1990-01-01, limited to the range of a
    /// DATE_AND_TIME; whether it was within.
    fn write_dt(&mut self, call: &LibraryCall, index: usize, ms: i64) -> Result<bool, Fault> {
        self.store_date_and_time(call.params[index], date_and_time_of_instant(ms))?;
        Ok((0..=LAST_MS).contains(&ms))
    }

    pub(super) fn date_time_fc(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        match call.number {
            // AD_DT_TM (T, D) and SB_DT_TM (IN1, IN2): an instant plus or minus a TIME.
            1 | 35 => {
                let Some(instant) = self.read_dt(call, 0)? else {
                    return Ok(false);
                };
                let duration = i64::from(self.read_arg(call, 1)? as i32);
                let sum = if call.number == 1 {
                    instant + duration
                } else {
                    instant - duration
                };
                self.write_dt(call, 2, sum)
            }
            // D_TOD_DT: a DATE and a TIME_OF_DAY.
            3 => {
                let days = i64::from(self.read_arg(call, 0)? as u16);
                let ms = i64::from(self.read_arg(call, 1)?);
                if days >= DAYS || ms >= DAY_MS {
                    return Ok(false);
                }
                self.write_dt(call, 2, days * DAY_MS + ms)
            }
            // DT_DATE, DT_DAY (1 Sunday … 7 Saturday; 1990-01-01 was a Monday), DT_TOD.
            6..=8 => {
                let Some(instant) = self.read_dt(call, 0)? else {
                    return Ok(false);
                };
                let (days, ms) = (instant / DAY_MS, instant % DAY_MS);
                let value = match call.number {
                    6 => days,
                    7 => (days + 1) % 7 + 1,
                    _ => ms,
                };
                self.write_arg(call, 1, value as u32)?;
                Ok(true)
            }
            // SB_DT_DT: the TIME between two instants, limited to a TIME's range.
            34 => {
                let (Some(first), Some(second)) = (self.read_dt(call, 0)?, self.read_dt(call, 1)?)
                else {
                    return Ok(false);
                };
                let difference = first - second;
                let limited = difference.clamp(i64::from(i32::MIN), i64::from(i32::MAX));
                self.write_arg(call, 2, limited as i32 as u32)?;
                Ok(limited == difference)
            }
            // S5TI_TIM: the three BCD digits times the base.
            33 => {
                let (count, base) = decode_time(self.read_arg(call, 0)?);
                let ms = u32::from(count) * BASE_MS[usize::from(base)];
                self.write_arg(call, 1, ms)?;
                Ok(true)
            }
            // TIM_S5TI: negative and too long TIMEs give the nearest S5TIME.
            40 => {
                let ms = self.read_arg(call, 0)? as i32;
                let limited = ms.clamp(0, S5TIME_MS);
                let word = s5time_word(limited as u32).unwrap_or(0);
                self.write_arg(call, 1, word)?;
                Ok(limited == ms)
            }
            // EQ_DT and NE_DT compare the eight bytes as they are and report no error, as the
            // library's own code does (a value that is no date compares like any other).
            9 | 28 => {
                let first = self.fetch_date_and_time(call.params[0])?;
                let second = self.fetch_date_and_time(call.params[1])?;
                let equal = first == second;
                self.write_arg(call, 2, u32::from(equal == (call.number == 9)))?;
                Ok(true)
            }
            // The other comparisons order by the year (1990 to 2089), then by the other seven
            // bytes as they are, as the library's own code does: only a year that is no BCD
            // number is an error.
            _ => {
                let first = self.fetch_date_and_time(call.params[0])?;
                let second = self.fetch_date_and_time(call.params[1])?;
                let (Some(first), Some(second)) = (order_key(first), order_key(second)) else {
                    return Ok(false);
                };
                let result = match call.number {
                    12 => first >= second,
                    14 => first > second,
                    18 => first <= second,
                    _ => first < second,
                };
                self.write_arg(call, 2, u32::from(result))?;
                Ok(true)
            }
        }
    }
}

/// What the ordering comparisons compare a DATE_AND_TIME by: its year, then its other bytes;
/// `None` when the year is no BCD number.
fn order_key(bytes: [u8; 8]) -> Option<(u32, [u8; 7])> {
    let year = date_and_time_year(bytes[0])?;
    let mut rest = [0; 7];
    rest.copy_from_slice(&bytes[1..]);
    Some((year, rest))
}
