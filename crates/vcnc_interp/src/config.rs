//! What a run reads and never changes: the machine, the dialect, the
//! operator's switches, and what follows from them once (the axis words,
//! whether travel is limited, how a word without a point reads). Every
//! stage of the interpreter reads it; none writes it. The machine's
//! geometry questions a move asks — which axes a plane has, which word
//! placed an axis, whether a move stays within travel — are answered here
//! from the configuration alone, so that the motion stage and the codes
//! need no interpreter to ask them.

use crate::alarms;
use crate::dialect::{AxisWord, Dialect};
use vcnc_core::events::Plane;
use vcnc_core::geometry::PlaneAxes;
use vcnc_core::machine::Machine;
use vcnc_syntax::{Diagnostic, Span};

/// Operator switches.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    /// Skip blocks that start with `/`.
    pub block_delete: bool,
    /// Stop at M01.
    pub optional_stop: bool,
    /// Go on after an alarm with the next block, the state as it was
    /// before the alarmed one (`vcnc check --keep-going`, the language
    /// server): every alarm becomes an `alarm` event and the run ends as
    /// the program does, its outcome the first alarm.
    pub keep_going: bool,
}

/// What a run reads and never changes: the machine, the dialect, the
/// operator's switches and what follows from them.
pub(crate) struct Config<'a> {
    pub machine: &'a Machine,
    pub dialect: &'a Dialect,
    pub opts: Options,
    /// Letters that address axes (axis letters and incremental words).
    pub axis_mask: u32,
    /// How each machine axis is written, in axis order.
    pub axis_words: Vec<AxisWord>,
    /// Whether the machine has travel limits to check (E501).
    pub travel_limited: bool,
    /// The highest cutting feed, mm/min (the control's clamp).
    pub max_feed: f64,
    /// The dialect reads `%@MACRO` files (checked for every block).
    pub macro_files: bool,
    /// A word without a decimal point is in whole units all the same
    /// (the dialect's integers, or a calculator-style machine).
    pub whole_words: bool,
    /// Whether the markers of program coordinates are emitted
    /// (`Interpreter::with_program_markers`).
    pub markers: bool,
}

impl<'a> Config<'a> {
    /// The configuration of a run of `dialect` on `machine`.
    pub fn new(machine: &'a Machine, dialect: &'a Dialect, opts: Options) -> Config<'a> {
        let mut axis_words: Vec<AxisWord> = machine
            .axes
            .iter()
            .map(|a| AxisWord::of(a.letter, dialect))
            .collect();
        let mut rest = 0;
        for a in axis_words.iter_mut().rev() {
            rest |= a.mask;
            a.rest = rest;
        }
        Config {
            machine,
            dialect,
            opts,
            axis_mask: axis_words.iter().fold(0, |m, a| m | a.mask),
            axis_words,
            travel_limited: machine.has_travel_limits(),
            max_feed: machine.max_feed_mm_per_min(),
            macro_files: dialect.macros.files != crate::dialect::MacroFiles::None,
            whole_words: dialect.integers == crate::dialect::IntegerWords::WholeUnits
                || machine.params.decimal_input == vcnc_core::machine::DecimalInput::Calculator,
            markers: false,
        }
    }

    /// The machine axes of a plane (E305 when the machine lacks one).
    pub fn plane_axes(&self, plane: Plane, cmd: Span) -> Result<PlaneAxes, Diagnostic> {
        let [la, lb, ln] = plane.letters();
        match (self.machine.axis_of(la), self.machine.axis_of(lb)) {
            (Some(a), Some(b)) => Ok(PlaneAxes {
                a,
                b,
                n: self.machine.axis_of(ln),
            }),
            _ => Err(alarms::arc_without_center(cmd, plane.as_str())),
        }
    }
}
