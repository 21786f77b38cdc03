//! Removed volume against closed forms, within 1 % (the bar): a
//! flat slot, a pocket, a ball-nose groove, an arc ring, a helical bore,
//! drilled holes, and on a lathe turning, facing and grooving with the
//! nose radius. Each expected volume is worked out in the test from the
//! geometry, not taken from a run.

use crate::harness::{close, library, mill, run_with, tool};
use std::f64::consts::PI;
use vcnc_core::ToolKind;

#[test]
fn a_flat_slot_removes_its_box_and_round_ends() {
    let p = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\nG01 Z-2. F300\nG01 X50.\nG00 Z5.\nM30\n";
    let f = mill(
        p,
        &[tool(1, ToolKind::Flat, 10.0)],
        "box:-20,-20,-10,70,20,0",
    );
    // 50 long, 10 wide, 2 deep, plus a 10 mm disc 2 deep (two half ends).
    close(
        f.report.removed_mm3,
        50.0 * 10.0 * 2.0 + PI * 25.0 * 2.0,
        0.01,
    );
    close(f.report.stock_mm3, 90.0 * 40.0 * 10.0, 1e-9);
    assert!(f.report.collisions.is_empty(), "{:?}", f.report.collisions);
}

#[test]
fn a_pocket_removes_its_rounded_rectangle() {
    // Zig-zag at 5 mm steps over the tool centre's rectangle [5,35]×[5,25]
    // and its outline: the pocket is that rectangle grown by the 5 mm
    // radius, 40 × 30 with 5 mm corners, 5 deep.
    let p = "G21 G90 G17\nT1 M06\nG00 X5. Y5. Z5.\nG01 Z-5. F300\n\
             X35.\nY10.\nX5.\nY15.\nX35.\nY20.\nX5.\nY25.\nX35.\nY5.\nX5.\nY25.\nG00 Z5.\nM30\n";
    let f = mill(
        p,
        &[tool(1, ToolKind::Flat, 10.0)],
        "box:-10,-10,-10,50,40,0",
    );
    let area = 30.0 * 20.0 + 2.0 * 5.0 * (30.0 + 20.0) + PI * 25.0;
    close(f.report.removed_mm3, area * 5.0, 0.01);
}

/// Area of the circular segment of height `d` in a circle of radius `r`.
fn segment(r: f64, d: f64) -> f64 {
    r * r * ((r - d) / r).acos() - (r - d) * (2.0 * r * d - d * d).sqrt()
}

#[test]
fn a_ball_nose_groove_is_its_segment_times_length_plus_a_cap() {
    let p = "G21 G90 G17\nT2 M06\nG00 X0. Y0. Z5.\nG01 Z-3. F200\nG01 X40.\nG00 Z5.\nM30\n";
    let f = mill(
        p,
        &[tool(2, ToolKind::Ball, 10.0)],
        "box:-10,-10,-10,50,10,0",
    );
    // The groove's section is a segment of the 5 mm circle 3 deep; the two
    // half caps at its ends make one spherical cap of height 3.
    let cap = PI * 9.0 * (3.0 * 5.0 - 3.0) / 3.0;
    close(f.report.removed_mm3, segment(5.0, 3.0) * 40.0 + cap, 0.01);
}

#[test]
fn an_arc_ring_is_its_annulus() {
    let p = "G21 G90 G17\nT1 M06\nG00 X20. Y0. Z5.\nG01 Z-2. F300\nG03 X20. Y0. I-20. J0.\nG00 Z5.\nM30\n";
    let f = mill(
        p,
        &[tool(1, ToolKind::Flat, 6.0)],
        "box:-30,-30,-10,30,30,0",
    );
    close(
        f.report.removed_mm3,
        PI * (23.0f64.powi(2) - 17.0f64.powi(2)) * 2.0,
        0.01,
    );
}

#[test]
fn a_helical_bore_is_its_cylinder() {
    // A 10 mm end mill on a 5 mm helix radius: a 20 mm bore, four turns
    // down to 10 deep and a full circle at the bottom.
    let p = "G21 G90 G17\nT1 M06\nG00 X5. Y0. Z1.\nG01 Z1. F300\n\
             G03 X5. Y0. I-5. J0. Z-1.75\nG03 X5. Y0. I-5. J0. Z-4.5\n\
             G03 X5. Y0. I-5. J0. Z-7.25\nG03 X5. Y0. I-5. J0. Z-10.\n\
             G03 X5. Y0. I-5. J0.\nG00 Z5.\nM30\n";
    let f = mill(
        p,
        &[tool(1, ToolKind::Flat, 10.0)],
        "box:-15,-15,-20,15,15,0",
    );
    close(f.report.removed_mm3, PI * 100.0 * 10.0, 0.01);
}

#[test]
fn drilled_holes_have_their_point() {
    let p = "G21 G90 G17\nT3 M06\nG00 X10. Y10. Z5.\nG99 G81 X10. Y10. Z-15. R2. F100\nX30.\nX50.\nG80\nG00 Z5.\nM30\n";
    let drill = tool(
        3,
        ToolKind::Drill {
            point_angle_deg: 118.0,
        },
        10.0,
    );
    let f = mill(p, &[drill], "box:0,0,-30,60,20,0");
    // Each hole: a 10 mm cylinder down to where the 118° cone starts, and
    // the cone (height 5 / tan 59°) below it, its tip at Z−15.
    let h = 5.0 / 59f64.to_radians().tan();
    let hole = PI * 25.0 * (15.0 - h) + PI * 25.0 * h / 3.0;
    close(f.report.removed_mm3, 3.0 * hole, 0.01);
}

fn insert(number: u32, nose: f64, tip: u8) -> vcnc_core::ToolShape {
    tool(
        number,
        ToolKind::Turning {
            nose_radius_mm: nose,
            tip,
        },
        2.0 * nose,
    )
}

fn lathe(p: &str, stock: &str) -> vcnc_sim::Finished {
    let tools = library(&[insert(1, 0.8, 3), insert(4, 0.2, 3)]);
    run_with(p, "fanuc-lathe", &tools, stock, None, None)
}

/// A corner's material a nose of radius `r` leaves in a square corner at
/// radius `r0` (the corner's own): the square minus a quarter disc, its
/// centroid `r·(10 − 3π)/(12 − 3π)` from the corner; the volume it turns.
fn fillet_volume(r: f64, r0: f64) -> f64 {
    let area = r * r * (1.0 - PI / 4.0);
    let centroid = r0 + r * (10.0 - 3.0 * PI) / (12.0 - 3.0 * PI);
    2.0 * PI * centroid * area
}

#[test]
fn turning_to_a_shoulder_leaves_the_nose_fillet() {
    // Ø50 bar turned to Ø46 over 40 mm with a 0.8 mm nose (tip 3): the
    // shoulder keeps a 0.8 mm fillet at Z−40.
    let p =
        "G21 G18 G40 G99\nT0101 S1000 M03\nG00 X46. Z2.\nG01 Z-40. F0.2\nG01 X52.\nG00 Z2.\nM30\n";
    let f = lathe(p, "bar:50,100");
    let want = PI * (25.0f64.powi(2) - 23.0f64.powi(2)) * 40.0 - fillet_volume(0.8, 23.0);
    close(f.report.removed_mm3, want, 0.01);
    close(f.report.stock_mm3, PI * 625.0 * 100.0, 1e-9);
}

#[test]
fn facing_removes_a_disc_to_the_centre() {
    let p = "G21 G18 G40 G99\nT0101 S1000 M03\nG00 X52. Z-1.\nG01 X-1.6 F0.2\nG00 Z2.\nM30\n";
    let f = lathe(p, "bar:50,100");
    close(f.report.removed_mm3, PI * 625.0, 0.01);
}

#[test]
fn grooving_leaves_rounded_bottom_corners() {
    // A 0.2 mm nose (tip 3) plunges to Ø40 at Z−20, feeds to Z−25 and
    // retracts: a groove from Z−25 to Z−19.6 (the nose is 0.4 wide) with
    // two 0.2 mm fillets at its bottom.
    let p = "G21 G18 G40 G99\nT0404 S1000 M03\nG00 X52. Z-20.\nG01 X40. F0.05\nG01 Z-25.\nG01 X52.\nG00 Z2.\nM30\n";
    let f = lathe(p, "bar:50,100");
    let want = PI * (625.0 - 400.0) * 5.4 - 2.0 * fillet_volume(0.2, 20.0);
    close(f.report.removed_mm3, want, 0.01);
}
