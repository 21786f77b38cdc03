//! The program coordinate frame: how a point the program writes becomes a
//! machine position, and back.
//!
//! ```text
//!   machine = A(program) + origin + tool
//!             │            │        └ tool length offset (G43/G44), on Z
//!             │            └ work offset (G54…) + local (G52) + shift (G92)
//!             └ programmable transforms, nested in the order commanded:
//!               G51 …; G68 …;  →  A(p) = Scale(Rotate(p))
//! ```
//!
//! Each transform (mirror G51.1, scaling G51, rotation G68) is given in
//! program coordinates; a later one is applied first to the program point,
//! so "scaling then rotation" scales the rotation's centre too, as Fanuc
//! describes (30i manual, "Scaling and coordinate system rotation"). The
//! stack is composed into one affine map on X, Y, Z whenever it changes, so
//! a move costs one matrix product, and nothing at all when no transform is
//! active. Everything here is pure: the interpreter owns a `Frame` in its
//! state and asks it to convert points, vectors and arcs.

use vcnc_core::events::{MAX_AXES, Plane, Pos};

/// The machine axis indices of X, Y and Z, where the machine has them.
pub(crate) type Xyz = [Option<usize>; 3];

/// One programmable transform, its centre in program coordinates (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Transform {
    /// G51.1: each `Some(c)` axis is mirrored about `c`.
    Mirror { about: [Option<f64>; 3] },
    /// G51: `p → c + k·(p − c)` per axis.
    Scale { factor: [f64; 3], centre: [f64; 3] },
    /// G68: counter-clockwise by `degrees` about `centre` in `plane`.
    Rotate {
        plane: Plane,
        degrees: f64,
        centre: [f64; 3],
    },
}

impl Transform {
    /// Which kind of transform (one of each kind may be active).
    fn kind(&self) -> usize {
        match self {
            Transform::Mirror { .. } => 0,
            Transform::Scale { .. } => 1,
            Transform::Rotate { .. } => 2,
        }
    }

    fn affine(&self) -> Affine {
        let mut a = Affine::IDENTITY;
        match *self {
            Transform::Mirror { about } => {
                for (r, c) in about.iter().enumerate() {
                    if let Some(c) = c {
                        a.m[r][r] = -1.0;
                        a.t[r] = 2.0 * c;
                    }
                }
            }
            Transform::Scale { factor, centre } => {
                for r in 0..3 {
                    a.m[r][r] = factor[r];
                    a.t[r] = centre[r] * (1.0 - factor[r]);
                }
            }
            Transform::Rotate {
                plane,
                degrees,
                centre,
            } => {
                let (i, j) = plane_rows(plane);
                let (s, c) = degrees.to_radians().sin_cos();
                // Exact quarter turns: no rounding noise at 90°, 180°, 270°.
                let (s, c) = (snap(s), snap(c));
                a.m[i][i] = c;
                a.m[i][j] = -s;
                a.m[j][i] = s;
                a.m[j][j] = c;
                a.t[i] = centre[i] - c * centre[i] + s * centre[j];
                a.t[j] = centre[j] - s * centre[i] - c * centre[j];
            }
        }
        a
    }
}

/// 1, 0 and −1 as they should be: sin/cos of multiples of 90° in f64 are
/// off by 1e-16, which would turn exact programs into near misses.
fn snap(v: f64) -> f64 {
    for exact in [-1.0, 0.0, 1.0] {
        if (v - exact).abs() < 1e-15 {
            return exact;
        }
    }
    v
}

/// The rows (x = 0, y = 1, z = 2) of a plane's first and second axis.
pub(crate) fn plane_rows(plane: Plane) -> (usize, usize) {
    match plane {
        Plane::Xy => (0, 1),
        Plane::Zx => (2, 0),
        Plane::Yz => (1, 2),
    }
}

/// `q = m·p + t` on (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    pub m: [[f64; 3]; 3],
    pub t: [f64; 3],
}

impl Affine {
    pub const IDENTITY: Affine = Affine {
        m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// `self ∘ inner`: apply `inner` first.
    fn then_outer(self, outer: Affine) -> Affine {
        let mut out = Affine {
            m: [[0.0; 3]; 3],
            t: outer.t,
        };
        for r in 0..3 {
            for c in 0..3 {
                out.m[r][c] = (0..3).map(|k| outer.m[r][k] * self.m[k][c]).sum();
                out.t[r] += outer.m[r][c] * self.t[c];
            }
        }
        out
    }

    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let mut q = self.t;
        for (r, qr) in q.iter_mut().enumerate() {
            *qr += (0..3).map(|c| self.m[r][c] * p[c]).sum::<f64>();
        }
        q
    }

    /// The linear part alone: a vector's image.
    fn apply_vector(&self, v: [f64; 3]) -> [f64; 3] {
        let mut q = [0.0; 3];
        for (r, qr) in q.iter_mut().enumerate() {
            *qr = (0..3).map(|c| self.m[r][c] * v[c]).sum();
        }
        q
    }

    fn det(&self) -> f64 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// The inverse map, if `m` is invertible.
    fn inverse(&self) -> Option<Affine> {
        let d = self.det();
        if d.abs() < 1e-12 {
            return None;
        }
        let m = &self.m;
        let cof = |r0: usize, r1: usize, c0: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let inv = [
            [
                cof(1, 2, 1, 2) / d,
                -cof(0, 2, 1, 2) / d,
                cof(0, 1, 1, 2) / d,
            ],
            [
                -cof(1, 2, 0, 2) / d,
                cof(0, 2, 0, 2) / d,
                -cof(0, 1, 0, 2) / d,
            ],
            [
                cof(1, 2, 0, 1) / d,
                -cof(0, 2, 0, 1) / d,
                cof(0, 1, 0, 1) / d,
            ],
        ];
        let mut out = Affine {
            m: inv,
            t: [0.0; 3],
        };
        let t = out.apply_vector(self.t);
        out.t = [-t[0], -t[1], -t[2]];
        Some(out)
    }
}

/// How an arc in the program looks on the machine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ArcMap {
    /// The plane maps onto itself by a similarity; `reversed` when it flips
    /// the arc's direction (an odd number of mirrored axes).
    Similar { reversed: bool },
    /// Different scale factors on the plane's axes: the arc would become an
    /// ellipse.
    Uneven,
    /// A rotation in another plane tilts the arc out of its plane.
    Tilted,
}

/// The programmable transforms in force, in the order commanded (the first
/// is outermost). At most one of each kind.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Transforms(pub [Option<Transform>; 3]);

impl Transforms {
    /// The active transform of the kind of `like`, if any.
    pub fn like(&self, like: &Transform) -> Option<Transform> {
        self.0
            .iter()
            .flatten()
            .find(|t| t.kind() == like.kind())
            .copied()
    }

    /// With `t` set: replacing the active one of its kind where it stands
    /// in the order, or added innermost.
    pub fn with(&self, t: Transform) -> Transforms {
        let mut next = *self;
        match next
            .0
            .iter_mut()
            .find(|s| s.is_some_and(|x| x.kind() == t.kind()))
        {
            Some(slot) => *slot = Some(t),
            None => {
                if let Some(slot) = next.0.iter_mut().find(|s| s.is_none()) {
                    *slot = Some(t);
                }
            }
        }
        next
    }

    /// Without the transform of the kind of `like`; the others keep their order.
    pub fn without(&self, like: &Transform) -> Transforms {
        let mut next = Transforms::default();
        let kept = self.0.iter().flatten().filter(|x| x.kind() != like.kind());
        for (slot, x) in next.0.iter_mut().zip(kept) {
            *slot = Some(*x);
        }
        next
    }

    /// How many machine millimetres one program millimetre along X
    /// becomes (1 without scaling; rotation and mirror keep lengths).
    pub fn x_length_scale(&self) -> f64 {
        self.compose().map_or(1.0, |a| {
            let v = a.apply_vector([1.0, 0.0, 0.0]);
            v.iter().map(|c| c * c).sum::<f64>().sqrt()
        })
    }

    /// The composed map, `None` when it cannot be inverted (a zero factor).
    pub fn compose(&self) -> Option<Affine> {
        let mut a = Affine::IDENTITY;
        // The first transform is outermost: apply the others inside it.
        for t in self.0.iter().flatten().rev() {
            a = a.then_outer(t.affine());
        }
        a.inverse().map(|_| a)
    }
}

/// No axis (an index in `Frame::xyz`).
const NO_AXIS: u8 = u8::MAX;

/// The active frame: origin, the composed transforms and the tool length
/// offset. Small and `Copy`: it is part of the state saved before a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// Work offset + G52 + G92, machine coordinates of program zero.
    pub origin: Pos,
    /// Tool length offset, machine axes.
    pub tool: Pos,
    affine: Affine,
    identity: bool,
    /// Machine axis indices of X, Y, Z (`NO_AXIS` when missing).
    xyz: [u8; 3],
}

impl Frame {
    /// No offsets, no transforms, on a machine whose X, Y, Z are `xyz`.
    pub fn new(xyz: Xyz) -> Frame {
        Frame {
            origin: Pos::default(),
            tool: Pos::default(),
            affine: Affine::IDENTITY,
            identity: true,
            xyz: xyz.map(|i| i.and_then(|i| u8::try_from(i).ok()).unwrap_or(NO_AXIS)),
        }
    }

    /// Whether a rotation, scaling or mirror is active.
    pub fn is_transformed(&self) -> bool {
        !self.identity
    }

    /// Uses the composition of the transforms.
    pub fn set_affine(&mut self, a: Affine) {
        self.affine = a;
        self.identity = a == Affine::IDENTITY;
    }

    fn xyz_of(&self, p: &Pos) -> [f64; 3] {
        self.xyz.map(|i| p.get(usize::from(i)))
    }

    fn put_xyz(&self, p: &mut Pos, v: [f64; 3]) {
        for (k, i) in self.xyz.iter().enumerate() {
            if *i != NO_AXIS {
                p.set(usize::from(*i), v[k]);
            }
        }
    }

    /// The machine position of program point `p` (the controlled point:
    /// the tool length offset included). Inlined into every move's commit,
    /// the transforms too (out of line they cost a G68 block 12
    /// instructions, and an untransformed one 3).
    #[inline(always)]
    pub fn machine_of(&self, p: Pos) -> Pos {
        let q = if self.identity {
            p
        } else {
            self.transformed(p)
        };
        let mut out = q;
        for i in 0..MAX_AXES {
            out.0[i] = q.0[i] + self.origin.0[i] + self.tool.0[i];
        }
        out
    }

    /// `p` through the scaling, mirror and rotation (G51, G51.1, G68).
    #[inline(always)]
    fn transformed(&self, p: Pos) -> Pos {
        let mut q = p;
        let v = self.affine.apply(self.xyz_of(&p));
        self.put_xyz(&mut q, v);
        q
    }

    /// The program point whose machine position is `m`.
    pub fn program_of(&self, m: Pos) -> Pos {
        let mut q = m;
        for i in 0..MAX_AXES {
            q.0[i] = m.0[i] - self.origin.0[i] - self.tool.0[i];
        }
        if !self.identity {
            // Checked invertible when the transforms were set; inverted on
            // demand because this runs only when the frame changes or a
            // move ends at a machine point, and it keeps `State` small.
            if let Some(inv) = self.affine.inverse() {
                let v = inv.apply(self.xyz_of(&q));
                self.put_xyz(&mut q, v);
            }
        }
        q
    }

    /// The origin on axis `i` at which machine coordinate `m` reads `v` in
    /// program coordinates: `machine = p + origin + tool` solved for the
    /// origin, on one axis. `m` and the result count from the same base, so
    /// a caller that sets only part of the origin takes the other parts off
    /// `m` first and gets its own (G10 L20: the work offset, from `m` less
    /// G52 and G92; G92: the shift, from `m` less the work offset). The
    /// transforms are left out: G92 refuses them, and G10 L20 sets the work
    /// offset as if none were active.
    pub fn origin_for(&self, i: usize, m: f64, v: f64) -> f64 {
        m - self.tool.get(i) - v
    }

    /// A program vector (an increment, an arc's centre offset) on the machine.
    pub fn vector_to_machine(&self, v: Pos) -> Pos {
        if self.identity {
            return v;
        }
        let mut q = v;
        let w = self.affine.apply_vector(self.xyz_of(&v));
        self.put_xyz(&mut q, w);
        q
    }

    /// How an arc in `plane` maps onto the machine.
    pub fn arc_map(&self, plane: Plane) -> ArcMap {
        if self.identity {
            return ArcMap::Similar { reversed: false };
        }
        let (i, j) = plane_rows(plane);
        let n = 3 - i - j;
        let m = &self.affine.m;
        let eps = 1e-12;
        if m[i][n].abs() > eps || m[j][n].abs() > eps || m[n][i].abs() > eps || m[n][j].abs() > eps
        {
            return ArcMap::Tilted;
        }
        // Columns of the plane's 2×2 block: orthogonal with equal length.
        let (a, b) = ((m[i][i], m[j][i]), (m[i][j], m[j][j]));
        let dot = a.0 * b.0 + a.1 * b.1;
        let (la, lb) = (a.0.hypot(a.1), b.0.hypot(b.1));
        if dot.abs() > 1e-9 * la * lb || (la - lb).abs() > 1e-9 * la.max(lb) {
            return ArcMap::Uneven;
        }
        ArcMap::Similar {
            reversed: a.0 * b.1 - a.1 * b.0 < 0.0,
        }
    }

    /// Whether an odd number of mirrors act in `plane` (the compensation
    /// side swaps, Syntec 1.2.21): the plane's 2×2 block turns left into
    /// right, also under an uneven scale with a negative factor (which
    /// carries lines though not arcs).
    pub fn mirrors(&self, plane: Plane) -> bool {
        if self.identity {
            return false;
        }
        let (i, j) = plane_rows(plane);
        let m = &self.affine.m;
        m[i][i] * m[j][j] - m[i][j] * m[j][i] < 0.0
    }

    /// The linear part (rows and columns x, y, z), for the `frame` event.
    pub fn linear(&self) -> Option<[[f64; 3]; 3]> {
        (!self.identity).then_some(self.affine.m)
    }

    /// Machine point `m` seen from program zero as Fanuc's position
    /// variables read it (#5041…, #5061…): less the origin and the
    /// transforms' shift, the tool offset left in and a rotation or
    /// scaling not undone.
    pub fn work_of(&self, m: Pos) -> Pos {
        m.minus(self.origin_with_transforms())
    }

    /// Machine coordinates of program zero without the tool offset.
    pub fn origin_with_transforms(&self) -> Pos {
        let mut o = self.origin;
        if !self.identity {
            for (k, i) in self.xyz.iter().enumerate() {
                if *i != NO_AXIS {
                    let i = usize::from(*i);
                    o.set(i, o.get(i) + self.affine.t[k]);
                }
            }
        }
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const XYZ: Xyz = [Some(0), Some(1), Some(2)];

    fn p(x: f64, y: f64, z: f64) -> Pos {
        Pos([x, y, z, 0.0, 0.0, 0.0])
    }

    fn close(a: Pos, b: Pos) -> bool {
        (0..3).all(|i| (a.get(i) - b.get(i)).abs() < 1e-9)
    }

    fn frame(t: &Transforms) -> Frame {
        let mut f = Frame::new(XYZ);
        f.set_affine(t.compose().unwrap());
        f
    }

    #[test]
    fn origin_for_puts_the_program_value_at_the_machine_point() {
        // Tool 5 on Z, machine Z 100 to read 20: the origin is 75, and
        // program Z 20 then goes to 20 + 75 + 5 = 100.
        let mut f = Frame::new(XYZ);
        f.tool = p(0.0, 0.0, 5.0);
        assert_eq!(f.origin_for(2, 100.0, 20.0), 75.0);
        f.origin = p(0.0, 0.0, 75.0);
        assert_eq!(f.machine_of(p(0.0, 0.0, 20.0)).get(2), 100.0);
        assert_eq!(f.program_of(p(0.0, 0.0, 100.0)).get(2), 20.0);
        // No tool offset on X: the origin is what is left.
        assert_eq!(f.origin_for(0, -30.0, 12.5), -42.5);
    }

    #[test]
    fn work_of_keeps_the_tool_and_the_rotation_in() {
        // G68 90° about (10, 0): its shift is (10, −10), so program zero
        // sits at origin (10, 0, 0) + (10, −10, 0) = (20, −10, 0).
        let t = Transforms::default().with(Transform::Rotate {
            plane: Plane::Xy,
            degrees: 90.0,
            centre: [10.0, 0.0, 0.0],
        });
        let mut f = frame(&t);
        f.origin = p(10.0, 0.0, 0.0);
        f.tool = p(0.0, 0.0, 5.0);
        assert!(close(f.work_of(p(25.0, 0.0, 7.0)), p(5.0, 10.0, 7.0)));
    }

    #[test]
    fn scaling_then_rotation_scales_the_rotation_centre() {
        let t = Transforms::default()
            .with(Transform::Scale {
                factor: [0.5; 3],
                centre: [0.0; 3],
            })
            .with(Transform::Rotate {
                plane: Plane::Xy,
                degrees: 90.0,
                centre: [10.0, 0.0, 0.0],
            });
        let f = frame(&t);
        // Rotate (10,10) about (10,0) by 90° → (0,0); then scale by 0.5 → (0,0).
        assert!(close(f.machine_of(p(10.0, 10.0, 4.0)), p(0.0, 0.0, 2.0)));
        // And back.
        assert!(close(f.program_of(p(0.0, 0.0, 2.0)), p(10.0, 10.0, 4.0)));
    }

    #[test]
    fn one_mirror_reverses_arcs_two_do_not() {
        let one = Transforms::default().with(Transform::Mirror {
            about: [Some(60.0), None, None],
        });
        let f = frame(&one);
        assert!(close(f.machine_of(p(80.0, 75.0, 0.0)), p(40.0, 75.0, 0.0)));
        assert_eq!(f.arc_map(Plane::Xy), ArcMap::Similar { reversed: true });
        let two = one.with(Transform::Mirror {
            about: [Some(60.0), Some(55.0), None],
        });
        assert_eq!(
            frame(&two).arc_map(Plane::Xy),
            ArcMap::Similar { reversed: false }
        );
        let none = two.without(&Transform::Mirror { about: [None; 3] });
        assert!(!frame(&none).is_transformed());
    }

    #[test]
    fn uneven_scaling_and_tilted_planes_are_reported() {
        let uneven = Transforms::default().with(Transform::Scale {
            factor: [2.0, 1.0, 1.0],
            centre: [0.0; 3],
        });
        assert_eq!(frame(&uneven).arc_map(Plane::Xy), ArcMap::Uneven);
        assert_eq!(
            frame(&uneven).arc_map(Plane::Yz),
            ArcMap::Similar { reversed: false }
        );
        let r = Transforms::default().with(Transform::Rotate {
            plane: Plane::Xy,
            degrees: 30.0,
            centre: [0.0; 3],
        });
        assert_eq!(frame(&r).arc_map(Plane::Zx), ArcMap::Tilted);
        let zero = Transforms::default().with(Transform::Scale {
            factor: [0.0; 3],
            centre: [0.0; 3],
        });
        assert!(zero.compose().is_none());
    }
}
