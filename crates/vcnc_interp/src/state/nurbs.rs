//! A G06.2 curve while its blocks are being read (the reading is
//! `codes/nurbs.rs`).

use vcnc_core::Nurbs;
use vcnc_syntax::Span;

/// A curve whose blocks are being read.
#[derive(Debug, Clone)]
pub(crate) struct NurbsBuild {
    pub curve: Nurbs,
    /// The K-only blocks have begun: no more control points.
    pub knots_only: bool,
    /// The G06.2 word, for alarms about the whole curve.
    pub cmd: Span,
}
