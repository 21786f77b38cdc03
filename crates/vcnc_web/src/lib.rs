//! vcnc in the browser (`docs/web.md`): the engine of the offline page
//! `tools/build-web.sh` writes, over the same crates as the CLI. Each call
//! takes a program text and [`Settings`] (dialect or auto, a machine file's
//! text, a tool table's text) and returns plain data that serde hands to
//! JavaScript as objects (`bindings.rs`, compiled for wasm32 only); natively
//! the same functions are the tests' and the benchmark's API.
//!
//! ```text
//!   text + Settings ─▶ setup (detect or the named dialect, machine TOML
//!                      or grbl $$, the tool table into the registers)
//!     ─▶ check:   keep-going run ─┬─▶ PlotSink (clock: Summary + Blocks) ─▶ viewer data
//!                                 └─▶ Numbered ─▶ Planner ─▶ Stamps (planned time, retime)
//!                 ─▶ Checked: diagnostics at UTF-16 columns, summary, view
//!     ─▶ time:    Planner ─▶ CycleTime      (as `vcnc time`)
//!     ─▶ flatten: GcodeSink with markers    (as `vcnc run --format gcode`)
//!     ─▶ events:  write_event per event     (as `vcnc run --format jsonl`)
//!     ─▶ sim:     Survey? ─▶ Simulation     (as `vcnc sim`'s report; meshes)
//!   viewer():     the viewer page, loaded once; each `view` is posted to it
//! ```
//!
//! The page runs these in a Web Worker; a run ends by the interpreter's
//! own limits (block budget, line length, call depth), so a runaway
//! program ends with the CLI's located alarm.

mod check;
mod setup;
mod sim;

#[cfg(target_arch = "wasm32")]
mod bindings;

pub use check::{
    Checked, Diag, Events, Extents, Flattened, Summary, TimeSplit, ToolRow, check, events, flatten,
    time,
};
pub use setup::{DialectChoice, Settings, Setup, detect, dialects};
pub use sim::{SimCollision, Simulated, sim};

/// The viewer page the app loads once (`vcnc_plot::write_viewer`): it
/// draws each plot [`check`] returns in `view`, keeping its camera.
pub fn viewer() -> String {
    let mut out = Vec::with_capacity(1 << 17);
    match vcnc_plot::write_viewer(&mut out) {
        Ok(()) => String::from_utf8_lossy(&out).into_owned(),
        Err(e) => format!("<p>the viewer could not be written: {e}</p>"),
    }
}
