//! What the canned drilling cycles remember between blocks: the cycle in
//! force, what it does at each hole, and the data its blocks stored.

/// Canned-cycle mode and the data its blocks store (program coordinates on
/// the drilling axis, mm; seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleData {
    /// The active cycle (`None`: G80 or a group-01 code).
    pub code: Option<vcnc_core::events::Cycle>,
    /// What the active cycle does at each hole (the dialect table's
    /// reading of its code).
    pub hole: crate::dialect::Hole,
    /// The drilling-axis level when the cycle mode was entered.
    pub initial: f64,
    /// Z point (the hole bottom).
    pub z: Option<f64>,
    /// R level.
    pub r: Option<f64>,
    /// Q: peck depth, or the G76/G87 shift.
    pub q: Option<f64>,
    /// P: dwell at the bottom, seconds.
    pub p_s: Option<f64>,
    /// Haas's reduced peck (G73/G83 I, J, K), mm: the first peck, how much
    /// less each next one, the least.
    pub reduced: Option<ReducedPeck>,
    /// LinuxCNC: R and Z as written (mm), which every block reads again
    /// under its own G90/G91 (`r`, `z` are their levels for this block).
    pub written_rz: (Option<f64>, Option<f64>),
    /// The cycle code before the last block that wrote one (LinuxCNC wants
    /// R, the depth and the cycle's P or Q again when the code changes).
    pub before: Option<vcnc_core::events::Cycle>,
}

/// Pecks that start at `first` and shrink by `less` each time down to
/// `least` (Haas G73/G83 I, J, K).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReducedPeck {
    /// I: the first peck.
    pub first: f64,
    /// J: how much less each next peck.
    pub less: f64,
    /// K: the least peck.
    pub least: f64,
}

impl CycleData {
    /// No cycle mode, no data.
    pub const OFF: CycleData = CycleData {
        code: None,
        hole: crate::dialect::Hole::Drill,
        initial: 0.0,
        z: None,
        r: None,
        q: None,
        p_s: None,
        reduced: None,
        written_rz: (None, None),
        before: None,
    };
}
