//! From events to tool-tip moves: the one place that follows the event
//! stream (position, frame, tool, spindle) for the survey, the milling
//! Z-map and the lathe section alike.
//!
//! Events give machine coordinates of the controlled point; with a tool
//! length offset (G43, a lathe's T offset) that point is the spindle's
//! gauge point or the turret's, and the tool's tip is `machine −
//! tool_offset` (`frame` events carry the offset). Every move here is in
//! those tip coordinates, still machine-fixed, so that a stock placed once
//! stays put whatever work offsets the program changes later.
//!
//! Arcs in the XY plane stay arcs (the Z-map cuts them exactly); arcs in
//! other planes and NURBS curves become chords within [`CHORD_MM`], and a
//! lathe cuts every arc as chords (its polygons are chords anyway).

use crate::kernel::{Arc, Line};
use std::sync::Arc as Shared;
use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_core::{Event, Feed, FrameInfo, Loc, Machine, Plane, Pos};

/// Chord tolerance for curves cut as straight pieces, mm.
pub const CHORD_MM: f64 = 1e-3;

/// Most chords one curve becomes.
const MAX_CHORDS: usize = 100_000;

/// The path of one move, tip coordinates (x, y, z), mm.
#[derive(Debug, Clone, PartialEq)]
pub enum Path {
    /// Straight.
    Line(Line),
    /// An arc or helix in XY.
    Arc(Arc),
    /// Straight pieces through these points (the start excluded: it is
    /// `from`).
    Chords {
        /// Where the curve starts.
        from: [f64; 3],
        /// The points after it.
        points: Shared<[[f64; 3]]>,
    },
}

impl Path {
    /// The tip's start point.
    pub fn start(&self) -> [f64; 3] {
        match self {
            Path::Line(l) => l.a,
            Path::Arc(a) => a.point_at(0.0),
            Path::Chords { from, .. } => *from,
        }
    }

    /// The tip's end point.
    pub fn end(&self) -> [f64; 3] {
        match self {
            Path::Line(l) => l.b,
            Path::Arc(a) => a.point_at(1.0),
            Path::Chords { from, points } => points.last().copied().unwrap_or(*from),
        }
    }

    /// The straight pieces of a chorded path (a line is one; an arc none).
    pub fn lines(&self) -> Vec<Line> {
        match self {
            Path::Line(l) => vec![*l],
            Path::Arc(_) => Vec::new(),
            Path::Chords { from, points } => {
                let mut a = *from;
                points
                    .iter()
                    .map(|b| {
                        let l = Line { a, b: *b };
                        a = *b;
                        l
                    })
                    .collect()
            }
        }
    }

    /// The lowest tip height.
    pub fn min_z(&self) -> f64 {
        match self {
            Path::Line(l) => l.a[2].min(l.b[2]),
            Path::Arc(a) => a.z0.min(a.z0 + a.dz),
            Path::Chords { from, points } => points.iter().fold(from[2], |m, p| m.min(p[2])),
        }
    }
}

/// One move of the tool.
#[derive(Debug, Clone, PartialEq)]
pub struct Motion {
    /// The block it comes from.
    pub loc: Loc,
    /// A rapid (G00), not a cutting move.
    pub rapid: bool,
    /// The tip's path.
    pub path: Path,
    /// The tool in the spindle (`None`: no tool selected yet).
    pub tool: Option<u32>,
    /// How long the move takes at its programmed feed, s (0 for rapids
    /// and where the feed per revolution has no spindle speed).
    pub seconds: f64,
    /// A rotary axis moves: not simulated.
    pub rotary: bool,
    /// The frame in force.
    pub frame: FrameInfo,
}

/// Follows the event stream and turns motion events into [`Motion`]s.
#[derive(Debug, Clone)]
pub struct Tracker {
    axes: [Option<usize>; 3],
    rotary: Vec<usize>,
    /// Machine position of the controlled point.
    pos: Pos,
    /// The frame in force.
    pub frame: FrameInfo,
    /// The tool in the spindle.
    pub tool: Option<u32>,
    rpm: f64,
}

fn identity_frame() -> FrameInfo {
    FrameInfo {
        origin: Pos::default(),
        linear: None,
        tool_offset: Pos::default(),
    }
}

impl Tracker {
    /// A tracker at the machine's power-on position.
    pub fn new(machine: &Machine) -> Tracker {
        let rotary = [b'A', b'B', b'C']
            .iter()
            .filter_map(|l| machine.axis_of(*l))
            .collect();
        Tracker {
            axes: [
                machine.axis_of(b'X'),
                machine.axis_of(b'Y'),
                machine.axis_of(b'Z'),
            ],
            rotary,
            pos: machine.start,
            frame: identity_frame(),
            tool: None,
            rpm: 0.0,
        }
    }

    /// The tip (x, y, z) of the machine position `p` under the frame in
    /// force (a missing axis reads 0).
    pub fn tip(&self, p: &Pos) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (o, axis) in out.iter_mut().zip(self.axes) {
            if let Some(i) = axis {
                *o = p.get(i) - self.frame.tool_offset.get(i);
            }
        }
        out
    }

    /// The work-coordinate origin in tip space (x, y, z).
    pub fn origin(&self) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (o, axis) in out.iter_mut().zip(self.axes) {
            if let Some(i) = axis {
                *o = self.frame.origin.get(i);
            }
        }
        out
    }

    fn moves_rotary(&self, to: &Pos) -> bool {
        self.rotary
            .iter()
            .any(|i| (to.get(*i) - self.pos.get(*i)).abs() > 1e-9)
    }

    /// Seconds a cutting move of `len` mm takes at `feed`.
    fn seconds(&self, len: f64, feed: Feed) -> f64 {
        let per_min = match feed {
            Feed::PerMin(f) => f,
            Feed::PerRev(f) => f * self.rpm,
        };
        if per_min > 0.0 && per_min.is_finite() {
            len / per_min * 60.0
        } else {
            0.0
        }
    }

    /// Follows `e`; a motion event becomes a [`Motion`].
    pub fn event(&mut self, e: &Event) -> Option<Motion> {
        match e {
            Event::Frame { frame, .. } => {
                self.frame = *frame;
                None
            }
            Event::ToolChange { tool, .. } => {
                self.tool = Some(*tool);
                None
            }
            Event::Spindle { rpm, .. } => {
                self.rpm = if rpm.is_finite() { *rpm } else { 0.0 };
                None
            }
            Event::Rapid { loc, to, .. } => Some(self.straight(loc, to, None, true)),
            Event::Feed { loc, to, feed, .. } | Event::Skip { loc, to, feed, .. } => {
                Some(self.straight(loc, to, Some(*feed), false))
            }
            Event::Thread { loc, to, lead_mm } => {
                Some(self.straight(loc, to, Some(Feed::PerRev(*lead_mm)), false))
            }
            Event::Arc {
                loc,
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => Some(self.arc(loc, to, center, *plane, *dir, *feed)),
            Event::Nurbs { loc, curve, feed } => {
                let to = curve.points.last().copied().unwrap_or(self.pos);
                let points: Vec<[f64; 3]> = curve
                    .flatten(CHORD_MM)
                    .iter()
                    .map(|p| self.tip(p))
                    .collect();
                Some(self.chords(loc, &to, points, *feed))
            }
            _ => None,
        }
    }

    fn finish(&mut self, loc: &Loc, to: &Pos, path: Path, rapid: bool, seconds: f64) -> Motion {
        let rotary = self.moves_rotary(to);
        self.pos = *to;
        Motion {
            loc: loc.clone(),
            rapid,
            path,
            tool: self.tool,
            seconds,
            rotary,
            frame: self.frame,
        }
    }

    fn straight(&mut self, loc: &Loc, to: &Pos, feed: Option<Feed>, rapid: bool) -> Motion {
        let (a, b) = (self.tip(&self.pos), self.tip(to));
        let len = dist(a, b);
        let seconds = feed.map_or(0.0, |f| self.seconds(len, f));
        self.finish(loc, to, Path::Line(Line { a, b }), rapid, seconds)
    }

    fn chords(&mut self, loc: &Loc, to: &Pos, points: Vec<[f64; 3]>, feed: Feed) -> Motion {
        let from = self.tip(&self.pos);
        let mut len = 0.0;
        let mut a = from;
        for p in &points {
            len += dist(a, *p);
            a = *p;
        }
        let seconds = self.seconds(len, feed);
        let path = Path::Chords {
            from,
            points: points.into(),
        };
        self.finish(loc, to, path, false, seconds)
    }

    fn arc(
        &mut self,
        loc: &Loc,
        to: &Pos,
        center: &Pos,
        plane: Plane,
        dir: vcnc_core::ArcDir,
        feed: Feed,
    ) -> Motion {
        let [xi, yi, zi] = self.axes;
        let axes = match plane {
            Plane::Xy => (xi, yi, zi),
            Plane::Zx => (zi, xi, yi),
            Plane::Yz => (yi, zi, xi),
        };
        let (Some(a), Some(b)) = (axes.0, axes.1) else {
            return self.straight(loc, to, Some(feed), false);
        };
        let path = ArcPath::new(self.pos, *to, *center, PlaneAxes { a, b, n: axes.2 }, dir);
        let seconds = self.seconds(path.length(), feed);
        if plane == Plane::Xy && zi.is_some() && yi.is_some() {
            let off = |i: Option<usize>| i.map_or(0.0, |i| self.frame.tool_offset.get(i));
            let z0 = self.tip(&self.pos)[2];
            let arc = Arc {
                center: [path.center.0 - off(xi), path.center.1 - off(yi)],
                radius: path.radius,
                start_angle: path.start_angle,
                sweep: path.sweep,
                z0,
                dz: path.rise(),
            };
            // The end is the event's own, not the cosine's.
            let motion = self.finish(loc, to, Path::Arc(arc), false, seconds);
            return motion;
        }
        let points: Vec<[f64; 3]> = path
            .tessellate(CHORD_MM, MAX_CHORDS)
            .map(|p| self.tip(&p))
            .collect();
        let from = self.tip(&self.pos);
        self.finish(
            loc,
            to,
            Path::Chords {
                from,
                points: points.into(),
            },
            false,
            seconds,
        )
    }
}

/// Distance between two points.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
}
