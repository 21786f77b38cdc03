//! G16 polar input under G91 on Fanuc and Haas (`PolarIncremental::
//! CentreAtCurrentPosition`): the radius and angle a block omits, and the
//! angle a G91 angle adds to, are the current point's own about the origin
//! in the plane chosen now — whatever moved the tool there. Expected points
//! worked out by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common::{ends, near, run_str};
use vcnc_interp::{Dialect, Outcome};

fn run(dialect: &Dialect, program: &str) -> Vec<vcnc_interp::Event> {
    let (events, out) = run_str(dialect, program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    events
}

/// After a move that is not polar (G53 here), a G91 angle adds to the
/// current point's angle and the radius is its distance from the origin:
/// from (20, 20), radius 28.284 at 45° + 90° is (−20, 20) (review 4,
/// finding 2: the last polar block's radius 10 and angle 0 gave (0, 10)).
#[test]
fn a_g91_angle_after_a_move_that_was_not_polar_starts_from_the_current_point() {
    for dialect in [Dialect::fanuc(), Dialect::haas()] {
        let events = run(
            &dialect,
            "G90 G17 G16\nG01 X10. Y0 F100\nG53 X20. Y20.\nG91 Y90.\nM30\n",
        );
        let p = ends(&events, 4);
        assert!(p.len() == 1 && near(p[0], -20.0, 20.0, 0.0), "{p:?}");
        // After G92 makes the current point the origin, the radius is 0: a
        // G91 angle moves nothing.
        let events = run(
            &dialect,
            "G90 G17 G16\nG01 X10. Y0 F100\nG92 X0 Y0\nG91 Y90.\nM30\n",
        );
        assert!(ends(&events, 4).iter().all(|p| near(*p, 10.0, 0.0, 0.0)));
    }
}

/// After a plane change the angle is the current point's in the new plane:
/// (X 0, Y 10, Z 0) under G18 is at the ZX plane's origin, angle 0, so a
/// G91 radius of 5 along it goes to Z 5 (review 4, finding 3: the XY
/// plane's 90° was kept, and X moved instead).
#[test]
fn a_plane_change_takes_the_angle_in_the_new_plane() {
    let events = run(
        &Dialect::fanuc(),
        "G90 G17 G16\nG01 X10. Y90. F100\nG18\nG91 Z5. X0\nM30\n",
    );
    let p = ends(&events, 4);
    assert!(p.len() == 1 && near(p[0], 0.0, 10.0, 5.0), "{p:?}");
}

/// Under G90 too an omitted radius or angle is the current point's: after
/// G53 X20 Y20 (45°, 28.284), `G90 Y90.` keeps that radius (review 4,
/// finding 2b: the last polar block's radius 10 was kept).
#[test]
fn an_omitted_word_under_g90_is_the_current_points() {
    let events = run(
        &Dialect::fanuc(),
        "G90 G17 G16\nG01 X10. Y0 F100\nG53 X20. Y20.\nG90 Y90.\nM30\n",
    );
    let p = ends(&events, 4);
    let r = 20.0_f64.hypot(20.0);
    assert!(p.len() == 1 && near(p[0], 0.0, r, 0.0), "{p:?}");
}
