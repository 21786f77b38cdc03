//! `vcnc_core` is the contract every part of vcnc shares: the canonical
//! [`Event`]s the interpreter emits and the [`Sink`] they go to, the
//! [`Diagnostic`]s with their stable [`Code`]s, byte [`Span`]s, the
//! [`Machine`] model, and the path [`geometry`] of arcs.
//!
//! It is the leaf of the workspace: `vcnc_syntax` builds diagnostics with
//! it, `vcnc_interp` emits its events, and the consumers — `vcnc_output`'s
//! formats and summary, the planner, the plotter — read events and the
//! machine model without knowing anything of the interpreter.

mod decimal;
pub mod diagnostic;
pub mod display;
pub mod events;
pub mod geometry;
pub mod grbl_settings;
pub mod machine;
pub mod motion;
pub mod nurbs;
mod sink;
mod span;
pub mod tooling;

pub use diagnostic::{Code, Diagnostic};
pub use events::{
    ArcDir, Cycle, EndCode, Event, Feed, FrameInfo, Loc, MAX_AXES, Nurbs, PathMode, Plane, Pos,
    SpindleDir, StopCode, UnsetVariable, WaitReason,
};
pub use machine::Machine;
pub use sink::{NullSink, Sink, VecSink};
pub use span::{Span, clamp_u32, column_of};
pub use tooling::{ToolKind, ToolLibrary, ToolShape, ToolSource, ToolTableError};
