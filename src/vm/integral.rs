//! The blocks a CPU has built in, at run time: the integral FBs of the S5-115U (S5-115U manual,
//! chapter on integral blocks) and the system OBs awl does not simulate.
//!
//! Each FB reads its actual parameters, computes, and writes its outputs; the arithmetic is in
//! plain functions below so tests check it against the manual's rules. Decisions where the
//! manual leaves room: results are truncated toward zero; an FB that reports an error through
//! its error bit leaves its value output as it was; FB 250's single sampling (`EINZ`) converts
//! at the call, so `TBIT` is 0 after it.

use crate::compiler::builtin::{Builtin, IntegralFb};
use crate::compiler::bytecode::{BitSource, NO_PARAMS, Op, Width};
use crate::compiler::{Resolved, lower};
use crate::mnemonics::OpCode;

use super::Cpu;
use super::stop::{StopCause, StopDetail};

type Fault = (StopCause, StopDetail);

/// The most parameters an integral FB has (FB 250).
const MAX_PARAMS: usize = 9;

/// Analog modules sit in the peripheral bytes from 128 (S5-115U manual, addressing).
const ANALOG_AREA_START: i32 = 128;

/// The nominal range of an analog input: 2048 units, the value in bits 3–15.
const INPUT_NOMINAL: i32 = 2048;

/// The nominal range of an analog output: 1024 units, the value in bits 4–15.
const OUTPUT_NOMINAL: i32 = 1024;

/// FB 240 `COD:B4`: four BCD decades and a sign bit (1: negative) to a fixed-point number.
pub fn cod_b4(bcd: u16, negative: bool) -> i16 {
    let value = crate::rules::bcd::decode(u32::from(bcd), 4) as i16;
    if negative { -value } else { value }
}

/// FB 241 `COD:16`: a fixed-point number to its sign (true: negative), the fifth decade and
/// the four lower decades in BCD.
pub fn cod_16(value: i16) -> (bool, u8, u16) {
    let magnitude = i32::from(value).unsigned_abs();
    let low = crate::rules::bcd::encode(magnitude, 4) as u16;
    (value < 0, (magnitude / 10_000) as u8, low)
}

/// FB 242 `MUL:16`: the 32-bit product.
pub fn mul_16(first: i16, second: i16) -> i32 {
    i32::from(first) * i32::from(second)
}

/// What FB 243 `DIV:16` gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Division {
    /// `FEH`: division by zero; quotient and remainder are not written.
    pub by_zero: bool,
    /// `OV`: the quotient does not fit in 16 bits (-32768 / -1).
    pub overflow: bool,
    pub quotient: i16,
    pub remainder: i16,
}

/// FB 243 `DIV:16`: quotient and remainder, the remainder with the dividend's sign.
pub fn div_16(dividend: i16, divisor: i16) -> Division {
    let quotient = i32::from(dividend).checked_div(i32::from(divisor));
    let remainder = i32::from(dividend).checked_rem(i32::from(divisor));
    Division {
        by_zero: divisor == 0,
        overflow: quotient.is_some_and(|q| q > i32::from(i16::MAX)),
        quotient: quotient.unwrap_or(0) as i16,
        remainder: remainder.unwrap_or(0) as i16,
    }
}

/// The channel number and channel type of a `KNKT :KY channel,type`.
fn channel(knkt: u16) -> (i32, u8) {
    (i32::from(knkt >> 8), knkt as u8)
}

/// FB 250's result: the scaled value and the range error `BU`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AnalogIn {
    pub value: i16,
    pub range_error: bool,
}

/// FB 250 `RLG:AE`: the module's word `raw` of channel type 3 to 6 scaled to `UGR…OGR`.
/// Types 3 and 4 are unipolar (0…2048 units), 5 and 6 bipolar (-2048…2048); 3 and 5 give
/// the magnitude with the sign in bit 15, 4 and 6 a two's-complement number. Beyond the
/// nominal range, or with the module's overflow bit (bit 0) set, the value is limited and
/// `BU` set. `None` for a channel type outside 3…6.
pub fn read_analog(raw: u16, channel_type: u8, upper: i16, lower: i16) -> Option<AnalogIn> {
    let magnitude = i32::from((raw & 0x7FF8) >> 3);
    let units = match channel_type {
        3 | 5 if raw & 0x8000 != 0 => -magnitude,
        3 | 5 => magnitude,
        4 | 6 => i32::from(raw as i16 >> 3),
        _ => return None,
    };
    let bipolar = channel_type >= 5;
    let low = if bipolar { -INPUT_NOMINAL } else { 0 };
    let limited = units.clamp(low, INPUT_NOMINAL);
    let overflow = raw & 1 != 0;
    let (upper, lower) = (i32::from(upper), i32::from(lower));
    let span = i32::from(bipolar) * INPUT_NOMINAL + INPUT_NOMINAL;
    let value = lower + (upper - lower) * (limited - low) / span;
    Some(AnalogIn {
        value: value.clamp(i16::MIN.into(), i16::MAX.into()) as i16,
        range_error: overflow || limited != units,
    })
}

/// FB 251 `RLG:AA`: `value` in `UGR…OGR` to the module's word for channel type 0 (unipolar,
/// 0…1024 units) or 1 (bipolar, -1024…1024), the units in bits 4–15, and the range error
/// `BU` when `value` lies outside the limits (it is limited). `None` for equal limits or
/// another channel type.
pub fn write_analog(value: i16, channel_type: u8, upper: i16, lower: i16) -> Option<(u16, bool)> {
    let (upper, lower) = (i32::from(upper), i32::from(lower));
    if upper == lower || channel_type > 1 {
        return None;
    }
    let value = i32::from(value);
    let limited = value.clamp(upper.min(lower), upper.max(lower));
    let units = match channel_type {
        0 => OUTPUT_NOMINAL * (limited - lower) / (upper - lower),
        _ => 2 * OUTPUT_NOMINAL * (limited - lower) / (upper - lower) - OUTPUT_NOMINAL,
    };
    Some(((units << 4) as u16, limited != value))
}

impl Cpu {
    /// Runs a built-in block called with actual-parameter list `params`.
    pub(super) fn run_builtin(&mut self, block: Builtin, params: u16) -> Result<(), Fault> {
        let fb = match block {
            Builtin::SystemOb(ob) => {
                let summary = self.profile.system_ob(ob).map_or("", |entry| entry.summary);
                let text = format!(
                    "OB {ob} ({summary}) is a system OB of {} that awl does not simulate",
                    self.profile.name
                );
                return Err((StopCause::Bcf, StopDetail::Text(text)));
            }
            Builtin::Integral(fb) => fb,
        };
        let a = self.actuals(params)?;
        match fb {
            IntegralFb::CodB4 => {
                let value = cod_b4(self.read_word(a[0])?, self.read_bit(a[1])?);
                self.write_word(a[2], value as u16)
            }
            IntegralFb::Cod16 => {
                let (negative, high, low) = cod_16(self.read_word(a[0])? as i16);
                self.write_bit(a[1], negative)?;
                self.write_word(a[2], u16::from(high))?;
                self.write_word(a[3], low)
            }
            IntegralFb::Mul16 => {
                let product = mul_16(self.read_word(a[0])? as i16, self.read_word(a[1])? as i16);
                self.write_bit(a[2], product == 0)?;
                self.write_word(a[3], (product >> 16) as u16)?;
                self.write_word(a[4], product as u16)
            }
            IntegralFb::Div16 => {
                let result = div_16(self.read_word(a[0])? as i16, self.read_word(a[1])? as i16);
                self.write_bit(a[2], result.overflow)?;
                self.write_bit(a[3], result.by_zero)?;
                self.write_bit(a[4], !result.by_zero && result.quotient == 0)?;
                self.write_bit(a[5], !result.by_zero && result.remainder == 0)?;
                if !result.by_zero {
                    self.write_word(a[6], result.quotient as u16)?;
                    self.write_word(a[7], result.remainder as u16)?;
                }
                Ok(())
            }
            IntegralFb::RlgAe => self.analog_input(&a),
            IntegralFb::RlgAa => self.analog_output(&a),
        }
    }

    /// FB 250: BG, KNKT, OGR, UGR, EINZ, XA, FB, BU, TBIT.
    fn analog_input(&mut self, a: &[Resolved; MAX_PARAMS]) -> Result<(), Fault> {
        let (number, channel_type) = channel(self.read_word(a[1])?);
        let (upper, lower) = (self.read_word(a[2])? as i16, self.read_word(a[3])? as i16);
        self.read_bit(a[4])?;
        let module = self.read_word(a[0])?;
        let byte = self.module_word(module, number, 15);
        let result = match byte {
            Some(byte) => {
                let raw = self.read_periphery(Width::Word, byte, false) as u16;
                // Bit 1: the module reports a fault (a wire break).
                read_analog(raw, channel_type, upper, lower).filter(|_| raw & 2 == 0)
            }
            None => None,
        };
        if let Some(result) = result {
            self.write_word(a[5], result.value as u16)?;
        }
        self.write_bit(a[6], result.is_none())?;
        self.write_bit(a[7], result.is_some_and(|result| result.range_error))?;
        self.write_bit(a[8], false)
    }

    /// FB 251: XE, BG, KNKT, OGR, UGR, FEH, BU.
    fn analog_output(&mut self, a: &[Resolved; MAX_PARAMS]) -> Result<(), Fault> {
        let value = self.read_word(a[0])? as i16;
        let (number, channel_type) = channel(self.read_word(a[2])?);
        let (upper, lower) = (self.read_word(a[3])? as i16, self.read_word(a[4])? as i16);
        let module = self.read_word(a[1])?;
        let byte = self.module_word(module, number, 7);
        let result = byte.zip(write_analog(value, channel_type, upper, lower));
        if let Some((byte, (raw, _))) = result {
            self.write_periphery(Width::Word, byte, u32::from(raw), false);
        }
        self.write_bit(a[5], result.is_none())?;
        self.write_bit(a[6], result.is_some_and(|(_, (_, range))| range))
    }

    /// The peripheral byte of channel `number` of the module at `BG`, if the module lies in
    /// the analog area and the channel on the CPU's peripheral bytes.
    fn module_word(&self, module: u16, number: i32, last_channel: i32) -> Option<u16> {
        let module = i32::from(module as i16);
        let at = module + 2 * number;
        let peripheral = i32::from(self.profile.sizes.peripheral_bytes);
        (module >= ANALOG_AREA_START && number <= last_channel && at + 2 <= peripheral)
            .then_some(at as u16)
    }

    /// The actual parameters of list `params`, parameters passed on from a calling FB
    /// resolved.
    fn actuals(&self, params: u16) -> Result<[Resolved; MAX_PARAMS], Fault> {
        let mut actuals = [Resolved::None; MAX_PARAMS];
        let list = self.program.param_lists.get(usize::from(params));
        for (slot, actual) in actuals.iter_mut().zip(list.into_iter().flatten()) {
            *slot = match *actual {
                Resolved::Formal(param) => self.actual(param).ok_or_else(|| unusable(param))?,
                other => other,
            };
        }
        Ok(actuals)
    }

    fn read_word(&mut self, actual: Resolved) -> Result<u16, Fault> {
        let value = match lower::lower(OpCode::Load, actual, self.program.layout, NO_PARAMS) {
            Some(Op::LoadImageWord(byte)) => self.read_image(Width::Word, byte),
            Some(Op::LoadData(part, word)) => self.read_data(part, word)?,
            Some(Op::LoadPeripheral {
                width,
                byte,
                extended,
            }) => self.read_periphery(width, byte, extended),
            Some(Op::LoadConstant(value)) => value,
            _ => return Err(unusable(0)),
        };
        Ok(value as u16)
    }

    fn read_bit(&mut self, actual: Resolved) -> Result<bool, Fault> {
        match lower::lower(OpCode::And, actual, self.program.layout, NO_PARAMS) {
            Some(Op::And(bit)) => Ok(self.image_bit(bit)),
            Some(Op::LogicOther(_, BitSource::Data { word, bit })) => self.data_bit(word, bit),
            Some(Op::LogicOther(_, BitSource::Timer(n))) => {
                Ok(self.timers[usize::from(n)].bit(self.clock))
            }
            Some(Op::LogicOther(_, BitSource::Counter(n))) => {
                Ok(self.counters[usize::from(n)].bit())
            }
            _ => Err(unusable(0)),
        }
    }

    fn write_word(&mut self, actual: Resolved, value: u16) -> Result<(), Fault> {
        let value = u32::from(value);
        match lower::lower(OpCode::Transfer, actual, self.program.layout, NO_PARAMS) {
            Some(Op::TransferImageWord(byte)) => self.write_image(Width::Word, byte, value),
            Some(Op::TransferImageByte(byte)) => self.write_image(Width::Byte, byte, value),
            Some(Op::TransferData(part, word)) => self.write_data(part, word, value)?,
            Some(Op::TransferPeripheral {
                width,
                byte,
                extended,
            }) => self.write_periphery(width, byte, value, extended),
            _ => return Err(unusable(0)),
        }
        Ok(())
    }

    fn write_bit(&mut self, actual: Resolved, value: bool) -> Result<(), Fault> {
        match lower::lower(OpCode::Assign, actual, self.program.layout, NO_PARAMS) {
            Some(Op::Assign(bit)) => self.write_image_bit(bit, value),
            Some(Op::WriteData { word, bit, .. }) => self.write_data_bit(word, bit, value)?,
            _ => return Err(unusable(0)),
        }
        Ok(())
    }
}

/// An actual parameter that cannot be read or written as the integral FB needs: only a
/// parameter passed on from a calling FB can be one, as the compiler checks the rest.
fn unusable(param: u8) -> Fault {
    let text = format!(
        "an integral FB's parameter {} cannot be used here",
        param + 1
    );
    (StopCause::Bcf, StopDetail::Text(text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bcd_conversions() {
        assert_eq!(cod_b4(0x1234, false), 1234);
        assert_eq!(cod_b4(0x9999, true), -9999);
        assert_eq!(cod_16(-32768), (true, 3, 0x2768));
        assert_eq!(cod_16(12345), (false, 1, 0x2345));
        assert_eq!(cod_16(0), (false, 0, 0));
    }

    #[test]
    fn multiplication_and_division() {
        assert_eq!(mul_16(-300, 200), -60_000);
        assert_eq!(mul_16(i16::MIN, i16::MIN), 1 << 30);
        let division = div_16(-7, 2);
        assert_eq!((division.quotient, division.remainder), (-3, -1));
        assert!(div_16(5, 0).by_zero);
        let overflow = div_16(i16::MIN, -1);
        assert!(overflow.overflow && !overflow.by_zero);
    }

    #[test]
    fn analog_input_scaling() {
        // Bipolar fixed point: -2048…2048 units to -1000…1000; half scale is 1024 units.
        let half = read_analog(1024 << 3, 6, 1000, -1000).unwrap();
        assert_eq!(
            half,
            AnalogIn {
                value: 500,
                range_error: false
            }
        );
        let negative = read_analog((-2048i16 << 3) as u16, 6, 1000, -1000).unwrap();
        assert_eq!(negative.value, -1000);
        // Unipolar: 0…2048 units to 0…100.
        assert_eq!(read_analog(512 << 3, 4, 100, 0).unwrap().value, 25);
        // Absolute-value representation: the sign in bit 15.
        assert_eq!(
            read_analog(0x8000 | 1024 << 3, 5, 1000, -1000)
                .unwrap()
                .value,
            -500
        );
        // Above the nominal range: limited to OGR, BU set; the overflow bit alone sets BU.
        let over = read_analog(3000 << 3, 6, 1000, -1000).unwrap();
        assert_eq!(
            over,
            AnalogIn {
                value: 1000,
                range_error: true
            }
        );
        assert!(read_analog(1, 6, 1000, -1000).unwrap().range_error);
        assert_eq!(read_analog(0, 7, 1000, -1000), None);
    }

    #[test]
    fn analog_output_scaling() {
        assert_eq!(
            write_analog(50, 0, 100, 0),
            Some(((512 << 4) as u16, false))
        );
        assert_eq!(
            write_analog(-1000, 1, 1000, -1000),
            Some(((-1024i32 << 4) as u16, false))
        );
        assert_eq!(
            write_analog(150, 0, 100, 0),
            Some(((1024 << 4) as u16, true))
        );
        assert_eq!(write_analog(5, 0, 7, 7), None);
        assert_eq!(write_analog(5, 2, 100, 0), None);
    }
}
