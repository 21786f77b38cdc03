//! The HTML writer: one self-contained page (no network access; the data,
//! the program text, the styles and the viewer are all inlined) with a
//! rotatable, zoomable 3D back-plot drawn by hand-written WebGL
//! (`viewer/*.js`, `viewer.html` beside this file): the legend in a side
//! panel beside the searchable program text, a grid with a scale and an
//! axis triad, click-to-line and line-to-segment, a hover readout in work
//! and machine coordinates, a measure tool, the tool drawn to size, and
//! playback on the planned time.
//!
//! Data: one JSON object in a `<script type="application/json">` element.
//! Each path (and the holes, the tool changes, a mesh) is a table of
//! columns of varints, deflated and base64-encoded (`encode.rs` gives the
//! layout); the page inflates them with the browser's own
//! `DecompressionStream`. Positions are relative to `center` (a whole
//! number of quanta, so that the page adds it back exactly). Program texts
//! are base64 in `<script type="text/plain">` elements (so no text can
//! close a tag), deflated when longer than 64 KiB (`data-z="1"`), decoded
//! as UTF-8 by the page. Every string in the JSON escapes `<`, so the data
//! cannot end its script element either.
//!
//! [`Page::meshes`] takes triangle meshes (`vcnc plot --stock`: the
//! simulated stock and finished part) in machine coordinates; each gets a
//! toggle in the page and is drawn shaded under the path.

use crate::collect::{ColorBy, FitTo, Plot};
use crate::encode::{Columns, QUANTUM_FEED, QUANTUM_MM, QUANTUM_S, deflate, deltas, quanta, uvar};
use crate::path::{Kind, Path};
use crate::scene::Legend;
use crate::theme::{Palette, Rgb, Theme, palette};
use crate::view::{P3, View};
use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::fmt::Write as _;
use std::io::{self, Write};
use vcnc_core::display::DisplayUnits;
use vcnc_core::{ToolKind, ToolLibrary, ToolSource};

const PAGE: &str = include_str!("viewer.html");
/// The viewer, in parts run as one script: the data and formats, WebGL,
/// picking (hover, click, measure), and the controls.
const SCRIPTS: [&str; 4] = [
    include_str!("viewer/data.js"),
    include_str!("viewer/gl.js"),
    include_str!("viewer/pick.js"),
    include_str!("viewer/ui.js"),
];
/// Program texts longer than this are deflated in the page.
const DEFLATE_ABOVE: usize = 64 << 10;

/// A program text to show beside the plot.
#[derive(Debug, Clone)]
pub struct Source {
    /// Its name as shown (the main program first, then called programs in
    /// the order of the plot's `files`).
    pub name: String,
    /// Its bytes (any encoding; shown as UTF-8 with replacement), or their
    /// raw deflate stream when `deflated`.
    pub bytes: Vec<u8>,
    /// Whether `bytes` were already deflated ([`Source::deflated`]).
    pub deflated: bool,
}

impl Source {
    /// A text as it is.
    pub fn new(name: String, bytes: Vec<u8>) -> Source {
        Source {
            name,
            bytes,
            deflated: false,
        }
    }

    /// A text deflated now (when long enough to gain), so that a caller
    /// can do it on another thread while the program runs.
    pub fn deflated(name: String, bytes: &[u8]) -> Source {
        if bytes.len() > DEFLATE_ABOVE {
            Source {
                name,
                bytes: deflate(bytes, 1),
                deflated: true,
            }
        } else {
            Source::new(name, bytes.to_vec())
        }
    }
}

/// A triangle mesh drawn in the page, shaded, with a toggle: the hook for
/// the material-removal simulation's stock and finished part.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Its name on the toggle ("stock", "part").
    pub name: String,
    /// Its colour.
    pub color: Rgb,
    /// Whether it shows when the page opens.
    pub visible: bool,
    /// Vertices, machine X Y Z, mm (plot space).
    pub positions: Vec<P3>,
    /// Triangles, as indices into `positions`, counter-clockwise seen
    /// from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// What the page shows besides the plot.
#[derive(Debug, Clone)]
pub struct Page<'a> {
    /// Theme at load (the page can switch).
    pub theme: Theme,
    /// Colouring at load (the page can switch).
    pub color: ColorBy,
    /// Whether the machine is a lathe (front view is the half-section,
    /// and the page offers the lathe's views only).
    pub lathe: bool,
    /// The view the page opens in (`Xz` on a lathe: the half-section).
    pub view: View,
    /// What the view is fitted to, at load and by the Fit button.
    pub fit: FitTo,
    /// Whether rapids show at load.
    pub rapids: bool,
    /// The unit of the readouts, the grid and the legend at load.
    pub units: DisplayUnits,
    /// Title and facts.
    pub legend: &'a Legend,
    /// What the times are (e.g. "planned").
    pub time_label: &'a str,
    /// Program texts: `sources[0]` is the main program.
    pub sources: &'a [Source],
    /// The tools' shapes and sizes, for the tool marker.
    pub tools: Option<&'a ToolLibrary>,
    /// Meshes to show (`vcnc plot --stock`: the simulated stock and
    /// finished part).
    pub meshes: &'a [Mesh],
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

/// A JSON array of `items`, each written by `each`.
fn json_list<T>(
    out: &mut String,
    items: impl IntoIterator<Item = T>,
    mut each: impl FnMut(&mut String, T),
) {
    out.push('[');
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        each(out, item);
    }
    out.push(']');
}

fn json_p3(out: &mut String, p: P3) {
    json_list(out, p, json_num);
}

/// A box `[lo, hi]` relative to the centre, or `null`.
fn json_box(out: &mut String, b: Option<(P3, P3)>, rel: &dyn Fn(P3) -> P3) {
    match b {
        Some((lo, hi)) => json_list(out, [lo, hi], |o, p| json_p3(o, rel(p))),
        None => out.push_str("null"),
    }
}

fn json_rgb(out: &mut String, c: Rgb) {
    let _ = write!(out, "[{},{},{}]", c.0, c.1, c.2);
}

/// A path as a table: positions and kinds, with `attrs` the tool, line,
/// file, time and feed of each vertex too.
fn json_path(out: &mut String, path: &Path, origin_q: [i64; 3], attrs: bool) {
    let vs = &path.vertices;
    let mut t = Columns::default();
    t.positions(vs.iter().map(|v| v.at), origin_q);
    t.col("kind", |o| {
        o.extend(vs.iter().map(|v| match v.kind {
            Kind::Jump => 0u8,
            Kind::Rapid => 1,
            Kind::Cut => 2,
        }));
    });
    if attrs {
        t.col("tool", |o| {
            vs.iter().for_each(|v| uvar(o, u64::from(v.tool)))
        });
        t.col("line", |o| deltas(o, vs.iter().map(|v| i64::from(v.line))));
        if vs.iter().any(|v| v.file != 0) {
            t.col("file", |o| {
                vs.iter().for_each(|v| uvar(o, u64::from(v.file)))
            });
        }
        t.col("time", |o| {
            deltas(o, vs.iter().map(|v| quanta(f64::from(v.time_s), QUANTUM_S)));
        });
        t.col("feed", |o| {
            deltas(
                o,
                vs.iter()
                    .map(|v| quanta(f64::from(v.feed_mm_per_min), QUANTUM_FEED)),
            );
        });
    }
    t.write_json(out, vs.len());
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
    one(out, "muted", p.muted);
    one(out, "grid", p.grid);
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

/// The marks as JSON members: holes and tool changes as tables, work
/// origins, frames and the alarm, relative to the centre.
fn json_marks(o: &mut String, plot: &Plot, origin_q: [i64; 3], rel: &dyn Fn(P3) -> P3) {
    o.push_str(",\"holes\":");
    let mut t = Columns::default();
    t.positions(plot.holes.iter().map(|h| h.at), origin_q);
    t.write_json(o, plot.holes.len());
    let _ = write!(o, ",\"holeCount\":{},\"toolChanges\":", plot.hole_count);
    let mut t = Columns::default();
    let tc = &plot.tool_changes;
    t.positions(tc.iter().map(|c| c.at), origin_q);
    t.col("tool", |b| {
        tc.iter().for_each(|c| uvar(b, u64::from(c.tool)))
    });
    t.col("line", |b| deltas(b, tc.iter().map(|c| i64::from(c.line))));
    t.write_json(o, tc.len());
    o.push_str(",\"origins\":");
    json_list(o, &plot.origins, |o, g| {
        json_list(o, [rel(g.at), g.x_dir, g.y_dir], json_p3);
    });
    o.push_str(",\"frames\":");
    json_list(o, &plot.frames, |o, f| {
        o.push('[');
        json_p3(o, rel(f.origin));
        o.push(',');
        match f.linear {
            Some(m) => json_list(o, m, json_p3),
            None => o.push_str("null"),
        }
        o.push(',');
        json_p3(o, f.tool_offset);
        o.push(']');
    });
    o.push_str(",\"frameRuns\":");
    json_list(o, &plot.frame_runs, |o, (v, f)| {
        let _ = write!(o, "[{v},{f}]");
    });
    let _ = write!(o, ",\"framesComplete\":{},\"alarm\":", plot.frames_complete);
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

/// The shape of each of the plot's tools (`null` when nothing describes
/// it or only an assumption does: the page then marks the tool with a dot).
fn json_tool_shapes(o: &mut String, plot: &Plot, tools: Option<&ToolLibrary>) {
    o.push_str(",\"toolShapes\":[");
    for (i, n) in plot.tools.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        let shape = tools
            .and_then(|l| l.get(*n))
            .filter(|t| t.source != ToolSource::Assumed && t.diameter_mm > 0.0);
        let Some(t) = shape else {
            o.push_str("null");
            continue;
        };
        let (kind, corner, angle) = match t.kind {
            ToolKind::Flat => ("flat", 0.0, 0.0),
            ToolKind::Ball => ("ball", t.diameter_mm / 2.0, 0.0),
            ToolKind::Bull { corner_radius_mm } => ("bull", corner_radius_mm, 0.0),
            ToolKind::Drill { point_angle_deg } => ("drill", 0.0, point_angle_deg),
            ToolKind::Vee {
                included_angle_deg, ..
            } => ("vee", 0.0, included_angle_deg),
            ToolKind::Turning { nose_radius_mm, .. } => ("turning", nose_radius_mm, 0.0),
        };
        let _ = write!(o, "{{\"kind\":\"{kind}\",\"d\":");
        json_num(o, t.diameter_mm);
        o.push_str(",\"corner\":");
        json_num(o, corner);
        o.push_str(",\"angle\":");
        json_num(o, angle);
        o.push_str(",\"flute\":");
        json_num(o, t.flute_length_mm.unwrap_or(0.0));
        o.push_str(",\"name\":");
        json_str(o, &t.description);
        o.push('}');
    }
    o.push(']');
}

/// The meshes, each a table of vertex positions and triangle indices.
fn json_meshes(o: &mut String, meshes: &[Mesh], origin_q: [i64; 3]) {
    o.push_str(",\"meshes\":[");
    for (i, m) in meshes.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        o.push_str("{\"name\":");
        json_str(o, &m.name);
        o.push_str(",\"color\":");
        json_rgb(o, m.color);
        let _ = write!(
            o,
            ",\"visible\":{},\"tris\":{},\"table\":",
            m.visible,
            m.triangles.len()
        );
        let mut t = Columns::default();
        t.positions(m.positions.iter().copied(), origin_q);
        t.col("tri", |b| {
            m.triangles
                .iter()
                .flatten()
                .for_each(|k| uvar(b, u64::from(*k)));
        });
        t.write_json(o, m.positions.len());
        o.push('}');
    }
    o.push(']');
}

/// The box of `plot` and `compare` together, or of their cuts.
fn union(a: Option<(P3, P3)>, b: Option<(P3, P3)>) -> Option<(P3, P3)> {
    match (a, b) {
        (Some(a), Some(b)) => Some((
            [0, 1, 2].map(|k| a.0[k].min(b.0[k])),
            [0, 1, 2].map(|k| a.1[k].max(b.1[k])),
        )),
        (a, b) => a.or(b),
    }
}

fn view_name(v: View) -> &'static str {
    match v {
        View::Xy => "top",
        View::Xz => "front",
        View::Yz => "side",
        View::Iso => "iso",
    }
}

/// The page's settings: theme, colour, views, units, time.
fn json_settings(o: &mut String, page: &Page<'_>) {
    let _ = write!(
        o,
        ",\"theme\":\"{}\",\"color\":\"{}\",\"lathe\":{},\"view\":\"{}\",\"fit\":\"{}\",\"rapids\":{},\"units\":\"{}\",\"quantum\":{QUANTUM_MM}",
        match page.theme {
            Theme::Light => "light",
            Theme::Dark => "dark",
        },
        match page.color {
            ColorBy::Depth => "depth",
            ColorBy::Tool => "tool",
            ColorBy::Feed => "feed",
        },
        page.lathe,
        view_name(page.view),
        match page.fit {
            FitTo::Cuts => "cuts",
            FitTo::All => "all",
        },
        page.rapids,
        page.units.name(),
    );
    o.push_str(",\"timeLabel\":");
    json_str(o, page.time_label);
}

/// The page's data object.
fn data(plot: &Plot, compare: Option<(&Plot, &str)>, page: &Page<'_>) -> String {
    let (lo, hi) = union(Some(plot.bounds), compare.map(|c| c.0.bounds)).unwrap_or(plot.bounds);
    let cuts = union(plot.cut_bounds, compare.and_then(|c| c.0.cut_bounds));
    // The centre on the quantum grid, so that positions relative to it are
    // whole numbers of quanta that the page adds back exactly.
    let origin_q = [0, 1, 2].map(|k| quanta((lo[k] + hi[k]) / 2.0, QUANTUM_MM));
    let center = origin_q.map(|q| q as f64 * QUANTUM_MM);
    let size = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt();
    let rel = |p: P3| [0, 1, 2].map(|k| p[k] - center[k]);
    let mut o = String::with_capacity(plot.path.vertices.len() * 8 + (1 << 16));
    o.push_str("{\"title\":");
    json_str(&mut o, &page.legend.title);
    json_settings(&mut o, page);
    o.push_str(",\"center\":");
    json_p3(&mut o, center);
    o.push_str(",\"size\":");
    json_num(&mut o, size.max(1e-3));
    o.push_str(",\"lo\":");
    json_p3(&mut o, rel(lo));
    o.push_str(",\"hi\":");
    json_p3(&mut o, rel(hi));
    o.push_str(",\"cuts\":");
    json_box(&mut o, cuts, &rel);
    o.push_str(",\"limits\":");
    json_box(&mut o, plot.limits, &rel);
    let _ = write!(
        o,
        ",\"moves\":{},\"cutMoves\":{}",
        plot.moves, plot.cut_moves
    );
    o.push_str(",\"path\":");
    json_path(&mut o, &plot.path, origin_q, true);
    o.push_str(",\"contour\":");
    if plot.contour.vertices.len() > 1 {
        json_path(&mut o, &plot.contour, origin_q, false);
    } else {
        o.push_str("null");
    }
    o.push_str(",\"compare\":");
    match compare {
        Some((c, name)) => {
            json_path(&mut o, &c.path, origin_q, false);
            o.push_str(",\"compareName\":");
            json_str(&mut o, name);
        }
        None => o.push_str("null"),
    }
    o.push_str(",\"tools\":[");
    for (i, t) in plot.tools.iter().enumerate() {
        let _ = write!(o, "{}{t}", if i > 0 { "," } else { "" });
    }
    o.push(']');
    json_tool_shapes(&mut o, plot, page.tools);
    o.push_str(",\"files\":[");
    for (i, s) in page.sources.iter().enumerate() {
        if i > 0 {
            o.push(',');
        }
        json_str(&mut o, &s.name);
    }
    o.push(']');
    json_marks(&mut o, plot, origin_q, &rel);
    json_meshes(&mut o, page.meshes, origin_q);
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
    o.push_str(",\"palette\":{\"light\":");
    json_palette(&mut o, &palette(Theme::Light));
    o.push_str(",\"dark\":");
    json_palette(&mut o, &palette(Theme::Dark));
    o.push_str("}}");
    o
}

/// The page's data object alone (the JSON `write_html` puts in the page),
/// without program texts: what an embedded viewer loaded by
/// [`write_viewer`] is sent for each new plot (`docs/web.md`), so that it
/// keeps its camera and draws the new path without a new page.
pub fn page_data(plot: &Plot, compare: Option<(&Plot, &str)>, page: &Page<'_>) -> String {
    data(plot, compare, page)
}

/// Meshes alone, as JSON for an embedded viewer (`{vcnc: "meshes"}`):
/// `{"center":[…],"quantum":…,"meshes":[…]}`, each mesh's positions
/// relative to `center` (the middle of the meshes' box on the quantum
/// grid), so that the viewer places them whatever its path's centre.
pub fn meshes_data(meshes: &[Mesh]) -> String {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in meshes.iter().flat_map(|m| &m.positions) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let origin_q = [0, 1, 2].map(|k| {
        if lo[k] <= hi[k] {
            quanta(f64::midpoint(lo[k], hi[k]), QUANTUM_MM)
        } else {
            0
        }
    });
    let center = origin_q.map(|q| q as f64 * QUANTUM_MM);
    let mut o = String::with_capacity(1 << 16);
    o.push_str("{\"center\":");
    json_p3(&mut o, center);
    let _ = write!(o, ",\"quantum\":{QUANTUM_MM}");
    json_meshes(&mut o, meshes, origin_q);
    o.push('}');
    o
}

/// The viewer page with no plot in it: it draws nothing until its parent
/// posts `{vcnc: "data", data, text, frame}` (`data`: [`page_data`]'s
/// JSON; `text`: the program, for the readout; `frame`: fit the view to
/// the new plot, else the camera stays where it is), then again for each
/// new plot; `{vcnc: "meshes", data}` ([`meshes_data`]) replaces the
/// meshes it draws besides the page's own. Its program text pane is
/// hidden (the parent shows the text).
pub fn write_viewer(out: &mut impl Write) -> io::Result<()> {
    let (head, rest) = PAGE.split_once("__DATA__").unwrap_or((PAGE, ""));
    let (mid, tail) = rest.split_once("__SCRIPT__").unwrap_or((rest, ""));
    let head = head
        .replace("__TITLE__", "viewer")
        .replace("__THEME__", "light")
        .replace("</head>", EMBED_STYLE);
    out.write_all(head.as_bytes())?;
    out.write_all(b"null")?;
    out.write_all(mid.replace("__SOURCES__", "").as_bytes())?;
    for script in SCRIPTS {
        out.write_all(script.as_bytes())?;
    }
    out.write_all(tail.as_bytes())
}

/// The embedded viewer without its text pane.
const EMBED_STYLE: &str = "<style>#side{display:none!important}#app{grid-template-columns:minmax(0,1fr)!important}</style>\n</head>";

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
        let packed;
        let (bytes, z) = if s.deflated {
            (&s.bytes[..], true)
        } else if s.bytes.len() > DEFLATE_ABOVE {
            packed = deflate(&s.bytes, 1);
            (&packed[..], true)
        } else {
            (&s.bytes[..], false)
        };
        let _ = write!(
            buf,
            "<script type=\"text/plain\" id=\"vcnc-src-{i}\" data-z=\"{}\">",
            u8::from(z)
        );
        STANDARD.encode_string(bytes, &mut buf);
        buf.push_str("</script>\n");
        out.write_all(buf.as_bytes())?;
    }
    out.write_all(after_src.as_bytes())?;
    for script in SCRIPTS {
        out.write_all(script.as_bytes())?;
    }
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
        for page in std::iter::once(PAGE).chain(SCRIPTS) {
            for bad in ["http://", "https://", "src=\"", "@import", "url("] {
                assert!(!page.contains(bad), "{bad}");
            }
        }
    }
}
