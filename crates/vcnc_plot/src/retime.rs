//! Times and frames per vertex, once a run is over: [`Plot::retime`] turns
//! the clock's stamps into seconds (the CLI stamps blocks and retimes them
//! with the planner's times, which a look-ahead planner knows only some
//! blocks late), sharing a block's time among its vertices by length; and
//! `frame_runs` says which frame each vertex was cut in, for the page's
//! readout in work coordinates. Part of the plot sink (`collect.rs`).
//!
//! ```text
//!   stamps   0    1    2    2    2    3        block numbers (the clock's)
//!   time_of  0   10        20        30        end of each block, s
//!   seconds  0   10  13.3 16.7  20   30        a block's chords by length
//! ```

use crate::collect::{FrameMark, Plot, f32_of};
use crate::path::{Kind, Path};
use crate::view::P3;

/// Which frame each vertex of `path` was drawn under: the last frame whose
/// stamp is at or before the vertex's (a frame is reported before the
/// motion of its block, which carries the same stamp), as runs.
pub(crate) fn frame_runs(path: &Path, frames: &[FrameMark]) -> Vec<(u32, u32)> {
    let mut runs = Vec::new();
    let mut next = 0usize;
    for (i, v) in path.vertices.iter().enumerate() {
        let before = next;
        while frames.get(next).is_some_and(|f| f.time_s <= v.time_s) {
            next += 1;
        }
        if next != before
            && let (Ok(i), Ok(f)) = (u32::try_from(i), u32::try_from(next - 1))
        {
            runs.push((i, f));
        }
    }
    runs
}

impl Plot {
    /// Turns the clock's stamps into seconds: `time_of` maps a stamp to the
    /// time at the end of that point of the run (monotone), and `total_s`
    /// is the run's whole time. Vertices that share a stamp (the chords of
    /// one arc, the steps of one cycle) share its time by length, from the
    /// end of the vertex before them to the end of the stamp.
    pub fn retime(&mut self, total_s: f64, time_of: impl Fn(f64) -> f64) {
        retime_path(&mut self.path, &time_of);
        retime_path(&mut self.contour, &time_of);
        for f in &mut self.frames {
            f.time_s = f32_of(time_of(f64::from(f.time_s)));
        }
        self.total_time_s = total_s;
    }
}

/// Length of the segment from `a` to `b`.
fn dist(a: P3, b: P3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// [`Plot::retime`] for one path.
fn retime_path(path: &mut Path, time_of: &impl Fn(f64) -> f64) {
    let vs = &mut path.vertices;
    let mut start = 0usize;
    let mut t_before = 0.0f64;
    while start < vs.len() {
        let stamp = vs.get(start).map_or(0.0, |v| v.time_s);
        let mut end = start;
        while vs
            .get(end + 1)
            .is_some_and(|v| v.time_s.to_bits() == stamp.to_bits())
        {
            end += 1;
        }
        let t_end = time_of(f64::from(stamp));
        // Lengths of the segments that end at start..=end.
        let lens: Vec<f64> = (start..=end)
            .map(
                |i| match (i.checked_sub(1).and_then(|j| vs.get(j)), vs.get(i)) {
                    (Some(a), Some(b)) if b.kind != Kind::Jump => dist(a.at, b.at),
                    _ => 0.0,
                },
            )
            .collect();
        let total: f64 = lens.iter().sum();
        let mut run = 0.0;
        for (v, len) in vs.iter_mut().skip(start).zip(&lens) {
            run += len;
            let t = if total > 0.0 && t_end > t_before {
                t_before + (t_end - t_before) * run / total
            } else {
                t_end
            };
            v.time_s = f32_of(t);
        }
        t_before = t_end;
        start = end + 1;
    }
}
