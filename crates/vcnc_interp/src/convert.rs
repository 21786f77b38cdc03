//! The "convert" phase: what a word's value means in mm, seconds or counts.
//!
//! A length or angle written without a decimal point is in least input
//! increments (0.001 mm, 0.0001 inch, 0.001°) unless the machine reads
//! numbers calculator-style; inch values become mm here, so nothing after
//! this module knows the program's units. Integer words (P, L, H, T, N) must
//! be whole and in range.

use crate::alarms;
use crate::events::Pos;
use crate::interpreter::{AxisWord, Interpreter};
use crate::machine::DecimalInput;
use crate::words::Words;
use vcnc_syntax::{Diagnostic, Word};

/// mm per inch.
pub const MM_PER_INCH: f64 = 25.4;

impl Interpreter<'_> {
    /// Program units → mm factor.
    pub(crate) fn unit_mm(&self) -> f64 {
        if self.state.modal.inch {
            MM_PER_INCH
        } else {
            1.0
        }
    }

    fn whole_units(&self, w: &Word) -> bool {
        w.point
            || self.dialect.whole_unit_integers
            || self.machine.params.decimal_input == DecimalInput::Calculator
    }

    /// A length word in mm.
    pub(crate) fn length_mm(&self, w: &Word) -> f64 {
        let inch = self.state.modal.inch;
        let v = if self.whole_units(w) {
            w.value
        } else {
            w.value * if inch { 0.0001 } else { 0.001 }
        };
        if inch { v * MM_PER_INCH } else { v }
    }

    /// An X-direction length that follows diameter programming (lathe G23
    /// halves it): axis words, and the cycles' X depths.
    pub(crate) fn x_length_mm(&self, w: &Word) -> f64 {
        let v = self.length_mm(w);
        if self.state.modal.diameter {
            v / 2.0
        } else {
            v
        }
    }

    /// The value of an axis word: mm (a radius for a diameter axis), or
    /// degrees for a rotary axis.
    #[inline]
    pub(crate) fn axis_mm(&self, a: &AxisWord, w: &Word) -> f64 {
        if a.rotary {
            if self.whole_units(w) {
                w.value
            } else {
                w.value * 0.001
            }
        } else if a.diameter {
            self.x_length_mm(w)
        } else {
            self.length_mm(w)
        }
    }

    /// The value of the axis word of machine axis `i`.
    pub(crate) fn axis_value(&self, i: usize, w: &Word) -> f64 {
        match self.axis_words.get(i) {
            Some(a) => self.axis_mm(a, w),
            None => self.length_mm(w),
        }
    }

    /// A time word (G04 X): seconds with a point, milliseconds without.
    pub(crate) fn seconds(&self, w: &Word) -> f64 {
        if self.whole_units(w) {
            w.value
        } else {
            w.value * 0.001
        }
    }

    /// Target of the block's axis words in machine coordinates, absolute or
    /// incremental from the current position (an incremental word such as U
    /// always counts from here); axes not named stay put. The mask says
    /// which axes were named.
    pub(crate) fn target(&self, w: &Words<'_>, incremental: bool) -> (Pos, u32) {
        let mut to = self.state.pos;
        let mut named = 0;
        for (i, a) in self.axis_words.iter().enumerate() {
            let (word, inc) = match w.get(a.letter) {
                Some(word) => (word, incremental),
                None => match a.inc.and_then(|l| w.get(l)) {
                    Some(word) => (word, true),
                    None => continue,
                },
            };
            let v = self.axis_mm(a, &word);
            let machine = if inc {
                self.state.pos.get(i) + v
            } else {
                v + self.state.origin.get(i)
            };
            to.set(i, machine);
            named |= 1 << i;
        }
        (to, named)
    }
}

/// A whole number word in `min..=max`.
pub(crate) fn whole(
    w: &Word,
    letter: u8,
    min: f64,
    max: f64,
    why: &str,
) -> Result<u32, Diagnostic> {
    if w.point {
        return Err(alarms::no_decimal_point(w.span, letter, why));
    }
    if w.value < min || w.value > max {
        return Err(alarms::value_out_of_range(
            w.span,
            letter,
            w.value,
            &format!("{letter_c} is {min}..{max}", letter_c = char::from(letter)),
        ));
    }
    // In range and whole (no point), so the cast is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok(w.value as u32)
}
