//! The plane geometry of cutter radius compensation (Syntec 1.2.18, Fanuc
//! type A), pure and testable on its own: offsets of lines and arcs,
//! their intersections, and what the tool centre does at a corner.
//!
//! ```text
//!   α: the angle between two blocks on the workpiece side.
//!   θ: the signed turn from the first block's end tangent to the second's
//!      start tangent (left positive);  α = 180° + s·θ  (s = +1 left, −1 right)
//!
//!   inside (α > 180°) or 90° ≤ α < 180°      α < 90° (outside, acute)
//!        ────────●  intersection of the         P1 ──▶ L1   extend r along A,
//!                │  two offset paths             ╲         join, come back r
//!   ─────────┐   │                                L2 ◀── P2  along B's start
//!   program  │                                    ▲
//! ```
//!
//! Lengths are mm in the compensation plane's (first, second) axes; `s`
//! is the side (+1 left of the direction of travel, −1 right) and `r` the
//! radius, never negative.

use std::f64::consts::PI;

/// Below this two lengths are equal, mm.
const EPS: f64 = 1e-9;
/// Below this two angles are equal, degrees (α exactly 90° or 180°).
const ANGLE_EPS_DEG: f64 = 1e-7;
/// Offsets that miss each other by less than this touch, mm. Programs are
/// rounded (to 0.001 mm by most CAM posts) and an arc's end may lie off its
/// radius by up to the arc tolerance (0.01 mm by default), so a tangent
/// junction of a line or an arc with an arc is tangent only to within that:
/// its offsets then pass within a few micrometres without meeting, and the
/// tangent point is the corner, not an over-cut.
const TOUCH_MM: f64 = 0.01;

/// A point or vector of the plane.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct V2 {
    pub x: f64,
    pub y: f64,
}

impl V2 {
    pub fn new(x: f64, y: f64) -> V2 {
        V2 { x, y }
    }
    fn add(self, o: V2) -> V2 {
        V2::new(self.x + o.x, self.y + o.y)
    }
    fn sub(self, o: V2) -> V2 {
        V2::new(self.x - o.x, self.y - o.y)
    }
    fn scale(self, k: f64) -> V2 {
        V2::new(self.x * k, self.y * k)
    }
    fn dot(self, o: V2) -> f64 {
        self.x * o.x + self.y * o.y
    }
    fn cross(self, o: V2) -> f64 {
        self.x * o.y - self.y * o.x
    }
    fn len(self) -> f64 {
        // Plane lengths never overflow: no need for `hypot`'s care (and cost).
        (self.x * self.x + self.y * self.y).sqrt()
    }
    fn unit(self) -> V2 {
        let l = self.len();
        if l < EPS {
            V2::default()
        } else {
            self.scale(1.0 / l)
        }
    }
    /// Turned 90° counter-clockwise: the left normal of a direction.
    fn left(self) -> V2 {
        V2::new(-self.y, self.x)
    }
    pub fn dist(self, o: V2) -> f64 {
        self.sub(o).len()
    }
}

/// A programmed path element in the plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Seg {
    pub a: V2,
    pub b: V2,
    /// `None` for a line; the centre and direction of an arc.
    pub arc: Option<(V2, bool)>,
    /// A line's unit direction, worked out once (every corner needs it
    /// twice for each of its two blocks); zero for an arc.
    dir: V2,
}

/// An offset path: a line through `p` along unit `d`, or a circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Offset {
    Line { p: V2, d: V2 },
    Circle { c: V2, r: f64 },
}

/// Why compensation cannot go on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Fault {
    /// An arc whose offset radius would be zero or negative.
    ArcTooSmall,
    /// Two offset paths that do not meet (the tool cannot reach the corner
    /// without cutting into the part).
    NoIntersection,
}

impl Seg {
    /// A line from `a` to `b`.
    pub fn line(a: V2, b: V2) -> Seg {
        Seg {
            a,
            b,
            arc: None,
            dir: b.sub(a).unit(),
        }
    }

    /// An arc from `a` to `b` about `c`, counter-clockwise when `ccw`.
    pub fn arc(a: V2, b: V2, c: V2, ccw: bool) -> Seg {
        Seg {
            a,
            b,
            arc: Some((c, ccw)),
            dir: V2::default(),
        }
    }

    /// The unit tangent at the start (`at_end` false) or end.
    pub fn tangent(&self, at_end: bool) -> V2 {
        match self.arc {
            None => self.dir,
            Some((c, ccw)) => {
                let p = if at_end { self.b } else { self.a };
                let radial = p.sub(c).unit().left();
                if ccw { radial } else { radial.scale(-1.0) }
            }
        }
    }

    /// The radius an arc's offset has with the tool on side `s` at `r`.
    pub fn offset_radius(&self, s: f64, r: f64) -> Option<f64> {
        let (c, ccw) = self.arc?;
        let sigma = if ccw { 1.0 } else { -1.0 };
        Some(self.a.dist(c) - s * sigma * r)
    }

    /// Fault when an arc cannot be offset (radius ≤ 0).
    pub fn check(&self, s: f64, r: f64) -> Result<(), Fault> {
        match self.offset_radius(s, r) {
            Some(rr) if rr <= EPS => Err(Fault::ArcTooSmall),
            _ => Ok(()),
        }
    }

    /// The offset path on side `s` at distance `r`.
    pub fn offset(&self, s: f64, r: f64) -> Offset {
        match self.arc {
            None => {
                let d = self.tangent(false);
                Offset::Line {
                    p: self.a.add(d.left().scale(s * r)),
                    d,
                }
            }
            Some((c, _)) => Offset::Circle {
                c,
                r: self.offset_radius(s, r).unwrap_or(0.0),
            },
        }
    }

    /// The point `r` from the start (or end) on side `s`, square to the path.
    pub fn perpendicular(&self, at_end: bool, s: f64, r: f64) -> V2 {
        let p = if at_end { self.b } else { self.a };
        p.add(self.tangent(at_end).left().scale(s * r))
    }

    /// Whether a compensated version from `s2` to `e2` runs the same way as
    /// the programmed path (a line not turned by more than 90°, an arc whose
    /// sweep does not reverse).
    pub fn keeps_direction(&self, s2: V2, e2: V2) -> bool {
        match self.compensated_sweep(s2, e2) {
            None => e2.sub(s2).dot(self.b.sub(self.a)) >= -EPS,
            Some(sweep) => sweep >= -1e-9,
        }
    }

    /// An arc's sweep (radians, in its direction) compensated from `s2` to
    /// `e2`: the programmed sweep less what the start moved on, plus what
    /// the end did. It can pass a full turn (a circle entered and left at
    /// outside corners). `None` for a line.
    fn compensated_sweep(&self, s2: V2, e2: V2) -> Option<f64> {
        let (c, ccw) = self.arc?;
        let sigma = if ccw { 1.0 } else { -1.0 };
        // Angle from p to q about c, in the arc's direction, in (−π, π].
        let ang = |p: V2, q: V2| {
            let (u, v) = (p.sub(c), q.sub(c));
            sigma * u.cross(v).atan2(u.dot(v))
        };
        let full = self.a.dist(self.b) < EPS;
        let sweep = if full {
            2.0 * PI
        } else {
            ang(self.a, self.b).rem_euclid(2.0 * PI)
        };
        Some(sweep - ang(self.a, s2) + ang(self.b, e2))
    }

    /// Whether the compensated arc from `s2` to `e2` shrinks to a point
    /// (its corners take all of its sweep): it must not leave as an arc
    /// from a point to itself, which reads as a full circle.
    pub fn collapses(&self, s2: V2, e2: V2) -> bool {
        self.arc.is_some()
            && s2.dist(e2) < 1e-6
            && self
                .compensated_sweep(s2, e2)
                .is_some_and(|sweep| sweep < PI)
    }

    /// Where to split the compensated arc from `s2` to `e2` in two, when
    /// one event from `s2` to `e2` would say another sweep than it has: a
    /// reader takes the sweep from `s2` to `e2` in the arc's direction, a
    /// full turn when they coincide, never more. The split point is half
    /// way round.
    pub fn split(&self, s2: V2, e2: V2) -> Option<V2> {
        let (c, ccw) = self.arc?;
        let sweep = self.compensated_sweep(s2, e2)?;
        if self.collapses(s2, e2) {
            return None;
        }
        let sigma = if ccw { 1.0 } else { -1.0 };
        let (u, v) = (s2.sub(c), e2.sub(c));
        let read = if s2.dist(e2) < EPS {
            2.0 * PI
        } else {
            (sigma * u.cross(v).atan2(u.dot(v))).rem_euclid(2.0 * PI)
        };
        if (read - sweep).abs() < 1e-6 {
            return None;
        }
        let (sin, cos) = (sigma * sweep / 2.0).sin_cos();
        Some(c.add(V2::new(u.x * cos - u.y * sin, u.x * sin + u.y * cos)))
    }
}

/// The kind of a corner, from the unit tangents alone (no trigonometry:
/// this runs for every block under compensation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// α = 180°: the blocks meet tangentially.
    Tangent,
    /// α > 180°: the path turns towards the tool.
    Inside,
    /// 90° ≤ α < 180°.
    Obtuse,
    /// α < 90°.
    Acute,
}

/// α's kind for directions `t1`, `t2` (unit) with the tool on side `s`.
pub(crate) fn kind(t1: V2, t2: V2, s: f64) -> Kind {
    // sin and cos of the turn θ; α = 180° + s·θ.
    let (sin, cos) = (t1.cross(t2), t1.dot(t2));
    let tiny = ANGLE_EPS_DEG.to_radians();
    if sin.abs() <= tiny {
        return if cos > 0.0 {
            Kind::Tangent
        } else {
            Kind::Inside
        };
    }
    if s * sin > 0.0 {
        Kind::Inside
    } else if cos >= -tiny {
        Kind::Obtuse
    } else {
        Kind::Acute
    }
}

/// Where two offset paths meet, the point nearest `near`.
pub(crate) fn intersect(o1: Offset, o2: Offset, near: V2) -> Option<V2> {
    let pick = |p: V2, q: V2| if p.dist(near) <= q.dist(near) { p } else { q };
    match (o1, o2) {
        (Offset::Line { p: p1, d: d1 }, Offset::Line { p: p2, d: d2 }) => {
            let den = d1.cross(d2);
            if den.abs() < 1e-12 {
                return None;
            }
            let t = p2.sub(p1).cross(d2) / den;
            Some(p1.add(d1.scale(t)))
        }
        (Offset::Line { p, d }, Offset::Circle { c, r })
        | (Offset::Circle { c, r }, Offset::Line { p, d }) => {
            let foot = p.add(d.scale(c.sub(p).dot(d)));
            if foot.dist(c) > r + TOUCH_MM {
                return None;
            }
            let h2 = r * r - foot.dist(c).powi(2);
            let h = h2.max(0.0).sqrt();
            Some(pick(foot.add(d.scale(h)), foot.sub(d.scale(h))))
        }
        (Offset::Circle { c: c1, r: r1 }, Offset::Circle { c: c2, r: r2 }) => {
            let dd = c1.dist(c2);
            if dd < EPS || dd > r1 + r2 + TOUCH_MM || dd < (r1 - r2).abs() - TOUCH_MM {
                return None;
            }
            let a = (r1 * r1 - r2 * r2 + dd * dd) / (2.0 * dd);
            let h = (r1 * r1 - a * a).max(0.0).sqrt();
            let u = c2.sub(c1).unit();
            let m = c1.add(u.scale(a));
            Some(pick(m.add(u.left().scale(h)), m.sub(u.left().scale(h))))
        }
    }
}

/// What the tool centre does at the corner between two compensated blocks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Corner {
    /// The first block ends, and the second starts, at this point.
    At(V2),
    /// α < 90° outside: the first block ends at `p1` and goes on straight
    /// to `l1`; a line joins `l1` to `l2`, then `p2`, where the second
    /// block starts.
    Around { p1: V2, l1: V2, l2: V2, p2: V2 },
}

/// The corner between `a` (side `sa`) and `b` (side `sb`) at radius `r`.
pub(crate) fn corner(a: &Seg, sa: f64, b: &Seg, sb: f64, r: f64) -> Result<Corner, Fault> {
    let (ta, tb) = (a.tangent(true), b.tangent(false));
    let meet = || intersect(a.offset(sa, r), b.offset(sb, r), a.b).ok_or(Fault::NoIntersection);
    if sa != sb {
        // A change of side: where the two offset paths cross; where they
        // do not (a straight line on), `a` ends square to its end and a line
        // joins the point square to `b`'s start (Fanuc).
        return Ok(match meet() {
            Ok(p) => Corner::At(p),
            Err(_) => {
                let (p1, p2) = (a.perpendicular(true, sa, r), b.perpendicular(false, sb, r));
                Corner::Around {
                    p1,
                    l1: p1,
                    l2: p2,
                    p2,
                }
            }
        });
    }
    match kind(ta, tb, sa) {
        Kind::Tangent => return Ok(Corner::At(a.perpendicular(true, sa, r))),
        Kind::Inside | Kind::Obtuse => return meet().map(Corner::At),
        Kind::Acute => {}
    }
    let (p1, p2) = (a.perpendicular(true, sa, r), b.perpendicular(false, sb, r));
    Ok(Corner::Around {
        p1,
        l1: p1.add(ta.scale(r)),
        l2: p2.sub(tb.scale(r)),
        p2,
    })
}

/// Where a start-up block `u` (a line, from the uncompensated point) ends
/// before block `b`: square to `b` at its start when the corner is outside
/// (type A), the intersection of the offsets when it is inside.
#[inline(never)]
pub(crate) fn startup(u: &Seg, b: &Seg, s: f64, r: f64) -> Result<V2, Fault> {
    if kind(u.tangent(true), b.tangent(false), s) != Kind::Inside || u.a.dist(u.b) < EPS {
        return Ok(b.perpendicular(false, s, r));
    }
    intersect(u.offset(s, r), b.offset(s, r), u.b).ok_or(Fault::NoIntersection)
}

/// Where the last compensated block `a` ends before the cancel block `c`
/// (a line to the uncompensated point): square to `a` at its end when the
/// corner is outside, the intersection with `c`'s offset when inside.
#[inline(never)]
pub(crate) fn cancel(a: &Seg, c: &Seg, s: f64, r: f64) -> Result<V2, Fault> {
    if kind(a.tangent(true), c.tangent(false), s) != Kind::Inside || c.a.dist(c.b) < EPS {
        return Ok(a.perpendicular(true, s, r));
    }
    intersect(a.offset(s, r), c.offset(s, r), a.b).ok_or(Fault::NoIntersection)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> V2 {
        V2::new(x, y)
    }

    fn close(p: V2, q: V2) -> bool {
        p.dist(q) < 1e-6
    }

    // Expected points from tests/fixtures/manual/README.comp.md, worked out
    // by hand there.

    #[test]
    fn line_line_outside_obtuse_meets_at_the_intersection() {
        // Figure i, G41: +X to 40,0, then towards 60,-30.
        let a = Seg::line(v(0.0, 0.0), v(40.0, 0.0));
        let b = Seg::line(v(40.0, 0.0), v(60.0, -30.0));
        let c = corner(&a, 1.0, &b, 1.0, 5.0).unwrap();
        assert!(
            matches!(c, Corner::At(p) if close(p, v(42.675919, 5.0))),
            "{c:?}"
        );
    }

    #[test]
    fn line_line_outside_acute_goes_around() {
        // Figure v, G41: +X to 40,0, then towards -0.5547,-0.83205.
        let a = Seg::line(v(0.0, 0.0), v(40.0, 0.0));
        let b = Seg::line(v(40.0, 0.0), v(40.0 - 20.0 * 0.554700, -20.0 * 0.832050));
        match corner(&a, 1.0, &b, 1.0, 5.0).unwrap() {
            Corner::Around { p1, l1, l2, p2 } => {
                assert!(close(p1, v(40.0, 5.0)));
                assert!(close(l1, v(45.0, 5.0)));
                assert!(close(p2, v(44.160251, -2.773501)));
                assert!(close(l2, v(46.933752, 1.386750)));
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn arcs_meet_where_their_offset_circles_cross() {
        // Figure iv, G41: G02 about 0,-30 then G02 about -20,-20 at 0,0.
        let a = Seg::arc(v(-30.0, -30.0), v(0.0, 0.0), v(0.0, -30.0), false);
        let b = Seg::arc(v(0.0, 0.0), v(20.0, -40.0), v(-20.0, -20.0), false);
        let c = corner(&a, 1.0, &b, 1.0, 5.0).unwrap();
        assert!(
            matches!(c, Corner::At(p) if close(p, v(2.041279, 4.940423))),
            "{c:?}"
        );
    }

    #[test]
    fn startup_and_cancel_follow_type_a() {
        // i_line_line_g42: start-up from -20,-20 to 0,0 then +X, inside.
        let u = Seg::line(v(-20.0, -20.0), v(0.0, 0.0));
        let b = Seg::line(v(0.0, 0.0), v(40.0, 0.0));
        assert!(close(
            startup(&u, &b, -1.0, 5.0).unwrap(),
            v(2.071068, -5.0)
        ));
        // i_line_line_g41: start-up from 0,-20, outside: square to B.
        let u = Seg::line(v(0.0, -20.0), v(0.0, 0.0));
        assert!(close(startup(&u, &b, 1.0, 5.0).unwrap(), v(0.0, 5.0)));
        // Cancel outside: square to A's end.
        let a = Seg::line(v(40.0, 0.0), v(60.0, -30.0));
        let c = Seg::line(v(60.0, -30.0), v(60.0, -50.0));
        assert!(close(
            cancel(&a, &c, 1.0, 5.0).unwrap(),
            v(64.160251, -27.226499)
        ));
    }

    #[test]
    fn a_reversed_offset_and_a_too_small_arc_are_faults() {
        let bottom = Seg::line(v(20.0, -10.0), v(28.0, -10.0));
        assert!(!bottom.keeps_direction(v(25.0, -5.0), v(23.0, -5.0)));
        assert!(bottom.keeps_direction(v(23.0, -5.0), v(25.0, -5.0)));
        let small = Seg::arc(v(30.0, 0.0), v(30.0, -8.0), v(30.0, -4.0), false);
        assert_eq!(small.check(-1.0, 5.0), Err(Fault::ArcTooSmall));
        assert_eq!(small.check(1.0, 5.0), Ok(()));
    }
}
