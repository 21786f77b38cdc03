//! The Syntec 900M and Fanuc 0i mill dialects: the G-code list of the Syntec
//! manual (section 1.1) as far as vcnc runs it, and the M-code table of its
//! chapter 2. The two differ only in the inch/metric codes.

use super::{
    BareReturn, CYCLE_WORDS, CYCLE_WORDS_L, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn,
    G10Rules, GOp, GRow, Group, HAAS_PECK_WORDS, IntegerWords, LongChord, MOp, OffsetDefault,
    ProgramStop, RapidPath, SurfaceSpeedOn, ThreadLead, ToolChangeSpindle, ToolLengthChange,
    ToolWords, bit, g,
};
use super::{
    CircleCutForm, CompOp, CycleOp, FlowOp, FrameOp, Hole, ModeOp, MotionOp, MoveOp, PaceOp, SetOp,
    m_codes::{self, MRow, m},
};
use vcnc_core::events::{ArcDir, Cycle, Plane};
use vcnc_core::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{Addr, Extended, LexRules, Semicolon};

/// Rows shared by the Syntec 900M and Fanuc 0i mill dialects.
const MILL_G: &[GRow] = &[
    g(0, GOp::Motion(MotionOp::Rapid), Group::Motion),
    g(10, GOp::Motion(MotionOp::Linear), Group::Motion),
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion),
    g(40, GOp::Pace(PaceOp::Dwell), Group::NonModal)
        .reads(bit(b'P') | bit(b'X'))
        .refuses_axes(),
    g(50, GOp::Pace(PaceOp::HighSpeed), Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    g(51, GOp::Pace(PaceOp::PathSmoothing), Group::NonModal)
        .reads(bit(b'Q') | bit(b'E'))
        .refuses_axes(),
    g(62, GOp::Motion(MotionOp::Nurbs), Group::Motion).reads(bit(b'P') | bit(b'K') | bit(b'R')),
    g(90, GOp::Pace(PaceOp::ExactStopOnce), Group::NonModal),
    g(100, GOp::Set(SetOp::Data), Group::NonModal)
        .reads(bit(b'L') | bit(b'P') | bit(b'R'))
        .claims_absolute_axes(),
    g(150, GOp::Frame(FrameOp::PolarOff), Group::Polar),
    g(160, GOp::Frame(FrameOp::PolarOn), Group::Polar),
    g(170, GOp::Mode(ModeOp::PlaneXy), Group::Plane),
    g(180, GOp::Mode(ModeOp::PlaneZx), Group::Plane),
    g(190, GOp::Mode(ModeOp::PlaneYz), Group::Plane),
    g(280, GOp::Move(MoveOp::RefReturn), Group::NonModal).claims_axes(),
    g(290, GOp::Move(MoveOp::RefFrom), Group::NonModal).claims_axes(),
    g(300, GOp::Move(MoveOp::RefReturnN), Group::NonModal)
        .reads(bit(b'P'))
        .claims_axes(),
    g(310, GOp::Move(MoveOp::Skip), Group::NonModal).claims_axes(),
    g(330, GOp::Motion(MotionOp::Thread), Group::Motion),
    g(400, GOp::Comp(CompOp::Cancel), Group::CutterComp),
    g(410, GOp::Comp(CompOp::Left), Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::Comp(CompOp::Right), Group::CutterComp).reads(bit(b'D')),
    g(430, GOp::Frame(FrameOp::ToolLengthPlus), Group::ToolLength).reads(bit(b'H')),
    g(440, GOp::Frame(FrameOp::ToolLengthMinus), Group::ToolLength).reads(bit(b'H')),
    g(
        490,
        GOp::Frame(FrameOp::ToolLengthCancel),
        Group::ToolLength,
    ),
    g(500, GOp::Frame(FrameOp::ScaleOff), Group::Scaling),
    g(501, GOp::Frame(FrameOp::MirrorOff), Group::Mirror).claims_absolute_axes(),
    g(510, GOp::Frame(FrameOp::ScaleOn), Group::Scaling)
        .reads(bit(b'P') | bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_absolute_axes(),
    g(511, GOp::Frame(FrameOp::MirrorOn), Group::Mirror).claims_absolute_axes(),
    g(520, GOp::Set(SetOp::LocalSystem), Group::NonModal).claims_absolute_axes(),
    g(530, GOp::Move(MoveOp::MachineCoords), Group::NonModal).claims_absolute_axes(),
    g(540, GOp::Mode(ModeOp::WorkSystem(0)), Group::Wcs),
    g(550, GOp::Mode(ModeOp::WorkSystem(1)), Group::Wcs),
    g(560, GOp::Mode(ModeOp::WorkSystem(2)), Group::Wcs),
    g(570, GOp::Mode(ModeOp::WorkSystem(3)), Group::Wcs),
    g(580, GOp::Mode(ModeOp::WorkSystem(4)), Group::Wcs),
    g(590, GOp::Mode(ModeOp::WorkSystem(5)), Group::Wcs),
    g(591, GOp::Mode(ModeOp::WorkSystem(6)), Group::Wcs),
    g(592, GOp::Mode(ModeOp::WorkSystem(7)), Group::Wcs),
    g(593, GOp::Mode(ModeOp::WorkSystem(8)), Group::Wcs),
    g(594, GOp::Mode(ModeOp::WorkSystem(9)), Group::Wcs),
    g(595, GOp::Mode(ModeOp::WorkSystem(10)), Group::Wcs),
    g(596, GOp::Mode(ModeOp::WorkSystem(11)), Group::Wcs),
    g(597, GOp::Mode(ModeOp::WorkSystem(12)), Group::Wcs),
    g(598, GOp::Mode(ModeOp::WorkSystem(13)), Group::Wcs),
    g(599, GOp::Mode(ModeOp::WorkSystem(14)), Group::Wcs),
    g(610, GOp::Mode(ModeOp::PathExact), Group::Path),
    g(620, GOp::Mode(ModeOp::PathSurface), Group::Path),
    g(630, GOp::Mode(ModeOp::PathTapping), Group::Path),
    g(640, GOp::Mode(ModeOp::PathCutting), Group::Path),
    // G65/G66 take every letter as the call's P, L and arguments.
    g(650, GOp::Flow(FlowOp::MacroCall), Group::NonModal)
        .reads(ALL_LETTERS)
        .refuses_axes(),
    g(660, GOp::Flow(FlowOp::MacroModal), Group::MacroModal)
        .reads(ALL_LETTERS)
        .refuses_axes(),
    g(670, GOp::Flow(FlowOp::MacroModalCancel), Group::MacroModal),
    g(680, GOp::Frame(FrameOp::RotateOn), Group::Rotation)
        .reads(bit(b'R'))
        .claims_absolute_axes(),
    g(690, GOp::Frame(FrameOp::RotateOff), Group::Rotation),
    g(
        730,
        GOp::Cycle(CycleOp::Drill(Cycle::G73, Hole::HighSpeedPeck)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        740,
        GOp::Cycle(CycleOp::Drill(Cycle::G74, Hole::LeftTap)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        760,
        GOp::Cycle(CycleOp::Drill(Cycle::G76, Hole::FineBore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(800, GOp::Cycle(CycleOp::Cancel), Group::Cycle),
    g(
        810,
        GOp::Cycle(CycleOp::Drill(Cycle::G81, Hole::Drill)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        820,
        GOp::Cycle(CycleOp::Drill(Cycle::G82, Hole::DrillDwell)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        830,
        GOp::Cycle(CycleOp::Drill(Cycle::G83, Hole::DeepPeck)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        840,
        GOp::Cycle(CycleOp::Drill(Cycle::G84, Hole::Tap)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        850,
        GOp::Cycle(CycleOp::Drill(Cycle::G85, Hole::Bore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        860,
        GOp::Cycle(CycleOp::Drill(Cycle::G86, Hole::BoreStop)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        870,
        GOp::Cycle(CycleOp::Drill(Cycle::G87, Hole::BackBore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        880,
        GOp::Cycle(CycleOp::Drill(Cycle::G88, Hole::BoreManual)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(
        890,
        GOp::Cycle(CycleOp::Drill(Cycle::G89, Hole::BoreDwell)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS),
    g(900, GOp::Mode(ModeOp::Absolute), Group::Distance),
    g(910, GOp::Mode(ModeOp::Incremental), Group::Distance),
    g(920, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(940, GOp::Mode(ModeOp::PerMinute), Group::FeedMode),
    g(950, GOp::Mode(ModeOp::PerRev), Group::FeedMode),
    g(960, GOp::Mode(ModeOp::SurfaceSpeed), Group::SpindleMode),
    g(970, GOp::Mode(ModeOp::SpindleRpm), Group::SpindleMode),
    g(1340, GOp::Cycle(CycleOp::PatternCircle), Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_axes(),
    g(1350, GOp::Cycle(CycleOp::PatternLine), Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_axes(),
    g(1360, GOp::Cycle(CycleOp::PatternArc), Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K') | bit(b'P'))
        .claims_axes(),
    g(1371, GOp::Cycle(CycleOp::PatternGrid), Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K') | bit(b'P'))
        .claims_axes(),
    g(980, GOp::Mode(ModeOp::ReturnInitial), Group::ReturnLevel),
    g(990, GOp::Mode(ModeOp::ReturnR), Group::ReturnLevel),
];

/// Every letter (the arguments of G65/G66).
pub(super) const ALL_LETTERS: u32 = (1 << 26) - 1;

/// Syntec 900M: inch/metric are G70/G71 (manual 1.1, 1.2.29).
const SYNTEC_UNITS: &[GRow] = &[
    g(700, GOp::Mode(ModeOp::Inch), Group::Units),
    g(710, GOp::Mode(ModeOp::Metric), Group::Units),
];

/// Fanuc's codes beyond the shared mill rows, which Haas also reads.
const FANUC_G: &[GRow] = &[
    // G08 P1/P0: AI look-ahead control (Fanuc 0i-MD/MF: "look-ahead
    // acceleration/deceleration before interpolation"), a planner mode.
    g(80, GOp::Pace(PaceOp::LookAhead), Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
];

/// Fanuc 0i: inch/metric are G20/G21.
const FANUC_UNITS: &[GRow] = &[
    g(200, GOp::Mode(ModeOp::Inch), Group::Units),
    g(210, GOp::Mode(ModeOp::Metric), Group::Units),
];

const MILL_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: true,
    fullwidth_semicolon: true,
    extended: Extended::NONE,
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
    paren_in_comment_alarms: false,
};

/// Codes of the Syntec G-code list (manual 1.1) that later work will run.
const SYNTEC_LATER: &[(u16, &str)] = &[];

/// The words of Haas's G12/G13: radii I, K and the step Q, the cutter's
/// D, the repeats L.
const CIRCLE_CUT_WORDS: u32 = bit(b'I') | bit(b'K') | bit(b'Q') | bit(b'D') | bit(b'L');

/// Haas's codes beyond Fanuc's that its programs use (Haas mill operator's
/// manual, G- and M-code chapters).
const HAAS_G: &[GRow] = &[
    // G187 P1–P3 (rough, medium, finish) E corner tolerance: a setting for
    // the planner.
    g(1870, GOp::Pace(PaceOp::Smoothing), Group::NonModal).reads(bit(b'P') | bit(b'E')),
    // G12/G13 circular pocket milling: I, K, Q radii, D, L repeats, Z
    // depth (`codes/circle_cut.rs`).
    g(
        120,
        GOp::Cycle(CycleOp::CircleCut(ArcDir::Cw, CircleCutForm::Spiral)),
        Group::NonModal,
    )
    .reads(CIRCLE_CUT_WORDS)
    .claims_axes(),
    g(
        130,
        GOp::Cycle(CycleOp::CircleCut(ArcDir::Ccw, CircleCutForm::Spiral)),
        Group::NonModal,
    )
    .reads(CIRCLE_CUT_WORDS)
    .claims_axes(),
    // The cycles repeat by L; G73/G83 also peck by I, J, K.
    g(
        730,
        GOp::Cycle(CycleOp::Drill(Cycle::G73, Hole::HighSpeedPeck)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L | HAAS_PECK_WORDS),
    g(
        740,
        GOp::Cycle(CycleOp::Drill(Cycle::G74, Hole::LeftTap)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        760,
        GOp::Cycle(CycleOp::Drill(Cycle::G76, Hole::FineBore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        810,
        GOp::Cycle(CycleOp::Drill(Cycle::G81, Hole::Drill)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        820,
        GOp::Cycle(CycleOp::Drill(Cycle::G82, Hole::DrillDwell)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        830,
        GOp::Cycle(CycleOp::Drill(Cycle::G83, Hole::DeepPeck)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L | HAAS_PECK_WORDS),
    g(
        840,
        GOp::Cycle(CycleOp::Drill(Cycle::G84, Hole::Tap)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        850,
        GOp::Cycle(CycleOp::Drill(Cycle::G85, Hole::Bore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        860,
        GOp::Cycle(CycleOp::Drill(Cycle::G86, Hole::BoreStop)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        870,
        GOp::Cycle(CycleOp::Drill(Cycle::G87, Hole::BackBore)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        880,
        GOp::Cycle(CycleOp::Drill(Cycle::G88, Hole::BoreManual)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        890,
        GOp::Cycle(CycleOp::Drill(Cycle::G89, Hole::BoreDwell)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
];

/// Haas M codes with a controller meaning (the machine builder's others
/// are in `default_haas.toml`'s `[m_codes]`): M16 changes the tool, M97
/// calls a local subprogram.
const HAAS_M: &[MRow] = &[
    m(16, MOp::ToolChange),
    m(97, MOp::LocalCall).reads(bit(b'P') | bit(b'L')),
];

fn mill(name: &'static str, units: &'static [GRow]) -> Dialect {
    let (g, m) = Dialect::tables(&[MILL_G, units], m_codes::MILL);
    Dialect {
        name,
        lex: MILL_LEX,
        g,
        m,
        incremental_words: &[],
        diameter: Diameter {
            axis: None,
            at_power_on: false,
            lathe: false,
        },
        integers: IntegerWords::LeastIncrement,
        plane: Plane::Xy,
        long_chord: LongChord::Alarm,
        arc_end: super::ArcEnd::MachineTolerance,
        o_in_flow: super::OInFlow::EndsProgram,
        arc_letters: 0,
        default_machine: DEFAULT_MILL_TOML,
        unsupported: SYNTEC_LATER,
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::FANUC,
        bare_return: BareReturn::NeedsAxes,
        g10: G10Rules::FANUC,
        program_stop: ProgramStop::StopsSpindleAndCoolant,
        tool_length_change: ToolLengthChange::MovesNow,
        offset_default: OffsetDefault::Modal,
        macros: super::MacroRules::FANUC,
        feed_at_power_on: FeedAtPowerOn::PerMinute,
        surface_speed: SurfaceSpeedOn::ToolDiameter,
        tool_words: ToolWords::Select,
        dwell_p: DwellP::WholeMilliseconds,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        tip_numbering: vcnc_core::tooling::TipNumbering::Fanuc,
        g53_incremental: super::G53Incremental::Ignored,
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        gcode_systems: false,
        polar_words: false,
    }
}

/// Syntec's M198: a subprogram call like M98 (its MACRO manual §2.3; the
/// controller re-reads the file, which vcnc always does).
const SYNTEC_M: &[MRow] = &[m(198, MOp::Call).reads(bit(b'P') | bit(b'H') | bit(b'L'))];

/// Syntec 900M mill.
pub(super) fn syntec() -> Dialect {
    let rows: Vec<&[MRow]> = m_codes::MILL.iter().copied().chain([SYNTEC_M]).collect();
    let (g, m) = Dialect::tables(&[MILL_G, SYNTEC_UNITS], &rows);
    Dialect {
        g,
        m,
        macros: super::MacroRules::SYNTEC,
        thread_lead: ThreadLead::FHundredths,
        g53_incremental: super::G53Incremental::Alarm,
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        gcode_systems: false,
        polar_words: false,
        ..mill("syntec", SYNTEC_UNITS)
    }
}

/// Fanuc's lexing: the mill's, and `:` for the program number's O (ISO
/// code; Fanuc 0i operator's manual, program number: "In ISO code, a
/// colon (:) can be used instead of O"). Haas's too.
/// Fanuc 0i-MF and Haas mills: `:` is the ISO program number's O, and
/// `,C`/`,R` chamfer or round the corner at a G01's end (0i-MF "optional
/// chamfering and corner R", Haas mill "corner rounding and chamfering").
const FANUC_LEX: LexRules = LexRules {
    colon_is_o: true,
    paren_in_comment_alarms: false,
    extended: Extended::new(&[(",C", Addr::COMMA_C), (",R", Addr::COMMA_R)]),
    ..MILL_LEX
};

/// Fanuc 0i mill.
pub(super) fn fanuc() -> Dialect {
    let rows: Vec<&[MRow]> = m_codes::MILL
        .iter()
        .copied()
        .chain([m_codes::RIGID_TAP])
        .collect();
    let (g, m) = Dialect::tables(&[MILL_G, FANUC_UNITS, FANUC_G], &rows);
    Dialect {
        lex: FANUC_LEX,
        g,
        m,
        ..mill("fanuc", FANUC_UNITS)
    }
}

/// Haas mills: Fanuc plus G187, M97 local subprograms, M16, G28 without
/// axes homing every axis, and the Haas machine's M codes.
pub(super) fn haas() -> Dialect {
    let rows: Vec<&[MRow]> = m_codes::MILL
        .iter()
        .copied()
        .chain([m_codes::RIGID_TAP, HAAS_M])
        .collect();
    let (g, m) = Dialect::tables(&[MILL_G, FANUC_UNITS, FANUC_G, HAAS_G], &rows);
    Dialect {
        name: "haas",
        g,
        m,
        default_machine: vcnc_core::machine::DEFAULT_HAAS_TOML,
        bare_return: BareReturn::AllAxes,
        cycles: CycleRules::HAAS,
        dwell_p: DwellP::SecondsWithPoint,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        tip_numbering: vcnc_core::tooling::TipNumbering::Fanuc,
        macros: super::MacroRules::HAAS,
        ..fanuc()
    }
}
