//! The core crate's tests (geometry, NURBS, tooling, grbl settings), one binary.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod grbl_settings;
mod nurbs;
mod robustness;
mod tooling;
