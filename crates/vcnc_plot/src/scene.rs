//! The flat picture as data: a [`Scene`] of paths, shapes and text in pixel
//! coordinates, laid out once and drawn by both the SVG writer and the PNG
//! rasterizer, so that the two formats always show the same thing.
//!
//! ```text
//!   ┌──────────────────────────────────────┬──────────────┐
//!   │ ┆ grid, ticks (mm or in)              │ legend panel │
//!   │ ┆    the frame (the cuts, or all)     │ title, view  │
//!   │ ┆    fitted, aspect kept, centred;    ▶ line key     │
//!   │ ┆    moves leaving it clipped, ▶      │ colour scale │
//!   │ └──────────────────────────────       │ marks, rows  │
//!   └──────────────────────────────────────┴──────────────┘
//! ```
//!
//! The frame is the box of the cuts (`FitTo::Cuts`: every cutting move,
//! both its ends, the programmed contour, the holes and the alarm; a
//! lathe's from the spindle axis up) or of everything drawn; a program
//! that cut nothing is framed on everything. What lies outside is clipped
//! (`clip.rs`), with an arrowhead where a move leaves.
//!
//! Drawing order, bottom to top: grid and axes, the travel limits, the
//! compared program, the spindle centre line and chuck side (lathe),
//! rapids, cuts, the programmed contour, the exit arrowheads, then the
//! marks (holes, work origins, tool changes, start, alarm), the notes and
//! the legend. Coordinates are rounded only by the writers.

use crate::axes;
use crate::clip::{Clip, Exits, Runs, arc_points};
use crate::collect::{ColorBy, FitTo, Plot};
use crate::path::{Kind, Path, Vertex};
use crate::theme::{
    DEPTH_STEPS, FEED_STEPS, Palette, Rgb, Theme, fraction, palette, ramp, tool_color,
};
use crate::view::{P3, Projection};
use vcnc_core::display::DisplayUnits;

/// Width of the legend panel, px.
pub const PANEL_W: f64 = 300.0;
const MARGIN_L: f64 = 56.0;
const MARGIN_B: f64 = 36.0;
const MARGIN_T: f64 = 24.0;
const MARGIN_R: f64 = 16.0;
/// Room kept inside the plot area so marks at the edge stay whole, px.
const PAD: f64 = 12.0;
/// Most tool-change marks that get a label.
const MAX_TOOL_LABELS: usize = 200;

/// How a picture looks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Theme.
    pub theme: Theme,
    /// How cuts are coloured.
    pub color: ColorBy,
    /// Picture size, px.
    pub width_px: u32,
    /// Picture size, px.
    pub height_px: u32,
    /// What the picture is framed on.
    pub fit: FitTo,
    /// Whether rapids are drawn (a program of rapids alone always shows
    /// them).
    pub rapids: bool,
    /// The unit of ticks and legend figures.
    pub units: DisplayUnits,
}

/// What the legend says besides what the scene knows: a title and rows of
/// facts (cycle time, extents, tools…) that the caller computed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Legend {
    /// First line (the program).
    pub title: String,
    /// Rows of (label, value).
    pub rows: Vec<(String, String)>,
    /// Name of the compared program, when there is one.
    pub compare: Option<String>,
}

/// A stroke style.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Colour.
    pub color: Rgb,
    /// Width, px.
    pub width: f64,
    /// Dash and gap lengths, px.
    pub dash: Option<[f64; 2]>,
}

/// One piece of a drawn path, screen coordinates (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Seg {
    /// A straight line to a point.
    Line([f64; 2]),
    /// A circular arc to `to` about `center`: `start_angle` and the signed
    /// `sweep` are screen angles (y down, so a positive sweep turns
    /// clockwise on the screen).
    Arc {
        /// End point.
        to: [f64; 2],
        /// Centre.
        center: [f64; 2],
        /// Radius, px.
        radius: f64,
        /// Angle of the start point, rad.
        start_angle: f64,
        /// Signed sweep, rad.
        sweep: f64,
    },
}

/// Text anchoring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// Left edge at `at`.
    Start,
    /// Centred on `at`.
    Middle,
    /// Right edge at `at`.
    End,
}

/// Text size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextSize {
    /// 10 px: ticks.
    Small,
    /// 12 px: legend.
    Normal,
    /// 12 px bold: titles.
    Bold,
}

/// One drawn item.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// A stroked path.
    Path {
        /// Style.
        stroke: Stroke,
        /// First point.
        start: [f64; 2],
        /// What follows it.
        segs: Vec<Seg>,
    },
    /// A polygon or polyline, stroked and/or filled.
    Shape {
        /// Points.
        pts: Vec<[f64; 2]>,
        /// Whether the last point joins the first.
        closed: bool,
        /// Outline.
        stroke: Option<Stroke>,
        /// Fill.
        fill: Option<Rgb>,
    },
    /// A circle.
    Circle {
        /// Centre.
        c: [f64; 2],
        /// Radius.
        r: f64,
        /// Outline.
        stroke: Option<Stroke>,
        /// Fill.
        fill: Option<Rgb>,
    },
    /// A filled rectangle.
    Rect {
        /// Top-left corner and size.
        xywh: [f64; 4],
        /// Fill.
        fill: Rgb,
    },
    /// One line of text; `at` is on its baseline.
    Text {
        /// Anchor point.
        at: [f64; 2],
        /// The text.
        text: String,
        /// Size.
        size: TextSize,
        /// Colour.
        color: Rgb,
        /// Anchoring.
        anchor: Anchor,
    },
}

/// A laid-out picture.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Size, px.
    pub width: u32,
    /// Size, px.
    pub height: u32,
    /// Background colour.
    pub background: Rgb,
    /// Items, bottom to top.
    pub items: Vec<Item>,
    /// Where plot space lands on the picture.
    pub fit: Fit,
}

/// The plot area (width, height) of a picture, px: what a
/// [`crate::Space::Flat`] sink merges for.
pub fn plot_area(width_px: u32, height_px: u32) -> (f64, f64) {
    let (_, _, w, h) = area(f64::from(width_px), f64::from(height_px));
    ((w - 2.0 * PAD).max(1.0), (h - 2.0 * PAD).max(1.0))
}

/// The plot area's x, y, width, height.
fn area(width: f64, height: f64) -> (f64, f64, f64, f64) {
    let w = (width - PANEL_W - MARGIN_L - MARGIN_R).max(10.0);
    let h = (height - MARGIN_T - MARGIN_B).max(10.0);
    (MARGIN_L, MARGIN_T, w, h)
}

/// Plot space → screen: `x = x0 + s·(u − u0)`, `y = y0 − s·(v − v0)`
/// (one scale on both axes, so shapes keep their proportions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fit {
    pub(crate) proj: Projection,
    s: f64,
    u0: f64,
    v0: f64,
    x0: f64,
    y0: f64,
}

impl Fit {
    /// The screen point of a plot-space point, px.
    pub fn xy(&self, p: P3) -> [f64; 2] {
        let (u, v) = self.proj.uv(p);
        [self.x_of(u), self.y_of(v)]
    }

    /// Screen x of a plot-space `u`.
    pub(crate) fn x_of(&self, u: f64) -> f64 {
        self.x0 + self.s * (u - self.u0)
    }

    /// Screen y of a plot-space `v`.
    pub(crate) fn y_of(&self, v: f64) -> f64 {
        self.y0 - self.s * (v - self.v0)
    }

    /// Pixels per mm.
    pub fn scale(&self) -> f64 {
        self.s
    }

    /// Plot-space (u, v) at a screen point.
    pub(crate) fn uv_at(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.u0 + (x - self.x0) / self.s,
            self.v0 + (self.y0 - y) / self.s,
        )
    }
}

/// A screen (u, v) box being grown.
struct UvBox<'a> {
    proj: &'a Projection,
    bx: Option<[f64; 4]>,
}

impl UvBox<'_> {
    fn add(&mut self, p: P3) {
        let (u, v) = self.proj.uv(p);
        let b = self.bx.get_or_insert([u, v, u, v]);
        b[0] = b[0].min(u);
        b[1] = b[1].min(v);
        b[2] = b[2].max(u);
        b[3] = b[3].max(v);
    }

    /// Vertex `i` of `path` and, for an arc, the box of the arc (arcs are
    /// kept only in the view plane, where the box of the arc projects onto
    /// the box of its picture).
    fn vertex(&mut self, path: &Path, i: usize, v: &Vertex) {
        self.add(v.at);
        if let Some(arc) = path.arc_of(i) {
            let (lo, hi) = arc.bounds(3);
            self.add([lo.get(0), lo.get(1), lo.get(2)]);
            self.add([hi.get(0), hi.get(1), hi.get(2)]);
        }
    }

    /// Everything drawn: vertices, arcs and marks.
    fn all(&mut self, plot: &Plot) {
        for path in [&plot.path, &plot.contour] {
            for (i, v) in path.vertices.iter().enumerate() {
                self.vertex(path, i, v);
            }
        }
        plot.holes.iter().for_each(|h| self.add(h.at));
        plot.origins.iter().for_each(|o| self.add(o.at));
        plot.tool_changes.iter().for_each(|t| self.add(t.at));
        if let Some(a) = &plot.alarm {
            self.add(a.at);
        }
    }

    /// The cuts (both ends of each), the contour, the holes and the alarm.
    fn cuts(&mut self, plot: &Plot) {
        let vs = &plot.path.vertices;
        for (i, v) in vs.iter().enumerate() {
            if v.kind == Kind::Cut {
                if let Some(from) = i.checked_sub(1).and_then(|j| vs.get(j)) {
                    self.add(from.at);
                }
                self.vertex(&plot.path, i, v);
            }
        }
        for (i, v) in plot.contour.vertices.iter().enumerate() {
            self.vertex(&plot.contour, i, v);
        }
        plot.holes.iter().for_each(|h| self.add(h.at));
        if let Some(a) = &plot.alarm {
            self.add(a.at);
        }
    }
}

/// Whether a plot cut anything (or drilled, or alarmed): else it is
/// framed on everything.
fn has_cuts(plot: &Plot) -> bool {
    plot.cut_bounds.is_some()
}

/// The screen box the picture is framed on.
fn frame_box(plot: &Plot, compare: Option<&Plot>, proj: &Projection, look: &Look) -> [f64; 4] {
    let mut bx = UvBox { proj, bx: None };
    let on_cuts = look.fit == FitTo::Cuts && (has_cuts(plot) || compare.is_some_and(has_cuts));
    for p in std::iter::once(plot).chain(compare) {
        if on_cuts {
            bx.cuts(p);
        } else {
            bx.all(p);
        }
    }
    if !on_cuts && let Some((lo, hi)) = plot.limits {
        for k in 0..8usize {
            bx.add([0, 1, 2].map(|i| if k >> i & 1 == 1 { hi[i] } else { lo[i] }));
        }
    }
    let mut b = bx.bx.unwrap_or([0.0; 4]);
    // A half-section reaches from the spindle axis to the largest radius.
    if proj.diameter_up {
        b[1] = b[1].min(0.0);
        b[3] = b[3].max(0.0);
    }
    // A single point (one hole seen from the top) gets a 10 mm frame.
    if b[2] - b[0] < 1e-6 && b[3] - b[1] < 1e-6 {
        b = [b[0] - 5.0, b[1] - 5.0, b[2] + 5.0, b[3] + 5.0];
    }
    b
}

fn fit(plot: &Plot, compare: Option<&Plot>, proj: &Projection, look: &Look) -> Fit {
    let [u_lo, v_lo, u_hi, v_hi] = frame_box(plot, compare, proj, look);
    let (ax, ay, aw, ah) = area(f64::from(look.width_px), f64::from(look.height_px));
    let (aw, ah) = (aw - 2.0 * PAD, ah - 2.0 * PAD);
    let (du, dv) = (u_hi - u_lo, v_hi - v_lo);
    let s = match (du > 1e-9, dv > 1e-9) {
        (true, true) => (aw / du).min(ah / dv),
        (true, false) => aw / du,
        (false, true) => ah / dv,
        (false, false) => 1.0,
    };
    // A half-section stands on its spindle axis at the bottom of the plot
    // area; other pictures are centred.
    let spare_v = if proj.diameter_up {
        0.0
    } else {
        (ah - s * dv) / 2.0
    };
    Fit {
        proj: *proj,
        s,
        u0: u_lo,
        v0: v_lo,
        x0: ax + PAD + (aw - s * du) / 2.0,
        y0: ay + PAD + ah - spare_v,
    }
}

/// What colours a cut: the ranges seen in the plot.
pub(crate) struct Coloring {
    pub(crate) by: ColorBy,
    pub(crate) pal: Palette,
    pub(crate) depth: (f64, f64),
    pub(crate) feed: (f64, f64),
    pub(crate) proj: Projection,
}

impl Coloring {
    fn new(plot: &Plot, proj: &Projection, look: &Look) -> Coloring {
        let mut depth: Option<(f64, f64)> = None;
        let mut feed: Option<(f64, f64)> = None;
        let grow = |r: &mut Option<(f64, f64)>, x: f64| {
            let (lo, hi) = r.get_or_insert((x, x));
            *lo = lo.min(x);
            *hi = hi.max(x);
        };
        for v in plot.path.vertices.iter().skip(1) {
            if v.kind == Kind::Cut {
                grow(&mut depth, proj.depth_of(v.at));
                if v.feed_mm_per_min > 0.0 {
                    grow(&mut feed, f64::from(v.feed_mm_per_min));
                }
            }
        }
        Coloring {
            by: look.color,
            pal: palette(look.theme),
            depth: depth.unwrap_or((0.0, 0.0)),
            feed: feed.unwrap_or((0.0, 0.0)),
            proj: *proj,
        }
    }

    pub(crate) fn depth_color(&self, d: f64) -> Rgb {
        ramp(
            &self.pal.depth,
            fraction(d, self.depth.0, self.depth.1),
            DEPTH_STEPS,
        )
    }

    fn feed_color(&self, f: f64) -> Rgb {
        ramp(
            &self.pal.feed,
            fraction(f, self.feed.0, self.feed.1),
            FEED_STEPS,
        )
    }

    /// The stroke of the segment of vertex `i`. A cut takes the colour of
    /// the depth where it ends (an arc: its middle): the end is where the
    /// block sends the tool, and a plunge merged away as invisible cannot
    /// lend its depth to the move after it.
    fn stroke(&self, path: &Path, i: usize, v: &Vertex) -> Stroke {
        if v.kind == Kind::Rapid {
            return rapid_stroke(self.pal.rapid);
        }
        let color = match self.by {
            ColorBy::Tool => tool_color(&self.pal, v.tool),
            ColorBy::Feed => self.feed_color(f64::from(v.feed_mm_per_min)),
            ColorBy::Depth => {
                let mid = match path.arc_of(i) {
                    Some(arc) => {
                        let m = arc.point_at(0.5);
                        [m.get(0), m.get(1), m.get(2)]
                    }
                    None => v.at,
                };
                self.depth_color(self.proj.depth_of(mid))
            }
        };
        cut_stroke(color)
    }
}

pub(crate) fn rapid_stroke(color: Rgb) -> Stroke {
    Stroke {
        color,
        width: 1.0,
        dash: Some([4.0, 3.0]),
    }
}

pub(crate) fn cut_stroke(color: Rgb) -> Stroke {
    Stroke {
        color,
        width: 1.5,
        dash: None,
    }
}

pub(crate) fn contour_stroke(color: Rgb) -> Stroke {
    Stroke {
        color,
        width: 1.0,
        dash: Some([6.0, 2.0]),
    }
}

/// Draws `path` as runs of equal style, clipped to the frame; `style`
/// picks the stroke of a segment (`None`: not drawn). Moves that leave the
/// frame go to `exits`.
fn path_items(
    path: &Path,
    ctx: (&Fit, &Clip),
    exits: &mut Exits,
    style: &dyn Fn(usize, &Vertex) -> Option<Stroke>,
    out: &mut Vec<Item>,
) {
    let (fit, clip) = ctx;
    let mut runs = Runs::new(out);
    let mut prev: Option<[f64; 2]> = None;
    for (i, v) in path.vertices.iter().enumerate() {
        let here = fit.xy(v.at);
        let stroke = if v.kind == Kind::Jump {
            None
        } else {
            style(i, v)
        };
        let (Some(stroke), Some(from)) = (stroke, prev) else {
            runs.flush();
            prev = Some(here);
            continue;
        };
        match path.arc_of(i) {
            Some(arc) => {
                let (lo, hi) = arc.bounds(3);
                let inside = clip.contains(fit.xy([lo.get(0), lo.get(1), lo.get(2)]), 0.0)
                    && clip.contains(fit.xy([hi.get(0), hi.get(1), hi.get(2)]), 0.0);
                let seg = screen_arc(fit, &arc, here);
                match seg {
                    Seg::Arc {
                        center,
                        radius,
                        start_angle,
                        sweep,
                        ..
                    } if !inside => {
                        // Partly outside: chords, each clipped.
                        let mut a = from;
                        for b in arc_points(center, radius, start_angle, sweep) {
                            runs.line(clip, exits, stroke, a, b);
                            a = b;
                        }
                    }
                    _ => runs.push(stroke, from, seg, here),
                }
            }
            None => runs.line(clip, exits, stroke, from, here),
        }
        prev = Some(here);
    }
    runs.flush();
}

/// An arc of the view plane on the screen.
fn screen_arc(fit: &Fit, arc: &vcnc_core::geometry::ArcPath, to: [f64; 2]) -> Seg {
    let (a, b) = (arc.axes.a, arc.axes.b);
    // The centre in plot space: its normal coordinate is the start's.
    let mut c3 = [arc.from.get(0), arc.from.get(1), arc.from.get(2)];
    c3[a] = arc.center.0;
    c3[b] = arc.center.1;
    let center = fit.xy(c3);
    let from = fit.xy([arc.from.get(0), arc.from.get(1), arc.from.get(2)]);
    // Orientation of the plane's (a, b) on the y-down screen.
    let (u, v) = (fit.proj.u, fit.proj.v);
    let det = -(u[a] * v[b] - u[b] * v[a]);
    let sign = if det < 0.0 { -1.0 } else { 1.0 };
    Seg::Arc {
        to,
        center,
        radius: arc.radius * fit.s,
        start_angle: (from[1] - center[1]).atan2(from[0] - center[0]),
        sweep: arc.sweep * sign,
    }
}

/// What the picture says about itself in the plot area: nothing to draw,
/// or rapids drawn although they were to be hidden.
fn notes(plot: &Plot, look: &Look) -> Vec<&'static str> {
    let mut notes = Vec::new();
    if plot.moves == 0 {
        notes.push("no motion: the program moves nothing");
    } else if plot.cut_moves == 0 && !look.rapids {
        notes.push("every move is a rapid: rapids are drawn although hidden");
    }
    notes
}

/// Lays out the picture of `plot` (and of `compare`, underneath).
pub fn scene(
    plot: &Plot,
    compare: Option<&Plot>,
    proj: &Projection,
    look: &Look,
    legend: &Legend,
) -> Scene {
    let pal = palette(look.theme);
    let fit = fit(plot, compare, proj, look);
    let coloring = Coloring::new(plot, proj, look);
    let area = area(f64::from(look.width_px), f64::from(look.height_px));
    let (ax, ay, aw, ah) = area;
    let clip = Clip {
        x0: ax,
        y0: ay,
        x1: ax + aw,
        y1: ay + ah,
    };
    let mut items = Vec::new();
    let mut exits = Exits::default();
    axes::grid(&fit, &pal, look.units, area, &mut items);
    if let Some(box_) = plot.limits {
        axes::limits(&fit, &pal, &clip, box_, &mut items);
    }
    // Rapids are hidden only when there is something else to show.
    let rapids_shown = look.rapids || plot.cut_moves == 0;
    if let Some(c) = compare {
        let style = |_: usize, v: &Vertex| match v.kind {
            Kind::Rapid => rapids_shown.then(|| rapid_stroke(pal.compare)),
            _ => Some(Stroke {
                color: pal.compare,
                width: 2.5,
                dash: None,
            }),
        };
        path_items(&c.path, (&fit, &clip), &mut exits, &style, &mut items);
    }
    if proj.diameter_up {
        axes::lathe(&fit, &pal, area, &mut items);
    }
    let rapids = |_: usize, v: &Vertex| {
        (v.kind == Kind::Rapid && rapids_shown).then(|| rapid_stroke(pal.rapid))
    };
    path_items(&plot.path, (&fit, &clip), &mut exits, &rapids, &mut items);
    let cuts =
        |i: usize, v: &Vertex| (v.kind == Kind::Cut).then(|| coloring.stroke(&plot.path, i, v));
    path_items(&plot.path, (&fit, &clip), &mut exits, &cuts, &mut items);
    let contour = |_: usize, _: &Vertex| Some(contour_stroke(pal.contour));
    path_items(
        &plot.contour,
        (&fit, &clip),
        &mut exits,
        &contour,
        &mut items,
    );
    exits.items(&mut items);
    marks(plot, (&fit, &clip), &pal, &mut items);
    for (k, note) in notes(plot, look).iter().enumerate() {
        let y = if plot.moves == 0 {
            ay + ah / 2.0
        } else {
            ay + 18.0
        };
        items.push(text(
            [
                ax + aw / 2.0,
                y + 17.0 * f64::from(u8::try_from(k).unwrap_or(0)),
            ],
            (*note).to_string(),
            TextSize::Bold,
            pal.muted,
            Anchor::Middle,
        ));
    }
    let framing = Framing {
        on_cuts: look.fit == FitTo::Cuts && has_cuts(plot),
        exits: exits.count,
        rapids_hidden: !rapids_shown,
    };
    crate::legend::panel(plot, &coloring, look, legend, &framing, &mut items);
    Scene {
        width: look.width_px,
        height: look.height_px,
        background: pal.background,
        items,
        fit,
    }
}

/// How the picture was framed, for the legend.
pub(crate) struct Framing {
    /// Framed on the cuts (else on everything).
    pub(crate) on_cuts: bool,
    /// Moves that leave the frame.
    pub(crate) exits: u64,
    /// Rapids are not drawn.
    pub(crate) rapids_hidden: bool,
}

pub(crate) fn line_item(a: [f64; 2], b: [f64; 2], stroke: Stroke) -> Item {
    Item::Path {
        stroke,
        start: a,
        segs: vec![Seg::Line(b)],
    }
}

pub(crate) fn text(at: [f64; 2], text: String, size: TextSize, color: Rgb, anchor: Anchor) -> Item {
    Item::Text {
        at,
        text,
        size,
        color,
        anchor,
    }
}

/// The shapes of each mark, centred on `c`.
pub(crate) mod shapes {
    use super::*;

    pub fn start(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
        out.push(Item::Shape {
            pts: vec![
                [c[0], c[1] - 8.0],
                [c[0] + 7.0, c[1] + 5.0],
                [c[0] - 7.0, c[1] + 5.0],
            ],
            closed: true,
            stroke: Some(Stroke {
                color: pal.background,
                width: 1.0,
                dash: None,
            }),
            fill: Some(pal.start),
        });
    }

    pub fn hole(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
        let s = Stroke {
            color: pal.hole,
            width: 1.0,
            dash: None,
        };
        out.push(Item::Circle {
            c,
            r: 4.0,
            stroke: Some(s),
            fill: None,
        });
        out.push(line_item([c[0] - 6.0, c[1]], [c[0] + 6.0, c[1]], s));
        out.push(line_item([c[0], c[1] - 6.0], [c[0], c[1] + 6.0], s));
    }

    pub fn tool_change(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
        out.push(Item::Shape {
            pts: vec![
                [c[0], c[1] - 6.0],
                [c[0] + 6.0, c[1]],
                [c[0], c[1] + 6.0],
                [c[0] - 6.0, c[1]],
            ],
            closed: true,
            stroke: Some(Stroke {
                color: pal.tool_change,
                width: 1.5,
                dash: None,
            }),
            fill: Some(pal.background),
        });
    }

    pub fn alarm(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
        let s = Stroke {
            color: pal.alarm,
            width: 2.5,
            dash: None,
        };
        out.push(Item::Circle {
            c,
            r: 10.0,
            stroke: Some(Stroke { width: 1.5, ..s }),
            fill: None,
        });
        out.push(line_item(
            [c[0] - 6.0, c[1] - 6.0],
            [c[0] + 6.0, c[1] + 6.0],
            s,
        ));
        out.push(line_item(
            [c[0] - 6.0, c[1] + 6.0],
            [c[0] + 6.0, c[1] - 6.0],
            s,
        ));
    }

    pub fn origin(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
        out.push(Item::Circle {
            c,
            r: 5.0,
            stroke: Some(Stroke {
                color: pal.text,
                width: 1.0,
                dash: None,
            }),
            fill: None,
        });
        out.push(Item::Shape {
            pts: vec![
                [c[0], c[1] - 5.0],
                [c[0] + 5.0, c[1]],
                [c[0], c[1]],
                [c[0], c[1] + 5.0],
                [c[0] - 5.0, c[1]],
                [c[0], c[1]],
            ],
            closed: true,
            stroke: None,
            fill: Some(pal.text),
        });
    }
}

/// Holes, work origins, tool changes, start and alarm: those in the frame
/// (the alarm is pinned to the frame's edge when it stopped outside).
fn marks(plot: &Plot, (fit, clip): (&Fit, &Clip), pal: &Palette, out: &mut Vec<Item>) {
    let seen = |c: [f64; 2]| clip.contains(c, 2.0);
    for h in &plot.holes {
        let c = fit.xy(h.at);
        if seen(c) {
            shapes::hole(c, pal, out);
        }
    }
    for o in &plot.origins {
        let c = fit.xy(o.at);
        if !seen(c) {
            continue;
        }
        shapes::origin(c, pal, out);
        for (dir, name) in [(o.x_dir, "X"), (o.y_dir, "Y")] {
            let tip = fit.xy([0, 1, 2].map(|k| o.at[k] + dir[k]));
            let (dx, dy) = (tip[0] - c[0], tip[1] - c[1]);
            let len = dx.hypot(dy);
            // An axis seen end-on has no arrow.
            if len > 1e-9 * fit.s.max(1.0) && len / fit.s > 0.2 {
                let (ux, uy) = (dx / len, dy / len);
                let end = [c[0] + 22.0 * ux, c[1] + 22.0 * uy];
                out.push(line_item(
                    c,
                    end,
                    Stroke {
                        color: pal.text,
                        width: 1.0,
                        dash: None,
                    },
                ));
                out.push(text(
                    [c[0] + 30.0 * ux, c[1] + 30.0 * uy + 4.0],
                    name.into(),
                    TextSize::Small,
                    pal.text,
                    Anchor::Middle,
                ));
            }
        }
    }
    let mut labels = 0usize;
    for t in &plot.tool_changes {
        let c = fit.xy(t.at);
        if !seen(c) {
            continue;
        }
        shapes::tool_change(c, pal, out);
        if labels < MAX_TOOL_LABELS {
            labels += 1;
            out.push(text(
                [c[0] + 8.0, c[1] - 8.0],
                format!("T{}", t.tool),
                TextSize::Small,
                pal.tool_change,
                Anchor::Start,
            ));
        }
    }
    if let Some(v) = plot.path.vertices.first() {
        let c = fit.xy(v.at);
        if seen(c) {
            shapes::start(c, pal, out);
        }
    }
    if let Some(a) = &plot.alarm {
        let c = clip.pin(fit.xy(a.at));
        shapes::alarm(c, pal, out);
        let right = c[0] < clip.x1 - 120.0;
        out.push(text(
            [c[0] + if right { 14.0 } else { -14.0 }, c[1] - 10.0],
            format!("{} line {}", a.code, a.line),
            TextSize::Normal,
            pal.alarm,
            if right { Anchor::Start } else { Anchor::End },
        ));
    }
}
