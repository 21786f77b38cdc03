//! The PNG writer: a [`Scene`] rasterized with tiny-skia (anti-aliased
//! strokes and fills, PNG encoding), text with embedded-graphics' mono
//! fonts (the public-domain X11 "fixed" fonts, Latin-1), drawn straight
//! into the same pixmap. tiny-skia has no text and no arcs: arcs are drawn
//! as chords within a quarter pixel of the circle, and characters outside
//! Latin-1 show as `?`.

use crate::clip::arc_points;
use crate::scene::{Anchor, Item, Scene, Seg, Stroke, TextSize};
use crate::theme::Rgb;
use embedded_graphics::Drawable;
use embedded_graphics::mono_font::MonoTextStyle;
use embedded_graphics::mono_font::iso_8859_1::{FONT_6X10, FONT_7X13, FONT_7X13_BOLD};
use embedded_graphics::pixelcolor::Rgb888;
use embedded_graphics::prelude::{DrawTarget, OriginDimensions, Point, Size};
use embedded_graphics::text::{Baseline, Text};
use std::io::{self, Write};
use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, StrokeDash, Transform,
};

/// f64 → f32 for pixel coordinates: rounding is intended.
#[allow(clippy::cast_possible_truncation)]
fn f(v: f64) -> f32 {
    v as f32
}

fn paint(c: Rgb) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color_rgba8(c.0, c.1, c.2, 255);
    p.anti_alias = true;
    p
}

fn ts_stroke(s: &Stroke) -> tiny_skia::Stroke {
    tiny_skia::Stroke {
        width: f(s.width),
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        dash: s
            .dash
            .and_then(|[a, b]| StrokeDash::new(vec![f(a), f(b)], 0.0)),
        ..tiny_skia::Stroke::default()
    }
}

fn draw_path(pm: &mut Pixmap, stroke: &Stroke, start: [f64; 2], segs: &[Seg]) {
    let mut pb = PathBuilder::new();
    pb.move_to(f(start[0]), f(start[1]));
    for s in segs {
        match *s {
            Seg::Line(p) => pb.line_to(f(p[0]), f(p[1])),
            Seg::Arc {
                to,
                center,
                radius,
                start_angle,
                sweep,
            } => {
                for p in arc_points(center, radius, start_angle, sweep) {
                    pb.line_to(f(p[0]), f(p[1]));
                }
                pb.line_to(f(to[0]), f(to[1]));
            }
        }
    }
    if let Some(path) = pb.finish() {
        pm.stroke_path(
            &path,
            &paint(stroke.color),
            &ts_stroke(stroke),
            Transform::identity(),
            None,
        );
    }
}

fn fill_and_stroke(
    pm: &mut Pixmap,
    path: Option<tiny_skia::Path>,
    stroke: Option<&Stroke>,
    fill: Option<Rgb>,
) {
    let Some(path) = path else { return };
    if let Some(c) = fill {
        pm.fill_path(
            &path,
            &paint(c),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
    if let Some(s) = stroke {
        pm.stroke_path(
            &path,
            &paint(s.color),
            &ts_stroke(s),
            Transform::identity(),
            None,
        );
    }
}

/// embedded-graphics drawing into a tiny-skia pixmap (opaque pixels).
struct Canvas<'a>(&'a mut Pixmap);

impl OriginDimensions for Canvas<'_> {
    fn size(&self) -> Size {
        Size::new(self.0.width(), self.0.height())
    }
}

impl DrawTarget for Canvas<'_> {
    type Color = Rgb888;
    type Error = std::convert::Infallible;

    fn draw_iter<I>(&mut self, pixels: I) -> Result<(), Self::Error>
    where
        I: IntoIterator<Item = embedded_graphics::Pixel<Self::Color>>,
    {
        use embedded_graphics::pixelcolor::RgbColor;
        let w = self.0.width();
        let h = self.0.height();
        let data = self.0.data_mut();
        for embedded_graphics::Pixel(p, c) in pixels {
            let (Ok(x), Ok(y)) = (u32::try_from(p.x), u32::try_from(p.y)) else {
                continue;
            };
            if x >= w || y >= h {
                continue;
            }
            let Ok(i) = usize::try_from((u64::from(y) * u64::from(w) + u64::from(x)) * 4) else {
                continue;
            };
            if let Some(px) = data.get_mut(i..i + 4) {
                px.copy_from_slice(&[c.r(), c.g(), c.b(), 255]);
            }
        }
        Ok(())
    }
}

/// Latin-1 text (the fonts' range); other characters become `?`.
fn latin1(s: &str) -> String {
    s.chars()
        .map(|c| if u32::from(c) < 256 { c } else { '?' })
        .collect()
}

fn draw_text(pm: &mut Pixmap, at: [f64; 2], s: &str, size: TextSize, color: Rgb, anchor: Anchor) {
    let font = match size {
        TextSize::Small => &FONT_6X10,
        TextSize::Normal => &FONT_7X13,
        TextSize::Bold => &FONT_7X13_BOLD,
    };
    let s = latin1(s);
    let char_w = f64::from(font.character_size.width + font.character_spacing);
    let width = char_w * s.chars().count() as f64;
    let x = match anchor {
        Anchor::Start => at[0],
        Anchor::Middle => at[0] - width / 2.0,
        Anchor::End => at[0] - width,
    };
    let style = MonoTextStyle::new(font, Rgb888::new(color.0, color.1, color.2));
    // Pixel positions; far-off values are clamped by the conversion.
    #[allow(clippy::cast_possible_truncation)]
    let p = Point::new(
        x.round().clamp(-1e6, 1e6) as i32,
        at[1].round().clamp(-1e6, 1e6) as i32,
    );
    let _ = Text::with_baseline(&s, p, style, Baseline::Alphabetic).draw(&mut Canvas(pm));
}

/// Rasterizes `scene`.
pub fn render(scene: &Scene) -> Option<Pixmap> {
    let mut pm = Pixmap::new(scene.width.max(1), scene.height.max(1))?;
    let bg = scene.background;
    pm.fill(Color::from_rgba8(bg.0, bg.1, bg.2, 255));
    for it in &scene.items {
        match it {
            Item::Path {
                stroke,
                start,
                segs,
            } => draw_path(&mut pm, stroke, *start, segs),
            Item::Shape {
                pts,
                closed,
                stroke,
                fill,
            } => {
                let mut pb = PathBuilder::new();
                for (i, p) in pts.iter().enumerate() {
                    if i == 0 {
                        pb.move_to(f(p[0]), f(p[1]));
                    } else {
                        pb.line_to(f(p[0]), f(p[1]));
                    }
                }
                if *closed {
                    pb.close();
                }
                fill_and_stroke(&mut pm, pb.finish(), stroke.as_ref(), *fill);
            }
            Item::Circle { c, r, stroke, fill } => {
                let path = PathBuilder::from_circle(f(c[0]), f(c[1]), f(*r));
                fill_and_stroke(&mut pm, path, stroke.as_ref(), *fill);
            }
            Item::Rect { xywh, fill } => {
                if let Some(rect) = Rect::from_xywh(f(xywh[0]), f(xywh[1]), f(xywh[2]), f(xywh[3]))
                {
                    pm.fill_rect(rect, &paint(*fill), Transform::identity(), None);
                }
            }
            Item::Text {
                at,
                text,
                size,
                color,
                anchor,
            } => {
                draw_text(&mut pm, *at, text, *size, *color, *anchor);
            }
        }
    }
    Some(pm)
}

/// Writes `scene` as a PNG.
pub fn write_png(scene: &Scene, out: &mut impl Write) -> io::Result<()> {
    let pm = render(scene).ok_or_else(|| io::Error::other("picture size out of range"))?;
    let bytes = pm.encode_png().map_err(io::Error::other)?;
    out.write_all(&bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arc_chords_stay_within_a_quarter_pixel() {
        let r = 100.0;
        let pts: Vec<[f64; 2]> = arc_points([0.0, 0.0], r, 0.0, std::f64::consts::PI).collect();
        let mut prev = [r, 0.0];
        for p in &pts {
            let mid = [(prev[0] + p[0]) / 2.0, (prev[1] + p[1]) / 2.0];
            assert!(r - mid[0].hypot(mid[1]) <= 0.25 + 1e-9);
            prev = *p;
        }
        let last = pts.last().unwrap();
        assert!((last[0] + r).abs() < 1e-9 && last[1].abs() < 1e-9);
    }
}
