//! The legend panel of a flat picture: title and view, the line key, the
//! colour scale of the cuts, the marks, the caller's facts (cycle time,
//! extents, tools) and the alarm, written top to bottom at the right of
//! the picture. Part of the [`crate::scene`], in its own file for size.

use crate::collect::{ColorBy, Plot};
use crate::path::Kind;
use crate::scene::{
    Anchor, Coloring, Framing, Item, Legend, Look, PANEL_W, Stroke, TextSize, contour_stroke,
    cut_stroke, line_item, rapid_stroke, shapes, text,
};
use crate::theme::{DEPTH_STEPS, FEED_STEPS, Palette, Rgb, ramp, tool_color};
use crate::view::{Projection, View};
use vcnc_core::display::DisplayUnits;

/// Characters of 12 px text that fit a legend line.
const LEGEND_CHARS: usize = 37;

/// Splits `s` into lines of at most `width` characters at spaces.
fn wrap(s: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in s.split_whitespace() {
        let mut word = word.to_string();
        while word.chars().count() > width {
            let head: String = word.chars().take(width).collect();
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            lines.push(head);
            word = word.chars().skip(width).collect();
        }
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// The end of a long text, with an ellipsis in front.
fn tail(s: &str, width: usize) -> String {
    let n = s.chars().count();
    if n <= width {
        s.to_string()
    } else {
        let keep: String = s.chars().skip(n + 3 - width).collect();
        format!("...{keep}")
    }
}

/// The legend panel, written top to bottom.
struct Panel<'a> {
    x: f64,
    y: f64,
    pal: &'a Palette,
    out: &'a mut Vec<Item>,
}

impl Panel<'_> {
    fn line(&mut self, s: String, size: TextSize, color: Rgb) {
        self.out
            .push(text([self.x, self.y], s, size, color, Anchor::Start));
        self.y += 17.0;
    }

    fn gap(&mut self) {
        self.y += 8.0;
    }

    /// A line key: a short sample of `stroke` and a label.
    fn key(&mut self, stroke: Stroke, label: &str) {
        let y = self.y - 4.0;
        self.out
            .push(line_item([self.x, y], [self.x + 34.0, y], stroke));
        self.out.push(text(
            [self.x + 44.0, self.y],
            label.into(),
            TextSize::Normal,
            self.pal.text,
            Anchor::Start,
        ));
        self.y += 17.0;
    }

    /// A mark key: `draw` puts the mark at a point, then a label.
    fn mark(&mut self, draw: fn([f64; 2], &Palette, &mut Vec<Item>), label: String) {
        draw([self.x + 17.0, self.y - 4.0], self.pal, self.out);
        self.out.push(text(
            [self.x + 44.0, self.y],
            label,
            TextSize::Normal,
            self.pal.text,
            Anchor::Start,
        ));
        self.y += 19.0;
    }

    /// A ramp of `steps` colours with its two end labels.
    fn ramp(&mut self, color: &dyn Fn(f64) -> Rgb, steps: u32, lo: String, hi: String) {
        let w = 200.0;
        let n = f64::from(steps);
        for k in 0..steps {
            let k = f64::from(k);
            self.out.push(Item::Rect {
                xywh: [self.x + w * k / n, self.y - 10.0, w / n + 0.5, 10.0],
                fill: color(k / (n - 1.0)),
            });
        }
        self.y += 14.0;
        if lo == hi {
            self.out.push(text(
                [self.x, self.y],
                format!("all at {lo}"),
                TextSize::Small,
                self.pal.muted,
                Anchor::Start,
            ));
        } else {
            self.out.push(text(
                [self.x, self.y],
                lo,
                TextSize::Small,
                self.pal.muted,
                Anchor::Start,
            ));
            self.out.push(text(
                [self.x + w, self.y],
                hi,
                TextSize::Small,
                self.pal.muted,
                Anchor::End,
            ));
        }
        self.y += 18.0;
    }
}

/// An arrowhead mark, as the frame's exits are drawn.
fn exit_mark(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
    out.push(Item::Shape {
        pts: vec![
            [c[0] + 5.0, c[1]],
            [c[0] - 4.0, c[1] - 4.0],
            [c[0] - 4.0, c[1] + 4.0],
        ],
        closed: true,
        stroke: None,
        fill: Some(pal.rapid),
    });
}

/// A hatched jaw, as the half-section marks the chuck side.
fn chuck_mark(c: [f64; 2], pal: &Palette, out: &mut Vec<Item>) {
    let s = Stroke {
        color: pal.muted,
        width: 1.0,
        dash: None,
    };
    out.push(line_item(
        [c[0] + 4.0, c[1] - 7.0],
        [c[0] + 4.0, c[1] + 7.0],
        s,
    ));
    for k in 0..3 {
        let y = c[1] + 7.0 - 5.0 * f64::from(k);
        out.push(line_item([c[0] - 4.0, y], [c[0] + 4.0, y - 6.0], s));
    }
}

/// Draws the legend panel at the right of the picture.
pub(crate) fn panel(
    plot: &Plot,
    coloring: &Coloring,
    look: &Look,
    legend: &Legend,
    framing: &Framing,
    out: &mut Vec<Item>,
) {
    let pal = &coloring.pal;
    let x0 = f64::from(look.width_px) - PANEL_W;
    out.push(Item::Rect {
        xywh: [x0, 0.0, PANEL_W, f64::from(look.height_px)],
        fill: pal.panel,
    });
    let mut p = Panel {
        x: x0 + 16.0,
        y: 28.0,
        pal,
        out,
    };
    p.line(tail(&legend.title, LEGEND_CHARS), TextSize::Bold, pal.text);
    let view = match (coloring.proj.view, coloring.proj.diameter_up) {
        (View::Xz, true) => "view XZ half-section (lathe)".to_string(),
        (View::Xy, _) => "view XY (top)".into(),
        (View::Xz, _) => "view XZ (front)".into(),
        (View::Yz, _) => "view YZ (side)".into(),
        (View::Iso, _) => "view isometric".into(),
    };
    p.line(view, TextSize::Normal, pal.muted);
    let frame = match (framing.on_cuts, look.fit) {
        (true, _) => "framed on the cuts",
        (false, crate::FitTo::Cuts) => "framed on all moves (no cuts)",
        (false, crate::FitTo::All) => "framed on all moves",
    };
    p.line(frame.into(), TextSize::Normal, pal.muted);
    p.gap();
    if framing.rapids_hidden {
        p.line("rapids hidden".into(), TextSize::Normal, pal.muted);
    } else {
        p.key(rapid_stroke(pal.rapid), "rapid");
    }
    let cut_label = match look.color {
        ColorBy::Depth => "cut, coloured by depth",
        ColorBy::Tool => "cut, coloured by tool",
        ColorBy::Feed => "cut, coloured by feed",
    };
    let sample = match look.color {
        ColorBy::Tool => tool_color(pal, 1),
        ColorBy::Depth => ramp(&pal.depth, 0.5, DEPTH_STEPS),
        ColorBy::Feed => ramp(&pal.feed, 0.5, FEED_STEPS),
    };
    p.key(cut_stroke(sample), cut_label);
    if plot.contour.vertices.len() > 1 {
        p.key(contour_stroke(pal.contour), "programmed contour");
    }
    if let Some(name) = &legend.compare {
        p.key(
            Stroke {
                color: pal.compare,
                width: 2.5,
                dash: None,
            },
            &tail(&format!("compare: {name}"), LEGEND_CHARS - 6),
        );
    }
    if coloring.proj.diameter_up {
        p.mark(chuck_mark, "chuck side (-Z)".into());
    }
    if plot.limits.is_some() {
        p.key(
            Stroke {
                color: pal.muted,
                width: 1.0,
                dash: Some([2.0, 3.0]),
            },
            "travel limits",
        );
    }
    p.gap();
    color_scale(&mut p, plot, coloring, look);
    if framing.exits > 0 {
        p.mark(exit_mark, format!("leaves the frame ({})", framing.exits));
    }
    p.mark(shapes::start, "start".into());
    if plot.hole_count > 0 {
        p.mark(shapes::hole, format!("holes ({})", plot.hole_count));
    }
    if !plot.tool_changes.is_empty() {
        p.mark(shapes::tool_change, "tool change".into());
    }
    if !plot.origins.is_empty() {
        p.mark(shapes::origin, "work origin".into());
    }
    if plot.alarm.is_some() {
        p.mark(shapes::alarm, "alarm: stopped here".into());
    }
    p.gap();
    for (k, v) in &legend.rows {
        p.line(k.clone(), TextSize::Bold, pal.text);
        for part in v.lines() {
            for l in wrap(part, LEGEND_CHARS) {
                p.line(l, TextSize::Normal, pal.text);
            }
        }
    }
    if let Some(a) = &plot.alarm {
        p.gap();
        p.line(
            format!("alarm {} line {} column {}", a.code, a.line, a.column),
            TextSize::Bold,
            pal.alarm,
        );
        for l in wrap(&a.message, LEGEND_CHARS) {
            p.line(l, TextSize::Normal, pal.alarm);
        }
    }
}

/// The colour scale of the cuts: depth or feed ramp, or tool swatches.
fn color_scale(p: &mut Panel<'_>, plot: &Plot, c: &Coloring, look: &Look) {
    let has_cuts = plot.path.vertices.iter().any(|v| v.kind == Kind::Cut);
    if !has_cuts {
        return;
    }
    match look.color {
        ColorBy::Depth => {
            let name = depth_name(&c.proj, look.units);
            let (lo, hi) = c.depth;
            let k = if c.proj.depth == [1.0, 0.0, 0.0] {
                2.0
            } else {
                1.0
            };
            p.line(format!("depth {name}"), TextSize::Normal, p.pal.muted);
            let ramp_at = |t: f64| ramp(&c.pal.depth, t, DEPTH_STEPS);
            p.ramp(
                &ramp_at,
                DEPTH_STEPS,
                look.units.len(lo * k),
                look.units.len(hi * k),
            );
        }
        ColorBy::Feed => {
            let (lo, hi) = c.feed;
            let u = look.units;
            p.line(
                format!("feed {}/min", u.name()),
                TextSize::Normal,
                p.pal.muted,
            );
            let ramp_at = |t: f64| ramp(&c.pal.feed, t, FEED_STEPS);
            let decimals = if u == DisplayUnits::In { 1 } else { 0 };
            p.ramp(
                &ramp_at,
                FEED_STEPS,
                format!("{:.*}", decimals, u.of_mm(lo)),
                format!("{:.*}", decimals, u.of_mm(hi)),
            );
        }
        ColorBy::Tool => {
            let mut used: Vec<u16> = plot
                .path
                .vertices
                .iter()
                .filter(|v| v.kind == Kind::Cut)
                .map(|v| v.tool)
                .collect();
            used.sort_unstable();
            used.dedup();
            for t in used.iter().take(12) {
                let name = match usize::from(*t)
                    .checked_sub(1)
                    .and_then(|i| plot.tools.get(i))
                {
                    Some(n) => format!("T{n}"),
                    None => "no tool".into(),
                };
                p.key(cut_stroke(tool_color(&c.pal, *t)), &name);
            }
            if used.len() > 12 {
                p.line(
                    format!("+{} more tools", used.len() - 12),
                    TextSize::Normal,
                    p.pal.muted,
                );
            }
            p.gap();
        }
    }
}

/// The depth axis as the legend names it.
fn depth_name(proj: &Projection, units: DisplayUnits) -> String {
    if proj.depth == [1.0, 0.0, 0.0] {
        format!("X diameter, {} (deep .. high)", units.name())
    } else {
        format!("Z, {} (deep .. high)", units.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_text_wraps_and_long_titles_keep_their_end() {
        assert_eq!(wrap("a bb ccc dddd", 6), vec!["a bb", "ccc", "dddd"]);
        assert_eq!(wrap("abcdefgh", 3), vec!["abc", "def", "gh"]);
        assert_eq!(tail("/a/long/path/prog.nc", 10), "...prog.nc");
    }
}
