//! LinuxCNC's RS274/NGC (2.9), the mill interpreter as its G-code
//! reference describes it, for the programs its CAM posts write (FreeCAD,
//! Fusion 360's LinuxCNC post, pcb2gcode, SheetCam): grbl's reading (`;`
//! comments, integers in whole units, G90.1/G91.1, probes, G10 L2/L20,
//! G28.1/G30.1, G43.1, G92.1, G93) with the codes grbl lacks — tool length
//! from the tool table (G43 without H takes the tool in the spindle), cutter
//! compensation (D is a tool number; without D the tool in the spindle),
//! the canned cycles G73, G74 and G81–G86, G89 repeated by L with the dwell
//! P in seconds and LinuxCNC's cycle levels, G52, G59.1–G59.3, G61.1, G64
//! P Q, G92.2/G92.3, G96/G97, G98/G99, an M6 that stops the spindle, the tool table
//! written by `G10 L1 P Z R` and the machine's own M codes (M62–M68,
//! M100–M199) — as `docs/dialects.md` lists them.
//!
//! Parameters and expressions are LinuxCNC's own (`macros/ngc.rs`), and
//! so are the O-word subroutines and loops (`macros/exec.rs`). Lathe
//! mode adds G7/G8, the finishing cycle G70, the roughing cycles G71/G72
//! (and .1, .2) and the threading cycle G76. Not read: splines (G5, G5.1, G5.2) and the UVW planes (E201 says why).

use super::grbl::{GRBL_G, GRBL_M, grbl};
use super::{
    AuxM, CYCLE_WORDS_L, CycleRules, Dialect, G10Rules, GOp, GRow, Group, MOp, OffsetDefault,
    ThreadLead, ToolChangeSpindle, bit, g,
};
use super::{
    CompOp, CycleOp, FrameOp, Hole, ModeOp, MotionOp, PaceOp, RoughPockets, SetOp, TurnOp,
    m_codes::{MRow, m},
};
use super::{Diameter, SurfaceSpeedOn};
use vcnc_core::events::{Cycle, Plane};
use vcnc_core::machine::DEFAULT_FANUC_LATHE_TOML;
use vcnc_syntax::{Addr, Extended, LexRules};

/// LinuxCNC's codes beyond grbl's (its rows replace grbl's G10, which
/// reads R here for L1).
pub(super) const LINUXCNC_G: &[GRow] = &[
    // G2/G3 P: the number of turns (rs274's ARC_FEED turns; P1 is the
    // plain arc, more turns are not run: `motion/arc.rs`).
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion).reads(bit(b'P')),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion).reads(bit(b'P')),
    // G4 P seconds; the block's axis words go to its motion, after the
    // dwell (`G4 P0.5 G0 X10`, LinuxCNC's order of execution).
    g(40, GOp::Pace(PaceOp::DwellP), Group::NonModal).reads(bit(b'P')),
    // L1 (tool table: P tool, R radius, Z length), L2/L20 (work offsets).
    g(100, GOp::Set(SetOp::Data), Group::NonModal)
        .reads(bit(b'L') | bit(b'P') | bit(b'R'))
        .claims_absolute_axes(),
    g(410, GOp::Comp(CompOp::Left), Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::Comp(CompOp::Right), Group::CutterComp).reads(bit(b'D')),
    // G41.1/G42.1 D diameter [L orientation]: dynamic compensation.
    g(411, GOp::Comp(CompOp::LeftDiameter), Group::CutterComp).reads(bit(b'D') | bit(b'L')),
    g(421, GOp::Comp(CompOp::RightDiameter), Group::CutterComp).reads(bit(b'D') | bit(b'L')),
    g(430, GOp::Frame(FrameOp::ToolLengthPlus), Group::ToolLength).reads(bit(b'H')),
    g(520, GOp::Set(SetOp::LocalSystem), Group::NonModal).claims_absolute_axes(),
    g(591, GOp::Mode(ModeOp::WorkSystem(6)), Group::Wcs),
    g(592, GOp::Mode(ModeOp::WorkSystem(7)), Group::Wcs),
    g(593, GOp::Mode(ModeOp::WorkSystem(8)), Group::Wcs),
    // G61.1 (exact stop) stops at every block end, as G61 does here.
    g(611, GOp::Mode(ModeOp::PathExact), Group::Path),
    g(
        730,
        GOp::Cycle(CycleOp::Drill(Cycle::G73, Hole::HighSpeedPeck)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    g(
        740,
        GOp::Cycle(CycleOp::Drill(Cycle::G74, Hole::LeftTap)),
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
    .reads(CYCLE_WORDS_L),
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
        890,
        GOp::Cycle(CycleOp::Drill(Cycle::G89, Hole::BoreDwell)),
        Group::Cycle,
    )
    .reads(CYCLE_WORDS_L),
    // G33 X Z K: spindle-synchronized motion, K the distance per turn.
    g(330, GOp::Motion(MotionOp::Thread), Group::Motion).reads(bit(b'K')),
    // G33.1 X Y Z K: rigid tapping, K the pitch.
    g(331, GOp::Motion(MotionOp::RigidTap), Group::Motion).reads(bit(b'K')),
    // G92.2 suspends the G92 shift, keeping its values; G92.3 restores it.
    g(922, GOp::Set(SetOp::ShiftSuspend(false)), Group::NonModal),
    g(923, GOp::Set(SetOp::ShiftSuspend(true)), Group::NonModal),
    g(950, GOp::Mode(ModeOp::PerRev), Group::FeedMode),
    // G96 D S: D the highest spindle speed.
    g(960, GOp::Mode(ModeOp::SurfaceSpeed), Group::SpindleMode).reads(bit(b'D')),
    g(970, GOp::Mode(ModeOp::SpindleRpm), Group::SpindleMode),
    g(980, GOp::Mode(ModeOp::ReturnInitial), Group::ReturnLevel),
    g(990, GOp::Mode(ModeOp::ReturnR), Group::ReturnLevel),
];

/// LinuxCNC's M codes beyond grbl's: M19 orients the spindle (R angle, Q
/// time-out, P direction: read, the angle is not modelled), M60 (pallet
/// change pause) stops like M00.
const LINUXCNC_M: &[MRow] = &[
    m(19, MOp::SpindleOrient).reads(bit(b'R') | bit(b'Q') | bit(b'P')),
    m(60, MOp::Stop),
];

/// LinuxCNC's M codes for the machine's own functions, passed on as `aux`
/// events with their words (its M-code reference).
const LINUXCNC_AUX_M: &[AuxM] = &[
    aux(48, 49, "override switches on (M48) or off (M49)", 0),
    aux(50, 50, "feed override control (P0 off, P1 on)", bit(b'P')),
    aux(
        51,
        51,
        "spindle speed override control (P0 off, P1 on)",
        bit(b'P'),
    ),
    aux(52, 52, "adaptive feed control (P0 off, P1 on)", bit(b'P')),
    aux(53, 53, "feed stop control (P0 off, P1 on)", bit(b'P')),
    aux(62, 62, "digital output P on, with the next move", bit(b'P')),
    aux(
        63,
        63,
        "digital output P off, with the next move",
        bit(b'P'),
    ),
    aux(64, 64, "digital output P on, now", bit(b'P')),
    aux(65, 65, "digital output P off, now", bit(b'P')),
    aux(
        66,
        66,
        "wait on input P (digital) or E (analog), mode L, timeout Q",
        bit(b'P') | bit(b'E') | bit(b'L') | bit(b'Q'),
    ),
    aux(
        67,
        67,
        "analog output E to Q, with the next move",
        bit(b'E') | bit(b'Q'),
    ),
    aux(68, 68, "analog output E to Q, now", bit(b'E') | bit(b'Q')),
    aux(
        100,
        199,
        "a user-defined M code (P and Q its arguments)",
        bit(b'P') | bit(b'Q'),
    ),
];

const fn aux(first: u16, last: u16, what: &'static str, letters: u32) -> AuxM {
    AuxM {
        first,
        last,
        what,
        letters,
    }
}

/// LinuxCNC codes vcnc does not run, and why.
const NOT_RUN: &[(u16, &str)] = &[
    (50, "LinuxCNC's cubic spline G5 is not run by vcnc"),
    (51, "LinuxCNC's quadratic B-spline G5.1 is not run by vcnc"),
    (52, "LinuxCNC's NURBS block G5.2/G5.3 is not run by vcnc"),
    (171, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (181, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (191, "the UVW planes G17.1-G19.1 are not run by vcnc"),
    (
        330,
        "LinuxCNC's spindle-synchronized G33 (K pitch) is not run by vcnc",
    ),
    (
        432,
        "G43.2 (an added tool length offset) is not run by vcnc",
    ),
    (
        700,
        "LinuxCNC's lathe finishing cycle G70 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        710,
        "LinuxCNC's lathe roughing cycle G71 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        711,
        "LinuxCNC's lathe roughing cycle G71.1 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        712,
        "LinuxCNC's lathe roughing cycle G71.2 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        720,
        "LinuxCNC's lathe roughing cycle G72 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        721,
        "LinuxCNC's lathe roughing cycle G72.1 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        722,
        "LinuxCNC's lathe roughing cycle G72.2 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        760,
        "LinuxCNC's lathe threading cycle G76 runs in lathe mode: use --dialect linuxcnc-lathe",
    ),
    (
        870,
        "LinuxCNC's back boring G87 (I, J, K offsets) is not run by vcnc",
    ),
    (
        880,
        "LinuxCNC's G88 (stop for a manual retract) is not run by vcnc",
    ),
];

/// grbl's lexing, and the polar words `@` (distance) and `^` (angle)
/// (LinuxCNC G-code reference, "Polar Coordinates").
/// grbl's reading with the polar words `@` and `^`; rs274 refuses any `(`
/// inside a comment ("Nested comment found").
const LINUXCNC_LEX: LexRules = LexRules {
    extended: Extended::new(&[("@", Addr::AT), ("^", Addr::CARET)]),
    paren_in_comment_alarms: true,
    ..super::grbl::GRBL_LEX
};

/// The LinuxCNC dialect: grbl's reading (`;` comments, whole-unit
/// integers, its codes and rules) with the codes and policies above.
pub(super) fn linuxcnc() -> Dialect {
    let m: Vec<&[MRow]> = GRBL_M.iter().copied().chain([LINUXCNC_M]).collect();
    let (g, m) = Dialect::tables(&[GRBL_G, LINUXCNC_G, LINUXCNC_DIAMETER_G], &m);
    Dialect {
        name: "linuxcnc",
        // G7/G8 on X, in radii at power-on; not a lathe.
        diameter: Diameter {
            axis: Some(b'X'),
            at_power_on: false,
            lathe: false,
        },
        g,
        m,
        unsupported: NOT_RUN,
        cycles: CycleRules::RS274,
        g10: G10Rules::RS274,
        offset_default: OffsetDefault::ToolInSpindle,
        aux_m: LINUXCNC_AUX_M,
        tool_change: ToolChangeSpindle::Stops,
        thread_lead: ThreadLead::K,
        macros: super::MacroRules::NGC,
        arc_end: super::ArcEnd::Rs274,
        g53_without_axes: super::G53WithoutAxes::Alarm,
        // P, the arc's number of turns, also in a modal G2/G3 block.
        arc_letters: bit(b'P'),
        comp_when_on: super::CompWhenOn::Alarm,
        // rs274 starts compensation on an arc too ("entry arc").
        comp_start: super::CompStart::LineOrArc,
        lex: LINUXCNC_LEX,
        polar_words: true,
        ..grbl()
    }
}

/// G7 (X in diameters) and G8 (in radii): lathe mode's, which rs274 runs
/// in a mill program too (`G7 G0 X1` goes to X0.5).
const LINUXCNC_DIAMETER_G: &[GRow] = &[
    g(70, GOp::Mode(ModeOp::DiameterMode), Group::DiameterMode),
    g(80, GOp::Mode(ModeOp::RadiusMode), Group::DiameterMode),
];

/// Lathe mode's cycles.
const LINUXCNC_LATHE_G: &[GRow] = &[
    // G70 Q [X Z D E P]: finishing along the profile of subroutine Q.
    g(700, GOp::Turn(TurnOp::NgcFinishCycle), Group::NonModal)
        .reads(bit(b'Q') | bit(b'D') | bit(b'E') | bit(b'P'))
        .claims_axes(),
    // G71/G72 Q [X Z D I R]: roughing to the profile of subroutine Q
    // (codes/ngc_rough.rs); .1 cuts no pocket, .2 those after the first.
    rough(710, false, RoughPockets::All),
    rough(711, false, RoughPockets::None),
    rough(712, false, RoughPockets::AfterFirst),
    rough(720, true, RoughPockets::All),
    rough(721, true, RoughPockets::None),
    rough(722, true, RoughPockets::AfterFirst),
    // G76 P Z I J K [R Q H E L]: the threading cycle (codes/ngc_thread.rs).
    g(760, GOp::Turn(TurnOp::NgcThreadCycle), Group::NonModal)
        .reads(
            bit(b'P')
                | bit(b'I')
                | bit(b'J')
                | bit(b'K')
                | bit(b'R')
                | bit(b'Q')
                | bit(b'H')
                | bit(b'E')
                | bit(b'L'),
        )
        .claims_axes(),
];

/// A roughing cycle's row: G `code` (× 10) reads Q, D, I, R and its start
/// point X Z.
const fn rough(code: u16, facing: bool, pockets: RoughPockets) -> GRow {
    g(
        code,
        GOp::Turn(TurnOp::NgcRoughCycle { facing, pockets }),
        Group::NonModal,
    )
    .reads(bit(b'Q') | bit(b'D') | bit(b'I') | bit(b'R'))
    .claims_axes()
}

/// LinuxCNC in lathe mode (a lathe configuration: X and Z, the XZ plane,
/// G7/G8): the mill dialect's reading and codes, X in radii until G7, G96
/// on the work diameter, the built-in turning centre.
pub(super) fn linuxcnc_lathe() -> Dialect {
    let m: Vec<&[MRow]> = GRBL_M.iter().copied().chain([LINUXCNC_M]).collect();
    let (g, m) = Dialect::tables(
        &[GRBL_G, LINUXCNC_G, LINUXCNC_DIAMETER_G, LINUXCNC_LATHE_G],
        &m,
    );
    Dialect {
        name: "linuxcnc-lathe",
        g,
        m,
        diameter: Diameter {
            axis: Some(b'X'),
            at_power_on: false,
            lathe: true,
        },
        plane: Plane::Zx,
        default_machine: DEFAULT_FANUC_LATHE_TOML,
        surface_speed: SurfaceSpeedOn::WorkDiameter,
        tip_numbering: vcnc_core::tooling::TipNumbering::LinuxCnc,
        g53_incremental: super::G53Incremental::Alarm,
        // rs274 reads `@`/`^` as X and Y whatever the plane; a lathe has no
        // Y, so the words alarm as not used here.
        polar_words: false,
        ..linuxcnc()
    }
}
