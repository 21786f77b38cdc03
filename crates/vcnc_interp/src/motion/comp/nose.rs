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

use crate::motion::MachineKind;
use crate::plane::P2;

/// The unit direction (Z, X) from the nose centre to the imaginary tip
/// (the table lives in `vcnc_core::tooling`, shared with the simulation).
pub(crate) fn tip_direction(tip: u8) -> (f64, f64) {
    vcnc_core::tooling::tip_direction(tip)
}

/// The Fanuc tip number of LinuxCNC's lathe tool orientation `q` (its tool
/// table's Q): `vcnc_core::tooling`'s mapping, which `--tools` uses too.
pub(crate) fn linuxcnc_tip(q: u8) -> u8 {
    vcnc_core::tooling::fanuc_tip_of_linuxcnc(q)
}

/// A move's kind with an arc's centre moved by `shift` (the offset arc of
/// the nose centre is concentric with the programmed one; the tip's is
/// that arc moved).
pub(crate) fn shifted_kind(kind: MachineKind, shift: P2) -> MachineKind {
    match kind {
        MachineKind::Arc {
            center,
            plane,
            dir,
            feed,
        } => MachineKind::Arc {
            center: (center.0 + shift.0, center.1 + shift.1),
            plane,
            dir,
            feed,
        },
        k => k,
    }
}
