//! What a Fanuc lathe remembers between blocks beyond the modal codes: the
//! turret offset in force, the modal data of the single cycles G90/G92/G94,
//! the parameters the first blocks of the multiple repetitive cycles set
//! (Fanuc keeps them in parameters 5130–5143, so they stay until changed),
//! and a G01 whose chamfer or corner R waits for the next block.
//!
//! It is part of [`State`](crate::state::State), copied before each block
//! and restored whole when a block alarms, like every other modal datum.

use vcnc_core::events::{Feed, Pos};
use vcnc_core::machine::Machine;
use vcnc_syntax::Span;

/// Lathe data of the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LatheData {
    /// Offset register of the T word in force (0: none).
    pub offset: u32,
    /// Imaginary tip direction of that offset (0–9).
    pub tip: u8,
    /// G90/G92/G94: the end point and taper R of the last cycle block.
    pub single: SingleCycle,
    /// G71–G76 first-block data.
    pub mrc: MrcParams,
    /// A G01 with `,C`/`,R` whose corner waits for the next move.
    pub corner: Option<PendingCorner>,
}

impl LatheData {
    /// Power-on values: no offset, the machine's thread chamfer, no
    /// depth of cut (a G71 without its first block alarms).
    pub fn power_on(machine: &Machine) -> LatheData {
        LatheData {
            offset: 0,
            tip: 0,
            single: SingleCycle::default(),
            mrc: MrcParams {
                depth_mm: 0.0,
                retract_mm: 0.0,
                relief_x_mm: 0.0,
                relief_z_mm: 0.0,
                divisions: 1,
                peck_retract_mm: 0.0,
                finish_count: 1,
                chamfer_tenths: machine.params.thread_chamfer_tenths,
                tool_angle_deg: 60.0,
                min_depth_mm: 0.0,
                allowance_mm: 0.0,
            },
            corner: None,
        }
    }
}

/// Modal data of G90/G92/G94 (Fanuc: "X(U), Z(W) and R are modal during
/// the canned cycle"): program coordinates, mm (X a radius).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct SingleCycle {
    /// End point X (radius), program coordinates.
    pub x: f64,
    /// End point Z.
    pub z: f64,
    /// Taper: X at the start of the cut minus X at its end (G90, G92;
    /// radius), or Z at the start minus Z at the end (G94).
    pub r: f64,
}

/// Values the first blocks of G71–G76 set (Fanuc parameters 5130–5143).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MrcParams {
    /// G71 U / G72 W: depth of cut, radius mm (5132).
    pub depth_mm: f64,
    /// G71/G72 R: retract at 45° after each pass, mm (5133).
    pub retract_mm: f64,
    /// G73 U: X relief, radius mm (5135).
    pub relief_x_mm: f64,
    /// G73 W: Z relief, mm (5136).
    pub relief_z_mm: f64,
    /// G73 R: number of passes (5137).
    pub divisions: u32,
    /// G74/G75 R: retract after each peck, mm (5139).
    pub peck_retract_mm: f64,
    /// G76 P m: finishing passes at full depth (5142).
    pub finish_count: u32,
    /// G76 P r: thread chamfer-out, tenths of the lead (5130).
    pub chamfer_tenths: u8,
    /// G76 P a: tool angle, degrees (5143).
    pub tool_angle_deg: f64,
    /// G76 Q: minimum depth of cut, radius mm (5140).
    pub min_depth_mm: f64,
    /// G76 R: finishing allowance, radius mm (5141).
    pub allowance_mm: f64,
}

/// What a G01's `,C` or `,R` asks for at its end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum CornerKind {
    /// A straight chamfer, this far from the corner along both lines.
    Chamfer(f64),
    /// A round of this radius, tangent to both lines.
    Round(f64),
}

/// A G01 held until the next block says where the path turns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PendingCorner {
    pub kind: CornerKind,
    /// Where the G01 starts (program coordinates); `State::prog` is
    /// already the corner, so that the next block's U/W count from it.
    pub start: Pos,
    pub feed: Feed,
    /// A held arc's centre (program coordinates) and whether it turns
    /// clockwise; `None` for a G01.
    pub arc: Option<(Pos, bool)>,
    /// The G01 word (or the block's first word) and the `,C`/`,R` word.
    pub cmd: Span,
    pub word: Span,
    /// The line of the G01 block and where in it the block starts.
    pub line: u64,
    pub block_at: u32,
    /// Its source and line, to place alarms about its moves.
    pub source_line: Option<(usize, vcnc_syntax::Line)>,
}
