//! The machine state the interpreter owns: modal codes, position, offsets,
//! spindle, tool and the values that outlive a block.
//!
//! ```text
//!   machine = program + work offset (G54…) + local (G52) + shift (G92)
//!             └─ what the program writes ─┘ └────── `origin` ──────┘
//! ```
//!
//! Positions are stored in machine coordinates; program coordinates are
//! derived by subtracting the cached `origin`, which is recomputed only when
//! an offset or the active work system changes. [`Modal`] is a small `Copy`
//! value so that a block updates a copy and commits it only when the whole
//! block has succeeded.

use crate::dialect::Dialect;
use crate::events::{PathMode, Plane, Pos, SpindleDir};
use crate::machine::{Machine, WORK_SYSTEMS};

/// Active codes of the modal groups.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modal {
    /// Group 01.
    pub motion: Motion,
    /// Group 02.
    pub plane: Plane,
    /// Group 03: G91 when true.
    pub incremental: bool,
    /// Group 05: G95 when true.
    pub per_rev: bool,
    /// Group 06: G70/G20 when true.
    pub inch: bool,
    /// Group 13: G96 when true.
    pub css: bool,
    /// Group 14: index into the work offsets (0 = G54).
    pub wcs: usize,
    /// Group 15.
    pub path: PathMode,
    /// Lathe G23 (diameter programming) when true, G22 when false.
    pub diameter: bool,
}

/// The modal motion (group 01).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// G00.
    Rapid,
    /// G01.
    Linear,
    /// G02.
    ArcCw,
    /// G03.
    ArcCcw,
    /// G33 (lead in program units).
    Thread,
    /// Lathe G32 (lead in inches).
    ThreadInch,
    /// Lathe G05 (arc through a middle point).
    ThreePoint,
}

impl Modal {
    /// Power-on state: Fanuc 0i defaults (Syntec manual 1.2.12 for G17),
    /// with the plane and diameter mode of the dialect.
    pub fn power_on(dialect: &Dialect) -> Modal {
        Modal {
            motion: Motion::Rapid,
            plane: dialect.plane,
            incremental: false,
            per_rev: false,
            inch: false,
            css: false,
            wcs: 0,
            path: PathMode::Cutting,
            diameter: dialect.diameter_at_power_on,
        }
    }
}

/// Offsets that together make the program origin.
#[derive(Debug, Clone, PartialEq)]
pub struct Offsets {
    /// Work offsets, G54 first (G10 L2 changes them).
    pub work: [Pos; WORK_SYSTEMS],
    /// G52 local offset, in the active work system.
    pub local: Pos,
    /// G92 shift, common to all work systems.
    pub shift: Pos,
}

/// Everything the interpreter remembers between blocks.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Modal codes.
    pub modal: Modal,
    /// Current position, machine coordinates.
    pub pos: Pos,
    /// Offsets.
    pub offsets: Offsets,
    /// `work[wcs] + local + shift`, kept current.
    pub origin: Pos,
    /// Programmed F, in program units (converted when used).
    pub feed: f64,
    /// Programmed S (rpm under G97, m/min under G96).
    pub s_value: f64,
    /// G92 S spindle clamp, rpm.
    pub max_rpm: Option<f64>,
    /// Spindle direction.
    pub spindle: SpindleDir,
    /// Speed the spindle turns at (last `spindle` event), rpm.
    pub rpm: f64,
    /// Last T word.
    pub tool_selected: Option<u32>,
    /// Tool in the spindle.
    pub tool_active: Option<u32>,
    /// G28/G30 intermediate point, program coordinates, per axis.
    pub intermediate: [Option<f64>; crate::events::MAX_AXES],
    /// Last G33 lead, mm.
    pub thread_lead_mm: Option<f64>,
    /// Where the last G31 stopped, machine coordinates.
    pub skip_pos: Option<Pos>,
    /// Where the program started (lathe G76 returns there).
    pub start_pos: Pos,
    /// Lathe G08/G09 steps of ±10 % feed.
    pub feed_steps: i32,
    /// Lathe G31 F: feed magnification in percent (G30 resets to 100).
    pub magnification_pct: f64,
    /// `(1 + 0.1·feed_steps) · magnification_pct / 100`, kept current.
    pub feed_factor: f64,
}

impl State {
    /// Power-on state of `machine`.
    pub fn power_on(machine: &Machine, dialect: &Dialect) -> State {
        let offsets = Offsets {
            work: machine.work_offsets,
            local: Pos::default(),
            shift: Pos::default(),
        };
        let mut s = State {
            modal: Modal::power_on(dialect),
            pos: machine.start,
            offsets,
            origin: Pos::default(),
            feed: 0.0,
            s_value: 0.0,
            max_rpm: None,
            spindle: SpindleDir::Stop,
            rpm: 0.0,
            tool_selected: None,
            tool_active: None,
            intermediate: [None; crate::events::MAX_AXES],
            thread_lead_mm: None,
            skip_pos: None,
            start_pos: machine.start,
            feed_steps: 0,
            magnification_pct: 100.0,
            feed_factor: 1.0,
        };
        s.refresh_origin();
        s
    }

    /// Recomputes `origin` after an offset or work-system change.
    pub fn refresh_origin(&mut self) {
        let o = &self.offsets;
        self.origin = o
            .work
            .get(self.modal.wcs)
            .copied()
            .unwrap_or_default()
            .plus(o.local)
            .plus(o.shift);
    }

    /// Current position in program coordinates.
    pub fn program_pos(&self) -> Pos {
        self.pos.minus(self.origin)
    }
}
