//! vcnc_sim's tests, one binary: removed volumes against closed forms
//! (`removal`), the Z-map against a dense-sampling reference on random
//! programs (`reference`), each collision kind at its line (`collisions`)
//! and the finished part's mesh (`part`). Programs run through the real
//! interpreter (`harness`); expected values are worked out by hand in
//! each test.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report
#![allow(clippy::cast_possible_truncation)] // small, bounded grid indices

mod collisions;
mod harness;
mod part;
mod reference;
mod removal;
