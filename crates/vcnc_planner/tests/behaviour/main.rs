//! The planner's tests (closed-form times, invariants, robustness), one binary.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod analytic;
mod invariants;
mod robustness;
