//! Generic EIA-274-D (seed 004, "Preparatory Functions and Codes"): the
//! chapter's codes and nothing else, with the word formats
//! `docs/eia-spec.md` decides (the chapter gives none). A profile of the
//! mill engine: G00 with axis priority, its own reading of the canned
//! cycles, the pockets G78/G79 and G99 as a junction marker.

use super::{
    BareReturn, CYCLE_WORDS, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn, G10Rules, GOp,
    GRow, Group, IntegerWords, LongChord, OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn,
    ThreadLead, ToolChangeSpindle, ToolLengthChange, ToolWords, bit, g, mill::MILL_M,
};
use crate::events::{Cycle, Plane};
use crate::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{LexRules, Semicolon};

/// What a drilling cycle reads (Q and P only where they mean something,
/// but the data words are shared: `CycleRules::words`).
const DRILL: u32 = bit(b'R') | bit(b'Q') | bit(b'P');

/// The pockets' words besides the axes (§6): size I J, corner K, R level,
/// depth per pass Q, finishing allowance P, entry feed E.
const POCKET: u32 =
    bit(b'I') | bit(b'J') | bit(b'K') | bit(b'R') | bit(b'Q') | bit(b'P') | bit(b'E');

const EIA_G: &[GRow] = &[
    g(0, GOp::Rapid, Group::Motion),
    g(10, GOp::Linear, Group::Motion),
    g(20, GOp::ArcCw, Group::Motion),
    g(30, GOp::ArcCcw, Group::Motion),
    g(40, GOp::DwellOrWait, Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    g(400, GOp::CompCancel, Group::CutterComp),
    g(410, GOp::CompLeft, Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::CompRight, Group::CutterComp).reads(bit(b'D')),
    g(700, GOp::Inch, Group::Units),
    g(710, GOp::Metric, Group::Units),
    g(780, GOp::PocketRect, Group::NonModal)
        .reads(POCKET)
        .claims_axes(),
    g(790, GOp::PocketCircle, Group::NonModal)
        .reads(POCKET)
        .claims_axes(),
    g(800, GOp::CycleCancel, Group::Cycle),
    g(810, GOp::Cycle(Cycle::G81), Group::Cycle).reads(DRILL),
    g(820, GOp::Cycle(Cycle::G82), Group::Cycle).reads(DRILL),
    g(830, GOp::Cycle(Cycle::G83), Group::Cycle).reads(DRILL),
    g(840, GOp::Cycle(Cycle::G84), Group::Cycle).reads(DRILL),
    g(850, GOp::Cycle(Cycle::G85), Group::Cycle).reads(DRILL),
    g(860, GOp::Cycle(Cycle::G86), Group::Cycle).reads(DRILL),
    g(870, GOp::Cycle(Cycle::G87), Group::Cycle).reads(DRILL),
    g(890, GOp::Cycle(Cycle::G89), Group::Cycle).reads(DRILL),
    g(900, GOp::Absolute, Group::Distance),
    g(910, GOp::Incremental, Group::Distance),
    g(920, GOp::PresetOrClamp, Group::NonModal).claims_absolute_axes(),
    g(990, GOp::Junction, Group::NonModal),
];

/// RS-274-D reading: no `//` comments, no full-width `；` (Syntec habits).
const EIA_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: false,
    fullwidth_semicolon: false,
    extended: &[],
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
};

/// The EIA-274-D dialect.
pub(super) fn eia() -> Dialect {
    // The drilling words are the shared cycle words without K.
    debug_assert_eq!(DRILL, CYCLE_WORDS & !bit(b'K'));
    let (g, m) = Dialect::tables(&[EIA_G], MILL_M);
    Dialect {
        name: "eia",
        lex: EIA_LEX,
        g,
        m,
        incremental_words: &[],
        diameter: Diameter {
            axis: None,
            at_power_on: false,
        },
        integers: IntegerWords::LeastIncrement,
        plane: Plane::Xy,
        long_chord: LongChord::Alarm,
        arc_letters: 0,
        default_machine: DEFAULT_MILL_TOML,
        unsupported: &[],
        rapid: RapidPath::ZPriority,
        cycles: CycleRules::Eia,
        bare_return: BareReturn::NeedsAxes,
        g10: G10Rules::Fanuc,
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
    }
}
