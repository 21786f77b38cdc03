//! Generic EIA-274-D (seed 004, "Preparatory Functions and Codes"): the
//! chapter's codes and nothing else, with the word formats
//! `docs/eia-spec.md` decides (the chapter gives none). A profile of the
//! mill engine: G00 with axis priority, its own reading of the canned
//! cycles, the pockets G78/G79 and G99 as a junction marker.

use super::{
    BareReturn, CYCLE_WORDS, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp,
    GRow, Group, IntegerWords, LongChord, OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn,
    ThreadLead, ToolChangeSpindle, ToolLengthChange, ToolWords, bit, g,
};
use super::{CompOp, CycleOp, Hole, ModeOp, MotionOp, PaceOp, SetOp};
use vcnc_core::events::{Cycle, Plane};
use vcnc_core::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{Extended, LexRules, Semicolon};

/// What a drilling cycle reads (Q and P only where they mean something,
/// but the data words are shared: `CycleRules::words`).
const DRILL: u32 = bit(b'R') | bit(b'Q') | bit(b'P');

/// The pockets' words besides the axes (§6): size I J, corner K, R level,
/// depth per pass Q, finishing allowance P, entry feed E.
const POCKET: u32 =
    bit(b'I') | bit(b'J') | bit(b'K') | bit(b'R') | bit(b'Q') | bit(b'P') | bit(b'E');

const EIA_G: &[GRow] = &[
    g(0, GOp::Motion(MotionOp::Rapid), Group::Motion),
    g(10, GOp::Motion(MotionOp::Linear), Group::Motion),
    g(20, GOp::Motion(MotionOp::ArcCw), Group::Motion),
    g(30, GOp::Motion(MotionOp::ArcCcw), Group::Motion),
    g(40, GOp::Pace(PaceOp::DwellOrWait), Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    g(400, GOp::Comp(CompOp::Cancel), Group::CutterComp),
    g(410, GOp::Comp(CompOp::Left), Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::Comp(CompOp::Right), Group::CutterComp).reads(bit(b'D')),
    g(700, GOp::Mode(ModeOp::Inch), Group::Units),
    g(710, GOp::Mode(ModeOp::Metric), Group::Units),
    g(780, GOp::Cycle(CycleOp::PocketRect), Group::NonModal)
        .reads(POCKET)
        .claims_axes(),
    g(790, GOp::Cycle(CycleOp::PocketCircle), Group::NonModal)
        .reads(POCKET)
        .claims_axes(),
    g(800, GOp::Cycle(CycleOp::Cancel), Group::Cycle),
    g(
        810,
        GOp::Cycle(CycleOp::Drill(Cycle::G81, Hole::Drill)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        820,
        GOp::Cycle(CycleOp::Drill(Cycle::G82, Hole::DrillDwell)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        830,
        GOp::Cycle(CycleOp::Drill(Cycle::G83, Hole::DeepPeck)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        840,
        GOp::Cycle(CycleOp::Drill(Cycle::G84, Hole::TapEitherWay)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        850,
        GOp::Cycle(CycleOp::Drill(Cycle::G85, Hole::Bore)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        860,
        GOp::Cycle(CycleOp::Drill(Cycle::G86, Hole::BoreWaitStart)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        870,
        GOp::Cycle(CycleOp::Drill(Cycle::G87, Hole::ChipBreak)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(
        890,
        GOp::Cycle(CycleOp::Drill(Cycle::G89, Hole::BoreDwell)),
        Group::Cycle,
    )
    .reads(DRILL),
    g(900, GOp::Mode(ModeOp::Absolute), Group::Distance),
    g(910, GOp::Mode(ModeOp::Incremental), Group::Distance),
    g(920, GOp::Set(SetOp::PresetOrClamp), Group::NonModal).claims_absolute_axes(),
    g(990, GOp::Pace(PaceOp::Junction), Group::NonModal),
];

/// RS-274-D reading: no `//` comments, no full-width `；` (Syntec habits).
const EIA_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: false,
    fullwidth_semicolon: false,
    extended: Extended::NONE,
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
    paren_in_comment_alarms: false,
};

/// The EIA-274-D dialect.
pub(super) fn eia() -> Dialect {
    // The drilling words are the shared cycle words without K.
    debug_assert_eq!(DRILL, CYCLE_WORDS & !bit(b'K'));
    let (g, m) = Dialect::tables(&[EIA_G], super::m_codes::MILL);
    Dialect {
        name: "eia",
        lex: EIA_LEX,
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
        unsupported: &[],
        rapid: RapidPath::ZPriority,
        cycles: CycleRules::EIA,
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
