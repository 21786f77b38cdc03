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
//! radius, never negative. Points, elements and the meeting of lines and
//! circles are the interpreter's one plane vocabulary (`crate::plane`);
//! what compensation asks of an element (its offset, whether a
//! compensated arc reverses, collapses or must be split) is here.

use crate::plane::{Curve, P2, Seg, ZERO_MM, intersect};
use std::f64::consts::PI;

/// Below this two angles are equal, degrees (α exactly 90° or 180°).
const ANGLE_EPS_DEG: f64 = 1e-7;
/// Below this a compensated arc's sweep has not reversed, radians: a sweep
/// is an angle, not a length, so [`ZERO_MM`] does not apply, though it has
/// the same value.
const SWEEP_EPS_RAD: f64 = 1e-9;
/// Below this a compensated arc's ends are one point (it collapses), mm,
/// and its sweep reads as the one it has, radians: corners move an arc's
/// ends by sums of offsets, which round to more than [`ZERO_MM`].
const SAME_END: f64 = 1e-6;
/// Offsets that miss each other by less than this touch, mm. Programs are
/// rounded (to 0.001 mm by most CAM posts) and an arc's end may lie off its
/// radius by up to the arc tolerance (0.01 mm by default), so a tangent
/// junction of a line or an arc with an arc is tangent only to within that:
/// its offsets then pass within a few micrometres without meeting, and the
/// tangent point is the corner, not an over-cut.
const TOUCH_MM: f64 = 0.01;

/// The smallest cosine between an entry arc's chord (start to the tool's
/// end) and its end radius that rs274 accepts.
const ENTRY_MIN_COS: f64 = 1e-4;

/// An entry arc (compensation starting on `arc`, `CompStart::LineOrArc`,
/// as rs274 runs it): the tool leaves the arc's start and ends `r` from its
/// programmed end along the radius, on side `s`, about a centre on the line
/// through the programmed centre and end, as far from the start as from
/// that new end. Returned as the arc about that centre whose offset on
/// side `s` at `r` is the tool's path (it ends at the programmed end, so
/// the corner to the next block is worked out as for any arc), with the
/// centre; `None` when the start is within `r` of the end or no such
/// centre exists (rs274: "Radius of cutter compensation entry arc is not
/// greater than the tool radius").
pub(crate) fn entry_arc(arc: &Seg, s: f64, r: f64) -> Option<(Seg, P2)> {
    let (c, ccw) = arc.arc_of()?;
    let (a, e) = (arc.start(), arc.end());
    if r <= ZERO_MM {
        // An empty register: the tool runs the programmed arc.
        return Some((Seg::arc(a, e, c, ccw), c));
    }
    if a.dist(e) <= r {
        return None;
    }
    let sigma = if ccw { 1.0 } else { -1.0 };
    // Unit vector from the end toward the centre; left of a CCW arc's
    // direction of travel.
    let u = (c - e).unit();
    let tool_end = e + u * (s * sigma * r);
    // The centre tool_end + λu is as far from a as from tool_end.
    let chord = tool_end - a;
    let along = u.dot(chord);
    // rs274 refuses an entry whose chord is this near square to the
    // radius (cosine below 1e-4): the centre would run off to kilometres.
    if along.abs() < ENTRY_MIN_COS * chord.dot(chord).sqrt() {
        return None;
    }
    let lambda = -chord.dot(chord) / (2.0 * along);
    let centre = tool_end + u * lambda;
    let tool_r = lambda.abs();
    // The arc whose offset is the tool's circle: radius tool_r + sσr.
    let prog_r = tool_r + s * sigma * r;
    if prog_r <= ZERO_MM || tool_r <= ZERO_MM {
        return None;
    }
    let start = centre + (a - centre) * (prog_r / tool_r);
    let end = centre + (e - centre).unit() * prog_r;
    Some((Seg::arc(start, end, centre, ccw), centre))
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

/// What compensation asks of a programmed element (`Seg` itself is the
/// plane module's).
impl Seg {
    /// The radius an arc's offset has with the tool on side `s` at `r`.
    pub fn offset_radius(&self, s: f64, r: f64) -> Option<f64> {
        let (c, ccw) = self.arc_of()?;
        let sigma = if ccw { 1.0 } else { -1.0 };
        Some(self.start().dist(c) - s * sigma * r)
    }

    /// Fault when an arc cannot be offset (radius ≤ 0).
    pub fn check(&self, s: f64, r: f64) -> Result<(), Fault> {
        match self.offset_radius(s, r) {
            Some(rr) if rr <= ZERO_MM => Err(Fault::ArcTooSmall),
            _ => Ok(()),
        }
    }

    /// The offset path on side `s` at distance `r`.
    pub fn offset(&self, s: f64, r: f64) -> Curve {
        match self.arc_of() {
            None => {
                let d = self.tangent(false);
                Curve::Line {
                    p: self.start() + d.left() * (s * r),
                    d,
                }
            }
            Some((c, _)) => Curve::Circle {
                c,
                r: self.offset_radius(s, r).unwrap_or(0.0),
            },
        }
    }

    /// Whether a compensated version from `s2` to `e2` runs the same way as
    /// the programmed path (a line not turned by more than 90°, an arc whose
    /// sweep does not reverse).
    pub fn keeps_direction(&self, s2: P2, e2: P2) -> bool {
        match self.compensated_sweep(s2, e2) {
            None => (e2 - s2).dot(self.end() - self.start()) >= -ZERO_MM,
            Some(sweep) => sweep >= -SWEEP_EPS_RAD,
        }
    }

    /// An arc's sweep (radians, in its direction) compensated from `s2` to
    /// `e2`: the programmed sweep less what the start moved on, plus what
    /// the end did. It can pass a full turn (a circle entered and left at
    /// outside corners). `None` for a line.
    fn compensated_sweep(&self, s2: P2, e2: P2) -> Option<f64> {
        let (c, ccw) = self.arc_of()?;
        let sigma = if ccw { 1.0 } else { -1.0 };
        // Angle from p to q about c, in the arc's direction, in (−π, π].
        let ang = |p: P2, q: P2| sigma * (p - c).angle_to(q - c);
        let full = self.start().dist(self.end()) < ZERO_MM;
        let sweep = if full {
            2.0 * PI
        } else {
            ang(self.start(), self.end()).rem_euclid(2.0 * PI)
        };
        Some(sweep - ang(self.start(), s2) + ang(self.end(), e2))
    }

    /// Whether the compensated arc from `s2` to `e2` shrinks to a point
    /// (its corners take all of its sweep): it must not leave as an arc
    /// from a point to itself, which reads as a full circle.
    #[inline]
    pub fn collapses(&self, s2: P2, e2: P2) -> bool {
        self.is_arc()
            && s2.dist(e2) < SAME_END
            && self
                .compensated_sweep(s2, e2)
                .is_some_and(|sweep| sweep < PI)
    }

    /// Where to split the compensated arc from `s2` to `e2` in two, when
    /// one event from `s2` to `e2` would say another sweep than it has: a
    /// reader takes the sweep from `s2` to `e2` in the arc's direction, a
    /// full turn when they coincide, never more. The split point is half
    /// way round.
    pub fn split(&self, s2: P2, e2: P2) -> Option<P2> {
        let (c, ccw) = self.arc_of()?;
        let sweep = self.compensated_sweep(s2, e2)?;
        if self.collapses(s2, e2) {
            return None;
        }
        let sigma = if ccw { 1.0 } else { -1.0 };
        let (u, v) = (s2 - c, e2 - c);
        let read = if s2.dist(e2) < ZERO_MM {
            2.0 * PI
        } else {
            (sigma * u.angle_to(v)).rem_euclid(2.0 * PI)
        };
        if (read - sweep).abs() < SAME_END {
            return None;
        }
        let (sin, cos) = (sigma * sweep / 2.0).sin_cos();
        Some(c + u.rotated(sin, cos))
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
pub(crate) fn kind(t1: P2, t2: P2, s: f64) -> Kind {
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

/// Where two offset paths meet, the point nearest `near` (offsets that
/// miss by less than [`TOUCH_MM`] touch).
fn meet(o1: Curve, o2: Curve, near: P2) -> Result<P2, Fault> {
    intersect(o1, o2, near, TOUCH_MM).ok_or(Fault::NoIntersection)
}

/// What the tool centre does at the corner between two compensated blocks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Corner {
    /// The first block ends, and the second starts, at this point.
    At(P2),
    /// α < 90° outside: the first block ends at `p1` and goes on straight
    /// to `l1`; a line joins `l1` to `l2`, then `p2`, where the second
    /// block starts.
    Around { p1: P2, l1: P2, l2: P2, p2: P2 },
}

/// The corner between `a` (side `sa`) and `b` (side `sb`) at radius `r`.
pub(crate) fn corner(a: &Seg, sa: f64, b: &Seg, sb: f64, r: f64) -> Result<Corner, Fault> {
    let (ta, tb) = (a.tangent(true), b.tangent(false));
    let offsets_meet = || meet(a.offset(sa, r), b.offset(sb, r), a.end());
    if sa != sb {
        // A change of side: where the two offset paths cross; where they
        // do not (a straight line on), `a` ends square to its end and a line
        // joins the point square to `b`'s start (Fanuc).
        return Ok(match offsets_meet() {
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
        Kind::Inside | Kind::Obtuse => return offsets_meet().map(Corner::At),
        Kind::Acute => {}
    }
    let (p1, p2) = (a.perpendicular(true, sa, r), b.perpendicular(false, sb, r));
    Ok(Corner::Around {
        p1,
        l1: p1 + ta * r,
        l2: p2 - tb * r,
        p2,
    })
}

/// Where a start-up block `u` (a line, from the uncompensated point) ends
/// before block `b`: square to `b` at its start when the corner is outside
/// (type A), the intersection of the offsets when it is inside.
#[inline(never)]
pub(crate) fn startup(u: &Seg, b: &Seg, s: f64, r: f64) -> Result<P2, Fault> {
    if kind(u.tangent(true), b.tangent(false), s) != Kind::Inside
        || u.start().dist(u.end()) < ZERO_MM
    {
        return Ok(b.perpendicular(false, s, r));
    }
    meet(u.offset(s, r), b.offset(s, r), u.end())
}

/// Where the last compensated block `a` ends before the cancel block `c`
/// (a line to the uncompensated point): square to `a` at its end when the
/// corner is outside, the intersection with `c`'s offset when inside.
#[inline(never)]
pub(crate) fn cancel(a: &Seg, c: &Seg, s: f64, r: f64) -> Result<P2, Fault> {
    if kind(a.tangent(true), c.tangent(false), s) != Kind::Inside
        || c.start().dist(c.end()) < ZERO_MM
    {
        return Ok(a.perpendicular(true, s, r));
    }
    meet(a.offset(s, r), c.offset(s, r), a.end())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> P2 {
        P2(x, y)
    }

    fn close(p: P2, q: P2) -> bool {
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
