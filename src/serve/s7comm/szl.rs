//! The system status lists (SZL) awl answers, and the clock's answer, built from what the CPU
//! reports of itself ("System Software for S7-300/400 System and Standard Functions", System
//! Status Lists): a partial list is its id, index, the length of one record, the number of
//! records, then the records.

use crate::serve::request::{CpuMode, CpuStatus};
use crate::step7::literal::{date_and_time_of_instant, date_and_time_year};

/// The list of the SZL ids awl has.
const LIST: u16 = 0x0000;
/// Module identification: order code and versions.
const MODULE_IDENTIFICATION: u16 = 0x0011;
/// Component identification: station and module names, copyright, serial number, module type.
const COMPONENT_IDENTIFICATION: u16 = 0x001C;
/// The current operating mode (the last mode transition).
const MODE: u16 = 0x0424;
const ANSWERED: [u16; 4] = [LIST, MODULE_IDENTIFICATION, COMPONENT_IDENTIFICATION, MODE];

/// The operating mode codes of SZL 0x0424's mode byte.
const MODE_STOP: u8 = 0x04;
const MODE_STARTUP: u8 = 0x05;
const MODE_RUN: u8 = 0x08;

/// The partial list `id` with `index` (both echoed first), or `None` when awl has no such list.
pub fn partial_list(id: u16, index: u16, status: &CpuStatus) -> Option<Vec<u8>> {
    let (record_length, records) = match (id, index) {
        (LIST, 0) => (2, ANSWERED.iter().flat_map(|id| id.to_be_bytes()).collect()),
        (MODULE_IDENTIFICATION, 0) => (28, module_identification(status)),
        (COMPONENT_IDENTIFICATION, 0) => (34, component_identification(status)),
        (MODE, 0) => (20, mode(status)),
        _ => return None,
    };
    let count = records.len() / record_length;
    let mut list = Vec::with_capacity(8 + records.len());
    for word in [id, index, record_length as u16, count as u16] {
        list.extend_from_slice(&word.to_be_bytes());
    }
    list.extend_from_slice(&records);
    Some(list)
}

/// awl's version, as a module's firmware version.
fn version() -> [u8; 3] {
    let mut parts = env!("CARGO_PKG_VERSION")
        .split('.')
        .map(|part| part.parse::<u8>().unwrap_or(0));
    [(); 3].map(|()| parts.next().unwrap_or(0))
}

/// Records 0x0001 (the module: its order code) and 0x0007 (the firmware: 'V' and the
/// version): index, 20 characters of order code, module type, two version words.
fn module_identification(status: &CpuStatus) -> Vec<u8> {
    let [major, minor, patch] = version();
    let mut records = Vec::with_capacity(2 * 28);
    for (index, name, versions) in [
        (1u16, status.order_code.as_str(), [0, 0, 0, 0]),
        (7, "", [b'V', major, minor, patch]),
    ] {
        records.extend_from_slice(&index.to_be_bytes());
        records.extend_from_slice(&padded(name, 20, b' '));
        records.extend_from_slice(&[0, 0]);
        records.extend_from_slice(&versions);
    }
    records
}

/// Records 0x0001 to 0x0005, 0x0007, 0x0008 and 0x000B: index and a text field of 32 bytes,
/// its text as long as the record's field (24 characters, 26 for the copyright, 32 for the
/// module type and the location).
fn component_identification(status: &CpuStatus) -> Vec<u8> {
    let module = format!("awl {}", status.profile);
    let texts = [
        (1u16, "awl", 24),
        (2, module.as_str(), 24),
        (3, "", 32),
        (4, "awl, MIT licence", 26),
        (5, "AWL 0000001", 24),
        (7, module.as_str(), 32),
        // The memory card's serial number and the location designation: none.
        (8, "", 32),
        (11, "", 32),
    ];
    let mut records = Vec::with_capacity(texts.len() * 34);
    for (index, text, length) in texts {
        records.extend_from_slice(&index.to_be_bytes());
        records.extend_from_slice(&padded(text, length, 0));
        records.resize(records.len() + 32 - length, 0);
    }
    records
}

/// `text` cut or filled with `fill` to `length` bytes.
fn padded(text: &str, length: usize, fill: u8) -> Vec<u8> {
    let mut bytes: Vec<u8> = text.bytes().take(length).collect();
    bytes.resize(length, fill);
    bytes
}

/// The one record of SZL 0x0424: event id, an unused byte, the mode (a whole byte, as clients
/// compare it: 0x08 RUN, 0x04 STOP), four reserved bytes, then the time of the CPU's clock.
fn mode(status: &CpuStatus) -> Vec<u8> {
    let mode = match status.mode {
        CpuMode::Run => MODE_RUN,
        CpuMode::Stop => MODE_STOP,
        CpuMode::Startup => MODE_STARTUP,
    };
    let mut record = vec![0, 0, 0, mode, 0, 0, 0, 0, 0, 0, 0, 0];
    record.extend_from_slice(&date_and_time_of_instant(status.clock_ms));
    record
}

/// The clock's answer: a reserved byte, the century in BCD, then the DATE_AND_TIME of the CPU's
/// clock.
pub fn clock(status: &CpuStatus) -> [u8; 10] {
    let date_and_time = date_and_time_of_instant(status.clock_ms);
    let century = date_and_time_year(date_and_time[0]).map_or(19, |year| year / 100);
    let mut answer = [0u8; 10];
    answer[1] = (century / 10 * 16 + century % 10) as u8;
    answer[2..].copy_from_slice(&date_and_time);
    answer
}

#[cfg(test)]
mod tests {
    use super::*;

    fn status(mode: CpuMode, clock_ms: i64) -> CpuStatus {
        CpuStatus {
            mode,
            profile: "speed7",
            order_code: "6ES7 315-2AG10-0AB0".to_string(),
            clock_ms,
            cycles: 0,
        }
    }

    /// 2024-05-17 13:45:30.250: 12 555 days after 1990-01-01.
    const CLOCK_MS: i64 = 12_555 * 86_400_000 + ((13 * 60 + 45) * 60 + 30) * 1000 + 250;

    #[test]
    fn the_clock_answer_is_the_century_and_a_date_and_time() {
        assert_eq!(
            clock(&status(CpuMode::Run, CLOCK_MS)),
            [0, 0x20, 0x24, 0x05, 0x17, 0x13, 0x45, 0x30, 0x25, 0x06]
        );
        assert_eq!(clock(&status(CpuMode::Run, 0))[..4], [0, 0x19, 0x90, 0x01]);
    }

    #[test]
    fn the_mode_list_holds_the_mode_byte_clients_read() {
        let run = partial_list(MODE, 0, &status(CpuMode::Run, CLOCK_MS)).unwrap();
        assert_eq!(run[..8], [0x04, 0x24, 0, 0, 0, 20, 0, 1]);
        // Clients read the mode as the eighth byte after the id and index.
        assert_eq!(run[4 + 7], MODE_RUN);
        assert_eq!(run[20..], [0x24, 0x05, 0x17, 0x13, 0x45, 0x30, 0x25, 0x06]);
        let stop = partial_list(MODE, 0, &status(CpuMode::Stop, 0)).unwrap();
        assert_eq!(stop[4 + 7], MODE_STOP);
    }

    #[test]
    fn module_identification_names_the_order_code_and_awls_version() {
        let list = partial_list(MODULE_IDENTIFICATION, 0, &status(CpuMode::Run, 0)).unwrap();
        assert_eq!(list[..8], [0, 0x11, 0, 0, 0, 28, 0, 2]);
        assert_eq!(&list[8..10], &[0, 1]);
        assert_eq!(&list[10..30], b"6ES7 315-2AG10-0AB0 ");
        let firmware = &list[36..64];
        assert_eq!(&firmware[..2], &[0, 7]);
        assert_eq!(firmware[24], b'V');
        assert_eq!(firmware[25..], version());
    }

    #[test]
    fn component_identification_has_the_fields_at_their_places() {
        let list = partial_list(COMPONENT_IDENTIFICATION, 0, &status(CpuMode::Run, 0)).unwrap();
        assert_eq!(list[..8], [0, 0x1C, 0, 0, 0, 34, 0, 8]);
        let records = &list[8..];
        let text = |at: usize, length: usize| {
            String::from_utf8_lossy(&records[at..at + length])
                .trim_end_matches('\0')
                .to_string()
        };
        assert_eq!(text(2, 24), "awl");
        assert_eq!(text(34 + 2, 24), "awl speed7");
        assert_eq!(text(3 * 34 + 2, 26), "awl, MIT licence");
        assert_eq!(text(4 * 34 + 2, 24), "AWL 0000001");
        assert_eq!(text(5 * 34 + 2, 32), "awl speed7");
    }

    #[test]
    fn lists_awl_does_not_have_are_none() {
        let status = status(CpuMode::Run, 0);
        assert_eq!(partial_list(0x0132, 4, &status), None);
        assert_eq!(partial_list(MODULE_IDENTIFICATION, 1, &status), None);
        let list = partial_list(LIST, 0, &status).unwrap();
        assert_eq!(list[8..], [0, 0, 0, 0x11, 0, 0x1C, 0x04, 0x24]);
    }
}
