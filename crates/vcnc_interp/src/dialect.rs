//! Dialects as data: which G and M codes exist, what operation each one is,
//! which modal group it belongs to and which words it reads.
//!
//! A [`Dialect`] is built from rows (`code, op, group`) into flat lookup
//! tables indexed by the code × 10 (`G59.1` → 591), so the interpreter asks
//! "what is G20 here?" with one array index and never branches on the
//! dialect's name. Syntec and Fanuc share every row except the unit codes
//! (G70/G71 against G20/G21); the lathe and EIA profiles will be further row
//! sets over the same operations.

use vcnc_syntax::LexRules;

/// Modal groups (Fanuc numbering in the comments). `NonModal` is group 00.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// 00: one-shot codes.
    NonModal,
    /// 01: motion.
    Motion,
    /// 02: plane.
    Plane,
    /// 03: absolute/incremental.
    Distance,
    /// 05: feed per minute / per revolution.
    FeedMode,
    /// 06: inch/metric.
    Units,
    /// 13: constant surface speed.
    SpindleMode,
    /// 14: work coordinate system.
    Wcs,
    /// 15: path control.
    Path,
}

/// Number of modal groups other than `NonModal`.
pub const MODAL_GROUPS: usize = 8;

impl Group {
    /// Slot of a modal group in per-block tables (`None` for group 00).
    pub fn slot(self) -> Option<usize> {
        match self {
            Group::NonModal => None,
            Group::Motion => Some(0),
            Group::Plane => Some(1),
            Group::Distance => Some(2),
            Group::FeedMode => Some(3),
            Group::Units => Some(4),
            Group::SpindleMode => Some(5),
            Group::Wcs => Some(6),
            Group::Path => Some(7),
        }
    }
}

/// What a G code does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)] // each variant is named after its code's function
pub enum GOp {
    Rapid,
    Linear,
    ArcCw,
    ArcCcw,
    Thread,
    Dwell,
    ExactStopOnce,
    SetData,
    PlaneXy,
    PlaneZx,
    PlaneYz,
    RefReturn,
    RefFrom,
    RefReturnN,
    Skip,
    Inch,
    Metric,
    LocalSystem,
    MachineCoords,
    WorkSystem(u8),
    PathExact,
    PathSurface,
    PathTapping,
    PathCutting,
    Absolute,
    Incremental,
    PresetOrClamp,
    PerMinute,
    PerRev,
    SurfaceSpeed,
    SpindleRpm,
}

/// What an M code does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)]
pub enum MOp {
    Stop,
    OptionalStop,
    End,
    EndRewind,
    SpindleCw,
    SpindleCcw,
    SpindleStop,
    SpindleOrient,
    ToolChange,
    CoolantOn,
    CoolantOff,
    Call,
    Return,
}

/// M-code groups: two codes of one group in a block alarm (E206).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MGroup {
    /// M00 M01 M02 M30 M98 M99: program flow, executed last.
    Flow = 0,
    /// M03 M04 M05 M19.
    Spindle = 1,
    /// M08 M09.
    Coolant = 2,
    /// M06.
    Tool = 3,
}

/// Number of M groups.
pub const M_GROUPS: usize = 4;

/// One G-code row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GDef {
    /// Operation.
    pub op: GOp,
    /// Modal group.
    pub group: Group,
    /// Letters (bit 0 = 'A') the code reads besides the axes it moves.
    pub letters: u32,
    /// Whether the code takes the block's axis words for itself.
    pub takes_axes: bool,
}

/// One M-code row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MDef {
    /// Operation.
    pub op: MOp,
    /// Group.
    pub group: MGroup,
    /// Letters the code reads.
    pub letters: u32,
}

/// Bit of a letter in a letter mask.
pub const fn bit(l: u8) -> u32 {
    1 << (l - b'A')
}

const NONE: u32 = 0;

/// A dialect profile.
pub struct Dialect {
    /// Name as given to `--dialect`.
    pub name: &'static str,
    /// Lexical rules.
    pub lex: LexRules,
    g: Vec<Option<GDef>>,
    m: Vec<Option<MDef>>,
}

impl std::fmt::Debug for Dialect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Dialect")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// Largest G code × 10 in the tables.
const G_SLOTS: usize = 10_000;
/// Largest M code + 1.
const M_SLOTS: usize = 1_000;

type GRow = (u16, GOp, Group, u32, bool);

/// Rows shared by the Syntec 900M and Fanuc 0i mill dialects.
const MILL_G: &[GRow] = &[
    (0, GOp::Rapid, Group::Motion, NONE, false),
    (10, GOp::Linear, Group::Motion, NONE, false),
    (20, GOp::ArcCw, Group::Motion, NONE, false),
    (30, GOp::ArcCcw, Group::Motion, NONE, false),
    (40, GOp::Dwell, Group::NonModal, bit(b'P') | bit(b'X'), true),
    (90, GOp::ExactStopOnce, Group::NonModal, NONE, false),
    (
        100,
        GOp::SetData,
        Group::NonModal,
        bit(b'L') | bit(b'P'),
        true,
    ),
    (170, GOp::PlaneXy, Group::Plane, NONE, false),
    (180, GOp::PlaneZx, Group::Plane, NONE, false),
    (190, GOp::PlaneYz, Group::Plane, NONE, false),
    (280, GOp::RefReturn, Group::NonModal, NONE, true),
    (290, GOp::RefFrom, Group::NonModal, NONE, true),
    (300, GOp::RefReturnN, Group::NonModal, bit(b'P'), true),
    (310, GOp::Skip, Group::NonModal, NONE, true),
    (330, GOp::Thread, Group::Motion, NONE, false),
    (520, GOp::LocalSystem, Group::NonModal, NONE, true),
    (530, GOp::MachineCoords, Group::NonModal, NONE, true),
    (540, GOp::WorkSystem(0), Group::Wcs, NONE, false),
    (550, GOp::WorkSystem(1), Group::Wcs, NONE, false),
    (560, GOp::WorkSystem(2), Group::Wcs, NONE, false),
    (570, GOp::WorkSystem(3), Group::Wcs, NONE, false),
    (580, GOp::WorkSystem(4), Group::Wcs, NONE, false),
    (590, GOp::WorkSystem(5), Group::Wcs, NONE, false),
    (591, GOp::WorkSystem(6), Group::Wcs, NONE, false),
    (592, GOp::WorkSystem(7), Group::Wcs, NONE, false),
    (593, GOp::WorkSystem(8), Group::Wcs, NONE, false),
    (594, GOp::WorkSystem(9), Group::Wcs, NONE, false),
    (595, GOp::WorkSystem(10), Group::Wcs, NONE, false),
    (596, GOp::WorkSystem(11), Group::Wcs, NONE, false),
    (597, GOp::WorkSystem(12), Group::Wcs, NONE, false),
    (598, GOp::WorkSystem(13), Group::Wcs, NONE, false),
    (599, GOp::WorkSystem(14), Group::Wcs, NONE, false),
    (610, GOp::PathExact, Group::Path, NONE, false),
    (620, GOp::PathSurface, Group::Path, NONE, false),
    (630, GOp::PathTapping, Group::Path, NONE, false),
    (640, GOp::PathCutting, Group::Path, NONE, false),
    (900, GOp::Absolute, Group::Distance, NONE, false),
    (910, GOp::Incremental, Group::Distance, NONE, false),
    (920, GOp::PresetOrClamp, Group::NonModal, NONE, true),
    (940, GOp::PerMinute, Group::FeedMode, NONE, false),
    (950, GOp::PerRev, Group::FeedMode, NONE, false),
    (960, GOp::SurfaceSpeed, Group::SpindleMode, NONE, false),
    (970, GOp::SpindleRpm, Group::SpindleMode, NONE, false),
];

/// Syntec 900M: inch/metric are G70/G71 (manual 1.1, 1.2.29).
const SYNTEC_UNITS: &[GRow] = &[
    (700, GOp::Inch, Group::Units, NONE, false),
    (710, GOp::Metric, Group::Units, NONE, false),
];

/// Fanuc 0i: inch/metric are G20/G21.
const FANUC_UNITS: &[GRow] = &[
    (200, GOp::Inch, Group::Units, NONE, false),
    (210, GOp::Metric, Group::Units, NONE, false),
];

type MRow = (u16, MOp, MGroup, u32);

/// The M-code table of manual chapter 2 (same in both mill dialects).
const MILL_M: &[MRow] = &[
    (0, MOp::Stop, MGroup::Flow, NONE),
    (1, MOp::OptionalStop, MGroup::Flow, NONE),
    (2, MOp::End, MGroup::Flow, NONE),
    (3, MOp::SpindleCw, MGroup::Spindle, NONE),
    (4, MOp::SpindleCcw, MGroup::Spindle, NONE),
    (5, MOp::SpindleStop, MGroup::Spindle, NONE),
    (6, MOp::ToolChange, MGroup::Tool, NONE),
    (8, MOp::CoolantOn, MGroup::Coolant, NONE),
    (9, MOp::CoolantOff, MGroup::Coolant, NONE),
    (19, MOp::SpindleOrient, MGroup::Spindle, NONE),
    (30, MOp::EndRewind, MGroup::Flow, NONE),
    (
        98,
        MOp::Call,
        MGroup::Flow,
        bit(b'P') | bit(b'H') | bit(b'L'),
    ),
    (99, MOp::Return, MGroup::Flow, bit(b'P')),
];

const MILL_LEX: LexRules = LexRules {
    slash_comments: true,
    fullwidth_semicolon: true,
    extended: &[],
};

impl Dialect {
    /// Looks a dialect up by its `--dialect` name.
    pub fn by_name(name: &str) -> Option<Dialect> {
        match name {
            "syntec" => Some(Dialect::syntec()),
            "fanuc" => Some(Dialect::fanuc()),
            _ => None,
        }
    }

    /// Names accepted by [`by_name`](Self::by_name).
    pub const NAMES: &'static [&'static str] = &["syntec", "fanuc"];

    /// Syntec 900M mill (the default).
    pub fn syntec() -> Dialect {
        Dialect::build("syntec", MILL_LEX, &[MILL_G, SYNTEC_UNITS], MILL_M)
    }

    /// Fanuc 0i mill.
    pub fn fanuc() -> Dialect {
        Dialect::build("fanuc", MILL_LEX, &[MILL_G, FANUC_UNITS], MILL_M)
    }

    fn build(name: &'static str, lex: LexRules, g_rows: &[&[GRow]], m_rows: &[MRow]) -> Dialect {
        let mut g = vec![None; G_SLOTS];
        for &(code, op, group, letters, takes_axes) in g_rows.iter().flat_map(|r| r.iter()) {
            g[usize::from(code)] = Some(GDef {
                op,
                group,
                letters,
                takes_axes,
            });
        }
        let mut m = vec![None; M_SLOTS];
        for &(code, op, group, letters) in m_rows {
            m[usize::from(code)] = Some(MDef { op, group, letters });
        }
        Dialect { name, lex, g, m }
    }

    /// The G code whose value is `value` (`59.1`), if this dialect has it.
    pub fn g(&self, value: f64) -> Option<GDef> {
        let tenths = (value * 10.0).round();
        if (value * 10.0 - tenths).abs() > 1e-6 || !(0.0..G_SLOTS as f64).contains(&tenths) {
            return None;
        }
        // In 0..G_SLOTS and whole, so the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let slot = tenths as usize;
        self.g.get(slot).copied().flatten()
    }

    /// The M code `value`, if this dialect has it.
    pub fn m(&self, value: f64) -> Option<MDef> {
        if value.fract() != 0.0 || !(0.0..M_SLOTS as f64).contains(&value) {
            return None;
        }
        // In 0..M_SLOTS and whole, so the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let slot = value as usize;
        self.m.get(slot).copied().flatten()
    }

    /// Another dialect that knows G `value`, for a hint.
    pub fn g_elsewhere(&self, value: f64) -> Option<&'static str> {
        Dialect::NAMES
            .iter()
            .copied()
            .find(|n| *n != self.name && Dialect::by_name(n).and_then(|d| d.g(value)).is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_codes_differ_by_dialect_only() {
        let s = Dialect::syntec();
        let f = Dialect::fanuc();
        assert_eq!(s.g(70.0).map(|d| d.op), Some(GOp::Inch));
        assert_eq!(s.g(20.0), None);
        assert_eq!(f.g(20.0).map(|d| d.op), Some(GOp::Inch));
        assert_eq!(f.g(70.0), None);
        assert_eq!(s.g(59.1).map(|d| d.op), Some(GOp::WorkSystem(6)));
        assert_eq!(s.g(59.15), None);
        assert_eq!(s.g(-1.0), None);
        assert_eq!(s.g_elsewhere(20.0), Some("fanuc"));
    }
}
