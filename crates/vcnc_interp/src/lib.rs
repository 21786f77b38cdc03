//! `vcnc_interp` executes part programs the way a CNC controller does and
//! reports what the machine does as canonical [`Event`]s.
//!
//! It owns one [`State`] per run, reads blocks from `vcnc_syntax`, maps codes
//! to operations through a [`Dialect`] table and sends events to a [`Sink`].
//! It knows nothing of planning, rendering, terminals or files: program text
//! arrives through [`vcnc_syntax::TextSource`] and called programs through a
//! [`ProgramStore`]. See `ARCHITECTURE.md` for the whole pipeline.
//!
//! ```
//! use vcnc_interp::{Dialect, Interpreter, Machine, Options, VecSink, Outcome};
//! let machine = Machine::default_mill();
//! let dialect = Dialect::syntec();
//! let mut sink = VecSink::default();
//! let out = Interpreter::new(&machine, &dialect, Options::default())
//!     .run_str("S1000 M03\nG01 X10. F300;\nM30\n", &mut sink);
//! assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
//! // spindle, feed, end
//! assert_eq!(sink.0.len(), 3);
//! ```

pub mod alarms;
mod block;
mod codes;
mod config;
pub mod detect;
pub mod dialect;
pub mod explain;
mod flow;
mod interpreter;
mod macros;
mod motion;
mod plane;
pub mod state;
mod words;

pub use dialect::Dialect;
pub use flow::{NoPrograms, ProgramStore};
pub use interpreter::{HAND_OVER, Interpreter, MAX_ALARMS, Options, Outcome};
pub use state::{State, Tables};
pub use vcnc_core::{
    ArcDir, Cycle, EndCode, Event, Feed, FrameInfo, Loc, MAX_AXES, Machine, NullSink, PathMode,
    Plane, Pos, Sink, SpindleDir, StopCode, UnsetVariable, VecSink, WaitReason, events, machine,
};
