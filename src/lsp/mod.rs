//! `awl lsp`: a language server over stdio. Each document is read with the program its
//! workspace makes of it (`workspace`); the diagnostics are `awl check`'s, published on
//! open and on every change; hover and navigation read the same front end's syntax trees.
//!
//! The server answers every request: one it does not know with `MethodNotFound`, bad
//! parameters with `InvalidParams`, a handler that fails with `InternalError`, one cancelled
//! while it waited with `RequestCanceled`, and it stops when the client has gone. Edits that
//! arrive together are checked once, when nothing else waits.
//!
//! Completion, quick fixes, semantic tokens and formatting are modules of their own on plain
//! types (`text`); `features` serves them. Each feature has its capability in
//! [`capabilities`] and an arm in `Server::request`, where `Server::at_position` hands a
//! handler the document's `workspace::Analysis` (front end, file paths, CPU) and the cursor's
//! byte offset, and `Server::analysed` the analysis alone.

pub mod complete;
mod diagnostics;
mod documents;
mod features;
pub mod fixes;
pub mod format;
mod hover;
mod lookup;
mod navigate;
mod position;
pub mod text;
pub mod textmate;
pub mod tokens;
mod workspace;

use std::collections::VecDeque;
use std::panic::AssertUnwindSafe;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{self as notify, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::{
    CodeActionProviderCapability, CompletionOptions, HoverProviderCapability, InitializeParams,
    OneOf, PublishDiagnosticsParams, SemanticTokensFullOptions, SemanticTokensOptions,
    SemanticTokensServerCapabilities, ServerCapabilities, ServerInfo, TextDocumentSyncCapability,
    TextDocumentSyncKind, Uri,
};
use serde::Serialize;
use serde::de::DeserializeOwned;

use position::LineIndex;
use workspace::Workspace;
pub use workspace::{Settings, SettingsError};

/// What the server can do, told at `initialize`.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        workspace_symbol_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions::default()),
        code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: features::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                ..SemanticTokensOptions::default()
            },
        )),
        document_formatting_provider: Some(OneOf::Left(true)),
        ..ServerCapabilities::default()
    }
}

/// Why the server could not talk with its client.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
#[error("awl lsp: the connection to the editor failed: {reason}")]
#[diagnostic(
    code(awl::lsp::connection),
    help(
        "`awl lsp` is started by an editor, which speaks the Language Server Protocol on its \
         stdin and stdout and sends `initialize` first"
    )
)]
pub struct ConnectionError {
    reason: String,
}

/// Runs the server on stdin and stdout until the client says `exit` or goes away.
pub fn serve_stdio() -> Result<(), ConnectionError> {
    let (connection, threads) = Connection::stdio();
    let result = serve(&connection);
    drop(connection);
    // Once the session has begun, a client that vanished ends the server like `exit`; before
    // it, the reader's error says what came instead of `initialize`.
    let read = threads.join();
    result.map_err(|reason| ConnectionError {
        reason: read.err().map_or(reason, |error| error.to_string()),
    })
}

/// The handshake, then the loop, on any connection (stdio, or memory in the tests).
pub fn serve(connection: &Connection) -> Result<(), String> {
    let initialize = serde_json::to_value(InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo {
            name: "awl".to_string(),
            version: Some(env!("CARGO_PKG_VERSION").to_string()),
        }),
    })
    .map_err(|error| error.to_string())?;
    let (id, params) = connection.initialize_start().map_err(protocol)?;
    connection
        .initialize_finish(id, initialize)
        .map_err(protocol)?;
    let params: InitializeParams = serde_json::from_value(params).unwrap_or_default();
    let mut server = Server::new(connection, params);
    server.main_loop()
}

fn protocol(error: lsp_server::ProtocolError) -> String {
    if error.channel_is_disconnected() {
        "its input ended before the session began".to_string()
    } else {
        error.to_string()
    }
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct InitializeResult {
    capabilities: ServerCapabilities,
    server_info: Option<ServerInfo>,
}

struct Server<'a> {
    connection: &'a Connection,
    workspace: Workspace,
    /// Documents changed since their diagnostics were last published.
    changed: Vec<Uri>,
}

/// Why a request got no result.
enum Failure {
    BadParams(String),
    NotFound,
}

impl<'a> Server<'a> {
    #[allow(deprecated)] // `root_uri`: the folder of clients that send no workspace folders
    fn new(connection: &'a Connection, params: InitializeParams) -> Self {
        let root = params
            .workspace_folders
            .as_ref()
            .and_then(|folders| folders.first())
            .map(|folder| &folder.uri)
            .or(params.root_uri.as_ref())
            .and_then(workspace::path_of);
        let mut server = Server {
            connection,
            workspace: Workspace {
                root,
                ..Workspace::default()
            },
            changed: Vec::new(),
        };
        server.take_settings(params.initialization_options);
        server
    }

    /// Reads what has arrived before acting on it, so a `$/cancelRequest` cancels a request
    /// still waiting behind others, and a burst of edits is checked once: diagnostics go out
    /// when nothing more is waiting.
    fn main_loop(&mut self) -> Result<(), String> {
        let mut waiting = VecDeque::new();
        loop {
            if waiting.is_empty() {
                self.publish_changed();
                match self.connection.receiver.recv() {
                    Ok(message) => waiting.push_back(message),
                    Err(_) => return Ok(()),
                }
            }
            waiting.extend(self.connection.receiver.try_iter());
            self.cancel_waiting(&mut waiting);
            let Some(message) = waiting.pop_front() else {
                continue;
            };
            match message {
                Message::Request(request) => match self.connection.handle_shutdown(&request) {
                    Ok(true) => return Ok(()),
                    Ok(false) => self.answer(request),
                    Err(error) => return Err(error.to_string()),
                },
                // `exit` without `shutdown` first: the client is done all the same.
                Message::Notification(notification) if notification.method == "exit" => {
                    return Ok(());
                }
                Message::Notification(notification) => self.notified(notification),
                Message::Response(_) => {}
            }
        }
    }

    /// Answers each waiting request a waiting `$/cancelRequest` names with `RequestCanceled`,
    /// and drops the cancellations (one for a request already answered has nothing to do).
    fn cancel_waiting(&self, waiting: &mut VecDeque<Message>) {
        let cancelled: Vec<RequestId> = waiting
            .iter()
            .filter_map(|message| match message {
                Message::Notification(notification)
                    if notification.method == notify::Cancel::METHOD =>
                {
                    serde_json::from_value::<lsp_types::CancelParams>(notification.params.clone())
                        .ok()
                        .map(|params| match params.id {
                            lsp_types::NumberOrString::Number(id) => RequestId::from(id),
                            lsp_types::NumberOrString::String(id) => RequestId::from(id),
                        })
                }
                _ => None,
            })
            .collect();
        if cancelled.is_empty() {
            return;
        }
        waiting.retain(|message| match message {
            Message::Notification(notification) => notification.method != notify::Cancel::METHOD,
            Message::Request(request) if cancelled.contains(&request.id) => {
                self.send(Message::Response(Response::new_err(
                    request.id.clone(),
                    ErrorCode::RequestCanceled as i32,
                    format!("`{}` was cancelled before it was answered", request.method),
                )));
                false
            }
            _ => true,
        });
    }

    fn send(&self, message: Message) {
        // A client that has gone cannot be told anything; the loop ends when its input does.
        let _ = self.connection.sender.send(message);
    }

    /// Answers one request, whatever happens in its handler.
    fn answer(&mut self, request: Request) {
        let id = request.id.clone();
        let method = request.method.clone();
        let outcome = std::panic::catch_unwind(AssertUnwindSafe(|| self.request(request)));
        let response = match outcome {
            Ok(Ok(value)) => Response::new_ok(id, value),
            Ok(Err(Failure::BadParams(reason))) => {
                Response::new_err(id, ErrorCode::InvalidParams as i32, reason)
            }
            Ok(Err(Failure::NotFound)) => Response::new_err(
                id,
                ErrorCode::MethodNotFound as i32,
                format!("awl lsp does not answer `{method}`"),
            ),
            Err(_) => Response::new_err(
                id,
                ErrorCode::InternalError as i32,
                format!("awl lsp failed on `{method}`; the document is kept"),
            ),
        };
        self.send(Message::Response(response));
    }

    fn request(&mut self, request: Request) -> Result<serde_json::Value, Failure> {
        match request.method.as_str() {
            req::HoverRequest::METHOD => {
                let params: lsp_types::HoverParams = params_of(request.params)?;
                let at = &params.text_document_position_params;
                let found = self.at_position(&at.text_document.uri, at.position, hover::hover);
                to_json(found.flatten())
            }
            req::GotoDefinition::METHOD => {
                let params: lsp_types::GotoDefinitionParams = params_of(request.params)?;
                let at = &params.text_document_position_params;
                let found = self.at_position(&at.text_document.uri, at.position, |a, o| {
                    navigate::target_at(a, o).and_then(|target| navigate::definition(a, &target))
                });
                to_json(found.flatten())
            }
            req::References::METHOD => {
                let params: lsp_types::ReferenceParams = params_of(request.params)?;
                let at = &params.text_document_position;
                let with_definition = params.context.include_declaration;
                let found = self.at_position(&at.text_document.uri, at.position, |a, o| {
                    navigate::target_at(a, o)
                        .map(|target| navigate::references(a, &target, with_definition))
                });
                to_json(found.flatten())
            }
            req::DocumentSymbolRequest::METHOD => {
                let params: lsp_types::DocumentSymbolParams = params_of(request.params)?;
                let uri = &params.text_document.uri;
                let found = self
                    .workspace
                    .documents
                    .get(uri)
                    .map(|text| navigate::document_symbols(&self.workspace.analyse(uri, text)));
                to_json(found)
            }
            req::WorkspaceSymbolRequest::METHOD => {
                let params: lsp_types::WorkspaceSymbolParams = params_of(request.params)?;
                to_json(navigate::workspace_symbols(&self.workspace, &params.query))
            }
            req::Completion::METHOD => {
                let params: lsp_types::CompletionParams = params_of(request.params)?;
                let at = &params.text_document_position;
                let found = self.analysed(&at.text_document.uri, |analysis| {
                    features::completions(analysis, at.position)
                });
                to_json(found)
            }
            req::CodeActionRequest::METHOD => {
                let params: lsp_types::CodeActionParams = params_of(request.params)?;
                let uri = &params.text_document.uri;
                let found = self.analysed(uri, |analysis| {
                    features::code_actions(analysis, uri, params.range)
                });
                to_json(found)
            }
            req::SemanticTokensFullRequest::METHOD => {
                let params: lsp_types::SemanticTokensParams = params_of(request.params)?;
                to_json(self.analysed(&params.text_document.uri, features::semantic_tokens))
            }
            req::Formatting::METHOD => {
                let params: lsp_types::DocumentFormattingParams = params_of(request.params)?;
                to_json(self.analysed(&params.text_document.uri, features::formatting))
            }
            _ => Err(Failure::NotFound),
        }
    }

    /// `handler` on the open document `uri` at `position`; `None` for a document not open.
    fn at_position<T>(
        &self,
        uri: &Uri,
        position: lsp_types::Position,
        handler: impl FnOnce(&workspace::Analysis, usize) -> T,
    ) -> Option<T> {
        let text = self.workspace.documents.get(uri)?;
        let analysis = self.workspace.analyse(uri, text);
        let offset = LineIndex::new(text).offset(position);
        Some(handler(&analysis, offset))
    }

    /// `handler` on the analysis of the open document `uri`; `None` for a document not open.
    fn analysed<T>(&self, uri: &Uri, handler: impl FnOnce(&workspace::Analysis) -> T) -> Option<T> {
        let text = self.workspace.documents.get(uri)?;
        Some(handler(&self.workspace.analyse(uri, text)))
    }

    fn notified(&mut self, notification: Notification) {
        match notification.method.as_str() {
            notify::DidOpenTextDocument::METHOD => {
                if let Ok(params) =
                    params_of::<lsp_types::DidOpenTextDocumentParams>(notification.params)
                {
                    let uri = params.text_document.uri;
                    self.workspace
                        .documents
                        .open(uri.clone(), params.text_document.text);
                    self.mark_changed(uri);
                }
            }
            notify::DidChangeTextDocument::METHOD => {
                if let Ok(params) =
                    params_of::<lsp_types::DidChangeTextDocumentParams>(notification.params)
                {
                    let uri = params.text_document.uri;
                    self.workspace
                        .documents
                        .change(&uri, params.content_changes);
                    self.mark_changed(uri);
                }
            }
            notify::DidCloseTextDocument::METHOD => {
                if let Ok(params) =
                    params_of::<lsp_types::DidCloseTextDocumentParams>(notification.params)
                {
                    let uri = params.text_document.uri;
                    self.workspace.documents.close(&uri);
                    self.changed.retain(|changed| *changed != uri);
                    self.publish_list(uri, Vec::new());
                }
            }
            notify::DidChangeConfiguration::METHOD => {
                // A client that pulls its configuration sends `null`: the settings stand.
                if let Ok(params) =
                    params_of::<lsp_types::DidChangeConfigurationParams>(notification.params)
                    && !params.settings.is_null()
                {
                    let settings = params
                        .settings
                        .get("awl")
                        .cloned()
                        .unwrap_or(params.settings);
                    self.take_settings(Some(settings));
                    let open: Vec<Uri> = self.workspace.documents.uris().cloned().collect();
                    for uri in open {
                        self.mark_changed(uri);
                    }
                }
            }
            // `$/cancelRequest` is taken while requests wait (`cancel_waiting`).
            _ => {}
        }
    }

    /// Uses the client's settings, or tells the user why they cannot be used.
    fn take_settings(&mut self, value: Option<serde_json::Value>) {
        match Settings::from_json(value) {
            Ok(settings) => self.workspace.settings = settings,
            Err(error) => {
                let report = miette::Report::new(error);
                let message = match report.help() {
                    Some(help) => format!(
                        "{report} ({}); help: {help}",
                        report.code().map(|c| c.to_string()).unwrap_or_default()
                    ),
                    None => report.to_string(),
                };
                let params = lsp_types::ShowMessageParams {
                    typ: lsp_types::MessageType::WARNING,
                    message,
                };
                self.send(Message::Notification(Notification::new(
                    notify::ShowMessage::METHOD.to_string(),
                    params,
                )));
            }
        }
    }

    fn mark_changed(&mut self, uri: Uri) {
        if !self.changed.contains(&uri) {
            self.changed.push(uri);
        }
    }

    fn publish_changed(&mut self) {
        for uri in std::mem::take(&mut self.changed) {
            self.publish(&uri);
        }
    }

    /// The diagnostics of the document and of its program's files that are not open (those
    /// have their own), after the front end has read it.
    fn publish(&self, uri: &Uri) {
        let Some(text) = self.workspace.documents.get(uri) else {
            return;
        };
        let found = std::panic::catch_unwind(AssertUnwindSafe(|| {
            diagnostics::of_program(&self.workspace.analyse(uri, text))
        }));
        // A front end that fails leaves the last diagnostics standing rather than the server.
        let Ok(found) = found else { return };
        for (file, (file_uri, list)) in found.into_iter().enumerate() {
            let file_uri = if file == 0 {
                Some(uri.clone())
            } else {
                file_uri
            };
            match file_uri {
                Some(file_uri)
                    if file == 0 || self.workspace.documents.get(&file_uri).is_none() =>
                {
                    self.publish_list(file_uri, list);
                }
                _ => {}
            }
        }
    }

    fn publish_list(&self, uri: Uri, diagnostics: Vec<lsp_types::Diagnostic>) {
        let params = PublishDiagnosticsParams {
            uri,
            diagnostics,
            version: None,
        };
        self.send(Message::Notification(Notification::new(
            notify::PublishDiagnostics::METHOD.to_string(),
            params,
        )));
    }
}

fn params_of<T: DeserializeOwned>(value: serde_json::Value) -> Result<T, Failure> {
    serde_json::from_value(value).map_err(|error| Failure::BadParams(error.to_string()))
}

fn to_json(value: impl Serialize) -> Result<serde_json::Value, Failure> {
    Ok(serde_json::to_value(value).unwrap_or(serde_json::Value::Null))
}

#[cfg(test)]
mod tests;
