//! What a code does, as small role enums: the vocabulary the dialect tables
//! map G and M numbers to, and the one place that says in words what each
//! operation means.
//!
//! ```text
//!   table row  G87 ─▶ GOp::Cycle(CycleOp::Drill(Cycle::G87, Hole::BackBore))   (fanuc)
//!              G87 ─▶ GOp::Cycle(CycleOp::Drill(Cycle::G87, Hole::ChipBreak))  (eia)
//!                        │
//!   dispatch   match GOp { Motion(m) ⇒ …, Mode(m) ⇒ …, Cycle(c) ⇒ … }
//!              each role matched exhaustively, never with `_ =>`
//! ```
//!
//! The roles follow what the interpreter does with a code, so that each is
//! dispatched in one place by a `match` the compiler checks: a new variant
//! does not build until every dispatcher says what it does with it, and a
//! test fails until some table lists it and [`GOp::meaning`] describes it.
//! The same meanings feed `vcnc explain`, E201's help, the dialect matrix
//! in docs/dialects.md and the editor's hover: there is no second list.

use vcnc_core::events::{ArcDir, Cycle};

/// What a G code does: its role, then the operation within the role.
#[cfg_attr(
    test,
    derive(strum::EnumDiscriminants),
    strum_discriminants(derive(strum::EnumIter))
)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GOp {
    /// Group 01: the modal motion.
    Motion(MotionOp),
    /// A modal setting that moves nothing (plane, units, distances …).
    Mode(ModeOp),
    /// Tool length compensation and the programmable transforms.
    Frame(FrameOp),
    /// Cutter radius compensation (group 07).
    Comp(CompOp),
    /// A one-shot code that moves by the block's axis words (G28, G53 …).
    Move(MoveOp),
    /// A one-shot code that sets data from the block's words (G10, G52, G92 …).
    Set(SetOp),
    /// Dwells, exact stops and the settings of path control and feed.
    Pace(PaceOp),
    /// Canned drilling cycles, hole patterns and pockets.
    Cycle(CycleOp),
    /// The lathes' turning and threading cycles.
    Turn(TurnOp),
    /// Subprograms, jumps, loops and macro calls.
    Flow(FlowOp),
}

/// Group 01: how the axis words of later blocks move the tool.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MotionOp {
    Rapid,
    Linear,
    ArcCw,
    ArcCcw,
    /// Spindle-synchronised motion, the lead in program units.
    Thread,
    /// The seed lathe's G32: a thread whose lead is in inches.
    ThreadInch,
    /// The seed lathe's G05: an arc through a middle point.
    ThreePointArc,
    /// Syntec G06.2: NURBS interpolation.
    Nurbs,
    /// Fanuc lathe G90: the turning cycle, modal.
    TurnCycle,
    /// Fanuc lathe G92: the threading cycle, modal.
    ThreadingCycle,
    /// Fanuc lathe G94: the facing cycle, modal.
    FaceCycle,
    /// LinuxCNC's G33.1: rigid tapping, in to the axis words with the
    /// spindle, reversed out to where it started (K the pitch).
    RigidTap,
}

/// A modal setting.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(
    test,
    derive(strum::EnumDiscriminants),
    strum_discriminants(derive(strum::EnumIter))
)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeOp {
    PlaneXy,
    PlaneZx,
    PlaneYz,
    Absolute,
    Incremental,
    PerMinute,
    PerRev,
    InverseTime,
    Inch,
    Metric,
    SurfaceSpeed,
    SpindleRpm,
    /// Work coordinate system n (0 = G54).
    WorkSystem(u8),
    /// The seed lathe's G53/G500: no work offset, no shift.
    CancelOffsets,
    PathExact,
    PathSurface,
    PathTapping,
    PathCutting,
    ReturnInitial,
    ReturnR,
    ArcCentersAbsolute,
    ArcCentersIncremental,
    RadiusMode,
    DiameterMode,
}

/// Tool length compensation and the programmable transforms.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameOp {
    ToolLengthPlus,
    ToolLengthMinus,
    ToolLengthCancel,
    /// LinuxCNC G43.1: a tool length given in the block.
    ToolLengthDynamic,
    PolarOn,
    PolarOff,
    ScaleOn,
    ScaleOff,
    MirrorOn,
    MirrorOff,
    RotateOn,
    RotateOff,
}

/// Cutter radius compensation.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompOp {
    Cancel,
    Left,
    Right,
    /// LinuxCNC's dynamic compensation G41.1/G42.1: D the tool's diameter
    /// (a length, not a register), L a lathe tool's orientation.
    LeftDiameter,
    RightDiameter,
}

/// One-shot codes that move by the block's axis words.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(
    test,
    derive(strum::EnumDiscriminants),
    strum_discriminants(derive(strum::EnumIter))
)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MoveOp {
    /// G28: through the intermediate point to reference point 1.
    RefReturn,
    /// G29: from the reference point through the intermediate point.
    RefFrom,
    /// G30 P2–P4: to reference point n.
    RefReturnN,
    /// G53: a move in machine coordinates.
    MachineCoords,
    /// G31: a feed that stops at the skip signal.
    Skip,
    /// G38.2–G38.5: a probing move (`true`: alarm if the probe does not trip).
    Probe { must_trip: bool },
    /// The seed lathe's G74: X, then Z, to the reference point.
    RefXThenZ,
    /// The seed lathe's G76: back to the start point.
    StartPoint,
}

/// One-shot codes that set data.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(
    test,
    derive(strum::EnumDiscriminants),
    strum_discriminants(derive(strum::EnumIter))
)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetOp {
    /// G10: offsets and parameters.
    Data,
    /// G52: the local coordinate system.
    LocalSystem,
    /// G92 (a lathe's G50): set the coordinate system, or with S the spindle clamp.
    PresetOrClamp,
    /// G92.1: cancel the G92 shift.
    ShiftCancel,
    /// LinuxCNC's G92.2 (false: suspend the G92 shift, keeping its values)
    /// and G92.3 (true: put the kept shift back in force).
    ShiftSuspend(bool),
    /// G28.1 (1) / G30.1 (2): store the position as that reference point.
    RefStore(u8),
    /// The seed lathe's G75: the program zero from the tool's position.
    ProgramZero,
}

/// Dwells, exact stops, path control and feed settings.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PaceOp {
    /// G04 P milliseconds or X seconds (Fanuc, Syntec).
    Dwell,
    /// The seed lathe's G04: seconds.
    DwellSeconds,
    /// G04 P seconds (grbl, LinuxCNC).
    DwellP,
    /// EIA G04: a dwell, or a wait for the operator.
    DwellOrWait,
    ExactStopOnce,
    /// G05 P: high-speed machining mode.
    HighSpeed,
    /// Syntec G05.1: G01 path smoothing.
    PathSmoothing,
    /// Haas G187: the planner's smoothness setting.
    Smoothing,
    /// Fanuc G08 P1/P0: AI look-ahead control on/off.
    LookAhead,
    /// EIA G99: the junction after this block may blend.
    Junction,
    /// The seed lathe's G08/G09: feed ±10 %.
    FeedUp,
    FeedDown,
    /// The seed lathe's G30/G31: the feed magnification off / on.
    OverrideCancel,
    OverrideSet,
}

/// Canned drilling cycles, hole patterns and pockets.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(
    test,
    derive(strum::EnumDiscriminants),
    strum_discriminants(derive(strum::EnumIter))
)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleOp {
    /// A drilling cycle (group 09): the code its holes report, and what it
    /// does at each hole.
    Drill(Cycle, Hole),
    /// G80: no cycle.
    Cancel,
    PatternCircle,
    PatternLine,
    PatternArc,
    PatternGrid,
    /// EIA G78: a rectangular pocket.
    PocketRect,
    /// EIA G79: a circular pocket.
    PocketCircle,
    /// G12/G13 (Haas, Mach3): a circle cut about where the tool stands,
    /// clockwise or not, in the form the dialect reads.
    CircleCut(ArcDir, CircleCutForm),
}

/// How a dialect's G12/G13 reads its words and leaves the centre
/// (`codes/circle_cut.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CircleCutForm {
    /// Haas: I the first radius (the finish radius without K), K the
    /// finish radius, Q the step between them, D the cutter's radius
    /// register, L repeats, Z the depth (an increment under G91); in and
    /// out of each depth along half circles from and to the centre.
    Spiral,
    /// Mach3: I the radius of the tool centre's circle, straight out along
    /// X by I and straight back to the centre, at the level it stands.
    StraightInOut,
}

/// What a drilling cycle does at each hole (after the approach to R).
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hole {
    /// Feed to the bottom, out at rapid (G81).
    Drill,
    /// Feed to the bottom, dwell, out at rapid (G82).
    DrillDwell,
    /// Pecks, backing off by the clearance between them (G73).
    HighSpeedPeck,
    /// Pecks, out to R between them (G83).
    DeepPeck,
    /// Pecks, backing off 0.010 inch between them (EIA G87).
    ChipBreak,
    /// Tap right-hand: in forward, reverse, out (G84; pecks by Q).
    Tap,
    /// Tap left-hand (G74).
    LeftTap,
    /// Tap in the direction the spindle turns (EIA G84).
    TapEitherWay,
    /// Feed in, feed out (G85).
    Bore,
    /// Feed in, dwell, feed out (G89).
    BoreDwell,
    /// Feed in, spindle stop, out at rapid (G86).
    BoreStop,
    /// Feed in, wait for cycle start, out (EIA G86).
    BoreWaitStart,
    /// Feed in, dwell, stop, manual motion, out (G88).
    BoreManual,
    /// Feed in, orient, shift, out (G76).
    FineBore,
    /// From below the part, boring upward (G87).
    BackBore,
}

/// The lathes' turning and threading cycles.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TurnOp {
    /// The seed lathe's G81: a cylinder or taper cycle.
    CylinderCycle,
    /// The seed lathe's G331: a threading cycle.
    ThreadCycle,
    /// Fanuc lathe G70: finish along the profile P..Q.
    FinishCycle,
    /// Fanuc lathe G71: rough turning along the profile.
    RoughTurnCycle,
    /// Fanuc lathe G72: rough facing along the profile.
    RoughFaceCycle,
    /// Fanuc lathe G73: pattern repeating.
    PatternCycle,
    /// Fanuc lathe G74: face peck drilling.
    FacePeckCycle,
    /// Fanuc lathe G75: grooving.
    GrooveCycle,
    /// Fanuc lathe G76: multiple threading.
    ThreadMultiCycle,
    /// LinuxCNC's lathe G76: threading passes from the drive line (P
    /// pitch, I peak, J first depth, K full depth, R Q H E L).
    NgcThreadCycle,
    /// LinuxCNC's lathe G70: finishing passes along the profile of the
    /// subroutine Q.
    NgcFinishCycle,
    /// LinuxCNC's lathe roughing G71 (`facing` false) or G72, and which
    /// pockets it cuts (G7x, G7x.1, G7x.2).
    NgcRoughCycle { facing: bool, pockets: RoughPockets },
}

/// Which pockets (parts of the profile that dip again after rising)
/// LinuxCNC's roughing cycles cut.
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RoughPockets {
    /// G71, G72: every pocket.
    #[default]
    All,
    /// G71.1, G72.1: none; the profile is followed up to its end.
    None,
    /// G71.2, G72.2: only those after the first descent.
    AfterFirst,
}

/// Program flow.
#[allow(missing_docs)] // described in words by `meaning`, below
#[cfg_attr(test, derive(strum::EnumIter))]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlowOp {
    /// The seed lathe's G20: a subroutine call.
    SubCall,
    /// The seed lathe's G24: return.
    SubReturn,
    /// The seed lathe's G25: a jump.
    Jump,
    /// The seed lathe's G26: a loop.
    Loop,
    /// G65: a macro call.
    MacroCall,
    /// G66: a modal macro call.
    MacroModal,
    /// G67: cancel the modal macro call.
    MacroModalCancel,
}

impl GOp {
    /// Whether the code is one of the Fanuc lathe's G70–G73, which read
    /// their profile from the program text.
    pub fn reads_profile(self) -> bool {
        matches!(
            self,
            GOp::Turn(
                TurnOp::FinishCycle
                    | TurnOp::RoughTurnCycle
                    | TurnOp::RoughFaceCycle
                    | TurnOp::PatternCycle
                    | TurnOp::NgcFinishCycle
                    | TurnOp::NgcRoughCycle { .. }
            )
        )
    }

    /// What the code does, in a sentence (`vcnc explain`, hover, E201).
    pub fn meaning(self) -> &'static str {
        match self {
            GOp::Motion(m) => m.meaning(),
            GOp::Mode(m) => m.meaning(),
            GOp::Frame(f) => f.meaning(),
            GOp::Comp(c) => c.meaning(),
            GOp::Move(m) => m.meaning(),
            GOp::Set(s) => s.meaning(),
            GOp::Pace(p) => p.meaning(),
            GOp::Cycle(c) => c.meaning(),
            GOp::Turn(t) => t.meaning(),
            GOp::Flow(f) => f.meaning(),
        }
    }
}

impl MotionOp {
    fn meaning(self) -> &'static str {
        match self {
            MotionOp::Rapid => "rapid positioning: the axes move at their rapid rates",
            MotionOp::Linear => "linear interpolation: a straight cut at the feed F",
            MotionOp::ArcCw => {
                "circular interpolation clockwise: an arc by R or by the centre I/J/K, a helix with the axis off the plane"
            }
            MotionOp::ArcCcw => {
                "circular interpolation counterclockwise: an arc by R or by the centre I/J/K, a helix with the axis off the plane"
            }
            MotionOp::Thread => {
                "thread cutting: motion synchronised with the spindle, one lead per revolution"
            }
            MotionOp::ThreadInch => "thread cutting with the lead in inches",
            MotionOp::RigidTap => {
                "rigid tapping: in to the axis words with the spindle (K the pitch), the spindle reversed, out to the start"
            }
            MotionOp::ThreePointArc => "an arc through a middle point (IX/IZ) to the end point",
            MotionOp::Nurbs => {
                "NURBS interpolation: a curve from the control points of the following blocks (K knots, R weights)"
            }
            MotionOp::TurnCycle => "turning cycle (modal): cut to X/Z and return, a taper with R",
            MotionOp::ThreadingCycle => {
                "threading cycle (modal): one threading pass to X/Z and return"
            }
            MotionOp::FaceCycle => "facing cycle (modal): face to X/Z and return, a taper with R",
        }
    }
}

impl ModeOp {
    fn meaning(self) -> &'static str {
        match self {
            ModeOp::PlaneXy => "selects the XY plane for arcs, compensation and cycles",
            ModeOp::PlaneZx => "selects the ZX plane for arcs, compensation and cycles",
            ModeOp::PlaneYz => "selects the YZ plane for arcs, compensation and cycles",
            ModeOp::Absolute => "absolute programming: axis words are positions",
            ModeOp::Incremental => {
                "incremental programming: axis words are distances from where the tool is"
            }
            ModeOp::PerMinute => "feed per minute: F is a distance per minute",
            ModeOp::PerRev => "feed per revolution: F is a distance per spindle revolution",
            ModeOp::InverseTime => "inverse-time feed: F is one over the move's time in minutes",
            ModeOp::Inch => "inch input: lengths are read in inches",
            ModeOp::Metric => "metric input: lengths are read in millimetres",
            ModeOp::SurfaceSpeed => {
                "constant surface speed: S is a cutting speed (m/min or ft/min)"
            }
            ModeOp::SpindleRpm => "constant surface speed off: S is spindle rpm",
            ModeOp::WorkSystem(_) => "selects a work coordinate system (work offset)",
            ModeOp::CancelOffsets => {
                "cancels the work offset and the coordinate shift: program coordinates are machine coordinates"
            }
            ModeOp::PathExact => "exact stop mode: every move decelerates to a stop",
            ModeOp::PathSurface => "automatic corner override mode",
            ModeOp::PathTapping => "tapping mode: no feed override, no feed hold",
            ModeOp::PathCutting => {
                "cutting mode: moves blend at corners (P sets a tolerance where read)"
            }
            ModeOp::ReturnInitial => "canned cycles return to the initial level",
            ModeOp::ReturnR => "canned cycles return to the R level",
            ModeOp::ArcCentersAbsolute => "arc centres I/J/K are absolute positions",
            ModeOp::ArcCentersIncremental => "arc centres I/J/K are distances from the start point",
            ModeOp::RadiusMode => "X is programmed as a radius",
            ModeOp::DiameterMode => "X is programmed as a diameter",
        }
    }
}

impl FrameOp {
    fn meaning(self) -> &'static str {
        match self {
            FrameOp::ToolLengthPlus => "tool length compensation +: the H offset is added to Z",
            FrameOp::ToolLengthMinus => {
                "tool length compensation −: the H offset is subtracted from Z"
            }
            FrameOp::ToolLengthCancel => "cancels tool length compensation",
            FrameOp::ToolLengthDynamic => {
                "tool length compensation by the length given in the block"
            }
            FrameOp::PolarOn => "polar coordinate input: X is a radius, Y an angle",
            FrameOp::PolarOff => "cancels polar coordinate input",
            FrameOp::ScaleOn => "scaling about a centre by P (or I/J/K per axis)",
            FrameOp::ScaleOff => "cancels scaling",
            FrameOp::MirrorOn => "programmable mirror image about the named axis positions",
            FrameOp::MirrorOff => "cancels the mirror image of the named axes",
            FrameOp::RotateOn => "coordinate rotation by R degrees about a centre",
            FrameOp::RotateOff => "cancels coordinate rotation",
        }
    }
}

impl CompOp {
    fn meaning(self) -> &'static str {
        match self {
            CompOp::Cancel => "cancels cutter radius compensation",
            CompOp::Left => {
                "cutter radius compensation left: the tool runs left of the path by the D radius"
            }
            CompOp::Right => {
                "cutter radius compensation right: the tool runs right of the path by the D radius"
            }
            CompOp::LeftDiameter => {
                "cutter compensation left by the block's D diameter (L: a lathe tool's orientation)"
            }
            CompOp::RightDiameter => {
                "cutter compensation right by the block's D diameter (L: a lathe tool's orientation)"
            }
        }
    }
}

impl MoveOp {
    fn meaning(self) -> &'static str {
        match self {
            MoveOp::RefReturn => {
                "reference point return: through the named axes' intermediate point to the reference point"
            }
            MoveOp::RefFrom => {
                "return from the reference point through the intermediate point to the commanded point"
            }
            MoveOp::RefReturnN => {
                "return to reference point P (2 to 4) through the intermediate point"
            }
            MoveOp::MachineCoords => "a move in machine coordinates, this block only",
            MoveOp::Skip => "skip function: a feed that stops where the skip signal fires",
            MoveOp::Probe { must_trip: true } => {
                "probing: a feed that alarms if the probe does not trip"
            }
            MoveOp::Probe { must_trip: false } => {
                "probing: a feed that stops where the probe trips, no alarm if it does not"
            }
            MoveOp::RefXThenZ => "reference point return, X first, then Z",
            MoveOp::StartPoint => "return to the program's start point",
        }
    }
}

impl SetOp {
    fn meaning(self) -> &'static str {
        match self {
            SetOp::Data => {
                "data setting: writes work offsets (L2/L20) or tool offsets (L1/L10–L13)"
            }
            SetOp::LocalSystem => {
                "local coordinate system: shifts the program zero inside the work system"
            }
            SetOp::PresetOrClamp => {
                "sets the coordinate system so the tool reads the axis words; with S alone, the spindle speed clamp"
            }
            SetOp::ShiftCancel => "cancels the coordinate shift",
            SetOp::ShiftSuspend(false) => "suspends the coordinate shift, keeping its values",
            SetOp::ShiftSuspend(true) => "restores the coordinate shift that G92.2 suspended",
            SetOp::RefStore(_) => "stores the current position as a reference point",
            SetOp::ProgramZero => "sets the program zero from the tool's position",
        }
    }
}

impl PaceOp {
    fn meaning(self) -> &'static str {
        match self {
            PaceOp::Dwell => "dwell: P milliseconds or X seconds",
            PaceOp::DwellSeconds => "dwell: seconds",
            PaceOp::DwellP => "dwell: P seconds",
            PaceOp::DwellOrWait => "dwell for the time given, or wait for the operator",
            PaceOp::ExactStopOnce => "exact stop: this block's move decelerates to a stop",
            PaceOp::HighSpeed => "high-speed machining mode by parameter set P",
            PaceOp::PathSmoothing => "path smoothing of G01 chains (Q1 on, Q0 off, E tolerance)",
            PaceOp::Smoothing => {
                "the planner's smoothness setting (P1 rough to P3 finish, E tolerance)"
            }
            PaceOp::LookAhead => {
                "AI look-ahead control: P1 on (feed planned ahead, corners slowed by acceleration), P0 off"
            }
            PaceOp::Junction => "the junction after this block's cut may blend",
            PaceOp::FeedUp => "feed +10 %",
            PaceOp::FeedDown => "feed −10 %",
            PaceOp::OverrideCancel => "feed magnification off (100 %)",
            PaceOp::OverrideSet => "feed magnification F percent",
        }
    }
}

impl CycleOp {
    fn meaning(self) -> &'static str {
        match self {
            CycleOp::Drill(_, hole) => hole.meaning(),
            CycleOp::Cancel => "cancels the canned cycle",
            CycleOp::PatternCircle => {
                "bolt circle: the cycle's holes on a circle of radius I, from angle J, K holes"
            }
            CycleOp::PatternLine => "holes on a line: interval I, angle J, K holes",
            CycleOp::PatternArc => {
                "holes on an arc: radius I, from angle J, K holes, P degrees apart"
            }
            CycleOp::PatternGrid => "a grid of holes: intervals I and J, P holes a row, K rows",
            CycleOp::PocketRect => "rectangular pocket milling",
            CycleOp::PocketCircle => "circular pocket milling",
            CycleOp::CircleCut(dir, form) => match (dir, form) {
                (ArcDir::Cw, CircleCutForm::Spiral) => {
                    "circular pocket milling clockwise: from the centre to radius I, out by Q to K, less D's radius, L times to Z, back to the centre"
                }
                (ArcDir::Ccw, CircleCutForm::Spiral) => {
                    "circular pocket milling counter-clockwise: from the centre to radius I, out by Q to K, less D's radius, L times to Z, back to the centre"
                }
                (ArcDir::Cw, CircleCutForm::StraightInOut) => {
                    "circular pocket clockwise: out along X by I, a circle about the starting point, back to it"
                }
                (ArcDir::Ccw, CircleCutForm::StraightInOut) => {
                    "circular pocket counter-clockwise: out along X by I, a circle about the starting point, back to it"
                }
            },
        }
    }
}

impl Hole {
    fn meaning(self) -> &'static str {
        match self {
            Hole::Drill => "drilling cycle: feed to Z, rapid out",
            Hole::DrillDwell => "spot drilling cycle: feed to Z, dwell P, rapid out",
            Hole::HighSpeedPeck => {
                "high-speed peck drilling: pecks of Q, backing off between pecks"
            }
            Hole::DeepPeck => "deep-hole peck drilling: pecks of Q, out to R between pecks",
            Hole::ChipBreak => {
                "chip-breaking peck drilling: pecks of Q, backing off 0.010 inch between pecks"
            }
            Hole::Tap => "tapping cycle: in with the spindle forward, reverse at Z, out",
            Hole::LeftTap => {
                "left-hand tapping cycle: in with the spindle reversed, forward at Z, out"
            }
            Hole::TapEitherWay => "tapping cycle in the spindle's direction: reverse at Z, out",
            Hole::Bore => "boring cycle: feed to Z, feed out",
            Hole::BoreDwell => "boring cycle: feed to Z, dwell P, feed out",
            Hole::BoreStop => "boring cycle: feed to Z, spindle stop, rapid out",
            Hole::BoreWaitStart => "boring cycle: feed to Z, wait for cycle start, out",
            Hole::BoreManual => "boring cycle: feed to Z, dwell, spindle stop, manual retract",
            Hole::FineBore => "fine boring: feed to Z, orient the spindle, shift by Q, rapid out",
            Hole::BackBore => "back boring: shifted down past the part, bore upward to Z",
        }
    }
}

impl TurnOp {
    fn meaning(self) -> &'static str {
        match self {
            TurnOp::CylinderCycle => "cylinder or taper turning cycle",
            TurnOp::ThreadCycle => "threading cycle",
            TurnOp::FinishCycle => "finishing cycle along the profile between N P and N Q",
            TurnOp::RoughTurnCycle => {
                "stock removal in turning along the profile between N P and N Q"
            }
            TurnOp::RoughFaceCycle => {
                "stock removal in facing along the profile between N P and N Q"
            }
            TurnOp::PatternCycle => "pattern repeating along the profile between N P and N Q",
            TurnOp::FacePeckCycle => "end face peck drilling cycle",
            TurnOp::GrooveCycle => "outer or inner diameter grooving cycle",
            TurnOp::ThreadMultiCycle => "multiple threading cycle",
            TurnOp::NgcFinishCycle => {
                "finishing cycle along the profile of subroutine o<Q> (X Z the start point, P passes)"
            }
            TurnOp::NgcRoughCycle { facing, pockets } => match (facing, pockets) {
                (false, RoughPockets::All) => {
                    "roughing cycle along Z cutting every pocket (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
                (false, RoughPockets::None) => {
                    "roughing cycle along Z cutting no pocket (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
                (false, RoughPockets::AfterFirst) => {
                    "roughing cycle along Z cutting the pockets after the first descent (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
                (true, RoughPockets::All) => {
                    "facing roughing cycle cutting every pocket (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
                (true, RoughPockets::None) => {
                    "facing roughing cycle cutting no pocket (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
                (true, RoughPockets::AfterFirst) => {
                    "facing roughing cycle cutting the pockets after the first descent (profile o<Q>, D allowance, I depth of cut, R retract)"
                }
            },
            TurnOp::NgcThreadCycle => {
                "threading cycle: passes from the drive line to Z (P pitch, I peak, J first depth, K full depth)"
            }
        }
    }
}

impl FlowOp {
    fn meaning(self) -> &'static str {
        match self {
            FlowOp::SubCall => "subroutine call",
            FlowOp::SubReturn => "return from a subroutine",
            FlowOp::Jump => "jump to a sequence number",
            FlowOp::Loop => "repeat the blocks up to a sequence number",
            FlowOp::MacroCall => "macro call: program P with the block's words as arguments",
            FlowOp::MacroModal => "modal macro call: program P after every move until G67",
            FlowOp::MacroModalCancel => "cancels the modal macro call",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::{Dialect, MOp};
    use std::collections::BTreeSet;
    use strum::IntoEnumIterator;

    /// The operation's variant, without its data.
    fn variant(op: GOp) -> String {
        match op {
            GOp::Motion(m) => format!("Motion::{m:?}"),
            GOp::Mode(m) => format!("Mode::{:?}", ModeOpDiscriminants::from(m)),
            GOp::Frame(f) => format!("Frame::{f:?}"),
            GOp::Comp(c) => format!("Comp::{c:?}"),
            GOp::Move(m) => format!("Move::{:?}", MoveOpDiscriminants::from(m)),
            GOp::Set(s) => format!("Set::{:?}", SetOpDiscriminants::from(s)),
            GOp::Pace(p) => format!("Pace::{p:?}"),
            GOp::Cycle(c) => format!("Cycle::{:?}", CycleOpDiscriminants::from(c)),
            GOp::Turn(t) => format!("Turn::{t:?}"),
            GOp::Flow(f) => format!("Flow::{f:?}"),
        }
    }

    /// Every variant of every role, by the same names.
    fn every_variant() -> BTreeSet<String> {
        let mut all = BTreeSet::new();
        for role in GOpDiscriminants::iter() {
            let names: Vec<String> = match role {
                GOpDiscriminants::Motion => {
                    MotionOp::iter().map(|m| format!("Motion::{m:?}")).collect()
                }
                GOpDiscriminants::Mode => ModeOpDiscriminants::iter()
                    .map(|m| format!("Mode::{m:?}"))
                    .collect(),
                GOpDiscriminants::Frame => {
                    FrameOp::iter().map(|f| format!("Frame::{f:?}")).collect()
                }
                GOpDiscriminants::Comp => CompOp::iter().map(|c| format!("Comp::{c:?}")).collect(),
                GOpDiscriminants::Move => MoveOpDiscriminants::iter()
                    .map(|m| format!("Move::{m:?}"))
                    .collect(),
                GOpDiscriminants::Set => SetOpDiscriminants::iter()
                    .map(|s| format!("Set::{s:?}"))
                    .collect(),
                GOpDiscriminants::Pace => PaceOp::iter().map(|p| format!("Pace::{p:?}")).collect(),
                GOpDiscriminants::Cycle => CycleOpDiscriminants::iter()
                    .map(|c| format!("Cycle::{c:?}"))
                    .collect(),
                GOpDiscriminants::Turn => TurnOp::iter().map(|t| format!("Turn::{t:?}")).collect(),
                GOpDiscriminants::Flow => FlowOp::iter().map(|f| format!("Flow::{f:?}")).collect(),
            };
            all.extend(names);
        }
        all
    }

    fn dialects() -> Vec<Dialect> {
        Dialect::NAMES
            .iter()
            .filter_map(|n| Dialect::by_name(n))
            .collect()
    }

    /// A new operation fails here until a dialect's table lists it, and a
    /// new role until it is enumerated above: no code the interpreter can
    /// dispatch is missing from every table (nor from `vcnc explain`).
    #[test]
    fn every_operation_is_in_some_table() {
        let mut listed = BTreeSet::new();
        let mut holes = BTreeSet::new();
        let mut m_ops = BTreeSet::new();
        for d in dialects() {
            for (_, def) in d.g_rows() {
                listed.insert(variant(def.op));
                if let GOp::Cycle(CycleOp::Drill(_, hole)) = def.op {
                    holes.insert(format!("{hole:?}"));
                }
            }
            for (_, def) in d.m_rows() {
                m_ops.insert(format!("{:?}", def.op));
            }
        }
        let missing: Vec<_> = every_variant().difference(&listed).cloned().collect();
        assert!(missing.is_empty(), "in no dialect table: {missing:?}");
        let missing: Vec<_> = Hole::iter()
            .map(|h| format!("{h:?}"))
            .filter(|h| !holes.contains(h))
            .collect();
        assert!(missing.is_empty(), "no cycle does: {missing:?}");
        let missing: Vec<_> = MOp::iter()
            .map(|m| format!("{m:?}"))
            .filter(|m| !m_ops.contains(m))
            .collect();
        assert!(missing.is_empty(), "in no M table: {missing:?}");
    }

    /// Every table entry has its words: the meaning `vcnc explain` and the
    /// hover show is a sentence, not empty.
    #[test]
    fn every_table_entry_has_text() {
        for d in dialects() {
            for (code, def) in d.g_rows() {
                let text = def.op.meaning();
                assert!(
                    text.len() > 8,
                    "{}: G{} has no text",
                    d.name,
                    f64::from(code) / 10.0
                );
            }
            for (code, def) in d.m_rows() {
                assert!(
                    def.op.meaning().len() > 8,
                    "{}: M{code} has no text",
                    d.name
                );
            }
        }
    }
}
