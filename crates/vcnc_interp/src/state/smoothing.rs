//! What G05.1 path smoothing remembers between blocks (its behaviour is
//! `codes/smoothing.rs`).

/// The smoothing state (part of the `Copy` block state).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Smoothing {
    /// E of the G05.1 Q1 in force, mm (0: off).
    pub tolerance_mm: f64,
    /// The next G01 follows a tool length or work system change.
    pub skip_next: bool,
    /// What the last `smoothing` event said (0: off).
    pub reported_mm: f64,
}

impl Smoothing {
    /// Power-on: off.
    pub const OFF: Smoothing = Smoothing {
        tolerance_mm: 0.0,
        skip_next: false,
        reported_mm: 0.0,
    };
}
