//! The Fanuc 0i-TF lathe dialect (G-code system A), which Haas lathes also
//! run: another profile of the same engine, with the numbers a Fanuc lathe
//! gives its codes.
//!
//! ```text
//!   code   mill (fanuc)            fanuc-lathe (system A)
//!   G50    scaling off             coordinate setting / spindle clamp (S)
//!   G70–G76 —, canned drilling      multiple repetitive cycles (two blocks)
//!   G90    absolute                turning cycle (modal, group 01)
//!   G92    coordinate setting      threading cycle (modal, group 01)
//!   G94    feed per minute         facing cycle (modal, group 01)
//!   G98/G99 cycle return level     feed per minute / per revolution
//! ```
//!
//! There is no G90/G91: X/Z are absolute and U/W incremental in every
//! block. X is a diameter (events keep the radius), G18 and G99 are on at
//! power-on, a T word indexes the turret and applies an offset (`T0101`),
//! G96 keeps the surface speed on the work diameter under the tool.
//! Decisions are in `docs/dialects.md` (the Fanuc lathe).

use super::{
    AxisWords, BareReturn, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp,
    GRow, Group, IntegerWords, LongChord, OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn,
    ThreadLead, ToolChangeSpindle, ToolLengthChange, ToolWords, bit, g,
};
use super::{
    CompOp, CycleOp, FlowOp, ModeOp, MotionOp, MoveOp, PaceOp, SetOp, TurnOp,
    m_codes::{self, MRow},
};
use vcnc_core::events::Plane;
use vcnc_core::machine::{DEFAULT_FANUC_LATHE_TOML, GcodeSystem};
use vcnc_syntax::{Addr, Extended, LexRules, Semicolon};

/// Words of the multiple repetitive cycles besides the axis words they
/// claim (U and W are their parameters too): P, Q, R and Haas's D (the
/// depth of cut of its one-block G71/G72).
const MRC: u32 = bit(b'P') | bit(b'Q') | bit(b'R');

/// The one-block (FS15 tape format, Haas) G74/G75 words: I and K for the
/// two-block P and Q, D for its relief R.
const ONE_BLOCK_PECK: u32 = bit(b'I') | bit(b'K') | bit(b'D');

/// The one-block G76 words: K the thread height, D the first depth, I the
/// taper, A the tool angle.
const ONE_BLOCK_THREAD: u32 = bit(b'K') | bit(b'D') | bit(b'I') | bit(b'A');

const FANUC_LATHE_G: &[GRow] = &[
    // Custom Macro B calls, as on the mill: every letter is an argument.
    g(650, GOp::Flow(FlowOp::MacroCall), Group::NonModal)
        .reads(super::mill::ALL_LETTERS)
        .refuses_axes(),
    g(660, GOp::Flow(FlowOp::MacroModal), Group::MacroModal)
        .reads(super::mill::ALL_LETTERS)
        .refuses_axes(),
    g(670, GOp::Flow(FlowOp::MacroModalCancel), Group::MacroModal),
    g(0, GOp::Motion(MotionOp::Rapid), Group::Motion),
    g(10, GOp::Motion(MotionOp::Linear), Group::Motion),
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion),
    // G04 X/U seconds (milliseconds without a point), P milliseconds.
    g(40, GOp::Pace(PaceOp::Dwell), Group::NonModal)
        .reads(bit(b'P') | bit(b'X') | bit(b'U'))
        .refuses_axes(),
    g(180, GOp::Mode(ModeOp::PlaneZx), Group::Plane),
    g(280, GOp::Move(MoveOp::RefReturn), Group::NonModal).claims_axes(),
    g(300, GOp::Move(MoveOp::RefReturnN), Group::NonModal)
        .reads(bit(b'P'))
        .claims_axes(),
    g(400, GOp::Comp(CompOp::Cancel), Group::CutterComp),
    g(410, GOp::Comp(CompOp::Left), Group::CutterComp),
    g(420, GOp::Comp(CompOp::Right), Group::CutterComp),
    g(530, GOp::Move(MoveOp::MachineCoords), Group::NonModal).claims_absolute_axes(),
    g(540, GOp::Mode(ModeOp::WorkSystem(0)), Group::Wcs),
    g(550, GOp::Mode(ModeOp::WorkSystem(1)), Group::Wcs),
    g(560, GOp::Mode(ModeOp::WorkSystem(2)), Group::Wcs),
    g(570, GOp::Mode(ModeOp::WorkSystem(3)), Group::Wcs),
    g(580, GOp::Mode(ModeOp::WorkSystem(4)), Group::Wcs),
    g(590, GOp::Mode(ModeOp::WorkSystem(5)), Group::Wcs),
    g(800, GOp::Cycle(CycleOp::Cancel), Group::Cycle),
    g(960, GOp::Mode(ModeOp::SurfaceSpeed), Group::SpindleMode),
    g(970, GOp::Mode(ModeOp::SpindleRpm), Group::SpindleMode),
];

/// The multiple repetitive cycles (finishing, rough turning, rough facing,
/// pattern repeating, face peck, grooving, threading), numbered from
/// `first`: G70–G76 in systems A and B, G72–G78 in system C.
const fn repetitive_cycles(first: u16) -> [GRow; 7] {
    [
        g(first, GOp::Turn(TurnOp::FinishCycle), Group::NonModal)
            .reads(bit(b'P') | bit(b'Q'))
            .claims_axes(),
        g(
            first + 10,
            GOp::Turn(TurnOp::RoughTurnCycle),
            Group::NonModal,
        )
        .reads(MRC | bit(b'D'))
        .claims_axes(),
        g(
            first + 20,
            GOp::Turn(TurnOp::RoughFaceCycle),
            Group::NonModal,
        )
        .reads(MRC | bit(b'D'))
        .claims_axes(),
        g(first + 30, GOp::Turn(TurnOp::PatternCycle), Group::NonModal)
            .reads(MRC)
            .claims_axes(),
        g(
            first + 40,
            GOp::Turn(TurnOp::FacePeckCycle),
            Group::NonModal,
        )
        .reads(MRC | ONE_BLOCK_PECK)
        .claims_axes(),
        g(first + 50, GOp::Turn(TurnOp::GrooveCycle), Group::NonModal)
            .reads(MRC | ONE_BLOCK_PECK)
            .claims_axes(),
        // G76's F is the lead, not a feed.
        g(
            first + 60,
            GOp::Turn(TurnOp::ThreadMultiCycle),
            Group::NonModal,
        )
        .reads(MRC | ONE_BLOCK_THREAD | bit(b'F'))
        .claims_axes(),
    ]
}

/// System A's own rows (0i-TF "G code list", column A): G32 threading,
/// the single cycles
/// at G90/G92/G94, G50 coordinate setting, G98/G99 feed per minute and per
/// revolution; G20/G21 units; G70–G76.
const SYSTEM_A: &[GRow] = &[
    // G32: lead F in program units (mm or inch), like the mill's G33.
    g(320, GOp::Motion(MotionOp::Thread), Group::Motion),
    g(200, GOp::Mode(ModeOp::Inch), Group::Units),
    g(210, GOp::Mode(ModeOp::Metric), Group::Units),
    g(500, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(900, GOp::Motion(MotionOp::TurnCycle), Group::Motion),
    g(920, GOp::Motion(MotionOp::ThreadingCycle), Group::Motion),
    g(940, GOp::Motion(MotionOp::FaceCycle), Group::Motion),
    g(980, GOp::Mode(ModeOp::PerMinute), Group::FeedMode),
    g(990, GOp::Mode(ModeOp::PerRev), Group::FeedMode),
];

const CYCLES_AB: [GRow; 7] = repetitive_cycles(700);
const CYCLES_C: [GRow; 7] = repetitive_cycles(720);

/// Systems B and C alike (columns B and C): G33 threading (A's G32),
/// G90/G91 absolute and
/// incremental, G92 coordinate setting and spindle clamp, G94/G95 feed per
/// minute and per revolution, G98/G99 the drilling cycles' return level.
const SYSTEM_B_AND_C: &[GRow] = &[
    g(330, GOp::Motion(MotionOp::Thread), Group::Motion),
    g(900, GOp::Mode(ModeOp::Absolute), Group::Distance),
    g(910, GOp::Mode(ModeOp::Incremental), Group::Distance),
    g(920, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(940, GOp::Mode(ModeOp::PerMinute), Group::FeedMode),
    g(950, GOp::Mode(ModeOp::PerRev), Group::FeedMode),
    g(980, GOp::Mode(ModeOp::ReturnInitial), Group::ReturnLevel),
    g(990, GOp::Mode(ModeOp::ReturnR), Group::ReturnLevel),
];

/// System B: G20/G21 units, G70–G76, and the single cycles at G77/G78/G79.
const SYSTEM_B: &[GRow] = &[
    g(200, GOp::Mode(ModeOp::Inch), Group::Units),
    g(210, GOp::Mode(ModeOp::Metric), Group::Units),
    g(770, GOp::Motion(MotionOp::TurnCycle), Group::Motion),
    g(780, GOp::Motion(MotionOp::ThreadingCycle), Group::Motion),
    g(790, GOp::Motion(MotionOp::FaceCycle), Group::Motion),
];

/// System C: the single cycles at G20/G21/G24, G70/G71 inch and mm, the
/// multiple repetitive cycles at G72–G78.
const SYSTEM_C: &[GRow] = &[
    g(200, GOp::Motion(MotionOp::TurnCycle), Group::Motion),
    g(210, GOp::Motion(MotionOp::ThreadingCycle), Group::Motion),
    g(240, GOp::Motion(MotionOp::FaceCycle), Group::Motion),
    g(700, GOp::Mode(ModeOp::Inch), Group::Units),
    g(710, GOp::Mode(ModeOp::Metric), Group::Units),
];

/// The rows of `system`.
fn system_rows(system: GcodeSystem) -> [&'static [GRow]; 4] {
    match system {
        GcodeSystem::A => [FANUC_LATHE_G, SYSTEM_A, &CYCLES_AB, &[]],
        GcodeSystem::B => [FANUC_LATHE_G, SYSTEM_B_AND_C, SYSTEM_B, &CYCLES_AB],
        GcodeSystem::C => [FANUC_LATHE_G, SYSTEM_B_AND_C, SYSTEM_C, &CYCLES_C],
    }
}

/// Fanuc lathe M codes: the mill's without M06 (a T word indexes the
/// turret) and without M19 (spindle orientation is the builder's).
const FANUC_LATHE_M: &[&[MRow]] = &[
    m_codes::PROGRAM_END,
    m_codes::SPINDLE,
    m_codes::COOLANT,
    m_codes::SUBPROGRAMS,
];

/// `;` ends a block (Fanuc's EOB); `,C`/`,R` are chamfer and corner R; `:`
/// is the program number's O (ISO code), as on the mill.
const FANUC_LATHE_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: false,
    fullwidth_semicolon: false,
    extended: Extended::new(&[(",C", Addr::COMMA_C), (",R", Addr::COMMA_R)]),
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: true,
    paren_in_comment_alarms: false,
};

/// Codes of the 0i-TF list vcnc does not run, and why (E201 quotes it).
const NOT_RUN: &[(u16, &str)] = &[
    (
        170,
        "G17 selects the XY plane for live tooling (a Y or C axis), which this lathe dialect does not run",
    ),
    (
        190,
        "G19 selects the YZ plane for live tooling (a Y or C axis), which this lathe dialect does not run",
    ),
    (
        830,
        "G83 (live-tool face drilling) is not run by this lathe dialect: use G74 for peck drilling on the spindle axis",
    ),
    (
        840,
        "G84 (live-tool face tapping) is not run by this lathe dialect",
    ),
    (
        1120,
        "G112 polar coordinate interpolation (C axis) is not run by this lathe dialect",
    ),
];

/// The Fanuc lathe dialect in G-code system A (the default).
pub(super) fn fanuc_lathe() -> Dialect {
    fanuc_lathe_in(GcodeSystem::A)
}

/// The Fanuc lathe dialect with the code numbers of `system` (the machine
/// file's `gcode_system`).
pub(super) fn fanuc_lathe_in(system: GcodeSystem) -> Dialect {
    let rows = system_rows(system);
    let (g, m) = Dialect::tables(&rows, FANUC_LATHE_M);
    debug_assert!(
        rows.iter()
            .flat_map(|r| r.iter())
            .all(|r| r.def.group != Group::Motion || r.def.axes == AxisWords::Free)
    );
    Dialect {
        name: "fanuc-lathe",
        lex: FANUC_LATHE_LEX,
        g,
        m,
        incremental_words: &[(b'U', b'X'), (b'W', b'Z')],
        diameter: Diameter {
            axis: Some(b'X'),
            at_power_on: true,
            lathe: true,
        },
        integers: IntegerWords::LeastIncrement,
        plane: Plane::Zx,
        long_chord: LongChord::Alarm,
        arc_end: super::ArcEnd::MachineTolerance,
        o_in_flow: super::OInFlow::EndsProgram,
        arc_letters: 0,
        default_machine: DEFAULT_FANUC_LATHE_TOML,
        unsupported: NOT_RUN,
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::FANUC,
        // Haas lathes send every axis home on a bare G28.
        bare_return: BareReturn::AllAxes,
        g10: G10Rules::FANUC,
        program_stop: ProgramStop::StopsSpindleAndCoolant,
        // A T word's offset applies at the next move.
        tool_length_change: ToolLengthChange::AtNextMove,
        offset_default: OffsetDefault::Modal,
        feed_at_power_on: FeedAtPowerOn::PerRevolution,
        surface_speed: SurfaceSpeedOn::WorkDiameter,
        tool_words: ToolWords::TurretOffset,
        dwell_p: DwellP::WholeMilliseconds,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        tip_numbering: vcnc_core::tooling::TipNumbering::Fanuc,
        g53_incremental: super::G53Incremental::Ignored,
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        gcode_systems: true,
        polar_words: false,
        macros: super::MacroRules::FANUC,
    }
}

/// Haas's own rows over the Fanuc lathe's: its G70 takes U, W and D beside
/// P and Q and ignores them. Haas's G70 page lists P and Q only, but a
/// shop's programs that ran on Haas lathes copy the G71 line's
/// `U… W… D…` into G70 (`corpus/lathe-haas/cadekiely-*`); the finishing
/// pass follows the profile as written.
const HAAS_LATHE_G: &[GRow] = &[g(700, GOp::Turn(TurnOp::FinishCycle), Group::NonModal)
    .reads(bit(b'P') | bit(b'Q') | bit(b'U') | bit(b'W') | bit(b'D'))
    .claims_axes()];

/// Haas lathes: the Fanuc 0i-TF reading (Haas's one-block G71/G72 and
/// G74–G76 are read there too) with the Haas rules the mill has: `G04 P3.`
/// is 3 s, and the tool-life variables #5401–#6000 exist (Haas lathe
/// operator's manual, G04 and macro variables).
pub(super) fn haas_lathe() -> Dialect {
    let [common, own, cycles, _] = system_rows(GcodeSystem::A);
    let (g, m) = Dialect::tables(&[common, own, cycles, HAAS_LATHE_G], FANUC_LATHE_M);
    Dialect {
        name: "haas-lathe",
        g,
        m,
        dwell_p: DwellP::SecondsWithPoint,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        tip_numbering: vcnc_core::tooling::TipNumbering::Fanuc,
        g53_incremental: super::G53Incremental::Ignored,
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        // Haas lathes run system A only.
        gcode_systems: false,
        polar_words: false,
        macros: super::MacroRules::HAAS,
        ..fanuc_lathe()
    }
}
