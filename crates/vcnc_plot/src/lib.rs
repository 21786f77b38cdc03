//! `vcnc_plot` draws what a program does: back-plots as SVG, PNG, or a
//! self-contained HTML page with a 3D viewer.
//!
//! It consumes canonical events through [`PlotSink`] (a
//! [`vcnc_core::Sink`]) and knows nothing of the interpreter: the sink
//! collects a bounded, merged [`Plot`] (`path.rs` states the merging rule),
//! and the writers turn a plot into bytes. Flat pictures go through one
//! [`scene`] (layout, colours, marks and legend) that both the SVG writer
//! and the PNG rasterizer draw, so the two always agree; the HTML page gets
//! the path as deflated columns of varints (`encode.rs`) and draws it with
//! hand-written WebGL.
//!
//! ```text
//!   events ─▶ PlotSink ─▶ Plot ─┬─▶ scene ─┬─▶ svg  (hand-written, byte-stable)
//!             (merge, marks,    │          └─▶ png  (tiny-skia)
//!              Clock for time)  └─▶ html (base64 typed arrays + WebGL page)
//! ```
//!
//! Arc geometry is `vcnc_core::geometry`'s, shared with the interpreter and
//! the summary, so a plot's arcs are the arcs the travel check saw.

mod axes;
mod clip;
mod collect;
mod encode;
mod html;
mod legend;
pub mod path;
mod png;
mod retime;
pub mod scene;
mod svg;
pub mod theme;
pub mod view;

pub use collect::{
    AlarmMark, Clock, ColorBy, FitTo, FrameMark, HoleMark, NoClock, OriginMark, Plot, PlotOptions,
    PlotSink, Space, ToolMark,
};
pub use html::{Mesh, Page, Source, meshes_data, page_data, write_html, write_viewer};
pub use png::{render as render_png, write_png};
pub use scene::{Legend, Look, Scene, plot_area, scene};
pub use svg::write_svg;
pub use theme::{Rgb, Theme};
pub use view::{AxisMap, P3, Projection, View};
