//! The HTML writer: one self-contained page (no network access; the data,
//! the program text, the styles and the viewer are all inlined) with a
//! rotatable, zoomable 3D back-plot drawn by hand-written WebGL
//! (`viewer.js`, `viewer.html` beside this file), a slider that scrubs
//! through the program while the program text beside it follows, colours
//! per tool, depth or feed, and a compared program overlaid.
//!
//! Data layout (kept compact so a 1,000,000-block program stays small
//! enough to load): each path is a set of little-endian typed arrays,
//! base64-encoded inside one JSON object in a `<script
//! type="application/json">` element, one entry per vertex —
//!
//! ```text
//!   pos   Float32 ×3   x y z relative to `center` (mm)
//!   kind  Uint8        0 jump, 1 rapid, 2 cut
//!   tool  Uint16       index into `tools` (0 = none)
//!   line  Uint32       source line;  file Uint16 (only with subprograms)
//!   time  Float32      s from the start (the Clock's);  feed Float32 mm/min
//! ```
//!
//! Program texts are base64 in `<script type="text/plain">` elements (so
//! no text can close a tag), decoded as UTF-8 by the page. Every string in
//! the JSON escapes `<`, so the data cannot end its script element either.

use crate::collect::{ColorBy, Plot};
use crate::path::{Kind, Path};
use crate::scene::Legend;
use crate::theme::{Palette, Rgb, Theme, palette};
use crate::view::P3;
use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::fmt::Write as _;
use std::io::{self, Write};

const PAGE: &str = include_str!("viewer.html");
const SCRIPT: &str = include_str!("viewer.js");

/// A program text to show beside the plot.
#[derive(Debug, Clone)]
pub struct Source {
    /// Its name as shown (the main program first, then called programs in
    /// the order of the plot's `files`).
    pub name: String,
    /// Its bytes (any encoding; shown as UTF-8 with replacement).
    pub bytes: Vec<u8>,
}

/// What the page shows besides the plot.
#[derive(Debug, Clone)]
pub struct Page<'a> {
    /// Theme at load (the page can switch).
    pub theme: Theme,
    /// Colouring at load (the page can switch).
    pub color: ColorBy,
    /// Whether the machine is a lathe (front view is the half-section).
    pub lathe: bool,
    /// Title and facts.
    pub legend: &'a Legend,
    /// What the times are (e.g. "distance/feed estimate").
    pub time_label: &'a str,
    /// Program texts: `sources[0]` is the main program.
    pub sources: &'a [Source],
}

/// A JSON string literal with `<` escaped.
fn json_str(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '<' => out.push_str("\\u003c"),
            c if u32::from(c) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

/// A JSON number (finite; 0 otherwise).
fn json_num(out: &mut String, v: f64) {
    if v.is_finite() {
        let _ = write!(out, "{v}");
    } else {
        out.push('0');
    }
}

fn json_p3(out: &mut String, p: P3) {
    out.push('[');
    for (i, v) in p.iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        json_num(out, *v);
    }
    out.push(']');
}

fn json_rgb(out: &mut String, c: Rgb) {
    let _ = write!(out, "[{},{},{}]", c.0, c.1, c.2);
}

/// f64 → f32 for the page's coordinates: rounding is intended.
#[allow(clippy::cast_possible_truncation)]
fn f32_of(v: f64) -> f32 {
    v as f32
}

/// The typed arrays of a path, as JSON members.
fn json_path(out: &mut String, path: &Path, center: P3, with_attrs: bool) {
    let n = path.vertices.len();
    let mut pos = Vec::with_capacity(n * 12);
    let mut kind = Vec::with_capacity(n);
    for v in &path.vertices {
        for (a, c) in v.at.iter().zip(center) {
            pos.extend_from_slice(&f32_of(a - c).to_le_bytes());
        }
        kind.push(match v.kind {
            Kind::Jump => 0u8,
            Kind::Rapid => 1,
            Kind::Cut => 2,
        });
    }
    let _ = write!(out, "{{\"n\":{n},\"pos\":\"");
    STANDARD.encode_string(&pos, out);
    drop(pos);
    out.push_str("\",\"kind\":\"");
    STANDARD.encode_string(&kind, out);
    out.push('"');
    if with_attrs {
        let mut member = |name: &str, bytes: Vec<u8>| {
            let _ = write!(out, ",\"{name}\":\"");
            STANDARD.encode_string(&bytes, out);
            out.push('"');
        };
        let vs = &path.vertices;
        member(
            "tool",
            vs.iter().flat_map(|v| v.tool.to_le_bytes()).collect(),
        );
        member(
            "line",
            vs.iter().flat_map(|v| v.line.to_le_bytes()).collect(),
        );
        member(
            "time",
            vs.iter().flat_map(|v| v.time_s.to_le_bytes()).collect(),
        );
        member(
            "feed",
            vs.iter()
                .flat_map(|v| v.feed_mm_per_min.to_le_bytes())
                .collect(),
        );
        if vs.iter().any(|v| v.file != 0) {
            member(
                "file",
                vs.iter().flat_map(|v| v.file.to_le_bytes()).collect(),
            );
        }
    }
    out.push('}');
}

fn json_palette(out: &mut String, p: &Palette) {
    let one = |out: &mut String, name: &str, c: Rgb| {
        let _ = write!(out, "\"{name}\":");
        json_rgb(out, c);
        out.push(',');
    };
    out.push('{');
    one(out, "bg", p.background);
    one(out, "panel", p.panel);
    one(out, "text", p.text);
    one(out, "rapid", p.rapid);
    one(out, "contour", p.contour);
    one(out, "compare", p.compare);
    one(out, "start", p.start);
    one(out, "hole", p.hole);
    one(out, "toolChange", p.tool_change);
    one(out, "alarm", p.alarm);
    one(out, "noTool", p.no_tool);
    let list = |out: &mut String, name: &str, cs: &[Rgb], last: bool| {
        let _ = write!(out, "\"{name}\":[");
        for (i, c) in cs.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            json_rgb(out, *c);
        }
        out.push(']');
        if !last {
            out.push(',');
        }
    };
    list(out, "depth", &p.depth, false);
    list(out, "feed", &p.feed, false);
    list(out, "tools", &p.tools, true);
    out.push('}');
}

/// The marks as JSON members (after `files`): holes as base64 Float32
/// triples, tool changes, work origins and the alarm, relative to `center`.
fn json_marks(o: &mut String, plot: &Plot, center: P3) {
    let rel = |p: P3| [0, 1, 2].map(|k| p[k] - center[k]);
    o.push_str("],\"holes\":\"");
    let holes: Vec<u8> = plot
        .holes
        .iter()
        .flat_map(|h| rel(h.at))
        .flat_map(|v| f32_of(v).to_le_bytes())
        .collect();
    STANDARD.encode_string(&holes, o);
    let _ = write!(o, "\",\"holeCount\":{},\"toolChanges\":[", plot.hole_count);
    for (i, t) in plot.tool_changes.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        let p = rel(t.at);
        o.push('[');
        for v in p {
            json_num(o, v);
            o.push(',');
        }
        let _ = write!(o, "{},{}]", t.tool, t.line);
    }
    o.push_str("],\"origins\":[");
    for (i, g) in plot.origins.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        o.push('[');
        json_p3(o, rel(g.at));
        o.push(',');
        json_p3(o, g.x_dir);
        o.push(',');
        json_p3(o, g.y_dir);
        o.push(']');
    }
    o.push_str("],\"alarm\":");
    match &plot.alarm {
        Some(a) => {
            o.push_str("{\"at\":");
            json_p3(o, rel(a.at));
            let _ = write!(
                o,
                ",\"code\":\"{}\",\"line\":{},\"column\":{},\"message\":",
                a.code, a.line, a.column
            );
            json_str(o, &a.message);
            o.push('}');
        }
        None => o.push_str("null"),
    }
}

/// The page's data object.
fn data(plot: &Plot, compare: Option<(&Plot, &str)>, page: &Page<'_>) -> String {
    let (lo, hi) = plot.bounds;
    let (lo, hi) = match compare {
        Some((c, _)) => (
            [0, 1, 2].map(|k| lo[k].min(c.bounds.0[k])),
            [0, 1, 2].map(|k| hi[k].max(c.bounds.1[k])),
        ),
        None => (lo, hi),
    };
    let center = [0, 1, 2].map(|k| (lo[k] + hi[k]) / 2.0);
    let size = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    let rel = |p: P3| [0, 1, 2].map(|k| p[k] - center[k]);
    let mut o = String::with_capacity(plot.path.vertices.len() * 40 + (1 << 16));
    o.push_str("{\"title\":");
    json_str(&mut o, &page.legend.title);
    let _ = write!(
        o,
        ",\"theme\":\"{}\",\"color\":\"{}\",\"lathe\":{},\"center\":",
        match page.theme {
            Theme::Light => "light",
            Theme::Dark => "dark",
        },
        match page.color {
            ColorBy::Depth => "depth",
            ColorBy::Tool => "tool",
            ColorBy::Feed => "feed",
        },
        page.lathe
    );
    json_p3(&mut o, center);
    o.push_str(",\"size\":");
    json_num(&mut o, size.max(1e-3));
    o.push_str(",\"lo\":");
    json_p3(&mut o, rel(lo));
    o.push_str(",\"hi\":");
    json_p3(&mut o, rel(hi));
    o.push_str(",\"path\":");
    json_path(&mut o, &plot.path, center, true);
    o.push_str(",\"contour\":");
    if plot.contour.vertices.len() > 1 {
        json_path(&mut o, &plot.contour, center, false);
    } else {
        o.push_str("null");
    }
    o.push_str(",\"compare\":");
    match compare {
        Some((c, name)) => {
            json_path(&mut o, &c.path, center, false);
            o.push_str(",\"compareName\":");
            json_str(&mut o, name);
        }
        None => o.push_str("null"),
    }
    o.push_str(",\"tools\":[");
    for (i, t) in plot.tools.iter().enumerate() {
        let _ = write!(o, "{}{t}", if i > 0 { "," } else { "" });
    }
    o.push_str("],\"files\":[");
    for (i, s) in page.sources.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        json_str(&mut o, &s.name);
    }
    json_marks(&mut o, plot, center);
    o.push_str(",\"rows\":[");
    for (i, (k, v)) in page.legend.rows.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        o.push('[');
        json_str(&mut o, k);
        o.push(',');
        json_str(&mut o, v);
        o.push(']');
    }
    o.push_str("],\"totalTime\":");
    json_num(&mut o, plot.total_time_s);
    o.push_str(",\"timeLabel\":");
    json_str(&mut o, page.time_label);
    o.push_str(",\"palette\":{\"light\":");
    json_palette(&mut o, &palette(Theme::Light));
    o.push_str(",\"dark\":");
    json_palette(&mut o, &palette(Theme::Dark));
    o.push_str("}}");
    o
}

/// Writes the page for `plot` (and `compare`, overlaid).
pub fn write_html(
    plot: &Plot,
    compare: Option<(&Plot, &str)>,
    page: &Page<'_>,
    out: &mut impl Write,
) -> io::Result<()> {
    let mut title = String::new();
    for c in page.legend.title.chars() {
        match c {
            '<' => title.push_str("&lt;"),
            '>' => title.push_str("&gt;"),
            '&' => title.push_str("&amp;"),
            c => title.push(c),
        }
    }
    let (head, rest) = PAGE.split_once("__DATA__").unwrap_or((PAGE, ""));
    let (mid, tail) = rest.split_once("__SCRIPT__").unwrap_or((rest, ""));
    let head = head.replace("__TITLE__", &title).replace(
        "__THEME__",
        if page.theme == Theme::Dark {
            "dark"
        } else {
            "light"
        },
    );
    out.write_all(head.as_bytes())?;
    out.write_all(data(plot, compare, page).as_bytes())?;
    let (before_src, after_src) = mid.split_once("__SOURCES__").unwrap_or((mid, ""));
    out.write_all(before_src.as_bytes())?;
    let mut buf = String::new();
    for (i, s) in page.sources.iter().enumerate() {
        buf.clear();
        let _ = write!(buf, "<script type=\"text/plain\" id=\"vcnc-src-{i}\">");
        STANDARD.encode_string(&s.bytes, &mut buf);
        buf.push_str("</script>\n");
        out.write_all(buf.as_bytes())?;
    }
    out.write_all(after_src.as_bytes())?;
    out.write_all(SCRIPT.as_bytes())?;
    out.write_all(tail.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_strings_cannot_close_the_script_element() {
        let mut s = String::new();
        json_str(&mut s, "a</script>\"\\\n");
        assert_eq!(s, "\"a\\u003c/script>\\\"\\\\\\u000a\"");
    }

    #[test]
    fn the_page_template_has_its_slots() {
        for slot in [
            "__TITLE__",
            "__THEME__",
            "__DATA__",
            "__SOURCES__",
            "__SCRIPT__",
        ] {
            assert!(PAGE.contains(slot), "{slot}");
        }
        // Self-contained: nothing is loaded from elsewhere.
        for page in [PAGE, SCRIPT] {
            for bad in ["http://", "https://", "src=\"", "@import", "url("] {
                assert!(!page.contains(bad), "{bad}");
            }
        }
    }
}
