//! Each collision kind, located at the line that causes it, and a safe
//! program with none.

use crate::harness::{library, mill, run_with, tool};
use vcnc_core::ToolKind;
use vcnc_sim::{CollisionKind, Finished};

fn kinds(f: &Finished) -> Vec<(CollisionKind, u64)> {
    f.report
        .collisions
        .iter()
        .map(|c| (c.kind, c.line))
        .collect()
}

const STOCK: &str = "box:0,0,-10,60,40,0";

#[test]
fn a_safe_program_reports_nothing() {
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG01 Z-3. F300\nG01 X50.\nG02 X50. Y30. I0. J10.\nG01 X10.\nG00 Z5.\nG00 X100. Y100.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], STOCK);
    assert_eq!(kinds(&f), vec![]);
    assert!(f.report.removed_mm3 > 0.0);
}

#[test]
fn a_rapid_into_the_stock_is_found_at_its_line() {
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG00 Z-2.\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], STOCK);
    assert_eq!(kinds(&f), vec![(CollisionKind::RapidIntoStock, 4)]);
    // A rapid that only grazes (5 µm) is not a crash.
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG00 Z-0.005\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], STOCK);
    assert_eq!(kinds(&f), vec![]);
}

#[test]
fn a_cut_deeper_than_the_flutes_puts_the_shank_in_the_stock() {
    let mut t = tool(1, ToolKind::Flat, 6.0);
    t.flute_length_mm = Some(5.0);
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG01 Z-4. F300\nG01 X30.\nG01 Z-8.\nG01 X50.\nG00 Z5.\nM30\n";
    let f = mill(p, &[t], STOCK);
    // The plunge to −8 (line 6) stays in the hole cut at −4, the shank
    // above its floor; the cut after it (line 7) drags the shank, 3 mm
    // deep, through the stock ahead.
    assert_eq!(kinds(&f), vec![(CollisionKind::HolderIntoStock, 7)]);
}

#[test]
fn a_holder_below_the_top_is_found() {
    let mut t = tool(1, ToolKind::Flat, 6.0);
    t.flute_length_mm = Some(20.0);
    t.stickout_mm = Some(6.0);
    t.holder_diameter_mm = Some(30.0);
    let p = "G21 G90 G17\nT1 M06\nG00 X30. Y20. Z10.\nG01 Z-3. F300\nG00 Z10.\nM30\n";
    let f = mill(p, &[t.clone()], STOCK);
    assert_eq!(kinds(&f), vec![]);
    let p = "G21 G90 G17\nT1 M06\nG00 X30. Y20. Z10.\nG01 Z-7. F300\nG00 Z10.\nM30\n";
    let f = mill(p, &[t], STOCK);
    assert_eq!(kinds(&f), vec![(CollisionKind::HolderIntoStock, 4)]);
}

#[test]
fn a_cut_through_the_bottom_is_found() {
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG01 Z-9. F300\nG01 X20.\nG01 Z-11.\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], STOCK);
    assert_eq!(kinds(&f), vec![(CollisionKind::BelowStock, 6)]);
}

#[test]
fn the_table_is_found_at_its_height() {
    let p = "G21 G90 G17\nT1 M06\nG00 X100. Y100. Z5.\nG01 Z-19. F300\nG01 Z-21.\nG00 Z5.\nM30\n";
    let tools = library(&[tool(1, ToolKind::Flat, 6.0)]);
    let f = run_with(p, "fanuc", &tools, STOCK, Some(0.1), Some(-20.0));
    assert_eq!(kinds(&f), vec![(CollisionKind::Fixture, 5)]);
}

#[test]
fn a_non_centre_cutting_plunge_is_found() {
    let mut t = tool(1, ToolKind::Flat, 6.0);
    t.center_cutting = Some(false);
    // A ramp (line 4) is fine; the straight plunge (line 7) is not.
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z1.\nG01 X30. Z-2. F300\nG00 Z5.\nG00 X45. Y20.\nG01 Z-3.\nG00 Z5.\nM30\n";
    let f = mill(p, &[t], STOCK);
    assert_eq!(kinds(&f), vec![(CollisionKind::NonCenterCuttingPlunge, 7)]);
}

#[test]
fn a_rapid_into_a_bar_is_found_on_a_lathe() {
    let shape = crate::harness::tool(
        1,
        ToolKind::Turning {
            nose_radius_mm: 0.8,
            tip: 3,
        },
        1.6,
    );
    let p = "G21 G18 G40 G99\nT0101 S1000 M03\nG00 X60. Z2.\nG00 X40. Z-10.\nG00 X60. Z2.\nM30\n";
    let f = run_with(
        p,
        "fanuc-lathe",
        &library(&[shape]),
        "bar:50,100",
        None,
        None,
    );
    assert_eq!(kinds(&f), vec![(CollisionKind::RapidIntoStock, 4)]);
}

#[test]
fn moves_with_rotary_axes_are_counted_not_simulated() {
    let p = "G21 G90 G17\nT1 M06\nG00 X10. Y10. Z5.\nG01 Z-1. F300\nG01 X20. A90.\nG01 X30.\nG00 Z5.\nM30\n";
    let f = mill(p, &[tool(1, ToolKind::Flat, 6.0)], STOCK);
    assert_eq!(f.report.not_simulated, 1);
    assert_eq!(
        f.report.first_not_simulated.as_ref().map(|(l, _)| *l),
        Some(5)
    );
}
