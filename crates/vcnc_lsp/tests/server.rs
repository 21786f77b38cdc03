//! The server in memory (`lsp_server::Connection::memory`), fed what an
//! editor may send it: binary junk, a 10 MB line, a macro loop that never
//! ends, edits that come while a run is in flight, requests about closed
//! documents. Whatever comes, it answers and keeps serving.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::{Value, json};
use std::time::{Duration, Instant};

/// Longest wait for any one message: the runaway program runs to the
/// machine's limits (a million jumps) in a debug build.
const PATIENCE: Duration = Duration::from_secs(120);

struct Client {
    conn: Connection,
    server: Option<std::thread::JoinHandle<Result<(), String>>>,
    next: i32,
    notes: Vec<Notification>,
}

impl Client {
    fn start(settings: Value) -> Client {
        let (server, conn) = Connection::memory();
        let handle = std::thread::spawn(move || vcnc_lsp::server::serve(&server));
        let mut c = Client {
            conn,
            server: Some(handle),
            next: 0,
            notes: Vec::new(),
        };
        c.request(
            "initialize",
            json!({"capabilities": {}, "initializationOptions": settings}),
        )
        .unwrap();
        c.notify("initialized", json!({}));
        c
    }

    fn send_request(&mut self, method: &str, params: Value) -> RequestId {
        self.next += 1;
        let id = RequestId::from(self.next);
        self.conn
            .sender
            .send(Message::Request(Request::new(
                id.clone(),
                method.into(),
                params,
            )))
            .unwrap();
        id
    }

    fn wait(&mut self, id: &RequestId) -> Result<Value, i32> {
        loop {
            match self
                .conn
                .receiver
                .recv_timeout(PATIENCE)
                .expect("an answer in time")
            {
                Message::Response(r) if r.id == *id => {
                    return r.response_result.map_err(|e| e.code);
                }
                Message::Notification(n) => self.notes.push(n),
                _ => {}
            }
        }
    }

    fn request(&mut self, method: &str, params: Value) -> Result<Value, i32> {
        let id = self.send_request(method, params);
        self.wait(&id)
    }

    fn notify(&self, method: &str, params: Value) {
        self.conn
            .sender
            .send(Message::Notification(Notification::new(
                method.into(),
                params,
            )))
            .unwrap();
    }

    fn open(&self, uri: &str, version: i32, text: &str) {
        self.notify(
            "textDocument/didOpen",
            json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": version, "text": text}}),
        );
    }

    fn replace(&self, uri: &str, version: i32, text: &str) {
        self.notify(
            "textDocument/didChange",
            json!({"textDocument": {"uri": uri, "version": version}, "contentChanges": [{"text": text}]}),
        );
    }

    /// The diagnostics published for `uri` at `version`.
    fn diagnostics(&mut self, uri: &str, version: i32) -> Vec<Value> {
        let wanted = |n: &Notification| {
            n.method == "textDocument/publishDiagnostics"
                && n.params["uri"] == uri
                && n.params["version"] == json!(version)
        };
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Some(i) = self.notes.iter().position(wanted) {
                let n = self.notes.remove(i);
                return n.params["diagnostics"].as_array().unwrap().clone();
            }
            let left = deadline.saturating_duration_since(Instant::now());
            match self
                .conn
                .receiver
                .recv_timeout(left)
                .expect("diagnostics in time")
            {
                Message::Notification(n) => self.notes.push(n),
                other => panic!("unexpected {other:?}"),
            }
        }
    }

    fn stop(mut self) {
        assert_eq!(self.request("shutdown", Value::Null), Ok(Value::Null));
        self.notify("exit", Value::Null);
        let result = self.server.take().unwrap().join().unwrap();
        assert_eq!(result, Ok(()));
    }
}

fn codes(d: &[Value]) -> Vec<&str> {
    d.iter().map(|d| d["code"].as_str().unwrap_or("")).collect()
}

/// Every request the server answers, at a few places of the document.
fn ask_everything(c: &mut Client, uri: &str) {
    for (line, character) in [(0, 0), (0, 3), (1, 1), (5, 40), (99_999, 7)] {
        let at = json!({"textDocument": {"uri": uri}, "position": {"line": line, "character": character}});
        c.request("textDocument/hover", at.clone()).unwrap();
        c.request("textDocument/definition", at).unwrap();
    }
    c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": uri}}),
    )
    .unwrap();
    c.request(
        "textDocument/semanticTokens/full",
        json!({"textDocument": {"uri": uri}}),
    )
    .unwrap();
    let range = json!({"start": {"line": 0, "character": 0}, "end": {"line": 9, "character": 0}});
    c.request(
        "textDocument/inlayHint",
        json!({"textDocument": {"uri": uri}, "range": range}),
    )
    .unwrap();
}

#[test]
fn junk_and_huge_lines_are_reported_and_the_server_goes_on() {
    let mut c = Client::start(json!({"vcnc": {"inlayHints": true}}));
    // Bytes of every value, as an editor shows a binary file.
    let bytes: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13).to_le_bytes()[0])
        .collect();
    let junk = String::from_utf8_lossy(&bytes).into_owned();
    c.open("file:///tmp/junk.nc", 1, &junk);
    let d = c.diagnostics("file:///tmp/junk.nc", 1);
    assert!(!d.is_empty());
    ask_everything(&mut c, "file:///tmp/junk.nc");

    // A 10 MB line: the reader's line limit alarms, once.
    let huge = format!("G00 X0\n{}\nM30\n", "G01 X1. Y2. F100. ".repeat(600_000));
    assert!(huge.len() > 10_000_000);
    c.open("file:///tmp/huge.nc", 1, &huge);
    let d = c.diagnostics("file:///tmp/huge.nc", 1);
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0]["range"]["start"]["line"], 1);
    ask_everything(&mut c, "file:///tmp/huge.nc");

    // Requests about a document that is not open get empty answers.
    ask_everything(&mut c, "file:///tmp/never-opened.nc");
    // An unknown method is an error answer, not a dead server.
    assert_eq!(c.request("vcnc/nothing", json!({})), Err(-32601));
    c.stop();
}

#[test]
fn a_runaway_loop_ends_at_the_limit_and_an_edit_cancels_it() {
    let mut c = Client::start(json!({"vcnc": {"dialect": "fanuc"}}));
    let forever = "#1 = 0\nWHILE [1 EQ 1] DO1\n#1 = #1 + 1\nEND1\nM30\n";
    // Left alone, it runs into the machine's jump limit.
    c.open("file:///tmp/loop.nc", 1, forever);
    // The loop is not blocked while it runs: symbols come back at once.
    c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": "file:///tmp/loop.nc"}}),
    )
    .unwrap();
    let d = c.diagnostics("file:///tmp/loop.nc", 1);
    assert_eq!(codes(&d), vec!["E405"], "{d:?}");

    // The same loop, edited away while it runs: the old run is cancelled
    // and the new text's diagnostics arrive.
    c.open("file:///tmp/again.nc", 1, forever);
    c.replace("file:///tmp/again.nc", 2, "G00 X1.\nM30\n");
    let d = c.diagnostics("file:///tmp/again.nc", 2);
    assert!(d.is_empty(), "{d:?}");
    assert!(
        !c.notes
            .iter()
            .any(|n| n.params["uri"] == "file:///tmp/again.nc" && n.params["version"] == 1),
        "the cancelled run published"
    );

    // A hover on the runaway program waits for its run, on a thread; an
    // edit meanwhile answers it ContentModified.
    c.replace("file:///tmp/again.nc", 3, forever);
    let id = c.send_request(
        "textDocument/hover",
        json!({"textDocument": {"uri": "file:///tmp/again.nc"}, "position": {"line": 4, "character": 1}}),
    );
    c.replace("file:///tmp/again.nc", 4, "M30\n");
    assert_eq!(c.wait(&id), Err(-32801));
    c.stop();
}

#[test]
fn settings_choose_the_dialect_and_a_bad_one_is_shown() {
    let mut c = Client::start(json!({}));
    // G187 is no code of any dialect; an unknown dialect name is shown on
    // the first line instead of a run.
    c.notify(
        "workspace/didChangeConfiguration",
        json!({"settings": {"vcnc": {"dialect": "okuma"}}}),
    );
    c.open("file:///tmp/a.nc", 1, "G187\nM30\n");
    let d = c.diagnostics("file:///tmp/a.nc", 1);
    assert_eq!(d.len(), 1);
    assert!(
        d[0]["message"]
            .as_str()
            .unwrap()
            .contains("unknown dialect \"okuma\"")
    );
    // The first-line comment wins over the settings.
    c.replace(
        "file:///tmp/a.nc",
        2,
        "(vcnc: --dialect linuxcnc)\nG64 P0.01\nM2\n",
    );
    assert!(c.diagnostics("file:///tmp/a.nc", 2).is_empty());
    // Closing clears the document's diagnostics.
    c.notify(
        "textDocument/didClose",
        json!({"textDocument": {"uri": "file:///tmp/a.nc"}}),
    );
    let cleared = c.diagnostics_unversioned("file:///tmp/a.nc");
    assert!(cleared.is_empty());
    c.stop();
}

impl Client {
    /// The next diagnostics published for `uri` without a version (a
    /// closed document's).
    fn diagnostics_unversioned(&mut self, uri: &str) -> Vec<Value> {
        let deadline = Instant::now() + PATIENCE;
        loop {
            if let Some(i) = self.notes.iter().position(|n| {
                n.method == "textDocument/publishDiagnostics"
                    && n.params["uri"] == uri
                    && n.params.get("version").is_none_or(Value::is_null)
            }) {
                return self.notes.remove(i).params["diagnostics"]
                    .as_array()
                    .unwrap()
                    .clone();
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if let Message::Notification(n) = self.conn.receiver.recv_timeout(left).unwrap() {
                self.notes.push(n);
            }
        }
    }
}
