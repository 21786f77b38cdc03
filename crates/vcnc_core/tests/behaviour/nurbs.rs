//! The NURBS evaluator (de Boor in homogeneous coordinates) against a
//! second, independent implementation written here from the manual's
//! definition (Syntec 1.2.8): the Cox–de Boor recursion for the basis
//! functions N_i,p and the rational sum C(u) = Σ N_i,p·w_i·P_i / Σ N_i,p·w_i;
//! and against the non-rational case (equal weights give the B-spline of
//! the same points, whatever the weight).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_core::{Nurbs, Pos};

/// N_i,p(u) by the recursion of the manual (degree p = order − 1), with the
/// convention 0/0 = 0 and the last non-empty span closed at its end.
fn basis(knots: &[f64], i: usize, p: usize, u: f64, n: usize) -> f64 {
    if p == 0 {
        let (a, b) = (knots[i], knots[i + 1]);
        let last = knots[n]; // end of the domain
        return if (a <= u && u < b) || (u == last && b == last && a < b) {
            1.0
        } else {
            0.0
        };
    }
    let mut out = 0.0;
    let d1 = knots[i + p] - knots[i];
    if d1 > 0.0 {
        out += (u - knots[i]) / d1 * basis(knots, i, p - 1, u, n);
    }
    let d2 = knots[i + p + 1] - knots[i + 1];
    if d2 > 0.0 {
        out += (knots[i + p + 1] - u) / d2 * basis(knots, i + 1, p - 1, u, n);
    }
    out
}

fn by_basis(c: &Nurbs, u: f64) -> Pos {
    let p = usize::from(c.order) - 1;
    let n = c.points.len();
    let (mut num, mut den) = ([0.0; 6], 0.0);
    for i in 0..n {
        let b = basis(&c.knots, i, p, u, n) * c.weights[i];
        den += b;
        for (a, x) in num.iter_mut().zip(c.points[i].0) {
            *a += b * x;
        }
    }
    Pos(num.map(|x| x / den))
}

/// A clamped curve of `order` with the given points, interior knots and weights.
fn curve(order: u8, pts: Vec<(f64, f64, f64)>, mut interior: Vec<f64>, weights: Vec<f64>) -> Nurbs {
    let n = pts.len();
    let k = usize::from(order);
    interior.truncate(n - k);
    interior.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut knots = vec![0.0; k];
    knots.extend(interior);
    knots.extend(vec![1.0; k]);
    Nurbs {
        order,
        knots,
        points: pts
            .into_iter()
            .map(|(x, y, z)| Pos([x, y, z, 0.0, 0.0, 0.0]))
            .collect(),
        weights: weights.into_iter().take(n).collect(),
    }
}

fn arb_curve() -> impl Strategy<Value = Nurbs> {
    (2u8..=4, 4usize..=9).prop_flat_map(|(order, n)| {
        (
            Just(order),
            prop::collection::vec((-100.0..100.0f64, -100.0..100.0f64, -50.0..50.0f64), n),
            prop::collection::vec(0.0..1.0f64, n),
            prop::collection::vec(-3.0..3.0f64, n),
        )
            .prop_map(|(order, pts, interior, logw)| {
                let w = logw.into_iter().map(|l| 10f64.powf(l)).collect();
                curve(order, pts, interior, w)
            })
    })
}

fn close(a: &Pos, b: &Pos, tol: f64) -> bool {
    a.0.iter()
        .zip(b.0)
        .all(|(x, y)| (x - y).abs() <= tol * (1.0 + x.abs().max(y.abs())))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn de_boor_agrees_with_the_basis_functions(c in arb_curve(), u in 0.0..=1.0f64) {
        prop_assert_eq!(c.check(), Ok(()));
        let a = c.point(u);
        let b = by_basis(&c, u);
        prop_assert!(close(&a, &b, 1e-9), "{:?} vs {:?} at {}", a, b, u);
    }

    #[test]
    fn equal_weights_give_the_b_spline(c in arb_curve(), w in 0.001..1000.0f64, u in 0.0..=1.0f64) {
        let mut plain = c.clone();
        plain.weights = vec![1.0; c.points.len()];
        let mut scaled = c;
        scaled.weights = vec![w; scaled.points.len()];
        prop_assert!(close(&plain.point(u), &scaled.point(u), 1e-9));
        // With weights 1 the basis functions sum to one: the curve is the
        // plain B-spline Σ N_i,p·P_i.
        prop_assert!(close(&plain.point(u), &by_basis(&plain, u), 1e-9));
    }

    #[test]
    fn a_curve_starts_and_ends_at_its_end_control_points(c in arb_curve()) {
        prop_assert!(close(&c.point(0.0), &c.points[0], 1e-9));
        prop_assert!(close(&c.point(1.0), c.points.last().unwrap(), 1e-9));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Flattening ends exactly at the last control point, within the
    /// bound on the number of chords.
    #[test]
    fn chords_stay_near_the_curve(c in arb_curve()) {
        let chords = c.flatten(0.5);
        prop_assert_eq!(chords.last(), c.points.last());
        prop_assert!(chords.len() <= vcnc_core::nurbs::MAX_NURBS_CHORDS);
    }
}
