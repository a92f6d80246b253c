//! The virtual PLC: the servers bound and started on their own threads, the CPU run on this
//! one, paced to the wall clock, from STOP through STARTUP to RUN and on until a halt, the
//! scenario's run length, or for ever; a client may stop and restart it on the way.

use std::net::{SocketAddr, TcpListener};
use std::sync::Arc;

use miette::{Diagnostic, Report};
use thiserror::Error;

use crate::runner::{self, NotRun, Persistence, Ran, RunOptions};
use crate::vm::Cpu;
use crate::vm::cycle::{RunLimit, RunOutcome};

use super::network::Network;
use super::online::Online;
use super::opcua::catalog::Catalog;
use super::pacing::{Lateness, Pacer};
use super::request::Requests;
use super::station::{Served, Snapshot, Station};

/// What `awl serve` is asked to do.
#[derive(Debug, Clone)]
pub struct ServeOptions {
    pub run: RunOptions,
    /// Simulated time per wall time: 1 is real time, 0.1 slow motion, 10 ten times faster.
    pub speed: f64,
    pub s7: Option<SocketAddr>,
    pub modbus: Option<SocketAddr>,
    /// The online page and its API.
    pub http: Option<SocketAddr>,
    /// The OPC UA server.
    pub opcua: Option<SocketAddr>,
    /// The OPC UA server's users and passwords (`--opcua-users`); anonymous clients without.
    pub opcua_users: Option<std::path::PathBuf>,
    /// Every write and control request is refused.
    pub read_only: bool,
    pub max_connections: usize,
}

/// Where the servers listen, with the ports the system gave for port 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Listening {
    pub s7: Option<SocketAddr>,
    pub modbus: Option<SocketAddr>,
    pub http: Option<SocketAddr>,
    pub opcua: Option<SocketAddr>,
}

/// A finished serve: the run as `awl run` reports it, and what was served.
pub struct ServedRun {
    pub ran: Ran,
    pub served: Served,
    pub lateness: Option<Lateness>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum ServeError {
    #[error("cannot listen for {server} on {address}: {reason}")]
    #[diagnostic(code(awl::serve::bind))]
    Bind {
        server: &'static str,
        address: SocketAddr,
        reason: String,
        #[help]
        help: String,
    },
    #[error("cannot start the network servers: {reason}")]
    #[diagnostic(
        code(awl::serve::runtime),
        help("the system refused the threads or sockets the servers need; free some and retry")
    )]
    Runtime { reason: String },
}

/// Binds the servers' sockets now, so that a port in use is told before the CPU starts.
fn bind(server: &'static str, address: SocketAddr) -> Result<TcpListener, NotRun> {
    TcpListener::bind(address)
        .and_then(|listener| listener.set_nonblocking(true).map(|()| listener))
        .map_err(|error| {
            let why = match error.kind() {
                std::io::ErrorKind::AddrInUse => "another program listens on that port",
                std::io::ErrorKind::PermissionDenied => {
                    "ports below 1024 need administrator rights"
                }
                _ => "the address is not one of this machine's, or the system refused it",
            };
            NotRun::Usage(Report::new(ServeError::Bind {
                server,
                address,
                reason: error.to_string(),
                help: format!("{why}; {}", free_port_help(server, address)),
            }))
        })
}

/// A free alternative to give, and where the client takes the port.
fn free_port_help(server: &str, address: SocketAddr) -> String {
    let host = address.ip();
    match server {
        "S7" => format!(
            "serve on another port, e.g. `--s7 {host}:1102`, and give the client that port \
             (python-snap7: `client.connect(\"{host}\", 0, 1, tcp_port=1102)`)"
        ),
        "OPC UA" => format!(
            "serve on another port, e.g. `--opcua {}`, and give the client that address \
             (asyncua: `Client(\"opc.tcp://{}/\")`)",
            SocketAddr::new(host, 4841),
            SocketAddr::new(host, 4841)
        ),
        "HTTP" => format!(
            "serve on another port, e.g. `--http {}`, and open the page there",
            SocketAddr::new(host, 8103)
        ),
        _ => format!(
            "serve on another port, e.g. `--modbus {host}:1502`, and give the client that port \
             (pymodbus: `ModbusTcpClient(\"{host}\", port=1502)`)"
        ),
    }
}

/// Serves until `halted` says so, the scenario's or the command line's run length ends, or
/// forever. `listening` hears where the servers listen once they do, with the program's and
/// the setup's warnings; `report` gets the status now and then.
pub fn serve(
    options: &ServeOptions,
    halted: fn() -> bool,
    listening: &mut dyn FnMut(&Listening, Vec<Report>, &Requests),
    report: &mut dyn FnMut(&Snapshot),
) -> Result<ServedRun, NotRun> {
    let mut prepared = runner::prepare(&options.run)?;
    // The station writes retentive memory itself: at its control points, at every STOP and
    // after a cold restart.
    let mut persistence = std::mem::take(&mut prepared.persistence);
    let modbus_map = prepared.modbus_map().map_err(NotRun::Failed)?;
    let s7 = options.s7.map(|address| bind("S7", address)).transpose()?;
    let modbus = options
        .modbus
        .map(|address| bind("Modbus TCP", address))
        .transpose()?;
    let http = options
        .http
        .map(|address| bind("HTTP", address))
        .transpose()?;
    let opcua = options
        .opcua
        .map(|address| bind("OPC UA", address))
        .transpose()?;
    let opcua_users = options
        .opcua_users
        .as_deref()
        .map(super::opcua::users::read)
        .transpose()
        .map_err(|error| NotRun::Usage(Report::new(error)))?
        .unwrap_or_default();
    let address = |listener: &Option<TcpListener>| {
        listener
            .as_ref()
            .and_then(|listener| listener.local_addr().ok())
    };
    let bound = Listening {
        s7: address(&s7),
        modbus: address(&modbus),
        http: address(&http),
        opcua: address(&opcua),
    };
    let (requests, received) = super::request::channel();
    // The servers run on the CPU's own thread, at its control point (see [`Network`]).
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .map_err(|error| runtime_error(&error))?;
    let opcua = match opcua {
        Some(listener) => {
            let _entered = runtime.enter();
            let catalog = Catalog::new(Arc::clone(&prepared.cpu.program), prepared.mnemonics);
            let settings = super::opcua::Settings {
                max_connections: options.max_connections,
                read_only: options.read_only,
                users: opcua_users,
            };
            let server = super::opcua::prepare(listener, catalog, requests.clone(), settings)
                .map_err(|error| NotRun::Failed(vec![Report::new(error)]))?;
            Some(server)
        }
        None => None,
    };
    let servers = Servers {
        s7,
        modbus,
        http,
        opcua,
        modbus_map,
        requests: requests.clone(),
        max_connections: options.max_connections,
        read_only: options.read_only,
    };
    servers
        .start(&runtime)
        .map_err(|error| runtime_error(&error))?;
    listening(&bound, prepared.take_warnings(), &requests);
    let limit = if prepared.limit_given {
        prepared.limit
    } else {
        RunLimit::Duration(u64::MAX)
    };
    prepared.limit = limit;
    let pacer = Pacer::new(options.speed, prepared.cpu.clock);
    let network = Network::new(runtime, received);
    let online = Online::new(prepared.mnemonics, options.read_only);
    let mut station = Station::new(network, options.read_only, pacer, online, halted, report);
    let mut ran = prepared.run_driven(&mut |cpu, limit, observe| {
        let outcome = drive(cpu, limit, observe, &mut station, &mut persistence);
        // What the page watched leaves the CPU before the run's outputs are finished.
        station.desk.borrow_mut().online.leave(cpu);
        outcome
    });
    ran.warnings.extend(persistence.finish(&ran.cpu));
    drop(requests);
    let served = station.desk.borrow().served;
    let lateness = station.pacer.lateness();
    // The servers' tasks end with their runtime, in the station.
    drop(station);
    Ok(ServedRun {
        ran,
        served,
        lateness,
    })
}

fn runtime_error(error: &std::io::Error) -> NotRun {
    NotRun::Failed(vec![Report::new(ServeError::Runtime {
        reason: error.to_string(),
    })])
}

/// Runs the CPU with the station at its control point; a STOP (the program's or a client's)
/// is served until a client restarts the CPU or a halt ends the serve.
fn drive(
    cpu: &mut Cpu,
    limit: RunLimit,
    observe: &mut dyn FnMut(&mut Cpu) -> bool,
    station: &mut Station,
    persistence: &mut Persistence,
) -> RunOutcome {
    let started = std::time::Instant::now();
    loop {
        let mut outcome = cpu.run_watched(limit, &mut |cpu| {
            persistence.at_control_point(cpu);
            observe(cpu) && station.at_control_point(cpu)
        });
        outcome.wall = started.elapsed();
        let stopped = cpu.mode == crate::vm::Mode::Stop;
        if !stopped {
            return outcome;
        }
        if let Some(stop) = &outcome.stop {
            station.desk.borrow_mut().online.stopped(cpu, stop);
        }
        persistence.write_retained(cpu);
        match station.while_stopped(cpu) {
            Some(cold) => {
                cpu.prepare_restart(cold);
                if cold {
                    persistence.write_retained(cpu);
                }
                station.pacer.rebase(cpu.clock);
                let restart = if cold { "cold" } else { "warm" };
                station
                    .desk
                    .borrow_mut()
                    .online
                    .mode_changed(cpu, format!("STARTUP: {restart} restart"));
            }
            None => {
                outcome.halted = true;
                outcome.wall = started.elapsed();
                return outcome;
            }
        }
    }
}

/// The servers to start on the network's runtime.
struct Servers {
    s7: Option<TcpListener>,
    modbus: Option<TcpListener>,
    http: Option<TcpListener>,
    opcua: Option<super::opcua::Prepared>,
    modbus_map: super::modbus::Map,
    requests: Requests,
    max_connections: usize,
    read_only: bool,
}

impl Servers {
    fn start(self, runtime: &tokio::runtime::Runtime) -> std::io::Result<()> {
        let _entered = runtime.enter();
        if let Some(listener) = self.s7 {
            let listener = tokio::net::TcpListener::from_std(listener)?;
            runtime.spawn(super::s7comm::serve(
                listener,
                self.requests.clone(),
                self.max_connections,
            ));
        }
        if let Some(listener) = self.modbus {
            let listener = tokio::net::TcpListener::from_std(listener)?;
            runtime.spawn(super::modbus::serve(
                listener,
                self.requests.clone(),
                self.modbus_map,
                self.max_connections,
            ));
        }
        if let Some(listener) = self.http {
            let listener = tokio::net::TcpListener::from_std(listener)?;
            let settings = super::http::Settings {
                max_connections: self.max_connections,
                read_only: self.read_only,
            };
            runtime.spawn(super::http::serve(
                listener,
                self.requests.clone(),
                settings,
            ));
        }
        if let Some(server) = self.opcua {
            runtime.spawn(super::opcua::serve(server, self.requests.clone()));
        }
        Ok(())
    }
}
