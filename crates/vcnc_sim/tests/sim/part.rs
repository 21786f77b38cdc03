//! The finished part's STL: closed (every edge shared by exactly two
//! triangles, once in each direction, so the faces are consistently
//! oriented) and as large as the stock less what was removed.

use crate::harness::{library, mill, run_with, tool};
use std::collections::HashMap;
use vcnc_core::ToolKind;
use vcnc_sim::mesh::{
    HeightField, Indexed, MAX_MESH_CELLS, VIEW_MESH_CELLS, revolve, stock_and_part, write_stl,
};
use vcnc_sim::{Finished, Part};

/// Reads a binary STL's triangles.
fn read_stl(bytes: &[u8]) -> Vec<[[f32; 3]; 3]> {
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(bytes.len(), 84 + 50 * n, "size matches the count");
    (0..n)
        .map(|k| {
            let rec = &bytes[84 + 50 * k..84 + 50 * (k + 1)];
            let f = |i: usize| f32::from_le_bytes(rec[12 + 4 * i..16 + 4 * i].try_into().unwrap());
            [[f(0), f(1), f(2)], [f(3), f(4), f(5)], [f(6), f(7), f(8)]]
        })
        .collect()
}

/// Every directed edge appears once and its reverse once; returns the
/// enclosed volume (divergence theorem).
fn closed_volume(tris: &[[[f32; 3]; 3]]) -> f64 {
    let key = |p: [f32; 3]| p.map(f32::to_bits);
    let mut edges: HashMap<([u32; 3], [u32; 3]), u32> = HashMap::new();
    let mut volume = 0.0f64;
    for t in tris {
        for k in 0..3 {
            *edges.entry((key(t[k]), key(t[(k + 1) % 3]))).or_default() += 1;
        }
        let [a, b, c] = t.map(|p| p.map(f64::from));
        volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))
            / 6.0;
    }
    for ((a, b), n) in &edges {
        assert_eq!(*n, 1, "edge {a:?}→{b:?} used {n} times");
        assert_eq!(
            edges.get(&(*b, *a)),
            Some(&1),
            "edge {a:?}→{b:?} has no twin"
        );
    }
    volume
}

fn stl_of(f: &Finished) -> Vec<u8> {
    let mut out = Vec::new();
    match &f.part {
        Part::Mill(map, origin) => {
            let field = HeightField::of(map, *origin, MAX_MESH_CELLS);
            write_stl(&mut out, &|emit| field.triangles(emit)).unwrap();
        }
        Part::Lathe(s) => write_stl(&mut out, &|emit| revolve(s, emit)).unwrap(),
        Part::Empty => panic!("no part"),
    }
    out
}

#[test]
fn a_milled_part_is_closed_and_holds_the_stock_less_the_cut() {
    // A pocket and a slot through one side of the block.
    let p = "G21 G90 G17\nT1 M06\nG00 X5. Y5. Z5.\nG01 Z-5. F300\nX35.\nY25.\nX5.\nY5.\nG00 Z5.\n\
             G00 X-5. Y15. Z-2.\nG01 X45.\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], "box:0,0,-10,40,30,0");
    let tris = read_stl(&stl_of(&f));
    let v = closed_volume(&tris);
    let want = f.report.stock_mm3 - f.report.removed_mm3;
    assert!(v > 0.0, "outward faces: {v}");
    assert!(
        (v - want).abs() < 2e-3 * want,
        "mesh {v}, stock − removed {want}"
    );
}

#[test]
fn a_turned_part_is_closed_and_holds_the_stock_less_the_cut() {
    let shape = tool(
        1,
        ToolKind::Turning {
            nose_radius_mm: 0.8,
            tip: 3,
        },
        1.6,
    );
    let p = "G21 G18 G40 G99\nT0101 S1000 M03\nG00 X46. Z2.\nG01 Z-40. F0.2\nG01 X52.\nG00 Z2.\n\
             G00 X30. Z2.\nG01 Z0.\nG01 X-1.6\nG00 Z5.\nM30\n";
    let f = run_with(
        p,
        "fanuc-lathe",
        &library(&[shape]),
        "bar:50,100,10",
        None,
        None,
    );
    let tris = read_stl(&stl_of(&f));
    let v = closed_volume(&tris);
    let want = f.report.stock_mm3 - f.report.removed_mm3;
    // 256 steps inscribe the circle: sin(2π/256)·256/2π = 0.9999.
    assert!(v > 0.0, "outward faces: {v}");
    assert!(
        (v - want).abs() < 2e-4 * want,
        "mesh {v}, stock − removed {want}"
    );
}

/// An indexed mesh's triangles, as the viewer draws them.
fn unindexed(m: &Indexed) -> Vec<[[f32; 3]; 3]> {
    #[allow(clippy::cast_possible_truncation)] // as STL stores them
    m.triangles
        .iter()
        .map(|t| t.map(|k| m.positions[k as usize].map(|c| c as f32)))
        .collect()
}

#[test]
fn the_viewer_gets_the_stock_block_and_the_part_in_machine_coordinates() {
    // Work zero at machine (100, 50, −20) (G54 from the machine file's
    // offsets is not needed: G92 sets it).
    let p = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\nG92 X-100. Y-50. Z25.\nG00 X5. Y5.\n\
             G01 Z-5. F300\nX35.\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], "box:0,0,-10,40,30,0");
    let (stock, part) = stock_and_part(&f.part).expect("a milled part");
    // The block: 40 × 30 × 10 at machine X100..140, Y50..80, Z−30..−20.
    let v = closed_volume(&unindexed(&stock));
    assert!((v - 12_000.0).abs() < 1e-6, "{v}");
    let lo = [0, 1, 2].map(|k| {
        stock
            .positions
            .iter()
            .map(|p| p[k])
            .fold(f64::MAX, f64::min)
    });
    let hi = [0, 1, 2].map(|k| {
        stock
            .positions
            .iter()
            .map(|p| p[k])
            .fold(f64::MIN, f64::max)
    });
    assert_eq!((lo, hi), ([100.0, 50.0, -30.0], [140.0, 80.0, -20.0]));
    // The part: closed, the stock less the cut (its grid of 400 × 300
    // cells averaged down to fit the viewer's budget keeps the volume).
    let v = closed_volume(&unindexed(&part));
    let want = f.report.stock_mm3 - f.report.removed_mm3;
    assert!((v - want).abs() < 2e-3 * want, "mesh {v}, want {want}");
    assert!(part.triangles.len() <= 2 * VIEW_MESH_CELLS + 8 * 260 + 16);
    // Welded: the top alone has a vertex per cell centre, not six.
    assert!(
        part.positions.len() < part.triangles.len(),
        "{}",
        part.positions.len()
    );
}

#[test]
fn the_viewer_gets_a_turned_part_as_the_half_facing_the_section() {
    let shape = tool(
        1,
        ToolKind::Turning {
            nose_radius_mm: 0.8,
            tip: 3,
        },
        1.6,
    );
    let p =
        "G21 G18 G40 G99\nT0101 S1000 M03\nG00 X46. Z2.\nG01 Z-40. F0.2\nG01 X52.\nG00 Z5.\nM30\n";
    let f = run_with(
        p,
        "fanuc-lathe",
        &library(&[shape]),
        "bar:50,100",
        None,
        None,
    );
    let (bar, part) = stock_and_part(&f.part).expect("a turned part");
    let Part::Lathe(s) = &f.part else {
        panic!("a lathe part")
    };
    for m in [&bar, &part] {
        assert!(!m.triangles.is_empty());
        // The half X ≥ the axis, within the bar's radius.
        for p in &m.positions {
            assert!(p[0] >= s.axis_x - 1e-9, "{p:?}");
            assert!(((p[0] - s.axis_x).powi(2) + p[1] * p[1]).sqrt() <= 25.0 + 1e-9);
        }
    }
    // The bar reaches radius 25 at Y = 0; the turned part only 23 over
    // its first 40 mm.
    let reach = |m: &Indexed, z: f64| {
        m.positions
            .iter()
            .filter(|p| (p[2] - z).abs() < 1e-6 && p[1].abs() < 1e-9)
            .map(|p| p[0] - s.axis_x)
            .fold(0.0, f64::max)
    };
    assert!((reach(&bar, s.stock_box.2) - 25.0).abs() < 1e-9);
    let front = s.stock_box.2;
    assert!(
        (reach(&part, front) - 23.0).abs() < 0.01,
        "{}",
        reach(&part, front)
    );
}
