//! The Syntec 900M and Fanuc 0i mill dialects: the G-code list of the Syntec
//! manual (section 1.1) as far as vcnc runs it, and the M-code table of its
//! chapter 2. The two differ only in the inch/metric codes.

use super::{
    BareReturn, CYCLE_WORDS, CYCLE_WORDS_L, CycleRules, Dialect, Diameter, DwellP, FeedAtPowerOn,
    G10Rules, GOp, GRow, Group, HAAS_PECK_WORDS, IntegerWords, LongChord, MGroup, MOp, MRow,
    OffsetDefault, ProgramStop, RapidPath, SurfaceSpeedOn, ThreadLead, ToolChangeSpindle,
    ToolLengthChange, ToolWords, bit, g,
};
use crate::events::{Cycle, Plane};
use crate::machine::DEFAULT_MILL_TOML;
use vcnc_syntax::{LexRules, Semicolon};

/// Rows shared by the Syntec 900M and Fanuc 0i mill dialects.
const MILL_G: &[GRow] = &[
    g(0, GOp::Rapid, Group::Motion),
    g(10, GOp::Linear, Group::Motion),
    g(20, GOp::ArcCw, Group::Motion),
    g(30, GOp::ArcCcw, Group::Motion),
    g(40, GOp::Dwell, Group::NonModal)
        .reads(bit(b'P') | bit(b'X'))
        .refuses_axes(),
    g(50, GOp::HighSpeed, Group::NonModal)
        .reads(bit(b'P'))
        .refuses_axes(),
    g(51, GOp::PathSmoothing, Group::NonModal)
        .reads(bit(b'Q') | bit(b'E'))
        .refuses_axes(),
    g(62, GOp::Nurbs, Group::Motion).reads(bit(b'P') | bit(b'K') | bit(b'R')),
    g(90, GOp::ExactStopOnce, Group::NonModal),
    g(100, GOp::SetData, Group::NonModal)
        .reads(bit(b'L') | bit(b'P') | bit(b'R'))
        .claims_absolute_axes(),
    g(150, GOp::PolarOff, Group::Polar),
    g(160, GOp::PolarOn, Group::Polar),
    g(170, GOp::PlaneXy, Group::Plane),
    g(180, GOp::PlaneZx, Group::Plane),
    g(190, GOp::PlaneYz, Group::Plane),
    g(280, GOp::RefReturn, Group::NonModal).claims_axes(),
    g(290, GOp::RefFrom, Group::NonModal).claims_axes(),
    g(300, GOp::RefReturnN, Group::NonModal)
        .reads(bit(b'P'))
        .claims_axes(),
    g(310, GOp::Skip, Group::NonModal).claims_axes(),
    g(330, GOp::Thread, Group::Motion),
    g(400, GOp::CompCancel, Group::CutterComp),
    g(410, GOp::CompLeft, Group::CutterComp).reads(bit(b'D')),
    g(420, GOp::CompRight, Group::CutterComp).reads(bit(b'D')),
    g(430, GOp::ToolLengthPlus, Group::ToolLength).reads(bit(b'H')),
    g(440, GOp::ToolLengthMinus, Group::ToolLength).reads(bit(b'H')),
    g(490, GOp::ToolLengthCancel, Group::ToolLength),
    g(500, GOp::ScaleOff, Group::Scaling),
    g(501, GOp::MirrorOff, Group::Mirror).claims_absolute_axes(),
    g(510, GOp::ScaleOn, Group::Scaling)
        .reads(bit(b'P') | bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_absolute_axes(),
    g(511, GOp::MirrorOn, Group::Mirror).claims_absolute_axes(),
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
    g(594, GOp::WorkSystem(9), Group::Wcs),
    g(595, GOp::WorkSystem(10), Group::Wcs),
    g(596, GOp::WorkSystem(11), Group::Wcs),
    g(597, GOp::WorkSystem(12), Group::Wcs),
    g(598, GOp::WorkSystem(13), Group::Wcs),
    g(599, GOp::WorkSystem(14), Group::Wcs),
    g(610, GOp::PathExact, Group::Path),
    g(620, GOp::PathSurface, Group::Path),
    g(630, GOp::PathTapping, Group::Path),
    g(640, GOp::PathCutting, Group::Path),
    // G65/G66 take every letter as the call's P, L and arguments.
    g(650, GOp::MacroCall, Group::NonModal)
        .reads(ALL_LETTERS)
        .refuses_axes(),
    g(660, GOp::MacroModal, Group::MacroModal)
        .reads(ALL_LETTERS)
        .refuses_axes(),
    g(670, GOp::MacroModalCancel, Group::MacroModal),
    g(680, GOp::RotateOn, Group::Rotation)
        .reads(bit(b'R'))
        .claims_absolute_axes(),
    g(690, GOp::RotateOff, Group::Rotation),
    g(730, GOp::Cycle(Cycle::G73), Group::Cycle).reads(CYCLE_WORDS),
    g(740, GOp::Cycle(Cycle::G74), Group::Cycle).reads(CYCLE_WORDS),
    g(760, GOp::Cycle(Cycle::G76), Group::Cycle).reads(CYCLE_WORDS),
    g(800, GOp::CycleCancel, Group::Cycle),
    g(810, GOp::Cycle(Cycle::G81), Group::Cycle).reads(CYCLE_WORDS),
    g(820, GOp::Cycle(Cycle::G82), Group::Cycle).reads(CYCLE_WORDS),
    g(830, GOp::Cycle(Cycle::G83), Group::Cycle).reads(CYCLE_WORDS),
    g(840, GOp::Cycle(Cycle::G84), Group::Cycle).reads(CYCLE_WORDS),
    g(850, GOp::Cycle(Cycle::G85), Group::Cycle).reads(CYCLE_WORDS),
    g(860, GOp::Cycle(Cycle::G86), Group::Cycle).reads(CYCLE_WORDS),
    g(870, GOp::Cycle(Cycle::G87), Group::Cycle).reads(CYCLE_WORDS),
    g(880, GOp::Cycle(Cycle::G88), Group::Cycle).reads(CYCLE_WORDS),
    g(890, GOp::Cycle(Cycle::G89), Group::Cycle).reads(CYCLE_WORDS),
    g(900, GOp::Absolute, Group::Distance),
    g(910, GOp::Incremental, Group::Distance),
    g(920, GOp::PresetOrClamp, Group::NonModal).claims_absolute_axes(),
    g(940, GOp::PerMinute, Group::FeedMode),
    g(950, GOp::PerRev, Group::FeedMode),
    g(960, GOp::SurfaceSpeed, Group::SpindleMode),
    g(970, GOp::SpindleRpm, Group::SpindleMode),
    g(1340, GOp::PatternCircle, Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_axes(),
    g(1350, GOp::PatternLine, Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K'))
        .claims_axes(),
    g(1360, GOp::PatternArc, Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K') | bit(b'P'))
        .claims_axes(),
    g(1371, GOp::PatternGrid, Group::NonModal)
        .reads(bit(b'I') | bit(b'J') | bit(b'K') | bit(b'P'))
        .claims_axes(),
    g(980, GOp::ReturnInitial, Group::ReturnLevel),
    g(990, GOp::ReturnR, Group::ReturnLevel),
];

/// Every letter (the arguments of G65/G66).
pub(super) const ALL_LETTERS: u32 = (1 << 26) - 1;

/// Syntec 900M: inch/metric are G70/G71 (manual 1.1, 1.2.29).
const SYNTEC_UNITS: &[GRow] = &[
    g(700, GOp::Inch, Group::Units),
    g(710, GOp::Metric, Group::Units),
];

/// Fanuc 0i: inch/metric are G20/G21.
const FANUC_UNITS: &[GRow] = &[
    g(200, GOp::Inch, Group::Units),
    g(210, GOp::Metric, Group::Units),
];

/// The M-code table of manual chapter 2 (also the lathe's).
pub(super) const MILL_M: &[MRow] = &[
    (0, MOp::Stop, MGroup::Flow, 0),
    (1, MOp::OptionalStop, MGroup::Flow, 0),
    (2, MOp::End, MGroup::Flow, 0),
    (3, MOp::SpindleCw, MGroup::Spindle, 0),
    (4, MOp::SpindleCcw, MGroup::Spindle, 0),
    (5, MOp::SpindleStop, MGroup::Spindle, 0),
    (6, MOp::ToolChange, MGroup::Tool, 0),
    (8, MOp::CoolantOn, MGroup::Coolant, 0),
    (9, MOp::CoolantOff, MGroup::Coolant, 0),
    (19, MOp::SpindleOrient, MGroup::Spindle, 0),
    (30, MOp::EndRewind, MGroup::Flow, 0),
    (
        98,
        MOp::Call,
        MGroup::Flow,
        bit(b'P') | bit(b'H') | bit(b'L'),
    ),
    (99, MOp::Return, MGroup::Flow, bit(b'P')),
];

const MILL_LEX: LexRules = LexRules {
    semicolon: Semicolon::EndOfBlock,
    slash_comments: true,
    fullwidth_semicolon: true,
    extended: &[],
    foreign: &[("CR=", "lathe"), ("IX", "lathe"), ("IZ", "lathe")],
    colon_is_o: false,
};

/// Codes of the Syntec G-code list (manual 1.1) that later work will run.
const SYNTEC_LATER: &[(u16, &str)] = &[];

/// Haas's codes beyond Fanuc's that its programs use (Haas mill operator's
/// manual, G- and M-code chapters).
const HAAS_G: &[GRow] = &[
    // G187 P1–P3 (rough, medium, finish) E corner tolerance: a setting for
    // the planner.
    g(1870, GOp::Smoothing, Group::NonModal).reads(bit(b'P') | bit(b'E')),
    // The cycles repeat by L; G73/G83 also peck by I, J, K.
    g(730, GOp::Cycle(Cycle::G73), Group::Cycle).reads(CYCLE_WORDS_L | HAAS_PECK_WORDS),
    g(740, GOp::Cycle(Cycle::G74), Group::Cycle).reads(CYCLE_WORDS_L),
    g(760, GOp::Cycle(Cycle::G76), Group::Cycle).reads(CYCLE_WORDS_L),
    g(810, GOp::Cycle(Cycle::G81), Group::Cycle).reads(CYCLE_WORDS_L),
    g(820, GOp::Cycle(Cycle::G82), Group::Cycle).reads(CYCLE_WORDS_L),
    g(830, GOp::Cycle(Cycle::G83), Group::Cycle).reads(CYCLE_WORDS_L | HAAS_PECK_WORDS),
    g(840, GOp::Cycle(Cycle::G84), Group::Cycle).reads(CYCLE_WORDS_L),
    g(850, GOp::Cycle(Cycle::G85), Group::Cycle).reads(CYCLE_WORDS_L),
    g(860, GOp::Cycle(Cycle::G86), Group::Cycle).reads(CYCLE_WORDS_L),
    g(870, GOp::Cycle(Cycle::G87), Group::Cycle).reads(CYCLE_WORDS_L),
    g(880, GOp::Cycle(Cycle::G88), Group::Cycle).reads(CYCLE_WORDS_L),
    g(890, GOp::Cycle(Cycle::G89), Group::Cycle).reads(CYCLE_WORDS_L),
];

/// Haas M codes with a controller meaning (the machine builder's others
/// are in `default_haas.toml`'s `[m_codes]`).
const HAAS_M: &[MRow] = &[
    (16, MOp::ToolChange, MGroup::Tool, 0),
    (97, MOp::LocalCall, MGroup::Flow, bit(b'P') | bit(b'L')),
];

fn mill(name: &'static str, units: &'static [GRow]) -> Dialect {
    let (g, m) = Dialect::tables(&[MILL_G, units], MILL_M);
    Dialect {
        name,
        lex: MILL_LEX,
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
        unsupported: SYNTEC_LATER,
        rapid: RapidPath::ByParameter,
        cycles: CycleRules::Fanuc,
        bare_return: BareReturn::NeedsAxes,
        g10: G10Rules::Fanuc,
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
    }
}

/// Syntec's M198: a subprogram call like M98 (its MACRO manual §2.3; the
/// controller re-reads the file, which vcnc always does).
const SYNTEC_M: &[MRow] = &[(
    198,
    MOp::Call,
    MGroup::Flow,
    bit(b'P') | bit(b'H') | bit(b'L'),
)];

/// Syntec 900M mill.
pub(super) fn syntec() -> Dialect {
    let rows: Vec<MRow> = MILL_M.iter().chain(SYNTEC_M).copied().collect();
    let (g, m) = Dialect::tables(&[MILL_G, SYNTEC_UNITS], &rows);
    Dialect {
        g,
        m,
        macros: super::MacroRules::SYNTEC,
        ..mill("syntec", SYNTEC_UNITS)
    }
}

/// Fanuc's lexing: the mill's, and `:` for the program number's O (ISO
/// code; Fanuc 0i operator's manual, program number: "In ISO code, a
/// colon (:) can be used instead of O"). Haas's too.
const FANUC_LEX: LexRules = LexRules {
    colon_is_o: true,
    ..MILL_LEX
};

/// Fanuc 0i mill.
pub(super) fn fanuc() -> Dialect {
    Dialect {
        lex: FANUC_LEX,
        ..mill("fanuc", FANUC_UNITS)
    }
}

/// Haas mills: Fanuc plus G187, M97 local subprograms, M16, G28 without
/// axes homing every axis, and the Haas machine's M codes.
pub(super) fn haas() -> Dialect {
    let rows: Vec<MRow> = MILL_M.iter().chain(HAAS_M).copied().collect();
    let (g, m) = Dialect::tables(&[MILL_G, FANUC_UNITS, HAAS_G], &rows);
    Dialect {
        name: "haas",
        g,
        m,
        default_machine: crate::machine::DEFAULT_HAAS_TOML,
        bare_return: BareReturn::AllAxes,
        cycles: CycleRules::Haas,
        dwell_p: DwellP::SecondsWithPoint,
        aux_m: &[],
        tool_change: ToolChangeSpindle::Keeps,
        thread_lead: ThreadLead::F,
        macros: super::MacroRules::HAAS,
        ..fanuc()
    }
}
