//! What the program's length words have looked like so far, for warning
//! W101 (a length without its decimal point read in least increments; the
//! check is `block/convert.rs`).

use crate::dialect::IntegerWords;
use vcnc_core::events::Pos;
use vcnc_core::machine::DecimalInput;

/// What the program's axis words look like so far (warning W101).
#[derive(Debug, Clone, Default)]
pub(crate) struct PointStyle {
    /// Integers are least increments here (else nothing to warn about).
    pub active: bool,
    /// A length with a decimal point was written.
    pub seen_point: bool,
    /// The first length without one, before any point was seen.
    pub first_plain: Option<vcnc_syntax::Diagnostic>,
    /// Warnings given (at most `MAX_WARNINGS`).
    pub warned: u32,
    /// The longest length without a point: letter, value, mm as read
    /// (W109; angles left out).
    pub longest: Option<(u8, f64, f64)>,
    /// The box of program positions since then, while no point was seen.
    pub reach: Option<(Pos, Pos)>,
}

impl PointStyle {
    /// Past this many, the trap is reported no more (the program has it
    /// throughout).
    pub const MAX_WARNINGS: u32 = 10;

    /// The program reached `p`.
    pub(crate) fn reached(&mut self, p: Pos) {
        self.reach = Some(PointStyle::grown(self.reach, p));
    }

    /// `reach` grown to hold `p`.
    pub(crate) fn grown(reach: Option<(Pos, Pos)>, p: Pos) -> (Pos, Pos) {
        let (mut lo, mut hi) = reach.unwrap_or((p, p));
        for i in 0..vcnc_core::MAX_AXES {
            lo.0[i] = lo.0[i].min(p.0[i]);
            hi.0[i] = hi.0[i].max(p.0[i]);
        }
        (lo, hi)
    }

    pub fn new(
        machine: &vcnc_core::machine::Machine,
        dialect: &crate::dialect::Dialect,
    ) -> PointStyle {
        PointStyle {
            active: dialect.integers == IntegerWords::LeastIncrement
                && machine.params.decimal_input == DecimalInput::Increment,
            ..PointStyle::default()
        }
    }
}
