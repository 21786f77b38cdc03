//! Planned times per block, for a back-plot whose vertices were stamped
//! with block numbers (`vcnc plot`'s page and the browser app alike): a
//! look-ahead planner knows a block's time only some blocks after the
//! block ran, so the plot's clock numbers the blocks ([`Blocks`]), the
//! planner is fed the same events with that number as their line
//! ([`Numbered`]), and its timeline ([`Stamps`]) keeps the planned time at
//! the end of each block, to retime the vertices after the run.
//!
//! ```text
//!   events ─┬─▶ plot sink (clock: Blocks::see) ─▶ vertices stamped 1, 2, 3 …
//!           └─▶ Numbered ─▶ Planner ─▶ Stamps: (block, seconds) … ─▶ time_of(stamp)
//! ```

use crate::{AxesMove, CycleTime, Pause, Profile, Segment, Timeline};
use std::sync::Arc;
use vcnc_core::{Event, Sink};

/// Numbers the blocks as events arrive: a new number whenever the source
/// line or file changes. The plot's clock and the planner's feed count
/// alike, so that a vertex's stamp names the block the planner timed.
#[derive(Debug, Default)]
pub struct Blocks {
    n: u64,
    last: Option<(u64, Option<Arc<str>>)>,
}

impl Blocks {
    /// Blocks counted so far (the number of the current one).
    pub fn count(&self) -> u64 {
        self.n
    }

    /// The number of the block `event` belongs to (counting it when it
    /// starts a new one).
    pub fn see(&mut self, event: &Event) -> u64 {
        if let Some(loc) = event.loc() {
            let same = self.last.as_ref().is_some_and(|(line, file)| {
                *line == loc.line
                    && match (file, &loc.file) {
                        (Some(a), Some(b)) => Arc::ptr_eq(a, b) || a == b,
                        (None, None) => true,
                        _ => false,
                    }
            });
            if !same {
                self.n += 1;
                self.last = Some((loc.line, loc.file.clone()));
            }
        }
        self.n
    }
}

/// Feeds `inner` (the planner) the events with their block number in
/// place of the line.
pub struct Numbered<S> {
    /// The sink fed (the planner).
    pub inner: S,
    /// The block count.
    pub blocks: Blocks,
}

impl<S: Sink> Sink for Numbered<S> {
    fn event(&mut self, event: &Event) {
        let n = self.blocks.see(event);
        let mut e = event.clone();
        if let Some(loc) = e.loc_mut() {
            loc.line = n;
        }
        self.inner.event(&e);
    }
    fn is_done(&self) -> bool {
        self.inner.is_done()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.inner.finish()
    }
}

/// Most blocks whose end time is kept (16 bytes each); past it every
/// other one is dropped and the rest are interpolated.
pub const MAX_STAMPS: usize = 1 << 18;

/// The planned timeline summed up, and the time at the end of each block
/// (the block number is the line `Numbered` gave it): exact up to
/// `MAX_STAMPS` blocks, then for every second, fourth … block.
#[derive(Debug, Default)]
pub struct Stamps {
    /// The planned timeline summed up.
    pub sum: CycleTime,
    table: Vec<(u64, f64)>,
    stride: u64,
}

impl Stamps {
    fn mark(&mut self, block: u64) {
        let t = self.sum.total_s;
        match self.table.last_mut() {
            Some(last) if last.0 == block => last.1 = t,
            Some(last) if block < last.0 + self.stride.max(1) => {}
            _ => {
                self.table.push((block, t));
                if self.table.len() >= MAX_STAMPS {
                    let mut k = 0usize;
                    self.table.retain(|_| {
                        k += 1;
                        k.is_multiple_of(2)
                    });
                    self.stride = self.stride.max(1) * 2;
                }
            }
        }
    }

    /// The planned time at the end of block `stamp` (interpolated between
    /// the blocks kept around it).
    pub fn time_of(&self, stamp: f64) -> f64 {
        let i = self.table.partition_point(|(b, _)| (*b as f64) < stamp);
        let Some(&(b1, t1)) = self.table.get(i) else {
            return self.sum.total_s;
        };
        let (b0, t0) = i
            .checked_sub(1)
            .and_then(|j| self.table.get(j))
            .copied()
            .unwrap_or((0, 0.0));
        let (b0, b1) = (b0 as f64, b1 as f64);
        if b1 <= b0 || stamp >= b1 {
            t1
        } else {
            t0 + (t1 - t0) * (stamp - b0).max(0.0) / (b1 - b0)
        }
    }
}

impl Timeline for Stamps {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        self.sum.segment(seg, profile);
        self.mark(seg.attr.line);
    }
    fn axes(&mut self, mv: &AxesMove) {
        self.sum.axes(mv);
        self.mark(mv.attr.line);
    }
    fn pause(&mut self, p: &Pause) {
        self.sum.pause(p);
        self.mark(p.attr.line);
    }
    fn untimed(&mut self, from: vcnc_core::Pos, to: vcnc_core::Pos, attr: &crate::Attr) {
        self.sum.untimed(from, to, attr);
        self.mark(attr.line);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_core::Loc;

    fn at_line(line: u64, file: Option<&Arc<str>>) -> Event {
        Event::Dwell {
            loc: Loc {
                line,
                file: file.cloned(),
            },
            seconds: 1.0,
        }
    }

    #[test]
    fn blocks_are_numbered_by_a_change_of_line_or_file() {
        let sub: Arc<str> = Arc::from("O0010");
        let mut b = Blocks::default();
        let seen: Vec<u64> = [
            at_line(5, None),
            at_line(5, None),
            at_line(6, None),
            at_line(6, Some(&sub)),
            at_line(6, Some(&Arc::from("O0010"))),
            at_line(5, None),
        ]
        .iter()
        .map(|e| b.see(e))
        .collect();
        assert_eq!(seen, vec![1, 1, 2, 3, 3, 4]);
    }

    #[test]
    fn stamps_give_each_block_its_end_time_exactly_then_within_a_stride() {
        // Odd blocks take 1 s, even blocks 2 s: block b ends at
        // b + ⌊b/2⌋ seconds.
        let end = |b: u64| (b + b / 2) as f64;
        let mut s = Stamps::default();
        let few = 1000u64;
        for b in 1..=few {
            s.sum.total_s = end(b);
            s.mark(b);
        }
        for b in [1, 2, 3, 500, 999, 1000] {
            assert_eq!(s.time_of(b as f64), end(b));
        }
        assert_eq!(s.time_of(0.0), 0.0);
        // Past MAX_STAMPS blocks every other one is dropped: the kept ones
        // stay exact and the others are interpolated within a block's time.
        let many = 3 * MAX_STAMPS as u64;
        for b in few + 1..=many {
            s.sum.total_s = end(b);
            s.mark(b);
        }
        assert!(s.table.len() < MAX_STAMPS);
        assert!(s.stride >= 4, "{}", s.stride);
        let mut worst = 0.0f64;
        for b in (1..=many).step_by(997) {
            worst = worst.max((s.time_of(b as f64) - end(b)).abs());
        }
        assert!(worst <= 1.0, "{worst}");
        assert_eq!(s.time_of(many as f64 + 5.0), end(many));
    }
}
