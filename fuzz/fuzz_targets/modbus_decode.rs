//! Any bytes as what a Modbus TCP client sends: the server's own reading of the stream (frame
//! by frame, as a connection reads it) never panics; a frame is refused, waited for, or read
//! into a request with CPU items within the protocol's limits, or an exception; the response,
//! built from made-up item results (the CPU's answers, or one of its errors), is a frame the
//! server itself would split whole. The first byte picks the map: the default, or tables at
//! the far ends of a data block. It needs no seeds: a frame's header is seven bytes.
#![no_main]

use awl::serve::modbus::connection::incoming;
use awl::serve::modbus::frame::{self, MAX_FRAME_LENGTH};
use awl::serve::modbus::{Map, Table, access};
use awl::serve::request::{Area, Item, ItemError, ItemResult};
use libfuzzer_sys::fuzz_target;

/// The most bytes one item may reach: 2000 bits lie in at most 251 bytes, 125 registers in 250.
const MAX_ITEM_BYTES: u32 = 251;

fn map(byte: u8) -> Map {
    let far = |start| Table {
        area: Area::DataBlock(65535),
        start,
    };
    match byte % 3 {
        0 => Map::default(),
        1 => Map {
            discrete_inputs: far(65535 * 8 + 7),
            coils: far(65535 * 8 + 7),
            input_registers: far(65534),
            holding_registers: far(65535),
        },
        _ => Map {
            discrete_inputs: far(3),
            coils: Table {
                area: Area::Inputs,
                start: 9,
            },
            input_registers: far(1),
            holding_registers: Table {
                area: Area::Flags,
                start: 7,
            },
        },
    }
}

/// What the CPU might answer an item: its bytes, or (when `fail` picks it) an error.
fn answer(item: &Item, fail: u8) -> ItemResult {
    match fail % 8 {
        1 => return Err(ItemError::OutOfRange),
        2 => return Err(ItemError::ReadOnly),
        3 => return Err(ItemError::NoSuchBlock),
        _ => {}
    }
    Ok(match item {
        Item::Read(range) => (0..range.length).map(|at| (at as u8) ^ fail).collect(),
        Item::ReadBit { .. } => vec![fail & 1],
        Item::Write { .. } | Item::WriteBit { .. } => Vec::new(),
    })
}

fn check_item(item: &Item) {
    match item {
        Item::Read(range) => assert!((1..=MAX_ITEM_BYTES).contains(&range.length), "{item:?}"),
        Item::Write { range, bytes } => {
            assert!((1..=MAX_ITEM_BYTES).contains(&range.length), "{item:?}");
            assert_eq!(bytes.len(), range.length as usize, "{item:?}");
        }
        Item::ReadBit { bit, .. } | Item::WriteBit { bit, .. } => assert!(*bit < 8, "{item:?}"),
    }
}

fuzz_target!(|bytes: &[u8]| {
    let bytes = awl_fuzz::bounded(bytes);
    let Some((&choice, mut stream)) = bytes.split_first() else {
        return;
    };
    let map = map(choice);
    while let Ok(Some(request)) = incoming(stream, &map) {
        assert!(request.length <= stream.len() && request.length <= MAX_FRAME_LENGTH);
        let answer = match request.request {
            Ok((decoded, items)) => {
                items.iter().for_each(check_item);
                let results = items.iter().map(|item| answer(item, choice)).collect();
                access::response(&decoded, &map, results)
            }
            Err(exception) => Err(exception),
        };
        let response = frame::encode(request.header, request.function, &answer);
        let split = frame::split(&response).expect("a response frame the server accepts");
        let split = split.expect("a whole response frame");
        assert_eq!(split.length, response.len());
        assert_eq!(split.header, request.header);
        stream = &stream[request.length..];
    }
});
