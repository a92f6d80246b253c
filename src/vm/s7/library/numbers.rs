//! The selection functions of the IEC library — FC 22 LIMIT, FC 25 MAX, FC 27 MIN, FC 36
//! SEL — on the INT, DINT or REAL the compiler found the ANY parameters to share, and the TI-S7
//! converting blocks FC 105 SCALE and FC 106 UNSCALE (an analog value of 0 … 27648, bipolar
//! -27648 … 27648, to and from a REAL of LO_LIM … HI_LIM).

use crate::step7::library::{AnyType, LibraryCall};
use crate::vm::Cpu;

use super::super::memory::Fault;

/// The top of an analog value's nominal range.
const NOMINAL: f32 = 27_648.0;
/// SCALE's and UNSCALE's RET_VAL for an input beyond its range.
const OUT_OF_RANGE: u32 = 0x0008;

/// A value of an ANY parameter as a number; `None` for a REAL that is no number.
fn number(ty: AnyType, raw: u32) -> Option<f64> {
    match ty {
        AnyType::Int => Some(f64::from(raw as u16 as i16)),
        AnyType::Dint => Some(f64::from(raw as i32)),
        AnyType::Real | AnyType::Bits => {
            let value = f32::from_bits(raw);
            (!value.is_nan()).then_some(f64::from(value))
        }
    }
}

impl Cpu {
    pub(super) fn number_fc(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        match call.number {
            22 => self.limit(call),
            25 | 27 => self.extreme(call),
            36 => {
                // SEL: G picks IN1 (1) or IN0 (0).
                let pick = if self.read_arg(call, 0)? & 1 != 0 {
                    2
                } else {
                    1
                };
                let value = self.read_arg(call, pick)?;
                self.write_arg(call, 3, value)?;
                Ok(true)
            }
            105 => self.scale(call),
            _ => self.unscale(call),
        }
    }

    /// The raw value and the number of ANY parameter `index`.
    fn any_number(
        &mut self,
        call: &LibraryCall,
        index: usize,
    ) -> Result<(u32, Option<f64>), Fault> {
        let raw = self.read_arg(call, index)?;
        Ok((raw, number(call.any_type, raw)))
    }

    /// LIMIT (MN, IN, MX): IN within MN … MX; MN above MX gives IN and an error, a REAL that
    /// is no number an error and RET_VAL as it was.
    fn limit(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let (low_raw, low) = self.any_number(call, 0)?;
        let (raw, value) = self.any_number(call, 1)?;
        let (high_raw, high) = self.any_number(call, 2)?;
        let (Some(low), Some(value), Some(high)) = (low, value, high) else {
            return Ok(false);
        };
        if low > high {
            self.write_arg(call, 3, raw)?;
            return Ok(false);
        }
        let result = if value < low {
            low_raw
        } else if value > high {
            high_raw
        } else {
            raw
        };
        self.write_arg(call, 3, result)?;
        Ok(true)
    }

    /// MAX and MIN of IN1, IN2, IN3; a REAL that is no number an error, RET_VAL as it was.
    fn extreme(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let largest = call.number == 25;
        let mut best: Option<(u32, f64)> = None;
        for index in 0..3 {
            let (raw, Some(value)) = self.any_number(call, index)? else {
                return Ok(false);
            };
            let better = match best {
                None => true,
                Some((_, kept)) if largest => value > kept,
                Some((_, kept)) => value < kept,
            };
            if better {
                best = Some((raw, value));
            }
        }
        if let Some((raw, _)) = best {
            self.write_arg(call, 3, raw)?;
        }
        Ok(true)
    }

    /// The low end of the analog range: -27648 bipolar, else 0.
    fn analog_low(&mut self, call: &LibraryCall) -> Result<f32, Fault> {
        Ok(if self.read_arg(call, 3)? & 1 != 0 {
            -NOMINAL
        } else {
            0.0
        })
    }

    /// SCALE (IN, HI_LIM, LO_LIM, BIPOLAR, RET_VAL, OUT): OUT = (IN − K1) / (K2 − K1) ×
    /// (HI_LIM − LO_LIM) + LO_LIM; an IN beyond K1 … K2 gives the limit on its side and
    /// RET_VAL 16#0008.
    fn scale(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let input = f32::from(self.read_int(call, 0)?);
        let high = self.read_real(call, 1)?;
        let low = self.read_real(call, 2)?;
        let k1 = self.analog_low(call)?;
        let (out, code) = if input > NOMINAL {
            (high, OUT_OF_RANGE)
        } else if input < k1 {
            (low, OUT_OF_RANGE)
        } else {
            ((input - k1) / (NOMINAL - k1) * (high - low) + low, 0)
        };
        self.write_arg(call, 4, code)?;
        self.write_arg(call, 5, out.to_bits())?;
        Ok(code == 0)
    }

    /// UNSCALE (IN, HI_LIM, LO_LIM, BIPOLAR, RET_VAL, OUT): OUT = (IN − LO_LIM) / (HI_LIM −
    /// LO_LIM) × (K2 − K1) + K1, rounded to the nearest INT; an IN beyond LO_LIM … HI_LIM
    /// gives K1 or K2, the end on its side, and RET_VAL 16#0008.
    fn unscale(&mut self, call: &LibraryCall) -> Result<bool, Fault> {
        let input = self.read_real(call, 0)?;
        let high = self.read_real(call, 1)?;
        let low = self.read_real(call, 2)?;
        let k1 = self.analog_low(call)?;
        let (lowest, highest) = (low.min(high), low.max(high));
        let (out, code) = if input >= lowest && input <= highest {
            let scaled = (input - low) / (high - low) * (NOMINAL - k1) + k1;
            (scaled.round_ties_even(), 0)
        } else if (input < lowest) == (low <= high) {
            (k1, OUT_OF_RANGE)
        } else {
            (NOMINAL, OUT_OF_RANGE)
        };
        self.write_arg(call, 4, code)?;
        self.write_arg(call, 5, out as i16 as u16 as u32)?;
        Ok(code == 0)
    }
}
