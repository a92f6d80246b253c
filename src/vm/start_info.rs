//! The start information of a STEP 7 OB: the first 20 bytes of its local data, which the
//! operating system writes before the OB's first operation ("System Software for S7-300/400
//! System and Standard Functions", Organization Blocks, the local data of each OB; VIPA SPEED7
//! operation list, Organization Blocks). A program reads them by address (`L LB 1`) or by the
//! names its OB declares in `VAR_TEMP`, which STEP 7 lays out from byte 0 in declaration order.
//!
//! Every OB: byte 0 the event class, byte 1 the event number, byte 2 the priority class, byte 3
//! the OB number, bytes 4–11 what the OB's table gives, bytes 12–19 the DATE_AND_TIME the OB
//! was started. awl's clock is the simulated time since the run began, which is
//! [`START_DATE`]: the CPU's clock starts there.

use crate::step7::literal::date_and_time_bytes;

use super::interrupts::{Cause, Request};
use super::{Cpu, IDLE};

/// The date and time a run begins at, for the DATE_AND_TIME of the start information.
pub const START_DATE: &str = "2024-01-01 00:00:00.000 (a Monday)";

/// [`START_DATE`] as days after 1990-01-01, the origin of STEP 7's dates.
pub const START_DAY: u32 = 12_418;

pub use crate::step7::layout::START_INFO_BYTES;

/// The bytes before the DATE_AND_TIME.
pub type Head = [u8; 12];

/// Event class 1, "start events of standard OBs", identifier 1 ("System Software for
/// S7-300/400", SFC 6 RD_SINFO): OB 1 and the hardware interrupt OBs.
const STANDARD_OB: u8 = 0x11;
/// Event class 1, identifier 3: a startup OB.
const STARTUP_OB: u8 = 0x13;
/// Event class 3 ("asynchronous error"), identifier 9: an incoming event (OB 82).
const INCOMING_ERROR: u8 = 0x39;
/// Event class 3, identifier 5: OB 85's start events for an OB not loaded, and OB 80's.
const OB85_EVENT: u8 = 0x35;
/// OB 85's error code: "a start event for an OB that is not loaded on the CPU".
const OB_NOT_LOADED: u8 = 0xA1;
/// OB 80's error code 16#02: "The called OB is still being executed" ("System Software for
/// S7-300/400 System and Standard Functions", 1.16).
const OB_STILL_RUNNING: u8 = 0x02;
/// The first cyclic interrupt OB; OB 30 + n has event number 16#31 + n (OB 35: 16#36).
const FIRST_CYCLIC_OB: u8 = 30;
/// Event class 3, identifier 8: an outgoing event (OB 86: a station's return).
const OUTGOING_ERROR: u8 = 0x38;
/// OB 86's error code 16#C4: "failure of a DP station" (VIPA SPEED7 operation list, OB 86).
const DP_STATION_FAILURE: u8 = 0xC4;
/// OB86_MDL_ADDR: the logical base address of the DP master, awl's one master system.
const DP_MASTER_ADDRESS: u16 = 2047;
/// The DP master system ID in OB86_Z23 (bits 8–15).
const DP_MASTER_SYSTEM: u8 = 1;
/// OB 82's error code.
const DIAGNOSTIC_INTERRUPT: u8 = 0x42;
/// OB40_IO_FLAG, OB82_IO_FLAG: the module is an input module (awl's modules are).
const INPUT_MODULE: u8 = 0x54;
/// OB 82's first diagnostic byte (OB82_MDL_DEFECT, OB82_PNT_INFO): a fault of the module, on
/// a channel; the lost event is the channel's.
const CHANNEL_FAULT: u8 = 0x09;
/// The startup OBs' priority class.
const STARTUP_PRIORITY: u8 = 27;

/// The first hardware interrupt OB; OB 40 + n has event number 16#41 + n ("interrupt via
/// interrupt line n + 1").
const FIRST_HW_OB: u8 = 40;

impl Cpu {
    /// Writes the running level's OB's start information at the start of its local data.
    /// Only STEP 7 programs have an L stack; a level too deep for it gets none (its first
    /// access to its local data stops the CPU). Nothing when the start information is switched
    /// off ([`Cpu::writes_start_info`]).
    pub(super) fn write_start_info(&mut self, head: Head) {
        if !self.writes_start_info {
            return;
        }
        let start = self.level.local_base as usize;
        let Some(info) = self.local.get_mut(start..start + START_INFO_BYTES as usize) else {
            return;
        };
        info[..12].copy_from_slice(&head);
        let bytes = self.date_and_time();
        let start = self.level.local_base as usize;
        self.local[start + 12..start + START_INFO_BYTES as usize].copy_from_slice(&bytes);
    }

    /// The CPU's clock as a DATE_AND_TIME: [`START_DATE`] plus the simulated time, as far as
    /// SFC 0 (SET_CLK) moved it.
    pub(crate) fn date_and_time(&self) -> [u8; 8] {
        let ms = self.clock_ms();
        let days = ms / 86_400_000;
        date_and_time_bytes(
            u32::try_from(days).unwrap_or(u32::MAX),
            (ms % 86_400_000) as u32,
        )
    }

    /// The CPU's clock in milliseconds since 1990-01-01, the origin of STEP 7's dates.
    pub(crate) fn clock_ms(&self) -> u64 {
        let ms = i64::from(START_DAY) * 86_400_000 + (self.clock / 1_000_000) as i64;
        ms.saturating_add(self.clock_set_ms).max(0) as u64
    }

    /// OB 1's: OB1_SCAN_1 (byte 1) is 1 in the first cycle after a warm restart (OB 100), 4
    /// after a cold restart (OB 102), 3 in every other; OB1_PREV_CYCLE, OB1_MIN_CYCLE and
    /// OB1_MAX_CYCLE (INTs at bytes 6, 8 and 10) are the completed cycles' times in ms, 0
    /// before the first has completed.
    pub(super) fn cycle_start_info(&self) -> Head {
        let scan = match (self.cycle_times.count, self.startup_ob()) {
            (0, Some((102, _))) => 4,
            (0, _) => 1,
            _ => 3,
        };
        let times = &self.cycle_times;
        let [prev, min, max] =
            [times.last_ns, times.min_ns, times.max_ns].map(|ns| ms_int(ns).to_be_bytes());
        [
            STANDARD_OB,
            scan,
            1,
            1,
            0,
            0,
            prev[0],
            prev[1],
            min[0],
            min[1],
            max[0],
            max[1],
        ]
    }

    /// A startup OB's: OB10x_STRTUP a manual warm restart (16#81, OB 100) or cold restart
    /// (16#85, OB 102), as by the mode selector; OB10x_STOP (bytes 6–7) 0, as a run begins in
    /// STOP with no event before it; OB10x_STRT_INFO (bytes 8–11): the restart just completed
    /// was triggered with the mode selector, automatic and manual startup permitted.
    pub(super) fn startup_start_info(ob: u8) -> Head {
        let (request, completed) = if ob == 102 {
            (0x85, 0x07)
        } else {
            (0x81, 0x03)
        };
        [
            STARTUP_OB,
            request,
            STARTUP_PRIORITY,
            ob,
            0,
            0,
            0,
            0,
            0,
            completed,
            0x77,
            0x03,
        ]
    }

    /// An interrupt OB's, from its request.
    pub(super) fn interrupt_start_info(&self, request: &Request, priority: u8) -> Head {
        let ob = request.ob;
        match (ob, request.cause) {
            (82, cause) => {
                let (address, diagnosis) = match cause {
                    Cause::LostChannel { module } => (self.module_address(module), CHANNEL_FAULT),
                    _ => (0, 0),
                };
                let address = address.to_be_bytes();
                [
                    INCOMING_ERROR,
                    DIAGNOSTIC_INTERRUPT,
                    priority,
                    ob,
                    0,
                    INPUT_MODULE,
                    address[0],
                    address[1],
                    diagnosis,
                    0,
                    0,
                    0,
                ]
            }
            (85, cause) => {
                let (z1, missing) = match cause {
                    Cause::MissingOb {
                        ob,
                        module,
                        active_ob,
                        active_priority,
                    } => (
                        self.module_address(module),
                        [STANDARD_OB, hw_event(ob), active_priority, active_ob],
                    ),
                    _ => (0, [0; 4]),
                };
                let z1 = z1.to_be_bytes();
                [
                    OB85_EVENT,
                    OB_NOT_LOADED,
                    priority,
                    ob,
                    0,
                    0,
                    z1[0],
                    z1[1],
                    missing[0],
                    missing[1],
                    missing[2],
                    missing[3],
                ]
            }
            // OB80_ERROR_INFO (bytes 6–7) is a temporary variable of the OB that could not
            // start, which the manual leaves unnamed for a cyclic OB: awl writes 0.
            (80, cause) => {
                let missed = match cause {
                    Cause::TimeError { ob, priority } => {
                        [STANDARD_OB, cyclic_event(ob), priority, ob]
                    }
                    _ => [0; 4],
                };
                [
                    OB85_EVENT,
                    OB_STILL_RUNNING,
                    priority,
                    ob,
                    0,
                    0,
                    0,
                    0,
                    missed[0],
                    missed[1],
                    missed[2],
                    missed[3],
                ]
            }
            // OB86_Z23 (bytes 8–11): the station's number (bits 0–7) and its master system
            // (bits 8–15); its own logical address (bits 16–30) is 0, an input (bit 31 0).
            (86, cause) => {
                let (class, station) = match cause {
                    Cause::Station { station, failed } => (
                        if failed {
                            INCOMING_ERROR
                        } else {
                            OUTGOING_ERROR
                        },
                        station,
                    ),
                    _ => (INCOMING_ERROR, 0),
                };
                let master = DP_MASTER_ADDRESS.to_be_bytes();
                [
                    class,
                    DP_STATION_FAILURE,
                    priority,
                    ob,
                    0,
                    0,
                    master[0],
                    master[1],
                    0,
                    0,
                    DP_MASTER_SYSTEM,
                    station,
                ]
            }
            // OB35_PHASE_OFFSET (bytes 6–7) 0, OB35_EXC_FREQ (bytes 10–11) the interval in ms.
            (30..=38, _) => {
                let ms = ms_int(self.engine.config.ob35_interval_ns).to_be_bytes();
                [
                    STANDARD_OB,
                    cyclic_event(ob),
                    priority,
                    ob,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    ms[0],
                    ms[1],
                ]
            }
            (40..=47, _) => {
                let (address, points) = match request.hardware {
                    Some(source) => (
                        self.module_address(source.module),
                        1u32.checked_shl(u32::from(source.channel)).unwrap_or(0),
                    ),
                    None => (0, 0),
                };
                let address = address.to_be_bytes();
                let points = points.to_be_bytes();
                [
                    STANDARD_OB,
                    hw_event(ob),
                    priority,
                    ob,
                    0,
                    INPUT_MODULE,
                    address[0],
                    address[1],
                    points[0],
                    points[1],
                    points[2],
                    points[3],
                ]
            }
            _ => [0, 0, priority, ob, 0, 0, 0, 0, 0, 0, 0, 0],
        }
    }

    /// A module's logical base address ([[hw_module]] `address`; its number without one).
    fn module_address(&self, module: u16) -> u16 {
        self.engine.config.module_address(module)
    }

    /// The startup OB the CPU runs: the first of the profile's that the program has, with its
    /// block.
    pub(super) fn startup_ob(&self) -> Option<(u8, u16)> {
        self.profile
            .startup_obs
            .iter()
            .find_map(|&ob| self.program.ob(ob).map(|block| (ob, block)))
    }

    /// The OB running now and its priority class, for OB 85's start information: the
    /// operating system's own work between the parts of the cycle counts as OB 1's.
    pub(super) fn active_ob(&self) -> (u8, u8) {
        let block = self.level_block();
        let number = if block == IDLE {
            1
        } else {
            u8::try_from(self.block_id(block).number).unwrap_or(0)
        };
        match self.running_priority() {
            0 if self.mode == super::Mode::Startup => (number, STARTUP_PRIORITY),
            0 => (number, 1),
            priority => (number, priority),
        }
    }
}

/// A hardware interrupt OB's event number.
fn hw_event(ob: u8) -> u8 {
    0x41u8.wrapping_add(ob.wrapping_sub(FIRST_HW_OB))
}

/// A cyclic interrupt OB's event number.
fn cyclic_event(ob: u8) -> u8 {
    0x31u8.wrapping_add(ob.wrapping_sub(FIRST_CYCLIC_OB))
}

/// Nanoseconds as an INT of milliseconds, at most 32767.
fn ms_int(ns: u64) -> i16 {
    i16::try_from(ns / 1_000_000).unwrap_or(i16::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::step7::literal::typed;

    #[test]
    fn the_start_day_is_the_documented_date() {
        let literal = typed("DT#2024-01-01-00:00:00.000").unwrap();
        assert_eq!(date_and_time_bytes(START_DAY, 0).to_vec(), literal.bytes);
        assert!(START_DATE.starts_with("2024-01-01"));
    }

    #[test]
    fn hardware_interrupt_ob_events_count_from_16_41() {
        assert_eq!(hw_event(40), 0x41);
        assert_eq!(hw_event(41), 0x42);
    }

    #[test]
    fn cyclic_interrupt_obs_count_from_16_31() {
        assert_eq!(cyclic_event(35), 0x36);
    }

    #[test]
    fn cycle_times_saturate_at_the_largest_int() {
        assert_eq!(ms_int(1_999_999), 1);
        assert_eq!(ms_int(40_000_000_000), i16::MAX);
    }
}
