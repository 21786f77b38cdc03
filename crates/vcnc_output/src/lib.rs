//! `vcnc_output` turns canonical events into text and numbers: the JSON-lines
//! contract ([`JsonlSink`]), CSV ([`CsvSink`]), a flattened plain G-code
//! program ([`GcodeSink`]) and the summary of `vcnc check` ([`Summary`]).
//!
//! Writers take any `std::io::Write` and buffer nothing beyond what they are
//! given; the first write error is kept and reported by `finish`, since a
//! [`vcnc_core::Sink`] cannot fail mid-run; a writer whose reader went away says it is done, so the run stops early. Numbers are rounded to 1e-6 mm
//! (a nanometre) so that floating-point noise never reaches the output.

mod csv;
mod gcode;
mod jsonl;
mod num;
mod summary;

pub use csv::CsvSink;
pub use gcode::{Coords, GcodeOptions, GcodeSink, Units};
pub use jsonl::{EventAxes, JsonlSink, write_event};
pub use summary::{KEPT_WARNINGS, Summary};
