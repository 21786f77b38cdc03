//! How a dialect reads its canned drilling cycles, as named behaviours.
//!
//! What a cycle does at each hole is the table's business (`Hole`, so
//! that G87 is back boring on a Fanuc and chip-breaking pecks in
//! EIA-274-D); how blocks in cycle mode are read — which words repeat a
//! hole, whether R may be left out, where a hole ends, how strictly words
//! must be written again — is this policy. The cycle code reads these
//! fields and never asks which controller it runs.

use super::{CYCLE_WORDS, CYCLE_WORDS_L, HAAS_PECK_WORDS, Hole, bit};

/// The letter that repeats a block's holes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Repeat {
    /// K (Fanuc, Syntec) or L (Haas, LinuxCNC).
    pub letter: u8,
    /// The fewest repeats a block may ask for: 0 stores the data and
    /// drills nothing (Fanuc K0); LinuxCNC refuses L0.
    pub least: u8,
}

/// How the tool gets to each hole.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Approach {
    /// In the plane at the level it is at, then to R (Fanuc, Syntec, EIA).
    PlaneThenR,
    /// rs274's: a tool below R first rises to R, the return level is R
    /// under G99 or the level the cycle started at, and the way to the
    /// hole is straight to the return level when the tool is at R or below.
    ReturnLevelFirst,
}

/// The clearance d of G73's back-off and G83's way back down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PeckClearance {
    /// The machine's parameter (5114 on a Fanuc, `peck_return_mm`).
    Parameter,
    /// A fixed distance, mm (LinuxCNC: 0.010 inch; EIA's G83: none).
    Fixed(f64),
}

/// How G74/G84 tap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TapStyle {
    /// In, dwell, reverse, out to R, dwell, forward; G84 pecks by Q with
    /// parameter 4001's type (Fanuc, Syntec).
    PeckByQ,
    /// In, reverse, dwell P, out to the return level, forward (rs274).
    ReverseDwellOut,
}

/// A dialect's reading of the canned drilling cycles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CycleRules {
    /// Words a block may carry for the cycle data in cycle mode.
    pub words: u32,
    /// The letter that repeats holes (EIA: none).
    pub repeat: Option<Repeat>,
    /// R may be left out: the R level is then the initial level (EIA,
    /// Haas).
    pub r_optional: bool,
    /// A hole's bottom may be at the R level (LinuxCNC refuses only a
    /// bottom above R).
    pub bottom_at_r: bool,
    /// Every hole ends at R whatever G98/G99 say (EIA).
    pub always_back_to_r: bool,
    /// The cycles return to R at power-on (G99: LinuxCNC's initial modes).
    pub g99_at_power_on: bool,
    /// The way to each hole.
    pub approach: Approach,
    /// G73/G83's clearance.
    pub peck_clearance: PeckClearance,
    /// G73/G83 dwell P at the bottom after the last peck.
    pub peck_dwell: bool,
    /// G73/G83 take I (first peck), J (less each peck), K (least) for a
    /// shrinking peck (Haas).
    pub reduced_pecks: bool,
    /// The dwell P is part of G82/G89's data and must be known (EIA).
    pub dwell_required: bool,
    /// G86 dwells P at the bottom before the spindle stops (LinuxCNC).
    pub bore_stop_dwell: bool,
    /// G89 feeds out to the return level rather than to R (LinuxCNC).
    pub bore_out_to_return_level: bool,
    /// How G74/G84 tap.
    pub tap: TapStyle,
    /// rs274's strict words: P only on the cycles that dwell, Q only on
    /// the pecking ones; R and Z as written are read again under each
    /// block's G90/G91; a block that changes the cycle writes R, the depth
    /// and its P or Q again; a cycle code needs an axis word.
    pub rs274_words: bool,
}

impl CycleRules {
    /// Syntec 900M / Fanuc 0i (`docs/cycles-spec.md`): G98/G99 return, R
    /// required, K repeats, G86 spindle stop.
    pub const FANUC: CycleRules = CycleRules {
        words: CYCLE_WORDS,
        repeat: Some(Repeat {
            letter: b'K',
            least: 0,
        }),
        r_optional: false,
        bottom_at_r: false,
        always_back_to_r: false,
        g99_at_power_on: false,
        approach: Approach::PlaneThenR,
        peck_clearance: PeckClearance::Parameter,
        peck_dwell: true,
        reduced_pecks: false,
        dwell_required: false,
        bore_stop_dwell: false,
        bore_out_to_return_level: false,
        tap: TapStyle::PeckByQ,
        rs274_words: false,
    };

    /// EIA-274-D (`docs/eia-spec.md` §5): back to R always, R optional, no
    /// repeats, G82/G89 need their dwell, G83 without clearance.
    pub const EIA: CycleRules = CycleRules {
        words: bit(b'R') | bit(b'Q') | bit(b'P'),
        repeat: None,
        r_optional: true,
        always_back_to_r: true,
        peck_clearance: PeckClearance::Fixed(0.0),
        peck_dwell: false,
        dwell_required: true,
        ..CycleRules::FANUC
    };

    /// Haas mills: Fanuc's cycles, repeated by L, and G73/G83's I, J, K
    /// (Haas mill operator's manual, G73/G83, "L Number of repeats").
    pub const HAAS: CycleRules = CycleRules {
        words: CYCLE_WORDS_L | HAAS_PECK_WORDS,
        repeat: Some(Repeat {
            letter: b'L',
            least: 0,
        }),
        reduced_pecks: true,
        // The Haas mill operator's manual marks G81–G89's R optional ("*
        // indicates optional"): the R plane is then the initial level.
        r_optional: true,
        ..CycleRules::FANUC
    };

    /// LinuxCNC: Fanuc's cycles as rs274 runs them, repeated by L.
    pub const RS274: CycleRules = CycleRules {
        words: CYCLE_WORDS_L,
        repeat: Some(Repeat {
            letter: b'L',
            least: 1,
        }),
        bottom_at_r: true,
        g99_at_power_on: true,
        approach: Approach::ReturnLevelFirst,
        peck_clearance: PeckClearance::Fixed(LINUXCNC_PECK_CLEARANCE_MM),
        bore_stop_dwell: true,
        bore_out_to_return_level: true,
        tap: TapStyle::ReverseDwellOut,
        rs274_words: true,
        ..CycleRules::FANUC
    };

    /// Whether a cycle doing `hole` reads a dwell P: under rs274's words
    /// G74, G82, G84, G86 and G89 only (its other cycles alarm on P, and a
    /// P kept from an earlier G82 does not make G73/G83 dwell); elsewhere
    /// every cycle keeps P as modal data.
    pub(crate) fn reads_p(&self, hole: Hole) -> bool {
        !self.rs274_words
            || matches!(
                hole,
                Hole::LeftTap | Hole::DrillDwell | Hole::Tap | Hole::BoreStop | Hole::BoreDwell
            )
    }

    /// Whether a cycle doing `hole` reads a peck Q: under rs274's words
    /// G73 and G83 only.
    pub(crate) fn reads_q(&self, hole: Hole) -> bool {
        !self.rs274_words || matches!(hole, Hole::HighSpeedPeck | Hole::DeepPeck)
    }
}

/// LinuxCNC's G73 back-off and G83 clearance: 0.010 inch.
const LINUXCNC_PECK_CLEARANCE_MM: f64 = 0.254;
