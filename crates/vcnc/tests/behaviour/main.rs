//! The command line's behaviour tests, one binary (one link of the `vcnc`
//! crate), one module per behaviour; `common` is the harness they share.
//!
//! The tests that drive outside tools — headless Chromium (`browser.rs`,
//! `web.rs`) and Python (`python.rs`) — stay separate binaries: cargo runs
//! test binaries one after another, so a browser never competes with these
//! modules' threads for the machine's cores, and a missing tool fails only
//! its own binary.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod cli;
mod cli_macros;
mod common;
mod conformance;
mod fixtures;
mod flatten;
mod lsp;
mod plot;
mod sim;
mod snapshots;
mod time_cli;
