//! [`PlotSink`]: the [`Sink`] that turns a run's events into a [`Plot`] —
//! the merged tool path, the programmed contour under cutter compensation,
//! and the marks (start, holes, tool changes, work origins and frames, the
//! alarm).
//!
//! It reads events only (no interpreter, no files), in one pass: merge
//! units follow the extents seen so far of what the picture is framed on
//! (the cuts, or everything: [`FitTo`]), which only grow, so early points
//! are merged at least as finely as the finished picture needs (see
//! `path.rs` for the rule). Vertices are dated by a [`Clock`], a sink fed
//! the same events: seconds, or a stamp (the CLI numbers the blocks) that
//! [`Plot::retime`] turns into the planner's seconds after the run, since
//! a look-ahead planner knows a block's time only some blocks later.

use crate::path::{ArcRec, Kind, Metric, NO_ARC, Path, Vertex, arc_path};
use crate::view::{AxisMap, P3, Projection};
use std::collections::HashSet;
use std::sync::Arc;
use vcnc_core::{Cycle, EndCode, Event, Feed, FrameInfo, Loc, Machine, Pos, Sink};

/// What a picture is framed on (`--fit`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitTo {
    /// The cuts (and holes, the programmed contour, the alarm): home, G53
    /// and tool-change moves leave the frame and are clipped at its edge.
    Cuts,
    /// Everything drawn.
    All,
}

/// How cuts are coloured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorBy {
    /// By the depth axis (Z; X on a lathe).
    Depth,
    /// By tool.
    Tool,
    /// By feed rate.
    Feed,
}

/// What the plot will be drawn on; decides the merge units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Space {
    /// A flat picture: the projection and the plot area in pixels.
    Flat {
        /// The view.
        projection: Projection,
        /// Width of the plot area, px.
        width_px: f64,
        /// Height of the plot area, px.
        height_px: f64,
    },
    /// The 3D page: one merge unit is the model's diagonal / `resolution`.
    Volume {
        /// Units across the model's diagonal.
        resolution: f64,
    },
}

/// Options of a [`PlotSink`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotOptions {
    /// Where it is drawn.
    pub space: Space,
    /// How cuts are coloured (cuts at different feeds merge only when
    /// colouring by something else).
    pub color: ColorBy,
    /// Most vertices kept per path (memory bound, ~48 bytes each).
    pub max_vertices: usize,
    /// Most marks of each kind kept (holes, tool changes).
    pub max_marks: usize,
    /// What the picture is framed on: the merge units follow its extents.
    pub fit: FitTo,
}

/// The time seam: a sink fed every event before the plot sees it, which
/// says where the program is. Its [`Clock::now`] dates each vertex: either
/// seconds from the start, or any stamp that grows with the program (the
/// CLI counts blocks) which [`Plot::retime`] turns into seconds once the
/// run is over. Stamps are kept as `f32`: block numbers stay exact to
/// 2²⁴ blocks and within a few blocks beyond.
pub trait Clock: Sink {
    /// Seconds (or the stamp) at the end of the last event.
    fn now(&self) -> f64;
}

/// A clock that never moves (no timing known).
#[derive(Debug, Default, Clone, Copy)]
pub struct NoClock;

impl Sink for NoClock {
    fn event(&mut self, _: &Event) {}
}

impl Clock for NoClock {
    fn now(&self) -> f64 {
        0.0
    }
}

/// A drilled hole or cycle position (a `hole` event).
#[derive(Debug, Clone, PartialEq)]
pub struct HoleMark {
    /// Centre at the Z point.
    pub at: P3,
    /// The cycle.
    pub cycle: Cycle,
    /// Source line.
    pub line: u32,
}

/// A tool change and where the tool was.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolMark {
    /// Position when the tool changed.
    pub at: P3,
    /// The new tool.
    pub tool: u32,
    /// Source line.
    pub line: u32,
}

/// A work origin from a `frame` event.
#[derive(Debug, Clone, PartialEq)]
pub struct OriginMark {
    /// Program zero in machine coordinates (without tool length offset).
    pub at: P3,
    /// Directions of the program's X and Y axes (rotation, mirror).
    pub x_dir: P3,
    /// See `x_dir`.
    pub y_dir: P3,
    /// Source line of the block that set it.
    pub line: u32,
}

/// A program frame in force from a point of the run on: how work
/// coordinates map to machine ones (`machine = linear · work + origin +
/// tool_offset`), for the page's readout in work coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameMark {
    /// The clock's stamp when it took effect (seconds after a retime).
    pub time_s: f32,
    /// Machine coordinates of program zero.
    pub origin: P3,
    /// Rotation, scaling and mirror (rows and columns x, y, z); `None`:
    /// the identity.
    pub linear: Option<[[f64; 3]; 3]>,
    /// The tool length (or a lathe's offset register) in force.
    pub tool_offset: P3,
}

/// Where and why the program alarmed.
#[derive(Debug, Clone, PartialEq)]
pub struct AlarmMark {
    /// Position when it stopped.
    pub at: P3,
    /// Stable code, e.g. `E303`.
    pub code: &'static str,
    /// The message.
    pub message: String,
    /// Line and column.
    pub line: u64,
    /// See `line`.
    pub column: u32,
}

/// Everything collected from a run.
#[derive(Debug, Clone)]
pub struct Plot {
    /// The tool path (starts with a jump to the power-on position).
    pub path: Path,
    /// The programmed contour of compensated blocks (empty without cutter
    /// compensation).
    pub contour: Path,
    /// Tools in order of first use: a vertex's `tool` i > 0 is `tools[i-1]`.
    pub tools: Vec<u32>,
    /// Called programs: a vertex's `file` i > 0 is `files[i-1]`.
    pub files: Vec<Arc<str>>,
    /// Holes marked (at most `max_marks`; holes closer than about a mark's
    /// size share one mark).
    pub holes: Vec<HoleMark>,
    /// Holes drilled, marked or not.
    pub hole_count: u64,
    /// Tool changes (at most `max_marks`).
    pub tool_changes: Vec<ToolMark>,
    /// Distinct work origins, in order (at most 64).
    pub origins: Vec<OriginMark>,
    /// Every frame change, in order (at most 65,536; later ones are not
    /// kept and `frames_complete` is false).
    pub frames: Vec<FrameMark>,
    /// For each vertex of `path` from `.0` on, the frame `frames[.1]` is
    /// in force (runs in vertex order; before the first run, no frame).
    pub frame_runs: Vec<(u32, u32)>,
    /// Whether every frame change was kept.
    pub frames_complete: bool,
    /// The alarm that stopped the program, if one did.
    pub alarm: Option<AlarmMark>,
    /// How the program ended, if it did.
    pub end: Option<EndCode>,
    /// Plot-space box of everything drawn (path, contour, marks).
    pub bounds: (P3, P3),
    /// Plot-space box of the cuts, the holes, the contour and the alarm
    /// (`None`: the program cut nothing).
    pub cut_bounds: Option<(P3, P3)>,
    /// The machine's travel limits on X, Y and Z, when the machine file
    /// gives both limits of each of them it has.
    pub limits: Option<(P3, P3)>,
    /// Motion events drawn (rapids and cuts).
    pub moves: u64,
    /// Cutting motion events drawn.
    pub cut_moves: u64,
    /// Time at the end of the run (the clock's), s.
    pub total_time_s: f64,
    /// Events seen.
    pub events: u64,
}

/// Most work origins marked.
const MAX_ORIGINS: usize = 64;
/// Most frame changes kept for the readout.
const MAX_FRAMES: usize = 1 << 16;
/// Size of the cell, in merge units, in which holes share one mark (a hole
/// mark is 12 px across).
const HOLE_CELL: f64 = 8.0;
/// Most points an arc is drawn with when it cannot stay a true arc.
const MAX_ARC_POINTS: usize = 4096;

/// Collects a [`Plot`] from events.
#[derive(Debug)]
pub struct PlotSink<C: Clock = NoClock> {
    opts: PlotOptions,
    map: AxisMap,
    clock: C,
    plot: Plot,
    pos: P3,
    rpm: f64,
    tool: u16,
    metric: Metric,
    /// Screen box (u, v) and depth range of what was framed so far.
    uv: Option<([f64; 3], [f64; 3])>,
    hole_cells: HashSet<[i64; 3]>,
}

/// f64 → f32 for stored attributes (times, feeds): rounding is intended.
#[allow(clippy::cast_possible_truncation)]
pub(crate) fn f32_of(v: f64) -> f32 {
    v as f32
}

/// A saturating u64 → u32 for line numbers.
fn line_of(loc: &Loc) -> u32 {
    u32::try_from(loc.line).unwrap_or(u32::MAX)
}

impl PlotSink<NoClock> {
    /// A sink for a run on `machine`, without timing.
    pub fn new(machine: &Machine, opts: PlotOptions) -> PlotSink<NoClock> {
        PlotSink::with_clock(machine, opts, NoClock)
    }
}

impl<C: Clock> PlotSink<C> {
    /// A sink for a run on `machine` whose times come from `clock`.
    pub fn with_clock(machine: &Machine, opts: PlotOptions, clock: C) -> PlotSink<C> {
        let map = AxisMap::of(machine);
        let start = map.p3(&machine.start);
        let feed_breaks = opts.color == ColorBy::Feed;
        let mut sink = PlotSink {
            opts,
            map,
            clock,
            plot: Plot {
                path: Path::new(opts.max_vertices, feed_breaks),
                contour: Path::new(opts.max_vertices, feed_breaks),
                tools: Vec::new(),
                files: Vec::new(),
                holes: Vec::new(),
                hole_count: 0,
                tool_changes: Vec::new(),
                origins: Vec::new(),
                frames: Vec::new(),
                frame_runs: Vec::new(),
                frames_complete: true,
                alarm: None,
                end: None,
                bounds: (start, start),
                cut_bounds: None,
                limits: travel_box(machine, &map),
                moves: 0,
                cut_moves: 0,
                total_time_s: 0.0,
                events: 0,
            },
            pos: start,
            rpm: 0.0,
            tool: 0,
            metric: Metric {
                rows: [[0.0; 3]; 3],
                visible: 3,
            },
            uv: None,
            hole_cells: HashSet::new(),
        };
        // Until something framed is seen, points are merged as finely as
        // an empty box asks (none is dropped).
        sink.metric = sink.metric_now();
        sink.extend(start, false);
        let v = sink.vertex(start, Kind::Jump, &Loc::default(), 0.0);
        sink.plot.path.push_line(v, &sink.metric);
        sink
    }

    /// The finished plot and the clock.
    pub fn into_parts(mut self) -> (Plot, C) {
        self.plot.path.finish();
        self.plot.contour.finish();
        self.plot.total_time_s = self.clock.now();
        self.plot.frame_runs = crate::retime::frame_runs(&self.plot.path, &self.plot.frames);
        (self.plot, self.clock)
    }

    /// The finished plot.
    pub fn into_plot(self) -> Plot {
        self.into_parts().0
    }

    /// Grows the boxes by `p` (`cut`: a point of a cut, a hole, the
    /// contour or the alarm) and updates the merge units.
    fn extend(&mut self, p: P3, cut: bool) {
        let (lo, hi) = &mut self.plot.bounds;
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
        if cut {
            let (lo, hi) = self.plot.cut_bounds.get_or_insert((p, p));
            for i in 0..3 {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        } else if self.opts.fit == FitTo::Cuts {
            // Outside the frame: merged at the frame's units, never coarser.
            return;
        }
        let q = match self.opts.space {
            Space::Flat { projection, .. } => {
                let (u, v) = projection.uv(p);
                [u, v, projection.depth_of(p)]
            }
            Space::Volume { .. } => p,
        };
        let (lo, hi) = self.uv.get_or_insert((q, q));
        let mut grew = false;
        for i in 0..3 {
            if q[i] < lo[i] || q[i] > hi[i] {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
                grew = true;
            }
        }
        if grew {
            self.metric = self.metric_now();
        }
    }

    /// Merge units for the extents seen so far.
    fn metric_now(&self) -> Metric {
        let (lo, hi) = self.uv.unwrap_or(([0.0; 3], [0.0; 3]));
        let span = |i: usize| hi[i] - lo[i];
        match self.opts.space {
            Space::Flat {
                projection,
                width_px,
                height_px,
            } => {
                // mm per pixel when the box is fitted into the plot area.
                let mm_px = (span(0) / width_px.max(1.0))
                    .max(span(1) / height_px.max(1.0))
                    .max(1e-9);
                // Half a colour step of a 64-step depth scale.
                let depth_unit = (span(2) / 64.0).max(1e-9);
                let s = 1.0 / mm_px;
                Metric {
                    rows: [
                        projection.u.map(|c| c * s),
                        projection.v.map(|c| c * s),
                        projection.depth.map(|c| c / depth_unit),
                    ],
                    visible: 2,
                }
            }
            Space::Volume { resolution } => {
                let diag = (span(0).powi(2) + span(1).powi(2) + span(2).powi(2)).sqrt();
                let s = resolution.max(1.0) / diag.max(1e-9);
                Metric {
                    rows: [[s, 0.0, 0.0], [0.0, s, 0.0], [0.0, 0.0, s]],
                    visible: 3,
                }
            }
        }
    }

    fn file_index(&mut self, loc: &Loc) -> u16 {
        let Some(f) = &loc.file else { return 0 };
        let files = &mut self.plot.files;
        let found = files
            .iter()
            .rposition(|g| Arc::ptr_eq(g, f) || **g == **f)
            .or_else(|| {
                (files.len() < usize::from(u16::MAX - 1)).then(|| {
                    files.push(f.clone());
                    files.len() - 1
                })
            });
        found
            .and_then(|i| u16::try_from(i + 1).ok())
            .unwrap_or(u16::MAX)
    }

    fn vertex(&mut self, at: P3, kind: Kind, loc: &Loc, feed: f64) -> Vertex {
        Vertex {
            at,
            kind,
            arc: NO_ARC,
            tool: self.tool,
            file: self.file_index(loc),
            line: line_of(loc),
            feed_mm_per_min: f32_of(feed),
            time_s: f32_of(self.clock.now()),
        }
    }

    fn feed_mm_per_min(&self, feed: &Feed) -> f64 {
        match feed {
            Feed::PerMin(f) => *f,
            Feed::PerRev(f) => f * self.rpm,
        }
    }

    fn line(&mut self, loc: &Loc, to: &Pos, kind: Kind, feed: f64) {
        let p = self.map.p3(to);
        let cut = kind == Kind::Cut;
        self.count(cut);
        if cut {
            self.extend(self.pos, true);
        }
        self.extend(p, cut);
        let v = self.vertex(p, kind, loc, feed);
        self.plot.path.push_line(v, &self.metric);
        self.pos = p;
    }

    /// Adds the arc from `from` to `v.at` to `path` (the tool path or the
    /// contour): a true arc when the flat view shows its plane undistorted,
    /// else points within half a merge unit of it.
    fn arc_into(&mut self, contour: bool, from: P3, v: Vertex, rec: ArcRec) {
        let arc = arc_path(from, v.at, &rec);
        let (lo, hi) = arc.bounds(3);
        self.extend([lo.get(0), lo.get(1), lo.get(2)], true);
        self.extend([hi.get(0), hi.get(1), hi.get(2)], true);
        let metric = self.metric;
        let true_arc = match self.opts.space {
            Space::Flat { projection, .. } => {
                projection.arc_plane == Some(rec.plane) && arc.rise().abs() < 1e-9
            }
            Space::Volume { .. } => false,
        };
        let path = if contour {
            &mut self.plot.contour
        } else {
            &mut self.plot.path
        };
        if true_arc {
            path.push_arc(v, rec, &metric);
            return;
        }
        let tol_mm = path.tolerance() * metric.unit_mm();
        for q in arc.tessellate(tol_mm, MAX_ARC_POINTS) {
            let mut w = v;
            w.at = [q.get(0), q.get(1), q.get(2)];
            path.push_line(w, &metric);
        }
    }

    fn contour(&mut self, loc: &Loc, from: &Pos, to: &Pos, arc: Option<ArcRec>) {
        let (from, to) = (self.map.p3(from), self.map.p3(to));
        self.extend(from, true);
        self.extend(to, true);
        let joined = self
            .plot
            .contour
            .last()
            .is_some_and(|l| (0..3).all(|i| (l.at[i] - from[i]).abs() < 1e-9));
        if !joined {
            let jump = self.vertex(from, Kind::Jump, loc, 0.0);
            self.plot.contour.push_line(jump, &self.metric);
        }
        let v = self.vertex(to, Kind::Cut, loc, 0.0);
        match arc {
            Some(rec) => self.arc_into(true, from, v, rec),
            None => self.plot.contour.push_line(v, &self.metric),
        }
    }

    fn hole(&mut self, loc: &Loc, cycle: Cycle, at: &Pos) {
        let p = self.map.p3(at);
        self.plot.hole_count += 1;
        self.extend(p, true);
        if self.plot.holes.len() >= self.opts.max_marks {
            return;
        }
        // Holes closer than a mark's size share one mark: one per cell of
        // HOLE_CELL merge units (cells seen before the extents grew are
        // finer, so a few more marks are kept, never fewer).
        let m = self.metric.apply(p);
        let mut cell = [0i64; 3];
        for (c, v) in cell.iter_mut().zip(m).take(self.metric.visible) {
            // Clamped far inside i64 before the conversion.
            #[allow(clippy::cast_possible_truncation)]
            let k = (v / HOLE_CELL).floor().clamp(-1e15, 1e15) as i64;
            *c = k;
        }
        if self.hole_cells.insert(cell) {
            self.plot.holes.push(HoleMark {
                at: p,
                cycle,
                line: line_of(loc),
            });
        }
    }

    fn tool_change(&mut self, loc: &Loc, tool: u32) {
        let tools = &mut self.plot.tools;
        let i = match tools.iter().position(|t| *t == tool) {
            Some(i) => Some(i),
            None if tools.len() < usize::from(u16::MAX - 1) => {
                tools.push(tool);
                Some(tools.len() - 1)
            }
            None => None,
        };
        self.tool = i.and_then(|i| u16::try_from(i + 1).ok()).unwrap_or(0);
        if self.plot.tool_changes.len() < self.opts.max_marks {
            self.plot.tool_changes.push(ToolMark {
                at: self.pos,
                tool,
                line: line_of(loc),
            });
        }
    }

    /// A NURBS curve, drawn as a cut of chords within the merge tolerance.
    fn nurbs(&mut self, loc: &Loc, curve: &vcnc_core::Nurbs, feed: &Feed) {
        let f = self.feed_mm_per_min(feed);
        self.count(true);
        let tol_mm = self.plot.path.tolerance() * self.metric.unit_mm();
        for q in curve.flatten(tol_mm) {
            let p = self.map.p3(&q);
            self.extend(self.pos, true);
            self.extend(p, true);
            let v = self.vertex(p, Kind::Cut, loc, f);
            self.plot.path.push_line(v, &self.metric);
            self.pos = p;
        }
    }

    fn count(&mut self, cut: bool) {
        self.plot.moves += 1;
        if cut {
            self.plot.cut_moves += 1;
        }
    }

    fn frame(&mut self, loc: &Loc, f: &FrameInfo) {
        self.frame_change(f);
        let at = self.map.p3(&f.origin);
        let lin = f
            .linear
            .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let col = |j: usize| {
            let c = [lin[0][j], lin[1][j], lin[2][j]];
            let n = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
            if n > 0.0 { c.map(|v| v / n) } else { c }
        };
        let mark = OriginMark {
            at,
            x_dir: col(0),
            y_dir: col(1),
            line: line_of(loc),
        };
        let known = self
            .plot
            .origins
            .iter()
            .any(|o| o.at == mark.at && o.x_dir == mark.x_dir && o.y_dir == mark.y_dir);
        if !known && self.plot.origins.len() < MAX_ORIGINS {
            self.extend(at, false);
            self.plot.origins.push(mark);
        }
    }

    /// Keeps the frame for the readout (the origin and tool offset on X,
    /// Y and Z; rotary axes are not drawn).
    fn frame_change(&mut self, f: &FrameInfo) {
        let mark = FrameMark {
            time_s: f32_of(self.clock.now()),
            origin: self.map.p3(&f.origin),
            linear: f.linear,
            tool_offset: self.map.p3(&f.tool_offset),
        };
        if self.plot.frames.len() < MAX_FRAMES {
            self.plot.frames.push(mark);
        } else {
            self.plot.frames_complete = false;
        }
    }
}

/// The travel-limit box in plot space: every X, Y, Z axis the machine has
/// must have both limits (an axis it lacks is 0).
fn travel_box(machine: &Machine, map: &AxisMap) -> Option<(P3, P3)> {
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for (k, index) in map.index.iter().enumerate() {
        let Some(i) = index else { continue };
        let axis = machine.axes.get(*i)?;
        if !(axis.min_mm.is_finite() && axis.max_mm.is_finite()) {
            return None;
        }
        lo[k] = axis.min_mm;
        hi[k] = axis.max_mm;
    }
    map.index.iter().any(Option::is_some).then_some((lo, hi))
}

impl<C: Clock> Sink for PlotSink<C> {
    fn event(&mut self, event: &Event) {
        self.clock.event(event);
        self.plot.events += 1;
        match event {
            Event::Rapid { loc, to, .. } => self.line(loc, to, Kind::Rapid, 0.0),
            Event::Feed { loc, to, feed, .. } | Event::Skip { loc, to, feed, .. } => {
                let f = self.feed_mm_per_min(feed);
                self.line(loc, to, Kind::Cut, f);
            }
            Event::Thread { loc, to, lead_mm } => {
                let f = lead_mm * self.rpm;
                self.line(loc, to, Kind::Cut, f);
            }
            Event::Arc {
                loc,
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => {
                let f = self.feed_mm_per_min(feed);
                let (from, to) = (self.pos, self.map.p3(to));
                let rec = ArcRec {
                    center: self.map.p3(center),
                    plane: *plane,
                    dir: *dir,
                };
                let v = self.vertex(to, Kind::Cut, loc, f);
                self.arc_into(false, from, v, rec);
                self.pos = to;
            }
            Event::Contour { loc, from, to, arc } => {
                let rec = arc.map(|(center, plane, dir)| ArcRec {
                    center: self.map.p3(&center),
                    plane,
                    dir,
                });
                self.contour(loc, from, to, rec);
            }
            Event::Nurbs { loc, curve, feed } => self.nurbs(loc, curve, feed),
            Event::Spindle { rpm, .. } => self.rpm = *rpm,
            Event::ToolChange { loc, tool } => self.tool_change(loc, *tool),
            Event::Hole { loc, cycle, at } => self.hole(loc, *cycle, at),
            Event::Frame { loc, frame } => self.frame(loc, frame),
            Event::End { code, .. } => self.plot.end = Some(*code),
            Event::Alarm(d) => {
                self.extend(self.pos, true);
                self.plot.alarm = Some(AlarmMark {
                    at: self.pos,
                    code: d.code.as_str(),
                    message: d.message.clone(),
                    line: d.line,
                    column: d.column,
                });
            }
            _ => {}
        }
    }

    fn finish(&mut self) -> std::io::Result<()> {
        self.clock.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::view::View;
    use vcnc_core::{ArcDir, Plane};

    fn flat(view: View) -> PlotOptions {
        PlotOptions {
            space: Space::Flat {
                projection: Projection::new(view, false),
                width_px: 800.0,
                height_px: 600.0,
            },
            color: ColorBy::Depth,
            max_vertices: 1 << 16,
            max_marks: 1000,
            fit: FitTo::Cuts,
        }
    }

    fn at(x: f64, y: f64, z: f64) -> Pos {
        Pos([x, y, z, 0.0, 0.0, 0.0])
    }

    fn loc(line: u64) -> Loc {
        Loc { line, file: None }
    }

    #[test]
    fn an_arc_in_the_view_plane_stays_one_arc_and_in_iso_becomes_points() {
        let m = Machine::default_mill();
        let arc = Event::Arc {
            loc: loc(2),
            to: at(0.0, 10.0, 0.0),
            center: at(0.0, 0.0, 0.0),
            plane: Plane::Xy,
            dir: ArcDir::Ccw,
            feed: Feed::PerMin(100.0),
            exact_stop: false,
        };
        let first = Event::Feed {
            loc: loc(1),
            to: at(10.0, 0.0, 0.0),
            feed: Feed::PerMin(100.0),
            exact_stop: false,
        };
        let mut top = PlotSink::new(&m, flat(View::Xy));
        top.event(&first);
        top.event(&arc);
        let plot = top.into_plot();
        assert_eq!(plot.path.arcs.len(), 1);
        assert_eq!(plot.path.vertices.len(), 3);
        let mut iso = PlotSink::new(&m, flat(View::Iso));
        iso.event(&first);
        iso.event(&arc);
        let plot = iso.into_plot();
        assert!(plot.path.arcs.is_empty());
        assert!(
            plot.path.vertices.len() > 10,
            "{}",
            plot.path.vertices.len()
        );
        // The box holds the quarter circle.
        assert_eq!(plot.bounds.1[1], 10.0);
    }

    #[test]
    fn marks_tools_holes_and_the_alarm() {
        let m = Machine::default_mill();
        let mut s = PlotSink::new(&m, flat(View::Xy));
        s.event(&Event::ToolChange {
            loc: loc(1),
            tool: 7,
        });
        s.event(&Event::Rapid {
            loc: loc(2),
            to: at(5.0, 5.0, 0.0),
            exact_stop: false,
        });
        s.event(&Event::Hole {
            loc: loc(3),
            cycle: Cycle::G81,
            at: at(5.0, 5.0, -3.0),
        });
        let mut d = vcnc_core::Diagnostic::new(
            vcnc_core::Code::E301,
            vcnc_core::Span::default(),
            "no feed".into(),
            "give F",
        );
        d.line = 4;
        s.event(&Event::Alarm(d));
        let plot = s.into_plot();
        assert_eq!(plot.tools, vec![7]);
        assert_eq!(plot.tool_changes[0].at, [0.0, 0.0, 0.0]);
        assert_eq!(plot.holes[0].at, [5.0, 5.0, -3.0]);
        let alarm = plot.alarm.unwrap();
        assert_eq!(
            (alarm.code, alarm.line, alarm.at),
            ("E301", 4, [5.0, 5.0, 0.0])
        );
        assert_eq!(plot.path.vertices.last().map(|v| v.tool), Some(1));
    }

    /// A clock whose stamp is the line of the last event: block n ends at
    /// stamp n.
    #[derive(Default)]
    struct LineClock(f64);

    impl Sink for LineClock {
        fn event(&mut self, e: &Event) {
            if let Some(l) = e.loc() {
                self.0 = l.line as f64;
            }
        }
    }

    impl Clock for LineClock {
        fn now(&self) -> f64 {
            self.0
        }
    }

    fn volume() -> PlotOptions {
        PlotOptions {
            space: Space::Volume { resolution: 2048.0 },
            ..flat(View::Xy)
        }
    }

    fn feed(line: u64, x: f64, y: f64, z: f64) -> Event {
        Event::Feed {
            loc: loc(line),
            to: at(x, y, z),
            feed: Feed::PerMin(100.0),
            exact_stop: false,
        }
    }

    #[test]
    fn retiming_spreads_a_block_over_its_chords_by_length() {
        let m = Machine::default_mill();
        let mut s = PlotSink::with_clock(&m, volume(), LineClock::default());
        s.event(&feed(1, 10.0, 0.0, 0.0));
        // A half circle about (0, 0) from (10, 0) to (−10, 0): in the 3D
        // page it is drawn as equal chords.
        s.event(&Event::Arc {
            loc: loc(2),
            to: at(-10.0, 0.0, 0.0),
            center: at(0.0, 0.0, 0.0),
            plane: Plane::Xy,
            dir: ArcDir::Ccw,
            feed: Feed::PerMin(100.0),
            exact_stop: false,
        });
        s.event(&feed(3, -10.0, -5.0, 0.0));
        let mut plot = s.into_plot();
        // Block n ends at 10·n seconds.
        plot.retime(30.0, |stamp| 10.0 * stamp);
        let vs = &plot.path.vertices;
        let times: Vec<f32> = vs.iter().map(|v| v.time_s).collect();
        assert_eq!(times.first(), Some(&0.0));
        assert_eq!(times.get(1), Some(&10.0), "{times:?}");
        assert_eq!(times.last(), Some(&30.0));
        let arc: Vec<&Vertex> = vs.iter().filter(|v| v.line == 2).collect();
        assert!(arc.len() > 8, "{}", arc.len());
        // The chords are equal: times step evenly from 10 s to 20 s, and
        // the top of the circle (0, 10) is passed at 15 s.
        for (k, v) in arc.iter().enumerate() {
            let want = 10.0 + 10.0 * (k + 1) as f64 / arc.len() as f64;
            assert!(
                (f64::from(v.time_s) - want).abs() < 1e-3,
                "{k}: {} {want}",
                v.time_s
            );
            if v.at[0].abs() < 1e-9 {
                assert!((f64::from(v.time_s) - 15.0).abs() < 1e-3);
            }
        }
        assert_eq!(plot.total_time_s, 30.0);
    }

    #[test]
    fn each_vertex_knows_the_frame_it_was_cut_in() {
        let m = Machine::default_mill();
        let mut s = PlotSink::with_clock(&m, volume(), LineClock::default());
        s.event(&feed(1, 10.0, 0.0, 0.0));
        s.event(&Event::Frame {
            loc: loc(2),
            frame: FrameInfo {
                origin: at(100.0, 50.0, 0.0),
                linear: None,
                tool_offset: at(0.0, 0.0, 25.0),
            },
        });
        s.event(&feed(3, 110.0, 50.0, 0.0));
        s.event(&feed(4, 120.0, 50.0, 0.0));
        let plot = s.into_plot();
        assert_eq!(plot.frames.len(), 1);
        assert_eq!(plot.frames[0].origin, [100.0, 50.0, 0.0]);
        assert_eq!(plot.frames[0].tool_offset, [0.0, 0.0, 25.0]);
        // Vertex 0 is the start, 1 the cut of line 1; from vertex 2 (line
        // 3) on, the frame of line 2.
        assert_eq!(plot.path.vertices[2].line, 3);
        assert_eq!(plot.frame_runs, vec![(2, 0)]);
    }

    #[test]
    fn the_cuts_box_leaves_out_the_rapids_around_them() {
        let m = Machine::default_mill();
        let mut s = PlotSink::new(&m, flat(View::Xy));
        for (line, to) in [(1, at(500.0, 500.0, 0.0)), (2, at(0.0, 0.0, 5.0))] {
            s.event(&Event::Rapid {
                loc: loc(line),
                to,
                exact_stop: false,
            });
        }
        s.event(&feed(3, 0.0, 0.0, -1.0));
        s.event(&feed(4, 10.0, 0.0, -1.0));
        let plot = s.into_plot();
        // The plunge starts at Z 5: both ends of every cut are in the box.
        assert_eq!(plot.cut_bounds, Some(([0.0, 0.0, -1.0], [10.0, 0.0, 5.0])));
        assert_eq!(plot.bounds.1, [500.0, 500.0, 5.0]);
        assert_eq!((plot.moves, plot.cut_moves), (4, 2));
        assert_eq!(plot.limits, None, "the built-in mill has no travel limits");
    }

    #[test]
    fn travel_limits_make_a_box_when_every_axis_has_both() {
        let toml = vcnc_core::machine::DEFAULT_MILL_TOML.replace(
            "letter = \"x\"\n",
            "letter = \"x\"\nmin_mm = -10.0\nmax_mm = 500.0\n",
        );
        let half = Machine::from_toml(&toml).unwrap();
        assert_eq!(
            travel_box(&half, &AxisMap::of(&half)),
            None,
            "Y and Z have none"
        );
        let toml = toml
            .replace(
                "letter = \"y\"\n",
                "letter = \"y\"\nmin_mm = 0.0\nmax_mm = 400.0\n",
            )
            .replace(
                "letter = \"z\"\n",
                "letter = \"z\"\nmin_mm = -300.0\nmax_mm = 0.0\n",
            );
        let m = Machine::from_toml(&toml).unwrap();
        assert_eq!(
            travel_box(&m, &AxisMap::of(&m)),
            Some(([-10.0, 0.0, -300.0], [500.0, 400.0, 0.0]))
        );
    }

    #[test]
    fn a_nurbs_curve_is_drawn_as_a_cut_through_its_points() {
        // Order 2 with clamped knots: the polyline through its control
        // points (0, 0) → (10, 0) → (10, 10).
        let m = Machine::default_mill();
        let mut s = PlotSink::new(&m, volume());
        s.event(&Event::Nurbs {
            loc: loc(1),
            curve: Arc::new(vcnc_core::Nurbs {
                order: 2,
                knots: vec![0.0, 0.0, 1.0, 2.0, 2.0],
                points: vec![at(0.0, 0.0, 0.0), at(10.0, 0.0, 0.0), at(10.0, 10.0, 0.0)],
                weights: vec![1.0, 1.0, 1.0],
            }),
            feed: Feed::PerMin(100.0),
        });
        let plot = s.into_plot();
        let at_corner = plot
            .path
            .vertices
            .iter()
            .any(|v| (v.at[0] - 10.0).abs() < 1e-9 && v.at[1].abs() < 1e-9);
        assert!(at_corner, "{:?}", plot.path.vertices);
        assert_eq!(
            plot.path.vertices.last().map(|v| (v.at, v.kind)),
            Some(([10.0, 10.0, 0.0], Kind::Cut))
        );
        assert_eq!(plot.cut_bounds, Some(([0.0, 0.0, 0.0], [10.0, 10.0, 0.0])));
        assert_eq!(plot.cut_moves, 1);
    }
}
