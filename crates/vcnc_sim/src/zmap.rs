//! The milled stock as a height field (Z-map): one height per grid cell,
//! the top of the material over the cell's centre, lowered to the swept
//! envelope of every move (`kernel.rs`).
//!
//! ```text
//!   y ▲  row j ─▶ worker j mod n       each worker owns every n-th row, so
//!     │  ┌──┬──┬──┬──┬──┐              any footprint (tens of rows) splits
//!     │  ├──┼──┼──┼──┼──┤ ◀ worker 1   evenly; a batch of moves runs on all
//!     │  ├──┼──┼──┼──┼──┤ ◀ worker 0   workers at once, each applying every
//!     │  └──┴──┴──┴──┴──┘              move in order to its own rows, so a
//!     └──────────────────▶ x           row's history is the program's order
//! ```
//!
//! A move visits only the rows its footprint crosses and, in each, the span
//! of cells the footprint covers (a capsule for a line, an annulus for an
//! arc, both clipped to the bounding box). A straight feed of a flat end
//! mill that continues a chain of such moves skips the disc at one of its
//! ends (`Cut::skip_start`/`skip_end`, decided by `chain.rs`): the cells
//! there are lowered as far by the neighbouring move of the chain, which
//! is what makes 3D finishing programs of short segments affordable (the
//! work per move is the band the tool's edge sweeps, 2RL, not the whole
//! footprint 2RL + πR²).
//!
//! Heights are `f32` (a tenth of a micron at a metre) in `[bottom, top]`;
//! each cell also remembers which tool cut it last (for pictures).

use crate::kernel::{Arc, Line, arc_envelope, line_envelope};
use crate::tool::{Cutter, Profile};
use rayon::prelude::*;
use rows::{Gather, Run};

mod rows;

/// Most cells a Z-map may have: 4 bytes of height and 1 of tool each,
/// so at most 250 MB.
pub const MAX_CELLS: usize = 50_000_000;

/// Removal shallower than this is no removal (a pass over its own
/// surface), mm.
pub const CUT_EPS_MM: f64 = 1e-3;

/// A move's path, in tip coordinates (machine minus tool offset), mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A straight move.
    Line(Line),
    /// An arc or helix in the XY plane.
    Arc(Arc),
}

impl Shape {
    /// The lowest tip height along the path.
    pub fn min_z(&self) -> f64 {
        match self {
            Shape::Line(l) => l.a[2].min(l.b[2]),
            Shape::Arc(a) => a.z0.min(a.z0 + a.dz),
        }
    }

    /// The end point.
    pub fn end(&self) -> [f64; 3] {
        match self {
            Shape::Line(l) => l.b,
            Shape::Arc(a) => a.point_at(1.0),
        }
    }

    /// Bounding box of the tip path in XY: (x0, y0, x1, y1).
    pub fn bounds_xy(&self) -> (f64, f64, f64, f64) {
        match self {
            Shape::Line(l) => (
                l.a[0].min(l.b[0]),
                l.a[1].min(l.b[1]),
                l.a[0].max(l.b[0]),
                l.a[1].max(l.b[1]),
            ),
            Shape::Arc(a) => {
                let (s, e) = (a.point_at(0.0), a.point_at(1.0));
                let (mut x0, mut y0, mut x1, mut y1) = (
                    s[0].min(e[0]),
                    s[1].min(e[1]),
                    s[0].max(e[0]),
                    s[1].max(e[1]),
                );
                for k in 0..4u8 {
                    let ang = f64::from(k) * std::f64::consts::FRAC_PI_2;
                    if passes(a, ang) {
                        let (x, y) = (
                            a.center[0] + a.radius * ang.cos(),
                            a.center[1] + a.radius * ang.sin(),
                        );
                        x0 = x0.min(x);
                        x1 = x1.max(x);
                        y0 = y0.min(y);
                        y1 = y1.max(y);
                    }
                }
                (x0, y0, x1, y1)
            }
        }
    }
}

fn passes(a: &Arc, phi: f64) -> bool {
    if a.sweep.abs() >= std::f64::consts::TAU {
        return true;
    }
    let tau = std::f64::consts::TAU;
    if a.sweep >= 0.0 {
        (phi - a.start_angle).rem_euclid(tau) <= a.sweep
    } else {
        (a.start_angle - phi).rem_euclid(tau) <= -a.sweep
    }
}

/// One move as the Z-map applies it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cut {
    /// The path.
    pub shape: Shape,
    /// Index of the cutter (in the list given to [`ZMap::apply`]).
    pub cutter: u8,
    /// Skip the cells strictly inside the tool's disc at the start.
    pub skip_start: bool,
    /// Skip the cells strictly inside the tool's disc at the end.
    pub skip_end: bool,
    /// Check that no material stands under the tool's centre at the end
    /// (a plunge of a tool that does not cut at its centre).
    pub check_centre: bool,
}

/// What one move did to the stock.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Hit {
    /// The deepest removal, mm.
    pub depth_mm: f32,
    /// Where (cell column, row).
    pub at: (u32, u32),
    /// The tool's bottom went below the stock's bottom where there was
    /// material.
    pub below: bool,
    /// How far the shank stood in material, mm (0: not at all).
    pub shank_mm: f32,
    /// How far the holder stood in material, mm.
    pub holder_mm: f32,
    /// Material stood under the centre of the tool at the end of the move.
    pub centre: bool,
}

impl Hit {
    fn merge(&mut self, o: &Hit) {
        if o.depth_mm > self.depth_mm {
            self.depth_mm = o.depth_mm;
            self.at = o.at;
        }
        self.below |= o.below;
        self.shank_mm = self.shank_mm.max(o.shank_mm);
        self.holder_mm = self.holder_mm.max(o.holder_mm);
        self.centre |= o.centre;
    }
}

/// The rows one worker owns.
#[derive(Debug, Clone)]
struct Band {
    /// Heights, row-major, rows w, w + n, w + 2n, …
    h: Vec<f32>,
    /// The tool that cut each cell last (index + 1; 0: uncut).
    tool: Vec<u8>,
    /// This worker's findings for the current batch.
    hits: Vec<Hit>,
    /// The run of cuts being applied row by row (reused).
    run: Run,
}

/// The height field over a rectangle of stock.
#[derive(Debug, Clone)]
pub struct ZMap {
    /// X of the grid's lower-left corner (the stock's), mm.
    pub x0: f64,
    /// Y of that corner, mm.
    pub y0: f64,
    /// Cell width, mm.
    pub dx: f64,
    /// Cell depth, mm.
    pub dy: f64,
    /// Cells along X.
    pub nx: usize,
    /// Cells along Y.
    pub ny: usize,
    /// The stock's top, mm.
    pub top: f64,
    /// The stock's bottom, mm.
    pub bottom: f64,
    bands: Vec<Band>,
}

/// Cells whose centres lie in [a, b] on an axis of `n` cells from `origin`
/// with pitch `step`: an index range, possibly empty (lo > hi).
#[inline]
fn cells(a: f64, b: f64, origin: f64, step: f64, n: usize) -> (isize, isize) {
    cells_inv(a, b, origin, 1.0 / step, n)
}

/// [`cells`] with the pitch's inverse given.
#[inline]
fn cells_inv(a: f64, b: f64, origin: f64, inv: f64, n: usize) -> (isize, isize) {
    let lo = ceil_index((a - origin) * inv - 0.5, n);
    let hi = floor_index((b - origin) * inv - 0.5, n);
    (lo, hi.min(isize_of(n) - 1))
}

/// ⌊v⌋ clamped to −1 ..= n (NaN: −1), without a libm call (the hot path
/// converts a few numbers per row).
#[inline]
#[allow(clippy::cast_possible_truncation)] // clamped to a small range first
fn floor_index(v: f64, n: usize) -> isize {
    // Clamped first in float (NaN fails the comparison: −1), so the
    // conversion is in range and the adjustment is one compare.
    let v = fmin(fmax(v, -1.0), n as f64);
    let t = v as isize;
    t - isize::from((t as f64) > v)
}

/// ⌈v⌉ clamped to −1 ..= n (NaN: −1).
#[inline]
#[allow(clippy::cast_possible_truncation)] // clamped to a small range first
fn ceil_index(v: f64, n: usize) -> isize {
    let v = fmin(fmax(v, -1.0), n as f64);
    let t = v as isize;
    t + isize::from((t as f64) < v)
}

fn isize_of(n: usize) -> isize {
    isize::try_from(n).unwrap_or(isize::MAX)
}

/// The larger of two numbers that are never NaN here (one instruction,
/// where `f64::max` also handles NaN).
#[inline]
fn fmax(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// The smaller of two numbers that are never NaN here.
#[inline]
fn fmin(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// `v` as a stored height (heights are bounded by the stock, so this only
/// rounds).
#[allow(clippy::cast_possible_truncation)]
fn to_f32(v: f64) -> f32 {
    v as f32
}

/// The x-interval a row at `y` meets the disc of radius `r` about `c`.
fn disc_span(y: f64, c: [f64; 3], r: f64) -> Option<(f64, f64)> {
    let dy = y - c[1];
    let w2 = r * r - dy * dy;
    (w2 >= 0.0).then(|| {
        let w = w2.sqrt();
        (c[0] - w, c[0] + w)
    })
}

/// A capsule's row spans, its per-move constants computed once.
#[derive(Debug, Clone, Copy)]
struct CapsuleRows {
    a: [f64; 3],
    b: [f64; 3],
    r: f64,
    ux: f64,
    uy: f64,
    len: f64,
    /// 1/ux and 1/uy, or 0 along an axis.
    inv_ux: f64,
    inv_uy: f64,
}

impl CapsuleRows {
    fn new(a: [f64; 3], b: [f64; 3], r: f64) -> CapsuleRows {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        let (ux, uy) = if len > 1e-12 {
            (dx / len, dy / len)
        } else {
            (0.0, 0.0)
        };
        let inv = |u: f64| if u.abs() > 1e-15 { 1.0 / u } else { 0.0 };
        CapsuleRows {
            a,
            b,
            r,
            ux,
            uy,
            len,
            inv_ux: inv(ux),
            inv_uy: inv(uy),
        }
    }

    /// The x-interval the row at `y` meets the band between the discs.
    #[inline]
    fn band_span(&self, y: f64) -> Option<(f64, f64)> {
        if self.len <= 1e-12 {
            return None;
        }
        let ry = y - self.a[1];
        let across = if self.inv_uy != 0.0 {
            let (p, q) = (
                (ry * self.ux - self.r) * self.inv_uy,
                (ry * self.ux + self.r) * self.inv_uy,
            );
            (p.min(q), p.max(q))
        } else if (ry * self.ux).abs() <= self.r {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            return None;
        };
        let along = if self.inv_ux != 0.0 {
            let (p, q) = (
                -ry * self.uy * self.inv_ux,
                (self.len - ry * self.uy) * self.inv_ux,
            );
            (p.min(q), p.max(q))
        } else {
            let t = ry * self.uy;
            if (0.0..=self.len).contains(&t) {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                return None;
            }
        };
        let (lo, hi) = (across.0.max(along.0), across.1.min(along.1));
        (lo <= hi).then_some((lo + self.a[0], hi + self.a[0]))
    }

    /// The x-interval the row at `y` meets.
    #[inline]
    fn span(&self, y: f64) -> Option<(f64, f64)> {
        let mut out = disc_span(y, self.a, self.r);
        let mut join = |s: Option<(f64, f64)>| {
            if let Some((lo, hi)) = s {
                out = Some(out.map_or((lo, hi), |(l, h)| (l.min(lo), h.max(hi))));
            }
        };
        join(disc_span(y, self.b, self.r));
        if self.len > 1e-12 {
            let ry = y - self.a[1];
            // |(p − a)·n| ≤ r with n = (−uy, ux), and 0 ≤ (p − a)·u ≤ len,
            // as ranges of x − ax.
            let across = if self.inv_uy != 0.0 {
                let (p, q) = (
                    (ry * self.ux - self.r) * self.inv_uy,
                    (ry * self.ux + self.r) * self.inv_uy,
                );
                Some((p.min(q), p.max(q)))
            } else {
                ((ry * self.ux).abs() <= self.r).then_some((f64::NEG_INFINITY, f64::INFINITY))
            };
            let along = if self.inv_ux != 0.0 {
                let (p, q) = (
                    -ry * self.uy * self.inv_ux,
                    (self.len - ry * self.uy) * self.inv_ux,
                );
                Some((p.min(q), p.max(q)))
            } else {
                let t = ry * self.uy;
                (0.0 <= t && t <= self.len).then_some((f64::NEG_INFINITY, f64::INFINITY))
            };
            if let (Some((a0, a1)), Some((b0, b1))) = (across, along) {
                let (lo, hi) = (a0.max(b0), a1.min(b1));
                if lo <= hi {
                    join(Some((lo + self.a[0], hi + self.a[0])));
                }
            }
        }
        out
    }
}

/// The x-interval a row at `y` meets the capsule of radius `r` around the
/// segment a→b (in XY).
#[cfg(test)]
fn capsule_span(y: f64, a: [f64; 3], b: [f64; 3], r: f64) -> Option<(f64, f64)> {
    CapsuleRows::new(a, b, r).span(y)
}

/// A flat end mill along a straight move with some XY travel: the
/// envelope's constants (`kernel::line_envelope`, flat case) computed
/// once per move.
#[derive(Debug, Clone, Copy)]
struct FlatLine {
    ax: f64,
    ay: f64,
    az: f64,
    dx: f64,
    dy: f64,
    dz: f64,
    inv_l2: f64,
    /// 1 / |AB| in XY.
    inv_len: f64,
    r2: f64,
}

impl FlatLine {
    fn new(l: &Line, r: f64) -> Option<FlatLine> {
        let (dx, dy) = (l.b[0] - l.a[0], l.b[1] - l.a[1]);
        let l2 = dx * dx + dy * dy;
        (l2 > 1e-18).then(|| FlatLine {
            ax: l.a[0],
            ay: l.a[1],
            az: l.a[2],
            dx,
            dy,
            dz: l.b[2] - l.a[2],
            inv_l2: 1.0 / l2,
            inv_len: 1.0 / l2.sqrt(),
            r2: r * r,
        })
    }
}

/// Where a span of a flat line's row lies.
#[derive(Debug, Clone, Copy)]
struct FlatSpan {
    /// Its first cell's column.
    i0: usize,
    /// Its row.
    j: usize,
    /// The row's centre line.
    y: f64,
    /// Whether the move's tip goes under the stock's bottom at all.
    through: bool,
}

/// What a worker needs to apply one move to one row.
struct RowCtx {
    /// The stock's bottom.
    bottom: f64,
    /// Index stored in the tool map.
    id: u8,
}

/// The deepest removal of a span while the fast paths lower its cells
/// (kept in registers), and the one step each takes on a cell.
struct SpanCut {
    deepest: f64,
    at: Option<usize>,
}

impl SpanCut {
    #[inline(always)]
    fn start(hit: &Hit) -> SpanCut {
        SpanCut {
            deepest: f64::from(hit.depth_mm),
            at: None,
        }
    }

    /// Lowers cell `k` to the envelope's height `e` (never under the
    /// stock's bottom), marking the tool where it removed more than
    /// 0.1 µm, and a cut through the bottom.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn lower(
        &mut self,
        k: usize,
        cell: &mut f32,
        tool: &mut u8,
        e: f64,
        ctx: &RowCtx,
        span: &FlatSpan,
        hit: &mut Hit,
    ) {
        let bottom = ctx.bottom;
        let before = f64::from(*cell);
        if e < before - 1e-4 {
            let new = fmax(e, bottom);
            let depth = before - new;
            *cell = to_f32(new);
            *tool = ctx.id;
            if depth > self.deepest {
                self.deepest = depth;
                self.at = Some(k);
            }
            if span.through && e < bottom - CUT_EPS_MM && before > bottom {
                hit.below = true;
            }
        } else if e < before {
            *cell = to_f32(fmax(e, bottom));
        }
    }

    /// The span's deepest removal into the move's hit.
    #[inline(always)]
    fn finish(self, span: &FlatSpan, hit: &mut Hit) {
        if let Some(k) = self.at {
            hit.depth_mm = to_f32(self.deepest);
            hit.at = (
                u32::try_from(span.i0 + k).unwrap_or(0),
                u32::try_from(span.j).unwrap_or(0),
            );
        }
    }
}

impl ZMap {
    /// A flat stock over `[x0, x1] × [y0, y1]` from `bottom` to `top` with
    /// cells of about `resolution` (at most that), applied by `workers`
    /// threads. Fails when the grid would pass [`MAX_CELLS`].
    pub fn new(
        (x0, y0, x1, y1): (f64, f64, f64, f64),
        (bottom, top): (f64, f64),
        resolution: f64,
        workers: usize,
    ) -> Result<ZMap, String> {
        let (w, d) = (x1 - x0, y1 - y0);
        let count = |len: f64| (len / resolution).ceil().max(1.0);
        let (fx, fy) = (count(w), count(d));
        if (fx * fy).is_nan() || fx * fy > MAX_CELLS as f64 {
            return Err(format!(
                "a {resolution} mm grid over {w:.3} × {d:.3} mm needs {:.0} cells, more than the bound of {MAX_CELLS} (250 MB): use a resolution of {:.3} mm or coarser",
                fx * fy,
                (w * d / MAX_CELLS as f64).sqrt() * 1.01
            ));
        }
        let (nx, ny) = (usize_of(fx), usize_of(fy));
        let n = workers.clamp(1, 16).min(ny);
        let bands = (0..n)
            .map(|k| {
                let rows = (ny + n - 1 - k) / n;
                Band {
                    h: vec![to_f32(top); rows * nx],
                    tool: vec![0; rows * nx],
                    hits: Vec::new(),
                    run: Run::default(),
                }
            })
            .collect();
        Ok(ZMap {
            x0,
            y0,
            dx: w / fx,
            dy: d / fy,
            nx,
            ny,
            top,
            bottom,
            bands,
        })
    }

    /// The height of cell (`i`, `j`).
    pub fn height(&self, i: usize, j: usize) -> f32 {
        let n = self.bands.len();
        self.bands
            .get(j % n)
            .and_then(|b| b.h.get((j / n) * self.nx + i))
            .copied()
            .unwrap_or(to_f32(self.top))
    }

    /// Row `j`'s heights.
    pub fn row(&self, j: usize) -> &[f32] {
        let n = self.bands.len();
        let k = j / n;
        self.bands
            .get(j % n)
            .and_then(|b| b.h.get(k * self.nx..(k + 1) * self.nx))
            .unwrap_or(&[])
    }

    /// Row `j`'s tool marks (index + 1 of the cutter that cut each cell
    /// last; 0 uncut).
    pub fn tool_row(&self, j: usize) -> &[u8] {
        let n = self.bands.len();
        let k = j / n;
        self.bands
            .get(j % n)
            .and_then(|b| b.tool.get(k * self.nx..(k + 1) * self.nx))
            .unwrap_or(&[])
    }

    /// The centre of cell (`i`, `j`).
    pub fn centre(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.x0 + (i as f64 + 0.5) * self.dx,
            self.y0 + (j as f64 + 0.5) * self.dy,
        )
    }

    /// The volume removed so far, mm³.
    pub fn removed_mm3(&self) -> f64 {
        let top = self.top;
        let sum: f64 = self
            .bands
            .iter()
            .map(|b| b.h.iter().map(|h| top - f64::from(*h)).sum::<f64>())
            .sum();
        sum * self.dx * self.dy
    }

    /// The stock's volume, mm³.
    pub fn stock_mm3(&self) -> f64 {
        self.nx as f64 * self.dx * self.ny as f64 * self.dy * (self.top - self.bottom)
    }

    /// Applies `cuts` in order with `cutters`; `hits` gets one [`Hit`] per
    /// cut. The workers run in parallel, each on its own rows.
    pub fn apply(&mut self, cuts: &[Cut], cutters: &[Cutter], hits: &mut Vec<Hit>) {
        let n = self.bands.len();
        let geo = Geometry {
            x0: self.x0,
            y0: self.y0,
            dx: self.dx,
            dy: self.dy,
            nx: self.nx,
            ny: self.ny,
            top: self.top,
            bottom: self.bottom,
            n,
            inv_dx: 1.0 / self.dx,
        };
        let work = |(w, band): (usize, &mut Band)| geo.apply_batch(w, band, cuts, cutters);
        if n > 1 && cuts.len() > 1 {
            self.bands.par_iter_mut().enumerate().for_each(work);
        } else {
            self.bands.iter_mut().enumerate().for_each(work);
        }
        hits.clear();
        hits.resize(cuts.len(), Hit::default());
        for band in &self.bands {
            for (h, b) in hits.iter_mut().zip(&band.hits) {
                h.merge(b);
            }
        }
    }
}

fn usize_of(v: f64) -> usize {
    // Callers bound v by MAX_CELLS first.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = v.clamp(1.0, MAX_CELLS as f64) as usize;
    n
}

/// The grid's shape, shared by the workers while they own their rows.
#[derive(Debug, Clone, Copy)]
struct Geometry {
    x0: f64,
    y0: f64,
    dx: f64,
    dy: f64,
    nx: usize,
    ny: usize,
    top: f64,
    bottom: f64,
    n: usize,
    /// 1 / dx.
    inv_dx: f64,
}

impl Geometry {
    /// Worker `w`'s rows whose centres lie in [ya, yb].
    fn rows(&self, w: usize, ya: f64, yb: f64) -> impl Iterator<Item = usize> + use<> {
        let (lo, hi) = cells(ya, yb, self.y0, self.dy, self.ny);
        let lo = usize::try_from(lo.max(0)).unwrap_or(0);
        let hi = usize::try_from(hi).ok();
        let n = self.n;
        let first = lo + (w + n - lo % n) % n;
        let end = hi.map_or(0, |h| h + 1);
        (first..end).step_by(n)
    }

    /// Applies `cuts` to worker `w`'s rows: runs of cuts that only lower
    /// cells row by row (`rows.rs`), any other cut on its own.
    fn apply_batch(&self, w: usize, band: &mut Band, cuts: &[Cut], cutters: &[Cutter]) {
        band.hits.clear();
        band.hits.resize(cuts.len(), Hit::default());
        let mut run = std::mem::take(&mut band.run);
        let mut k = 0;
        while k < cuts.len() {
            // A run: the cuts from here that only lower cells and have
            // their rows' form, while their rows stay close.
            run.clear();
            while let Some(cut) = cuts.get(k) {
                let Some(cutter) = cutters.get(usize::from(cut.cutter)) else {
                    k += 1;
                    continue;
                };
                if !Self::lowers_only(cut, cutter) {
                    break;
                }
                match self.gather(&mut run, k, cut, cutter) {
                    Gather::Added | Gather::Nothing => k += 1,
                    Gather::Full | Gather::Other => break,
                }
            }
            if !run.is_empty() {
                self.run_rows(w, (&mut band.h, &mut band.tool), &run, &mut band.hits);
                continue;
            }
            // Nothing gathered: the cut here takes the general path.
            if let Some(cut) = cuts.get(k)
                && let Some(cutter) = cutters.get(usize::from(cut.cutter))
            {
                band.run = std::mem::take(&mut run);
                let mut hit = Hit::default();
                self.apply_cut(w, band, cut, cutter, &mut hit);
                if let Some(slot) = band.hits.get_mut(k) {
                    *slot = hit;
                }
                run = std::mem::take(&mut band.run);
            }
            k += 1;
        }
        band.run = run;
    }

    /// Whether applying `cut` only lowers cells: no shank, holder or
    /// centre check reads the stock around it first.
    fn lowers_only(cut: &Cut, cutter: &Cutter) -> bool {
        cutter.flute_mm.is_none() && cutter.holder.is_none() && !cut.check_centre
    }

    fn apply_cut(&self, w: usize, band: &mut Band, cut: &Cut, cutter: &Cutter, hit: &mut Hit) {
        let min_z = cut.shape.min_z();
        // A straight retract only leaves what its start stood in.
        let retract = matches!(cut.shape, Shape::Line(l)
            if l.a[0] == l.b[0] && l.a[1] == l.b[1] && l.b[2] > l.a[2]);
        // A straight plunge: the flutes go first and cut the whole column
        // the shank and holder then pass through, so a body no wider than
        // the cutter meets only the wall of its own hole.
        let plunge = matches!(cut.shape, Shape::Line(l)
            if l.a[0] == l.b[0] && l.a[1] == l.b[1] && l.b[2] < l.a[2]);
        let inside_hole = |body_radius: f64| plunge && body_radius <= cutter.radius;
        if let Some(flute) = cutter.flute_mm
            && !retract
            && !inside_hole(cutter.shank_radius)
            && min_z + flute < self.top
        {
            let shank = cutter.flat_of_radius(cutter.shank_radius);
            hit.shank_mm = self.penetration(w, band, cut, &shank, flute);
        }
        if let Some((at, radius)) = cutter.holder
            && !retract
            && !inside_hole(radius)
            && min_z + at < self.top
        {
            hit.holder_mm = self.penetration(w, band, cut, &cutter.flat_of_radius(radius), at);
        }
        if cut.check_centre {
            let e = cut.shape.end();
            let (i, j) = (
                cells(e[0], e[0], self.x0, self.dx, self.nx).0,
                cells(e[1], e[1], self.y0, self.dy, self.ny).0,
            );
            if let (Ok(i), Ok(j)) = (usize::try_from(i), usize::try_from(j))
                && j % self.n == w
                && let Some(h) = band.h.get((j / self.n) * self.nx + i)
            {
                hit.centre = f64::from(*h) > e[2] + CUT_EPS_MM;
            }
        }
        if min_z >= self.top {
            return;
        }
        let ctx = RowCtx {
            bottom: self.bottom,
            id: cut.cutter.saturating_add(1),
        };
        let mut run = std::mem::take(&mut band.run);
        run.clear();
        let gathered = self.gather(&mut run, 0, cut, cutter);
        if matches!(gathered, Gather::Added) {
            let hits = std::slice::from_mut(hit);
            self.run_rows(w, (&mut band.h, &mut band.tool), &run, hits);
        }
        band.run = run;
        if !matches!(gathered, Gather::Other) {
            return;
        }
        let r = cutter.radius;
        let (bx0, by0, bx1, by1) = cut.shape.bounds_xy();
        let rows = match &cut.shape {
            Shape::Line(l) => CapsuleRows::new(l.a, l.b, r),
            Shape::Arc(_) => CapsuleRows::new([0.0; 3], [0.0; 3], r),
        };
        for j in self.rows(w, by0 - r, by1 + r) {
            let y = self.y0 + (j as f64 + 0.5) * self.dy;
            let base = (j / self.n) * self.nx;
            for (lo, hi) in self.spans(&cut.shape, cut, &rows, y, (bx0 - r, bx1 + r)) {
                let (Some(h), Some(t)) = (
                    band.h.get_mut(base + lo..=base + hi),
                    band.tool.get_mut(base + lo..=base + hi),
                ) else {
                    continue;
                };
                match &cut.shape {
                    Shape::Line(l) => {
                        self.cut_span(&ctx, lo, h, t, j, hit, |x| line_envelope(x, y, l, cutter));
                    }
                    Shape::Arc(a) => {
                        self.cut_span(&ctx, lo, h, t, j, hit, |x| arc_envelope(x, y, a, cutter));
                    }
                }
            }
        }
    }

    /// The x-interval row `y` meets a line's capsule and the interval of
    /// the disc it skips, for a move not along X.
    fn row_of_line(
        &self,
        cut: &Cut,
        rows: &CapsuleRows,
        r2: f64,
        margin: f64,
        y: f64,
    ) -> Option<(f64, f64, f64, f64)> {
        let (a, b) = (rows.a, rows.b);
        let (wy, wyb) = (y - a[1], y - b[1]);
        let (wa2, wb2) = (r2 - wy * wy, r2 - wyb * wyb);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut h_lo, mut h_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        if wa2 >= 0.0 {
            let wa = wa2.sqrt();
            (lo, hi) = (a[0] - wa, a[0] + wa);
            if cut.skip_start {
                (h_lo, h_hi) = (lo + margin, hi - margin);
            }
        }
        if wb2 >= 0.0 {
            let wb = wb2.sqrt();
            lo = lo.min(b[0] - wb);
            hi = hi.max(b[0] + wb);
            if cut.skip_end {
                (h_lo, h_hi) = (b[0] - wb + margin, b[0] + wb - margin);
            }
        }
        if let Some((s_lo, s_hi)) = rows.band_span(y) {
            lo = lo.min(s_lo);
            hi = hi.max(s_hi);
        }
        (lo <= hi).then_some((lo, hi, h_lo, h_hi))
    }

    /// [`Geometry::cut_span`] for a flat line. Along a row the
    /// projection t_c and the signed distance d⊥ from the line are linear
    /// in x, so each cell costs two additions before its square root.
    #[inline]
    fn flat_span(
        &self,
        ctx: &RowCtx,
        span: &FlatSpan,
        h: &mut [f32],
        tools: &mut [u8],
        hit: &mut Hit,
        f: &FlatLine,
    ) {
        let x = self.x0 + (span.i0 as f64 + 0.5) * self.dx;
        let (wx, wy) = (x - f.ax, span.y - f.ay);
        let mut tc = (wx * f.dx + wy * f.dy) * f.inv_l2;
        let mut dp = (wx * f.dy - wy * f.dx) * f.inv_len;
        let (g, q) = (self.dx * f.dx * f.inv_l2, self.dx * f.dy * f.inv_len);
        let up = f.dz > 0.0;
        let (r2, inv_l2, az, dz) = (f.r2, f.inv_l2, f.az, f.dz);
        let mut cut = SpanCut::start(hit);
        for (k, (cell, tool)) in h.iter_mut().zip(tools.iter_mut()).enumerate() {
            let d2 = dp * dp;
            let s = (fmax(r2 - d2, 0.0) * inv_l2).sqrt();
            let (t0, t1) = (fmax(tc - s, 0.0), fmin(tc + s, 1.0));
            tc += g;
            dp += q;
            if d2 > r2 || t0 > t1 {
                continue;
            }
            let e = az + dz * if up { t0 } else { t1 };
            cut.lower(k, cell, tool, e, ctx, span, hit);
        }
        cut.finish(span, hit);
    }

    /// The cell spans (inclusive index ranges) of row `y` that a move with
    /// tool radius `r` may lower (`rows`: the move's capsule, for lines).
    fn spans(
        &self,
        shape: &Shape,
        cut: &Cut,
        rows: &CapsuleRows,
        y: f64,
        (xa, xb): (f64, f64),
    ) -> impl Iterator<Item = (usize, usize)> + use<> {
        let r = rows.r;
        let (outer, hole) = match shape {
            Shape::Line(l) => {
                let hole = if cut.skip_end {
                    disc_span(y, l.b, r)
                } else if cut.skip_start {
                    disc_span(y, l.a, r)
                } else {
                    None
                };
                (rows.span(y), hole)
            }
            Shape::Arc(a) => {
                let c = [a.center[0], a.center[1], 0.0];
                let inner = a.radius - r;
                let hole = if inner > 0.0 {
                    disc_span(y, c, inner)
                } else {
                    None
                };
                (disc_span(y, c, a.radius + r), hole)
            }
        };
        let mut out = [(1usize, 0usize); 2];
        if let Some((lo, hi)) = outer {
            let (lo, hi) = (lo.max(xa), hi.min(xb));
            let (i0, i1) = cells_inv(lo, hi, self.x0, self.inv_dx, self.nx);
            let (i0, i1) = (i0.max(0), i1);
            // Cells strictly inside the hole are skipped; a margin keeps
            // the boundary's cells (computing them is always right).
            let (h0, h1) = match hole {
                Some((a, b)) => {
                    let m = 1e-9 * (1.0 + r);
                    cells_inv(a + m, b - m, self.x0, self.inv_dx, self.nx)
                }
                None => (1, 0),
            };
            let pieces = if h0 <= h1 {
                [(i0, i1.min(h0 - 1)), (i0.max(h1 + 1), i1)]
            } else {
                [(i0, i1), (1, 0)]
            };
            for (slot, (a, b)) in out.iter_mut().zip(pieces) {
                if a <= b
                    && let (Ok(a), Ok(b)) = (usize::try_from(a), usize::try_from(b))
                {
                    *slot = (a, b);
                }
            }
        }
        out.into_iter().filter(|(a, b)| a <= b)
    }

    /// Lowers the cells `h` (starting at column `i0` of row `j`) to the
    /// envelope `env` gives at each cell's x.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn cut_span(
        &self,
        ctx: &RowCtx,
        i0: usize,
        h: &mut [f32],
        tools: &mut [u8],
        j: usize,
        hit: &mut Hit,
        env: impl Fn(f64) -> Option<f64>,
    ) {
        let mut x = self.x0 + (i0 as f64 + 0.5) * self.dx;
        for (k, (cell, tool)) in h.iter_mut().zip(tools.iter_mut()).enumerate() {
            let here = x;
            x += self.dx;
            let Some(e) = env(here) else { continue };
            let before = f64::from(*cell);
            if e < before {
                let new = e.max(ctx.bottom);
                let depth = before - new;
                if depth > f64::from(hit.depth_mm) {
                    hit.depth_mm = to_f32(depth);
                    hit.at = (
                        u32::try_from(i0 + k).unwrap_or(0),
                        u32::try_from(j).unwrap_or(0),
                    );
                }
                if e < ctx.bottom - CUT_EPS_MM && before > ctx.bottom {
                    hit.below = true;
                }
                *cell = to_f32(new);
                if depth > 1e-4 {
                    *tool = ctx.id;
                }
            }
        }
    }

    /// How far material stands above a flat body of `body`'s radius whose
    /// bottom rides `offset` above the tip along the move (0: nowhere).
    fn penetration(&self, w: usize, band: &Band, cut: &Cut, body: &Cutter, offset: f64) -> f32 {
        let r = body.radius;
        let lifted = match cut.shape {
            Shape::Line(l) => Shape::Line(Line {
                a: [l.a[0], l.a[1], l.a[2] + offset],
                b: [l.b[0], l.b[1], l.b[2] + offset],
            }),
            Shape::Arc(a) => Shape::Arc(Arc {
                z0: a.z0 + offset,
                ..a
            }),
        };
        let whole = Cut {
            skip_start: false,
            skip_end: false,
            ..*cut
        };
        let (bx0, by0, bx1, by1) = lifted.bounds_xy();
        let rows = match &lifted {
            Shape::Line(l) => CapsuleRows::new(l.a, l.b, r),
            Shape::Arc(_) => CapsuleRows::new([0.0; 3], [0.0; 3], r),
        };
        let mut worst = 0.0f64;
        for j in self.rows(w, by0 - r, by1 + r) {
            let y = self.y0 + (j as f64 + 0.5) * self.dy;
            let base = (j / self.n) * self.nx;
            for (lo, hi) in self.spans(&lifted, &whole, &rows, y, (bx0 - r, bx1 + r)) {
                for i in lo..=hi {
                    let Some(h) = band.h.get(base + i) else {
                        continue;
                    };
                    let x = self.x0 + (i as f64 + 0.5) * self.dx;
                    let e = match &lifted {
                        Shape::Line(l) => line_envelope(x, y, l, body),
                        Shape::Arc(a) => arc_envelope(x, y, a, body),
                    };
                    if let Some(e) = e {
                        worst = worst.max(f64::from(*h) - e);
                    }
                }
            }
        }
        if worst > CUT_EPS_MM {
            to_f32(worst)
        } else {
            0.0
        }
    }
}

/// Whether a cutter is cut as a flat end mill (chains apply).
pub fn is_flat(c: &Cutter) -> bool {
    matches!(c.profile, Profile::Flat)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_row_is_the_union_of_its_discs_and_band() {
        let (a, b) = ([0.0, 0.0, 0.0], [10.0, 0.0, 0.0]);
        assert_eq!(capsule_span(0.0, a, b, 2.0), Some((-2.0, 12.0)));
        let (lo, hi) = capsule_span(1.0, a, b, 2.0).unwrap();
        assert!((lo + 3f64.sqrt()).abs() < 1e-12 && (hi - 10.0 - 3f64.sqrt()).abs() < 1e-12);
        assert_eq!(capsule_span(2.5, a, b, 2.0), None);
        // A diagonal: the row through the middle meets the band.
        let (lo, hi) = capsule_span(5.0, a, [10.0, 10.0, 0.0], 1.0).unwrap();
        let half = 2f64.sqrt();
        assert!((lo - (5.0 - half)).abs() < 1e-12 && (hi - (5.0 + half)).abs() < 1e-12);
    }

    #[test]
    fn a_grid_too_fine_for_the_bound_is_refused() {
        let e = ZMap::new((0.0, 0.0, 1000.0, 1000.0), (-10.0, 0.0), 0.01, 2).unwrap_err();
        assert!(e.contains("bound"), "{e}");
    }
}
