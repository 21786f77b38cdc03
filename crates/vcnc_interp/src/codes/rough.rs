//! The passes of the rough turning and facing cycles G71/G72 (types I and
//! II), pure geometry on a profile: no interpreter, no events, so that
//! property tests can check it on thousands of shapes.
//!
//! Both cycles are one algorithm in a normalised frame (u across the cut
//! levels, v along the cuts): G71 has u = ±X, v = ±Z, G72 u = ±Z, v = ±X,
//! with signs such that the tool starts at A = (u_A, v_A) above and
//! behind the stock (u ≤ u_A, v ≤ v_A) and the part, the profile shifted
//! by the finishing allowance, lies below the profile chain.
//!
//! ```text
//!   u ▲ A ●─ ─ ─ ─ ─ ─ ─ ─ ─ ─ ─ ─ ─ ─      stock top u_A
//!     │   ┊ ◀━━━━━━━━━━━━━━━━━━━┓ 2        1 infeed to level u_k = u_A − k·Δd
//!     │  1┊━━━━━━━━━━━━━━━━━━━━━━▶╲ 3      2 cut along v while the chain is
//!     │   ┊     pocket (type II)    ╲ e       below the level
//!     │ A'●━━━━━━━━━━┓     ┏━━━━━━━━●B     3 retract e at 45°, back to v_A
//!     │   chain (profile + allowance)        (a pocket: over the top, u_A)
//!     └────────────────────────────────▶ v  last: one pass along the chain
//! ```
//!
//! The levels are u_A − k·Δd, every one strictly above the chain's lowest
//! point; at a level the tool cuts every interval of v where the chain is
//! below it (one for type I, several across pockets for type II). Only the
//! first interval of a level starts at the stock face v_A and is entered
//! with the profile's first move (G00 or G01); a pocket's is entered from
//! above (rapid over the stock top to the pocket, down to the previous
//! level, feed in), and a level with pockets returns over the stock top.
//! After the levels one pass follows the chain, then the tool goes back to
//! A: first across (u to u_A), then along (v to v_A).

use crate::plane::{P2, Seg, Xz, ZERO_MM};

/// Below this a cut is a sliver not worth a pass, mm: a level this close
/// above the chain's lowest point, an interval this short, a point this
/// close to the stock face. Looser than [`ZERO_MM`]: a level is u_A − k·Δd
/// and an interval's ends come from an arc's crossings (acos, cos, sin),
/// whose rounding is far above it, and a cut that exists only by that
/// rounding must not be made.
const SLIVER_MM: f64 = 1e-7;
/// Below this two parameters along an element, or two angles, are one
/// (fractions of an element or radians, not lengths): the ends of a sweep
/// and the pieces between crossings.
const PARAM_EPS: f64 = 1e-12;

/// Which cycle: the axis the levels step along.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Across {
    /// G71: levels in X, cuts along Z.
    X,
    /// G72: levels in Z, cuts along X.
    Z,
}

/// The normalised frame of a cycle: (u, v) from (X, Z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    pub across: Across,
    pub su: f64,
    pub sv: f64,
}

impl Frame {
    /// (u, v) of a program point.
    pub fn uv(&self, p: Xz) -> P2 {
        match self.across {
            Across::X => P2(self.su * p.0, self.sv * p.1),
            Across::Z => P2(self.su * p.1, self.sv * p.0),
        }
    }

    /// The program point of (u, v).
    pub fn xz(&self, P2(u, v): P2) -> Xz {
        match self.across {
            Across::X => P2(u / self.su, v / self.sv),
            Across::Z => P2(v / self.sv, u / self.su),
        }
    }

    /// Whether an arc counter-clockwise in (X, Z) is counter-clockwise in
    /// (u, v) too: whether the map from one to the other keeps turns.
    fn keeps_turn(&self) -> bool {
        let det = self.su * self.sv;
        match self.across {
            // u from X and v from Z: the signs alone.
            Across::X => det > 0.0,
            // u from Z and v from X swap the axes, which reverses turns.
            Across::Z => det < 0.0,
        }
    }
}

/// An element in the normalised frame.
#[derive(Debug, Clone, Copy, PartialEq)]
struct USeg {
    a: P2,
    b: P2,
    /// Centre, radius, start angle, signed sweep (radians, from +u to +v).
    arc: Option<(P2, f64, f64, f64)>,
}

impl USeg {
    fn of(s: &Seg, f: &Frame) -> USeg {
        let (a, b) = (f.uv(s.start()), f.uv(s.end()));
        let arc = s.arc_of().map(|(c, ccw_xz)| {
            let c = f.uv(c);
            let ccw = ccw_xz == f.keeps_turn();
            let r = (a - c).hypot();
            let t0 = (a - c).angle();
            let t1 = (b - c).angle();
            let tau = std::f64::consts::TAU;
            let mut sweep = if ccw {
                (t1 - t0).rem_euclid(tau)
            } else {
                -(t0 - t1).rem_euclid(tau)
            };
            if sweep.abs() < PARAM_EPS {
                sweep = if ccw { tau } else { -tau };
            }
            (c, r, t0, sweep)
        });
        USeg { a, b, arc }
    }

    /// The point at parameter t ∈ [0, 1].
    fn at(&self, t: f64) -> P2 {
        match self.arc {
            Some((c, r, t0, sweep)) => {
                let th = t0 + sweep * t;
                P2(c.0 + r * th.cos(), c.1 + r * th.sin())
            }
            None => self.a + (self.b - self.a) * t,
        }
    }

    /// Parameters in (0, 1) where u crosses `level`, sorted.
    fn crossings(&self, level: f64) -> Vec<f64> {
        let mut ts = Vec::new();
        match self.arc {
            Some((c, r, t0, sweep)) => {
                let k = (level - c.0) / r;
                if k.abs() <= 1.0 {
                    let base = k.acos();
                    for th in [base, -base] {
                        // Every angle of the sweep with this cosine.
                        for turn in -2..=2 {
                            let t = (th + f64::from(turn) * std::f64::consts::TAU - t0) / sweep;
                            if t > 0.0 && t < 1.0 {
                                ts.push(t);
                            }
                        }
                    }
                }
            }
            None => {
                let du = self.b.0 - self.a.0;
                if du.abs() > ZERO_MM {
                    let t = (level - self.a.0) / du;
                    if t > 0.0 && t < 1.0 {
                        ts.push(t);
                    }
                }
            }
        }
        ts.sort_by(f64::total_cmp);
        ts
    }

    /// The lowest u of the element.
    fn min_u(&self) -> f64 {
        let mut m = self.a.0.min(self.b.0);
        if let Some((c, r, t0, sweep)) = self.arc
            && sweeps_through(t0, sweep, std::f64::consts::PI)
        {
            m = m.min(c.0 - r);
        }
        m
    }
}

/// Whether the sweep from `t0` by `sweep` passes angle `th` (strictly inside).
fn sweeps_through(t0: f64, sweep: f64, th: f64) -> bool {
    let tau = std::f64::consts::TAU;
    let d = if sweep >= 0.0 {
        (th - t0).rem_euclid(tau)
    } else {
        (t0 - th).rem_euclid(tau)
    };
    d > PARAM_EPS && d < sweep.abs() - PARAM_EPS
}

/// Why a profile cannot be cut, and which element (0 = the first).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Unfit {
    pub elem: usize,
    pub why: &'static str,
}

/// Checks the monotonicity a cycle needs on the profile (not the approach
/// from A): v never increases, and for type I u never decreases, each
/// within a micrometre (an arc that starts a hair past the vertical is
/// monotone for any tool).
pub(crate) fn check_monotone(segs: &[Seg], f: &Frame, type_one: bool) -> Result<(), Unfit> {
    const TOL: f64 = 1e-6;
    for (k, s) in segs.iter().enumerate() {
        let u = USeg::of(s, f);
        // The points where u or v may turn: the ends and, on an arc, the
        // angles where u or v is extreme, in the order of the path.
        let mut pts = vec![u.a];
        if let Some((c, r, t0, sweep)) = u.arc {
            let tau = std::f64::consts::TAU;
            let mut turns: Vec<f64> = [
                0.0,
                std::f64::consts::FRAC_PI_2,
                std::f64::consts::PI,
                -std::f64::consts::FRAC_PI_2,
            ]
            .iter()
            .filter(|th| sweeps_through(t0, sweep, **th))
            .map(|th| {
                if sweep >= 0.0 {
                    (th - t0).rem_euclid(tau)
                } else {
                    (t0 - th).rem_euclid(tau)
                }
            })
            .collect();
            turns.sort_by(f64::total_cmp);
            for d in turns {
                let th = t0 + d * sweep.signum();
                pts.push(P2(c.0 + r * th.cos(), c.1 + r * th.sin()));
            }
        }
        pts.push(u.b);
        for w in pts.windows(2) {
            let (p, q) = (w[0], w[1]);
            if q.1 - p.1 > TOL {
                return Err(Unfit {
                    elem: k,
                    why: "the profile turns back along the cut direction (it must be monotone along the cutting axis)",
                });
            }
            if type_one && q.0 - p.0 < -TOL {
                return Err(Unfit {
                    elem: k,
                    why: "the profile is not monotone across the cuts, which type I needs (give the first block both X and Z for type II)",
                });
            }
        }
    }
    Ok(())
}

/// How a rough pass step moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Step {
    Rapid,
    Feed,
    /// The profile's first move (G00 or G01 as its block says).
    Approach,
    /// Along a profile element (a line or an arc).
    Along(Seg),
}

/// The data of one G71/G72.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rough {
    pub frame: Frame,
    /// Depth of cut Δd, mm (radius for G71).
    pub depth: f64,
    /// Retract e, mm.
    pub retract: f64,
}

/// Most moves one G71/G72 may make (the block's events are held).
pub(crate) const MAX_MOVES: usize = 200_000;

/// The roughing moves (program points) of G71/G72 from `a` over the
/// chain `segs` (already shifted by the finishing allowance, the first
/// element the approach from A), or `None` when they would be more than
/// [`MAX_MOVES`].
pub(crate) fn rough_passes(a: Xz, segs: &[Seg], r: &Rough) -> Option<Vec<(Step, Xz)>> {
    let useg: Vec<USeg> = segs.iter().map(|s| USeg::of(s, &r.frame)).collect();
    let P2(ua, va) = r.frame.uv(a);
    let u_min = useg.iter().map(USeg::min_u).fold(f64::INFINITY, f64::min);
    let mut p = Passes {
        r,
        ua,
        va,
        pos: P2(ua, va),
        out: Vec::new(),
    };
    let mut prev_level = ua;
    for k in 1u32.. {
        let level = ua - f64::from(k) * r.depth;
        if level <= u_min + SLIVER_MM {
            break;
        }
        let spans = below(&useg, level, va);
        if spans.is_empty() {
            // Nothing below this level inside the stock (the chain's lowest
            // point is in front of it), so nothing below the next either.
            break;
        }
        p.level(level, prev_level, &spans);
        if p.out.len() > MAX_MOVES {
            return None;
        }
        prev_level = level;
    }
    p.last_pass(a, segs);
    (p.out.len() <= MAX_MOVES).then_some(p.out)
}

/// The moves of G71/G72 being written, in the normalised frame.
struct Passes<'r> {
    r: &'r Rough,
    ua: f64,
    va: f64,
    /// Where the tool is, (u, v).
    pos: P2,
    out: Vec<(Step, Xz)>,
}

impl Passes<'_> {
    fn push(&mut self, step: Step, uv: P2) {
        self.out.push((step, self.r.frame.xz(uv)));
    }

    /// One level: every interval cut, then back towards the face.
    fn level(&mut self, level: f64, prev_level: f64, spans: &[(f64, f64)]) {
        let (ua, va) = (self.ua, self.va);
        for (j, &(v_in, v_out)) in spans.iter().enumerate() {
            if j == 0 && v_in >= va - SLIVER_MM {
                // From the face, with the profile's first move.
                self.push(Step::Approach, P2(level, va));
            } else {
                // A pocket: over the stock top to it, down to the level
                // above (already cut there), feed in.
                if (self.pos.0 - ua).abs() > ZERO_MM {
                    self.push(Step::Rapid, P2(ua, self.pos.1));
                }
                self.push(Step::Rapid, P2(ua, v_in));
                self.push(Step::Rapid, P2(prev_level, v_in));
                self.push(Step::Feed, P2(level, v_in));
            }
            self.push(Step::Feed, P2(level, v_out));
            // The 45° retract by e (not past where the cut began).
            let e = self.r.retract;
            self.pos = P2(level + e, (v_out + e).min(v_in));
            self.push(Step::Rapid, self.pos);
        }
        let single_at_face =
            spans.len() == 1 && spans.first().is_some_and(|s| s.0 >= va - SLIVER_MM);
        if single_at_face {
            self.pos = P2(self.pos.0, va);
            self.push(Step::Rapid, self.pos);
        } else {
            self.push(Step::Rapid, P2(ua, self.pos.1));
            self.pos = P2(ua, va);
            self.push(Step::Rapid, self.pos);
        }
    }

    /// The last pass along the chain, then back to A (across, then along).
    fn last_pass(&mut self, a: Xz, segs: &[Seg]) {
        let f = self.r.frame;
        let Some(first) = segs.first() else {
            return;
        };
        if f.uv(first.end()).1 < self.va - SLIVER_MM {
            // The chain starts inside the stock: in along its approach from A.
            self.out.push((Step::Rapid, a));
        }
        self.out.push((Step::Approach, first.end()));
        for s in segs.iter().skip(1) {
            self.out.push((Step::Along(*s), s.end()));
        }
        let end = segs.last().map_or(self.va, |s| f.uv(s.end()).1);
        self.push(Step::Rapid, P2(self.ua, end));
        self.out.push((Step::Rapid, a));
    }
}

/// The intervals (v_in ≥ v_out) where the chain is below `level`, within
/// v ≤ `va`, in the order the chain meets them.
fn below(segs: &[USeg], level: f64, va: f64) -> Vec<(f64, f64)> {
    let mut spans = Vec::new();
    let mut open: Option<f64> = None;
    let mut last_v = va;
    for s in segs {
        let mut ts = vec![0.0];
        ts.extend(s.crossings(level));
        ts.push(1.0);
        for w in ts.windows(2) {
            let (t0, t1) = (w[0], w[1]);
            if t1 - t0 < PARAM_EPS {
                continue;
            }
            let mid = s.at((t0 + t1) / 2.0);
            let (p0, p1) = (s.at(t0), s.at(t1));
            let is_below = mid.0 < level - ZERO_MM;
            match (open, is_below) {
                (None, true) => open = Some(p0.1.min(va)),
                (Some(v_in), false) => {
                    push_span(&mut spans, v_in, p0.1.min(va));
                    open = None;
                }
                _ => {}
            }
            last_v = p1.1.min(va);
        }
    }
    if let Some(v_in) = open {
        push_span(&mut spans, v_in, last_v);
    }
    spans
}

fn push_span(spans: &mut Vec<(f64, f64)>, v_in: f64, v_out: f64) {
    if v_in - v_out > SLIVER_MM {
        spans.push((v_in, v_out));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(from: (f64, f64), to: (f64, f64)) -> Seg {
        Seg::line(P2(from.0, from.1), P2(to.0, to.1))
    }

    #[test]
    fn a_step_shaft_is_roughed_in_even_levels() {
        // OD, cutting toward -Z: A at X radius 25, Z 2; the chain from A
        // down to X 10 at the face, then a step at Z -20 up to 20, to Z -40.
        let f = Frame {
            across: Across::X,
            su: 1.0,
            sv: 1.0,
        };
        let chain = [
            line((25.0, 2.0), (10.0, 2.0)),
            line((10.0, 2.0), (10.0, -20.0)),
            line((10.0, -20.0), (20.0, -20.0)),
            line((20.0, -20.0), (20.0, -40.0)),
            line((20.0, -40.0), (26.0, -40.0)),
        ];
        let r = Rough {
            frame: f,
            depth: 4.0,
            retract: 1.0,
        };
        let moves = rough_passes(P2(25.0, 2.0), &chain, &r).unwrap();
        let cuts: Vec<Xz> = moves
            .iter()
            .filter(|(s, _)| *s == Step::Feed)
            .map(|(_, p)| *p)
            .collect();
        // Levels 21 (to Z -40: the chain is below 21 all along), 17, 13
        // (both to Z -20); level 9 is below the chain's lowest point 10.
        assert_eq!(
            cuts,
            vec![P2(21.0, -40.0), P2(17.0, -20.0), P2(13.0, -20.0)]
        );
    }

    #[test]
    fn monotone_checks_find_the_element() {
        let f = Frame {
            across: Across::X,
            su: 1.0,
            sv: 1.0,
        };
        let pocket = [
            line((10.0, 0.0), (10.0, -10.0)),
            line((10.0, -10.0), (8.0, -15.0)),
            line((8.0, -15.0), (12.0, -20.0)),
        ];
        assert_eq!(check_monotone(&pocket, &f, false), Ok(()));
        assert_eq!(
            check_monotone(&pocket, &f, true).map_err(|u| u.elem),
            Err(1)
        );
        let back = [
            line((10.0, 0.0), (10.0, -10.0)),
            line((10.0, -10.0), (12.0, -5.0)),
        ];
        assert_eq!(check_monotone(&back, &f, false).map_err(|u| u.elem), Err(1));
    }
}
