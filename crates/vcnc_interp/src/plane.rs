//! The interpreter's plane geometry: one point type ([`P2`]), one path
//! element ([`Seg`], a line or an arc), where lines and circles meet
//! ([`intersect`]), an arc's centre from its radius, and the one length
//! tolerance ([`ZERO_MM`]). Cutter compensation (`motion/comp/geom.rs`),
//! the lathe's chamfers and rounds (`codes/corner.rs`) and its cycles
//! (`codes/rough.rs`, `profile.rs`, `mrc.rs`, `turning_cycles.rs`,
//! `lathe_cycles.rs`, `threads.rs`) all speak it; each keeps its own
//! algorithm (a corner's offsets, a roughing level's crossings) beside its
//! feature, on top of these.
//!
//! ```text
//!   second ▲                a P2 is (first, second) in the order its user
//!          │       ● end      keeps: the compensation plane's (a, b) axes,
//!          │   ↺  ╱           or a lathe's (X radius, Z), the order the
//!          │ ccw ╱            cycles' words come in ([`Xz`]). `ccw`,
//!          │    ╱             `left` and `cross` turn from +first towards
//!    start ●                  +second in that order. Swapping the order
//!          └──────────▶ first turns them round: a G02 in G18 (clockwise
//!                             from +Z towards +X) is counter-clockwise in
//!                             (X, Z), and [`Seg::swapped`] says so.
//! ```
//!
//! What the events and their readers share — an arc's sweep, length,
//! bounds and tessellation, and the tolerance itself — stays in
//! `vcnc_core::geometry`; this module is the interpreter's working
//! geometry in a plane, before anything is an event.
//!
//! Every operation keeps the exact order of floating-point operations of
//! the code it replaced (the refactor of issue #25 is held to byte-identical
//! output), which is why a length comes in two spellings: [`P2::len`]
//! (√(x² + y²), compensation's hot path) and [`P2::hypot`] (`f64::hypot`,
//! which the lathe's corners and profile arcs were written with). They
//! differ at most in the last bit; choosing one for all would move outputs.

use std::ops::{Add, Div, Mul, Sub};
use vcnc_core::events::Pos;

/// Below this a length is zero, mm: the one length tolerance of the
/// interpreter (and of the planner and plotter, which read it from
/// `vcnc_core`). Programs are rounded to 0.001 mm or 0.0001 in, so this is
/// far below anything a program can mean and far above the rounding of
/// sums of such numbers. Other tolerances are named where they are used,
/// each with why it differs (an angle, a ratio, a cycle's sliver, the
/// touch of two offsets).
pub(crate) use vcnc_core::geometry::ZERO_MM;

/// A point or a vector of a plane, (first, second) coordinates, mm.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct P2(pub f64, pub f64);

/// A point of the lathe plane in program coordinates, (X radius, Z): the
/// order of the lathe cycles' words (X/U before Z/W), which is G18's
/// (Z, X) swapped — see the module's note on turning.
pub(crate) type Xz = P2;

impl P2 {
    /// The coordinates of `p` on axes `i` and `j` (machine or program
    /// indices, as `p` is).
    pub fn of(p: &Pos, (i, j): (usize, usize)) -> P2 {
        P2(p.get(i), p.get(j))
    }

    /// `p` with axes `i` and `j` set to this point, the others as they are.
    pub fn placed(self, mut p: Pos, (i, j): (usize, usize)) -> Pos {
        p.set(i, self.0);
        p.set(j, self.1);
        p
    }

    pub fn dot(self, o: P2) -> f64 {
        self.0 * o.0 + self.1 * o.1
    }

    /// The z of the 3-D cross product: positive when `o` lies to the left
    /// of `self` (counter-clockwise from it).
    pub fn cross(self, o: P2) -> f64 {
        self.0 * o.1 - self.1 * o.0
    }

    /// The length, √(x² + y²). Plane lengths of programs never come near
    /// overflow, so this skips `hypot`'s care (and cost).
    pub fn len(self) -> f64 {
        (self.0 * self.0 + self.1 * self.1).sqrt()
    }

    /// The length by `f64::hypot`, for the computations written with it.
    pub fn hypot(self) -> f64 {
        self.0.hypot(self.1)
    }

    /// The distance to `o` by [`len`](Self::len).
    pub fn dist(self, o: P2) -> f64 {
        (self - o).len()
    }

    /// The unit vector along this one, zero for a vector shorter than
    /// [`ZERO_MM`].
    pub fn unit(self) -> P2 {
        let l = self.len();
        if l < ZERO_MM {
            P2::default()
        } else {
            self * (1.0 / l)
        }
    }

    /// Turned 90° counter-clockwise: the left normal of a direction.
    pub fn left(self) -> P2 {
        P2(-self.1, self.0)
    }

    /// The angle of this vector from +first, radians in (−π, π].
    pub fn angle(self) -> f64 {
        self.1.atan2(self.0)
    }

    /// The signed turn from `self` to `o`, radians in (−π, π], positive
    /// counter-clockwise.
    pub fn angle_to(self, o: P2) -> f64 {
        self.cross(o).atan2(self.dot(o))
    }

    /// Turned counter-clockwise by the angle whose sine and cosine are given.
    pub fn rotated(self, sin: f64, cos: f64) -> P2 {
        P2(self.0 * cos - self.1 * sin, self.0 * sin + self.1 * cos)
    }

    /// (second, first).
    pub fn swapped(self) -> P2 {
        P2(self.1, self.0)
    }
}

impl Add for P2 {
    type Output = P2;
    fn add(self, o: P2) -> P2 {
        P2(self.0 + o.0, self.1 + o.1)
    }
}

impl Sub for P2 {
    type Output = P2;
    fn sub(self, o: P2) -> P2 {
        P2(self.0 - o.0, self.1 - o.1)
    }
}

impl Mul<f64> for P2 {
    type Output = P2;
    fn mul(self, k: f64) -> P2 {
        P2(self.0 * k, self.1 * k)
    }
}

impl Div<f64> for P2 {
    type Output = P2;
    fn div(self, k: f64) -> P2 {
        P2(self.0 / k, self.1 / k)
    }
}

/// A path element in a plane: a line, or an arc about a centre.
///
/// The fields are private so that a line's direction, worked out once when
/// it is made (compensation asks for it at every corner, twice for each of
/// its two blocks), always belongs to its end points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seg {
    start: P2,
    end: P2,
    /// An arc's centre and whether it turns counter-clockwise.
    arc: Option<(P2, bool)>,
    /// A line's unit direction; zero for an arc.
    dir: P2,
}

impl Seg {
    /// A line from `start` to `end`.
    pub fn line(start: P2, end: P2) -> Seg {
        Seg {
            start,
            end,
            arc: None,
            dir: (end - start).unit(),
        }
    }

    /// An arc from `start` to `end` about `centre`, counter-clockwise
    /// when `ccw` (a full circle when its ends are one point).
    pub fn arc(start: P2, end: P2, centre: P2, ccw: bool) -> Seg {
        Seg {
            start,
            end,
            arc: Some((centre, ccw)),
            dir: P2::default(),
        }
    }

    /// A line, or an arc when `arc` gives its centre and turn.
    pub fn new(start: P2, end: P2, arc: Option<(P2, bool)>) -> Seg {
        match arc {
            Some((c, ccw)) => Seg::arc(start, end, c, ccw),
            None => Seg::line(start, end),
        }
    }

    pub fn start(&self) -> P2 {
        self.start
    }

    pub fn end(&self) -> P2 {
        self.end
    }

    /// An arc's centre and whether it turns counter-clockwise; `None` for
    /// a line.
    pub fn arc_of(&self) -> Option<(P2, bool)> {
        self.arc
    }

    pub fn is_arc(&self) -> bool {
        self.arc.is_some()
    }

    /// The same element ending at `end` (a line keeps its start).
    pub fn with_end(&self, end: P2) -> Seg {
        Seg::new(self.start, end, self.arc)
    }

    /// The same element starting at `start`.
    pub fn with_start(&self, start: P2) -> Seg {
        Seg::new(start, self.end, self.arc)
    }

    /// The unit tangent at the start (`at_end` false) or the end.
    pub fn tangent(&self, at_end: bool) -> P2 {
        match self.arc {
            None => self.dir,
            Some((c, ccw)) => {
                let p = if at_end { self.end } else { self.start };
                let radial = (p - c).unit().left();
                if ccw { radial } else { radial * -1.0 }
            }
        }
    }

    /// The point `r` from the start (or end) on side `s` (+1 left of the
    /// direction of travel, −1 right), square to the path.
    pub fn perpendicular(&self, at_end: bool, s: f64, r: f64) -> P2 {
        let p = if at_end { self.end } else { self.start };
        p + self.tangent(at_end).left() * (s * r)
    }

    /// The element moved by `d`.
    pub fn shifted(&self, d: P2) -> Seg {
        Seg::new(
            self.start + d,
            self.end + d,
            self.arc.map(|(c, ccw)| (c + d, ccw)),
        )
    }

    /// The element with each point's coordinates swapped, (first, second)
    /// → (second, first): the same path in the other order, so an arc's
    /// turn reverses.
    pub fn swapped(&self) -> Seg {
        Seg::new(
            self.start.swapped(),
            self.end.swapped(),
            self.arc.map(|(c, ccw)| (c.swapped(), !ccw)),
        )
    }
}

/// A whole line or circle, where two paths may meet: the line through `p`
/// along the unit vector `d`, or the circle about `c` of radius `r`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Curve {
    Line { p: P2, d: P2 },
    Circle { c: P2, r: f64 },
}

/// Where two curves meet, the crossing nearest `near`; `None` when they
/// do not. Curves that miss each other by up to `touch_mm` touch (at the
/// foot of the gap): geometry that should be tangent is tangent only to
/// within the rounding of the program. Parallel lines never meet.
///
/// ```text
///   line–line      p1 + t·d1 on the second line: t = (p2 − p1) × d2 / (d1 × d2)
///   line–circle    the foot f of c on the line, then f ± h·d, h² = r² − |f − c|²
///   circle–circle  along c1→c2 by a = (r1² − r2² + d²) / 2d, then ± h square
///                  to it, h² = r1² − a²
/// ```
// Inlined into its one caller, the compensation's corner (−11 a G41 block).
#[inline(always)]
pub(crate) fn intersect(o1: Curve, o2: Curve, near: P2, touch_mm: f64) -> Option<P2> {
    let pick = |p: P2, q: P2| if p.dist(near) <= q.dist(near) { p } else { q };
    match (o1, o2) {
        (Curve::Line { p: p1, d: d1 }, Curve::Line { p: p2, d: d2 }) => {
            let den = d1.cross(d2);
            // d1 × d2 is the sine of the angle between unit directions.
            if den.abs() < 1e-12 {
                return None;
            }
            let t = (p2 - p1).cross(d2) / den;
            Some(p1 + d1 * t)
        }
        (Curve::Line { p, d }, Curve::Circle { c, r })
        | (Curve::Circle { c, r }, Curve::Line { p, d }) => {
            let foot = p + d * (c - p).dot(d);
            if foot.dist(c) > r + touch_mm {
                return None;
            }
            let h2 = r * r - foot.dist(c).powi(2);
            let h = h2.max(0.0).sqrt();
            Some(pick(foot + d * h, foot - d * h))
        }
        (Curve::Circle { c: c1, r: r1 }, Curve::Circle { c: c2, r: r2 }) => {
            let dd = c1.dist(c2);
            if dd < ZERO_MM || dd > r1 + r2 + touch_mm || dd < (r1 - r2).abs() - touch_mm {
                return None;
            }
            let a = (r1 * r1 - r2 * r2 + dd * dd) / (2.0 * dd);
            let h = (r1 * r1 - a * a).max(0.0).sqrt();
            let u = (c2 - c1).unit();
            let m = c1 + u * a;
            Some(pick(m + u.left() * h, m - u.left() * h))
        }
    }
}

/// Why an arc's centre cannot be found from its radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RadiusFault {
    /// The radius is zero.
    Zero,
    /// The ends are one point: an R arc cannot be a full circle.
    FullCircle,
    /// The chord is longer than 2|R| by more than the tolerance.
    TooSmall { chord: f64 },
}

/// The centre of the arc from `s` to `e` of signed radius `r` (negative:
/// the arc over 180°), counter-clockwise when `ccw`. A chord longer than
/// 2|R| by at most `tol_mm` makes a half circle.
///
/// ```text
///          ● c = mid + side·h·n̂     h = √(R² − (chord/2)²), n̂ the chord's
///          ┆ h                      left normal; side +1 for a
///   s ●────┴────● e                 counter-clockwise arc with R > 0,
///         mid                       flipped for clockwise and for R < 0
/// ```
///
/// (`motion/arc.rs` finds a G02/G03's centre the same way but squares
/// `chord / 2` where this divides the square of the chord by 4: the two
/// agree unless the chord's square overflows, and stay apart so that no
/// output moves.)
pub(crate) fn centre_from_radius(
    s: P2,
    e: P2,
    r: f64,
    ccw: bool,
    tol_mm: f64,
) -> Result<P2, RadiusFault> {
    let d = e - s;
    let chord = d.hypot();
    if r.abs() < ZERO_MM {
        return Err(RadiusFault::Zero);
    }
    if chord < ZERO_MM {
        return Err(RadiusFault::FullCircle);
    }
    let h2 = r * r - chord * chord / 4.0;
    if h2 < 0.0 && chord - 2.0 * r.abs() > tol_mm {
        return Err(RadiusFault::TooSmall { chord });
    }
    let h = h2.max(0.0).sqrt();
    let n = P2(-d.1 / chord, d.0 / chord);
    let side = if ccw { 1.0 } else { -1.0 } * r.signum();
    Ok(P2(
        s.0 + d.0 / 2.0 + side * h * n.0,
        s.1 + d.1 / 2.0 + side * h * n.1,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(p: P2, q: P2) -> bool {
        p.dist(q) < 1e-12
    }

    #[test]
    fn products_and_turns_follow_the_first_then_second_order() {
        let (x, y) = (P2(1.0, 0.0), P2(0.0, 1.0));
        assert_eq!(x.cross(y), 1.0, "second is left of first");
        assert_eq!(y.cross(x), -1.0);
        assert_eq!(P2(3.0, 4.0).dot(P2(2.0, -1.0)), 2.0);
        assert_eq!(x.left(), y);
        assert_eq!(P2(3.0, 4.0).len(), 5.0);
        assert_eq!(P2(3.0, 4.0).hypot(), 5.0);
        assert!(close(P2(3.0, 4.0).unit(), P2(0.6, 0.8)));
        assert_eq!(P2(1e-10, 0.0).unit(), P2(0.0, 0.0), "shorter than ZERO_MM");
        assert!((x.angle_to(y) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((P2(-1.0, -1.0).angle() + 0.75 * std::f64::consts::PI).abs() < 1e-15);
        // A quarter turn with exact sine and cosine.
        assert_eq!(P2(2.0, 1.0).rotated(1.0, 0.0), P2(-1.0, 2.0));
        let mut p = Pos::default();
        p.set(2, 7.0);
        let placed = P2(1.0, 2.0).placed(p, (0, 3));
        assert_eq!(placed.0[..4], [1.0, 0.0, 7.0, 2.0]);
        assert_eq!(P2::of(&placed, (3, 2)), P2(2.0, 7.0));
    }

    #[test]
    fn tangents_run_along_lines_and_square_to_the_radius_on_arcs() {
        let line = Seg::line(P2(1.0, 1.0), P2(4.0, 5.0));
        assert!(close(line.tangent(false), P2(0.6, 0.8)));
        assert!(close(line.tangent(true), P2(0.6, 0.8)));
        // The quarter circle about 0,0 from 10,0 to 0,10, counter-clockwise:
        // it starts going +second and ends going −first.
        let ccw = Seg::arc(P2(10.0, 0.0), P2(0.0, 10.0), P2(0.0, 0.0), true);
        assert!(close(ccw.tangent(false), P2(0.0, 1.0)));
        assert!(close(ccw.tangent(true), P2(-1.0, 0.0)));
        let cw = Seg::arc(P2(0.0, 10.0), P2(10.0, 0.0), P2(0.0, 0.0), false);
        assert!(close(cw.tangent(false), P2(1.0, 0.0)));
        // 2 to the left of the line's end, 2 to the right of its start.
        assert!(close(line.perpendicular(true, 1.0, 2.0), P2(2.4, 6.2)));
        assert!(close(line.perpendicular(false, -1.0, 2.0), P2(2.6, -0.2)));
    }

    #[test]
    fn moving_and_swapping_keep_the_path() {
        let arc = Seg::arc(P2(10.0, 0.0), P2(0.0, 10.0), P2(0.0, 0.0), true);
        let moved = arc.shifted(P2(1.0, -2.0));
        assert_eq!(moved.start(), P2(11.0, -2.0));
        assert_eq!(moved.end(), P2(1.0, 8.0));
        assert_eq!(moved.arc_of(), Some((P2(1.0, -2.0), true)));
        // Swapped, the same quarter runs from (0, 10) to (10, 0) — clockwise.
        let swapped = arc.swapped();
        assert_eq!(swapped.start(), P2(0.0, 10.0));
        assert_eq!(swapped.arc_of(), Some((P2(0.0, 0.0), false)));
        assert!(close(swapped.tangent(false), P2(1.0, 0.0)));
        // A line's direction follows its new end.
        let line = Seg::line(P2(0.0, 0.0), P2(2.0, 0.0)).with_end(P2(0.0, -3.0));
        assert!(close(line.tangent(false), P2(0.0, -1.0)));
        assert_eq!(line.with_start(P2(0.0, 1.0)).start(), P2(0.0, 1.0));
    }

    #[test]
    fn lines_and_circles_meet_where_worked_out_by_hand() {
        let x_axis = Curve::Line {
            p: P2(0.0, 0.0),
            d: P2(1.0, 0.0),
        };
        let diagonal = Curve::Line {
            p: P2(0.0, 2.0),
            d: P2(1.0, 1.0).unit(),
        };
        // y = x + 2 meets y = 0 at x = −2.
        let p = intersect(x_axis, diagonal, P2(0.0, 0.0), 0.01).unwrap();
        assert!(p.dist(P2(-2.0, 0.0)) < 1e-12, "{p:?}");
        let parallel = Curve::Line {
            p: P2(0.0, 1.0),
            d: P2(1.0, 0.0),
        };
        assert_eq!(intersect(x_axis, parallel, P2(0.0, 0.0), 0.01), None);
        // The circle of radius 5 about (0, 3) cuts y = 0 at x = ±4: the
        // one nearer the given point.
        let circle = Curve::Circle {
            c: P2(0.0, 3.0),
            r: 5.0,
        };
        assert_eq!(
            intersect(x_axis, circle, P2(3.0, 0.0), 0.01),
            Some(P2(4.0, 0.0))
        );
        assert_eq!(
            intersect(circle, x_axis, P2(-3.0, 1.0), 0.01),
            Some(P2(-4.0, 0.0))
        );
        // Radius 2.995 about (0, 3) misses y = 0 by 5 µm: a touch at the
        // foot within 0.01, nothing within 0.001.
        let near_miss = Curve::Circle {
            c: P2(0.0, 3.0),
            r: 2.995,
        };
        assert_eq!(
            intersect(x_axis, near_miss, P2(1.0, 0.0), 0.01),
            Some(P2(0.0, 0.0))
        );
        assert_eq!(intersect(x_axis, near_miss, P2(1.0, 0.0), 0.001), None);
        // Circles of radius 5 about (0, 0) and (8, 0) cross at (4, ±3).
        let c1 = Curve::Circle {
            c: P2(0.0, 0.0),
            r: 5.0,
        };
        let c2 = Curve::Circle {
            c: P2(8.0, 0.0),
            r: 5.0,
        };
        let p = intersect(c1, c2, P2(4.0, -1.0), 0.01).unwrap();
        assert!(p.dist(P2(4.0, -3.0)) < 1e-12, "{p:?}");
        // Concentric circles never meet; far apart ones neither.
        let far = Curve::Circle {
            c: P2(20.0, 0.0),
            r: 5.0,
        };
        assert_eq!(intersect(c1, c1, P2(0.0, 0.0), 0.01), None);
        assert_eq!(intersect(c1, far, P2(0.0, 0.0), 0.01), None);
    }

    #[test]
    fn an_arc_centre_lies_left_for_ccw_and_right_for_cw() {
        // Chord (0,0)→(8,0), |R| = 5: the centre is 3 off the chord's
        // middle (3-4-5), left (+second) for G03 R5.
        let (s, e) = (P2(0.0, 0.0), P2(8.0, 0.0));
        let c = centre_from_radius(s, e, 5.0, true, 0.01).unwrap();
        assert!(close(c, P2(4.0, 3.0)), "{c:?}");
        assert!(close(
            centre_from_radius(s, e, 5.0, false, 0.01).unwrap(),
            P2(4.0, -3.0)
        ));
        // A negative R takes the long way round: the other side.
        assert!(close(
            centre_from_radius(s, e, -5.0, true, 0.01).unwrap(),
            P2(4.0, -3.0)
        ));
        // R a hair short of half the chord: a half circle within the
        // tolerance, a fault beyond it.
        assert!(close(
            centre_from_radius(s, e, 3.999, true, 0.01).unwrap(),
            P2(4.0, 0.0)
        ));
        assert_eq!(
            centre_from_radius(s, e, 3.9, true, 0.01),
            Err(RadiusFault::TooSmall { chord: 8.0 })
        );
        assert_eq!(
            centre_from_radius(s, e, 0.0, true, 0.01),
            Err(RadiusFault::Zero)
        );
        assert_eq!(
            centre_from_radius(s, s, 5.0, true, 0.01),
            Err(RadiusFault::FullCircle)
        );
    }
}
