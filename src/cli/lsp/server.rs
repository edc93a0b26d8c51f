//! The server's state and message loop: requests are answered in order,
//! edits mark their project for re-analysis, and diagnostics are published
//! once the client pauses (no message for [`SETTLE`]).

use super::convert;
use super::handlers;
use super::position::Columns;
use super::uri;
use super::workspace::{self, Workspace};
use lsp_server::{Connection, Message, Notification, Request, RequestId, Response};
use lsp_types as lsp;
use lsp_types::notification::Notification as _;
use plcrun::FileId;
use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// How long the client must be quiet before diagnostics are recomputed:
/// a burst of keystrokes costs one analysis.
const SETTLE: Duration = Duration::from_millis(60);

/// The server's state.
pub struct Server {
    pub ws: Workspace,
    pub columns: Columns,
    /// Projects edited since their diagnostics were last published.
    stale: HashSet<PathBuf>,
    /// The files each project last published diagnostics for.
    published: HashMap<PathBuf, Vec<PathBuf>>,
    /// Live values from a running plcrun, when asked for.
    pub live: Option<super::live::Live>,
    /// The client takes `workspace/inlayHint/refresh` requests.
    refresh_hints: bool,
    /// The number of the next request to the client.
    next_request: i32,
}

/// Where a request points: a project, a file of it and a byte offset.
pub struct Place {
    pub project: PathBuf,
    pub file: FileId,
    pub offset: u32,
}

/// An error answered to a request.
pub struct Failure {
    pub code: i32,
    pub message: String,
}

impl Failure {
    pub fn invalid(message: impl Into<String>) -> Failure {
        Failure {
            code: lsp_server::ErrorCode::InvalidParams as i32,
            message: message.into(),
        }
    }

    pub fn refused(message: impl Into<String>) -> Failure {
        Failure {
            code: lsp_server::ErrorCode::RequestFailed as i32,
            message: message.into(),
        }
    }
}

/// Initialises the session and answers until `exit`.
pub fn serve(connection: &Connection, live: Option<&str>) -> Result<(), String> {
    let (id, params) = connection.initialize_start().map_err(|e| e.to_string())?;
    let init: lsp::InitializeParams =
        serde_json::from_value(params).map_err(|e| format!("bad initialize request: {e}"))?;
    let utf8 = init
        .capabilities
        .general
        .as_ref()
        .and_then(|g| g.position_encodings.as_ref())
        .is_some_and(|e| e.contains(&lsp::PositionEncodingKind::UTF8));
    let columns = if utf8 { Columns::Utf8 } else { Columns::Utf16 };
    let option = init
        .initialization_options
        .as_ref()
        .and_then(|o| o["live"].as_str());
    let live = live.or(option).map(super::live::Live::new);
    let refresh_hints = init
        .capabilities
        .workspace
        .as_ref()
        .and_then(|w| w.inlay_hint.as_ref())
        .and_then(|h| h.refresh_support)
        .unwrap_or(false);
    let result = lsp::InitializeResult {
        capabilities: handlers::capabilities(utf8, live.is_some()),
        server_info: Some(lsp::ServerInfo {
            name: "plcrun".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    let result = serde_json::to_value(result).map_err(|e| e.to_string())?;
    connection
        .initialize_finish(id, result)
        .map_err(|e| e.to_string())?;
    let mut server = Server {
        ws: Workspace::new(roots(&init)),
        columns,
        stale: HashSet::new(),
        published: HashMap::new(),
        live,
        refresh_hints,
        next_request: 1,
    };
    server.run(connection)
}

/// The folders the client opened.
#[allow(deprecated)] // root_uri: older clients send only it.
fn roots(init: &lsp::InitializeParams) -> Vec<PathBuf> {
    let mut roots: Vec<PathBuf> = init
        .workspace_folders
        .iter()
        .flatten()
        .filter_map(|f| uri::to_path(&f.uri))
        .collect();
    if roots.is_empty() {
        roots.extend(init.root_uri.as_ref().and_then(uri::to_path));
    }
    roots.iter().map(|r| workspace::absolute(r)).collect()
}

impl Server {
    fn run(&mut self, connection: &Connection) -> Result<(), String> {
        loop {
            let message = match connection.receiver.recv_timeout(SETTLE) {
                Ok(m) => m,
                Err(e) if e.is_timeout() => {
                    self.publish(connection)?;
                    self.refresh_live_values(connection)?;
                    continue;
                }
                Err(_) => return Ok(()),
            };
            match message {
                Message::Request(request) => {
                    // After `shutdown`, a client that closes the pipe
                    // instead of sending `exit` has still asked to stop.
                    if connection.handle_shutdown(&request).unwrap_or(true) {
                        return Ok(());
                    }
                    // Answers must see the latest edits' diagnostics too.
                    self.publish(connection)?;
                    let response = self.answer(request);
                    send(connection, Message::Response(response))?;
                }
                Message::Notification(n) => {
                    if n.method == "exit" {
                        return Ok(());
                    }
                    // A malformed notification is the client's bug: say
                    // so on stderr (the client's log) and go on.
                    if let Err(e) = self.notified(n) {
                        sayln!("plcrun lsp: {e}");
                    }
                }
                Message::Response(_) => {}
            }
        }
    }

    /// Asks the client to fetch the inlay hints again when the running
    /// PLC's values moved on since it last did.
    fn refresh_live_values(&mut self, connection: &Connection) -> Result<(), String> {
        let Some(live) = &mut self.live else {
            return Ok(());
        };
        if !self.refresh_hints || !live.poll() {
            return Ok(());
        }
        let id = RequestId::from(self.next_request);
        self.next_request += 1;
        let method = <lsp::request::InlayHintRefreshRequest as lsp::request::Request>::METHOD;
        let request = Request::new(id, method.to_string(), serde_json::Value::Null);
        send(connection, Message::Request(request))
    }

    fn answer(&mut self, request: Request) -> Response {
        let id: RequestId = request.id.clone();
        match handlers::dispatch(self, &request.method, request.params) {
            Ok(value) => Response::new_ok(id, value),
            Err(f) => Response::new_err(id, f.code, f.message),
        }
    }

    fn notified(&mut self, n: Notification) -> Result<(), String> {
        use lsp::notification::{
            DidChangeTextDocument, DidChangeWatchedFiles, DidCloseTextDocument,
            DidOpenTextDocument, DidSaveTextDocument,
        };
        match n.method.as_str() {
            DidOpenTextDocument::METHOD => {
                let p: lsp::DidOpenTextDocumentParams = parse(n.params)?;
                if let Some(path) = self.path(&p.text_document.uri) {
                    self.ws.open.insert(path.clone(), p.text_document.text);
                    self.edited(&path);
                }
            }
            DidChangeTextDocument::METHOD => {
                let p: lsp::DidChangeTextDocumentParams = parse(n.params)?;
                if let Some(path) = self.path(&p.text_document.uri) {
                    // Full synchronisation: the last change is the text.
                    if let Some(change) = p.content_changes.into_iter().last() {
                        self.ws.open.insert(path.clone(), change.text);
                        self.edited(&path);
                    }
                }
            }
            DidCloseTextDocument::METHOD => {
                let p: lsp::DidCloseTextDocumentParams = parse(n.params)?;
                if let Some(path) = self.path(&p.text_document.uri) {
                    self.ws.open.remove(&path);
                    self.edited(&path);
                }
            }
            DidSaveTextDocument::METHOD => {
                let p: lsp::DidSaveTextDocumentParams = parse(n.params)?;
                if let Some(path) = self.path(&p.text_document.uri) {
                    if path.file_name().is_some_and(|f| f == "plcrun.toml") {
                        self.ws.forget_description(&path);
                    }
                    self.edited(&path);
                }
            }
            DidChangeWatchedFiles::METHOD => {
                let p: lsp::DidChangeWatchedFilesParams = parse(n.params)?;
                for change in p.changes {
                    if let Some(path) = self.path(&change.uri) {
                        self.ws.forget_description(&path);
                        self.edited(&path);
                    }
                }
            }
            _ => {}
        }
        Ok(())
    }

    fn edited(&mut self, path: &Path) {
        let key = self.ws.touch(path);
        self.stale.insert(key);
    }

    /// The local path of `uri`, made canonical.
    pub fn path(&self, uri: &lsp::Uri) -> Option<PathBuf> {
        uri::to_path(uri).map(|p| workspace::absolute(&p))
    }

    /// The project, file and offset a document position names.
    pub fn place(
        &mut self,
        doc: &lsp::TextDocumentIdentifier,
        pos: lsp::Position,
    ) -> Result<Place, Failure> {
        let path = self
            .path(&doc.uri)
            .ok_or_else(|| Failure::invalid("only file:// documents are served"))?;
        let project = self.ws.project_of(&path);
        let columns = self.columns;
        let open = &self.ws.open;
        let p = self
            .ws
            .projects
            .get_mut(&project)
            .expect("found by project_of");
        let file = p
            .file_id(&path)
            .ok_or_else(|| Failure::invalid("the document is not part of its project"))?;
        let analysis = p.analysis(open);
        let offset = columns.offset(analysis.sources().file(file), pos);
        Ok(Place {
            project,
            file,
            offset,
        })
    }

    /// The analysis of project `key`.
    pub fn analysis(&mut self, key: &Path) -> Option<&plcrun::Analysis> {
        let open = &self.ws.open;
        Some(self.ws.projects.get_mut(key)?.analysis(open))
    }

    /// Every project analysed, for workspace-wide requests.
    pub fn all_analyses(&mut self) -> Vec<(PathBuf, &plcrun::Analysis)> {
        let open = &self.ws.open;
        self.ws
            .projects
            .iter_mut()
            .map(|(k, p)| (k.clone(), p.analysis(open)))
            .collect()
    }

    /// Publishes the diagnostics of every project edited since last time.
    fn publish(&mut self, connection: &Connection) -> Result<(), String> {
        let columns = self.columns;
        for key in std::mem::take(&mut self.stale) {
            let Some(project) = self.ws.projects.get_mut(&key) else {
                continue;
            };
            if let Some(problem) = project.problem.take() {
                let show = lsp::ShowMessageParams {
                    typ: lsp::MessageType::ERROR,
                    message: problem,
                };
                notify::<lsp::notification::ShowMessage>(connection, show)?;
            }
            let files = project.files.clone();
            let analysis = project.analysis(&self.ws.open);
            let mut by_file: Vec<Vec<lsp::Diagnostic>> = vec![Vec::new(); files.len()];
            for d in analysis.diagnostics().iter() {
                let i = d.span.file.0 as usize;
                if i < files.len() {
                    let file = analysis.sources().file(d.span.file);
                    by_file[i].push(convert::diagnostic(d, file, columns));
                }
            }
            // Files that left the project lose the diagnostics it gave them.
            let before = self.published.insert(key.clone(), files.clone());
            let gone: Vec<PathBuf> = before
                .into_iter()
                .flatten()
                .filter(|f| !files.contains(f))
                .collect();
            by_file.resize(files.len() + gone.len(), Vec::new());
            for (path, diagnostics) in files.iter().chain(&gone).zip(by_file) {
                let Some(uri) = uri::from_path(path) else {
                    continue;
                };
                let params = lsp::PublishDiagnosticsParams {
                    uri,
                    diagnostics,
                    version: None,
                };
                notify::<lsp::notification::PublishDiagnostics>(connection, params)?;
            }
        }
        Ok(())
    }
}

fn parse<T: serde::de::DeserializeOwned>(params: serde_json::Value) -> Result<T, String> {
    serde_json::from_value(params).map_err(|e| format!("bad notification: {e}"))
}

fn send(connection: &Connection, message: Message) -> Result<(), String> {
    connection
        .sender
        .send(message)
        .map_err(|_| "the client went away".to_string())
}

fn notify<N: lsp::notification::Notification>(
    connection: &Connection,
    params: N::Params,
) -> Result<(), String> {
    let params = serde_json::to_value(params).map_err(|e| e.to_string())?;
    send(
        connection,
        Message::Notification(Notification::new(N::METHOD.to_string(), params)),
    )
}
