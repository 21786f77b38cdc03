//! Diagnostics of a 10,000-line program after an edit, the target
//! being 50 ms (docs/performance.md has the figures):
//!
//! - `edit_to_diagnostics`: the whole path, through the server in memory
//!   (`lsp_server::Connection::memory`): a `didChange` of one word goes
//!   in, the `publishDiagnostics` of that version comes out (the edit
//!   applied, the run on its thread, the alarms and warnings converted);
//! - `diagnose`: the run alone (`vcnc_lsp::analysis::diagnose`);
//! - `semantic_tokens`, `outline`: the requests an editor sends after each
//!   edit besides.
//!
//! The program is a CAM-style mill program: a tool list, four operations,
//! each a tool change and 2,500 lines of G01/G02/G03 contours and G81/G83
//! holes, and one arc whose end is off its circle (an alarm the run goes
//! on after), so every run reports something.
//!
//! `cargo bench -p vcnc_lsp --bench diagnostics`

use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::json;
use std::fmt::Write as _;
use std::str::FromStr;
use std::sync::atomic::AtomicBool;
use vcnc_lsp::analysis::{Job, diagnose};
use vcnc_lsp::dialect::Choice;
use vcnc_lsp::text::Text;

fn main() {
    divan::main();
}

const LINES: usize = 10_000;

/// The 10,000-line program.
fn program() -> String {
    let mut p = String::from("%\nO1000 (BENCH PART)\n");
    for t in 1..=4 {
        let _ = writeln!(p, "(T{t} D={}. FLAT END MILL)", 4 + 2 * t);
    }
    p.push_str("G90 G54 G17 G21 G40 G49 G80\n");
    let mut line = p.lines().count();
    let mut n = 0u32;
    // Where the tool is in XY: arcs start there.
    let (mut px, mut py) = (0.0, 0.0);
    for t in 1..=4 {
        let _ = writeln!(
            p,
            "(OPERATION {t})\nT{t} M06\nS{} M03\nG00 G43 Z5. H{t}",
            3000 + 500 * t
        );
        line += 4;
        while line < LINES * t / 4 - 2 {
            n += 1;
            let x = f64::from(n % 200) * 0.5;
            let y = f64::from(n % 130) * 0.25;
            let _ = match n % 10 {
                0 => writeln!(p, "G81 X{x:.3} Y{y:.3} Z-3. R2. F120."),
                1 => writeln!(p, "G83 X{x:.3} Y{y:.3} Z-9. R2. Q2. F90."),
                2 => writeln!(p, "G80"),
                // A half circle of radius 1 out and back.
                3 => writeln!(p, "G02 X{:.3} Y{py:.3} I1. J0. F400.", px + 2.0),
                4 => writeln!(p, "G03 X{px:.3} Y{py:.3} I-1. J0."),
                _ => writeln!(p, "G01 X{x:.3} Y{y:.3} Z-1. F600."),
            };
            if !matches!(n % 10, 2..=4) {
                (px, py) = (x, y);
            }
            line += 1;
        }
        p.push_str("G00 Z50.\nM05\n");
        line += 2;
    }
    // One arc whose end is off its circle (radius 1 at the start, 3 at the end).
    p.push_str("G00 X0 Y0\nG02 X4. Y0 I1. J0. F300.\nM30\n");
    p
}

fn job(text: &str) -> Job {
    Job::for_text(
        text,
        Choice {
            name: "fanuc",
            why: String::new(),
        },
    )
}

#[divan::bench(sample_count = 30)]
fn diagnose_10k_lines(bencher: divan::Bencher) {
    let text = program();
    assert!(text.lines().count() >= LINES);
    let job = job(&text);
    let uri = lsp_types::Uri::from_str("file:///bench.nc").unwrap_or_else(|_| unreachable!());
    let cancel = AtomicBool::new(false);
    bencher.bench_local(|| diagnose(&job, &uri, &cancel));
}

#[divan::bench(sample_count = 30)]
fn semantic_tokens_10k_lines(bencher: divan::Bencher) {
    let text = Text::new(program());
    let lex = vcnc_interp::Dialect::fanuc().lex;
    bencher.bench_local(|| vcnc_lsp::tokens::semantic_tokens(&text, &lex));
}

#[divan::bench(sample_count = 30)]
fn outline_10k_lines(bencher: divan::Bencher) {
    let text = Text::new(program());
    let dialect = vcnc_interp::Dialect::fanuc();
    bencher.bench_local(|| vcnc_lsp::symbols::outline(&text, &dialect));
}

/// An edit of one word in the middle of the program, and its diagnostics.
#[divan::bench(sample_count = 30)]
fn edit_to_diagnostics_10k_lines(bencher: divan::Bencher) {
    let (server, client) = Connection::memory();
    let handle = std::thread::spawn(move || vcnc_lsp::server::serve(&server));
    let send = |m: Message| {
        let _ = client.sender.send(m);
    };
    send(Message::Request(Request::new(
        RequestId::from(1),
        "initialize".into(),
        json!({"capabilities": {}, "initializationOptions": {"vcnc": {"dialect": "fanuc"}}}),
    )));
    let _ = client.receiver.recv();
    send(Message::Notification(Notification::new(
        "initialized".into(),
        json!({}),
    )));
    let text = program();
    let uri = "file:///bench.nc";
    send(Message::Notification(Notification::new(
        "textDocument/didOpen".into(),
        json!({"textDocument": {"uri": uri, "languageId": "gcode", "version": 1, "text": text}}),
    )));
    let wait = |version: i32| loop {
        match client.receiver.recv() {
            Ok(Message::Notification(n))
                if n.method == "textDocument/publishDiagnostics"
                    && n.params["version"] == json!(version) =>
            {
                return n.params["diagnostics"].as_array().map_or(0, Vec::len);
            }
            Ok(_) => {}
            Err(_) => return 0,
        }
    };
    assert_eq!(wait(1), 1);
    let mut version = 1;
    bencher.bench_local(|| {
        version += 1;
        // Line 5,000 is a G01 or G81 … line: its first character `G` is
        // typed again, so every version has the same diagnostics.
        let first = "G";
        send(Message::Notification(Notification::new(
            "textDocument/didChange".into(),
            json!({
                "textDocument": {"uri": uri, "version": version},
                "contentChanges": [{
                    "range": {"start": {"line": 5000, "character": 0}, "end": {"line": 5000, "character": 1}},
                    "text": first,
                }],
            }),
        )));
        wait(version)
    });
    send(Message::Request(Request::new(
        RequestId::from(2),
        "shutdown".into(),
        json!(null),
    )));
    send(Message::Notification(Notification::new(
        "exit".into(),
        json!(null),
    )));
    drop(client);
    let _ = handle.join();
}
