//! The flat picture as data: a [`Scene`] of paths, shapes and text in pixel
//! coordinates, laid out once and drawn by both the SVG writer and the PNG
//! rasterizer, so that the two formats always show the same thing.
//!
//! ```text
//!   ┌──────────────────────────────────────┬──────────────┐
//!   │ ┆ grid, ticks (mm)                    │ legend panel │
//!   │ ┆    path fitted, aspect kept,        │ title, view  │
//!   │ ┆    centred in the plot area         │ line key     │
//!   │ ┆                                     │ colour scale │
//!   │ └──────────────────────────────       │ marks, rows  │
//!   └──────────────────────────────────────┴──────────────┘
//! ```
//!
//! Drawing order, bottom to top: grid and axes, the compared program, the
//! spindle centre line (lathe), rapids, cuts, the programmed contour, then
//! the marks (holes, work origins, tool changes, start, alarm) and the
//! legend. Coordinates are rounded only by the writers.

use crate::collect::{ColorBy, Plot};
use crate::path::{Kind, Path, Vertex};
use crate::theme::{
    DEPTH_STEPS, FEED_STEPS, Palette, Rgb, Theme, fraction, palette, ramp, tool_color,
};
use crate::view::{P3, Projection, View};

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
    proj: Projection,
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
        [
            self.x0 + self.s * (u - self.u0),
            self.y0 - self.s * (v - self.v0),
        ]
    }

    /// Plot-space (u, v) at a screen point.
    fn uv_at(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.u0 + (x - self.x0) / self.s,
            self.v0 + (self.y0 - y) / self.s,
        )
    }
}

/// Screen (u, v) box of a plot: its vertices, arcs and marks.
fn uv_box(plot: &Plot, proj: &Projection, bx: &mut Option<[f64; 4]>) {
    let mut add = |p: P3| {
        let (u, v) = proj.uv(p);
        let b = bx.get_or_insert([u, v, u, v]);
        b[0] = b[0].min(u);
        b[1] = b[1].min(v);
        b[2] = b[2].max(u);
        b[3] = b[3].max(v);
    };
    for path in [&plot.path, &plot.contour] {
        for (i, v) in path.vertices.iter().enumerate() {
            add(v.at);
            if let Some(arc) = path.arc_of(i) {
                let (lo, hi) = arc.bounds(3);
                // Arcs are kept only in the view plane, where the box of
                // the arc projects onto the box of its picture.
                add([lo.get(0), lo.get(1), lo.get(2)]);
                add([hi.get(0), hi.get(1), hi.get(2)]);
            }
        }
    }
    plot.holes.iter().for_each(|h| add(h.at));
    plot.origins.iter().for_each(|o| add(o.at));
    plot.tool_changes.iter().for_each(|t| add(t.at));
    if let Some(a) = &plot.alarm {
        add(a.at);
    }
}

fn fit(plot: &Plot, compare: Option<&Plot>, proj: &Projection, look: &Look) -> Fit {
    let mut bx = None;
    uv_box(plot, proj, &mut bx);
    if let Some(c) = compare {
        uv_box(c, proj, &mut bx);
    }
    let [u_lo, v_lo, u_hi, v_hi] = bx.unwrap_or([0.0; 4]);
    let (ax, ay, aw, ah) = area(f64::from(look.width_px), f64::from(look.height_px));
    let (aw, ah) = (aw - 2.0 * PAD, ah - 2.0 * PAD);
    let (du, dv) = (u_hi - u_lo, v_hi - v_lo);
    let s = match (du > 1e-9, dv > 1e-9) {
        (true, true) => (aw / du).min(ah / dv),
        (true, false) => aw / du,
        (false, true) => ah / dv,
        (false, false) => 1.0,
    };
    Fit {
        proj: *proj,
        s,
        u0: u_lo,
        v0: v_lo,
        x0: ax + PAD + (aw - s * du) / 2.0,
        y0: ay + PAD + ah - (ah - s * dv) / 2.0,
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

/// Draws `path` as runs of equal style; `style` picks the stroke of a
/// segment (`None`: not drawn).
fn path_items(
    path: &Path,
    fit: &Fit,
    style: &dyn Fn(usize, &Vertex) -> Option<Stroke>,
    out: &mut Vec<Item>,
) {
    let mut current: Option<(Stroke, [f64; 2], Vec<Seg>)> = None;
    let flush = |c: &mut Option<(Stroke, [f64; 2], Vec<Seg>)>, out: &mut Vec<Item>| {
        if let Some((stroke, start, segs)) = c.take() {
            out.push(Item::Path {
                stroke,
                start,
                segs,
            });
        }
    };
    let mut prev: Option<[f64; 2]> = None;
    for (i, v) in path.vertices.iter().enumerate() {
        let here = fit.xy(v.at);
        let stroke = if v.kind == Kind::Jump {
            None
        } else {
            style(i, v)
        };
        let (Some(stroke), Some(from)) = (stroke, prev) else {
            flush(&mut current, out);
            prev = Some(here);
            continue;
        };
        let seg = match path.arc_of(i) {
            Some(arc) => screen_arc(fit, &arc, here),
            None => Seg::Line(here),
        };
        match &mut current {
            Some((s, _, segs)) if *s == stroke => segs.push(seg),
            _ => {
                flush(&mut current, out);
                current = Some((stroke, from, vec![seg]));
            }
        }
        prev = Some(here);
    }
    flush(&mut current, out);
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
    let mut items = Vec::new();
    axes_items(&fit, &pal, look, &mut items);
    if let Some(c) = compare {
        let style = |_: usize, v: &Vertex| {
            Some(match v.kind {
                Kind::Rapid => rapid_stroke(pal.compare),
                _ => Stroke {
                    color: pal.compare,
                    width: 2.5,
                    dash: None,
                },
            })
        };
        path_items(&c.path, &fit, &style, &mut items);
    }
    if proj.diameter_up {
        centre_line(&fit, &pal, look, &mut items);
    }
    let rapids = |_: usize, v: &Vertex| (v.kind == Kind::Rapid).then(|| rapid_stroke(pal.rapid));
    path_items(&plot.path, &fit, &rapids, &mut items);
    let cuts =
        |i: usize, v: &Vertex| (v.kind == Kind::Cut).then(|| coloring.stroke(&plot.path, i, v));
    path_items(&plot.path, &fit, &cuts, &mut items);
    let contour = |_: usize, _: &Vertex| Some(contour_stroke(pal.contour));
    path_items(&plot.contour, &fit, &contour, &mut items);
    marks(plot, &fit, &pal, &mut items);
    crate::legend::panel(plot, &coloring, look, legend, &mut items);
    Scene {
        width: look.width_px,
        height: look.height_px,
        background: pal.background,
        items,
        fit,
    }
}

/// A "nice" tick step (1, 2 or 5 × 10ⁿ) giving about `n` ticks over `range`.
fn tick_step(range: f64, n: f64) -> f64 {
    let raw = (range / n).max(1e-6);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// A tick label: as many decimals as the step needs.
fn tick_label(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 {
        0
    } else {
        // step < 1: a small positive count.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let d = (-step.log10()).ceil().clamp(0.0, 6.0) as usize;
        d
    };
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        format!("{:.decimals$}", 0.0)
    } else {
        s
    }
}

/// Grid, ticks and axis names (a triad in the iso view).
fn axes_items(fit: &Fit, pal: &Palette, look: &Look, out: &mut Vec<Item>) {
    let (ax, ay, aw, ah) = area(f64::from(look.width_px), f64::from(look.height_px));
    let thin = |color| Stroke {
        color,
        width: 1.0,
        dash: None,
    };
    if fit.proj.view == View::Iso {
        iso_triad(fit, pal, ax + 36.0, ay + ah - 36.0, out);
        return;
    }
    let (u_lo, v_hi) = fit.uv_at(ax, ay);
    let (u_hi, v_lo) = fit.uv_at(ax + aw, ay + ah);
    let step = tick_step((u_hi - u_lo).max(v_hi - v_lo), 8.0);
    let k0 = (u_lo / step).ceil();
    let mut k = k0;
    while k * step <= u_hi && k - k0 < 200.0 {
        let u = k * step;
        let x = fit.x0 + fit.s * (u - fit.u0);
        out.push(line_item([x, ay], [x, ay + ah], thin(pal.grid)));
        out.push(text(
            [x, ay + ah + 14.0],
            tick_label(u, step),
            TextSize::Small,
            pal.muted,
            Anchor::Middle,
        ));
        k += 1.0;
    }
    let k0 = (v_lo / step).ceil();
    let mut k = k0;
    let scale = if fit.proj.diameter_up { 2.0 } else { 1.0 };
    while k * step <= v_hi && k - k0 < 200.0 {
        let v = k * step;
        let y = fit.y0 - fit.s * (v - fit.v0);
        out.push(line_item([ax, y], [ax + aw, y], thin(pal.grid)));
        out.push(text(
            [ax - 6.0, y + 4.0],
            tick_label(v * scale, step * scale),
            TextSize::Small,
            pal.muted,
            Anchor::End,
        ));
        k += 1.0;
    }
    out.push(Item::Shape {
        pts: vec![[ax, ay], [ax, ay + ah], [ax + aw, ay + ah]],
        closed: false,
        stroke: Some(thin(pal.muted)),
        fill: None,
    });
    let [hu, hv] = fit.proj.labels;
    let up = if fit.proj.diameter_up {
        format!("{hv} diameter, mm")
    } else {
        format!("{hv} mm")
    };
    out.push(text(
        [ax + aw, ay + ah + 30.0],
        format!("{hu} mm"),
        TextSize::Normal,
        pal.text,
        Anchor::End,
    ));
    out.push(text(
        [ax - 6.0, ay - 4.0],
        up,
        TextSize::Normal,
        pal.text,
        Anchor::Start,
    ));
}

fn iso_triad(fit: &Fit, pal: &Palette, x: f64, y: f64, out: &mut Vec<Item>) {
    for (axis, name) in [
        ([1.0, 0.0, 0.0], "X"),
        ([0.0, 1.0, 0.0], "Y"),
        ([0.0, 0.0, 1.0], "Z"),
    ] {
        let (u, v) = fit.proj.uv(axis);
        let end = [x + 26.0 * u, y - 26.0 * v];
        out.push(line_item(
            [x, y],
            end,
            Stroke {
                color: pal.muted,
                width: 1.5,
                dash: None,
            },
        ));
        out.push(text(
            [x + 36.0 * u, y - 36.0 * v + 4.0],
            name.into(),
            TextSize::Small,
            pal.text,
            Anchor::Middle,
        ));
    }
}

/// The spindle axis of a lathe half-section (X = 0), dash-dot.
fn centre_line(fit: &Fit, pal: &Palette, look: &Look, out: &mut Vec<Item>) {
    let (ax, ay, aw, ah) = area(f64::from(look.width_px), f64::from(look.height_px));
    let y = fit.y0 - fit.s * (0.0 - fit.v0);
    if y >= ay && y <= ay + ah {
        out.push(line_item(
            [ax, y],
            [ax + aw, y],
            Stroke {
                color: pal.muted,
                width: 1.0,
                dash: Some([12.0, 3.0]),
            },
        ));
    }
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

/// Holes, work origins, tool changes, start and alarm.
fn marks(plot: &Plot, fit: &Fit, pal: &Palette, out: &mut Vec<Item>) {
    for h in &plot.holes {
        shapes::hole(fit.xy(h.at), pal, out);
    }
    for o in &plot.origins {
        let c = fit.xy(o.at);
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
    for (n, t) in plot.tool_changes.iter().enumerate() {
        let c = fit.xy(t.at);
        shapes::tool_change(c, pal, out);
        if n < MAX_TOOL_LABELS {
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
        shapes::start(fit.xy(v.at), pal, out);
    }
    if let Some(a) = &plot.alarm {
        let c = fit.xy(a.at);
        shapes::alarm(c, pal, out);
        out.push(text(
            [c[0] + 14.0, c[1] - 10.0],
            format!("{} line {}", a.code, a.line),
            TextSize::Normal,
            pal.alarm,
            Anchor::Start,
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers() {
        assert_eq!(tick_step(100.0, 8.0), 10.0);
        assert_eq!(tick_step(0.7, 8.0), 0.1);
        assert_eq!(tick_step(30.0, 8.0), 5.0);
        assert_eq!(tick_label(-0.0001, 0.1), "0.0");
        assert_eq!(tick_label(12.5, 0.5), "12.5");
    }
}
