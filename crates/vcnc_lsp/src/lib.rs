//! `vcnc_lsp`: the language server behind `vcnc lsp` (docs/editor.md), and
//! the dialect choice the Python module shares with it.
//!
//! ```text
//!   stdio ─▶ lsp-server (JSON-RPC framing, threads) ─▶ server (loop, documents, settings)
//!                                                        │ spawn per piece of work
//!             analysis (interpreter runs: diagnostics, state after a line, line times)
//!             hover · definition · symbols · tokens · inlay      (answers)
//!             scan (pieces of a line, via the interpreter's lexer) · text (positions)
//!             dialect (which dialect a document is read in) · uri · settings
//! ```
//!
//! The server is a library so that it is tested in memory
//! ([`server::serve`] over `lsp_server::Connection::memory`) and over
//! stdio through the CLI ([`serve_stdio`], `vcnc lsp`).

pub mod analysis;
pub mod definition;
pub mod dialect;
pub mod hover;
pub mod inlay;
pub mod scan;
pub mod server;
pub mod settings;
pub mod symbols;
pub mod text;
pub mod tokens;
pub mod uri;

/// Serves one client on standard input and output until it exits.
pub fn serve_stdio() -> Result<(), String> {
    let (conn, io) = lsp_server::Connection::stdio();
    server::serve(&conn)?;
    drop(conn);
    io.join().map_err(|e| format!("vcnc lsp: {e}"))
}
