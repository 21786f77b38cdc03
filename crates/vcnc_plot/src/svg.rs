//! The SVG writer: a [`Scene`] as an SVG 1.1 document.
//!
//! Hand-written (a few dozen lines; an SVG library would cost more than it
//! gives) so that output is byte-identical for the same program: numbers
//! are printed at 0.01 px with trailing zeros trimmed, no timestamps, ids
//! or hash-ordered maps, and items in scene order. Arcs of the view plane
//! are true SVG elliptical-arc commands (`A r r 0 large sweep x y`); a full
//! circle is two half arcs, since SVG cannot draw an arc whose ends meet.

use crate::scene::{Anchor, Item, Scene, Seg, Stroke, TextSize};
use std::f64::consts::PI;
use std::io::{self, Write};

/// Appends `v` rounded to 0.01 with trailing zeros trimmed (`12`, `3.5`,
/// `-0.25`); never `-0`.
fn num(out: &mut String, v: f64) {
    let r = (v * 100.0).round();
    if !r.is_finite() {
        out.push('0');
        return;
    }
    let r = if r == 0.0 { 0.0 } else { r };
    let s = format!("{:.2}", r / 100.0);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    out.push_str(s);
}

fn pt(out: &mut String, p: [f64; 2]) {
    num(out, p[0]);
    out.push(' ');
    num(out, p[1]);
}

/// XML text escaping.
fn escape(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            c if (c as u32) < 0x20 => o.push(' '),
            c => o.push(c),
        }
    }
    o
}

fn stroke_attrs(out: &mut String, s: &Stroke) {
    out.push_str(" stroke=\"");
    out.push_str(&s.color.hex());
    out.push_str("\" stroke-width=\"");
    num(out, s.width);
    out.push('"');
    if let Some([a, b]) = s.dash {
        out.push_str(" stroke-dasharray=\"");
        num(out, a);
        out.push(' ');
        num(out, b);
        out.push('"');
    }
}

/// One arc command (`A …`), or two for a (near) full circle.
fn arc_cmd(out: &mut String, to: [f64; 2], center: [f64; 2], radius: f64, start: f64, sweep: f64) {
    let flag = if sweep > 0.0 { '1' } else { '0' };
    let mut push = |end: [f64; 2], large: bool| {
        out.push('A');
        num(out, radius);
        out.push(' ');
        num(out, radius);
        out.push_str(" 0 ");
        out.push(if large { '1' } else { '0' });
        out.push(' ');
        out.push(flag);
        out.push(' ');
        pt(out, end);
    };
    if sweep.abs() > 1.999 * PI {
        let mid = start + sweep / 2.0;
        push(
            [
                center[0] + radius * mid.cos(),
                center[1] + radius * mid.sin(),
            ],
            false,
        );
        push(to, false);
    } else {
        push(to, sweep.abs() > PI);
    }
}

fn path_d(out: &mut String, start: [f64; 2], segs: &[Seg]) {
    out.push('M');
    pt(out, start);
    for s in segs {
        match *s {
            Seg::Line(p) => {
                out.push('L');
                pt(out, p);
            }
            Seg::Arc {
                to,
                center,
                radius,
                start_angle,
                sweep,
            } => arc_cmd(out, to, center, radius, start_angle, sweep),
        }
    }
}

fn item(out: &mut String, it: &Item) {
    match it {
        Item::Path {
            stroke,
            start,
            segs,
        } => {
            out.push_str("<path d=\"");
            path_d(out, *start, segs);
            out.push('"');
            stroke_attrs(out, stroke);
            out.push_str("/>\n");
        }
        Item::Shape {
            pts,
            closed,
            stroke,
            fill,
        } => {
            out.push_str(if *closed { "<polygon" } else { "<polyline" });
            out.push_str(" points=\"");
            for (i, p) in pts.iter().enumerate() {
                if i > 0 {
                    out.push(' ');
                }
                num(out, p[0]);
                out.push(',');
                num(out, p[1]);
            }
            out.push('"');
            paint(out, stroke.as_ref(), *fill);
            out.push_str("/>\n");
        }
        Item::Circle { c, r, stroke, fill } => {
            out.push_str("<circle cx=\"");
            num(out, c[0]);
            out.push_str("\" cy=\"");
            num(out, c[1]);
            out.push_str("\" r=\"");
            num(out, *r);
            out.push('"');
            paint(out, stroke.as_ref(), *fill);
            out.push_str("/>\n");
        }
        Item::Rect { xywh, fill } => {
            out.push_str("<rect x=\"");
            num(out, xywh[0]);
            out.push_str("\" y=\"");
            num(out, xywh[1]);
            out.push_str("\" width=\"");
            num(out, xywh[2]);
            out.push_str("\" height=\"");
            num(out, xywh[3]);
            out.push_str("\" fill=\"");
            out.push_str(&fill.hex());
            out.push_str("\" stroke=\"none\"/>\n");
        }
        Item::Text {
            at,
            text,
            size,
            color,
            anchor,
        } => {
            out.push_str("<text x=\"");
            num(out, at[0]);
            out.push_str("\" y=\"");
            num(out, at[1]);
            out.push_str("\" fill=\"");
            out.push_str(&color.hex());
            out.push_str("\" stroke=\"none\"");
            match size {
                TextSize::Small => out.push_str(" font-size=\"10\""),
                TextSize::Normal => {}
                TextSize::Bold => out.push_str(" font-weight=\"bold\""),
            }
            match anchor {
                Anchor::Start => {}
                Anchor::Middle => out.push_str(" text-anchor=\"middle\""),
                Anchor::End => out.push_str(" text-anchor=\"end\""),
            }
            out.push('>');
            out.push_str(&escape(text));
            out.push_str("</text>\n");
        }
    }
}

fn paint(out: &mut String, stroke: Option<&Stroke>, fill: Option<crate::theme::Rgb>) {
    match stroke {
        Some(s) => stroke_attrs(out, s),
        None => out.push_str(" stroke=\"none\""),
    }
    if let Some(f) = fill {
        out.push_str(" fill=\"");
        out.push_str(&f.hex());
        out.push('"');
    }
}

/// Writes `scene` as SVG.
pub fn write_svg(scene: &Scene, out: &mut impl Write) -> io::Result<()> {
    let mut s = String::with_capacity(1 << 16);
    s.push_str(&format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" \
         font-family=\"DejaVu Sans Mono, Menlo, Consolas, monospace\" font-size=\"12\">\n",
        w = scene.width,
        h = scene.height
    ));
    s.push_str(&format!(
        "<rect width=\"{}\" height=\"{}\" fill=\"{}\"/>\n",
        scene.width,
        scene.height,
        scene.background.hex()
    ));
    s.push_str("<g fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n");
    for it in &scene.items {
        item(&mut s, it);
        if s.len() > 1 << 20 {
            out.write_all(s.as_bytes())?;
            s.clear();
        }
    }
    s.push_str("</g>\n</svg>\n");
    out.write_all(s.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short_and_never_negative_zero() {
        let mut s = String::new();
        for v in [12.0, 3.5, -0.25, -0.001, 1.005, 100.129] {
            num(&mut s, v);
            s.push(' ');
        }
        assert_eq!(s, "12 3.5 -0.25 0 1 100.13 ");
    }

    #[test]
    fn a_full_circle_is_two_half_arcs() {
        let mut s = String::new();
        arc_cmd(&mut s, [10.0, 0.0], [0.0, 0.0], 10.0, 0.0, 2.0 * PI);
        assert_eq!(s, "A10 10 0 0 1 -10 0A10 10 0 0 1 10 0");
        let mut s = String::new();
        arc_cmd(&mut s, [0.0, 10.0], [0.0, 0.0], 10.0, 0.0, -1.5 * PI);
        assert_eq!(s, "A10 10 0 1 0 0 10");
    }
}
