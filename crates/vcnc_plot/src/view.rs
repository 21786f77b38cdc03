//! Views: how a machine position becomes a point of the picture.
//!
//! The plot works in *plot space*, the X, Y and Z machine coordinates of the
//! controlled point in mm (`[x, y, z]`, 0 for an axis the machine lacks;
//! rotary axes are not drawn). A flat picture projects plot space onto two
//! screen axes, right (`u`) and up (`v`), and colours by a *depth* axis:
//!
//! ```text
//!   view   right u      up v                  depth   arcs kept as arcs
//!   xy     X            Y                     Z       G17
//!   xz     X            Z                     Z       G18
//!   yz     Y            Z                     Z       G19
//!   iso    (X+Y)/√2     (−X+Y+2Z)/√6          Z       none (ellipses)
//!   lathe  Z            X (radius, labelled   X       G18
//!          xz           as a diameter)
//! ```
//!
//! `iso` looks from the front right (+X, −Y, +Z) towards the origin, Z up.
//! The lathe half-section puts the spindle axis (Z) across and the
//! diameter axis up, as a turning drawing does: a lathe's events carry X as
//! a radius, so the picture is true to scale and only the labels double.

use vcnc_core::{Machine, Plane, Pos};

/// A point of plot space: X, Y, Z machine coordinates, mm.
pub type P3 = [f64; 3];

/// The flat views of `vcnc plot --view`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Top view: X right, Y up.
    Xy,
    /// Front view (on a lathe: the half-section, Z right, diameter up).
    Xz,
    /// Side view: Y right, Z up.
    Yz,
    /// Isometric view from +X −Y +Z.
    Iso,
}

impl View {
    /// The `--view` name.
    pub fn name(self) -> &'static str {
        match self {
            View::Xy => "xy",
            View::Xz => "xz",
            View::Yz => "yz",
            View::Iso => "iso",
        }
    }
}

/// A linear projection of plot space onto the screen, plus the depth axis
/// that colours the cuts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The view it shows.
    pub view: View,
    /// Screen right as a combination of x, y, z.
    pub u: P3,
    /// Screen up as a combination of x, y, z.
    pub v: P3,
    /// The coordinate that colours cuts by depth.
    pub depth: P3,
    /// Axis names of u and v, for labels.
    pub labels: [&'static str; 2],
    /// The arc plane that appears undistorted (arcs in it stay true arcs).
    pub arc_plane: Option<Plane>,
    /// Whether the up axis is a lathe's X, shown as a diameter.
    pub diameter_up: bool,
}

const X: P3 = [1.0, 0.0, 0.0];
const Y: P3 = [0.0, 1.0, 0.0];
const Z: P3 = [0.0, 0.0, 1.0];

impl Projection {
    /// The projection of `view`; `lathe` selects the turning half-section
    /// for `xz` and colours by the radius.
    pub fn new(view: View, lathe: bool) -> Projection {
        let depth = if lathe { X } else { Z };
        let (u, v, labels, arc_plane) = match view {
            View::Xy => (X, Y, ["X", "Y"], Some(Plane::Xy)),
            View::Xz if lathe => (Z, X, ["Z", "X"], Some(Plane::Zx)),
            View::Xz => (X, Z, ["X", "Z"], Some(Plane::Zx)),
            View::Yz => (Y, Z, ["Y", "Z"], Some(Plane::Yz)),
            View::Iso => {
                let (a, b) = (std::f64::consts::FRAC_1_SQRT_2, 1.0 / 6f64.sqrt());
                ([a, a, 0.0], [-b, b, 2.0 * b], ["", ""], None)
            }
        };
        Projection {
            view,
            u,
            v,
            depth,
            labels,
            arc_plane,
            diameter_up: lathe && view == View::Xz,
        }
    }

    /// Screen coordinates (right, up) of a point, mm.
    pub fn uv(&self, p: P3) -> (f64, f64) {
        (dot(self.u, p), dot(self.v, p))
    }

    /// The depth of a point, mm.
    pub fn depth_of(&self, p: P3) -> f64 {
        dot(self.depth, p)
    }
}

/// The dot product.
pub fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where X, Y and Z sit in a machine's axis order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AxisMap {
    /// Machine axis index of X, Y, Z (`None` when the machine lacks it).
    pub index: [Option<usize>; 3],
}

impl AxisMap {
    /// The X, Y, Z axes of `machine`.
    pub fn of(machine: &Machine) -> AxisMap {
        AxisMap {
            index: [
                machine.axis_of(b'X'),
                machine.axis_of(b'Y'),
                machine.axis_of(b'Z'),
            ],
        }
    }

    /// The plot-space point of a machine position.
    pub fn p3(&self, p: &Pos) -> P3 {
        self.index.map(|i| i.map_or(0.0, |i| p.get(i)))
    }

    /// The machine position of a plot-space point (other axes zero).
    pub fn pos(&self, p: P3) -> Pos {
        let mut out = Pos::default();
        for (i, v) in self.index.iter().zip(p) {
            if let Some(i) = i {
                out.set(*i, v);
            }
        }
        out
    }
}

/// Plot-space indices (0 = x, 1 = y, 2 = z) of a plane's first, second and
/// normal axis.
pub fn plane_indices(plane: Plane) -> [usize; 3] {
    match plane {
        Plane::Xy => [0, 1, 2],
        Plane::Zx => [2, 0, 1],
        Plane::Yz => [1, 2, 0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn iso_shows_x_right_down_y_right_up_and_z_straight_up() {
        let p = Projection::new(View::Iso, false);
        let (ux, vx) = p.uv(X);
        let (uy, vy) = p.uv(Y);
        let (uz, vz) = p.uv(Z);
        assert!(ux > 0.0 && vx < 0.0, "X goes right and down");
        assert!(uy > 0.0 && vy > 0.0, "Y goes right and up");
        assert!(uz.abs() < 1e-12 && vz > 0.0, "Z goes straight up");
        // The three axes foreshorten alike: each projects to √(2/3).
        for (u, v) in [(ux, vx), (uy, vy), (uz, vz)] {
            assert!((u.hypot(v) - (2.0f64 / 3.0).sqrt()).abs() < 1e-12);
        }
    }

    #[test]
    fn the_lathe_half_section_has_z_across_and_x_up() {
        let p = Projection::new(View::Xz, true);
        assert_eq!(p.uv([10.0, 0.0, -30.0]), (-30.0, 10.0));
        assert_eq!(p.depth_of([10.0, 0.0, -30.0]), 10.0);
        assert!(p.diameter_up);
        assert!(!Projection::new(View::Xz, false).diameter_up);
    }

    #[test]
    fn a_lathe_has_no_y_in_plot_space() {
        let m = Machine::from_toml(vcnc_core::machine::DEFAULT_LATHE_TOML).unwrap();
        let map = AxisMap::of(&m);
        let mut pos = Pos::default();
        pos.set(0, 12.5);
        pos.set(1, -40.0);
        assert_eq!(map.p3(&pos), [12.5, 0.0, -40.0]);
        assert_eq!(map.pos([12.5, 0.0, -40.0]), pos);
    }
}
