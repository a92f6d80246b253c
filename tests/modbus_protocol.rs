//! The Modbus TCP server against real clients: `serve` on 127.0.0.1 with a fake CPU answering
//! its requests from plain byte arrays, and pymodbus scripts (tests/clients/modbus_*.py) as the
//! clients, run in the environment tests/common/python.rs makes under target/ (or by the Python
//! at `AWL_PYTHON`); without pymodbus the script tests fail, naming the command that installs it.

mod common;

use std::io::Read;
use std::net::{SocketAddr, TcpStream};
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::thread;
use std::time::Duration;

use awl::serve::modbus::{Map, Table, serve};
use awl::serve::request::{Area, Request};
use common::fake_memory::FakeMemory;

fn pattern(size: usize, factor: usize, offset: usize) -> Vec<u8> {
    (0..size)
        .map(|n| ((n * factor + offset) % 256) as u8)
        .collect()
}

/// The areas of the fake CPU, filled as tests/clients/modbus_common.py expects them.
fn memory(read_only: bool) -> FakeMemory {
    let areas = [
        (Area::Inputs, pattern(128, 7, 3)),
        (Area::Outputs, pattern(128, 11, 1)),
        (Area::Flags, pattern(256, 13, 5)),
        (Area::DataBlock(1), pattern(20, 17, 2)),
    ];
    FakeMemory::new(areas, read_only)
}

/// A server on a free port of 127.0.0.1, its fake CPU, and what the CPU saw.
struct Server {
    address: SocketAddr,
    memory: Arc<Mutex<FakeMemory>>,
    /// The connections opened and closed: (client number, open).
    connections: Arc<Mutex<Vec<(u32, bool)>>>,
    /// Kept for the server's life: dropping it ends the server.
    _runtime: tokio::runtime::Runtime,
}

impl Server {
    fn start(map: Map, max_connections: usize, read_only: bool) -> Server {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .expect("a tokio runtime");
        let listener = runtime
            .block_on(tokio::net::TcpListener::bind("127.0.0.1:0"))
            .expect("a free port");
        let address = listener.local_addr().expect("its address");
        let (requests, mut served) = awl::serve::request::channel();
        let memory = Arc::new(Mutex::new(memory(read_only)));
        let connections = Arc::new(Mutex::new(Vec::new()));
        let (cpu_memory, cpu_connections) = (memory.clone(), connections.clone());
        thread::spawn(move || {
            while let Some(request) = served.blocking_recv() {
                match request {
                    Request::Access { items, reply, .. } => {
                        let mut memory = cpu_memory.lock().unwrap();
                        let results = items.into_iter().map(|item| memory.serve(item)).collect();
                        let _ = reply.send(results);
                    }
                    Request::Connection { client, open } => {
                        cpu_connections.lock().unwrap().push((client.number, open));
                    }
                    other => panic!("the Modbus server asked {other:?}"),
                }
            }
        });
        runtime.spawn(serve(listener, requests, map, max_connections));
        Server {
            address,
            memory,
            connections,
            _runtime: runtime,
        }
    }

    fn byte(&self, area: Area, at: usize) -> u8 {
        self.memory.lock().unwrap().area(area)[at]
    }

    /// Runs a client script with the server's port.
    fn client(&self, script: &str) {
        let python = common::python::with("pymodbus");
        let clients = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/clients");
        let output = common::python::command(&python)
            .arg(clients.join(script))
            .arg(self.address.port().to_string())
            .current_dir(&clients)
            .output()
            .expect("the client runs");
        assert!(
            output.status.success(),
            "{script}:\n{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
    }

    /// Waits until the CPU has seen `count` connection messages.
    fn await_connections(&self, count: usize) -> Vec<(u32, bool)> {
        for _ in 0..500 {
            let seen = self.connections.lock().unwrap().clone();
            if seen.len() >= count {
                return seen;
            }
            thread::sleep(Duration::from_millis(10));
        }
        self.connections.lock().unwrap().clone()
    }
}

#[test]
fn every_function_on_the_default_map() {
    let server = Server::start(Map::default(), 16, false);
    server.client("modbus_functions.py");
    // Coil 100 on, 101 off: Q 12.4 and Q 12.5.
    assert_eq!(server.byte(Area::Outputs, 12) >> 4 & 0b11, 0b01);
    // Coils 203–223 (every third on): Q 25.3 to Q 27.7.
    let bits: Vec<bool> = (203..224)
        .map(|n| server.byte(Area::Outputs, n / 8) >> (n % 8) & 1 == 1)
        .collect();
    let wanted: Vec<bool> = (0..21).map(|n| n % 3 == 0).collect();
    assert_eq!(bits, wanted);
    // Register 7 is MW 14, big-endian.
    assert_eq!(server.byte(Area::Flags, 14), 0xBE);
    assert_eq!(server.byte(Area::Flags, 15), 0xEF);
    // Register 31 (function 23's write) is MW 62.
    assert_eq!(server.byte(Area::Flags, 62), 0x42);
}

#[test]
fn a_moved_map_reaches_the_areas_it_names() {
    let map = Map {
        coils: Table {
            area: Area::Inputs,
            start: 0,
        },
        discrete_inputs: Table {
            area: Area::Flags,
            start: 17,
        },
        input_registers: Table {
            area: Area::DataBlock(9),
            start: 0,
        },
        holding_registers: Table {
            area: Area::DataBlock(1),
            start: 0,
        },
    };
    let server = Server::start(map, 16, false);
    server.client("modbus_moved_map.py");
    assert_eq!(
        server.byte(Area::Inputs, 1),
        0xFF,
        "coils 8–15 are I 1.0–1.7"
    );
    assert_eq!(server.byte(Area::DataBlock(1), 18), 0xCA);
    assert_eq!(server.byte(Area::DataBlock(1), 19), 0xFE);
}

#[test]
fn eight_clients_at_once_each_numbered_and_announced() {
    let server = Server::start(Map::default(), 16, false);
    server.client("modbus_clients.py");
    let seen = server.await_connections(16);
    let mut opened: Vec<u32> = seen
        .iter()
        .filter(|(_, open)| *open)
        .map(|(n, _)| *n)
        .collect();
    let mut closed: Vec<u32> = seen
        .iter()
        .filter(|(_, open)| !*open)
        .map(|(n, _)| *n)
        .collect();
    opened.sort_unstable();
    closed.sort_unstable();
    assert_eq!(opened, (1..=8).collect::<Vec<u32>>());
    assert_eq!(closed, opened, "each connection's close is announced");
    for client in 0..8 {
        let register = client * 4 + 3;
        let value = client * 1000 + 24 * 10 + 3;
        let flags = [
            server.byte(Area::Flags, register * 2),
            server.byte(Area::Flags, register * 2 + 1),
        ];
        assert_eq!(u16::from_be_bytes(flags), value as u16, "client {client}");
    }
}

#[test]
fn malformed_frames_close_or_are_answered_and_a_client_after_them_is_served() {
    let server = Server::start(Map::default(), 16, false);
    server.client("modbus_malformed.py");
}

#[test]
fn read_only_refuses_writes_with_exception_1() {
    let server = Server::start(Map::default(), 16, true);
    let mut stream = TcpStream::connect(server.address).expect("a connection");
    stream
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    // Write single register 0 := 0x1234, then read it.
    let exchange = |stream: &mut TcpStream, pdu: &[u8]| {
        use std::io::Write;
        let mut frame = vec![0, 1, 0, 0, 0, pdu.len() as u8 + 1, 1];
        frame.extend_from_slice(pdu);
        stream.write_all(&frame).unwrap();
        let mut header = [0u8; 7];
        stream.read_exact(&mut header).unwrap();
        let mut response = vec![0u8; usize::from(header[5]) - 1];
        stream.read_exact(&mut response).unwrap();
        response
    };
    assert_eq!(exchange(&mut stream, &[6, 0, 0, 0x12, 0x34]), [0x86, 1]);
    assert_eq!(exchange(&mut stream, &[5, 0, 0, 0xFF, 0]), [0x85, 1]);
    assert_eq!(exchange(&mut stream, &[3, 0, 0, 0, 1]), [3, 2, 5, 18]);
}

#[test]
fn past_the_connection_limit_a_new_connection_is_closed_at_once() {
    let server = Server::start(Map::default(), 2, false);
    let first = TcpStream::connect(server.address).expect("the first");
    let _second = TcpStream::connect(server.address).expect("the second");
    server.await_connections(2);
    let mut third = TcpStream::connect(server.address).expect("connects, then closed");
    third
        .set_read_timeout(Some(Duration::from_secs(5)))
        .unwrap();
    assert_eq!(third.read(&mut [0u8; 8]).expect("an end"), 0, "closed");
    drop(first);
    server.await_connections(3);
    let _fourth = TcpStream::connect(server.address).expect("a place again");
    let seen = server.await_connections(4);
    assert_eq!(seen, [(1, true), (2, true), (1, false), (3, true)]);
}
