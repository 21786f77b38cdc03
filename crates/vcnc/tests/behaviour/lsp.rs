//! `vcnc lsp` driven over stdio by a JSON-RPC client written here (framing
//! by `Content-Length` headers, as the protocol's base layer says), not by
//! the server's own transport library: the bytes on the pipes are what an
//! editor sees.
//!
//! One session, as an editor runs it: initialize; open a program with two
//! independent mistakes (an arc whose end is off its circle, a G code the
//! dialect lacks) and get both; fix the arc and get one; hover G83; go
//! from `M98 P100` to `O100`; list the symbols, the tool change among
//! them; shut down and exit.

use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::{Duration, Instant};

/// How long any one answer may take before the test fails (a debug build
/// on a loaded 2-core machine answers in milliseconds).
const PATIENCE: Duration = Duration::from_secs(30);

struct Client {
    child: Child,
    stdin: ChildStdin,
    incoming: Receiver<Value>,
    next_id: i64,
    /// Notifications received while waiting for something else.
    notes: Vec<Value>,
}

impl Client {
    fn start() -> Client {
        let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
            .arg("lsp")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start vcnc lsp");
        let stdin = child.stdin.take().unwrap();
        let stdout = child.stdout.take().unwrap();
        let (tx, incoming) = channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(stdout);
            loop {
                let mut length = None;
                loop {
                    let mut header = String::new();
                    if r.read_line(&mut header).unwrap_or(0) == 0 {
                        return;
                    }
                    let header = header.trim_end();
                    if header.is_empty() {
                        break;
                    }
                    if let Some(n) = header.strip_prefix("Content-Length: ") {
                        length = n.parse::<usize>().ok();
                    }
                }
                let mut body = vec![0; length.expect("a Content-Length header")];
                r.read_exact(&mut body).unwrap();
                if tx.send(serde_json::from_slice(&body).unwrap()).is_err() {
                    return;
                }
            }
        });
        Client {
            child,
            stdin,
            incoming,
            next_id: 0,
            notes: Vec::new(),
        }
    }

    fn write(&mut self, msg: &Value) {
        let body = msg.to_string();
        write!(self.stdin, "Content-Length: {}\r\n\r\n{body}", body.len()).unwrap();
        self.stdin.flush().unwrap();
    }

    fn recv(&mut self, deadline: Instant) -> Value {
        let left = deadline.saturating_duration_since(Instant::now());
        match self.incoming.recv_timeout(left) {
            Ok(v) => v,
            Err(RecvTimeoutError::Timeout) => panic!("no message from the server in time"),
            Err(RecvTimeoutError::Disconnected) => panic!("the server closed its output"),
        }
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next_id += 1;
        let id = self.next_id;
        self.write(&json!({"jsonrpc": "2.0", "id": id, "method": method, "params": params}));
        let deadline = Instant::now() + PATIENCE;
        loop {
            let msg = self.recv(deadline);
            if msg["id"] == json!(id) && msg.get("method").is_none() {
                assert!(msg.get("error").is_none(), "{method}: {msg}");
                return msg["result"].clone();
            }
            self.notes.push(msg);
        }
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.write(&json!({"jsonrpc": "2.0", "method": method, "params": params}));
    }

    /// The diagnostics published for `version` of the document.
    fn diagnostics(&mut self, version: i64) -> Vec<Value> {
        let deadline = Instant::now() + PATIENCE;
        let wanted = |m: &Value| {
            m["method"] == "textDocument/publishDiagnostics"
                && m["params"]["version"] == json!(version)
        };
        if let Some(i) = self.notes.iter().position(wanted) {
            return self.notes.remove(i)["params"]["diagnostics"]
                .as_array()
                .unwrap()
                .clone();
        }
        loop {
            let msg = self.recv(deadline);
            if wanted(&msg) {
                return msg["params"]["diagnostics"].as_array().unwrap().clone();
            }
            self.notes.push(msg);
        }
    }
}

const URI: &str = "file:///tmp/vcnc-lsp-test/bracket.nc";

const PROGRAM: &str = "%
O0001 (BRACKET)
(T1 D=10. FLAT END MILL)
G90 G54 G17 G00 X0 Y0 Z5.
(DRILL CORNER)
T1 M06
S1200 M03
G83 X10. Y10. Z-12. R2. Q3. F80.
G80
(CONTOUR)
G01 X20. Y0 F200.
G02 X30. Y0 I3. J0.
G145 X40.
M98 P100
M30
O100 (SUB)
G00 Z10.
M99
%
";

fn codes(diagnostics: &[Value]) -> Vec<(String, u64)> {
    diagnostics
        .iter()
        .map(|d| {
            (
                d["code"].as_str().unwrap_or("").to_string(),
                d["range"]["start"]["line"].as_u64().unwrap(),
            )
        })
        .collect()
}

fn names(symbols: &Value, out: &mut Vec<(String, String)>) {
    for s in symbols.as_array().unwrap() {
        out.push((
            s["name"].as_str().unwrap().to_string(),
            s["detail"].as_str().unwrap_or("").to_string(),
        ));
        if let Some(children) = s.get("children").filter(|c| c.is_array()) {
            names(children, out);
        }
    }
}

#[test]
fn an_editor_session_over_stdio() {
    let mut c = Client::start();
    let init = c.request(
        "initialize",
        json!({
            "processId": null,
            "rootUri": null,
            "capabilities": {},
            "initializationOptions": { "vcnc": { "dialect": "fanuc" } },
        }),
    );
    assert_eq!(init["serverInfo"]["name"], "vcnc");
    assert_eq!(init["capabilities"]["hoverProvider"], true);
    c.notify("initialized", json!({}));

    // Two independent mistakes: both arrive, the later one marked.
    c.notify(
        "textDocument/didOpen",
        json!({"textDocument": {"uri": URI, "languageId": "gcode", "version": 1, "text": PROGRAM}}),
    );
    let d = c.diagnostics(1);
    // Line 12 (index 11): the arc from X20 about X23 ends 7 mm from its
    // centre, not 3; line 13 (index 12): Fanuc mills have no G145.
    assert_eq!(codes(&d), vec![("E303".into(), 11), ("E201".into(), 12)]);
    assert_eq!(d[0]["severity"], 1);
    assert_eq!(d[0]["range"]["end"]["character"], 3, "the span of G02");
    assert!(
        d[1]["message"]
            .as_str()
            .unwrap()
            .contains("after the alarm E303 at line 12")
    );
    assert_eq!(
        d[1]["relatedInformation"][0]["location"]["range"],
        d[0]["range"]
    );

    // Fix the arc (centre X25: radius 5 at both ends): one remains.
    c.notify(
        "textDocument/didChange",
        json!({
            "textDocument": {"uri": URI, "version": 2},
            "contentChanges": [{
                "range": {"start": {"line": 11, "character": 12}, "end": {"line": 11, "character": 15}},
                "text": "I5.",
            }],
        }),
    );
    let d = c.diagnostics(2);
    assert_eq!(codes(&d), vec![("E201".into(), 12)]);
    assert!(
        !d[0]["message"]
            .as_str()
            .unwrap()
            .contains("after the alarm")
    );

    // Hover on G83 (line 8, index 7).
    let h = c.request(
        "textDocument/hover",
        json!({"textDocument": {"uri": URI}, "position": {"line": 7, "character": 1}}),
    );
    let md = h["contents"]["value"].as_str().unwrap();
    assert!(md.contains("**G83**") && md.contains("peck"), "{md}");
    // The state at the end of that block: the cycle in force, F80, the
    // spindle on, T1 in the spindle, back at the initial level Z5 (G98).
    assert!(
        md.contains("G83") && md.contains("F80") && md.contains("M03"),
        "{md}"
    );
    assert!(md.contains("T1 in the spindle"), "{md}");
    assert!(md.contains("X10.000 Y10.000 Z5.000"), "{md}");

    // Definition of M98 P100 (line 14, index 13): the O100 header.
    let loc = c.request(
        "textDocument/definition",
        json!({"textDocument": {"uri": URI}, "position": {"line": 13, "character": 5}}),
    );
    assert_eq!(loc["uri"], URI);
    assert_eq!(
        loc["range"],
        json!({"start": {"line": 15, "character": 0}, "end": {"line": 15, "character": 4}})
    );

    // Symbols: the program, its operations, the tool change with its
    // description from the tool list.
    let s = c.request(
        "textDocument/documentSymbol",
        json!({"textDocument": {"uri": URI}}),
    );
    let mut got = Vec::new();
    names(&s, &mut got);
    assert!(
        got.contains(&("T1".to_string(), "D=10. FLAT END MILL".to_string())),
        "{got:?}"
    );
    assert!(got.iter().any(|(n, _)| n == "O100"), "{got:?}");

    let shut = c.request("shutdown", Value::Null);
    assert_eq!(shut, Value::Null);
    c.notify("exit", Value::Null);
    drop(c.stdin);
    let deadline = Instant::now() + PATIENCE;
    loop {
        if let Some(status) = c.child.try_wait().unwrap() {
            assert!(status.success(), "{status}");
            break;
        }
        assert!(Instant::now() < deadline, "the server did not exit");
        std::thread::sleep(Duration::from_millis(20));
    }
}
