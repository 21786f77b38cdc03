//! grbl 1.1 and the hobby CAM programs written for it (Fusion 360's grbl
//! post, CNC.js, Estlcam, Inkscape, pcb2gcode …): `;` comments, integers
//! in whole units, G91.1 arc centres, probes, inverse-time feed, G28.1 and
//! G43.1. The code list is grbl 1.1's (its wiki "Grbl v1.1 Commands"), with
//! G90.1, G64 and M06 accepted as the CAM output of LinuxCNC-minded posts
//! writes them (grblHAL runs them too). The flattened `--format gcode`
//! output runs on it.

use super::{
    BareReturn, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp, GRow, Group,
    IntegerWords, LongChord, OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn, ThreadLead,
    ToolChangeSpindle, ToolLengthChange, ToolWords, bit, g,
};
use super::{
    CompOp, CycleOp, FrameOp, ModeOp, MotionOp, MoveOp, PaceOp, SetOp,
    m_codes::{self, MRow},
};
use vcnc_core::events::Plane;
use vcnc_core::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{Extended, LexRules, Semicolon};

pub(super) const GRBL_G: &[GRow] = &[
    g(0, GOp::Motion(MotionOp::Rapid), Group::Motion),
    g(10, GOp::Motion(MotionOp::Linear), Group::Motion),
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion),
    g(40, GOp::Pace(PaceOp::DwellP), Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    g(100, GOp::Set(SetOp::Data), Group::NonModal)
        .reads(bit(b'L') | bit(b'P'))
        .claims_absolute_axes(),
    g(170, GOp::Mode(ModeOp::PlaneXy), Group::Plane),
    g(180, GOp::Mode(ModeOp::PlaneZx), Group::Plane),
    g(190, GOp::Mode(ModeOp::PlaneYz), Group::Plane),
    g(200, GOp::Mode(ModeOp::Inch), Group::Units),
    g(210, GOp::Mode(ModeOp::Metric), Group::Units),
    g(280, GOp::Move(MoveOp::RefReturn), Group::NonModal).claims_axes(),
    g(281, GOp::Set(SetOp::RefStore(1)), Group::NonModal),
    g(300, GOp::Move(MoveOp::RefReturnN), Group::NonModal).claims_axes(),
    g(301, GOp::Set(SetOp::RefStore(2)), Group::NonModal),
    // G38.2/G38.3 probe toward the work, G38.4/G38.5 away from it.
    g(
        382,
        GOp::Move(MoveOp::Probe { must_trip: true }),
        Group::NonModal,
    )
    .claims_axes(),
    g(
        383,
        GOp::Move(MoveOp::Probe { must_trip: false }),
        Group::NonModal,
    )
    .claims_axes(),
    g(
        384,
        GOp::Move(MoveOp::Probe { must_trip: true }),
        Group::NonModal,
    )
    .claims_axes(),
    g(
        385,
        GOp::Move(MoveOp::Probe { must_trip: false }),
        Group::NonModal,
    )
    .claims_axes(),
    g(400, GOp::Comp(CompOp::Cancel), Group::CutterComp),
    g(
        431,
        GOp::Frame(FrameOp::ToolLengthDynamic),
        Group::ToolLength,
    )
    .claims_absolute_axes(),
    g(
        490,
        GOp::Frame(FrameOp::ToolLengthCancel),
        Group::ToolLength,
    ),
    g(530, GOp::Move(MoveOp::MachineCoords), Group::NonModal).claims_absolute_axes(),
    g(540, GOp::Mode(ModeOp::WorkSystem(0)), Group::Wcs),
    g(550, GOp::Mode(ModeOp::WorkSystem(1)), Group::Wcs),
    g(560, GOp::Mode(ModeOp::WorkSystem(2)), Group::Wcs),
    g(570, GOp::Mode(ModeOp::WorkSystem(3)), Group::Wcs),
    g(580, GOp::Mode(ModeOp::WorkSystem(4)), Group::Wcs),
    g(590, GOp::Mode(ModeOp::WorkSystem(5)), Group::Wcs),
    g(610, GOp::Mode(ModeOp::PathExact), Group::Path),
    // LinuxCNC's blending tolerances P (path) and Q (naive CAM), for the
    // planner to read one day; accepted as LinuxCNC-minded posts write them.
    g(640, GOp::Mode(ModeOp::PathCutting), Group::Path).reads(bit(b'P') | bit(b'Q')),
    // grbl's G80 cancels the motion mode; with no canned cycles it asks
    // for nothing (a safe-start line's G80 runs).
    g(800, GOp::Cycle(CycleOp::Cancel), Group::Cycle),
    g(900, GOp::Mode(ModeOp::Absolute), Group::Distance),
    g(
        901,
        GOp::Mode(ModeOp::ArcCentersAbsolute),
        Group::ArcDistance,
    ),
    g(910, GOp::Mode(ModeOp::Incremental), Group::Distance),
    g(
        911,
        GOp::Mode(ModeOp::ArcCentersIncremental),
        Group::ArcDistance,
    ),
    g(920, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(921, GOp::Set(SetOp::ShiftCancel), Group::NonModal),
    g(930, GOp::Mode(ModeOp::InverseTime), Group::FeedMode),
    g(940, GOp::Mode(ModeOp::PerMinute), Group::FeedMode),
];

/// grbl's M codes; M07 is mist coolant, reported as coolant on.
pub(super) const GRBL_M: &[&[MRow]] = m_codes::GRBL;

/// `;` starts a comment; no `//` comments, no full-width `；`.
pub(super) const GRBL_LEX: LexRules = LexRules {
    semicolon: Semicolon::Comment,
    slash_comments: false,
    fullwidth_semicolon: false,
    extended: Extended::NONE,
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
    paren_in_comment_alarms: false,
};

/// The grbl dialect.
pub(super) fn grbl() -> Dialect {
    let (g, m) = Dialect::tables(&[GRBL_G], GRBL_M);
    Dialect {
        name: "grbl",
        lex: GRBL_LEX,
        g,
        m,
        incremental_words: &[],
        diameter: Diameter {
            axis: None,
            at_power_on: false,
            lathe: false,
        },
        // `X5` is 5 mm: grbl has no least-increment input.
        integers: IntegerWords::WholeUnits,
        plane: Plane::Xy,
        long_chord: LongChord::Alarm,
        arc_end: super::ArcEnd::MachineTolerance,
        o_in_flow: super::OInFlow::EndsProgram,
        arc_letters: 0,
        default_machine: DEFAULT_MILL_TOML,
        unsupported: &[],
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::FANUC,
        bare_return: BareReturn::AllAxes,
        g10: G10Rules::GRBL,
        program_stop: ProgramStop::Pause,
        tool_length_change: ToolLengthChange::AtNextMove,
        offset_default: OffsetDefault::Modal,
        macros: super::MacroRules::NONE,
        feed_at_power_on: FeedAtPowerOn::PerMinute,
        surface_speed: SurfaceSpeedOn::ToolDiameter,
        tool_words: ToolWords::Select,
        dwell_p: DwellP::WholeMilliseconds,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        tip_numbering: vcnc_core::tooling::TipNumbering::Fanuc,
        g53_incremental: super::G53Incremental::Alarm,
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        gcode_systems: false,
        polar_words: false,
    }
}
