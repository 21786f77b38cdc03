//! The plot crate's tests (any event stream draws, PNG pixels), one binary.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod any_events;
mod png_pixels;
