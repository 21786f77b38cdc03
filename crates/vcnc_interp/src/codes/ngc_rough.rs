//! LinuxCNC's lathe profile cycles in lathe mode: the roughing cycles
//! G71/G72 (and their variants .1 and .2) and the offset passes of the
//! finishing cycle G70 D E. Pure geometry: a profile in, the tool's moves
//! out; `mrc.rs` reads the blocks and runs the moves.
//!
//! The algorithm is rs274 2.9's (`interp_g7x.cc`, read to understand; this
//! is our own code), checked move by move against rs274 on the programs of
//! `tests/fixtures/linuxcnc_lathe_cycles`. It works in the plane (Z, X),
//! turned so that the profile runs towards −Z and up in X:
//!
//! ```text
//!   X ▲  S (start)                    the levels: X = S.x, S.x − I, …
//!     │   ╲  ┌─── rapid back, R at 45° each way
//!     │    ╲ │ ◀──────────────────┐  a pass: feed along −Z at a level
//!     │     ╲└────────────────────┘   until it meets the profile, rapid
//!     │      ╲______               ┐  up and back R·(1, 1), rapid to R
//!     │             ╲________      │  before the pass's start, down to it
//!     │   profile (offset D)  ╲____│  then the next level
//!     └──────────────────────────────▶ −Z
//! ```
//!
//! * The profile is the approach (the start point to the first point)
//!   then the subroutine's moves. G72 turns it by 90° first; then it is
//!   mirrored in Z and/or X so that its first point lies above and to the
//!   right of its last (`normalise`); the moves are turned back on output.
//! * The offset by D (`offset`) moves every element D away from the
//!   profile, on the start point's side, in steps no longer than half the
//!   shortest element; after each step an arc joins two elements that
//!   parted along Z, an element that turned back along Z is dropped, and
//!   neighbours are cut or extended to meet.
//! * The roughing (`Rough::pocket`) walks the profile from the start: it
//!   descends along a diving element to the next level, cuts along −Z to
//!   the first element that rises through the level, retracts, and goes
//!   on. At a rising element it follows the profile up; at the next
//!   diving element (a pocket, type II) it starts levels again there —
//!   G71/G72 cut every pocket, G71.1/G72.1 none (they follow the rising
//!   profile to the end), G71.2/G72.2 only those after the first.
//!
//! rs274's own tolerances are kept, each named below; they are what makes
//! the moves equal to its moves.

use crate::plane::{P2, Seg};

/// rs274's tolerance for a point on a level or an element (mm).
const ON_MM: f64 = 1e-6;
/// rs274's tolerance for "moving along Z" in a monotonic profile and for
/// an arc move too short to make (mm).
const SHORT_MM: f64 = 1e-3;
/// Two offset elements further apart than this along Z are joined by an
/// arc about their common corner (mm).
const GAP_MM: f64 = 1e-2;

/// Why a cycle cannot run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Fault {
    /// The profile, with rs274's own words where it has them.
    Profile(&'static str),
    /// The profile's element `k` (0 the approach to its first point).
    Element(usize, &'static str),
    /// More moves or levels than one block may make.
    TooMany,
}

use crate::dialect::RoughPockets as Pockets;

/// One move of a cycle, in the program's (X, Z) plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Cut {
    Rapid(P2),
    Feed(P2),
    /// An arc to `to` about `centre`, counter-clockwise in (X, Z) when
    /// `ccw_xz` (a G02 in G18's (Z, X)).
    Arc {
        to: P2,
        centre: P2,
        ccw_xz: bool,
    },
}

/// The profile in the cycle's frame (Z, X) and how that frame was turned.
#[derive(Debug, Clone)]
pub(crate) struct Path {
    segs: Vec<Seg>,
    /// G72: the profile was turned by −90° ((z, x) → (x, −z)).
    turned: bool,
    /// Mirrored in Z ((z, x) → (−z, x)).
    flip_z: bool,
    /// Mirrored in X ((z, x) → (z, −x)).
    flip_x: bool,
}

/// The roughing's parameters, in mm.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Roughing {
    pub pockets: Pockets,
    /// D: the distance kept from the profile.
    pub allowance: f64,
    /// I: the distance between levels (positive).
    pub step: f64,
    /// R: the retract after each pass, along each axis.
    pub retract: f64,
    /// G72: the levels run along Z.
    pub facing: bool,
}

impl Path {
    /// The approach from `start` to the profile's first point `first`,
    /// then the profile `segs`, all in the program's (X, Z) order.
    pub fn new(start: P2, first: P2, segs: &[Seg]) -> Path {
        let mut all = Vec::with_capacity(segs.len() + 1);
        all.push(Seg::line(start.swapped(), first.swapped()));
        all.extend(segs.iter().map(Seg::swapped));
        Path {
            segs: all,
            turned: false,
            flip_z: false,
            flip_x: false,
        }
    }

    fn map(&mut self, f: impl Fn(P2) -> P2, mirror: bool) {
        for s in &mut self.segs {
            *s = Seg::new(
                f(s.start()),
                f(s.end()),
                s.arc_of().map(|(c, ccw)| (f(c), ccw != mirror)),
            );
        }
    }

    /// Turns the profile by −90°, for G72 (before any mirroring).
    fn turn(&mut self) {
        self.map(|p| P2(p.1, -p.0), false);
        self.turned = true;
    }

    /// Mirrors the profile so that its first point is above (in X) and
    /// right of (in Z) its last.
    fn normalise(&mut self) {
        let (Some(first), Some(last)) = (self.segs.first(), self.segs.last()) else {
            return;
        };
        let d = first.end() - last.end();
        if d.1 > 0.0 {
            self.map(|p| P2(p.0, -p.1), true);
            self.flip_x = !self.flip_x;
        }
        if d.0 < 0.0 {
            self.map(|p| P2(-p.0, p.1), true);
            self.flip_z = !self.flip_z;
        }
    }

    /// A point of the cycle's frame in the program's (X, Z).
    fn out(&self, p: P2) -> P2 {
        let p = P2(
            if self.flip_z { -p.0 } else { p.0 },
            if self.flip_x { -p.1 } else { p.1 },
        );
        let p = if self.turned { P2(-p.1, p.0) } else { p };
        p.swapped()
    }

    fn out_cut(&self, c: Frame) -> Cut {
        match c {
            Frame::Rapid(p) => Cut::Rapid(self.out(p)),
            Frame::Feed(p) => Cut::Feed(self.out(p)),
            Frame::Arc { to, centre, ccw } => Cut::Arc {
                to: self.out(to),
                centre: self.out(centre),
                // Each mirror reverses the turn; (Z, X) → (X, Z) too.
                ccw_xz: ccw == (self.flip_z != self.flip_x),
            },
        }
    }

    /// G71/G72: the roughing passes from the start point.
    pub fn rough(mut self, r: &Roughing, max_moves: usize) -> Result<Vec<Cut>, Fault> {
        if r.facing {
            self.turn();
        }
        self.normalise();
        // The approach is straightened before the offset: the offset's
        // side is taken from it (rs274 2.9.0 does so; later versions too).
        self.check_monotonic()?;
        self.offset(r.allowance)?;
        let (Some(first), Some(last)) = (self.segs.first(), self.segs.last()) else {
            return Err(Fault::Profile("the profile has no moves"));
        };
        let start = first.start();
        // The profile ends below the start level: it climbs back to it.
        if last.end().1 < start.1 {
            let end = last.end();
            self.segs.push(Seg::line(end, P2(end.0, start.1)));
        }
        let lowest = self
            .segs
            .iter()
            .flat_map(|s| [s.start().1, s.end().1])
            .fold(start.1, f64::min);
        if r.step.is_nan() || r.step <= 0.0 || (start.1 - lowest) / r.step > MAX_LEVELS {
            return Err(Fault::TooMany);
        }
        let mut walk = Rough {
            segs: &self.segs,
            step: r.step,
            escape: r.retract,
            top: start.1,
            out: vec![Frame::Rapid(start)],
            max_moves,
        };
        walk.pocket(r.pockets, start)?;
        Ok(walk.out.iter().map(|c| self.out_cut(*c)).collect())
    }

    /// G70 D E P: `passes` passes along the profile offset from `d` … to
    /// `e` (the last), each a rapid to the start point and to the offset
    /// profile's first point, then the profile.
    pub fn finish(mut self, d: f64, e: f64, passes: u32) -> Result<Vec<Cut>, Fault> {
        // rs274: a start beyond the first point goes along Z first.
        let wrong_way = self.wrong_way();
        if wrong_way && let Some(first) = self.segs.first_mut() {
            // The approach then runs in X only: the offset meets the
            // first element at its offset start, not beyond it.
            *first = Seg::line(P2(first.end().0, first.start().1), first.end());
        }
        if self.segs.iter().any(|s| !monotonic(s)) {
            self.turn();
        }
        self.normalise();
        let mut out = Vec::new();
        for pass in (1..=passes).rev() {
            let distance = f64::from(pass - 1) * (d - e) / f64::from(passes) + e;
            let mut path = self.clone();
            path.offset(distance)?;
            let mut segs = path.segs.iter();
            if let Some(first) = segs.next() {
                let (a, b) = (self.out(first.start()), self.out(first.end()));
                // rs274 moves the approach's start there: each pass
                // returns to it, not to the start point.
                out.push(Cut::Rapid(a));
                out.push(Cut::Rapid(b));
            }
            out.extend(segs.map(|s| {
                self.out_cut(match s.arc_of() {
                    None => Frame::Feed(s.end()),
                    Some((centre, ccw)) => Frame::Arc {
                        to: s.end(),
                        centre,
                        ccw,
                    },
                })
            }));
        }
        Ok(out)
    }

    /// Plain G70's approach as rs274 runs it: when the dive from the
    /// start point to the profile's first point runs the wrong way along
    /// the profile, first along Z to the first point's Z (at the start's
    /// X); that corner, in the program's (X, Z).
    pub fn approach_corner(&self) -> Option<P2> {
        let first = self.segs.first()?;
        self.wrong_way()
            .then(|| P2(first.end().0, first.start().1).swapped())
    }

    /// Whether the start point lies beyond the profile's first point in
    /// Z, on the side the profile runs to (frame of `new`: (Z, X)).
    fn wrong_way(&self) -> bool {
        let (Some(first), Some(last)) = (self.segs.first(), self.segs.last()) else {
            return false;
        };
        let run = last.end().0 - first.end().0;
        (first.end().0 - first.start().0) * run < 0.0
    }

    /// rs274's first check: an approach that goes towards +Z starts at the
    /// first point's Z instead; every element must run towards −Z.
    fn check_monotonic(&mut self) -> Result<(), Fault> {
        if let Some(first) = self.segs.first_mut()
            && first.end().0 > first.start().0
        {
            *first = Seg::line(P2(first.end().0, first.start().1), first.end());
        }
        match self.segs.iter().position(|s| !monotonic(s)) {
            None => Ok(()),
            Some(k) => Err(Fault::Element(
                k,
                "the profile is not monotonic (rs274: \"Not monotonic\"): each element must run one way along the cuts, away from the start point",
            )),
        }
    }

    /// Moves the profile (not its approach) `distance` away from itself
    /// on the start point's side, in steps of at most half the shortest
    /// element.
    fn offset(&mut self, distance: f64) -> Result<(), Fault> {
        self.normalise();
        let (Some(first), Some(last)) = (self.segs.first(), self.segs.last()) else {
            return Err(Fault::Profile("the profile has no moves"));
        };
        let approach = first.end() - first.start();
        let across = last.start() - first.start();
        // The start point's side of the profile.
        let distance = if across.cross(approach) < 0.0 {
            -distance
        } else {
            distance
        };
        let approach = self.segs.remove(0);
        let segs = &mut self.segs;
        let mut done = 0.0;
        let mut rounds = 0;
        while done != distance {
            rounds += 1;
            if rounds > MAX_ROUNDS || segs.is_empty() {
                return Err(Fault::Profile(
                    "the offset profile vanishes: use a smaller D",
                ));
            }
            let shortest = segs.iter().map(size).fold(1e9, f64::min) / 2.0;
            let mut step = shortest.min((distance - done).abs());
            if distance < 0.0 {
                step = -step;
            }
            for s in segs.iter_mut() {
                *s = shifted(s, step);
            }
            segs.retain(|s| size(s) >= SHORT_MM);
            join_gaps(segs, step, distance > 0.0);
            meet(segs)?;
            done += step;
        }
        // Close what is left of the gaps between neighbours at midpoints.
        for k in 1..segs.len() {
            let mid = (segs[k - 1].end() + segs[k].start()) * 0.5;
            segs[k - 1] = segs[k - 1].with_end(mid);
            segs[k] = segs[k].with_start(mid);
        }
        let Some(first) = segs.first() else {
            return Err(Fault::Profile(
                "the offset profile vanishes: use a smaller D",
            ));
        };
        let approach = approach.with_end(first.start());
        segs.insert(0, approach);
        Ok(())
    }
}

/// Most offset steps (each at most half the shortest element).
const MAX_ROUNDS: usize = 10_000;

/// Most levels of one roughing cycle.
const MAX_LEVELS: f64 = 10_000.0;

/// rs274's size of an element: a line's length, an arc's chord or radius,
/// whichever is smaller.
fn size(s: &Seg) -> f64 {
    let chord = s.start().dist(s.end());
    match s.arc_of() {
        None => chord,
        Some((c, _)) => chord.min(s.start().dist(c)),
    }
}

/// Whether the element runs towards −Z (an arc: its ends on the side of
/// the centre it bulges to).
fn monotonic(s: &Seg) -> bool {
    let dz = s.end().0 - s.start().0;
    match s.arc_of() {
        None => dz <= SHORT_MM,
        Some((c, ccw)) => {
            let (entry, exit) = (s.start().1 - c.1, s.end().1 - c.1);
            let side = if ccw { 1.0 } else { -1.0 };
            side * entry >= -SHORT_MM && side * exit >= -SHORT_MM && dz <= -SHORT_MM
        }
    }
}

/// The element moved `d` to the left of its direction (a line), or its
/// radius grown by `d` for a counter-clockwise arc (shrunk for clockwise).
fn shifted(s: &Seg, d: f64) -> Seg {
    match s.arc_of() {
        None => {
            let back = (s.start() - s.end()).unit();
            // i·d·(start − end)/|start − end|
            let by = P2(-back.1, back.0) * d;
            Seg::line(s.start() + by, s.end() + by)
        }
        Some((c, ccw)) => {
            let r = s.start().dist(c);
            let k = (r + if ccw { d } else { -d }) / r;
            Seg::arc(c + (s.start() - c) * k, c + (s.end() - c) * k, c, ccw)
        }
    }
}

/// After an offset step of `step`: an arc (counter-clockwise when `ccw`)
/// about the corner the two elements shared joins neighbours that parted
/// by more than [`GAP_MM`] along Z.
fn join_gaps(segs: &mut Vec<Seg>, step: f64, ccw: bool) {
    let mut k = 0;
    while k + 1 < segs.len() {
        let (a, b) = (segs[k], segs[k + 1]);
        if a.end().0 - b.start().0 > GAP_MM {
            let corner = (shifted(&a, -step).end() + shifted(&b, -step).start()) * 0.5;
            segs.insert(k + 1, Seg::arc(a.end(), b.start(), corner, ccw));
            k += 1;
        }
        k += 1;
    }
}

/// After an offset step: drops an element that turned back along Z (the
/// shorter of it and the one before) or became too short, and makes
/// neighbours meet. Restarts from the front after a drop, as rs274 does.
fn meet(segs: &mut Vec<Seg>) -> Result<(), Fault> {
    let mut k = 0;
    while k + 1 < segs.len() {
        if !monotonic(&segs[k]) {
            if k == 0 || size(&segs[k]) < size(&segs[k - 1]) {
                segs.remove(k);
            } else {
                segs.remove(k - 1);
            }
            k = 0;
            if segs.len() < 2 {
                return Ok(());
            }
        }
        if size(&segs[k]) < SHORT_MM {
            segs.remove(k);
            // rs274 goes on with the second element.
            k = 1;
            continue;
        }
        let (a, b) = meeting(&segs[k], &segs[k + 1])?;
        segs[k] = a;
        segs[k + 1] = b;
        k += 1;
    }
    Ok(())
}

/// `a` and `b` cut or extended to meet: two lines at their crossing, a
/// line and an arc at the crossing nearest `b`'s start, two arcs turning
/// the same way at the crossing left of the line from `b`'s centre to
/// `a`'s (arcs turning opposite ways are left as they are).
fn meeting(a: &Seg, b: &Seg) -> Result<(Seg, Seg), Fault> {
    let p = match (a.arc_of(), b.arc_of()) {
        (None, None) => {
            let d = (b.start() - b.end()).unit();
            let (ps, pe) = (a.start() - b.end(), a.end() - b.end());
            let (hs, he) = (d.cross(ps), d.cross(pe));
            if hs - he == 0.0 {
                return Err(Fault::Profile(
                    "two neighbouring lines of the offset profile are parallel (rs274: \"Cannot intersect parallel lines\"): join them into one block",
                ));
            }
            a.start() + (a.end() - a.start()) * (hs / (hs - he))
        }
        (Some((c, _)), None) => {
            if b.start().dist(a.end()) < ON_MM {
                return Ok((*a, *b));
            }
            line_circle(b.end(), b.start() - b.end(), c, c.dist(a.end()), b.start())
        }
        (None, Some((c, _))) => {
            if b.start().dist(a.end()) < ON_MM {
                return Ok((*a, *b));
            }
            line_circle(a.end(), a.start() - a.end(), c, c.dist(b.end()), b.start())
        }
        (Some((ca, ccw_a)), Some((cb, ccw_b))) => {
            if ccw_a != ccw_b {
                return Ok((*a, *b));
            }
            let (rb, ra, dc) = (b.start().dist(cb), a.start().dist(ca), cb.dist(ca));
            let cos = (dc * dc + rb * rb - ra * ra) / 2.0 / rb / dc;
            let sin = (1.0 - (cos * cos).min(1.0)).sqrt();
            let u = (ca - cb) * (rb / dc);
            cb + P2(u.0 * cos - u.1 * sin, u.0 * sin + u.1 * cos)
        }
    };
    Ok((a.with_end(p), b.with_start(p)))
}

/// Where the line through `p` along `dir` meets the circle about `c` of
/// radius `r` (at the foot of the perpendicular when it misses), the
/// crossing nearest `near`.
fn line_circle(p: P2, dir: P2, c: P2, r: f64, near: P2) -> P2 {
    let u = dir.unit();
    let foot = p + u * (c - p).dot(u);
    let h = c.dist(foot);
    let b = (r * r - h * h).max(0.0).sqrt();
    let (s1, s2) = (foot + u * b, foot - u * b);
    if near.dist(s1) < near.dist(s2) {
        s1
    } else {
        s2
    }
}

/// Where the element crosses the level X = `x`, in rs274's order (a level
/// line gives both its ends).
fn crossings(s: &Seg, x: f64) -> ([f64; 2], usize) {
    let (a, e) = (s.start(), s.end());
    match s.arc_of() {
        None => {
            if a.1.min(e.1) > x + ON_MM || a.1.max(e.1) < x - ON_MM {
                ([0.0; 2], 0)
            } else if (a.1 - e.1).abs() < ON_MM {
                ([a.0, e.0], 2)
            } else {
                ([(x - a.1) / (e.1 - a.1) * (e.0 - a.0) + a.0, 0.0], 1)
            }
        }
        Some((c, ccw)) => {
            let r = a.dist(c);
            let q = -(x - r - c.1) * (x + r - c.1);
            if q < -ON_MM {
                return ([0.0; 2], 0);
            }
            let h = q.max(0.0).sqrt();
            let on = |p: P2| {
                let (from, to) = ((a - c).cross(p - c), (e - c).cross(p - c));
                if ccw {
                    from >= -ON_MM && to <= ON_MM
                } else {
                    from <= ON_MM && to >= -ON_MM
                }
            };
            let mut out = ([0.0; 2], 0);
            for z in [c.0 + h, c.0 - h] {
                if on(P2(z, x)) {
                    out.0[out.1] = z;
                    out.1 += 1;
                }
            }
            out
        }
    }
}

/// A move in the cycle's frame.
#[derive(Debug, Clone, Copy)]
enum Frame {
    Rapid(P2),
    Feed(P2),
    Arc { to: P2, centre: P2, ccw: bool },
}

/// The roughing walk over the normalised profile.
struct Rough<'a> {
    segs: &'a [Seg],
    step: f64,
    escape: f64,
    /// The start point's level: levels are `top − k·step`.
    top: f64,
    out: Vec<Frame>,
    max_moves: usize,
}

/// What a pass did.
enum Pass {
    /// It cut the level and came back.
    Cut,
    /// The next element starts right here: no pass, dive along it.
    Next,
    /// Nothing crosses the level.
    Open,
}

/// What a diving element did.
enum Dive {
    /// It descended (or was already at its end).
    Down,
    /// It does not descend from here.
    Rises,
}

impl Rough<'_> {
    fn push(&mut self, m: Frame) -> Result<(), Fault> {
        if self.out.len() >= self.max_moves {
            return Err(Fault::TooMany);
        }
        self.out.push(m);
        Ok(())
    }

    fn arc(&mut self, s: &Seg, to: P2) -> Result<(), Fault> {
        let (centre, ccw) = s.arc_of().unwrap_or_default();
        self.push(Frame::Arc { to, centre, ccw })
    }

    /// The walk from element `k` at `at`: levels while the profile
    /// descends, then along it while it rises; at the next descent, levels
    /// again (as `pockets` allows).
    fn pocket(&mut self, mut pockets: Pockets, mut at: P2) -> Result<(), Fault> {
        let mut k = 0;
        'pocket: loop {
            let mut x = self.top;
            if pockets == Pockets::AfterFirst {
                // The first descent follows the profile without levels.
                while let Some(s) = self.segs.get(k) {
                    if let Dive::Rises = self.dive(s, &mut at, -1e9, k == 0)? {
                        break;
                    }
                    k += 1;
                }
                pockets = Pockets::All;
            }
            while let Some(s) = self.segs.get(k) {
                while x > at.1 {
                    x -= self.step;
                }
                if let Dive::Rises = self.dive(s, &mut at, x, k == 0)? {
                    if pockets == Pockets::None {
                        for s in &self.segs[k..] {
                            self.climb_only(s, &mut at)?;
                        }
                        return Ok(());
                    }
                    for (j, s) in self.segs.iter().enumerate().skip(k) {
                        if self.climb(s, &mut at)? {
                            k = j;
                            continue 'pocket;
                        }
                    }
                    return Ok(());
                }
                if at.1 > x || (at.1 - x).abs() > ON_MM {
                    // Below this element's end: the next one.
                    k += 1;
                    continue;
                }
                match self.pass(k, at)? {
                    Pass::Cut => x -= self.step,
                    Pass::Next => k += 1,
                    // rs274 would try the same level again for ever.
                    Pass::Open => {
                        return Err(Fault::Profile(
                            "no part of the profile closes a level (the cycle would never end): check that the profile ends at or above the start point's level",
                        ));
                    }
                }
            }
            return Ok(());
        }
    }

    /// One pass at `at`'s level from element `k`: feed along −Z to the
    /// first element that crosses the level, retract, and come back.
    fn pass(&mut self, k: usize, at: P2) -> Result<Pass, Fault> {
        for j in k..self.segs.len() {
            let (zs, n) = crossings(&self.segs[j], at.1);
            if n == 0 {
                continue;
            }
            let z = if j == k { zs[n - 1] } else { zs[0] };
            let length = (z - at.0).abs();
            if length < ON_MM {
                if j == k {
                    continue;
                }
                return Ok(Pass::Next);
            }
            self.push(Frame::Feed(P2(z, at.1)))?;
            let s = (length / 2.0 / self.escape).min(1.0) * self.escape;
            self.push(Frame::Rapid(P2(z + s, at.1 + s)))?;
            self.push(Frame::Rapid(P2(at.0 - s, at.1 + s)))?;
            self.push(if k == 0 {
                Frame::Rapid(at)
            } else {
                Frame::Feed(at)
            })?;
            return Ok(Pass::Cut);
        }
        Ok(Pass::Open)
    }

    /// Descends along `s` from `at` to level `x` (or its end, if that is
    /// above the level); `fast` (the approach) at rapid.
    fn dive(&mut self, s: &Seg, at: &mut P2, x: f64, fast: bool) -> Result<Dive, Fault> {
        let e = s.end();
        match s.arc_of() {
            None => {
                if s.start().1 <= e.1 {
                    return Ok(Dive::Rises);
                }
                let to = if x < e.1 {
                    e
                } else {
                    let (zs, n) = crossings(s, x);
                    if n == 0 {
                        return Err(Fault::Profile(
                            "the level lies above the element it descends (rs274: \"x too large in straight dive\")",
                        ));
                    }
                    P2(zs[0], x)
                };
                self.push(if fast {
                    Frame::Rapid(to)
                } else {
                    Frame::Feed(to)
                })?;
                *at = to;
            }
            Some((c, ccw)) => {
                if at.dist(e) < SHORT_MM {
                    return Ok(Dive::Down);
                }
                let (zs, n) = crossings(s, x);
                let past = if ccw { at.0 > c.0 } else { at.0 <= c.0 };
                if past {
                    return Ok(Dive::Rises);
                }
                let z = if ccw { zs[..n].last() } else { zs[..n].first() };
                let beyond = z.is_none_or(|z| if ccw { *z > c.0 } else { *z < c.0 });
                if beyond {
                    self.arc(s, e)?;
                    *at = e;
                } else if let Some(z) = z {
                    let to = P2(*z, x);
                    if at.dist(to) > SHORT_MM {
                        self.arc(s, to)?;
                    }
                    *at = to;
                }
            }
        }
        Ok(Dive::Down)
    }

    /// Follows a rising element from `at`; true when it does not rise (a
    /// pocket starts there). A counter-clockwise arc is followed to its
    /// top at most, and always ends the climb.
    fn climb(&mut self, s: &Seg, at: &mut P2) -> Result<bool, Fault> {
        let e = s.end();
        match s.arc_of() {
            None => {
                if e.1 < s.start().1 {
                    return Ok(true);
                }
                if at.dist(s.start()) > ON_MM {
                    return Err(Fault::Profile(
                        "the profile cannot be followed from where the pass ended (rs274: \"How did we get here?\")",
                    ));
                }
                self.push(Frame::Feed(e))?;
                *at = e;
                Ok(false)
            }
            Some((c, false)) => {
                if at.0 > c.0 {
                    return Ok(true);
                }
                if at.dist(e) > SHORT_MM {
                    self.arc(s, e)?;
                }
                *at = e;
                Ok(false)
            }
            Some((c, true)) => {
                if at.0 < c.0 {
                    return Ok(true);
                }
                let to = top(s, c);
                if at.dist(to) > SHORT_MM {
                    self.arc(s, to)?;
                }
                *at = to;
                Ok(true)
            }
        }
    }

    /// G71.1: follows the rising parts of `s` from `at`'s level.
    fn climb_only(&mut self, s: &Seg, at: &mut P2) -> Result<(), Fault> {
        let e = s.end();
        let (zs, n) = crossings(s, at.1);
        match s.arc_of() {
            None => {
                if e.1 < s.start().1 || n == 0 {
                    return Ok(());
                }
                at.0 = zs[0];
                self.push(Frame::Feed(*at))?;
                self.push(Frame::Feed(e))?;
                *at = e;
            }
            Some((c, ccw)) => {
                if n == 0 {
                    return Ok(());
                }
                let z = if ccw { zs[0] } else { zs[n - 1] };
                if (ccw && z < c.0) || (!ccw && z > c.0) {
                    return Ok(());
                }
                at.0 = z;
                self.push(Frame::Feed(*at))?;
                let to = if ccw { top(s, c) } else { e };
                if at.dist(to) > SHORT_MM {
                    self.arc(s, to)?;
                }
                *at = to;
            }
        }
        Ok(())
    }
}

/// A counter-clockwise arc's end, or its top when it passes the top.
fn top(s: &Seg, c: P2) -> P2 {
    let e = s.end();
    if e.0 < c.0 {
        P2(c.0, c.1 + s.start().dist(c))
    } else {
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rough(start: P2, first: P2, segs: &[Seg], d: f64) -> Vec<Cut> {
        let r = Roughing {
            pockets: Pockets::All,
            allowance: d,
            step: 1.5,
            retract: 0.5,
            facing: false,
        };
        Path::new(start, first, segs).rough(&r, 1000).expect("cuts")
    }

    /// Worked by hand (X radius, Z): from (8, 2) straight down to the
    /// profile's first point (5, 2), along Z to −10 and up the face to
    /// X8. Levels X8 and X6.5 are cut to the face and retracted 0.5 at
    /// 45°; at X5 the level is the profile itself, which the tool follows.
    #[test]
    fn levels_run_from_the_start_down_to_the_profile_then_follow_it() {
        let segs = [
            Seg::line(P2(5.0, 2.0), P2(5.0, -10.0)),
            Seg::line(P2(5.0, -10.0), P2(8.0, -10.0)),
        ];
        use Cut::{Feed as F, Rapid as R};
        let want = [
            R(P2(8.0, 2.0)),
            R(P2(8.0, 2.0)),
            F(P2(8.0, -10.0)),
            R(P2(8.5, -9.5)),
            R(P2(8.5, 1.5)),
            R(P2(8.0, 2.0)),
            R(P2(6.5, 2.0)),
            F(P2(6.5, -10.0)),
            R(P2(7.0, -9.5)),
            R(P2(7.0, 1.5)),
            R(P2(6.5, 2.0)),
            R(P2(5.0, 2.0)),
            F(P2(5.0, -10.0)),
            F(P2(8.0, -10.0)),
        ];
        assert_eq!(rough(P2(8.0, 2.0), P2(5.0, 2.0), &segs, 0.0), want);
    }

    /// D moves the profile towards the start point's side: the line along
    /// Z goes up by D, the face towards +Z by D, and they meet at
    /// (5 + D, −10 + D); the approach still starts at the start point, and
    /// the profile, ending below it, climbs back to its level.
    #[test]
    fn the_allowance_moves_the_profile_towards_the_start_point() {
        let segs = [
            Seg::line(P2(5.0, 2.0), P2(5.0, -10.0)),
            Seg::line(P2(5.0, -10.0), P2(8.0, -10.0)),
        ];
        let cuts = rough(P2(9.0, 2.0), P2(5.0, 2.0), &segs, 0.25);
        let tail: Vec<Cut> = cuts.iter().rev().take(3).rev().copied().collect();
        assert_eq!(
            tail,
            [
                Cut::Feed(P2(5.25, -9.75)),
                Cut::Feed(P2(8.0, -9.75)),
                Cut::Feed(P2(9.0, -9.75))
            ]
        );
        assert_eq!(cuts.first(), Some(&Cut::Rapid(P2(9.0, 2.0))));
    }

    /// An element that turns back along the cuts is refused with its
    /// index (the approach is element 0).
    #[test]
    fn a_profile_that_turns_back_is_refused_at_its_element() {
        let segs = [
            Seg::line(P2(5.0, 0.0), P2(5.0, -5.0)),
            Seg::line(P2(5.0, -5.0), P2(7.0, -3.0)),
            Seg::line(P2(7.0, -3.0), P2(9.0, -14.0)),
        ];
        let r = Roughing {
            pockets: Pockets::All,
            allowance: 0.0,
            step: 1.0,
            retract: 0.5,
            facing: false,
        };
        let fault = Path::new(P2(11.0, 2.0), P2(5.0, 0.0), &segs).rough(&r, 1000);
        assert!(matches!(fault, Err(Fault::Element(2, _))), "{fault:?}");
    }

    /// G70 E: one pass along the profile moved E towards the start
    /// point, reached at rapid from it.
    #[test]
    fn a_finishing_pass_follows_the_offset_profile() {
        let segs = [
            Seg::line(P2(5.0, 2.0), P2(5.0, -10.0)),
            Seg::line(P2(5.0, -10.0), P2(8.0, -10.0)),
        ];
        let cuts = Path::new(P2(9.0, 3.0), P2(5.0, 2.0), &segs)
            .finish(0.5, 0.1, 1)
            .expect("cuts");
        assert_eq!(
            cuts,
            [
                Cut::Rapid(P2(9.0, 3.0)),
                Cut::Rapid(P2(5.1, 2.0)),
                Cut::Feed(P2(5.1, -9.9)),
                Cut::Feed(P2(8.0, -9.9)),
            ]
        );
    }
}
