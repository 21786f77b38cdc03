//! How the machine's axes are written in a dialect: each axis's letter, its
//! incremental word (U for X on a lathe), diameter programming, and the
//! letter masks a block is tested against.

use super::{Dialect, bit};

/// How one machine axis is addressed in the dialect.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AxisWord {
    /// Its letter (absolute under G90).
    pub letter: u8,
    /// Its always-incremental word (U for X on a lathe).
    pub inc: Option<u8>,
    /// Programmed in diameters under G23.
    pub diameter: bool,
    /// A rotary axis (degrees).
    pub rotary: bool,
    /// `letter` and `inc` as a letter mask (bit 0 = 'A'): a block without
    /// either skips the axis with one test.
    pub mask: u32,
    /// The masks of this axis and the ones after it: a block that names
    /// none of them is done with its axis words here.
    pub rest: u32,
}

impl AxisWord {
    pub(crate) fn of(letter: u8, dialect: &Dialect) -> AxisWord {
        let inc = dialect
            .incremental_words
            .iter()
            .find(|(_, a)| *a == letter)
            .map(|(w, _)| *w);
        AxisWord {
            letter,
            inc,
            diameter: dialect.diameter.axis == Some(letter),
            rotary: matches!(letter, b'A' | b'B' | b'C'),
            mask: bit(letter) | inc.map_or(0, bit),
            rest: 0,
        }
    }
}
