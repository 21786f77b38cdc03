//! Tool nose radius compensation on a lathe (Fanuc 0i-TF, G41/G42 with the
//! offset register's nose radius and imaginary tip direction): the same
//! stage as the mill's cutter compensation, plus one constant vector.
//!
//! A lathe is programmed by the imaginary tool tip, the corner of the
//! square around the insert's nose; compensation keeps the nose circle
//! tangent to the programmed contour, so the nose centre runs the offset
//! path the mill's geometry computes (`geom.rs`) and the controlled point,
//! the imaginary tip, runs that path moved by r·t, t the tip direction
//! from the nose centre:
//!
//! ```text
//!        +X ▲   2   6   1       t of each direction (X up, Z right, seen
//!           │    ╲  │  ╱        from +Y; G18):  1 (+Z,+X)  2 (−Z,+X)
//!           │   7 ─ ● ─ 5                       3 (−Z,−X)  4 (+Z,−X)
//!           │    ╱  │  ╲                        5 +Z  6 +X  7 −Z  8 −X
//!           │   3   8   4                       0, 9: the centre (t = 0)
//!           └──────────────▶ +Z
//! ```
//!
//! An OD turning tool is direction 3 (it touches the work towards −X and
//! −Z), a boring bar 2. Points without compensation (before the start-up,
//! after the cancel) are the imaginary tip itself, so the start-up and the
//! cancel move between the tip and the shifted offset path, as on a Fanuc.
//! On a mill the tip is 0 and nothing changes.

use super::geom::V2;
use crate::events::Plane;
use crate::interpreter::Interpreter;
use crate::motion::MachineKind;

/// The unit direction (Z, X) from the nose centre to the imaginary tip
/// (the table lives in `vcnc_core::tooling`, shared with the simulation).
pub(crate) fn tip_direction(tip: u8) -> (f64, f64) {
    vcnc_core::tooling::tip_direction(tip)
}

/// The Fanuc tip number of LinuxCNC's lathe tool orientation `q` (its tool
/// table's Q): the same directions mirrored in X (1↔4, 2↔3, 6↔8; 5 and 7
/// stay; 9, the nose centre, is Fanuc's 0), as rs274 offsets a G41/G42
/// path for each orientation (`tests/fixtures/linuxcnc_dialect`).
pub(crate) fn linuxcnc_tip(q: u8) -> u8 {
    match q {
        1 => 4,
        2 => 3,
        3 => 2,
        4 => 1,
        6 => 8,
        8 => 6,
        5 | 7 => q,
        _ => 0,
    }
}

/// `a + b`.
pub(crate) fn plus(a: V2, b: V2) -> V2 {
    V2::new(a.x + b.x, a.y + b.y)
}

/// A move's kind with an arc's centre moved by `shift` (the offset arc of
/// the nose centre is concentric with the programmed one; the tip's is
/// that arc moved).
pub(crate) fn shifted_kind(kind: MachineKind, shift: V2) -> MachineKind {
    match kind {
        MachineKind::Arc {
            center,
            plane,
            dir,
            feed,
        } => MachineKind::Arc {
            center: (center.0 + shift.x, center.1 + shift.y),
            plane,
            dir,
            feed,
        },
        k => k,
    }
}

impl Interpreter<'_> {
    /// The vector from the nose centre to the controlled point for a nose
    /// of radius `r`, in the compensation plane's (first, second) axes:
    /// the tip direction of the offset in force, in the ZX plane (G18),
    /// whose first axis is Z.
    pub(crate) fn nose_shift(&self, r: f64) -> V2 {
        if self.comp.plane != Plane::Zx {
            return V2::default();
        }
        let (z, x) = tip_direction(self.state.lathe.tip);
        V2::new(z * r, x * r)
    }
}
