//! Canonical events: the interpreter's only output, and the public contract
//! behind `vcnc run --format jsonl` (documented in `docs/events.md`).
//!
//! Events carry machine coordinates in mm ([`Pos`], indexed by the machine's
//! axis order), feeds in mm/min or mm/rev, and the source location of the
//! block that caused them. Sinks (`vcnc_output`, the planner, the plotter)
//! consume them by reference through [`crate::Sink`]. The enum is
//! `#[non_exhaustive]`: the contract is additive only, so a consumer must
//! ignore event types it does not know.

use crate::diagnostic::Diagnostic;
use std::sync::Arc;

/// Most axes a machine may have.
pub const MAX_AXES: usize = 6;

/// A position or vector in machine coordinates, mm (degrees for rotary
/// axes), indexed like the machine's `axes`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pos(pub [f64; MAX_AXES]);

impl Pos {
    /// `self + other`, axis by axis.
    pub fn plus(self, other: Pos) -> Pos {
        let mut out = self;
        for (o, b) in out.0.iter_mut().zip(other.0) {
            *o += b;
        }
        out
    }
    /// `self - other`, axis by axis.
    pub fn minus(self, other: Pos) -> Pos {
        let mut out = self;
        for (o, b) in out.0.iter_mut().zip(other.0) {
            *o -= b;
        }
        out
    }
    /// The coordinate of axis `i` (0 when out of range).
    pub fn get(&self, i: usize) -> f64 {
        self.0.get(i).copied().unwrap_or(0.0)
    }
    /// Sets the coordinate of axis `i` (ignored when out of range).
    pub fn set(&mut self, i: usize, v: f64) {
        if let Some(slot) = self.0.get_mut(i) {
            *slot = v;
        }
    }
}

/// Where an event comes from.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Loc {
    /// 1-based source line.
    pub line: u64,
    /// The file, when not the main program.
    pub file: Option<Arc<str>>,
}

/// Feed of a cutting move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// mm/min (G94).
    PerMin(f64),
    /// mm per spindle revolution (G95).
    PerRev(f64),
}

/// The plane of an arc, named by its two axes in rotation order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    /// G17.
    Xy,
    /// G18.
    Zx,
    /// G19.
    Yz,
}

impl Plane {
    /// `"xy"`, `"zx"` or `"yz"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Plane::Xy => "xy",
            Plane::Zx => "zx",
            Plane::Yz => "yz",
        }
    }
    /// The first, second and normal axis letters.
    pub fn letters(self) -> [u8; 3] {
        match self {
            Plane::Xy => [b'X', b'Y', b'Z'],
            Plane::Zx => [b'Z', b'X', b'Y'],
            Plane::Yz => [b'Y', b'Z', b'X'],
        }
    }
}

/// Rotation sense of an arc, looking from the positive normal axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcDir {
    /// G02.
    Cw,
    /// G03.
    Ccw,
}

/// Spindle state in a `spindle` event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpindleDir {
    /// M03.
    Cw,
    /// M04.
    Ccw,
    /// M05.
    Stop,
    /// M19: stopped at an orientation.
    Orient,
}

/// Path control mode (group 15), for the planner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathMode {
    /// G61.
    ExactStop,
    /// G62 (Syntec: curved-surface cutting).
    Surface,
    /// G63.
    Tapping,
    /// G64, the power-on mode.
    Cutting,
}

/// What ended a program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndCode {
    /// M02.
    M02,
    /// M30.
    M30,
    /// The main program ran out of blocks (end of file, `%`, next `O`).
    Eof,
    /// M99 in the main program: a controller would run it again for ever;
    /// vcnc runs one pass (warning W107).
    M99,
}

impl EndCode {
    /// `"M02"`, `"M30"`, `"EOF"` or `"M99"`.
    pub fn as_str(self) -> &'static str {
        match self {
            EndCode::M02 => "M02",
            EndCode::M30 => "M30",
            EndCode::Eof => "EOF",
            EndCode::M99 => "M99",
        }
    }
}

/// What stopped a program for the operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopCode {
    /// M00.
    M00,
    /// M01 with the optional-stop switch on.
    M01,
}

impl StopCode {
    /// `"M00"` or `"M01"`.
    pub fn as_str(self) -> &'static str {
        match self {
            StopCode::M00 => "M00",
            StopCode::M01 => "M01",
        }
    }
}

/// A canned drilling cycle (the `cycle` of a `hole` event).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)] // named after their codes
pub enum Cycle {
    G73,
    G74,
    G76,
    G81,
    G82,
    G83,
    G84,
    G85,
    G86,
    G87,
    G88,
    G89,
}

impl Cycle {
    /// `"G81"` …
    pub fn as_str(self) -> &'static str {
        match self {
            Cycle::G73 => "G73",
            Cycle::G74 => "G74",
            Cycle::G76 => "G76",
            Cycle::G81 => "G81",
            Cycle::G82 => "G82",
            Cycle::G83 => "G83",
            Cycle::G84 => "G84",
            Cycle::G85 => "G85",
            Cycle::G86 => "G86",
            Cycle::G87 => "G87",
            Cycle::G88 => "G88",
            Cycle::G89 => "G89",
        }
    }
}

/// Why the program waits for the operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WaitReason {
    /// The operator moves the tool by hand, then presses cycle start (G88).
    ManualMotion,
    /// The operator presses cycle start (an untimed dwell).
    CycleStart,
}

impl WaitReason {
    /// `"manual_motion"` or `"cycle_start"`.
    pub fn as_str(self) -> &'static str {
        match self {
            WaitReason::ManualMotion => "manual_motion",
            WaitReason::CycleStart => "cycle_start",
        }
    }
}

/// The program coordinate frame: `machine = linear · program + origin +
/// tool_offset`, with `linear` acting on the X, Y and Z axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameInfo {
    /// Machine coordinates of the program zero (work offset, G52, G92 and
    /// the transforms' own translation).
    pub origin: Pos,
    /// Rotation, scaling and mirror on X, Y, Z (rows and columns x, y, z);
    /// `None` when the identity.
    pub linear: Option<[[f64; 3]; 3]>,
    /// Tool length offset (G43/G44), machine axes.
    pub tool_offset: Pos,
}

/// A variable a macro program read before anything set it.
#[derive(Debug, Clone, PartialEq)]
pub struct UnsetVariable {
    /// `#101`, `@5`.
    pub name: Arc<str>,
    /// The line of its first read.
    pub line: u64,
    /// The file of that line, when not the main program.
    pub file: Option<Arc<str>>,
}

/// One canonical event.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Event {
    /// Positioning at rapid rate.
    Rapid {
        /// Source.
        loc: Loc,
        /// End point.
        to: Pos,
        /// G09 in the block.
        exact_stop: bool,
    },
    /// Straight cutting move.
    Feed {
        /// Source.
        loc: Loc,
        /// End point.
        to: Pos,
        /// Feed.
        feed: Feed,
        /// G09 in the block.
        exact_stop: bool,
    },
    /// Circular or helical move.
    Arc {
        /// Source.
        loc: Loc,
        /// End point.
        to: Pos,
        /// Centre; its normal-axis coordinate is the start's.
        center: Pos,
        /// Plane.
        plane: Plane,
        /// Direction.
        dir: ArcDir,
        /// Feed.
        feed: Feed,
        /// G09 in the block.
        exact_stop: bool,
    },
    /// Thread cutting (G33), feed locked to the spindle.
    Thread {
        /// Source.
        loc: Loc,
        /// End point.
        to: Pos,
        /// Lead, mm per revolution.
        lead_mm: f64,
    },
    /// Skip move (G31).
    Skip {
        /// Source.
        loc: Loc,
        /// Where the motion ended.
        to: Pos,
        /// Feed.
        feed: Feed,
        /// Whether the skip signal fired.
        triggered: bool,
    },
    /// Dwell (G04).
    Dwell {
        /// Source.
        loc: Loc,
        /// Duration.
        seconds: f64,
    },
    /// Tool change (M06).
    ToolChange {
        /// Source.
        loc: Loc,
        /// New tool.
        tool: u32,
    },
    /// Spindle start, stop or speed change.
    Spindle {
        /// Source.
        loc: Loc,
        /// Direction.
        dir: SpindleDir,
        /// Speed, rev/min (0 when stopped).
        rpm: f64,
        /// Surface speed under G96.
        surface_m_per_min: Option<f64>,
    },
    /// Coolant on/off.
    Coolant {
        /// Source.
        loc: Loc,
        /// On.
        on: bool,
    },
    /// Path control mode change.
    PathMode {
        /// Source.
        loc: Loc,
        /// New mode.
        mode: PathMode,
    },
    /// High-speed high-precision mode (Syntec G05 P…), for the planner.
    HighSpeed {
        /// Source.
        loc: Loc,
        /// On (P1–P5, P10000) or off (P0).
        on: bool,
        /// The P parameter set.
        p: u32,
    },
    /// Program stop (M00, M01).
    Stop {
        /// Source.
        loc: Loc,
        /// Which stop.
        code: StopCode,
    },
    /// Program end.
    End {
        /// Source.
        loc: Loc,
        /// What ended it.
        code: EndCode,
    },
    /// A hole of a canned cycle, sent before the hole's motions.
    Hole {
        /// Source.
        loc: Loc,
        /// The cycle that drills it.
        cycle: Cycle,
        /// The hole centre at its Z point (the bottom; G87: the top of the
        /// back bore), machine coordinates.
        at: Pos,
    },
    /// The program waits for the operator.
    Wait {
        /// Source.
        loc: Loc,
        /// What for.
        reason: WaitReason,
    },
    /// A marker for the planner: the junction after this block's motion may
    /// be passed without stopping (EIA G99 deceleration override).
    Junction {
        /// Source.
        loc: Loc,
        /// Whether the junction blends.
        blend: bool,
    },
    /// The programmed path of a block that cutter compensation offsets,
    /// sent before the block's (compensated) motion events: from `from` to
    /// `to`, straight or, with `arc`, about the arc's centre.
    Contour {
        /// Source.
        loc: Loc,
        /// The programmed start point, machine coordinates.
        from: Pos,
        /// The programmed end point, machine coordinates.
        to: Pos,
        /// Centre, plane and direction when the block is an arc.
        arc: Option<(Pos, Plane, ArcDir)>,
    },
    /// The program coordinate frame changed (work offset, G52, G92, tool
    /// length offset, rotation, scaling, mirror), so that a viewer can show
    /// program coordinates. Emitted before the first motion that uses it.
    Frame {
        /// Source.
        loc: Loc,
        /// The new frame.
        frame: FrameInfo,
    },
    /// A machine-builder M code the machine file lists (chip conveyor,
    /// door, brakes …): the interpreter passes it on, the machine acts.
    Aux {
        /// Source.
        loc: Loc,
        /// The M number.
        code: u32,
        /// What the machine file says it does.
        description: Arc<str>,
    },
    /// A warning: the run goes on (`vcnc --deny-warnings` fails it).
    Warning(Diagnostic),
    /// Path smoothing takes effect (`on`, with its largest path error) or
    /// stops, before the first move it concerns: G05.1 (Syntec 1.2.7) or
    /// Haas G187.
    Smoothing {
        /// Source.
        loc: Loc,
        /// Whether the following G01 moves are smoothed.
        on: bool,
        /// The largest allowed path error E, mm (0 when off).
        tolerance_mm: f64,
    },
    /// A NURBS curve (G06.2, Syntec 1.2.8): from the current position
    /// along the curve its control points and knots define, ending at the
    /// last control point.
    Nurbs {
        /// Source (the block that completed the definition).
        loc: Loc,
        /// The curve.
        curve: Arc<Nurbs>,
        /// Feed (the curve's F).
        feed: Feed,
    },
    /// A message for the operator from a macro program: Fanuc `#3006`
    /// (`stop`: the program waits for cycle start), Syntec `MSG()` (no
    /// stop).
    Message {
        /// Source.
        loc: Loc,
        /// The text.
        text: Arc<str>,
        /// Whether the program stops until the operator restarts it.
        stop: bool,
    },
    /// The variables the program read while they had never been set, sent
    /// once before the `end` (or the alarm) when there are any.
    UnsetVariables {
        /// Where the run ended.
        loc: Loc,
        /// Each variable and where it was first read.
        variables: Arc<[UnsetVariable]>,
    },
    /// The program selected another work coordinate system (not sent for
    /// the power-on G54), so that a consumer that writes program
    /// coordinates (the flattened program) can write them in it. The
    /// `frame` event carries the offsets.
    WorkSystem {
        /// Source.
        loc: Loc,
        /// Index into the machine's work offsets (0 = G54 … 5 = G59, 6 =
        /// G59.1 … 14 = G59.9); `None`: no work system (a lathe's G53/G500).
        system: Option<u8>,
    },
    /// The program's length units changed (G20/G21, Syntec G70/G71; not
    /// sent for the power-on mm). Events stay in mm.
    Units {
        /// Source.
        loc: Loc,
        /// Inches from here on.
        inch: bool,
    },
    /// The next motion events of this block, up to the one that ends at
    /// `to`, go to a point given in machine coordinates (G53, the
    /// reference leg of G28/G30, a lathe's return to the reference point),
    /// which no work offset moves.
    MachineMove {
        /// Source.
        loc: Loc,
        /// The machine point the move ends at.
        to: Pos,
        /// The axes the block commands (bit i: machine axis i); the others
        /// stay where they are.
        axes: u8,
    },
    /// The next move of this block places these axes (bit i: machine axis
    /// i) in program coordinates for the first time since power-on or since
    /// a `machine_move` moved them: until then a consumer that writes
    /// program coordinates does not know them (the flattened program leaves
    /// them out).
    Placed {
        /// Source.
        loc: Loc,
        /// The axes the block names among those.
        axes: u8,
    },
    /// An alarm; always the last event.
    Alarm(Diagnostic),
}

/// The G code of work system `index` (0 = G54 … 14 = G59.9).
pub fn work_system_name(index: u8) -> String {
    match index {
        0..=5 => format!("G{}", 54 + u16::from(index)),
        _ => format!("G59.{}", index.saturating_sub(5)),
    }
}

/// A NURBS curve in machine coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    /// Order (degree + 1), 2 to 4.
    pub order: u8,
    /// Knot vector, non-decreasing, `points.len() + order` long.
    pub knots: Vec<f64>,
    /// Control points, machine coordinates.
    pub points: Vec<Pos>,
    /// Weights, one per control point, positive.
    pub weights: Vec<f64>,
}

/// `Some(body)` with `loc` bound to the event's source location, `None`
/// for the events that carry their own (warnings, alarms): one list of the
/// variants for [`Event::loc`] and [`Event::loc_mut`].
macro_rules! with_loc {
    ($event:expr, $loc:ident => $body:expr) => {
        match $event {
            Event::Rapid { $loc, .. }
            | Event::Feed { $loc, .. }
            | Event::Arc { $loc, .. }
            | Event::Thread { $loc, .. }
            | Event::Skip { $loc, .. }
            | Event::Dwell { $loc, .. }
            | Event::ToolChange { $loc, .. }
            | Event::Spindle { $loc, .. }
            | Event::Coolant { $loc, .. }
            | Event::PathMode { $loc, .. }
            | Event::HighSpeed { $loc, .. }
            | Event::Stop { $loc, .. }
            | Event::End { $loc, .. }
            | Event::Frame { $loc, .. }
            | Event::Contour { $loc, .. }
            | Event::Hole { $loc, .. }
            | Event::Wait { $loc, .. }
            | Event::Junction { $loc, .. }
            | Event::Aux { $loc, .. }
            | Event::Smoothing { $loc, .. }
            | Event::Nurbs { $loc, .. }
            | Event::Message { $loc, .. }
            | Event::UnsetVariables { $loc, .. }
            | Event::WorkSystem { $loc, .. }
            | Event::Units { $loc, .. }
            | Event::MachineMove { $loc, .. }
            | Event::Placed { $loc, .. } => Some($body),
            Event::Warning(_) | Event::Alarm(_) => None,
        }
    };
}

impl Event {
    /// The `type` of the event in the JSON-lines contract.
    pub fn kind(&self) -> &'static str {
        match self {
            Event::Rapid { .. } => "rapid",
            Event::Feed { .. } => "feed",
            Event::Arc { .. } => "arc",
            Event::Thread { .. } => "thread",
            Event::Skip { .. } => "skip",
            Event::Dwell { .. } => "dwell",
            Event::ToolChange { .. } => "tool_change",
            Event::Spindle { .. } => "spindle",
            Event::Coolant { .. } => "coolant",
            Event::PathMode { .. } => "path_mode",
            Event::HighSpeed { .. } => "high_speed",
            Event::Stop { .. } => "stop",
            Event::End { .. } => "end",
            Event::Frame { .. } => "frame",
            Event::Contour { .. } => "contour",
            Event::Hole { .. } => "hole",
            Event::Wait { .. } => "wait",
            Event::Junction { .. } => "junction",
            Event::Aux { .. } => "aux",
            Event::Warning(_) => "warning",
            Event::Smoothing { .. } => "smoothing",
            Event::Nurbs { .. } => "nurbs",
            Event::Message { .. } => "message",
            Event::UnsetVariables { .. } => "unset_variables",
            Event::WorkSystem { .. } => "work_system",
            Event::Units { .. } => "units",
            Event::MachineMove { .. } => "machine_move",
            Event::Placed { .. } => "placed",
            Event::Alarm(_) => "alarm",
        }
    }

    /// Where the event comes from (an alarm carries its own line and file).
    pub fn loc(&self) -> Option<&Loc> {
        with_loc!(self, loc => loc)
    }

    /// Where the event comes from, to change: a consumer that numbers the
    /// blocks itself (the plot's planned-time stamps) rewrites the line.
    pub fn loc_mut(&mut self) -> Option<&mut Loc> {
        with_loc!(self, loc => loc)
    }

    /// The end point of a motion event.
    pub fn motion_end(&self) -> Option<Pos> {
        match self {
            Event::Rapid { to, .. }
            | Event::Feed { to, .. }
            | Event::Arc { to, .. }
            | Event::Thread { to, .. }
            | Event::Skip { to, .. } => Some(*to),
            Event::Nurbs { curve, .. } => curve.points.last().copied(),
            _ => None,
        }
    }
}
