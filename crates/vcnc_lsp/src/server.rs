//! The server's loop: messages from the client in, work out to threads,
//! results back in, answers out. The loop itself never interprets a
//! program, so a runaway macro loop or a 10 MB line never blocks it.
//!
//! ```text
//!   client ─▶ receiver ─┐                          ┌─▶ thread: diagnose(job)  ─┐
//!                       ├─ select ─▶ handle ─ spawn┼─▶ thread: hover(job)     ─┼─▶ done ─┐
//!   done   ─────────────┘              │           └─▶ thread: symbols …      ─┘         │
//!                                      ▼                                               ▼
//!                          documents (text, version, cancel flag)      publish if still current
//! ```
//!
//! Each open document has a cancel flag shared by the work started on its
//! current text; an edit sets it (the runs stop at their next block) and
//! starts afresh with a new flag. Diagnostics of a text that has changed
//! since are dropped; a request whose text changed is answered
//! `ContentModified`. Every piece of work runs under `catch_unwind`, and
//! so does every message the loop handles: a bug becomes an error
//! answer and a log message, never a dead server.

use crate::analysis::{Job, diagnose};
use crate::dialect::{self, Choice};
use crate::settings::Settings;
use crate::text::Text;
use crate::{definition, hover, inlay, symbols, tokens, uri};
use crossbeam_channel::{Receiver, Sender, select, unbounded};
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{self as note, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::{
    Diagnostic, DocumentSymbolResponse, GotoDefinitionResponse, InitializeParams, MessageType,
    OneOf, PublishDiagnosticsParams, SemanticTokens, SemanticTokensResult, ServerCapabilities,
    TextDocumentSyncCapability, TextDocumentSyncKind, Uri,
};
use serde_json::{Value, json};
use std::collections::HashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use vcnc_interp::{Machine, Options};

/// A worker thread's stack: deep call chains of macro programs stay far
/// inside it.
const WORKER_STACK: usize = 16 << 20;

/// What the server advertises.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(
            TextDocumentSyncKind::INCREMENTAL,
        )),
        hover_provider: Some(lsp_types::HoverProviderCapability::Simple(true)),
        definition_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        semantic_tokens_provider: Some(
            lsp_types::SemanticTokensServerCapabilities::SemanticTokensOptions(
                lsp_types::SemanticTokensOptions {
                    legend: tokens::legend(),
                    full: Some(lsp_types::SemanticTokensFullOptions::Bool(true)),
                    range: None,
                    work_done_progress_options: Default::default(),
                },
            ),
        ),
        inlay_hint_provider: Some(OneOf::Left(true)),
        ..ServerCapabilities::default()
    }
}

/// Serves one client over `conn` until it says `exit` (or goes away).
pub fn serve(conn: &Connection) -> Result<(), String> {
    let caps = serde_json::to_value(capabilities()).map_err(|e| e.to_string())?;
    let (id, params) = conn.initialize_start().map_err(|e| e.to_string())?;
    let init: InitializeParams = serde_json::from_value(params).unwrap_or_default();
    let result = json!({
        "capabilities": caps,
        "serverInfo": { "name": "vcnc", "version": env!("CARGO_PKG_VERSION") },
    });
    conn.initialize_finish(id, result)
        .map_err(|e| e.to_string())?;
    let mut server = Server::new(conn.sender.clone(), &init);
    server.run(&conn.receiver);
    Ok(())
}

/// One open document.
struct Doc {
    uri: Uri,
    version: i32,
    text: Arc<Text>,
    /// Set when this text is replaced: its work stops.
    cancel: Arc<AtomicBool>,
}

/// Work finished on a thread.
enum Done {
    Publish {
        uri: Uri,
        version: i32,
        diagnostics: Vec<Diagnostic>,
    },
    Reply(Response),
    Log(String),
}

struct Server {
    out: Sender<Message>,
    done_tx: Sender<Done>,
    done_rx: Receiver<Done>,
    docs: HashMap<String, Doc>,
    settings: Settings,
    machine: Result<Option<Arc<Machine>>, String>,
    tools: Result<Option<Arc<vcnc_core::ToolLibrary>>, String>,
    root: Option<PathBuf>,
    shut_down: bool,
}

impl Server {
    fn new(out: Sender<Message>, init: &InitializeParams) -> Server {
        let (done_tx, done_rx) = unbounded();
        #[allow(deprecated)] // root_uri: the fallback of clients without workspace folders
        let root = init
            .workspace_folders
            .as_ref()
            .and_then(|f| f.first())
            .map(|f| &f.uri)
            .or(init.root_uri.as_ref())
            .and_then(uri::to_path);
        let mut server = Server {
            out,
            done_tx,
            done_rx,
            docs: HashMap::new(),
            settings: Settings::default(),
            machine: Ok(None),
            tools: Ok(None),
            root,
            shut_down: false,
        };
        if let Some(options) = &init.initialization_options {
            server.configure(Settings::from_json(options));
        }
        server
    }

    fn run(&mut self, receiver: &Receiver<Message>) {
        loop {
            select! {
                recv(receiver) -> msg => {
                    let Ok(msg) = msg else { return };
                    let exit = matches!(&msg, Message::Notification(n) if n.method == note::Exit::METHOD);
                    if exit {
                        return;
                    }
                    if catch_unwind(AssertUnwindSafe(|| self.handle(msg))).is_err() {
                        self.log("vcnc: an internal error while handling a message (a bug); the server goes on");
                    }
                }
                recv(self.done_rx) -> done => {
                    if let Ok(done) = done {
                        self.finish(done);
                    }
                }
            }
        }
    }

    fn send(&self, msg: impl Into<Message>) {
        let _ = self.out.send(msg.into());
    }

    fn log(&self, message: &str) {
        self.send(Notification::new(
            note::LogMessage::METHOD.into(),
            lsp_types::LogMessageParams {
                typ: MessageType::WARNING,
                message: message.into(),
            },
        ));
    }

    fn handle(&mut self, msg: Message) {
        match msg {
            Message::Request(r) => self.request(r),
            Message::Notification(n) => self.notification(n),
            Message::Response(_) => {}
        }
    }

    fn finish(&mut self, done: Done) {
        match done {
            Done::Publish {
                uri,
                version,
                diagnostics,
            } => {
                let current = self
                    .docs
                    .get(uri.as_str())
                    .is_some_and(|d| d.version == version);
                if current {
                    self.publish(uri, Some(version), diagnostics);
                }
            }
            Done::Reply(r) => self.send(r),
            Done::Log(m) => self.log(&m),
        }
    }

    fn publish(&self, uri: Uri, version: Option<i32>, diagnostics: Vec<Diagnostic>) {
        self.send(Notification::new(
            note::PublishDiagnostics::METHOD.into(),
            PublishDiagnosticsParams {
                uri,
                diagnostics,
                version,
            },
        ));
    }

    // ── notifications ────────────────────────────────────────────────

    fn notification(&mut self, n: Notification) {
        match n.method.as_str() {
            note::DidOpenTextDocument::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(n.params)
                {
                    let d = p.text_document;
                    let doc = Doc {
                        uri: d.uri.clone(),
                        version: d.version,
                        text: Arc::new(Text::new(d.text)),
                        cancel: Arc::new(AtomicBool::new(false)),
                    };
                    self.docs.insert(d.uri.as_str().to_string(), doc);
                    self.diagnose(d.uri.as_str());
                }
            }
            note::DidChangeTextDocument::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params)
                {
                    let key = p.text_document.uri.as_str().to_string();
                    if let Some(doc) = self.docs.get_mut(&key) {
                        doc.cancel.store(true, Ordering::Relaxed);
                        doc.cancel = Arc::new(AtomicBool::new(false));
                        let text = Arc::make_mut(&mut doc.text);
                        for change in p.content_changes {
                            text.edit(change.range, &change.text);
                        }
                        doc.version = p.text_document.version;
                        self.diagnose(&key);
                    }
                }
            }
            note::DidCloseTextDocument::METHOD => {
                let closed =
                    serde_json::from_value::<lsp_types::DidCloseTextDocumentParams>(n.params)
                        .ok()
                        .and_then(|p| self.docs.remove(p.text_document.uri.as_str()));
                if let Some(doc) = closed {
                    doc.cancel.store(true, Ordering::Relaxed);
                    self.publish(doc.uri, None, Vec::new());
                }
            }
            note::DidChangeConfiguration::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidChangeConfigurationParams>(n.params)
                {
                    self.configure(Settings::from_json(&p.settings));
                    let keys: Vec<String> = self.docs.keys().cloned().collect();
                    for key in keys {
                        if let Some(doc) = self.docs.get_mut(&key) {
                            doc.cancel.store(true, Ordering::Relaxed);
                            doc.cancel = Arc::new(AtomicBool::new(false));
                        }
                        self.diagnose(&key);
                    }
                }
            }
            _ => {}
        }
    }

    fn configure(&mut self, settings: Settings) {
        self.machine = settings.load_machine(self.root.as_deref());
        self.tools = settings.load_tools(self.root.as_deref());
        self.settings = settings;
    }

    /// The job of a document's current text.
    fn job(&self, doc: &Doc) -> Job {
        let path = uri::to_path(&doc.uri);
        let mut setup_errors = Vec::new();
        let (choice, dialect_error) = match dialect::choose(
            doc.text.as_str(),
            path.as_deref(),
            self.settings.dialect.as_deref(),
        ) {
            Ok(c) => (c, None),
            Err(e) => (
                Choice {
                    name: "fanuc",
                    why: "the fallback after an unknown dialect name".into(),
                },
                Some(e),
            ),
        };
        let machine = match &self.machine {
            Ok(m) => m.clone(),
            Err(e) => {
                setup_errors.push(format!("{e} (the dialect's built-in machine is used)"));
                None
            }
        };
        let tools = match &self.tools {
            Ok(t) => t.clone(),
            Err(e) => {
                setup_errors.push(format!(
                    "{e} (the machine's registers are used as they are)"
                ));
                None
            }
        };
        Job {
            text: Arc::clone(&doc.text),
            path,
            choice,
            machine,
            tools,
            program_dir: self.settings.program_dir(self.root.as_deref()),
            options: Options {
                block_delete: self.settings.block_delete,
                optional_stop: self.settings.optional_stop,
                keep_going: true,
            },
            setup_errors,
            dialect_error,
        }
    }

    fn diagnose(&self, key: &str) {
        let Some(doc) = self.docs.get(key) else {
            return;
        };
        let job = self.job(doc);
        let (uri, version, cancel) = (doc.uri.clone(), doc.version, Arc::clone(&doc.cancel));
        spawn(self.done_tx.clone(), None, move || {
            diagnose(&job, &uri, &cancel).map(|diagnostics| Done::Publish {
                uri,
                version,
                diagnostics,
            })
        });
    }

    // ── requests ─────────────────────────────────────────────────────

    fn request(&mut self, r: Request) {
        if r.method == req::Shutdown::METHOD {
            self.shut_down = true;
            for doc in self.docs.values() {
                doc.cancel.store(true, Ordering::Relaxed);
            }
            self.send(Response::new_ok(r.id, ()));
            return;
        }
        if self.shut_down {
            self.send(Response::new_err(
                r.id,
                ErrorCode::InvalidRequest as i32,
                "the server is shutting down".into(),
            ));
            return;
        }
        let id = r.id.clone();
        let answered = match r.method.as_str() {
            req::HoverRequest::METHOD => self.on_doc::<lsp_types::HoverParams>(
                r,
                |p| (p.text_document_position_params.text_document.uri.clone(), p),
                |job, _, p, cancel| {
                    json(hover::hover(
                        job,
                        p.text_document_position_params.position,
                        cancel,
                    ))
                },
            ),
            req::GotoDefinition::METHOD => self.on_doc::<lsp_types::GotoDefinitionParams>(
                r,
                |p| (p.text_document_position_params.text_document.uri.clone(), p),
                |job, uri, p, _| {
                    json(
                        definition::definition(job, uri, p.text_document_position_params.position)
                            .map(GotoDefinitionResponse::Scalar),
                    )
                },
            ),
            req::DocumentSymbolRequest::METHOD => self.on_doc::<lsp_types::DocumentSymbolParams>(
                r,
                |p| (p.text_document.uri.clone(), p),
                |job, _, _, _| {
                    json(DocumentSymbolResponse::Nested(symbols::outline(
                        &job.text,
                        &job.choice.dialect(),
                    )))
                },
            ),
            req::SemanticTokensFullRequest::METHOD => self
                .on_doc::<lsp_types::SemanticTokensParams>(
                    r,
                    |p| (p.text_document.uri.clone(), p),
                    |job, _, _, _| {
                        let data = tokens::semantic_tokens(&job.text, &job.choice.dialect().lex);
                        json(SemanticTokensResult::Tokens(SemanticTokens {
                            result_id: None,
                            data,
                        }))
                    },
                ),
            req::InlayHintRequest::METHOD => {
                let enabled = self.settings.inlay_hints;
                self.on_doc::<lsp_types::InlayHintParams>(
                    r,
                    |p| (p.text_document.uri.clone(), p),
                    move |job, _, _, cancel| {
                        if !enabled {
                            return Some(json!([]));
                        }
                        inlay::operation_times(job, cancel).and_then(json)
                    },
                )
            }
            _ => false,
        };
        if !answered {
            self.send(Response::new_err(
                id,
                ErrorCode::MethodNotFound as i32,
                "vcnc does not answer this request".into(),
            ));
        }
    }

    /// Answers a request about one document on a thread: `key` reads the
    /// parameters and names the document, `work` answers (`None`: the
    /// document changed meanwhile). Returns whether the method was one of
    /// these (a bad parameter or an unknown document is still answered).
    fn on_doc<P>(
        &self,
        r: Request,
        key: impl FnOnce(P) -> (Uri, P),
        work: impl FnOnce(&Job, &Uri, &P, &AtomicBool) -> Option<Value> + Send + 'static,
    ) -> bool
    where
        P: serde::de::DeserializeOwned + Send + 'static,
    {
        let id = r.id.clone();
        let r_id = r.id.clone();
        let params: P = match serde_json::from_value(r.params) {
            Ok(p) => p,
            Err(e) => {
                self.send(Response::new_err(
                    id,
                    ErrorCode::InvalidParams as i32,
                    e.to_string(),
                ));
                return true;
            }
        };
        let (uri, params) = key(params);
        let Some(doc) = self.docs.get(uri.as_str()) else {
            self.send(Response::new_ok(id, Value::Null));
            return true;
        };
        let job = self.job(doc);
        let cancel = Arc::clone(&doc.cancel);
        spawn(self.done_tx.clone(), Some(r_id), move || {
            let answer = work(&job, &uri, &params, &cancel);
            Some(reply(
                id,
                answer.filter(|_| !cancel.load(Ordering::Relaxed)),
            ))
        });
        true
    }
}

/// A value as JSON (`null` for `None`).
fn json<T: serde::Serialize>(v: T) -> Option<Value> {
    serde_json::to_value(v).ok()
}

fn reply(id: RequestId, answer: Option<Value>) -> Done {
    Done::Reply(match answer {
        Some(v) => Response::new_ok(id, v),
        None => Response::new_err(
            id,
            ErrorCode::ContentModified as i32,
            "the document changed".into(),
        ),
    })
}

/// Runs `work` on its own thread and sends what it returns. A panic is
/// logged and, when the work answers request `id`, answered as an internal
/// error, so the client never waits for an answer that will not come.
fn spawn(
    tx: Sender<Done>,
    id: Option<RequestId>,
    work: impl FnOnce() -> Option<Done> + Send + 'static,
) {
    let on_panic = id.clone();
    let tx2 = tx.clone();
    let thread = std::thread::Builder::new()
        .name("vcnc-lsp-work".into())
        .stack_size(WORKER_STACK)
        .spawn(move || match catch_unwind(AssertUnwindSafe(work)) {
            Ok(Some(done)) => {
                let _ = tx.send(done);
            }
            Ok(None) => {}
            Err(_) => {
                let _ = tx.send(Done::Log(
                    "vcnc: an internal error while answering (a bug); the server goes on".into(),
                ));
                if let Some(id) = on_panic {
                    let _ = tx.send(Done::Reply(internal_error(id)));
                }
            }
        });
    if thread.is_err() {
        let _ = tx2.send(Done::Log("vcnc: cannot start a thread".into()));
        if let Some(id) = id {
            let _ = tx2.send(Done::Reply(internal_error(id)));
        }
    }
}

fn internal_error(id: RequestId) -> Response {
    Response::new_err(
        id,
        ErrorCode::InternalError as i32,
        "vcnc: internal error (a bug)".into(),
    )
}
