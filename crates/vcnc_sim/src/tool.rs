//! The cutter as the simulation sees it: an axisymmetric body described by
//! the height of its bottom above the tip at each radius, plus the shank
//! and holder above the flutes.
//!
//! ```text
//!        │ holder │  radius holder_radius, from stickout up
//!        ├──┐  ┌──┤
//!           │  │     shank: radius shank_radius, from flute_mm to stickout
//!         ┌─┘  └─┐
//!         │      │   flutes: radius `radius`, a cylinder above the profile
//!          ╲____╱    profile g(r): height of the bottom above the tip at
//!            ▲ tip   radius r (flat 0, ball R − √(R² − r²), bull, cone)
//! ```
//!
//! Every profile here is convex and non-decreasing in r. The Z-map's
//! envelope minimisation relies on that (`kernel.rs`): the lowest point
//! of the tool over a cell along a straight move is then a convex function
//! of the move's parameter. A lathe insert is its nose radius and tip
//! direction instead ([`Insert`]).

use vcnc_core::{ToolKind, ToolShape};

/// The bottom of a milling cutter: its height above the tip at a radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Profile {
    /// Flat end mill.
    Flat,
    /// Ball nose: a sphere of the cutter's radius.
    Ball,
    /// Bull nose: flat to `radius − corner`, then a quarter circle.
    Bull {
        /// Corner radius, mm (0 < corner < radius).
        corner_mm: f64,
    },
    /// A cone (drill point, V cutter) with an optional flat at the tip.
    Cone {
        /// Radius of the flat at the tip, mm.
        flat_mm: f64,
        /// Height gained per mm of radius past the flat (cot of half the
        /// included angle).
        rise_per_mm: f64,
    },
}

/// A milling cutter, sizes in mm.
#[derive(Debug, Clone, PartialEq)]
pub struct Cutter {
    /// The tool number (T).
    pub number: u32,
    /// The cutting radius.
    pub radius: f64,
    /// The bottom's shape.
    pub profile: Profile,
    /// The flute length (the shank starts there), when known.
    pub flute_mm: Option<f64>,
    /// The shank's radius above the flutes.
    pub shank_radius: f64,
    /// The holder: where it starts above the tip, and its radius.
    pub holder: Option<(f64, f64)>,
    /// Whether the tool may plunge straight down (`None`: not said).
    pub center_cutting: Option<bool>,
    /// How people read it: `T3 6 mm ball end mill`.
    pub label: String,
}

/// Smallest cutter radius simulated, mm (a smaller or invalid diameter is
/// raised to it: a zero-width tool removes nothing).
pub const MIN_RADIUS_MM: f64 = 0.005;

impl Cutter {
    /// The cutter a tool description gives. A turning insert on a mill
    /// (which cannot happen from the CLI) is cut as a flat end mill.
    pub fn from_shape(t: &ToolShape) -> Cutter {
        let radius = finite_or(t.diameter_mm / 2.0, 3.0).max(MIN_RADIUS_MM);
        let profile = match t.kind {
            ToolKind::Flat | ToolKind::Turning { .. } => Profile::Flat,
            ToolKind::Ball => Profile::Ball,
            ToolKind::Bull { corner_radius_mm } => {
                let c = finite_or(corner_radius_mm, 0.0);
                if c <= 0.0 {
                    Profile::Flat
                } else if c >= radius {
                    Profile::Ball
                } else {
                    Profile::Bull { corner_mm: c }
                }
            }
            ToolKind::Drill { point_angle_deg } => cone(0.0, point_angle_deg),
            ToolKind::Vee {
                included_angle_deg,
                tip_diameter_mm,
            } => cone(
                (finite_or(tip_diameter_mm, 0.0) / 2.0).clamp(0.0, radius),
                included_angle_deg,
            ),
        };
        let positive = |v: Option<f64>| v.filter(|v| v.is_finite() && *v > 0.0);
        let shank_radius = positive(t.shank_diameter_mm).map_or(radius, |d| d / 2.0);
        let holder = match (positive(t.stickout_mm), positive(t.holder_diameter_mm)) {
            (Some(at), Some(d)) => Some((at, d / 2.0)),
            _ => None,
        };
        Cutter {
            number: t.number,
            radius,
            profile,
            flute_mm: positive(t.flute_length_mm),
            shank_radius,
            holder,
            center_cutting: t.center_cutting,
            label: label(t),
        }
    }

    /// A flat end mill of `radius` (tests, the assumed tool).
    pub fn flat(number: u32, radius: f64) -> Cutter {
        Cutter {
            number,
            radius: radius.max(MIN_RADIUS_MM),
            profile: Profile::Flat,
            flute_mm: None,
            shank_radius: radius,
            holder: None,
            center_cutting: None,
            label: format!("T{number} {} mm flat end mill", 2.0 * radius),
        }
    }

    /// Height of the bottom above the tip at radius `r` (clamped to the
    /// cutter's radius).
    #[inline]
    pub fn g(&self, r: f64) -> f64 {
        let r = r.clamp(0.0, self.radius);
        match self.profile {
            Profile::Flat => 0.0,
            Profile::Ball => self.radius - (self.radius * self.radius - r * r).max(0.0).sqrt(),
            Profile::Bull { corner_mm } => {
                let q = r - (self.radius - corner_mm);
                if q <= 0.0 {
                    0.0
                } else {
                    corner_mm - (corner_mm * corner_mm - q * q).max(0.0).sqrt()
                }
            }
            Profile::Cone {
                flat_mm,
                rise_per_mm,
            } => (r - flat_mm).max(0.0) * rise_per_mm,
        }
    }

    /// The same body, flat-bottomed, of another radius: the shank or the
    /// holder seen as a cutter (their bottoms are flat).
    pub fn flat_of_radius(&self, radius: f64) -> Cutter {
        Cutter {
            radius: radius.max(MIN_RADIUS_MM),
            profile: Profile::Flat,
            ..self.clone()
        }
    }
}

fn finite_or(v: f64, or: f64) -> f64 {
    if v.is_finite() { v } else { or }
}

/// A cone of `angle_deg` included angle (clamped to 1°..179°).
fn cone(flat_mm: f64, angle_deg: f64) -> Profile {
    let half = (finite_or(angle_deg, 118.0).clamp(1.0, 179.0) / 2.0).to_radians();
    Profile::Cone {
        flat_mm,
        rise_per_mm: 1.0 / half.tan(),
    }
}

fn label(t: &ToolShape) -> String {
    let kind = match t.kind {
        ToolKind::Flat => "flat end mill".to_string(),
        ToolKind::Ball => "ball end mill".to_string(),
        ToolKind::Bull { corner_radius_mm } => format!("bull nose R{corner_radius_mm}"),
        ToolKind::Drill { point_angle_deg } => format!("drill {point_angle_deg}°"),
        ToolKind::Vee {
            included_angle_deg, ..
        } => format!("V cutter {included_angle_deg}°"),
        ToolKind::Turning {
            nose_radius_mm,
            tip,
        } => return format!("T{} insert R{nose_radius_mm} tip {tip}", t.number),
    };
    format!("T{} {} mm {kind}", t.number, t.diameter_mm)
}

/// A lathe insert: its nose circle and where the programmed point (the
/// imaginary tip) sits on the square around it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Insert {
    /// The tool number (turret station).
    pub number: u32,
    /// The nose radius simulated, mm.
    pub nose_mm: f64,
    /// The imaginary tip direction, Fanuc numbering 0–9.
    pub tip: u8,
}

/// Smallest nose simulated, mm: a sharp insert (threading, parting with no
/// radius in its register) still cuts a width; a point would remove
/// nothing.
pub const MIN_NOSE_MM: f64 = 0.05;

impl Insert {
    /// The insert a tool description gives; a milling tool on a lathe is a
    /// nose of its radius centred on the programmed point.
    pub fn from_shape(t: &ToolShape) -> Insert {
        let (nose, tip) = match t.kind {
            ToolKind::Turning {
                nose_radius_mm,
                tip,
            } => (nose_radius_mm, tip),
            _ => (t.diameter_mm / 2.0, 0),
        };
        Insert {
            number: t.number,
            nose_mm: finite_or(nose, 0.0).max(MIN_NOSE_MM),
            tip: if tip > 9 { 0 } else { tip },
        }
    }

    /// From the imaginary tip to the nose centre, (Z, X) in mm: the tip is
    /// the corner of the square around the nose in the tip's direction
    /// (Fanuc: 1 +Z+X, 2 −Z+X, 3 −Z−X, 4 +Z−X, 5 +Z, 6 +X, 7 −Z, 8 −X;
    /// 0 and 9 the centre itself).
    pub fn tip_to_centre(&self) -> (f64, f64) {
        let (z, x) = vcnc_core::tooling::tip_direction(self.tip);
        (-z * self.nose_mm, -x * self.nose_mm)
    }

    /// The direction (Z, X) the insert's body runs from its nose: away
    /// from the work, opposite the tip's X component (its Z component for
    /// tips 5 and 7); `None` for a nose-centre tool (0, 9).
    pub fn body(&self) -> Option<(f64, f64)> {
        match self.tip {
            3 | 4 | 8 => Some((0.0, 1.0)),
            1 | 2 | 6 => Some((0.0, -1.0)),
            5 => Some((-1.0, 0.0)),
            7 => Some((1.0, 0.0)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shape(kind: ToolKind, d: f64) -> ToolShape {
        ToolShape {
            kind,
            diameter_mm: d,
            ..ToolShape::assumed(1)
        }
    }

    #[test]
    fn profiles_have_their_textbook_heights() {
        let ball = Cutter::from_shape(&shape(ToolKind::Ball, 10.0));
        assert_eq!(ball.g(0.0), 0.0);
        assert!((ball.g(5.0) - 5.0).abs() < 1e-12);
        assert!((ball.g(3.0) - 1.0).abs() < 1e-12); // 5 − √(25 − 9)
        let bull = Cutter::from_shape(&shape(
            ToolKind::Bull {
                corner_radius_mm: 1.0,
            },
            10.0,
        ));
        assert_eq!(bull.g(4.0), 0.0);
        assert!((bull.g(5.0) - 1.0).abs() < 1e-12);
        let drill = Cutter::from_shape(&shape(
            ToolKind::Drill {
                point_angle_deg: 90.0,
            },
            10.0,
        ));
        assert!((drill.g(5.0) - 5.0).abs() < 1e-12); // 45° flank
        let vee = Cutter::from_shape(&shape(
            ToolKind::Vee {
                included_angle_deg: 60.0,
                tip_diameter_mm: 2.0,
            },
            10.0,
        ));
        assert_eq!(vee.g(1.0), 0.0);
        assert!((vee.g(2.0) - 3f64.sqrt()).abs() < 1e-12); // cot 30°
    }

    #[test]
    fn a_tip_three_nose_sits_up_and_right_of_its_tip() {
        let i = Insert {
            number: 1,
            nose_mm: 0.8,
            tip: 3,
        };
        assert_eq!(i.tip_to_centre(), (0.8, 0.8));
    }
}
