//! Stage 3 of the motion stage: the soft travel limits of the machine file,
//! checked on the path the tool really follows (after the frame and the
//! compensation) and before any event of the move leaves.
//!
//! A straight segment stays inside the limit box exactly when its end points
//! do (the box is convex), so its bounding box decides; an arc adds the
//! circle's extreme points inside its sweep (`vcnc_core::geometry`). A G00
//! dog-leg (parameter 411) stays inside the box of its end points too.
//! A limit is passed only by more than `ZERO_MM`, the rounding noise of
//! the frame's sums.

use super::{MachineKind, MachineMove};
use crate::alarms;
use crate::config::Config;
use crate::words::Words;
use vcnc_core::events::Pos;
use vcnc_core::geometry::{ArcPath, ZERO_MM};
use vcnc_core::machine::Machine;
use vcnc_syntax::{Diagnostic, Span};

/// A move that leaves the travel limits: which axis, and how far it goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct OverTravel {
    /// Machine axis index.
    pub axis: usize,
    /// The coordinate beyond the limit, mm.
    pub value: f64,
}

impl OverTravel {
    /// E501 pointing at `span` (the word that moved the axis).
    pub fn alarm(&self, machine: &Machine, span: Span) -> Diagnostic {
        let (letter, min, max) = machine
            .axes
            .get(self.axis)
            .map_or((b'?', 0.0, 0.0), |a| (a.letter, a.min_mm, a.max_mm));
        alarms::over_travel(span, letter, self.value, min, max)
    }
}

impl Config<'_> {
    /// The word that positioned machine axis `i` in this block, if any.
    fn axis_span(&self, w: &Words<'_>, i: usize) -> Option<Span> {
        let a = self.axis_words.get(i)?;
        w.get(a.letter)
            .or_else(|| a.inc.and_then(|l| w.get(l)))
            .map(|word| word.span)
    }

    /// Stage 3 for a move of the current block: the alarm points at the
    /// axis word of `w`, else at `cmd`.
    pub fn travel_alarm(
        &self,
        mm: &MachineMove,
        cmd: Span,
        w: Option<&Words<'_>>,
    ) -> Result<(), Diagnostic> {
        let arc = match mm.kind {
            MachineKind::Arc { plane, .. } => mm.arc_path(self.plane_axes(plane, cmd)?),
            _ => None,
        };
        if let Err(out) = check(self.machine, mm, arc.as_ref()) {
            let span = w.and_then(|w| self.axis_span(w, out.axis)).unwrap_or(cmd);
            return Err(out.alarm(self.machine, span));
        }
        Ok(())
    }
}

/// Whether the whole path of `m` (whose arc, if it is one, is `arc`) stays
/// inside the travel limits.
#[inline]
pub(crate) fn check(
    machine: &Machine,
    m: &MachineMove,
    arc: Option<&ArcPath>,
) -> Result<(), OverTravel> {
    if let Some(path) = arc {
        let (lo, hi) = path.bounds(machine.axes.len());
        return inside(machine, &lo, &hi);
    }
    // A segment's box is the box of its ends.
    for (i, axis) in machine.axes.iter().enumerate() {
        let (a, b) = (m.from.0[i], m.to.0[i]);
        if a.min(b) < axis.min_mm - ZERO_MM || a.max(b) > axis.max_mm + ZERO_MM {
            let (lo, hi) = span_box(m.from, m.to, machine.axes.len());
            return inside(machine, &lo, &hi);
        }
    }
    Ok(())
}

/// Whether the box `lo..hi` is inside the limits, else the first axis out.
fn inside(machine: &Machine, lo: &Pos, hi: &Pos) -> Result<(), OverTravel> {
    for (i, axis) in machine.axes.iter().enumerate() {
        let value = if lo.get(i) < axis.min_mm - ZERO_MM {
            lo.get(i)
        } else if hi.get(i) > axis.max_mm + ZERO_MM {
            hi.get(i)
        } else {
            continue;
        };
        return Err(OverTravel { axis: i, value });
    }
    Ok(())
}

/// The box spanned by two points on the first `n` axes.
fn span_box(a: Pos, b: Pos, n: usize) -> (Pos, Pos) {
    let (mut lo, mut hi) = (a, a);
    for i in 0..n {
        lo.set(i, a.get(i).min(b.get(i)));
        hi.set(i, a.get(i).max(b.get(i)));
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::MachineKind;
    use vcnc_core::events::{ArcDir, Feed, Plane};
    use vcnc_core::geometry::PlaneAxes;

    fn p(x: f64, y: f64) -> Pos {
        Pos([x, y, 0.0, 0.0, 0.0, 0.0])
    }

    fn arc_move(from: Pos, to: Pos, center: (f64, f64), dir: ArcDir) -> (MachineMove, ArcPath) {
        let m = MachineMove {
            kind: MachineKind::Arc {
                center,
                plane: Plane::Xy,
                dir,
                feed: Feed::PerMin(1.0),
            },
            from,
            to,
            exact_stop: false,
        };
        let axes = PlaneAxes {
            a: 0,
            b: 1,
            n: Some(2),
        };
        let path = m.arc_path(axes).unwrap();
        (m, path)
    }

    #[test]
    fn an_arc_whose_ends_are_inside_can_still_leave_the_box() {
        let machine = Machine::from_toml(include_str!(
            "../../../../tests/fixtures/machines/mill_travel_limits.toml"
        ))
        .unwrap();
        // From (999, 0) round (0, 0) to (-999, 0) through y = 999: inside.
        let (m, path) = arc_move(p(999.0, 0.0), p(-999.0, 0.0), (0.0, 0.0), ArcDir::Ccw);
        assert_eq!(check(&machine, &m, Some(&path)), Ok(()));
        // From (600, 500) clockwise round (600, 0) to (600, -500) passes
        // x = 1100, beyond the 1000 mm limit, though both ends are inside.
        let (m, path) = arc_move(p(600.0, 500.0), p(600.0, -500.0), (600.0, 0.0), ArcDir::Cw);
        assert_eq!(
            check(&machine, &m, Some(&path)),
            Err(OverTravel {
                axis: 0,
                value: 1100.0
            })
        );
        // The straight chord between the same ends stays inside.
        assert_eq!(check(&machine, &m, None), Ok(()));
    }
}
