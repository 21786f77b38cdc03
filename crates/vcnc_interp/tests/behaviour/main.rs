//! The interpreter's behaviour tests, one binary (one link), one module per
//! behaviour; `common` is the harness they share.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod alarms;
mod atomicity;
mod circle_pockets;
mod common;
mod compensation;
mod compensation_frames;
mod cycles;
mod detect;
mod fanuc_lathe;
mod fanuc_lathe_rules;
mod hand_over;
mod keep_going;
mod lathe_profile_words;
mod lathe_robustness;
mod linuxcnc_dialect;
mod macro_programs;
mod macros_eval;
mod macros_flow;
mod macros_followups;
mod macros_limits;
mod macros_parts;
mod macros_property;
mod macros_robustness;
mod offsets_and_profile_words;
mod polar;
mod real_programs;
mod robustness;
mod stop_after_line;
mod subprograms_and_limits;
mod transforms;
mod warnings;
