//! What the interpreter remembers between blocks, in two parts that differ
//! by how a failed block is undone.
//!
//! ```text
//!   State  (Copy, ~1 KB)            Tables (large, rarely written)
//!   modal codes, positions,         work offsets G54…G59.9,
//!   frame, feed, spindle, tool …    tool offsets H/D (G10 L10–L13)
//!   └ copied before every block,    └ every write journaled; a failed
//!     restored if it alarms           block rolls its writes back
//!     (a plain G00/G01 keeps only
//!     the few fields it changes
//!     before its last check:
//!     `block::execute::MoveUndo`)
//! ```
//!
//! Positions are kept twice: `prog`, the programmed point in program
//! coordinates (what G91 adds to), and `pos`, where the controlled point
//! is on the machine. The [`Frame`] converts one into the other.

use crate::dialect::Dialect;
use frame::{Frame, Transforms, Xyz};
use std::collections::BTreeMap;
use vcnc_core::events::{FrameInfo, PathMode, Plane, Pos, SpindleDir};
use vcnc_core::machine::{Machine, Tool, WORK_SYSTEMS};

mod cycle;
pub(crate) mod frame;
pub(crate) mod lathe;
mod nurbs;
mod points;
mod smoothing;

pub use cycle::{CycleData, ReducedPeck};
pub(crate) use nurbs::NurbsBuild;
pub(crate) use points::PointStyle;
pub(crate) use smoothing::Smoothing;

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
    /// Group 07: G40/G41/G42.
    pub comp: CompSide,
    /// Group 08: G43/G44/G49.
    pub tool_length: ToolLength,
    /// Group 10: canned cycles return to the R level (G99) when true, to the
    /// initial level (G98) when false.
    pub return_r: bool,
    /// Group 13: G96 when true.
    pub css: bool,
    /// Group 14: index into the work offsets (0 = G54).
    pub wcs: usize,
    /// Group 15.
    pub path: PathMode,
    /// Group 17: G16 polar coordinate input when true.
    pub polar: bool,
    /// Lathe G23 (diameter programming) when true, G22 when false.
    pub diameter: bool,
    /// G93 inverse-time feed (grbl) when true.
    pub inverse_time: bool,
    /// G90.1: arc centres I/J/K are absolute program coordinates when true.
    pub arc_absolute: bool,
    /// G05 P1–P5/P10000 high-speed mode (Syntec 1.2.6) when true.
    pub high_speed: bool,
    /// Group 12: G66 modal macro call when true, G67 when false.
    pub macro_call: bool,
}

/// The modal motion (group 01): the dialect table's own vocabulary, so
/// that a G code's operation is the mode it selects.
pub use crate::dialect::MotionOp as Motion;

/// Cutter radius compensation (group 07).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompSide {
    /// G40.
    Off,
    /// G41: the tool left of the path.
    Left,
    /// G42: the tool right of the path.
    Right,
}

/// Tool length compensation (group 08).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolLength {
    /// G49.
    Off,
    /// G43: the offset is added.
    Plus,
    /// G44: the offset is subtracted.
    Minus,
}

impl Modal {
    /// Power-on state: Fanuc 0i defaults (Syntec manual 1.2.12 for G17),
    /// with the plane and diameter mode of the dialect.
    pub fn power_on(dialect: &Dialect) -> Modal {
        Modal {
            motion: Motion::Rapid,
            plane: dialect.plane,
            incremental: false,
            per_rev: dialect.feed_at_power_on == crate::dialect::FeedAtPowerOn::PerRevolution,
            inch: false,
            comp: CompSide::Off,
            tool_length: ToolLength::Off,
            return_r: dialect.cycles.g99_at_power_on,
            css: false,
            wcs: 0,
            path: PathMode::Cutting,
            polar: false,
            diameter: dialect.diameter.at_power_on,
            inverse_time: false,
            arc_absolute: false,
            high_speed: false,
            macro_call: false,
        }
    }
}

/// Everything a block may change, copied before each block so that an
/// alarm restores it whole (but for the plain moves that
/// `block::execute::MoveUndo` covers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct State {
    /// Modal codes.
    pub modal: Modal,
    /// Where the controlled point is, machine coordinates.
    pub pos: Pos,
    /// The programmed point, program coordinates (mm; lathe X as a radius):
    /// the controller's absolute position register.
    pub(crate) prog: Pos,
    /// Where the programmed point is on the machine (before radius
    /// compensation); increments start here.
    pub(crate) nominal: Pos,
    /// The transforms changed without a move since the last absolute move:
    /// `nominal` is not where the frame puts `prog`, and increments must
    /// start from `nominal` (Fanuc; Syntec 1.2.21's note on G50.1).
    pub(crate) detached: bool,
    /// Program ↔ machine.
    pub(crate) frame: Frame,
    /// A fingerprint of the frame last reported in a `frame` event.
    pub(crate) reported: u64,
    /// The frame changed since it was last reported.
    pub(crate) frame_dirty: bool,
    /// H number of the tool length offset in force.
    pub(crate) h_number: u32,
    /// D number of the cutter radius in force.
    pub(crate) d_number: u32,
    /// The cutter radius latched when D was given (negative swaps the side).
    pub(crate) comp_d_mm: f64,
    /// Last polar radius and angle (G16), program units mm and degrees.
    pub(crate) polar: (f64, f64),
    /// Canned cycles.
    pub cycle: CycleData,
    /// Programmed F, in program units (converted when used).
    pub feed: f64,
    /// Programmed S (rpm under G97, m/min under G96).
    pub s_value: f64,
    /// G92 S spindle clamp, rpm.
    pub(crate) max_rpm: Option<f64>,
    /// Spindle direction.
    pub spindle: SpindleDir,
    /// Speed the spindle turns at (last `spindle` event), rpm.
    pub rpm: f64,
    /// Coolant on (M07/M08) or off (M09).
    pub coolant: bool,
    /// Last T word.
    pub tool_selected: Option<u32>,
    /// Tool in the spindle.
    pub tool_active: Option<u32>,
    /// G28/G30 intermediate point, program coordinates, of the axes set in
    /// `intermediate_axes` (bit i = axis i).
    pub(crate) intermediate: Pos,
    pub(crate) intermediate_axes: u8,
    /// Last G33 lead, mm.
    pub(crate) thread_lead_mm: Option<f64>,
    /// Where the last G31 stopped, machine coordinates.
    pub(crate) skip_pos: Option<Pos>,
    /// Lathe G08/G09 steps of ±10 % feed.
    pub(crate) feed_steps: i32,
    /// Lathe G31 F: feed magnification in percent (G30 resets to 100).
    pub(crate) magnification_pct: f64,
    /// `(1 + 0.1·feed_steps) · magnification_pct / 100`, kept current.
    pub(crate) feed_factor: f64,
    /// G05 parameter set in force (0: off).
    pub(crate) high_speed_p: u32,
    /// M29 rigid tapping mode: the next G84/G74 taps with the spindle
    /// synchronized to the axis, started by the cycle itself; G80 or a
    /// group-01 code ends it.
    pub(crate) rigid_tap: bool,
    /// G05.1 path smoothing (Syntec 1.2.7).
    pub(crate) smoothing: crate::state::Smoothing,
    /// Fanuc lathe: turret offset, cycle data, a pending chamfer.
    pub(crate) lathe: crate::state::lathe::LatheData,
}

impl State {
    /// Power-on state of `machine`.
    pub fn power_on(machine: &Machine, dialect: &Dialect) -> State {
        let xyz: Xyz = [b'X', b'Y', b'Z'].map(|l| machine.axis_of(l));
        let mut s = State {
            modal: Modal::power_on(dialect),
            pos: machine.start,
            prog: machine.start,
            nominal: machine.start,
            detached: false,
            frame: Frame::new(xyz),
            reported: fingerprint(&FrameInfo {
                origin: Pos::default(),
                linear: None,
                tool_offset: Pos::default(),
            }),
            frame_dirty: true,
            h_number: 0,
            d_number: 0,
            comp_d_mm: 0.0,
            polar: (0.0, 0.0),
            cycle: CycleData::OFF,
            feed: 0.0,
            s_value: 0.0,
            max_rpm: None,
            spindle: SpindleDir::Stop,
            rpm: 0.0,
            coolant: false,
            tool_selected: None,
            tool_active: None,
            intermediate: Pos::default(),
            intermediate_axes: 0,
            thread_lead_mm: None,
            skip_pos: None,
            feed_steps: 0,
            magnification_pct: 100.0,
            feed_factor: 1.0,
            high_speed_p: 0,
            rigid_tap: false,
            smoothing: crate::state::Smoothing::OFF,
            lathe: crate::state::lathe::LatheData::power_on(machine),
        };
        s.frame.origin = machine.work_offsets[0];
        s.prog = s.frame.program_of(s.pos);
        // Only a power-on frame other than the zero one needs reporting.
        s.frame_dirty = fingerprint(&s.frame_info()) != s.reported;
        s
    }

    /// The programmed point in program coordinates (mm; a lathe's X as a radius).
    pub fn program_pos(&self) -> Pos {
        self.prog
    }

    /// The frame as a `frame` event reports it.
    pub fn frame_info(&self) -> FrameInfo {
        FrameInfo {
            origin: self.frame.origin_with_transforms(),
            linear: self.frame.linear(),
            tool_offset: self.frame.tool,
        }
    }

    /// Changes the program origin, keeping the machine where it is: the
    /// programmed point becomes the same machine point seen from the new
    /// origin (Fanuc recomputes the absolute position on G52, G92 and a
    /// work-system change).
    pub(crate) fn move_origin(&mut self, origin: Pos) {
        self.frame.origin = origin;
        self.prog = self.frame.program_of(self.nominal);
        self.detached = false;
        self.frame_dirty = true;
    }

    /// Recomputes the origin after an offset or work-system change.
    pub(crate) fn refresh_origin(&mut self, tables: &Tables) {
        let work = tables.work.get(self.modal.wcs).copied().unwrap_or_default();
        let origin = work.plus(tables.local).plus(tables.shift);
        self.move_origin(origin);
    }
}

/// A fingerprint of a frame: frames equal to a nanometre give equal
/// fingerprints (a G92 that sets the position the tool already reads is no
/// change, whatever the last bit of the sum), and different ones practically
/// never collide (FNV-1a over the rounded values).
pub(crate) fn fingerprint(f: &FrameInfo) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut mix = |v: f64| {
        h ^= ((v * 1e9).round() + 0.0).to_bits();
        h = h.wrapping_mul(0x0100_0000_01b3);
    };
    f.origin.0.iter().for_each(|v| mix(*v));
    f.tool_offset.0.iter().for_each(|v| mix(*v));
    match &f.linear {
        Some(m) => m.iter().flatten().for_each(|v| mix(*v)),
        None => mix(f64::NAN),
    }
    h
}

/// One undoable write to the tables.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Undo {
    Work(usize, Pos),
    Tool(u32, Option<Tool>),
    Transforms(Transforms),
    Local(Pos),
    Shift(Pos, Pos),
    Reference(usize, Option<Pos>),
}

/// Data the program writes rarely: the offset tables (G10) and the
/// programmable transforms in force (G51, G51.1, G68), journaled so that a
/// block that alarms leaves them as they were. Kept out of [`State`] so that
/// the copy taken before every block stays small.
#[derive(Debug, Clone, PartialEq)]
pub struct Tables {
    /// Work offsets, G54 first.
    pub work: [Pos; WORK_SYSTEMS],
    /// Tool offsets by number (H and D share the numbers).
    pub tools: BTreeMap<u32, Tool>,
    /// Rotation, scaling and mirror in force, in the order commanded.
    pub(crate) transforms: Transforms,
    /// G52 local offset, in the active work system.
    pub local: Pos,
    /// G92 shift in force, common to all work systems.
    pub shift: Pos,
    /// The G92 shift as last set (LinuxCNC's parameters #5211–#5219):
    /// G92.2 suspends the shift and keeps this, G92.3 puts it back.
    pub shift_kept: Pos,
    /// Reference points 1–4 (machine coordinates): the machine file's,
    /// until G28.1/G30.1 store the current position.
    pub reference: [Option<Pos>; 4],
    journal: Vec<Undo>,
}

impl Tables {
    /// The tables of `machine` at power-on.
    pub fn new(machine: &Machine) -> Tables {
        Tables {
            work: machine.work_offsets,
            tools: machine.tools.clone(),
            transforms: Transforms::default(),
            local: Pos::default(),
            shift: Pos::default(),
            shift_kept: Pos::default(),
            reference: machine.reference,
            journal: Vec::new(),
        }
    }

    /// Sets work offset `n`.
    pub(crate) fn set_work(&mut self, n: usize, p: Pos) {
        if let Some(slot) = self.work.get_mut(n) {
            self.journal.push(Undo::Work(n, *slot));
            *slot = p;
        }
    }

    /// Sets the offsets of tool number `n`.
    pub(crate) fn set_tool(&mut self, n: u32, t: Tool) {
        let old = self.tools.insert(n, t);
        self.journal.push(Undo::Tool(n, old));
    }

    /// Sets the G52 local offset.
    pub(crate) fn set_local(&mut self, p: Pos) {
        self.journal.push(Undo::Local(self.local));
        self.local = p;
    }

    /// Sets the G92 shift (G92, G92.1), the kept one with it.
    pub(crate) fn set_shift(&mut self, p: Pos) {
        self.journal.push(Undo::Shift(self.shift, self.shift_kept));
        self.shift = p;
        self.shift_kept = p;
    }

    /// G92.2 (`on` false): the shift suspended, the kept one unchanged;
    /// G92.3 (`on` true): the kept shift in force again.
    pub(crate) fn suspend_shift(&mut self, on: bool) {
        self.journal.push(Undo::Shift(self.shift, self.shift_kept));
        self.shift = if on { self.shift_kept } else { Pos::default() };
    }

    /// Sets reference point `n` (0 = the first).
    pub(crate) fn set_reference(&mut self, n: usize, p: Pos) {
        if let Some(slot) = self.reference.get_mut(n) {
            self.journal.push(Undo::Reference(n, *slot));
            *slot = Some(p);
        }
    }

    /// Sets the transforms in force.
    pub(crate) fn set_transforms(&mut self, t: Transforms) {
        self.journal.push(Undo::Transforms(self.transforms));
        self.transforms = t;
    }

    /// The offsets of number `n` (zero when the table does not list it).
    pub fn tool(&self, n: u32) -> Tool {
        self.tools.get(&n).copied().unwrap_or_default()
    }

    /// The block succeeded: its writes stay.
    pub(crate) fn commit(&mut self) {
        self.journal.clear();
    }

    /// The block failed: undo its writes, newest first.
    pub(crate) fn rollback(&mut self) {
        while let Some(u) = self.journal.pop() {
            match u {
                Undo::Work(n, p) => {
                    if let Some(slot) = self.work.get_mut(n) {
                        *slot = p;
                    }
                }
                Undo::Tool(n, Some(t)) => {
                    self.tools.insert(n, t);
                }
                Undo::Tool(n, None) => {
                    self.tools.remove(&n);
                }
                Undo::Transforms(t) => self.transforms = t,
                Undo::Local(p) => self.local = p,
                Undo::Shift(p, kept) => {
                    self.shift = p;
                    self.shift_kept = kept;
                }
                Undo::Reference(n, p) => {
                    if let Some(slot) = self.reference.get_mut(n) {
                        *slot = p;
                    }
                }
            }
        }
    }
}
