//! The OPC UA server (`awl serve --opcua`), on async-opcua and the CPU's own network runtime:
//! the program's values by name in the namespace `urn:awl:plc` ([`nodes`]), read, written and
//! sampled at the cycle control point like the other servers' requests. The library decodes and
//! answers the protocol (malformed messages included); awl decodes no OPC UA bytes itself.
//!
//! Security: policy None only when listening on the loopback; Basic256Sha256 Sign and
//! SignAndEncrypt always, with a self-signed certificate made on the first start in awl's data
//! folder ([`data_folder`]); anonymous clients, or users and passwords from a file
//! ([`users`]). The connection limit holds for OPC UA as for the others: connections are
//! accepted (and counted) by awl and handed to the library's server over the loopback.

pub mod catalog;
pub mod nodes;
pub mod users;
pub mod value;

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::Duration;

use miette::Diagnostic;
use opcua_crypto::SecurityPolicy;
use opcua_server::node_manager::memory::InMemoryNodeManagerBuilder;
use opcua_server::{
    ANONYMOUS_USER_TOKEN_ID, Server, ServerBuilder, ServerEndpoint, ServerHandle, ServerUserToken,
};
use opcua_types::MessageSecurityMode;
use thiserror::Error;
use tokio::net::{TcpListener, TcpStream};

use super::listen::accept_each;
use super::request::{Protocol, Requests};
use catalog::Catalog;
use nodes::{FASTEST_SAMPLING_MS, PlcNodes};

/// The variable naming the folder awl keeps its data in (the OPC UA server's certificate)
/// instead of the platform's.
pub const DATA_FOLDER_VARIABLE: &str = "AWL_DATA_DIR";

/// The server's certificate and key, and the client certificates it has seen, below the data
/// folder.
const PKI_FOLDER: &str = "opcua-pki";

#[derive(Debug, Error, Diagnostic)]
pub enum OpcuaError {
    #[error("cannot start the OPC UA server: {reason}")]
    #[diagnostic(
        code(awl::serve::opcua),
        help(
            "awl keeps the server's certificate in {folder}; make that folder writable, or name \
             another with the environment variable AWL_DATA_DIR"
        )
    )]
    Start { reason: String, folder: String },
}

/// How the OPC UA server treats its clients.
#[derive(Debug, Clone)]
pub struct Settings {
    pub max_connections: usize,
    pub read_only: bool,
    /// Users and their passwords; anonymous clients when there are none.
    pub users: Vec<(String, String)>,
}

/// A server built and bound, to be run on the network's runtime.
pub struct Prepared {
    server: Server,
    handle: ServerHandle,
    /// Where clients connect.
    public: TcpListener,
    /// Where the library's server takes the connections awl accepted.
    inner: TcpListener,
    max_connections: usize,
}

/// Builds the server for `listener` (within the network runtime's context): its certificate
/// made on the first start, the program's nodes from `catalog`.
pub fn prepare(
    listener: std::net::TcpListener,
    catalog: Catalog,
    requests: Requests,
    settings: Settings,
) -> Result<Prepared, OpcuaError> {
    let folder = data_folder().join(PKI_FOLDER);
    let failed = |reason: String| OpcuaError::Start {
        reason,
        folder: folder.display().to_string(),
    };
    let address = listener
        .local_addr()
        .map_err(|error| failed(error.to_string()))?;
    let inner = std::net::TcpListener::bind((std::net::Ipv4Addr::LOCALHOST, 0))
        .and_then(|inner| inner.set_nonblocking(true).map(|()| inner))
        .and_then(TcpListener::from_std)
        .map_err(|error| failed(error.to_string()))?;
    let public = TcpListener::from_std(listener).map_err(|error| failed(error.to_string()))?;
    let catalog = Arc::new(catalog);
    let read_only = settings.read_only;
    let make_nodes = move |context, address_space: &mut _| {
        PlcNodes::new(&context, address_space, catalog, requests, read_only)
    };
    let mut builder = ServerBuilder::new()
        .application_name("awl")
        .application_uri("urn:awl:server")
        .product_uri("urn:awl")
        .host(address.ip().to_string())
        .port(address.port())
        .create_sample_keypair(true)
        .certificate_path("own/cert.der")
        .private_key_path("private/private.pem")
        .pki_dir(&folder)
        // A client's self-signed certificate is taken on first sight, as a PLC's is.
        .trust_client_certs(true)
        .discovery_urls(vec!["/".to_string()])
        .max_sessions(settings.max_connections)
        .diagnostics_enabled(false)
        .subscription_poll_interval_ms(FASTEST_SAMPLING_MS as u64)
        .with_node_manager(InMemoryNodeManagerBuilder::new(make_nodes));
    let subscriptions = &mut builder.limits_mut().subscriptions;
    subscriptions.min_sampling_interval_ms = FASTEST_SAMPLING_MS;
    subscriptions.min_publishing_interval_ms = FASTEST_SAMPLING_MS;
    let builder = endpoints(builder, address, &settings.users);
    let (server, handle) = builder.build().map_err(failed)?;
    Ok(Prepared {
        server,
        handle,
        public,
        inner,
        max_connections: settings.max_connections,
    })
}

/// The endpoints: None on the loopback only, Basic256Sha256 signed and encrypted everywhere;
/// each for anonymous clients, or for the users when there are some.
fn endpoints(
    mut builder: ServerBuilder,
    address: SocketAddr,
    users: &[(String, String)],
) -> ServerBuilder {
    let mut tokens = Vec::new();
    for (number, (user, password)) in users.iter().enumerate() {
        let id = format!("user{number}");
        builder = builder.add_user_token(
            &id,
            ServerUserToken::user_pass(user.as_str(), password.as_str()),
        );
        tokens.push(id);
    }
    if tokens.is_empty() {
        tokens.push(ANONYMOUS_USER_TOKEN_ID.to_string());
    }
    if address.ip().is_loopback() {
        builder = builder.add_endpoint("none", ServerEndpoint::new_none("/", &tokens));
    }
    let secured = |mode| ServerEndpoint::new("/", SecurityPolicy::Basic256Sha256, mode, &tokens);
    builder
        .add_endpoint("basic256sha256_sign", secured(MessageSecurityMode::Sign))
        .add_endpoint(
            "basic256sha256_sign_encrypt",
            secured(MessageSecurityMode::SignAndEncrypt),
        )
}

/// Runs the server until the runtime ends: connections accepted on the public address (at
/// most `max_connections`, each counted as a client) and passed to the library's server.
pub async fn serve(prepared: Prepared, requests: Requests) {
    let Prepared {
        server,
        handle,
        public,
        inner,
        max_connections,
    } = prepared;
    let (Ok(public_address), Ok(inner_address)) = (public.local_addr(), inner.local_addr()) else {
        return;
    };
    tokio::spawn(async move {
        let _ = server.run_with(inner).await;
    });
    // The library tells clients the port it listens on; they are to use the public one.
    let info = Arc::clone(handle.info());
    while info.port.load(Ordering::Acquire) != inner_address.port() {
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    info.port.store(public_address.port(), Ordering::Release);
    accept_each(
        public,
        Protocol::OpcUa,
        requests,
        max_connections,
        move |mut client, _, _| async move {
            if let Ok(mut server) = TcpStream::connect(inner_address).await {
                let _ = server.set_nodelay(true);
                let _ = tokio::io::copy_bidirectional(&mut client, &mut server).await;
            }
        },
    )
    .await;
    drop(handle);
}

/// The folder awl keeps its data in: `AWL_DATA_DIR`, else the platform's (`$XDG_DATA_HOME/awl`
/// or `~/.local/share/awl`, `~/Library/Application Support/awl`, `%APPDATA%\awl`).
pub fn data_folder() -> PathBuf {
    if let Some(folder) = std::env::var_os(DATA_FOLDER_VARIABLE).filter(|folder| !folder.is_empty())
    {
        return PathBuf::from(folder);
    }
    let home = || std::env::var_os("HOME").map(PathBuf::from);
    let platform = if cfg!(windows) {
        std::env::var_os("APPDATA").map(PathBuf::from)
    } else if cfg!(target_os = "macos") {
        home().map(|home| home.join("Library/Application Support"))
    } else {
        std::env::var_os("XDG_DATA_HOME")
            .filter(|folder| !folder.is_empty())
            .map(PathBuf::from)
            .or_else(|| home().map(|home| home.join(".local/share")))
    };
    platform.unwrap_or_else(std::env::temp_dir).join("awl")
}
