//! LinuxCNC's RS274/NGC (2.9), the mill interpreter as its G-code
//! reference describes it, for the programs its CAM posts write (FreeCAD,
//! Fusion 360's LinuxCNC post, pcb2gcode, SheetCam): grbl's reading (`;`
//! comments, integers in whole units, G90.1/G91.1, probes, G10 L2/L20,
//! G28.1/G30.1, G43.1, G92.1, G93) with the codes grbl lacks — tool length
//! from the tool table (G43 without H takes the tool in the spindle), cutter
//! compensation (D is a tool number; without D the tool in the spindle),
//! the canned cycles G73, G74 and G81–G86, G89 repeated by L with the dwell P in
//! seconds, G52, G59.1–G59.3, G61.1, G64 P Q, G96/G97, G98/G99 — and the
//! tool table written by `G10 L1 P Z R`.
//!
//! Not read (E201 says why): the O-word subprograms and flow control and
//! named parameters, lathe mode (G7/G8, G76, G33.1), splines (G5, G5.1,
//! G5.2) and the UVW planes.

use super::{
    BareReturn, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp, GRow, Group,
    IntegerWords, LongChord, MGroup, MOp, MRow, OffsetDefault, ProgramStop, RapidPath,
    SurfaceSpeedOn, ToolLengthChange, ToolWords, bit, g,
};
use crate::events::{Cycle, Plane};
use crate::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{LexRules, Semicolon};

/// LinuxCNC's canned-cycle words: R level, Q peck, P dwell (seconds), L
/// repeats.
const LCNC_CYCLE_WORDS: u32 = bit(b'R') | bit(b'Q') | bit(b'P') | bit(b'L');

const LINUXCNC_G: &[GRow] = &[
    g(0, GOp::Rapid, Group::Motion),
    g(10, GOp::Linear, Group::Motion),
    g(20, GOp::ArcCw, Group::Motion),
    g(30, GOp::ArcCcw, Group::Motion),
    // G4 P is seconds (`P2` 2 s, `P0.5` half a second).
    g(40, GOp::DwellP, Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    // L1 (tool table: P tool, R radius, Z length), L2/L20 (work offsets).
    g(100, GOp::SetData, Group::NonModal)
        .reads(bit(b'L') | bit(b'P') | bit(b'R'))
        .claims_absolute_axes(),
    g(170, GOp::PlaneXy, Group::Plane),
    g(180, GOp::PlaneZx, Group::Plane),
    g(190, GOp::PlaneYz, Group::Plane),
    g(200, GOp::Inch, Group::Units),
    g(210, GOp::Metric, Group::Units),
    g(280, GOp::RefReturn, Group::NonModal).claims_axes(),
    g(281, GOp::RefStore(1), Group::NonModal),
    g(300, GOp::RefReturnN, Group::NonModal).claims_axes(),
    g(301, GOp::RefStore(2), Group::NonModal),
    g(382, GOp::Probe { must_trip: true }, Group::NonModal).claims_axes(),
    g(383, GOp::Probe { must_trip: false }, Group::NonModal).claims_axes(),
    g(384, GOp::Probe { must_trip: true }, Group::NonModal).claims_axes(),
    g(385, GOp::Probe { must_trip: false }, Group::NonModal).claims_axes(),
    g(400, GOp::CompCancel, Group::CutterComp),
    g(410, GOp::CompLeft, Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::CompRight, Group::CutterComp).reads(bit(b'D')),
    g(430, GOp::ToolLengthPlus, Group::ToolLength).reads(bit(b'H')),
    g(431, GOp::ToolLengthDynamic, Group::ToolLength).claims_absolute_axes(),
    g(490, GOp::ToolLengthCancel, Group::ToolLength),
    g(520, GOp::LocalSystem, Group::NonModal).claims_absolute_axes(),
    g(530, GOp::MachineCoords, Group::NonModal).claims_absolute_axes(),
    g(540, GOp::WorkSystem(0), Group::Wcs),
    g(550, GOp::WorkSystem(1), Group::Wcs),
    g(560, GOp::WorkSystem(2), Group::Wcs),
    g(570, GOp::WorkSystem(3), Group::Wcs),
    g(580, GOp::WorkSystem(4), Group::Wcs),
    g(590, GOp::WorkSystem(5), Group::Wcs),
    g(591, GOp::WorkSystem(6), Group::Wcs),
    g(592, GOp::WorkSystem(7), Group::Wcs),
    g(593, GOp::WorkSystem(8), Group::Wcs),
    // G61 and G61.1 (exact path, exact stop) both stop at every block end.
    g(610, GOp::PathExact, Group::Path),
    g(611, GOp::PathExact, Group::Path),
    // The blending tolerances P (path) and Q (naive CAM): accepted, the
    // planner blends with the machine's corner tolerance.
    g(640, GOp::PathCutting, Group::Path).reads(bit(b'P') | bit(b'Q')),
    g(730, GOp::Cycle(Cycle::G73), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(740, GOp::Cycle(Cycle::G74), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(800, GOp::CycleCancel, Group::Cycle),
    g(810, GOp::Cycle(Cycle::G81), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(820, GOp::Cycle(Cycle::G82), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(830, GOp::Cycle(Cycle::G83), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(840, GOp::Cycle(Cycle::G84), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(850, GOp::Cycle(Cycle::G85), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(860, GOp::Cycle(Cycle::G86), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(890, GOp::Cycle(Cycle::G89), Group::Cycle).reads(LCNC_CYCLE_WORDS),
    g(900, GOp::Absolute, Group::Distance),
    g(901, GOp::ArcCentersAbsolute, Group::ArcDistance),
    g(910, GOp::Incremental, Group::Distance),
    g(911, GOp::ArcCentersIncremental, Group::ArcDistance),
    g(920, GOp::PresetOrClamp, Group::NonModal).claims_absolute_axes(),
    g(921, GOp::ShiftCancel, Group::NonModal),
    g(930, GOp::InverseTime, Group::FeedMode),
    g(940, GOp::PerMinute, Group::FeedMode),
    g(950, GOp::PerRev, Group::FeedMode),
    g(960, GOp::SurfaceSpeed, Group::SpindleMode),
    g(970, GOp::SpindleRpm, Group::SpindleMode),
    g(980, GOp::ReturnInitial, Group::ReturnLevel),
    g(990, GOp::ReturnR, Group::ReturnLevel),
];

/// LinuxCNC's M codes that vcnc runs. M60 (pallet change pause) stops like
/// M00.
const LINUXCNC_M: &[MRow] = &[
    (0, MOp::Stop, MGroup::Flow, 0),
    (1, MOp::OptionalStop, MGroup::Flow, 0),
    (2, MOp::End, MGroup::Flow, 0),
    (3, MOp::SpindleCw, MGroup::Spindle, 0),
    (4, MOp::SpindleCcw, MGroup::Spindle, 0),
    (5, MOp::SpindleStop, MGroup::Spindle, 0),
    (6, MOp::ToolChange, MGroup::Tool, 0),
    (7, MOp::CoolantOn, MGroup::Coolant, 0),
    (8, MOp::CoolantOn, MGroup::Coolant, 0),
    (9, MOp::CoolantOff, MGroup::Coolant, 0),
    (19, MOp::SpindleOrient, MGroup::Spindle, 0),
    (30, MOp::EndRewind, MGroup::Flow, 0),
    (60, MOp::Stop, MGroup::Flow, 0),
];

/// LinuxCNC codes vcnc does not run, and why.
const NOT_RUN: &[(u16, &str)] = &[
    (50, "LinuxCNC's cubic spline G5 is not run by vcnc"),
    (51, "LinuxCNC's quadratic B-spline G5.1 is not run by vcnc"),
    (52, "LinuxCNC's NURBS block G5.2/G5.3 is not run by vcnc"),
    (
        70,
        "lathe diameter mode: use --dialect fanuc-lathe for lathe programs",
    ),
    (
        80,
        "lathe radius mode: use --dialect fanuc-lathe for lathe programs",
    ),
    (171, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (181, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (191, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (
        330,
        "LinuxCNC's spindle-synchronized G33 (K pitch) is not run by vcnc",
    ),
    (331, "LinuxCNC's rigid tapping G33.1 is not run by vcnc"),
    (
        411,
        "dynamic cutter compensation G41.1/G42.1 is not run by vcnc",
    ),
    (
        421,
        "dynamic cutter compensation G41.1/G42.1 is not run by vcnc",
    ),
    (
        432,
        "G43.2 (an added tool length offset) is not run by vcnc",
    ),
    (
        700,
        "LinuxCNC's lathe finishing cycle G70 is not run by vcnc",
    ),
    (
        710,
        "LinuxCNC's lathe roughing cycle G71 is not run by vcnc",
    ),
    (
        720,
        "LinuxCNC's lathe roughing cycle G72 is not run by vcnc",
    ),
    (
        760,
        "LinuxCNC's lathe threading cycle G76 is not run by vcnc",
    ),
    (
        870,
        "LinuxCNC's back boring G87 (I, J, K offsets) is not run by vcnc",
    ),
    (
        880,
        "LinuxCNC's G88 (stop for a manual retract) is not run by vcnc",
    ),
    (922, "G92.2 (suspend the G92 offset) is not run by vcnc"),
    (923, "G92.3 (restore the G92 offset) is not run by vcnc"),
];

/// `;` starts a comment, as in grbl.
const LINUXCNC_LEX: LexRules = LexRules {
    semicolon: Semicolon::Comment,
    slash_comments: false,
    fullwidth_semicolon: false,
    extended: &[],
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
};

/// The LinuxCNC dialect.
pub(super) fn linuxcnc() -> Dialect {
    let (g, m) = Dialect::tables(&[LINUXCNC_G], LINUXCNC_M);
    Dialect {
        name: "linuxcnc",
        lex: LINUXCNC_LEX,
        g,
        m,
        incremental_words: &[],
        diameter: Diameter {
            axis: None,
            at_power_on: false,
        },
        // `X5` is 5 mm, `P2` 2 s.
        integers: IntegerWords::WholeUnits,
        plane: Plane::Xy,
        long_chord: LongChord::Alarm,
        arc_letters: 0,
        default_machine: DEFAULT_MILL_TOML,
        unsupported: NOT_RUN,
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::LinuxCnc,
        bare_return: BareReturn::AllAxes,
        g10: G10Rules::LinuxCnc,
        program_stop: ProgramStop::Pause,
        tool_length_change: ToolLengthChange::AtNextMove,
        offset_default: OffsetDefault::ToolInSpindle,
        // Numbered parameters and expressions (`#1 = 2`, `X[#1 * 2]`) as
        // their common subset with Custom Macro B.
        macros: super::MacroRules::FANUC,
        feed_at_power_on: FeedAtPowerOn::PerMinute,
        surface_speed: SurfaceSpeedOn::ToolDiameter,
        tool_words: ToolWords::Select,
        dwell_p: DwellP::WholeMilliseconds,
    }
}
