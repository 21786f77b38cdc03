//! `vcnc_sim`: what the cut leaves. It consumes the canonical event stream
//! (`vcnc_core` alone, like the planner and the plotter) and removes the
//! tools' swept volumes from a stock: a height field (Z-map) on mills, a
//! revolved half-section on lathes. It reports the volume removed, the
//! time spent cutting air and the crashes a programmer fears — a rapid
//! into the stock, the holder or shank in it, a cut through its bottom,
//! the tool on the table, a non-centre-cutting plunge — each located at
//! its block, and it writes the finished part (binary STL, a shaded PNG,
//! a replay page).
//!
//! ```text
//!   events ─▶ Survey (auto stock, move count)
//!   events ─▶ Simulation ─▶ Tracker ─▶ Motion ─┬▶ Mill ─▶ ZMap (exact swept envelopes)
//!                                              └▶ Section (polygon difference)
//!          finish_run ─▶ Finished { Report, Part, Replay }
//!                        ─▶ mesh (STL) · render (PNG) · page (HTML)
//! ```
//!
//! The model, its limits and its figures are in `docs/sim.md`.

pub mod kernel;
pub mod lathe;
pub mod mesh;
mod mill;
pub mod motion;
pub mod page;
pub mod render;
pub mod replay;
pub mod report;
mod sim;
pub mod stock;
mod survey;
pub mod tool;
pub mod zmap;

pub use mill::RAPID_DEPTH_MM;
pub use report::{Collision, CollisionKind, Report};
pub use sim::{
    DEFAULT_RESOLUTION_MM, Finished, Part, SimOptions, Simulation, Tools, check_setup,
    resolution_for,
};
pub use stock::{StockOrigin, StockSpec, from_header};
pub use survey::Survey;
