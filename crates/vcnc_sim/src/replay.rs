//! The replay of the viewer page: the stock at evenly spaced moments of
//! the run, kept small enough for a browser.
//!
//! A mill's frames are a coarse copy of the Z-map (at most 256 cells
//! across, each the mean of the fine cells it covers) stored as the cells
//! that changed since the frame before: the page applies frames in order
//! to go forward and replays from the stock to go back. A lathe's frames
//! are the half-section's contours. At most [`MAX_CHANGES`] changed cells
//! are kept in all; past that, frames are dropped until the last (the
//! finished part), which is always kept.

use crate::lathe::{Contour, Section};
use crate::zmap::ZMap;

/// Coarse cells across the longer side of the page's grid.
pub const PAGE_CELLS: usize = 256;

/// Most changed cells kept over all frames (8 bytes each).
pub const MAX_CHANGES: usize = 4_000_000;

/// The coarse grid the page draws.
#[derive(Debug, Clone, PartialEq)]
pub struct PageGrid {
    /// Fine cells per coarse cell along each axis.
    pub k: usize,
    /// Coarse cells along X.
    pub nx: usize,
    /// Coarse cells along Y.
    pub ny: usize,
    /// Heights of the last frame, row-major.
    pub heights: Vec<f32>,
}

/// One frame of a mill's replay.
#[derive(Debug, Clone, PartialEq)]
pub struct MapFrame {
    /// The program line the frame was taken at (0: the end).
    pub line: u64,
    /// Coarse cells that changed, and their new heights.
    pub changes: Vec<(u32, f32)>,
}

/// Frames of a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Replay {
    every: u64,
    next: u64,
    /// The coarse grid (mill).
    pub grid: Option<PageGrid>,
    /// Mill frames.
    pub map_frames: Vec<MapFrame>,
    /// Lathe frames: the line and the section's shapes.
    pub section_frames: Vec<(u64, Vec<Vec<Contour>>)>,
    changes: usize,
}

impl Replay {
    /// About `frames` frames over a run of `total` moves.
    pub fn new(frames: u32, total: u64) -> Replay {
        let every = (total / u64::from(frames.max(1))).max(1);
        Replay {
            every,
            next: every,
            ..Replay::default()
        }
    }

    /// Whether a frame is due after `moves` moves.
    pub fn due(&mut self, moves: u64) -> bool {
        if moves >= self.next {
            self.next = moves + self.every;
            true
        } else {
            false
        }
    }

    /// The coarse grid of `map` now.
    fn coarse(map: &ZMap, k: usize, nx: usize, ny: usize) -> Vec<f32> {
        let mut sum = vec![0.0f64; nx * ny];
        let mut count = vec![0u32; nx * ny];
        for j in 0..map.ny {
            let base = (j / k) * nx;
            for (i, h) in map.row(j).iter().enumerate() {
                let c = base + i / k;
                if let (Some(s), Some(n)) = (sum.get_mut(c), count.get_mut(c)) {
                    *s += f64::from(*h);
                    *n += 1;
                }
            }
        }
        sum.iter()
            .zip(&count)
            .map(|(s, n)| {
                #[allow(clippy::cast_possible_truncation)] // heights: rounding only
                let v = (s / f64::from((*n).max(1))) as f32;
                v
            })
            .collect()
    }

    /// Records the Z-map now, taken at `line`.
    pub fn record_map(&mut self, map: &ZMap, line: u64) {
        let grid = self.grid.get_or_insert_with(|| {
            let k = map.nx.max(map.ny).div_ceil(PAGE_CELLS).max(1);
            let (nx, ny) = (map.nx.div_ceil(k), map.ny.div_ceil(k));
            #[allow(clippy::cast_possible_truncation)]
            let top = map.top as f32;
            PageGrid {
                k,
                nx,
                ny,
                heights: vec![top; nx * ny],
            }
        });
        let now = Self::coarse(map, grid.k, grid.nx, grid.ny);
        let changes: Vec<(u32, f32)> = now
            .iter()
            .zip(&grid.heights)
            .enumerate()
            .filter(|(_, (a, b))| (**a - **b).abs() > 1e-5)
            .map(|(i, (a, _))| (u32::try_from(i).unwrap_or(0), *a))
            .collect();
        let last = line == 0;
        if !last && self.changes + changes.len() > MAX_CHANGES {
            return;
        }
        self.changes += changes.len();
        grid.heights = now;
        self.map_frames.push(MapFrame { line, changes });
    }

    /// Records the section now, taken at `line`.
    pub fn record_section(&mut self, s: &Section, line: u64) {
        let points: usize = s.shapes.iter().flatten().map(Vec::len).sum();
        if line != 0 && self.changes + points > MAX_CHANGES {
            return;
        }
        self.changes += points;
        self.section_frames.push((line, s.shapes.clone()));
    }
}
