//! A shaded picture of the finished part, as PNG: isometric (from +X −Y
//! +Z) or from above (a lathe: from the side), coloured by depth or by the
//! tool that cut each place last.
//!
//! The isometric view rasterises the part's mesh (`mesh.rs`, averaged to
//! at most [`RENDER_CELLS`] cells) with a depth buffer and Lambert shading
//! of each triangle; the view from above maps each pixel to its cell and
//! shades it by the surface's slope there. tiny-skia (the workspace's
//! raster crate) encodes the PNG and fills the lathe's section.

use crate::mesh::{HeightField, Triangle, revolve};
use crate::sim::Part;
use crate::zmap::ZMap;
use std::io::{self, Write};
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Transform};

/// Most cells the isometric picture's mesh has.
pub const RENDER_CELLS: usize = 1 << 18;

/// What colours the part.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorBy {
    /// Deep cuts dark, the stock's top light.
    Depth,
    /// The tool that cut each place last (uncut: grey).
    Tool,
}

/// Where the part is seen from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RenderView {
    /// Isometric from +X −Y +Z.
    Iso,
    /// From above (a lathe: the side).
    Top,
}

const BACKGROUND: [u8; 3] = [250, 250, 248];
const UNCUT: [u8; 3] = [196, 196, 190];
const TOOL_COLORS: [[u8; 3]; 8] = [
    [31, 119, 180],
    [255, 127, 14],
    [44, 160, 44],
    [214, 39, 40],
    [148, 103, 189],
    [140, 86, 75],
    [227, 119, 194],
    [23, 190, 207],
];

/// Depth colour: `t` 0 (the bottom) dark blue to 1 (the top) sand.
fn depth_color(t: f64) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    let lo = [40.0, 70.0, 140.0];
    let mid = [90.0, 170.0, 160.0];
    let hi = [230.0, 214.0, 170.0];
    let (a, b, u) = if t < 0.5 {
        (lo, mid, t * 2.0)
    } else {
        (mid, hi, (t - 0.5) * 2.0)
    };
    let mix = |k: usize| byte(a[k] + (b[k] - a[k]) * u);
    [mix(0), mix(1), mix(2)]
}

#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // clamped to 0..=255
fn byte(v: f64) -> u8 {
    v.clamp(0.0, 255.0) as u8
}

fn shade(c: [u8; 3], light: f64) -> [u8; 3] {
    c.map(|v| byte(f64::from(v) * light))
}

/// A colour picture being drawn, with a depth buffer.
struct Canvas {
    w: usize,
    h: usize,
    rgb: Vec<[u8; 3]>,
    depth: Vec<f64>,
}

impl Canvas {
    fn new(w: usize, h: usize) -> Canvas {
        Canvas {
            w,
            h,
            rgb: vec![BACKGROUND; w * h],
            depth: vec![f64::NEG_INFINITY; w * h],
        }
    }

    /// Fills a screen triangle (x, y, nearness) with `c` where it is
    /// nearer than what is drawn.
    fn triangle(&mut self, p: [[f64; 3]; 3], c: [u8; 3]) {
        let area =
            (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
        if area.abs() < 1e-12 {
            return;
        }
        let (x0, x1) = (
            p.iter()
                .map(|v| v[0])
                .fold(f64::INFINITY, f64::min)
                .floor()
                .max(0.0),
            p.iter()
                .map(|v| v[0])
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil()
                .min(self.w as f64 - 1.0),
        );
        let (y0, y1) = (
            p.iter()
                .map(|v| v[1])
                .fold(f64::INFINITY, f64::min)
                .floor()
                .max(0.0),
            p.iter()
                .map(|v| v[1])
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil()
                .min(self.h as f64 - 1.0),
        );
        let mut y = y0;
        while y <= y1 {
            let mut x = x0;
            while x <= x1 {
                let (px, py) = (x + 0.5, y + 0.5);
                let w0 = ((p[1][0] - px) * (p[2][1] - py) - (p[2][0] - px) * (p[1][1] - py)) / area;
                let w1 = ((p[2][0] - px) * (p[0][1] - py) - (p[0][0] - px) * (p[2][1] - py)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 >= -1e-9 && w1 >= -1e-9 && w2 >= -1e-9 {
                    let z = w0 * p[0][2] + w1 * p[1][2] + w2 * p[2][2];
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let k = y as usize * self.w + x as usize; // inside the picture
                    if let (Some(d), Some(rgb)) = (self.depth.get_mut(k), self.rgb.get_mut(k))
                        && z > *d
                    {
                        *d = z;
                        *rgb = c;
                    }
                }
                x += 1.0;
            }
            y += 1.0;
        }
    }

    fn png(&self, out: &mut dyn Write) -> io::Result<()> {
        let (w, h) = (
            u32::try_from(self.w).unwrap_or(1),
            u32::try_from(self.h).unwrap_or(1),
        );
        let mut pix = Pixmap::new(w, h).ok_or_else(|| io::Error::other("empty picture"))?;
        for (dst, src) in pix.data_mut().chunks_exact_mut(4).zip(&self.rgb) {
            dst.copy_from_slice(&[src[0], src[1], src[2], 255]);
        }
        let bytes = pix.encode_png().map_err(io::Error::other)?;
        out.write_all(&bytes)
    }
}

/// The isometric projection: screen right, screen up, nearness.
fn iso(p: [f64; 3]) -> [f64; 3] {
    let s2 = std::f64::consts::FRAC_1_SQRT_2;
    let s6 = 1.0 / 6f64.sqrt();
    let s3 = 1.0 / 3f64.sqrt();
    [
        (p[0] + p[1]) * s2,
        (-p[0] + p[1] + 2.0 * p[2]) * s6,
        (p[0] - p[1] + p[2]) * s3,
    ]
}

/// Draws `tris` isometrically, fitted to the picture; `color` gives each
/// triangle's colour before shading.
fn draw_iso(
    canvas: &mut Canvas,
    tris: crate::mesh::Triangles<'_>,
    color: &dyn Fn(&Triangle) -> [u8; 3],
) {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    tris(&mut |t| {
        for v in t {
            let s = iso(v);
            lo = [lo[0].min(s[0]), lo[1].min(s[1])];
            hi = [hi[0].max(s[0]), hi[1].max(s[1])];
        }
    });
    let margin = 0.06;
    let scale = ((canvas.w as f64) * (1.0 - 2.0 * margin) / (hi[0] - lo[0]).max(1e-9))
        .min((canvas.h as f64) * (1.0 - 2.0 * margin) / (hi[1] - lo[1]).max(1e-9));
    let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
    let (w, h) = (canvas.w as f64, canvas.h as f64);
    let light = {
        let l: [f64; 3] = [0.35, -0.55, 0.76];
        let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
        l.map(|v| v / n)
    };
    tris(&mut |t| {
        let n = crate::mesh::normal(&t);
        let lambert = (n[0] * light[0] + n[1] * light[1] + n[2] * light[2]).max(0.0);
        let c = shade(color(&t), 0.35 + 0.65 * lambert);
        let p = t.map(|v| {
            let s = iso(v);
            [
                w / 2.0 + (s[0] - cx) * scale,
                h / 2.0 - (s[1] - cy) * scale,
                s[2],
            ]
        });
        canvas.triangle(p, c);
    });
}

/// The tool mark of the cell nearest (`x`, `y`) (work coordinates).
fn tool_at(map: &ZMap, origin: [f64; 3], x: f64, y: f64) -> u8 {
    let i = ((x + origin[0] - map.x0) / map.dx).floor();
    let j = ((y + origin[1] - map.y0) / map.dy).floor();
    if !(i >= 0.0 && j >= 0.0 && i < map.nx as f64 && j < map.ny as f64) {
        return 0;
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // inside the grid
    let (i, j) = (i as usize, j as usize);
    map.tool_row(j).get(i).copied().unwrap_or(0)
}

fn tool_color(mark: u8) -> [u8; 3] {
    match mark.checked_sub(1) {
        None => UNCUT,
        Some(k) => TOOL_COLORS
            .get(usize::from(k) % TOOL_COLORS.len())
            .copied()
            .unwrap_or(UNCUT),
    }
}

/// Writes the picture of `part`.
pub fn write_png(
    part: &Part,
    view: RenderView,
    color: ColorBy,
    (w, h): (u32, u32),
    out: &mut dyn Write,
) -> io::Result<()> {
    let (wu, hu) = (w.max(16) as usize, h.max(16) as usize);
    let mut canvas = Canvas::new(wu, hu);
    match part {
        Part::Mill(map, origin) if view == RenderView::Iso => {
            let field = HeightField::of(map, *origin, RENDER_CELLS);
            let (bottom, top) = (map.bottom - origin[2], map.top - origin[2]);
            let colour = |t: &Triangle| {
                let z = (t[0][2] + t[1][2] + t[2][2]) / 3.0;
                match color {
                    ColorBy::Depth => depth_color((z - bottom) / (top - bottom).max(1e-9)),
                    ColorBy::Tool if z >= top - 1e-6 => UNCUT,
                    ColorBy::Tool => {
                        let (x, y) = (
                            (t[0][0] + t[1][0] + t[2][0]) / 3.0,
                            (t[0][1] + t[1][1] + t[2][1]) / 3.0,
                        );
                        tool_color(tool_at(map, *origin, x, y))
                    }
                }
            };
            draw_iso(&mut canvas, &|emit| field.triangles(emit), &colour);
        }
        Part::Mill(map, _) => top_view(&mut canvas, map, color),
        Part::Lathe(s) if view == RenderView::Iso => {
            let (z0, r0, z1, r1) = s.stock_box;
            let _ = (z0, z1, r0);
            draw_iso(&mut canvas, &|emit| revolve(s, emit), &|t: &Triangle| {
                let r = t.iter().map(|v| v[0].hypot(v[1])).sum::<f64>() / 3.0;
                depth_color(r / r1.max(1e-9))
            });
        }
        Part::Lathe(s) => return side_view(s, (w, h), out),
        Part::Empty => {}
    }
    canvas.png(out)
}

/// The Z-map from above: each pixel its cell's colour, shaded by slope.
fn top_view(canvas: &mut Canvas, map: &ZMap, color: ColorBy) {
    let (w, h) = (canvas.w as f64, canvas.h as f64);
    let (gw, gd) = (map.nx as f64 * map.dx, map.ny as f64 * map.dy);
    let scale = (w * 0.9 / gw).min(h * 0.9 / gd);
    let (ox, oy) = ((w - gw * scale) / 2.0, (h - gd * scale) / 2.0);
    let span = (map.top - map.bottom).max(1e-9);
    let at = |i: usize, j: usize| f64::from(map.height(i.min(map.nx - 1), j.min(map.ny - 1)));
    for py in 0..canvas.h {
        for px in 0..canvas.w {
            let gx = (px as f64 + 0.5 - ox) / scale / map.dx;
            let gy = (h - (py as f64 + 0.5) - oy) / scale / map.dy;
            if !(gx >= 0.0 && gy >= 0.0 && gx < map.nx as f64 && gy < map.ny as f64) {
                continue;
            }
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // inside the grid
            let (i, j) = (gx as usize, gy as usize);
            let z = at(i, j);
            let (sx, sy) = (
                (at(i + 1, j) - at(i.saturating_sub(1), j)) / (2.0 * map.dx),
                (at(i, j + 1) - at(i, j.saturating_sub(1))) / (2.0 * map.dy),
            );
            let n = [-sx, -sy, 1.0];
            let len = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
            let light = 0.45 + 0.55 * ((0.35 * n[0] - 0.55 * n[1] + 0.76) / len).max(0.0);
            let base = match color {
                ColorBy::Depth => depth_color((z - map.bottom) / span),
                ColorBy::Tool => tool_color(map.tool_row(j).get(i).copied().unwrap_or(0)),
            };
            if let Some(p) = canvas.rgb.get_mut(py * canvas.w + px) {
                *p = shade(base, light);
            }
        }
    }
}

/// A lathe part from the side: its section above and mirrored below the
/// axis, the stock's outline around it.
fn side_view(s: &crate::lathe::Section, (w, h): (u32, u32), out: &mut dyn Write) -> io::Result<()> {
    let mut pix =
        Pixmap::new(w.max(16), h.max(16)).ok_or_else(|| io::Error::other("empty picture"))?;
    pix.fill(tiny_skia::Color::from_rgba8(
        BACKGROUND[0],
        BACKGROUND[1],
        BACKGROUND[2],
        255,
    ));
    let (z0, _, z1, r1) = s.stock_box;
    let (wf, hf) = (f64::from(w), f64::from(h));
    let scale = (wf * 0.9 / (z1 - z0).max(1e-9)).min(hf * 0.9 / (2.0 * r1).max(1e-9));
    #[allow(clippy::cast_possible_truncation)] // pixel coordinates
    let map = |z: f64, r: f64| {
        (
            ((z - (z0 + z1) / 2.0) * scale + wf / 2.0) as f32,
            (hf / 2.0 - r * scale) as f32,
        )
    };
    let mut pb = PathBuilder::new();
    for sign in [1.0, -1.0] {
        for c in s.shapes.iter().flatten() {
            for (k, p) in c.iter().enumerate() {
                let (x, y) = map(p[0], sign * p[1]);
                if k == 0 {
                    pb.move_to(x, y);
                } else {
                    pb.line_to(x, y);
                }
            }
            pb.close();
        }
    }
    let mut paint = Paint::default();
    paint.set_color_rgba8(120, 140, 160, 255);
    paint.anti_alias = true;
    if let Some(path) = pb.finish() {
        pix.fill_path(
            &path,
            &paint,
            FillRule::EvenOdd,
            Transform::identity(),
            None,
        );
    }
    let mut outline = PathBuilder::new();
    let (a, b) = (map(z0, r1), map(z1, -r1));
    if let Some(rect) =
        tiny_skia::Rect::from_ltrb(a.0.min(b.0), a.1.min(b.1), a.0.max(b.0), a.1.max(b.1))
    {
        outline.push_rect(rect);
    }
    if let Some(path) = outline.finish() {
        let mut stroke_paint = Paint::default();
        stroke_paint.set_color_rgba8(90, 90, 90, 255);
        let stroke = tiny_skia::Stroke {
            width: 1.0,
            ..tiny_skia::Stroke::default()
        };
        pix.stroke_path(&path, &stroke_paint, &stroke, Transform::identity(), None);
    }
    let bytes = pix.encode_png().map_err(io::Error::other)?;
    out.write_all(&bytes)
}
