//! `awl serve`'s S7comm server against a fake CPU (plain byte arrays answering the requests on
//! a thread of its own): python-snap7 clients (the scripts in tests/clients/, run in the
//! environment tests/common/python.rs makes under target/, or by the Python at `AWL_PYTHON`;
//! a test fails where it cannot have them) and raw packets over a socket. All traffic stays on
//! 127.0.0.1.

mod common;

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use awl::serve::request::{Area, Control, ControlError, CpuMode, CpuStatus, Received, Request};
use awl::serve::s7comm::{Settings, serve_with};
use common::fake_memory::FakeMemory;

/// The fake CPU's clock: 2024-05-17 13:45:30.250, in milliseconds since 1990-01-01.
const CLOCK_MS: i64 = 12_555 * 86_400_000 + ((13 * 60 + 45) * 60 + 30) * 1000 + 250;

/// The fake CPU: DB 1 of 100 bytes (DB 2 absent), 128 bytes of inputs, outputs and flags, 16
/// timers and 16 counters.
struct Memory {
    areas: FakeMemory,
    mode: CpuMode,
    read_only: bool,
    controls: Vec<Control>,
    /// Each client's connection events, in order.
    connections: Vec<(u32, bool)>,
}

impl Memory {
    fn new(read_only: bool) -> Memory {
        let areas = [
            (Area::Inputs, vec![0; 128]),
            (Area::Outputs, vec![0; 128]),
            (Area::Flags, vec![0; 128]),
            (Area::DataBlock(1), vec![0; 100]),
            (Area::Timers, vec![0; 32]),
            (Area::Counters, vec![0; 32]),
        ];
        Memory {
            areas: FakeMemory::new(areas, read_only),
            mode: CpuMode::Run,
            read_only,
            controls: Vec::new(),
            connections: Vec::new(),
        }
    }

    fn control(&mut self, command: Control) -> Result<(), ControlError> {
        self.controls.push(command);
        if self.read_only {
            return Err(ControlError::ReadOnly);
        }
        match (command, self.mode) {
            (Control::Stop, _) => self.mode = CpuMode::Stop,
            (_, CpuMode::Run) => return Err(ControlError::AlreadyRunning),
            _ => self.mode = CpuMode::Run,
        }
        Ok(())
    }

    fn serve(&mut self, request: Request) {
        match request {
            Request::Access { items, reply, .. } => {
                let results = items.into_iter().map(|item| self.areas.serve(item));
                let _ = reply.send(results.collect());
            }
            Request::Status { reply } => {
                let _ = reply.send(CpuStatus {
                    mode: self.mode,
                    profile: "speed7",
                    order_code: "6ES7 315-2AG10-0AB0".to_string(),
                    clock_ms: CLOCK_MS,
                    cycles: 0,
                    read_only: self.read_only,
                });
            }
            Request::Control { command, reply, .. } => {
                let _ = reply.send(self.control(command));
            }
            Request::Connection { client, open } => self.connections.push((client.number, open)),
            Request::Online { ask, .. } => {
                panic!("the S7 server asked what the page asks: {ask:?}")
            }
            Request::Sample { probes, .. } => {
                panic!("the S7 server asked for an OPC UA sample: {probes:?}")
            }
            Request::Debug { message, .. } => {
                panic!("the S7 server asked what a debugger asks: {message:?}")
            }
        }
    }
}

fn run_cpu(memory: Arc<Mutex<Memory>>, mut requests: Received) {
    while let Some(request) = requests.blocking_recv() {
        lock(&memory).serve(request);
    }
}

fn lock(memory: &Mutex<Memory>) -> MutexGuard<'_, Memory> {
    memory
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A server on 127.0.0.1 with its fake CPU; the runtime ends with the test.
struct Server {
    address: SocketAddr,
    memory: Arc<Mutex<Memory>>,
    _runtime: tokio::runtime::Runtime,
}

fn start(settings: Settings, read_only: bool) -> Server {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let listener = runtime
        .block_on(tokio::net::TcpListener::bind("127.0.0.1:0"))
        .unwrap();
    let address = listener.local_addr().unwrap();
    let memory = Arc::new(Mutex::new(Memory::new(read_only)));
    let (requests, cpu) = awl::serve::request::channel();
    let cpu_memory = Arc::clone(&memory);
    std::thread::spawn(move || run_cpu(cpu_memory, cpu));
    runtime.spawn(serve_with(listener, requests, settings));
    Server {
        address,
        memory,
        _runtime: runtime,
    }
}

fn settings() -> Settings {
    Settings {
        max_connections: 8,
        idle_timeout: Duration::from_secs(30),
        packet_timeout: Duration::from_secs(2),
    }
}

/// The Python with python-snap7 3.x.
fn python() -> PathBuf {
    common::python::with("snap7")
}

/// The Python with python-snap7 1.x, whose wheel bundles Snap7's C library.
fn python_snap7_1() -> PathBuf {
    common::python::SNAP7_1.python("snap7")
}

fn run_script(python: &Path, script: &str, args: &[String]) -> Output {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/clients")
        .join(script);
    common::python::command(python)
        .arg(path)
        .args(args)
        .output()
        .unwrap()
}

fn assert_script(python: &Path, script: &str, args: &[String]) {
    let output = run_script(python, script, args);
    assert!(
        output.status.success(),
        "{script} {args:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}

fn args(values: &[&dyn ToString]) -> Vec<String> {
    values.iter().map(|value| value.to_string()).collect()
}

#[test]
fn python_snap7_reads_and_writes_every_area_and_width_on_rack_0_slot_1_and_2() {
    let python = python();
    let server = start(settings(), false);
    let port = server.address.port();
    // Slot 1 with the default PDU request (480), slot 2 asking for more than awl's 960.
    assert_script(&python, "s7_areas.py", &args(&[&port, &0, &1, &480, &480]));
    assert_script(&python, "s7_areas.py", &args(&[&port, &0, &2, &2000, &960]));
    let memory = lock(&server.memory);
    assert_eq!(&memory.areas.area(Area::DataBlock(1))[96..], b"AWL!");
    assert_eq!(
        &memory.areas.area(Area::DataBlock(1))[80..83],
        &[0xA1, 0xA2, 0xA3]
    );
    assert_eq!(&memory.areas.area(Area::Flags)[110..112], &[0xBE, 0xEF]);
    assert_eq!(
        &memory.areas.area(Area::Timers)[26..32],
        &[0x01, 0x23, 0x02, 0x50, 0x09, 0x99]
    );
}

#[test]
fn python_snap7_reads_the_cpu_state_order_code_info_and_clock_and_stops_and_starts_it() {
    let python = python();
    let server = start(settings(), false);
    let version = env!("CARGO_PKG_VERSION");
    let port = server.address.port();
    assert_script(&python, "s7_cpu.py", &args(&[&port, &CLOCK_MS, &version]));
    let memory = lock(&server.memory);
    use Control::*;
    assert_eq!(
        memory.controls,
        [HotStart, Stop, HotStart, Stop, ColdStart, ColdStart]
    );
}

#[test]
fn snap7_s_c_library_gets_every_answer_an_s7_300_gives() {
    let python = python_snap7_1();
    let server = start(settings(), false);
    let version = env!("CARGO_PKG_VERSION");
    let port = server.address.port();
    let connections = settings().max_connections;
    assert_script(
        &python,
        "s7_snap7_1.py",
        &args(&[&port, &version, &connections]),
    );
    let memory = lock(&server.memory);
    assert_eq!(
        &memory.areas.area(Area::DataBlock(1))[10..12],
        &[0x12, 0x34]
    );
    assert_eq!(&memory.areas.area(Area::DataBlock(1))[40..45], b"snap7");
    assert_eq!(&memory.areas.area(Area::Flags)[20..22], &[0xAB, 0xCD]);
    use Control::*;
    assert_eq!(memory.controls, [Stop, HotStart, HotStart]);
    assert_eq!(memory.mode, CpuMode::Run);
}

#[test]
fn snap7_s_c_library_sees_a_read_only_cpu_write_protected() {
    let python = python_snap7_1();
    let server = start(settings(), true);
    let port = server.address.port();
    assert_script(&python, "s7_snap7_1.py", &args(&[&port, &"read-only"]));
    assert_eq!(lock(&server.memory).mode, CpuMode::Run);
}

#[test]
fn a_read_only_cpu_refuses_writes_and_control_as_a_protected_cpu_does() {
    let python = python();
    let server = start(settings(), true);
    assert_script(&python, "s7_read_only.py", &args(&[&server.address.port()]));
    assert_eq!(lock(&server.memory).mode, CpuMode::Run);
}

#[test]
fn eight_clients_are_served_at_once_and_a_ninth_is_turned_away() {
    let python = python();
    let server = start(settings(), false);
    let port = server.address.port();
    assert_script(&python, "s7_concurrent.py", &args(&[&port, &2.0]));
    // Every client's opening and closing reached the CPU, the turned-away one's neither.
    let deadline = Instant::now() + Duration::from_secs(5);
    while lock(&server.memory).connections.len() < 16 && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(20));
    }
    let memory = lock(&server.memory);
    let mut numbers: Vec<u32> = memory
        .connections
        .iter()
        .map(|(number, _)| *number)
        .collect();
    numbers.sort();
    numbers.dedup();
    assert_eq!(numbers, (1..=8).collect::<Vec<_>>());
    for number in 1..=8 {
        let events: Vec<bool> = memory
            .connections
            .iter()
            .filter(|(client, _)| *client == number)
            .map(|(_, open)| *open)
            .collect();
        assert_eq!(events, [true, false], "client {number}");
    }
}

/// A raw client: TPKT and COTP by hand.
struct Raw {
    stream: TcpStream,
}

/// python-snap7's connection request for rack 0, slot 1.
const CONNECTION_REQUEST: [u8; 22] = [
    3, 0, 0, 22, 17, 0xE0, 0, 0, 0, 1, 0, 0xC1, 2, 1, 0, 0xC2, 2, 1, 1, 0xC0, 1, 0x0A,
];

impl Raw {
    fn connect(server: &Server) -> Raw {
        let stream = TcpStream::connect(server.address).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        Raw { stream }
    }

    /// Connected and set up with a PDU of 240 bytes.
    fn ready(server: &Server) -> Raw {
        let mut raw = Raw::connect(server);
        raw.send(&CONNECTION_REQUEST);
        let confirm = raw.packet().expect("a connection confirm");
        assert_eq!(confirm[1], 0xD0);
        let setup = raw.job(1, &[0xF0, 0, 0, 1, 0, 1, 0, 240], &[]);
        assert_eq!(&setup[12..], &[0xF0, 0, 0, 1, 0, 1, 0, 240]);
        raw
    }

    fn send(&mut self, bytes: &[u8]) {
        // The server may already have closed the connection.
        let _ = self.stream.write_all(bytes);
    }

    /// The payload of the next TPKT packet; `None` when the server closed the connection.
    fn packet(&mut self) -> Option<Vec<u8>> {
        let mut header = [0u8; 4];
        self.stream.read_exact(&mut header).ok()?;
        let length = usize::from(u16::from_be_bytes([header[2], header[3]]));
        let mut payload = vec![0; length - 4];
        self.stream.read_exact(&mut payload).ok()?;
        Some(payload)
    }

    /// Whether the server closes the connection (without answering).
    fn closed(&mut self) -> bool {
        let mut byte = [0u8; 1];
        matches!(self.stream.read(&mut byte), Ok(0) | Err(_))
    }

    /// Sends an S7 PDU in one data TPDU and returns the S7 PDU answered.
    fn exchange(&mut self, pdu: &[u8]) -> Vec<u8> {
        let mut packet = vec![3, 0];
        packet.extend_from_slice(&((pdu.len() + 7) as u16).to_be_bytes());
        packet.extend_from_slice(&[2, 0xF0, 0x80]);
        packet.extend_from_slice(pdu);
        self.send(&packet);
        let answer = self.packet().expect("an answer");
        assert_eq!(&answer[..3], &[2, 0xF0, 0x80]);
        answer[3..].to_vec()
    }

    fn job(&mut self, reference: u16, parameters: &[u8], data: &[u8]) -> Vec<u8> {
        self.exchange(&job(1, reference, parameters, data))
    }
}

fn job(pdu_type: u8, reference: u16, parameters: &[u8], data: &[u8]) -> Vec<u8> {
    let mut pdu = vec![0x32, pdu_type, 0, 0];
    pdu.extend_from_slice(&reference.to_be_bytes());
    pdu.extend_from_slice(&(parameters.len() as u16).to_be_bytes());
    pdu.extend_from_slice(&(data.len() as u16).to_be_bytes());
    pdu.extend_from_slice(parameters);
    pdu.extend_from_slice(data);
    pdu
}

/// A read job of `count` bytes of DB 1 from byte 0.
fn read_db1(count: u16) -> Vec<u8> {
    let mut parameters = vec![0x04, 1, 0x12, 0x0A, 0x10, 0x02];
    parameters.extend_from_slice(&count.to_be_bytes());
    parameters.extend_from_slice(&[0, 1, 0x84, 0, 0, 0]);
    parameters
}

/// The header error of an acknowledgement (PDU type 3) with `reference`.
fn header_error(answer: &[u8], reference: u16) -> u16 {
    assert_eq!(&answer[..2], &[0x32, 3]);
    assert_eq!(u16::from_be_bytes([answer[4], answer[5]]), reference);
    u16::from_be_bytes([answer[10], answer[11]])
}

fn still_serving(raw: &mut Raw) {
    let answer = raw.job(99, &read_db1(4), &[]);
    assert_eq!(header_error(&answer, 99), 0);
    assert_eq!(&answer[12..], &[0x04, 1, 0xFF, 0x04, 0, 32, 0, 0, 0, 0]);
}

#[test]
fn malformed_requests_get_the_protocols_errors_and_the_connection_serves_on() {
    let server = start(settings(), false);
    let mut raw = Raw::ready(&server);
    // The lengths promise a longer parameter section than there is.
    let mut short = job(1, 7, &read_db1(4), &[]);
    short[7] += 10;
    assert_eq!(header_error(&raw.exchange(&short), 7), 0x8500);
    // An item count past the items there are.
    let mut counted = read_db1(4);
    counted[1] = 5;
    assert_eq!(header_error(&raw.job(8, &counted, &[]), 8), 0x8500);
    // A write whose data section is cut short.
    let mut write = read_db1(4);
    write[0] = 0x05;
    assert_eq!(
        header_error(&raw.job(9, &write, &[0, 4, 0, 32, 1]), 9),
        0x8500
    );
    // An unknown function (request download) and an acknowledgement sent to the server.
    assert_eq!(header_error(&raw.job(10, &[0x1A, 0, 0], &[]), 10), 0x8104);
    assert_eq!(
        header_error(&raw.exchange(&job(3, 11, &[0x04, 0], &[])), 11),
        0x8104
    );
    // A PI service other than the program's.
    let mut compress = vec![0x28, 0, 0, 0, 0, 0, 0, 0xFD, 0, 0, 5];
    compress.extend_from_slice(b"_GARB");
    assert_eq!(header_error(&raw.job(12, &compress, &[]), 12), 0x8104);
    // 100 bytes fit a PDU of 240 bytes; three items of 100 bytes would not.
    assert_eq!(header_error(&raw.job(13, &read_db1(100), &[]), 13), 0);
    let mut too_long = read_db1(100);
    too_long[1] = 3;
    too_long.extend_from_slice(&read_db1(100)[2..]);
    too_long.extend_from_slice(&read_db1(100)[2..]);
    assert_eq!(header_error(&raw.job(14, &too_long, &[]), 14), 0x8500);
    // A userdata request of a group awl does not serve: the error in its parameters.
    let userdata = [0, 1, 0x12, 4, 0x11, 0x43, 0x01, 0];
    let answer = raw.exchange(&job(7, 15, &userdata, &[0x0A, 0, 0, 0]));
    assert_eq!(&answer[..2], &[0x32, 7]);
    assert_eq!(&answer[10 + 10..10 + 12], &[0x81, 0x04]);
    still_serving(&mut raw);
}

#[test]
fn a_packet_longer_than_the_pdu_is_dropped_unread_and_refused() {
    let server = start(settings(), false);
    let mut raw = Raw::ready(&server);
    // A TPKT of 65535 bytes whose S7 header claims a write job.
    let mut packet = vec![3, 0, 0xFF, 0xFF, 2, 0xF0, 0x80];
    packet.extend_from_slice(&job(1, 21, &[0x05, 1], &[]));
    packet.resize(0xFFFF, 0xEE);
    raw.send(&packet);
    let answer = raw.packet().expect("a refusal");
    assert_eq!(header_error(&answer[3..], 21), 0x8500);
    // The same PDU in data TPDUs of 200 bytes, past the PDU length of 240.
    let pdu = job(1, 22, &read_db1(4), &[0; 300]);
    for (index, piece) in pdu.chunks(200).enumerate() {
        let last = (index + 1) * 200 >= pdu.len();
        let mut packet = vec![3, 0];
        packet.extend_from_slice(&((piece.len() + 7) as u16).to_be_bytes());
        packet.extend_from_slice(&[2, 0xF0, if last { 0x80 } else { 0 }]);
        packet.extend_from_slice(piece);
        raw.send(&packet);
    }
    let answer = raw.packet().expect("a refusal");
    assert_eq!(header_error(&answer[3..], 22), 0x8500);
    // A PDU in two data TPDUs within the length is served.
    let pdu = job(1, 23, &read_db1(2), &[]);
    let (first, second) = pdu.split_at(5);
    for (piece, end) in [(first, 0), (second, 0x80)] {
        let mut packet = vec![3, 0, 0, (piece.len() + 7) as u8, 2, 0xF0, end];
        packet.extend_from_slice(piece);
        raw.send(&packet);
    }
    let answer = raw.packet().expect("an answer");
    assert_eq!(header_error(&answer[3..], 23), 0);
    still_serving(&mut raw);
}

#[test]
fn bytes_that_are_no_protocol_close_the_connection() {
    let server = start(settings(), false);
    let cases: [&[u8]; 5] = [
        b"GET / HTTP/1.1\r\n\r\n",
        // A TPKT too short to hold a TPDU.
        &[3, 0, 0, 4],
        // A data TPDU before the connection request.
        &[3, 0, 0, 7, 2, 0xF0, 0x80],
        // A connection request whose parameter runs past its end.
        &[3, 0, 0, 13, 8, 0xE0, 0, 0, 0, 1, 0, 0xC1, 9],
        // An expedited data TPDU.
        &[3, 0, 0, 7, 2, 0x10, 0x80],
    ];
    for bytes in cases {
        let mut raw = Raw::connect(&server);
        raw.send(bytes);
        assert!(raw.closed(), "{bytes:?} was answered");
    }
    // After the handshake: no S7 PDU, then a second connection request.
    let mut raw = Raw::ready(&server);
    raw.send(&[3, 0, 0, 9, 2, 0xF0, 0x80, 0x99, 0x99]);
    assert!(raw.closed());
    let mut raw = Raw::ready(&server);
    raw.send(&CONNECTION_REQUEST);
    assert!(raw.closed());
    still_serving(&mut Raw::ready(&server));
}

#[test]
fn slow_and_silent_clients_are_dropped_while_others_are_served() {
    let quick = Settings {
        max_connections: 8,
        idle_timeout: Duration::from_millis(1500),
        packet_timeout: Duration::from_millis(300),
    };
    let server = start(quick, false);
    let started = Instant::now();
    let mut silent = Raw::connect(&server);
    let mut unfinished = Raw::ready(&server);
    // Half a packet header, then nothing.
    unfinished.send(&[3, 0]);
    let mut lying = Raw::ready(&server);
    lying.send(&[3, 0, 0xFF, 0xFF, 2, 0xF0, 0x80]);
    let mut busy = Raw::ready(&server);
    still_serving(&mut busy);
    assert!(unfinished.closed());
    assert!(lying.closed());
    still_serving(&mut busy);
    assert!(silent.closed());
    assert!(started.elapsed() < Duration::from_secs(5));
}

/// A fixed pseudo-random sequence (xorshift), so a failure replays.
fn noise(seed: u64, length: usize) -> Vec<u8> {
    let mut state = seed.max(1);
    (0..length)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        })
        .collect()
}

#[test]
fn random_packets_are_answered_or_closed_and_a_python_client_is_served_after() {
    let quick = Settings {
        packet_timeout: Duration::from_millis(300),
        ..settings()
    };
    let server = start(quick, false);
    for seed in 1..200u64 {
        let mut raw = Raw::ready(&server);
        let body = noise(seed, (seed as usize * 7) % 90);
        // Mostly S7-looking PDUs of random content, some with random TPKT and COTP headers.
        let mut packet = match seed % 3 {
            0 => vec![3, 0],
            1 => vec![3, 0, 0, 0, 2, 0xF0, 0x80, 0x32, (seed % 8) as u8],
            _ => vec![3, 0, 0, 0, 2, 0xF0, 0x80, 0x32, 1, 0, 0, 0, 5],
        };
        packet.extend_from_slice(&body);
        if seed % 3 != 0 {
            let length = packet.len() as u16;
            packet[2..4].copy_from_slice(&length.to_be_bytes());
        }
        raw.send(&packet);
        raw.stream
            .set_read_timeout(Some(Duration::from_secs(3)))
            .unwrap();
        if seed % 3 == 0 {
            // Random headers: whatever the server makes of the bytes, it answers, closes or
            // waits for more; the reads end either way.
            while raw.packet().is_some() {}
        } else if raw.packet().is_some() {
            // An S7 PDU with a readable header is answered, and the connection serves on.
            still_serving(&mut raw);
        }
    }
    let mut raw = Raw::ready(&server);
    still_serving(&mut raw);
    let python = python();
    let port = server.address.port();
    assert_script(&python, "s7_areas.py", &args(&[&port, &0, &1, &480, &480]));
}
