//! Clipping a flat picture to its frame, and the marks where moves leave
//! it. Part of the [`crate::scene`]: a picture framed on the cuts
//! (`--fit cuts`) leaves home, G53 and tool-change moves partly outside;
//! they are cut at the frame's edge, and a small arrowhead in the move's
//! colour sits where each one leaves, pointing the way it goes:
//!
//! ```text
//!   ┌──────────────────────────┐
//!   │   ╱╲    cuts             │
//!   │  ╱  ╲______              ▶  a rapid to the tool change leaves here
//!   │ ╱          ╲ _ _ _ _ _ _ ▶
//!   └──────────────────────────┘
//! ```
//!
//! Lines are clipped with the Liang–Barsky parametric test (the segment's
//! parameter interval is narrowed by each of the four edges in turn); an
//! arc that does not fit the frame whole becomes chords within a quarter
//! pixel first. Exits that land within a few pixels of one another with
//! the same heading share one arrowhead, so a hundred retracts to the same
//! place show as one mark.

use crate::scene::{Item, Seg, Stroke};
use crate::theme::Rgb;
use std::collections::HashSet;

/// The frame: a screen rectangle, px (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clip {
    /// Left edge.
    pub x0: f64,
    /// Top edge.
    pub y0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y1: f64,
}

impl Clip {
    /// Whether `p` is inside, with `slack` px to spare outside.
    pub fn contains(&self, p: [f64; 2], slack: f64) -> bool {
        p[0] >= self.x0 - slack
            && p[0] <= self.x1 + slack
            && p[1] >= self.y0 - slack
            && p[1] <= self.y1 + slack
    }

    /// The parameter interval `[t0, t1]` of `a + t·(b − a)` inside the
    /// frame, if any (Liang–Barsky).
    pub fn line(&self, a: [f64; 2], b: [f64; 2]) -> Option<(f64, f64)> {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        // Each edge as p·t ≤ q: left, right, top, bottom.
        for (p, q) in [
            (-dx, a[0] - self.x0),
            (dx, self.x1 - a[0]),
            (-dy, a[1] - self.y0),
            (dy, self.y1 - a[1]),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        (t0 <= t1 && t0.is_finite() && t1.is_finite()).then_some((t0, t1))
    }

    /// The point of the frame's edge nearest to `p` (itself when inside).
    pub fn pin(&self, p: [f64; 2]) -> [f64; 2] {
        [p[0].clamp(self.x0, self.x1), p[1].clamp(self.y0, self.y1)]
    }
}

/// Points along a screen arc (the start excluded), chords within a
/// quarter pixel of it, at most 4096.
pub fn arc_points(
    center: [f64; 2],
    radius: f64,
    start: f64,
    sweep: f64,
) -> impl Iterator<Item = [f64; 2]> {
    let step = if radius > 0.25 {
        2.0 * (1.0 - 0.25 / radius).clamp(-1.0, 1.0).acos()
    } else {
        std::f64::consts::PI
    };
    let wanted = (sweep.abs() / step.max(1e-3)).ceil();
    // Clamped to 1..=4096, so the conversion is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = if wanted.is_finite() {
        wanted.clamp(1.0, 4096.0) as u32
    } else {
        1
    };
    (1..=n).map(move |k| {
        let a = start + sweep * f64::from(k) / f64::from(n);
        [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
    })
}

/// Most arrowheads drawn.
const MAX_EXITS: usize = 2000;
/// Exits closer than this (px) with the same heading share an arrowhead.
const EXIT_CELL: f64 = 8.0;

/// The places where moves leave the frame.
#[derive(Debug, Default)]
pub struct Exits {
    seen: HashSet<(i64, i64, u8, Rgb)>,
    marks: Vec<([f64; 2], [f64; 2], Rgb)>,
    /// Moves that leave the frame, marked or not.
    pub count: u64,
}

/// `v` as a whole number of `cell`s (clamped far inside i64).
fn cell_of(v: f64, cell: f64) -> i64 {
    // Clamped before the conversion.
    #[allow(clippy::cast_possible_truncation)]
    let k = (v / cell).floor().clamp(-1e15, 1e15) as i64;
    k
}

impl Exits {
    /// A move of colour `color` heading along `dir` leaves the frame at
    /// `at`.
    pub fn add(&mut self, at: [f64; 2], dir: [f64; 2], color: Rgb) {
        let len = dir[0].hypot(dir[1]);
        if len <= 0.0 || !len.is_finite() {
            return;
        }
        self.count += 1;
        let unit = [dir[0] / len, dir[1] / len];
        // One of 16 headings.
        let heading = cell_of(
            unit[1].atan2(unit[0]) + std::f64::consts::PI,
            std::f64::consts::PI / 8.0,
        );
        let heading = u8::try_from(heading.rem_euclid(16)).unwrap_or(0);
        let key = (
            cell_of(at[0], EXIT_CELL),
            cell_of(at[1], EXIT_CELL),
            heading,
            color,
        );
        if self.marks.len() < MAX_EXITS && self.seen.insert(key) {
            self.marks.push((at, unit, color));
        }
    }

    /// The arrowheads, tip on the edge.
    pub fn items(&self, out: &mut Vec<Item>) {
        for (at, u, color) in &self.marks {
            let n = [-u[1], u[0]];
            let back = [at[0] - 9.0 * u[0], at[1] - 9.0 * u[1]];
            out.push(Item::Shape {
                pts: vec![
                    *at,
                    [back[0] + 4.0 * n[0], back[1] + 4.0 * n[1]],
                    [back[0] - 4.0 * n[0], back[1] - 4.0 * n[1]],
                ],
                closed: true,
                stroke: None,
                fill: Some(*color),
            });
        }
    }
}

/// Builds runs of equally styled, connected pieces into path items.
pub struct Runs<'a> {
    out: &'a mut Vec<Item>,
    current: Option<(Stroke, [f64; 2], Vec<Seg>)>,
    pen: Option<[f64; 2]>,
}

impl<'a> Runs<'a> {
    /// Runs written into `out`.
    pub fn new(out: &'a mut Vec<Item>) -> Runs<'a> {
        Runs {
            out,
            current: None,
            pen: None,
        }
    }

    /// Ends the current run.
    pub fn flush(&mut self) {
        if let Some((stroke, start, segs)) = self.current.take() {
            self.out.push(Item::Path {
                stroke,
                start,
                segs,
            });
        }
        self.pen = None;
    }

    /// Adds `seg` from `from` to `to`, continuing the run when it has the
    /// same stroke and ends at `from`.
    pub fn push(&mut self, stroke: Stroke, from: [f64; 2], seg: Seg, to: [f64; 2]) {
        let continues =
            self.pen == Some(from) && self.current.as_ref().is_some_and(|(s, _, _)| *s == stroke);
        if continues {
            if let Some((_, _, segs)) = &mut self.current {
                segs.push(seg);
            }
        } else {
            self.flush();
            self.current = Some((stroke, from, vec![seg]));
        }
        self.pen = Some(to);
    }

    /// Adds the part of the line `a`–`b` inside `clip`, and an exit mark
    /// where it leaves.
    pub fn line(
        &mut self,
        clip: &Clip,
        exits: &mut Exits,
        stroke: Stroke,
        a: [f64; 2],
        b: [f64; 2],
    ) {
        let Some((t0, t1)) = clip.line(a, b) else {
            return;
        };
        let at = |t: f64| {
            if t <= 0.0 {
                a
            } else if t >= 1.0 {
                b
            } else {
                [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
            }
        };
        let (p0, p1) = (at(t0), at(t1));
        if p0 != p1 {
            self.push(stroke, p0, Seg::Line(p1), p1);
        }
        if t1 < 1.0 {
            exits.add(p1, [b[0] - a[0], b[1] - a[1]], stroke.color);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAME: Clip = Clip {
        x0: 0.0,
        y0: 0.0,
        x1: 100.0,
        y1: 50.0,
    };

    #[test]
    fn a_line_is_cut_where_it_crosses_the_edges() {
        // From inside (50, 25) to (150, 25): leaves at x = 100, t = 1/2.
        assert_eq!(FRAME.line([50.0, 25.0], [150.0, 25.0]), Some((0.0, 0.5)));
        // Across the whole frame diagonally from (-50, -25) to (150, 75):
        // enters at t = 1/4 (0, 0), leaves at t = 3/4 (100, 50).
        assert_eq!(
            FRAME.line([-50.0, -25.0], [150.0, 75.0]),
            Some((0.25, 0.75))
        );
        // Wholly outside, beside it.
        assert_eq!(FRAME.line([-10.0, 0.0], [-10.0, 50.0]), None);
        assert_eq!(FRAME.line([110.0, 60.0], [200.0, 70.0]), None);
    }

    #[test]
    fn one_arrowhead_for_many_moves_leaving_at_one_place() {
        let mut exits = Exits::default();
        for k in 0..100 {
            let y = 20.0 + f64::from(k) * 0.01;
            exits.add([100.0, y], [1.0, 0.0], Rgb(255, 0, 0));
        }
        exits.add([100.0, 20.0], [0.0, -1.0], Rgb(255, 0, 0));
        assert_eq!(exits.count, 101);
        let mut items = Vec::new();
        exits.items(&mut items);
        assert_eq!(items.len(), 2, "two headings, two arrowheads");
        // The first points right: its tip is the exit, its base 9 px back.
        let Item::Shape { pts, .. } = &items[0] else {
            panic!("{:?}", items[0]);
        };
        assert_eq!(pts[0], [100.0, 20.0]);
        assert_eq!(pts[1], [91.0, 24.0]);
    }
}
