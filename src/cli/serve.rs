//! `awl serve`: the program on a virtual PLC in real time, reached over S7comm and Modbus TCP,
//! with a status line on the terminal and `awl run`'s summary at the end.

use std::net::{SocketAddr, ToSocketAddrs};
use std::path::PathBuf;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::serve::plc::{self, Listening, ServeOptions, ServedRun};
use crate::serve::station::Snapshot;
use crate::trace::format_ms;

use super::memory::MemoryArgs;
use super::run::{
    Format, ProgramArgs, RunLength, StateFormat, not_run, print_state, program_options,
};
use super::terminal::in_foreground;
use super::{Console, EXIT_OK, EXIT_STOP, watch};

/// Where the S7 server listens without an address: ISO-on-TCP's port on the loopback.
const S7_DEFAULT: &str = "127.0.0.1:102";
/// Where the Modbus TCP server listens without an address.
const MODBUS_DEFAULT: &str = "127.0.0.1:502";
/// Where the online page is served without an address: the loopback, on a port no other
/// common service claims.
const HTTP_DEFAULT: &str = "127.0.0.1:8102";
/// Where the OPC UA server listens without an address: the protocol's registered port.
const OPCUA_DEFAULT: &str = "127.0.0.1:4840";

#[derive(Debug, clap::Args)]
#[command(
    after_long_help = "Without --s7, --modbus, --http and --opcua the S7 and Modbus servers \
start, on 127.0.0.1:102 and 127.0.0.1:502; with any of them, only those named. `awl help serve` \
describes the area maps, what a client's write does, the OPC UA address space and its \
security, and how HMIs, Node-RED and plant simulations connect; `awl help online` the online \
page and its JSON API.",
    mut_arg("cycles", |arg| arg.help("Serve this many cycles (at least 1), then end \
[default: the scenario's run, else until stopped]")),
    mut_arg("duration", |arg| arg.help("Serve for this much simulated time, e.g. 10s (ends at \
the next cycle end) [default: the scenario's run, else until stopped]"))
)]
pub struct ServeArgs {
    #[command(flatten)]
    pub program: ProgramArgs,
    #[command(flatten)]
    pub length: RunLength,
    /// Simulated time per wall-clock time: 1 is real time, 0.1 slow motion, 10 ten times
    /// faster
    #[arg(long, value_parser = parse_speed, default_value = "1")]
    pub speed: f64,
    /// Serve S7comm (ISO-on-TCP) on HOST:PORT; port 0 picks a free one [default: 127.0.0.1:102]
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = S7_DEFAULT, value_parser = parse_address)]
    pub s7: Option<SocketAddr>,
    /// Serve Modbus TCP on HOST:PORT; port 0 picks a free one [default: 127.0.0.1:502]
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = MODBUS_DEFAULT, value_parser = parse_address)]
    pub modbus: Option<SocketAddr>,
    /// Serve the online page (watch, modify, force, program status, the live timeline) and its
    /// JSON API on HOST:PORT; port 0 picks a free one [default: 127.0.0.1:8102]
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = HTTP_DEFAULT, value_parser = parse_address)]
    pub http: Option<SocketAddr>,
    /// Serve OPC UA on HOST:PORT: the program's data by name (namespace urn:awl:plc), with
    /// subscriptions; port 0 picks a free one [default: 127.0.0.1:4840]
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, default_missing_value = OPCUA_DEFAULT, value_parser = parse_address)]
    pub opcua: Option<SocketAddr>,
    /// Take the OPC UA users and passwords from FILE (TOML: `[users]`, then `name =
    /// "password"`) and refuse anonymous clients [default: anonymous clients]
    #[arg(long, value_name = "FILE", requires = "opcua")]
    pub opcua_users: Option<PathBuf>,
    /// Refuse every write and every STOP or start request [default: off]
    #[arg(long)]
    pub read_only: bool,
    /// Connections served at once, per server; one more is closed at once
    #[arg(long, default_value = "32", value_parser = clap::value_parser!(u16).range(1..))]
    pub max_connections: u16,
    /// Write a trace of what was served to FILE (`-` for stdout) [default: no trace]
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Trace format [default: jsonl]
    #[arg(long, value_enum, requires = "trace")]
    pub trace_format: Option<Format>,
    /// Draw the timeline of what was served into FILE (`.svg` or `.html`) [default: none]
    #[arg(long, value_name = "FILE")]
    pub timeline: Option<PathBuf>,
    /// Print the CPU's state at the end [default: off]
    #[arg(long)]
    pub state: bool,
    /// The state as text, or as JSON; implies --state [default: text]
    #[arg(long, value_enum)]
    pub state_format: Option<StateFormat>,
    #[command(flatten)]
    pub memory: MemoryArgs,
    /// Continue from a snapshot (`awl run --snapshot`, the online API's POST /api/snapshot,
    /// or `s` and Enter on the terminal) [default: the program as loaded]
    #[arg(long, value_name = "SNAPSHOT")]
    pub from: Option<PathBuf>,
}

fn parse_speed(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(speed) if speed.is_finite() && speed > 0.0 && speed <= 1000.0 => Ok(speed),
        _ => Err(format!(
            "`{text}` is no speed; give a number above 0 and up to 1000, e.g. 1, 0.1 or 10"
        )),
    }
}

/// `HOST:PORT`, or a bare port on the loopback.
fn parse_address(text: &str) -> Result<SocketAddr, String> {
    let text = text.trim();
    let with_host = if text.parse::<u16>().is_ok() {
        format!("127.0.0.1:{text}")
    } else {
        text.to_string()
    };
    with_host
        .to_socket_addrs()
        .ok()
        .and_then(|mut addresses| addresses.next())
        .ok_or_else(|| {
            format!("`{text}` is no address to listen on; write HOST:PORT, e.g. 127.0.0.1:1102")
        })
}

fn options(args: &ServeArgs) -> ServeOptions {
    let both =
        args.s7.is_none() && args.modbus.is_none() && args.http.is_none() && args.opcua.is_none();
    let default = |text: &str| text.parse().ok();
    let mut run = program_options(&args.program);
    run.limit = args.length.limit();
    run.trace = args.trace.clone();
    run.trace_format = args.trace_format.map(Format::trace_format);
    run.timeline = args.timeline.clone();
    run.retain = args.memory.retain_options();
    run.what_fits = args.memory.retain_what_fits;
    run.from_snapshot = args.from.clone();
    ServeOptions {
        run,
        speed: args.speed,
        s7: args.s7.or(if both { default(S7_DEFAULT) } else { None }),
        modbus: args
            .modbus
            .or(if both { default(MODBUS_DEFAULT) } else { None }),
        http: args.http,
        opcua: args.opcua,
        opcua_users: args.opcua_users.clone(),
        read_only: args.read_only,
        max_connections: usize::from(args.max_connections),
    }
}

pub fn serve(args: &ServeArgs, console: &mut Console) -> u8 {
    watch::install_handler();
    let options = options(args);
    let mut status = StatusLine::default();
    let served = plc::serve(
        &options,
        watch::halt_requested,
        &mut |listening, warnings, requests| {
            console.reports(&warnings);
            announce(listening, &mut std::io::stdout().lock());
            super::snapshot_key::listen(requests.clone(), snapshot_home(args));
        },
        &mut |snapshot| status.show(snapshot),
    );
    status.clear();
    let served = match served {
        Ok(served) => served,
        Err(reason) => return not_run("serve", reason, console),
    };
    finish(args, &options, &served, console)
}

/// Where the terminal's snapshots go: beside the first program file, else the scenario.
fn snapshot_home(args: &ServeArgs) -> PathBuf {
    args.program
        .files
        .first()
        .or(args.program.scenario.as_ref())
        .cloned()
        .unwrap_or_else(|| PathBuf::from("awl"))
}

/// The listening lines, which a script waits for, flushed at once.
fn announce(listening: &Listening, out: &mut dyn std::io::Write) {
    if let Some(address) = listening.s7 {
        let _ = writeln!(out, "S7 server listening on {address}");
    }
    if let Some(address) = listening.modbus {
        let _ = writeln!(out, "Modbus TCP server listening on {address}");
    }
    if let Some(address) = listening.http {
        let _ = writeln!(out, "Online page at http://{address}/");
    }
    if let Some(address) = listening.opcua {
        let _ = writeln!(out, "OPC UA server listening on opc.tcp://{address}");
    }
    let _ = out.flush();
}

/// The summary `awl run` prints, what was served, and the state when asked.
fn finish(
    args: &ServeArgs,
    options: &ServeOptions,
    served: &ServedRun,
    console: &mut Console,
) -> u8 {
    let ran = &served.ran;
    console.reports(&ran.warnings);
    if let Some(stop) = &ran.outcome.stop {
        console.err(&format!("{:?}\n", crate::runner::stop_report(ran, stop)));
    }
    let mut report = crate::report::summary(ran);
    report.push_str(&serve_summary(options, served));
    if ran.trace_to_stdout {
        console.err(&report);
    } else {
        console.out(&report);
    }
    if let Some(format) = args
        .state_format
        .or(args.state.then_some(StateFormat::Text))
    {
        print_state(ran, format, console);
    }
    console.err(&crate::report::written(ran));
    if ran.outcome.stop.is_some() {
        EXIT_STOP
    } else {
        EXIT_OK
    }
}

/// `served: 120 requests (4 writes) over 3 connections; cycles started late by 0.05 ms (p50),
/// 0.4 ms (p99) at speed 1`.
fn serve_summary(options: &ServeOptions, served: &ServedRun) -> String {
    let counts = &served.served;
    let mut line = format!(
        "served: {} ({}) over {}",
        super::plural(counts.requests, "request"),
        super::plural(counts.writes, "write"),
        super::plural(counts.connections, "connection"),
    );
    if let Some(lateness) = served.lateness {
        line.push_str(&format!(
            "; cycles started late by {:.3} ms (p50), {:.3} ms (p99) at speed {}",
            lateness.p50.as_secs_f64() * 1e3,
            lateness.p99.as_secs_f64() * 1e3,
            options.speed
        ));
    }
    line.push('\n');
    line
}

/// The one status line on a terminal: mode, cycle, cycle times, clients, requests per second.
#[derive(Default)]
struct StatusLine {
    bar: Option<ProgressBar>,
}

impl StatusLine {
    fn show(&mut self, snapshot: &Snapshot) {
        if !in_foreground(&std::io::stderr()) {
            self.clear();
            return;
        }
        let bar = self.bar.get_or_insert_with(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(ProgressStyle::with_template("{msg}").expect("valid template"));
            bar
        });
        bar.set_message(format!(
            "{}  cycle {}  cycle time {}–{}  {}  {:.0} requests/s  (s Enter: snapshot, Ctrl-C ends)",
            snapshot.mode.name(),
            snapshot.cycle,
            format_ms(snapshot.min_cycle_ns),
            format_ms(snapshot.max_cycle_ns),
            super::plural(snapshot.clients as u64, "client"),
            snapshot.requests_per_second
        ));
        bar.tick();
    }

    fn clear(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
