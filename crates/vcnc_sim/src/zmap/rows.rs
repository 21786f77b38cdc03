//! Runs of flat-end-mill cuts applied row by row.
//!
//! A 3D finishing program's move is short (0.5 mm) against the tool (6
//! mm): it crosses ~60 rows and lowers ~5 cells in each, so what a row
//! costs to set up (its half-width, the span's ends as cell indices, the
//! slices) was most of the work. A worker therefore takes a run of
//! consecutive cuts that only lower cells (no shank, holder or centre
//! check reads the stock around them) and applies them row by row: for
//! each of its rows, every cut of the run that crosses it, in program
//! order.
//!
//! ```text
//!   per cut (before)                 per run (now)
//!   for cut { for row { span } }     for row { for cut crossing it { span } }
//! ```
//!
//! A cell belongs to one row, so it still sees the cuts in program order;
//! a cut still visits its rows upwards and each row's cells left to
//! right, so its deepest removal and where it is are the same. What a run
//! shares: the row's slices and centre line, and for cuts along X and
//! discs about the same line (a raster pass and its chain's vertices) the
//! half-width the tool covers on the row — one square root a row for the
//! whole pass instead of one a move. The ends of a span are computed in
//! cell-index space from per-cut constants split into integer and
//! fractional parts ([`Split`]), so a row of a cut along X is a few
//! integer additions and comparisons, and its cells.

use crate::tool::Cutter;

use super::{
    CUT_EPS_MM, CapsuleRows, Cut, FlatLine, FlatSpan, Geometry, Hit, RowCtx, ceil_index, cells,
    floor_index, fmax, fmin, isize_of, to_f32,
};

/// A run's union of rows may be at most this many times the rows its
/// cuts really cross (each cut tests each row of the union once).
const RUN_SLACK: usize = 2;

/// What [`Geometry::gather`] did with a cut.
pub(super) enum Gather {
    /// It joined the run.
    Added,
    /// It lowers nothing (it stays above the stock).
    Nothing,
    /// It would spread the run's rows too far: the run is full.
    Full,
    /// It is for the general path (`Geometry::apply_cut`).
    Other,
}

/// A run of cuts being gathered, then applied row by row. Its vectors
/// are reused batch after batch (no allocation a move).
#[derive(Debug, Default, Clone)]
pub(super) struct Run {
    /// Each cut's first and last row, apart from the rest: every row of
    /// the run tests every cut's, so they are kept small and together.
    rows: Vec<[u32; 2]>,
    cuts: Vec<RowCut>,
    slanted: Vec<Slanted>,
    /// The union of the rows and how many rows the cuts cross in all.
    lo: u32,
    hi: u32,
    sum: usize,
}

/// One cut of a run, its constants computed once.
#[derive(Debug, Clone, Copy)]
struct RowCut {
    /// Its place in the batch (the hit it adds to).
    k: usize,
    /// Index stored in the tool map.
    id: u8,
    /// Whether its tip goes under the stock's bottom at all.
    through: bool,
    /// Its [`Slanted`] in the run's list, or `u32::MAX`: a [`Straight`].
    slanted: u32,
    /// Cuts with the same line number share their line (its y and the
    /// tool's radius), so a row's half-width is computed once for them.
    line: u32,
    s: Straight,
}

/// Any other straight move with some XY travel.
#[derive(Debug, Clone, Copy)]
struct Slanted {
    cut: Cut,
    f: FlatLine,
    rows: CapsuleRows,
}

/// A move along X (or a disc) in cell-index space: a cell i's centre is at
/// u = i, the path's ends at `lo` ≤ `hi`; on a row where the tool covers a
/// half-width h (h_u = h / dx cells) the move covers [lo − h_u, hi + h_u]
/// less the skipped disc, and its envelope is linear along the row:
/// max(base + slope·i − kz·h, floor) (the flat end mill's bottom where its
/// edge leaves the cell going down, or enters it going up).
#[derive(Debug, Clone, Copy)]
pub(super) struct Straight {
    /// The line's (or disc centre's) y and the tool's radius squared.
    cy: f64,
    r2: f64,
    lo: Split,
    hi: Split,
    /// The skipped disc's centre (`lo` or `hi`), if any.
    hole: Option<Split>,
    /// How far inside its disc a cell must be to be skipped, in cells.
    margin: f64,
    base: f64,
    slope: f64,
    kz: f64,
    floor: f64,
}

/// A place in cell-index space as its integer and fractional parts
/// (0 ≤ frac < 1), so that a span's end on a row is an integer sum and a
/// comparison of fractions — exact, and no float-to-index conversion.
#[derive(Debug, Clone, Copy)]
struct Split {
    int: isize,
    frac: f64,
}

/// Beyond this many cells from the grid a place is clamped (the grid has
/// at most 50 M cells a side; its spans are clamped to the row anyway).
const FAR: f64 = (1u64 << 40) as f64;

impl Split {
    #[allow(clippy::cast_possible_truncation)] // clamped to ±2⁴⁰ first
    fn of(u: f64) -> Split {
        let u = fmin(fmax(u, -FAR), FAR);
        let t = u as isize;
        let int = t - isize::from((t as f64) > u);
        Split {
            int,
            frac: u - int as f64,
        }
    }
}

/// The half-width a row's last line gave, kept while the cuts of a row
/// share their line.
struct Half {
    line: u32,
    /// mm, and in cells; `None`: the row misses the tool.
    half: Option<(f64, Split)>,
}

impl Run {
    /// Empties the run for the next.
    pub(super) fn clear(&mut self) {
        self.rows.clear();
        self.cuts.clear();
        self.slanted.clear();
        (self.lo, self.hi, self.sum) = (u32::MAX, 0, 0);
    }

    /// Takes a cut crossing rows `j0..=j1` unless testing every cut on
    /// every row of the grown union would cost more than [`RUN_SLACK`]
    /// times the rows the cuts cross (a run always takes its first cut).
    fn admit(&mut self, j0: u32, j1: u32) -> bool {
        let (lo, hi) = (self.lo.min(j0), self.hi.max(j1));
        let sum = self.sum + (j1 - j0) as usize + 1;
        let count = self.cuts.len();
        if count > 0 && (count + 1) * ((hi - lo) as usize + 1) > RUN_SLACK * sum {
            return false;
        }
        (self.lo, self.hi, self.sum) = (lo, hi, sum);
        true
    }

    /// The line number of a straight cut about `cy` with radius² `r2`.
    fn line_of(&self, cy: f64, r2: f64) -> u32 {
        let last = self.cuts.iter().rev().find(|c| c.slanted == u32::MAX);
        match last {
            Some(c) if c.s.cy == cy && c.s.r2 == r2 => c.line,
            Some(c) => c.line.wrapping_add(1),
            None => 0,
        }
    }

    pub(super) fn is_empty(&self) -> bool {
        self.cuts.is_empty()
    }
}

impl Geometry {
    /// Adds cut `k` to `run` when it is a straight move of a flat end
    /// mill that lowers something and the run has room for its rows.
    pub(super) fn gather(&self, run: &mut Run, k: usize, cut: &Cut, cutter: &Cutter) -> Gather {
        let (super::Shape::Line(l), true) = (&cut.shape, super::is_flat(cutter)) else {
            return Gather::Other;
        };
        let (a, b, r) = (l.a, l.b, cutter.radius);
        let min_z = fmin(a[2], b[2]);
        if min_z >= self.top {
            return Gather::Nothing;
        }
        let (j0, j1) = cells(
            fmin(a[1], b[1]) - r,
            fmax(a[1], b[1]) + r,
            self.y0,
            self.dy,
            self.ny,
        );
        // Rows are below the grid's bound of 50 M cells, so they fit u32.
        let (Ok(j0), Ok(j1)) = (u32::try_from(j0.max(0)), u32::try_from(j1)) else {
            return Gather::Nothing;
        };
        if j0 > j1 {
            return Gather::Nothing;
        }
        let standing = a[0] == b[0] && a[1] == b[1];
        let f = FlatLine::new(l, r);
        if !standing && f.is_none() {
            // A few nanometres of travel: the general path's exact form.
            return Gather::Other;
        }
        if !run.admit(j0, j1) {
            return Gather::Full;
        }
        let s = self.straight(cut, a, b, r);
        let slanted = match f {
            Some(f) if !standing && a[1] != b[1] => {
                run.slanted.push(Slanted {
                    cut: *cut,
                    f,
                    rows: CapsuleRows::new(a, b, r),
                });
                u32::try_from(run.slanted.len() - 1).unwrap_or(u32::MAX)
            }
            _ => u32::MAX,
        };
        let line = if slanted == u32::MAX {
            run.line_of(s.cy, s.r2)
        } else {
            u32::MAX
        };
        run.rows.push([j0, j1]);
        run.cuts.push(RowCut {
            k,
            id: cut.cutter.saturating_add(1),
            through: min_z < self.bottom - super::CUT_EPS_MM,
            slanted,
            line,
            s,
        });
        Gather::Added
    }

    /// A move along X (or standing, or straight up or down) in cell-index
    /// space. The envelope at a covered cell of x is the tip's height
    /// where the edge leaves it (descending) or enters it (ascending):
    /// z_a + dz·((x − x_a)/Dx) − |dz|·h/|Dx|, floored at the lower end; a
    /// tool without XY travel has the lower end's height over its disc.
    fn straight(&self, cut: &Cut, a: [f64; 3], b: [f64; 3], r: f64) -> Straight {
        let to_u = |x: f64| (x - self.x0) * self.inv_dx - 0.5;
        let (ua, ub) = (to_u(a[0]), to_u(b[0]));
        let travel = b[0] - a[0];
        let floor = fmin(a[2], b[2]);
        let (base, slope, kz) = if travel == 0.0 {
            (floor, 0.0, 0.0)
        } else {
            let dz = b[2] - a[2];
            let per_mm = dz / travel;
            (
                a[2] + per_mm * (self.x0 + 0.5 * self.dx - a[0]),
                per_mm * self.dx,
                dz.abs() / travel.abs(),
            )
        };
        let hole = if travel == 0.0 {
            None
        } else if cut.skip_end {
            Some(ub)
        } else if cut.skip_start {
            Some(ua)
        } else {
            None
        };
        Straight {
            cy: a[1],
            r2: r * r,
            lo: Split::of(fmin(ua, ub)),
            hi: Split::of(fmax(ua, ub)),
            hole: hole.map(Split::of),
            margin: 1e-9 * (1.0 + r) * self.inv_dx,
            base,
            slope,
            kz,
            floor,
        }
    }

    /// Applies a run to worker `w`'s rows, row by row, each row's cuts in
    /// program order; `hits[c.k]` gets cut c's findings.
    pub(super) fn run_rows(
        &self,
        w: usize,
        (h, tool): (&mut [f32], &mut [u8]),
        run: &Run,
        hits: &mut [Hit],
    ) {
        if run.lo > run.hi {
            return;
        }
        let (lo, hi) = (run.lo as usize, run.hi as usize);
        let (n, nx) = (self.n, self.nx);
        let mut j = lo + (w + n - lo % n) % n;
        let mut base = (j / n) * nx;
        while j <= hi {
            let (Some(hr), Some(tr)) = (h.get_mut(base..base + nx), tool.get_mut(base..base + nx))
            else {
                return;
            };
            let y = self.y0 + (j as f64 + 0.5) * self.dy;
            let mut half = Half {
                line: u32::MAX,
                half: None,
            };
            // j fits u32: it is a row of the grid.
            let j32 = u32::try_from(j).unwrap_or(u32::MAX);
            for (rows, c) in run.rows.iter().zip(&run.cuts) {
                if j32 < rows[0] || j32 > rows[1] {
                    continue;
                }
                let Some(hit) = hits.get_mut(c.k) else {
                    continue;
                };
                if c.slanted == u32::MAX {
                    if c.line != half.line {
                        half = Half::of(c, y, self.inv_dx);
                    }
                    if let Some(hw) = half.half {
                        self.straight_row(c, hw, hr, tr, hit, j);
                    }
                } else if let Some(sl) = run.slanted.get(c.slanted as usize) {
                    let ctx = RowCtx {
                        bottom: self.bottom,
                        id: c.id,
                    };
                    let span = FlatSpan {
                        i0: 0,
                        j,
                        y,
                        through: c.through,
                    };
                    self.slanted_row(&ctx, span, sl, hr, tr, hit);
                }
            }
            j += n;
            base += nx;
        }
    }

    /// One row (`j`) of a [`Straight`] cut whose tool covers the
    /// half-width `half` (mm, and in cells) there.
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn straight_row(
        &self,
        c: &RowCut,
        (half, hu): (f64, Split),
        hr: &mut [f32],
        tr: &mut [u8],
        hit: &mut Hit,
        j: usize,
    ) {
        let s = &c.s;
        // ⌈lo − h_u⌉ and ⌊hi + h_u⌋ from the parts: the fractions' sum
        // or difference lies within (−1, 2), so each is a comparison.
        let (m, g) = (hu.int, hu.frac);
        let i0 = (s.lo.int - m + isize::from(s.lo.frac > g)).max(0);
        let i1 = (s.hi.int + m + isize::from(s.hi.frac + g >= 1.0)).min(isize_of(self.nx) - 1);
        let cells = Cells {
            lift: s.base - s.kz * half,
            slope: s.slope,
            floor: s.floor,
            bottom: self.bottom,
            id: c.id,
            through: c.through,
        };
        let Some(hole) = s.hole else {
            cells.lower(i0, i1, hr, tr, hit, j);
            return;
        };
        // The skipped disc's cells: ⌈c − h_u + margin⌉ ..= ⌊c + h_u − margin⌋.
        let (x, y) = (hole.frac - g + s.margin, hole.frac + g - s.margin);
        let e0 = hole.int - m + isize::from(x > 0.0) + isize::from(x > 1.0);
        let e1 = hole.int + m + isize::from(y >= 1.0) - isize::from(y < 0.0);
        cells.lower(i0, i1.min(e0 - 1), hr, tr, hit, j);
        cells.lower(i0.max(e1 + 1), i1, hr, tr, hit, j);
    }

    /// One row of a [`Slanted`] cut: the capsule's span less the
    /// skipped disc, each cell's envelope from its own covered interval.
    #[allow(clippy::too_many_arguments)]
    fn slanted_row(
        &self,
        ctx: &RowCtx,
        span: FlatSpan,
        Slanted { cut, f, rows }: &Slanted,
        hr: &mut [f32],
        tr: &mut [u8],
        hit: &mut Hit,
    ) {
        let margin = 1e-9 * (1.0 + rows.r);
        let Some((lo, hi, h_lo, h_hi)) = self.row_of_line(cut, rows, f.r2, margin, span.y) else {
            return;
        };
        let to_u = |x: f64| (x - self.x0) * self.inv_dx - 0.5;
        let nx = self.nx;
        let i0 = ceil_index(to_u(lo), nx);
        let i1 = floor_index(to_u(hi), nx).min(isize_of(nx) - 1);
        let (e0, e1) = (ceil_index(to_u(h_lo), nx), floor_index(to_u(h_hi), nx));
        for (p0, p1) in pieces(i0, i1, e0, e1) {
            let (Some(h), Some(t)) = (hr.get_mut(p0..=p1), tr.get_mut(p0..=p1)) else {
                continue;
            };
            let span = FlatSpan { i0: p0, ..span };
            self.flat_span(ctx, &span, h, t, hit, f);
        }
    }
}

/// A straight cut's envelope on one row: cell i is lowered to
/// max(lift + slope·i, floor), never under the bottom.
struct Cells {
    lift: f64,
    slope: f64,
    floor: f64,
    bottom: f64,
    id: u8,
    through: bool,
}

impl Cells {
    /// Lowers cells `a..=b` of a row (`j`) — none when a > b; a ≥ 0 and b
    /// inside the row by the callers' clamps — marking the tool where a
    /// cell loses more than 0.1 µm, and the span's deepest removal and a
    /// cut through the bottom into `hit`.
    #[inline(always)]
    fn lower(&self, a: isize, b: isize, hr: &mut [f32], tr: &mut [u8], hit: &mut Hit, j: usize) {
        // Most moves stay above the bottom: their loop has no test for it.
        if self.through {
            self.lower_cells::<true>(a, b, hr, tr, hit, j);
        } else {
            self.lower_cells::<false>(a, b, hr, tr, hit, j);
        }
    }

    #[inline(always)]
    fn lower_cells<const THROUGH: bool>(
        &self,
        a: isize,
        b: isize,
        hr: &mut [f32],
        tr: &mut [u8],
        hit: &mut Hit,
        j: usize,
    ) {
        let (Ok(a), Ok(b)) = (usize::try_from(a), usize::try_from(b)) else {
            return;
        };
        let (Some(h), Some(t)) = (hr.get_mut(a..=b), tr.get_mut(a..=b)) else {
            return;
        };
        let t = &mut t[..h.len()];
        let (floor, step, bottom, id) = (self.floor, self.slope, self.bottom, self.id);
        let mut lin = self.lift + step * a as f64;
        let mut deepest = f64::from(hit.depth_mm);
        let mut at = usize::MAX;
        let mut below = false;
        for k in 0..h.len() {
            let e = fmax(lin, floor);
            lin += step;
            let before = f64::from(h[k]);
            if e < before {
                let new = fmax(e, bottom);
                h[k] = to_f32(new);
                if e < before - 1e-4 {
                    t[k] = id;
                    let depth = before - new;
                    if depth > deepest {
                        deepest = depth;
                        at = k;
                    }
                    if THROUGH && e < bottom - CUT_EPS_MM && before > bottom {
                        below = true;
                    }
                }
            }
        }
        hit.below |= below;
        if at != usize::MAX {
            hit.depth_mm = to_f32(deepest);
            hit.at = (
                u32::try_from(a + at).unwrap_or(0),
                u32::try_from(j).unwrap_or(0),
            );
        }
    }
}

impl Half {
    fn of(c: &RowCut, y: f64, inv_dx: f64) -> Half {
        let s = &c.s;
        let wy = y - s.cy;
        let w2 = s.r2 - wy * wy;
        let half = (w2 >= 0.0).then(|| {
            let h = w2.sqrt();
            (h, Split::of(h * inv_dx))
        });
        Half { line: c.line, half }
    }
}

/// The cells [i0, i1] less the skipped ones [e0, e1] (empty when e0 >
/// e1): at most two index ranges, inside the row.
#[inline]
fn pieces(i0: isize, i1: isize, e0: isize, e1: isize) -> impl Iterator<Item = (usize, usize)> {
    let both = if e0 <= e1 {
        [(i0.max(0), i1.min(e0 - 1)), (i0.max(e1 + 1).max(0), i1)]
    } else {
        [(i0.max(0), i1), (1, 0)]
    };
    both.into_iter().filter_map(|(p0, p1)| {
        let (p0, p1) = (usize::try_from(p0).ok()?, usize::try_from(p1).ok()?);
        (p0 <= p1).then_some((p0, p1))
    })
}

#[cfg(test)]
mod tests {
    use crate::kernel::Line;
    use crate::tool::Cutter;
    use crate::zmap::{Cut, Hit, Shape, ZMap};
    use vcnc_core::{ToolKind, ToolShape};

    /// Chains of flat-end-mill moves along X (skipping their discs as
    /// `mill.rs` decides), vertices, slanted moves and a ball's moves
    /// between them, from a fixed linear congruential sequence.
    fn cuts() -> Vec<Cut> {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut out = Vec::new();
        let mut p = [2.0, 2.0, -0.5];
        for _ in 0..400 {
            let kind = next();
            let mut q = p;
            if kind < 0.6 {
                q[0] = (p[0] + (next() - 0.5) * 1.4).clamp(-1.0, 21.0);
            } else {
                q[0] = next() * 20.0;
                q[1] = next() * 15.0;
            }
            q[2] = -0.3 - next() * 2.0;
            let ascending = q[2] > p[2];
            let flat = kind < 0.9;
            out.push(Cut {
                shape: Shape::Line(Line { a: p, b: q }),
                cutter: u8::from(!flat),
                skip_start: flat && kind < 0.6 && ascending,
                skip_end: flat && kind < 0.6 && !ascending,
                check_centre: false,
            });
            if kind < 0.1 {
                out.push(Cut {
                    shape: Shape::Line(Line { a: q, b: q }),
                    cutter: 0,
                    skip_start: false,
                    skip_end: false,
                    check_centre: false,
                });
            }
            p = q;
        }
        out
    }

    fn cutters() -> Vec<Cutter> {
        let flat = ToolShape::assumed(1);
        let ball = ToolShape {
            kind: ToolKind::Ball,
            ..ToolShape::assumed(2)
        };
        vec![Cutter::from_shape(&flat), Cutter::from_shape(&ball)]
    }

    fn map(workers: usize) -> ZMap {
        ZMap::new((0.0, 0.0, 20.0, 15.0), (-2.0, 0.0), 0.1, workers).unwrap()
    }

    /// Row by row over runs of cuts is the same as cut by cut: every
    /// height and tool mark to the bit, every cut's findings (deepest
    /// removal, where, through the bottom).
    #[test]
    fn runs_applied_row_by_row_equal_cuts_applied_one_by_one() {
        let (cuts, cutters) = (cuts(), cutters());
        let mut together = map(2);
        let mut hits = Vec::new();
        together.apply(&cuts, &cutters, &mut hits);
        let mut alone = map(2);
        let mut one = Vec::new();
        for (k, cut) in cuts.iter().enumerate() {
            alone.apply(std::slice::from_ref(cut), &cutters, &mut one);
            let expected: Vec<Hit> = one.clone();
            assert_eq!(hits.get(k..=k), Some(&expected[..]), "cut {k}: {cut:?}");
        }
        let cutting = hits.iter().filter(|h| h.depth_mm > 0.0).count();
        assert!(
            cutting > 100,
            "{cutting} of {} cuts remove material",
            hits.len()
        );
        for j in 0..together.ny {
            assert_eq!(together.row(j), alone.row(j), "row {j}");
            assert_eq!(together.tool_row(j), alone.tool_row(j), "row {j}");
        }
    }
}
