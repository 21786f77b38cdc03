//! What the planner hands on, in time order: planned moves with their
//! speed profiles, rapids whose axes run independently (parameter 411 = 1),
//! pauses (dwell, tool change, spindle, settling into the in-position
//! window) and moves it cannot time. A [`Timeline`] consumes them: the cycle
//! time ([`crate::CycleTime`]) sums them up, the trace sampler
//! ([`crate::Sampler`]) evaluates them at a fixed period.

use crate::path::Path;
use crate::ramp::{Kin, Profile};
use std::sync::Arc;
use vcnc_core::{MAX_AXES, Pos};

/// Rapid or cutting motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveKind {
    /// G00 and the reference-point legs.
    Rapid,
    /// G01, G02/G03, G33, G31, NURBS.
    Cut,
}

/// Who a piece of time belongs to.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Attr {
    /// Source line.
    pub line: u64,
    /// Subprogram file (`None`: the main program).
    pub file: Option<Arc<str>>,
    /// The tool in the spindle (`None`: none changed to yet).
    pub tool: Option<u32>,
}

/// A planned move and the limits it was planned with.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Its path.
    pub path: Path,
    /// Rapid or cut.
    pub kind: MoveKind,
    /// Source and tool.
    pub attr: Attr,
    /// Highest path speed (feed clamped by every axis' limit), mm/s.
    pub v_max: f64,
    /// Tangential acceleration and jerk along the path.
    pub kin: Kin,
    /// The corner tolerance of the corner at its start: the machine's, a
    /// G05 set's, or G05.1's E between two smoothed G01 moves, mm.
    pub corner_tolerance_mm: f64,
}

/// A rapid whose axes each run at their own rate (parameter 411 = 1): one
/// profile per axis, all starting together, each stopping when it arrives.
#[derive(Debug, Clone, PartialEq)]
pub struct AxesMove {
    /// Start point.
    pub from: Pos,
    /// End point.
    pub to: Pos,
    /// The profile of each moving axis (distance along that axis).
    pub profiles: [Option<Profile>; MAX_AXES],
    /// Duration: the slowest axis.
    pub duration_s: f64,
    /// Source and tool.
    pub attr: Attr,
}

/// Why the motion pauses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PauseKind {
    /// G04.
    Dwell,
    /// M06.
    ToolChange,
    /// Spindle start, reversal, stop or orientation.
    Spindle,
    /// Settling into the in-position window after an exact stop.
    InPosition,
    /// The `filter` profile's moving average running out after a stop:
    /// the machine still moves (the time counts as the stopped move's,
    /// cutting or rapid), at the stop's position in the commanded plan.
    Filter,
}

/// A pause at a fixed position.
#[derive(Debug, Clone, PartialEq)]
pub struct Pause {
    /// Why.
    pub kind: PauseKind,
    /// How long, s.
    pub seconds: f64,
    /// Source and tool.
    pub attr: Attr,
}

/// Consumes the planned timeline, in time order.
pub trait Timeline {
    /// A planned move: it takes `profile.duration()` seconds.
    fn segment(&mut self, seg: &Segment, profile: &Profile);
    /// A rapid with independent axes.
    fn axes(&mut self, mv: &AxesMove);
    /// A pause.
    fn pause(&mut self, pause: &Pause);
    /// A move the planner cannot time (feed per revolution with the spindle
    /// stopped, a zero feed): the machine would not move; it is skipped.
    fn untimed(&mut self, _from: Pos, _to: Pos, _attr: &Attr) {}
}

impl<A: Timeline, B: Timeline> Timeline for (A, B) {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        self.0.segment(seg, profile);
        self.1.segment(seg, profile);
    }
    fn axes(&mut self, mv: &AxesMove) {
        self.0.axes(mv);
        self.1.axes(mv);
    }
    fn pause(&mut self, pause: &Pause) {
        self.0.pause(pause);
        self.1.pause(pause);
    }
    fn untimed(&mut self, from: Pos, to: Pos, attr: &Attr) {
        self.0.untimed(from, to, attr);
        self.1.untimed(from, to, attr);
    }
}

impl<T: Timeline + ?Sized> Timeline for &mut T {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        (**self).segment(seg, profile);
    }
    fn axes(&mut self, mv: &AxesMove) {
        (**self).axes(mv);
    }
    fn pause(&mut self, pause: &Pause) {
        (**self).pause(pause);
    }
    fn untimed(&mut self, from: Pos, to: Pos, attr: &Attr) {
        (**self).untimed(from, to, attr);
    }
}
