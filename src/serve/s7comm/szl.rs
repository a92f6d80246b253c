//! The system status lists (SZL) awl answers, and the clock's answer, built from what the CPU
//! reports of itself ("System Software for S7-300/400 System and Standard Functions", System
//! Status Lists; the VIPA SPEED7 Operation list, SSL System status list): a partial list is its
//! id, index, the length of one record, the number of records, then the records. Values a real
//! module reports of its hardware are an S7-300's, the CPU 315-2 PN/DP a SPEED7 is configured
//! as; those of the connection (the PDU, the connections) are what awl serves.

use crate::serve::request::{CpuMode, CpuStatus};
use crate::step7::literal::{date_and_time_of_instant, date_and_time_year};

/// The list of the SZL ids awl has.
const LIST: u16 = 0x0000;
/// Module identification: order code and versions.
const MODULE_IDENTIFICATION: u16 = 0x0011;
/// Component identification: station and module names, copyright, serial number, module type.
const COMPONENT_IDENTIFICATION: u16 = 0x001C;
/// One record of the module identification, by its index.
const ONE_MODULE_IDENTIFICATION: u16 = 0x0111;
/// The communication capability parameters, by index.
const COMMUNICATION_CAPABILITIES: u16 = 0x0131;
/// The status data of one communication section of the CPU, by index.
const COMMUNICATION_STATUS: u16 = 0x0132;
/// The same for the CPU (each CPU of an H system); clients ask it for the protection.
const CPU_COMMUNICATION_STATUS: u16 = 0x0232;
/// The current operating mode (the last mode transition).
const MODE: u16 = 0x0424;
const ANSWERED: [u16; 8] = [
    LIST,
    MODULE_IDENTIFICATION,
    COMPONENT_IDENTIFICATION,
    ONE_MODULE_IDENTIFICATION,
    COMMUNICATION_CAPABILITIES,
    COMMUNICATION_STATUS,
    CPU_COMMUNICATION_STATUS,
    MODE,
];

/// The index of SZL 0x0131's general communication data.
const GENERAL_COMMUNICATION: u16 = 0x0001;
/// The index of SZL 0x0132's and 0x0232's protection levels and switch settings.
const PROTECTION: u16 = 0x0004;
/// The records of SZL 0x0131 and 0x0132 are 20 words long.
const COMMUNICATION_RECORD: usize = 40;
/// The records of SZL 0x0011.
const MODULE_RECORD: usize = 28;

/// The data rates a CPU 315-2 PN/DP reports: its MPI interface's (12 Mbit/s) and its
/// communication bus's (187.5 kbit/s), in bit/s.
const MPI_RATE: u32 = 12_000_000;
const COMMUNICATION_BUS_RATE: u32 = 187_500;

/// The protection levels of SZL 0x0232 index 4: 1 none, 2 write protection.
const NO_PROTECTION: u16 = 1;
const WRITE_PROTECTION: u16 = 2;
/// The mode selector's setting RUN-P, where a CPU is read and written without a password.
const SELECTOR_RUN_P: u16 = 2;
/// No startup switch (CRST/WRST): an S7-300 has none.
const NO_STARTUP_SWITCH: u16 = 0;

/// What the server reports of its communication (SZL 0x0131): the longest PDU it negotiates
/// and the connections it serves at once.
#[derive(Debug, Clone, Copy)]
pub struct Communication {
    pub largest_pdu: u16,
    pub max_connections: u16,
}

/// The operating mode codes of SZL 0x0424's mode byte.
const MODE_STOP: u8 = 0x04;
const MODE_STARTUP: u8 = 0x05;
const MODE_RUN: u8 = 0x08;
const MODE_HOLD: u8 = 0x0A;

/// The partial list `id` with `index` (both echoed first), or `None` when awl has no such list.
pub fn partial_list(
    id: u16,
    index: u16,
    status: &CpuStatus,
    communication: Communication,
) -> Option<Vec<u8>> {
    let (record_length, records) = match (id, index) {
        (LIST, 0) => (2, words(&ANSWERED)),
        (MODULE_IDENTIFICATION, 0) => (MODULE_RECORD, module_identification(status)),
        (ONE_MODULE_IDENTIFICATION, index) => {
            let records = module_identification(status);
            (MODULE_RECORD, record(&records, MODULE_RECORD, index)?)
        }
        (COMPONENT_IDENTIFICATION, 0) => (34, component_identification(status)),
        (COMMUNICATION_CAPABILITIES, GENERAL_COMMUNICATION) => {
            (COMMUNICATION_RECORD, general_communication(communication))
        }
        (COMMUNICATION_STATUS | CPU_COMMUNICATION_STATUS, PROTECTION) => {
            (COMMUNICATION_RECORD, protection(status))
        }
        (MODE, 0) => (20, mode(status)),
        _ => return None,
    };
    let count = records.len() / record_length;
    let mut list = words(&[id, index, record_length as u16, count as u16]);
    list.extend_from_slice(&records);
    Some(list)
}

/// `words` big-endian, as the lists hold them.
fn words(words: &[u16]) -> Vec<u8> {
    words.iter().flat_map(|word| word.to_be_bytes()).collect()
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
    let mut records = Vec::with_capacity(2 * MODULE_RECORD);
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

/// The record of `records` (each `length` bytes, its index first) whose index is `index`.
fn record(records: &[u8], length: usize, index: u16) -> Option<Vec<u8>> {
    records
        .chunks(length)
        .find(|record| record[..2] == index.to_be_bytes())
        .map(<[u8]>::to_vec)
}

/// The record of SZL 0x0131 index 1: the index, the longest PDU, the connections at once, the
/// MPI's and the communication bus's data rates, then reserved bytes.
fn general_communication(communication: Communication) -> Vec<u8> {
    let mut record = words(&[
        GENERAL_COMMUNICATION,
        communication.largest_pdu,
        communication.max_connections,
    ]);
    record.extend_from_slice(&MPI_RATE.to_be_bytes());
    record.extend_from_slice(&COMMUNICATION_BUS_RATE.to_be_bytes());
    record.resize(COMMUNICATION_RECORD, 0);
    record
}

/// The record of SZL 0x0232 (and 0x0132) index 4: the index, the protection level set with the
/// mode selector, the one set in the parameters (0: no password), the valid one, the mode
/// selector's and the startup switch's settings, then version ids awl leaves invalid (0).
/// awl's mode selector stands at RUN-P; `--read-only` is a write protection set in the
/// parameters, as a password sets one.
fn protection(status: &CpuStatus) -> Vec<u8> {
    let (parameters, valid) = if status.read_only {
        (WRITE_PROTECTION, WRITE_PROTECTION)
    } else {
        (0, NO_PROTECTION)
    };
    let mut record = words(&[
        PROTECTION,
        NO_PROTECTION,
        parameters,
        valid,
        SELECTOR_RUN_P,
        NO_STARTUP_SWITCH,
    ]);
    record.resize(COMMUNICATION_RECORD, 0);
    record
}

/// `text` cut or filled with `fill` to `length` bytes.
fn padded(text: &str, length: usize, fill: u8) -> Vec<u8> {
    let mut bytes: Vec<u8> = text.bytes().take(length).collect();
    bytes.resize(length, fill);
    bytes
}

/// The one record of SZL 0x0424: event id, an unused byte, the mode (a whole byte, as clients
/// compare it: 0x08 RUN, 0x04 STOP, 0x0A HOLD), four reserved bytes, then the time of the CPU's clock.
fn mode(status: &CpuStatus) -> Vec<u8> {
    let mode = match status.mode {
        CpuMode::Run => MODE_RUN,
        CpuMode::Stop => MODE_STOP,
        CpuMode::Startup => MODE_STARTUP,
        CpuMode::Hold => MODE_HOLD,
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
            read_only: false,
        }
    }

    const COMMUNICATION: Communication = Communication {
        largest_pdu: 960,
        max_connections: 32,
    };

    fn list(id: u16, index: u16, status: &CpuStatus) -> Option<Vec<u8>> {
        partial_list(id, index, status, COMMUNICATION)
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
        let run = list(MODE, 0, &status(CpuMode::Run, CLOCK_MS)).unwrap();
        assert_eq!(run[..8], [0x04, 0x24, 0, 0, 0, 20, 0, 1]);
        // Clients read the mode as the eighth byte after the id and index.
        assert_eq!(run[4 + 7], MODE_RUN);
        assert_eq!(run[20..], [0x24, 0x05, 0x17, 0x13, 0x45, 0x30, 0x25, 0x06]);
        let stop = list(MODE, 0, &status(CpuMode::Stop, 0)).unwrap();
        assert_eq!(stop[4 + 7], MODE_STOP);
    }

    #[test]
    fn module_identification_names_the_order_code_and_awls_version() {
        let list = list(MODULE_IDENTIFICATION, 0, &status(CpuMode::Run, 0)).unwrap();
        assert_eq!(list[..8], [0, 0x11, 0, 0, 0, 28, 0, 2]);
        assert_eq!(&list[8..10], &[0, 1]);
        assert_eq!(&list[10..30], b"6ES7 315-2AG10-0AB0 ");
        let firmware = &list[36..64];
        assert_eq!(&firmware[..2], &[0, 7]);
        assert_eq!(firmware[24], b'V');
        assert_eq!(firmware[25..], version());
    }

    #[test]
    fn one_module_identification_record_is_chosen_by_its_index() {
        let status = status(CpuMode::Run, 0);
        let all = list(MODULE_IDENTIFICATION, 0, &status).unwrap();
        let order_code = list(ONE_MODULE_IDENTIFICATION, 1, &status).unwrap();
        assert_eq!(order_code[..8], [0x01, 0x11, 0, 1, 0, 28, 0, 1]);
        assert_eq!(order_code[8..], all[8..36]);
        let firmware = list(ONE_MODULE_IDENTIFICATION, 7, &status).unwrap();
        assert_eq!(firmware[..8], [0x01, 0x11, 0, 7, 0, 28, 0, 1]);
        assert_eq!(firmware[8..], all[36..]);
        assert_eq!(list(ONE_MODULE_IDENTIFICATION, 6, &status), None);
    }

    #[test]
    fn component_identification_has_the_fields_at_their_places() {
        let list = list(COMPONENT_IDENTIFICATION, 0, &status(CpuMode::Run, 0)).unwrap();
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
    fn the_communication_capabilities_are_the_servers_pdu_and_connections_and_an_s7_300s_rates() {
        let list = list(COMMUNICATION_CAPABILITIES, 1, &status(CpuMode::Run, 0)).unwrap();
        // One record of 40 bytes.
        assert_eq!(list[..8], [0x01, 0x31, 0, 1, 0, 40, 0, 1]);
        assert_eq!(list.len(), 8 + 40);
        let record = &list[8..];
        assert_eq!(record[..6], [0, 1, 0x03, 0xC0, 0, 32]);
        assert_eq!(record[6..10], 12_000_000u32.to_be_bytes());
        assert_eq!(record[10..14], 187_500u32.to_be_bytes());
        assert!(record[14..].iter().all(|&byte| byte == 0));
    }

    #[test]
    fn the_protection_is_level_1_with_the_selector_at_run_p_and_level_2_when_read_only() {
        let open = status(CpuMode::Run, 0);
        for id in [COMMUNICATION_STATUS, CPU_COMMUNICATION_STATUS] {
            let list = list(id, 4, &open).unwrap();
            assert_eq!(list[..8], [(id >> 8) as u8, 0x32, 0, 4, 0, 40, 0, 1]);
            assert_eq!(list.len(), 8 + 40);
            // Index, switch level 1, no password, valid level 1, RUN-P, no startup switch.
            assert_eq!(list[8..20], [0, 4, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0]);
            assert!(list[20..].iter().all(|&byte| byte == 0));
        }
        let read_only = CpuStatus {
            read_only: true,
            ..open
        };
        let list = list(CPU_COMMUNICATION_STATUS, 4, &read_only).unwrap();
        assert_eq!(list[8..20], [0, 4, 0, 1, 0, 2, 0, 2, 0, 2, 0, 0]);
    }

    #[test]
    fn lists_awl_does_not_have_are_none() {
        let status = status(CpuMode::Run, 0);
        assert_eq!(list(0x0132, 1, &status), None);
        assert_eq!(list(0x0131, 2, &status), None);
        assert_eq!(list(0x0091, 0, &status), None);
        assert_eq!(list(MODULE_IDENTIFICATION, 1, &status), None);
    }

    #[test]
    fn the_list_of_lists_names_every_list_awl_answers() {
        let status = status(CpuMode::Run, 0);
        let all = list(LIST, 0, &status).unwrap();
        assert_eq!(all[..8], [0, 0, 0, 0, 0, 2, 0, 8]);
        let ids: Vec<u16> = all[8..]
            .chunks(2)
            .map(|id| u16::from_be_bytes([id[0], id[1]]))
            .collect();
        assert_eq!(
            ids,
            [
                0x0000, 0x0011, 0x001C, 0x0111, 0x0131, 0x0132, 0x0232, 0x0424
            ]
        );
        // Each is answered with the index its clients ask.
        for (id, index) in [
            (0x0011, 0),
            (0x001C, 0),
            (0x0111, 1),
            (0x0131, 1),
            (0x0132, 4),
            (0x0232, 4),
            (0x0424, 0),
        ] {
            assert!(list(id, index, &status).is_some(), "{id:#06x}");
        }
    }
}
