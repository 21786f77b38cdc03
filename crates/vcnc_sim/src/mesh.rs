//! The finished part as a closed triangle mesh, written as binary STL.
//!
//! A milled part is its height field: the top surface through the cells'
//! centres (and the stock's edges, each at its edge cell's height, so that
//! the surface spans the whole block), four walls down to the bottom and
//! the bottom as a fan about its centre. Every edge is shared by exactly
//! two triangles, and the volume under the surface is the cells' own sum
//! up to how each quad is split in two:
//!
//! ```text
//!   x0   c0    c1    c2   x1     vertices: the stock's edges and the
//!   ●────●─────●─────●────●      cells' centres; heights h0 h0 h1 h2 h2,
//!   │ ╲  │  ╲  │  ╲  │ ╲  │      so the trapezoid rule over them gives
//!   ●────●─────●─────●────●      exactly Σ hᵢ·dx along a row
//! ```
//!
//! A turned part is its half-section revolved in [`REVOLVE_STEPS`] steps.
//! Large grids are averaged down to at most [`MAX_MESH_CELLS`] cells (the
//! mean keeps the volume) so that the file stays near 100 MB. STL is small
//! enough to write by hand (80-byte header, count, 50 bytes a triangle);
//! a crate would add a dependency for twenty lines.

use crate::lathe::{Contour, Section};
use crate::sim::Part;
use crate::zmap::ZMap;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::f64::consts::TAU;
use std::io::{self, Write};

/// Most cells of a milled part's mesh (two triangles each).
pub const MAX_MESH_CELLS: usize = 1 << 20;

/// Angular steps of a revolved part.
pub const REVOLVE_STEPS: usize = 256;

/// A triangle, counter-clockwise seen from outside.
pub type Triangle = [[f64; 3]; 3];

/// A height field ready to mesh: cell heights on a (possibly averaged)
/// grid over `[x0, x1] × [y0, y1]`.
#[derive(Debug, Clone)]
pub struct HeightField {
    /// Lower-left corner, work coordinates.
    pub x0: f64,
    /// Lower-left corner, work coordinates.
    pub y0: f64,
    /// Cell centres along X.
    pub xs: Vec<f64>,
    /// Cell centres along Y.
    pub ys: Vec<f64>,
    /// Upper-right corner.
    pub x1: f64,
    /// Upper-right corner.
    pub y1: f64,
    /// Heights, row-major (`xs.len()` per row).
    pub h: Vec<f64>,
    /// The bottom, work Z.
    pub bottom: f64,
}

impl HeightField {
    /// The field of `map` in work coordinates (`origin` subtracted),
    /// averaged over `k`×`k` blocks so that it has at most `max_cells`.
    pub fn of(map: &ZMap, origin: [f64; 3], max_cells: usize) -> HeightField {
        let mut k = 1;
        while map.nx.div_ceil(k) * map.ny.div_ceil(k) > max_cells.max(1) {
            k += 1;
        }
        let (nx, ny) = (map.nx.div_ceil(k), map.ny.div_ceil(k));
        let mut sum = vec![0.0f64; nx * ny];
        let mut n = vec![0u32; nx * ny];
        for j in 0..map.ny {
            for (i, h) in map.row(j).iter().enumerate() {
                let c = (j / k) * nx + i / k;
                if let (Some(s), Some(n)) = (sum.get_mut(c), n.get_mut(c)) {
                    *s += f64::from(*h);
                    *n += 1;
                }
            }
        }
        let centre = |c: usize, step: f64, cells: usize, from: f64| {
            let lo = (c * k) as f64;
            let hi = ((c + 1) * k).min(cells) as f64;
            from + (lo + hi) / 2.0 * step
        };
        let (x0, y0) = (map.x0 - origin[0], map.y0 - origin[1]);
        HeightField {
            x0,
            y0,
            xs: (0..nx).map(|c| centre(c, map.dx, map.nx, x0)).collect(),
            ys: (0..ny).map(|c| centre(c, map.dy, map.ny, y0)).collect(),
            x1: x0 + map.nx as f64 * map.dx,
            y1: y0 + map.ny as f64 * map.dy,
            h: sum
                .iter()
                .zip(&n)
                .map(|(s, n)| s / f64::from((*n).max(1)) - origin[2])
                .collect(),
            bottom: map.bottom - origin[2],
        }
    }

    fn at(&self, i: usize, j: usize) -> f64 {
        let (nx, ny) = (self.xs.len(), self.ys.len());
        let (i, j) = (i.clamp(1, nx) - 1, j.clamp(1, ny) - 1);
        self.h.get(j * nx + i).copied().unwrap_or(self.bottom)
    }

    /// The vertex grid's coordinate `i` along X (edges included).
    fn vx(&self, i: usize) -> f64 {
        if i == 0 {
            self.x0
        } else {
            self.xs.get(i - 1).copied().unwrap_or(self.x1)
        }
    }

    fn vy(&self, j: usize) -> f64 {
        if j == 0 {
            self.y0
        } else {
            self.ys.get(j - 1).copied().unwrap_or(self.y1)
        }
    }

    /// Every triangle of the closed mesh, to `emit`.
    pub fn triangles(&self, emit: &mut dyn FnMut(Triangle)) {
        let (nx, ny) = (self.xs.len() + 2, self.ys.len() + 2);
        let v = |i: usize, j: usize| [self.vx(i), self.vy(j), self.at(i, j)];
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
                emit([a, b, c]);
                emit([a, c, d]);
            }
        }
        // The boundary, counter-clockwise seen from above.
        let mut ring = Vec::with_capacity(2 * (nx + ny));
        ring.extend((0..nx - 1).map(|i| (i, 0)));
        ring.extend((0..ny - 1).map(|j| (nx - 1, j)));
        ring.extend((1..nx).rev().map(|i| (i, ny - 1)));
        ring.extend((1..ny).rev().map(|j| (0, j)));
        let b = self.bottom;
        let centre = [(self.x0 + self.x1) / 2.0, (self.y0 + self.y1) / 2.0, b];
        for (k, &(i, j)) in ring.iter().enumerate() {
            let (qi, qj) = ring.get((k + 1) % ring.len()).copied().unwrap_or((i, j));
            let (p, q) = (v(i, j), v(qi, qj));
            let (pb, qb) = ([p[0], p[1], b], [q[0], q[1], b]);
            emit([pb, qb, q]);
            emit([pb, q, p]);
            emit([centre, qb, pb]);
        }
    }
}

/// Every triangle of the revolved section, work coordinates (Z along the
/// axis, the axis at X = Y = 0).
pub fn revolve(s: &Section, emit: &mut dyn FnMut(Triangle)) {
    let ring = |p: [f64; 2], k: usize| {
        let t = TAU * (k % REVOLVE_STEPS) as f64 / REVOLVE_STEPS as f64;
        let r = p[1].max(0.0);
        [r * t.cos(), r * t.sin(), p[0] - s.origin_z]
    };
    sweep(&s.shapes, REVOLVE_STEPS, &ring, emit);
}

/// Sweeps every contour edge of `shapes` through `steps` steps of `ring`
/// (a point of the section and a step → the point in space).
fn sweep(
    shapes: &[Vec<Contour>],
    steps: usize,
    ring: &dyn Fn([f64; 2], usize) -> [f64; 3],
    emit: &mut dyn FnMut(Triangle),
) {
    for c in shapes.iter().flatten() {
        // Material lies left of every contour (outer ones run
        // counter-clockwise, holes clockwise), so one winding faces out.
        for (n, p) in c.iter().enumerate() {
            let (p, q) = (*p, c.get((n + 1) % c.len()).copied().unwrap_or(*p));
            let on_axis = |v: [f64; 2]| v[1] <= 1e-12;
            if on_axis(p) && on_axis(q) {
                continue;
            }
            for k in 0..steps {
                let (p0, p1, q0, q1) = (ring(p, k), ring(p, k + 1), ring(q, k), ring(q, k + 1));
                if !on_axis(q) {
                    emit([p0, q0, q1]);
                }
                if !on_axis(p) {
                    emit([p0, q1, p1]);
                }
            }
        }
    }
}

/// Most cells of a milled part's mesh in a viewer page: 256 × 256, each
/// the mean of its fine cells, about a megabyte of page.
pub const VIEW_MESH_CELLS: usize = 1 << 16;

/// Steps of a turned part's half revolution in a viewer page.
pub const VIEW_REVOLVE_STEPS: usize = 48;

/// A triangle mesh with shared vertices: what a viewer page carries.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Indexed {
    /// Vertices, X Y Z.
    pub positions: Vec<[f64; 3]>,
    /// Triangles as indices into `positions`, counter-clockwise seen from
    /// outside.
    pub triangles: Vec<[u32; 3]>,
}

impl Indexed {
    /// Welds `triangles` into shared vertices (equal bit for bit: the
    /// meshes here compute each vertex once per use the same way).
    pub fn of(triangles: Triangles<'_>) -> Indexed {
        let mut m = Indexed::default();
        let mut seen: HashMap<[u64; 3], u32> = HashMap::new();
        triangles(&mut |t| {
            let mut tri = [0u32; 3];
            for (slot, v) in tri.iter_mut().zip(t) {
                let key = v.map(|c| (c + 0.0).to_bits());
                *slot = *seen.entry(key).or_insert_with(|| {
                    m.positions.push(v);
                    u32::try_from(m.positions.len() - 1).unwrap_or(u32::MAX)
                });
            }
            m.triangles.push(tri);
        });
        m
    }
}

/// The stock and the finished part, for a viewer: machine coordinates of
/// the tool's tip (where the path's tool marker puts its tip), a milled
/// part averaged to at most [`VIEW_MESH_CELLS`] cells, a turned one
/// revolved over the half X ≥ the spindle axis (the side the lathe's
/// section view shows) in [`VIEW_REVOLVE_STEPS`] steps. `None` when
/// nothing was simulated.
pub fn stock_and_part(part: &Part) -> Option<(Indexed, Indexed)> {
    match part {
        Part::Mill(map, _) => {
            let field = HeightField::of(map, [0.0; 3], VIEW_MESH_CELLS);
            let block = HeightField {
                x0: field.x0,
                y0: field.y0,
                xs: vec![(field.x0 + field.x1) / 2.0],
                ys: vec![(field.y0 + field.y1) / 2.0],
                x1: field.x1,
                y1: field.y1,
                h: vec![map.top],
                bottom: field.bottom,
            };
            Some((
                Indexed::of(&|emit| block.triangles(emit)),
                Indexed::of(&|emit| field.triangles(emit)),
            ))
        }
        Part::Lathe(s) => {
            let ring = |p: [f64; 2], k: usize| {
                let t = PI * (k as f64 / VIEW_REVOLVE_STEPS as f64 - 0.5);
                let r = p[1].max(0.0);
                [s.axis_x + r * t.cos(), r * t.sin(), p[0]]
            };
            let (z0, r0, z1, r1) = s.stock_box;
            let bar = [vec![vec![[z0, r0], [z1, r0], [z1, r1], [z0, r1]]]];
            Some((
                Indexed::of(&|emit| sweep(&bar, VIEW_REVOLVE_STEPS, &ring, emit)),
                Indexed::of(&|emit| sweep(&s.shapes, VIEW_REVOLVE_STEPS, &ring, emit)),
            ))
        }
        Part::Empty => None,
    }
}

/// Something that hands out a mesh's triangles, as often as asked.
pub type Triangles<'a> = &'a dyn Fn(&mut dyn FnMut(Triangle));

/// Writes triangles as binary STL; `triangles` is called twice (to count,
/// then to write).
pub fn write_stl(out: &mut dyn Write, triangles: Triangles<'_>) -> io::Result<()> {
    let mut count = 0u64;
    triangles(&mut |_| count += 1);
    let count = u32::try_from(count).map_err(|_| io::Error::other("more than 2³² triangles"))?;
    let mut header = [b' '; 80];
    let text = b"vcnc simulated part, mm";
    if let Some(h) = header.get_mut(..text.len()) {
        h.copy_from_slice(text);
    }
    out.write_all(&header)?;
    out.write_all(&count.to_le_bytes())?;
    let mut err = Ok(());
    triangles(&mut |t| {
        if err.is_err() {
            return;
        }
        let mut rec = [0u8; 50];
        let n = normal(&t);
        let vals = n.iter().chain(t.iter().flatten());
        for (slot, v) in rec.chunks_exact_mut(4).zip(vals) {
            #[allow(clippy::cast_possible_truncation)] // STL stores f32
            slot.copy_from_slice(&(*v as f32).to_le_bytes());
        }
        err = out.write_all(&rec);
    });
    err
}

/// The unit normal of a triangle (0 when degenerate).
pub fn normal(t: &Triangle) -> [f64; 3] {
    let (u, v) = (sub(t[1], t[0]), sub(t[2], t[0]));
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        [n[0] / len, n[1] / len, n[2] / len]
    } else {
        [0.0; 3]
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
