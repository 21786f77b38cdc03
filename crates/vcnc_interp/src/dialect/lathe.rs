//! The lathe dialect of seed 003 (`003_62526af55394feba.txt`), a profile of
//! the same engine: its own rows for the same operations where the codes
//! mean what they mean on a mill, new operations where they do not, and word
//! rules for X in diameters, U/W increments, `CR=`, `D`, `IX`/`IZ`.
//!
//! Decisions the document leaves open are in `docs/dialects.md` (lathe).

use super::{
    BareReturn, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp, GRow, Group,
    IntegerWords, LongChord, OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn, ThreadLead,
    ToolChangeSpindle, ToolLengthChange, ToolWords, bit, g,
};
use super::{FlowOp, ModeOp, MotionOp, MoveOp, PaceOp, SetOp, TurnOp};
use vcnc_core::events::Plane;
use vcnc_core::machine::DEFAULT_LATHE_TOML;
use vcnc_syntax::{Addr, Extended, LexRules, Semicolon};

const LATHE_G: &[GRow] = &[
    g(0, GOp::Motion(MotionOp::Rapid), Group::Motion),
    g(10, GOp::Motion(MotionOp::Linear), Group::Motion),
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion),
    g(40, GOp::Pace(PaceOp::DwellSeconds), Group::NonModal)
        .reads(bit(b'F') | bit(b'K'))
        .refuses_axes(),
    g(50, GOp::Motion(MotionOp::ThreePointArc), Group::Motion),
    g(80, GOp::Pace(PaceOp::FeedUp), Group::NonModal)
        .refuses_axes()
        .alone(),
    g(90, GOp::Pace(PaceOp::FeedDown), Group::NonModal)
        .refuses_axes()
        .alone(),
    g(200, GOp::Flow(FlowOp::SubCall), Group::NonModal)
        .reads(bit(b'L'))
        .refuses_axes()
        .alone(),
    g(220, GOp::Mode(ModeOp::RadiusMode), Group::DiameterMode).alone(),
    g(2200, GOp::Mode(ModeOp::RadiusMode), Group::DiameterMode).alone(),
    g(230, GOp::Mode(ModeOp::DiameterMode), Group::DiameterMode).alone(),
    g(2300, GOp::Mode(ModeOp::DiameterMode), Group::DiameterMode).alone(),
    g(240, GOp::Flow(FlowOp::SubReturn), Group::NonModal)
        .refuses_axes()
        .alone(),
    g(250, GOp::Flow(FlowOp::Jump), Group::NonModal)
        .reads(bit(b'L'))
        .refuses_axes(),
    g(260, GOp::Flow(FlowOp::Loop), Group::NonModal)
        .reads(bit(b'L') | bit(b'Q'))
        .refuses_axes(),
    g(300, GOp::Pace(PaceOp::OverrideCancel), Group::NonModal)
        .refuses_axes()
        .alone(),
    g(310, GOp::Pace(PaceOp::OverrideSet), Group::NonModal)
        .reads(bit(b'F'))
        .refuses_axes(),
    g(320, GOp::Motion(MotionOp::ThreadInch), Group::Motion),
    g(330, GOp::Motion(MotionOp::Thread), Group::Motion),
    g(530, GOp::Mode(ModeOp::CancelOffsets), Group::Wcs),
    g(5000, GOp::Mode(ModeOp::CancelOffsets), Group::Wcs),
    g(540, GOp::Mode(ModeOp::WorkSystem(0)), Group::Wcs),
    g(550, GOp::Mode(ModeOp::WorkSystem(1)), Group::Wcs),
    g(560, GOp::Mode(ModeOp::WorkSystem(2)), Group::Wcs),
    g(570, GOp::Mode(ModeOp::WorkSystem(3)), Group::Wcs),
    g(580, GOp::Mode(ModeOp::WorkSystem(4)), Group::Wcs),
    g(590, GOp::Mode(ModeOp::WorkSystem(5)), Group::Wcs),
    g(600, GOp::Mode(ModeOp::PathExact), Group::Path),
    g(640, GOp::Mode(ModeOp::PathCutting), Group::Path),
    g(700, GOp::Mode(ModeOp::Inch), Group::Units),
    g(710, GOp::Mode(ModeOp::Metric), Group::Units),
    g(740, GOp::Move(MoveOp::RefXThenZ), Group::NonModal)
        .claims_axes()
        .alone(),
    g(750, GOp::Set(SetOp::ProgramZero), Group::NonModal).claims_axes(),
    g(760, GOp::Move(MoveOp::StartPoint), Group::NonModal).refuses_axes(),
    g(810, GOp::Turn(TurnOp::CylinderCycle), Group::NonModal)
        .reads(bit(b'R') | bit(b'I') | bit(b'K'))
        .claims_axes(),
    g(3310, GOp::Turn(TurnOp::ThreadCycle), Group::NonModal)
        .reads(bit(b'I') | bit(b'K') | bit(b'R') | bit(b'P'))
        .claims_axes(),
    g(900, GOp::Mode(ModeOp::Absolute), Group::Distance),
    g(910, GOp::Mode(ModeOp::Incremental), Group::Distance),
    g(920, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(940, GOp::Mode(ModeOp::PerMinute), Group::FeedMode),
    g(950, GOp::Mode(ModeOp::PerRev), Group::FeedMode),
];

const LATHE_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: true,
    fullwidth_semicolon: true,
    extended: Extended::new(&[
        ("CR=", Addr::CR),
        ("IX", Addr::IX),
        ("IZ", Addr::IZ),
        ("D=", Addr(b'D')),
    ]),
    foreign: &[],
    colon_is_o: false,
    paren_in_comment_alarms: false,
};

/// Listed by the document without a format to run.
const UNSPECIFIED: &[(u16, &str)] = &[(
    70,
    "G07 (Z-spline interpolation) is listed by the lathe document without any format or parameters",
)];

/// The lathe dialect.
pub(super) fn lathe() -> Dialect {
    let (g, m) = Dialect::tables(&[LATHE_G], super::m_codes::MILL);
    Dialect {
        name: "lathe",
        lex: LATHE_LEX,
        g,
        m,
        incremental_words: &[(b'U', b'X'), (b'W', b'Z')],
        diameter: Diameter {
            axis: Some(b'X'),
            at_power_on: true,
            lathe: true,
        },
        integers: IntegerWords::WholeUnits,
        plane: Plane::Zx,
        long_chord: LongChord::Line,
        arc_end: super::ArcEnd::MachineTolerance,
        o_in_flow: super::OInFlow::EndsProgram,
        arc_letters: bit(b'D'),
        default_machine: DEFAULT_LATHE_TOML,
        unsupported: UNSPECIFIED,
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::FANUC,
        bare_return: BareReturn::NeedsAxes,
        g10: G10Rules::FANUC,
        program_stop: ProgramStop::StopsSpindleAndCoolant,
        tool_length_change: ToolLengthChange::MovesNow,
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
