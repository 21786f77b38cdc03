//! The finished part's STL: closed (every edge shared by exactly two
//! triangles, once in each direction, so the faces are consistently
//! oriented) and as large as the stock less what was removed.

use crate::harness::{library, mill, run_with, tool};
use std::collections::HashMap;
use vcnc_core::ToolKind;
use vcnc_sim::mesh::{HeightField, MAX_MESH_CELLS, revolve, write_stl};
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
