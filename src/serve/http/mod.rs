//! The online page's server (`awl serve --http`): the page, embedded in the binary, and its
//! JSON API over HTTP/1, on the CPU's own network runtime. A request is checked
//! ([`guard`]), decoded into a plain value ([`api`]) and sent to the CPU as a [`Request`];
//! the answer, given at the cycle control point, goes back as JSON. Nothing here touches the
//! CPU.

pub mod api;
pub mod guard;
mod live;

use std::convert::Infallible;
use std::net::SocketAddr;
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, LazyLock};
use std::time::{Duration, Instant};

use axum::body::Body;
use axum::extract::FromRequestParts;
use axum::extract::ws::WebSocketUpgrade;
use axum::http::header::{CONTENT_DISPOSITION, CONTENT_LENGTH, CONTENT_TYPE, HOST, ORIGIN};
use axum::http::{HeaderMap, HeaderValue, Method, Response, StatusCode};
use hyper::body::Incoming;
use hyper_util::rt::{TokioIo, TokioTimer};
use serde::Serialize;
use tokio::net::TcpListener;
use tokio::sync::oneshot;

use super::listen::accept_each;
use super::online::error::OnlineError;
use super::request::{Ask, Client, Control, ControlError, Protocol, Refusal, Request, Requests};
use api::Call;

/// The live view's path.
const LIVE: &str = "/api/live";

/// The page: one file, with the look and the script it shares with the playground put in
/// once; nothing fetched from the network.
static PAGE: LazyLock<String> = LazyLock::new(|| {
    include_str!("../../../web/online/index.html")
        .replace(
            "/* {{COMMON_STYLE}} */\n",
            include_str!("../../../web/common.css"),
        )
        .replace(
            "// {{COMMON_SCRIPT}}\n",
            include_str!("../../../web/common.js"),
        )
});

/// The largest body a request may have.
pub const BODY_LIMIT: usize = 64 * 1024;

/// A client must send a request's head within this time.
const HEADER_TIMEOUT: Duration = Duration::from_secs(10);

/// How long a start waits to see the CPU leave STOP, to answer with the mode it reached.
const START_WAIT: Duration = Duration::from_secs(5);

/// How the server treats its clients.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Connections open at once; a further one is closed at once.
    pub max_connections: usize,
    /// Modify, force and mode changes are refused.
    pub read_only: bool,
}

/// What every connection's requests share.
struct Shared {
    requests: Requests,
    listening: SocketAddr,
    read_only: bool,
    /// The live connections open (each also counted as a connection until its upgrade).
    live: Arc<AtomicUsize>,
    max_connections: usize,
}

/// Serves the page and the API on `listener` forever, at most `max_connections` at once.
pub async fn serve(listener: TcpListener, requests: Requests, settings: Settings) {
    let Ok(listening) = listener.local_addr() else {
        return;
    };
    let shared = Arc::new(Shared {
        requests: requests.clone(),
        listening,
        read_only: settings.read_only,
        live: Arc::new(AtomicUsize::new(0)),
        max_connections: settings.max_connections,
    });
    accept_each(
        listener,
        Protocol::Http,
        requests,
        settings.max_connections,
        move |stream, client, _requests| {
            let shared = Arc::clone(&shared);
            let service = hyper::service::service_fn(move |request| {
                let shared = Arc::clone(&shared);
                async move { Ok::<_, Infallible>(respond(request, client, &shared).await) }
            });
            async move {
                // A connection that fails ends; the others go on.
                let _ = hyper::server::conn::http1::Builder::new()
                    .timer(TokioTimer::new())
                    .header_read_timeout(HEADER_TIMEOUT)
                    .serve_connection(TokioIo::new(stream), service)
                    .with_upgrades()
                    .await;
            }
        },
    )
    .await;
}

async fn respond(
    request: hyper::Request<Incoming>,
    client: Client,
    shared: &Arc<Shared>,
) -> Response<Body> {
    answer(request, client, shared)
        .await
        .unwrap_or_else(|refusal| {
            let status =
                StatusCode::from_u16(refusal.kind.status()).unwrap_or(StatusCode::BAD_REQUEST);
            json(status, &refusal)
        })
}

async fn answer(
    request: hyper::Request<Incoming>,
    client: Client,
    shared: &Arc<Shared>,
) -> Result<Response<Body>, Refusal> {
    let (mut parts, body) = request.into_parts();
    let header = |name| {
        parts
            .headers
            .get(name)
            .and_then(|value| value.to_str().ok())
    };
    let host = header(HOST);
    guard::check_host(host, shared.listening)?;
    let changes = parts.method != Method::GET && parts.method != Method::HEAD;
    if changes || parts.uri.path() == LIVE {
        guard::check_origin(header(ORIGIN), host.unwrap_or(""))?;
    }
    let body = read_body(&parts.headers, body).await?;
    let call = api::decode(
        parts.method.as_str(),
        parts.uri.path(),
        parts.uri.query(),
        &body,
    )?;
    if call.changes() && shared.read_only {
        return Err(OnlineError::ReadOnly.into());
    }
    Ok(match call {
        Call::Live => return live(&mut parts, client, shared).await,
        Call::Page => page(),
        Call::Cpu => ok(&ask_for(shared, client, |reply| Ask::Cpu { reply }).await?),
        Call::Mode(command) => ok(&mode(shared, client, command).await?),
        Call::Values(watched) => {
            let values = ask_for(shared, client, |reply| Ask::Values { watched, reply }).await??;
            ok(&Values { values })
        }
        Call::Modify { operand, value } => {
            let make = |reply| Ask::Modify {
                operand,
                value,
                reply,
            };
            ok(&ask_for(shared, client, make).await??)
        }
        Call::Force { operand, value } => {
            let make = |reply| Ask::Force {
                operand,
                value,
                reply,
            };
            ok(&ask_for(shared, client, make).await??)
        }
        Call::Unforce(operand) => {
            let one = operand.clone();
            let make = |reply| Ask::Unforce { operand, reply };
            let operands = ask_for(shared, client, make).await??;
            match one {
                Some(operand) => ok(&Unforced { operand }),
                None => ok(&AllUnforced { operands }),
            }
        }
        Call::Forces => {
            let forces = ask_for(shared, client, |reply| Ask::Forces { reply }).await?;
            ok(&ForcesView { forces })
        }
        Call::Status { block, level } => {
            let make = |reply| Ask::ProgramStatus {
                block,
                level,
                reply,
            };
            ok(&ask_for(shared, client, make).await??)
        }
        Call::Diagnostics => {
            let entries = ask_for(shared, client, |reply| Ask::Diagnostics { reply }).await?;
            ok(&Entries { entries })
        }
        Call::Snapshot => {
            let file = ask_for(shared, client, |reply| Ask::Snapshot { reply }).await?;
            let mut answer = response(StatusCode::OK, "application/json", file.into());
            answer.headers_mut().insert(
                CONTENT_DISPOSITION,
                HeaderValue::from_static("attachment; filename=\"awl-snapshot.json\""),
            );
            answer
        }
        Call::Timeline(seconds) => {
            let svg = ask_for(shared, client, |reply| Ask::Timeline { seconds, reply }).await?;
            ok(&Timeline { svg })
        }
        Call::Debug(message) => ok(&DebugMessages {
            messages: debug(shared, Some(message)).await?,
        }),
        Call::DebugEvents => ok(&DebugMessages {
            messages: debug(shared, None).await?,
        }),
    })
}

#[derive(Serialize)]
struct Values {
    values: Vec<super::request::Value>,
}

#[derive(Serialize)]
struct Unforced {
    operand: String,
}

#[derive(Serialize)]
struct AllUnforced {
    operands: Vec<String>,
}

#[derive(Serialize)]
struct ForcesView {
    forces: Vec<super::request::Value>,
}

#[derive(Serialize)]
struct Entries {
    entries: Vec<super::request::DiagnosticEntry>,
}

#[derive(Serialize)]
struct Timeline {
    svg: String,
}

#[derive(Serialize)]
struct DebugMessages {
    messages: Vec<serde_json::Value>,
}

#[derive(Serialize)]
struct ModeView {
    mode: &'static str,
}

/// The body, up to [`BODY_LIMIT`] bytes.
async fn read_body(headers: &HeaderMap, body: Incoming) -> Result<axum::body::Bytes, Refusal> {
    let declared = headers
        .get(CONTENT_LENGTH)
        .and_then(|length| length.to_str().ok())
        .and_then(|length| length.parse::<u64>().ok());
    if declared.is_some_and(|length| length > BODY_LIMIT as u64) {
        return Err(OnlineError::TooLarge.into());
    }
    axum::body::to_bytes(Body::new(body), BODY_LIMIT)
        .await
        .map_err(|_| OnlineError::TooLarge.into())
}

/// Sends the CPU a request and waits for its answer.
async fn ask_for<T>(
    shared: &Shared,
    client: Client,
    make: impl FnOnce(oneshot::Sender<T>) -> Ask,
) -> Result<T, Refusal> {
    let (reply, answer) = oneshot::channel();
    shared
        .requests
        .send(Request::Online {
            client,
            ask: make(reply),
        })
        .map_err(|_| Refusal::from(OnlineError::Gone))?;
    answer.await.map_err(|_| OnlineError::Gone.into())
}

/// Hands the CPU a debugger's message (or asks for its events) and waits for what it brings.
async fn debug(
    shared: &Shared,
    message: Option<Vec<u8>>,
) -> Result<Vec<serde_json::Value>, Refusal> {
    let (reply, answer) = oneshot::channel();
    shared
        .requests
        .send(Request::Debug { message, reply })
        .map_err(|_| Refusal::from(OnlineError::Gone))?;
    answer.await.map_err(|_| OnlineError::Gone.into())
}

/// A mode change; a start is answered once the CPU has left STOP (or after [`START_WAIT`]).
async fn mode(shared: &Shared, client: Client, command: Control) -> Result<ModeView, Refusal> {
    let (reply, answer) = oneshot::channel();
    shared
        .requests
        .send(Request::Control {
            client,
            command,
            reply,
        })
        .map_err(|_| Refusal::from(OnlineError::Gone))?;
    match answer.await.map_err(|_| Refusal::from(OnlineError::Gone))? {
        Err(ControlError::ReadOnly) => return Err(OnlineError::ReadOnly.into()),
        Err(ControlError::AlreadyRunning) => return Err(OnlineError::Running.into()),
        Ok(()) => {}
    }
    let asked = Instant::now();
    loop {
        let cpu = ask_for(shared, client, |reply| Ask::Cpu { reply }).await?;
        let settled = command == Control::Stop || cpu.mode != "STOP";
        if settled || asked.elapsed() > START_WAIT {
            return Ok(ModeView { mode: cpu.mode });
        }
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

/// Opens a live connection, if the server takes one more.
async fn live(
    parts: &mut axum::http::request::Parts,
    client: Client,
    shared: &Arc<Shared>,
) -> Result<Response<Body>, Refusal> {
    let upgrade = WebSocketUpgrade::from_request_parts(parts, &())
        .await
        .map_err(|_| Refusal::from(OnlineError::NotWebSocket))?;
    let slot =
        live::LiveSlot::take(&shared.live, shared.max_connections).ok_or(OnlineError::Busy {
            live: shared.max_connections,
        })?;
    let shared = Arc::clone(shared);
    Ok(upgrade
        .max_message_size(BODY_LIMIT)
        .max_frame_size(BODY_LIMIT)
        .on_upgrade(move |socket| live::serve(socket, client, shared, slot)))
}

fn page() -> Response<Body> {
    response(
        StatusCode::OK,
        "text/html; charset=utf-8",
        PAGE.as_str().into(),
    )
}

fn ok(value: &impl Serialize) -> Response<Body> {
    json(StatusCode::OK, value)
}

fn json(status: StatusCode, value: &impl Serialize) -> Response<Body> {
    let body = serde_json::to_vec(value).unwrap_or_default();
    response(status, "application/json", body.into())
}

fn response(status: StatusCode, content_type: &'static str, body: Body) -> Response<Body> {
    let mut response = Response::new(body);
    *response.status_mut() = status;
    response
        .headers_mut()
        .insert(CONTENT_TYPE, HeaderValue::from_static(content_type));
    response
}
