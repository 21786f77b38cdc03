//! Adversarial review of cutter radius compensation (G40/G41/G42) and the
//! frames it runs under: each test guards one bug found in review, with
//! the expected tool-centre points worked out by hand in its comments.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_interp::{Dialect, Event, Interpreter, Options, Outcome, Pos, VecSink};
use vcnc_syntax::Code;

use crate::common;

use common::{ends, near};

fn run(program: &str) -> (Vec<Event>, Outcome) {
    common::run_str(&Dialect::fanuc(), program)
}

/// A square pocket wall cut with G41 (r = 5) along +X at y = 0, then a
/// machine-coordinate Z move (`mid`), then on up along x = 40.
fn wall_then(mid: &str) -> String {
    format!(
        "G10 L12 P1 R5.\n\
         G00 X0 Y-20. Z-5.\n\
         G41 D1 G01 X0 Y0 F100.\n\
         X40.\n\
         {mid}\n\
         Y30.\n\
         G40 X60.\n\
         M30\n"
    )
}

#[test]
fn g53_z_under_compensation_moves_z_alone() {
    // Line 4 (+X to 40,0, tool left at y = +5) is held until line 5; G53
    // ends it square to its path at (40, 5), then only Z goes to machine
    // 0: the rapid of line 5 ends at (40, 5, 0). X and Y must not jump back
    // to where the tool was when the block was read (the start-up's end,
    // 0, 5), which would rapid the tool across the part.
    let (ev, out) = run(&wall_then("G53 Z0."));
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l5 = ends(&ev, 5);
    assert_eq!(l5.len(), 1, "{l5:?}");
    assert!(near(l5[0], 40.0, 5.0, 0.0), "{l5:?}");
    // Nothing after it goes back towards x = 0 before the cancel.
    for p in ends(&ev, 6) {
        assert!(p.0[0] > 30.0, "line 6 at {p:?}");
    }
}

#[test]
fn g28_z_under_compensation_moves_z_alone() {
    // G28 Z10.: to the intermediate point Z10 (program), then Z to the
    // reference point (machine z = 0). Both legs keep X and Y where the
    // tool is once line 4 has ended square at (40, 5).
    let (ev, out) = run(&wall_then("G28 Z10."));
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l5 = ends(&ev, 5);
    assert_eq!(l5.len(), 2, "{l5:?}");
    assert!(near(l5[0], 40.0, 5.0, 10.0), "{l5:?}");
    assert!(near(l5[1], 40.0, 5.0, 0.0), "{l5:?}");
    for p in ends(&ev, 6) {
        assert!(p.0[0] > 30.0, "line 6 at {p:?}");
    }
}

#[test]
fn an_increment_after_g53_under_compensation_starts_from_the_programmed_point() {
    // After `G53 Z0.` the tool stays at (40, 5) (line 4's square end), but
    // the programmed point is still (40, 0): the vector of 5 is not a
    // programmed offset. So `G91 Y30.` programs (40, 0) → (40, 30) and
    // `X-40.` (40, 30) → (0, 30). Line 7 runs -X with the tool left (−Y):
    // on y = 25. Its start is the corner with line 6 (+Y, tool at
    // x = 35): (35, 25). The cancel runs −Y from (0, 30): after −X that
    // turns left, towards the tool, an inside corner, so line 7 ends where
    // y = 25 meets the cancel's offset x = 5 (left of −Y is +X): (5, 25).
    let prog = "G10 L12 P1 R5.\n\
                G00 X0 Y-20. Z-5.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                X40.\n\
                G53 Z0.\n\
                G91 Y30.\n\
                X-40.\n\
                G90 G40 X0 Y-20.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l6 = ends(&ev, 6);
    assert!(near(*l6.last().unwrap(), 35.0, 25.0, 0.0), "{l6:?}");
    let l7 = ends(&ev, 7);
    assert!(near(*l7.last().unwrap(), 5.0, 25.0, 0.0), "{l7:?}");
    // The programmed path of line 7, as its contour event reports it.
    let contour = ev
        .iter()
        .find_map(|e| match e {
            Event::Contour { loc, from, to, .. } if loc.line == 7 => Some((*from, *to)),
            _ => None,
        })
        .unwrap();
    assert!(near(contour.0, 40.0, 30.0, 0.0), "{contour:?}");
    assert!(near(contour.1, 0.0, 30.0, 0.0), "{contour:?}");
}

#[test]
fn g31_under_compensation_alarms_at_its_g_word() {
    // A skip stops where the signal fires, so the corner the compensation
    // worked out for its end is wrong once it leaves (here an over-cut
    // alarm at the next block, or a tool centre 5 mm off). Fanuc refuses
    // G31 in cutter compensation mode (PS0035): E210 at the G31 word
    // (line 4, column 1), and nothing of line 4 or later moves.
    let prog = "G10 L12 P1 R5.\n\
                G00 X0 Y-20.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                G31 X40.\n\
                G01 Y30.\n\
                M30\n";
    let (ev, out) = run(prog);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!(d.code, Code::E210, "{d:?}");
    assert_eq!((d.line, d.column), (4, 1), "{d:?}");
    assert!(ends(&ev, 4).is_empty() && ends(&ev, 5).is_empty());
}

#[test]
fn g41_to_g42_on_a_straight_line_on_joins_the_two_offsets() {
    // G41 along +X to (40, 0) (tool at y = +5), then G42 on along +X to
    // (80, 0) (tool at y = −5). The two offset lines are parallel: no
    // intersection. Fanuc ("change in the offset direction", no
    // intersection): block A ends square to its end, (40, 5), and a vector
    // square to block B is made at B's start, (40, −5); the tool goes
    // there straight and on along y = −5. B then meets the cancel (−Y
    // after +X turns right, towards the tool on the right: inside) where
    // y = −5 meets the cancel's offset x = 75: (75, −5).
    let prog = "G10 L12 P1 R5.\n\
                G00 X0 Y-20.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                X40.\n\
                G42 X80.\n\
                G40 X80. Y-20.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l4 = ends(&ev, 4);
    assert_eq!(l4.len(), 1, "{l4:?}");
    assert!(near(l4[0], 40.0, 5.0, 0.0), "{l4:?}");
    let l5 = ends(&ev, 5);
    assert_eq!(l5.len(), 2, "{l5:?}");
    assert!(near(l5[0], 40.0, -5.0, 0.0), "{l5:?}");
    assert!(near(l5[1], 75.0, -5.0, 0.0), "{l5:?}");
}

#[test]
fn a_nearly_tangent_arc_to_line_from_rounded_coordinates_is_cut() {
    // CAM output rounds to 0.001 mm, so an arc and the line leaving it
    // tangentially are tangent only to within that. Here the G03 about
    // (0, 10) ends 0.001 beyond its radius (10.001, accepted as an arc)
    // and the line leaves it 0.003° off the tangent (+Y). G42 puts the
    // tool outside the arc (r = 3): its offset circle has radius 13, the
    // line's offset runs along x ≈ 13.001 and misses that circle by
    // 0.001 mm: no intersection, but nothing is over-cut — the corner is
    // the tangent point. Expected: the arc ends at (13.001, 10) and the
    // line, meeting the cancel's offset y = 27 (inside corner),
    // at x = 13.001 + 0.00005·17 = 13.0019.
    let prog = "G10 L12 P1 R3.\n\
                G00 X-30. Y-10.\n\
                G42 D1 G01 X-30. Y0 F100.\n\
                X0\n\
                G03 X10.001 Y10. I0 J10.\n\
                G01 X10.002 Y30.\n\
                G40 X30. Y30.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let near2 = |p: Pos, x: f64, y: f64| (p.0[0] - x).abs() < 2e-3 && (p.0[1] - y).abs() < 2e-3;
    let l5 = ends(&ev, 5);
    assert!(near2(*l5.last().unwrap(), 13.001, 10.0), "{l5:?}");
    let l6 = ends(&ev, 6);
    assert!(near2(*l6.last().unwrap(), 13.0019, 27.0), "{l6:?}");
}

#[test]
fn an_uneven_scale_with_a_negative_factor_swaps_the_side_like_a_mirror() {
    // G51 I-2000 J1000 about (0, 0): x' = −2x, y' = y, a mirror in X with
    // an uneven scale (lines only: arcs would alarm E315). The programmed
    // pocket (0, 0)–(40, 0)–(40, 30) with G41 inside it becomes, on the
    // machine, (0, 0)–(−80, 0)–(−80, 30), still with the tool inside: the
    // mirror swaps G41 to the machine's right, as it does for G51 I-1000.
    // Line 5 runs −X at y = +5 and ends at the inside corner (−75, 5);
    // line 6 runs +Y at x = −75 (right of +Y is +X).
    let prog = "G10 L12 P1 R5.\n\
                G00 X0 Y-20.\n\
                G51 X0 Y0 I-2000 J1000\n\
                G41 D1 G01 X0 Y0 F100.\n\
                X40.\n\
                Y30.\n\
                G40 X60.\n\
                G50\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l5 = ends(&ev, 5);
    assert!(near(*l5.last().unwrap(), -75.0, 5.0, 0.0), "{l5:?}");
    let l6 = ends(&ev, 6);
    assert!((l6.last().unwrap().0[0] + 75.0).abs() < 1e-6, "{l6:?}");
}

#[test]
fn a_full_circle_with_outside_corners_on_both_sides_sweeps_more_than_a_turn() {
    // A full G03 circle about (0, 10) (r 10) at (0, 0), entered along
    // y = x/2 from (−20, −10) and left along y = −x/2 to (20, −10), G41:
    // the tool inside the circle, offset circle radius 5. Both corners
    // are outside (the entry turns right into +X, the exit turns right
    // out of it), so each corner is where the line's offset crosses the
    // offset circle: the entry's offset y = x/2 + 5.59 meets it at
    // (−0.9846, 5.0979) (258.64° about the centre), the exit's at
    // (0.9846, 5.0979) (281.36°). The tool runs from the first over the
    // top (y = 15) round to the second: 360° + 22.71° = 382.71°, 33.40 mm.
    // An event from the one point to the other says 22.71° to a reader,
    // and the circle is never cut.
    let prog = "G10 L12 P1 R5.\n\
                G00 X-40. Y0\n\
                G41 D1 G01 X-20. Y-10. F100.\n\
                X0 Y0\n\
                G03 X0 Y0 I0 J10.\n\
                G01 X20. Y-10.\n\
                G40 X40.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let xy = PlaneAxes {
        a: 0,
        b: 1,
        n: Some(2),
    };
    let mut pos = Pos::default();
    let mut length = 0.0;
    for e in &ev {
        match e {
            Event::Feed { to, .. } | Event::Rapid { to, .. } => pos = *to,
            Event::Arc {
                loc,
                to,
                center,
                dir,
                ..
            } => {
                if loc.line == 5 {
                    length += ArcPath::new(pos, *to, *center, xy, *dir).length();
                }
                pos = *to;
            }
            _ => {}
        }
    }
    assert!((length - 33.398).abs() < 0.01, "arc length {length}");
    assert!(near(*ends(&ev, 5).last().unwrap(), 0.984554, 5.097893, 0.0));
}

#[test]
fn an_arc_the_corners_shrink_to_a_point_is_not_a_full_circle() {
    // A G03 of radius 10 about (0, 0) from 240° (−5, −8.660254) to 300°
    // (5, −8.660254), between a line down x = −5 and a line up x = 5,
    // G41: the tool is inside, the offset circle has radius 5, and both
    // line offsets are x = 0. Both inside corners are where x = 0 meets
    // the offset circle nearest the arc's ends: (0, −5). The compensated
    // arc runs from (0, −5) to (0, −5) sweeping 60° − 30° − 30° = 0: the
    // tool touches the arc's bottom and leaves. One arc event from a point
    // to itself reads as a full circle of radius 5, which passes x = ±5,
    // right through both walls; the tool must stay on x = 0.
    let prog = "G10 L12 P1 R5.\n\
                G00 X-5. Y20.\n\
                G41 D1 G01 X-5. Y10. F100.\n\
                Y-8.660254\n\
                G03 X5. Y-8.660254 I5. J8.660254\n\
                G01 Y10.\n\
                G40 X5. Y20.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    for e in &ev {
        if let Event::Arc { loc, .. } = e {
            assert!(loc.line != 5, "an arc event for the collapsed arc: {e:?}");
        }
    }
    for p in ends(&ev, 5) {
        assert!(p.0[0].abs() < 1e-4 && (p.0[1] + 5.0).abs() < 1e-4, "{p:?}");
    }
}

#[test]
fn a_d_word_in_an_arc_block_under_g41_is_the_offset_number_not_a_diameter() {
    // Fanuc: under G41/G42 a D word in any motion block, arcs included,
    // changes the radius offset. Only the lathe dialect reads D on an arc
    // as its diameter. Here D2 (r = 3) comes with a G03 given by I/J about
    // (0, 20) from (0, 0) to (20, 20); the tool is left, towards the
    // centre. The line after it leaves tangentially (+Y), so the arc ends
    // square to its end at the new radius: (20 − 3, 20) = (17, 20).
    let prog = "G10 L12 P1 R5.\n\
                G10 L12 P2 R3.\n\
                G00 X0 Y-20.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                G03 X20. Y20. I0. J20. D2\n\
                G01 X20. Y40.\n\
                G40 X40.\n\
                M30\n";
    let (ev, out) = run(prog);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let l5 = ends(&ev, 5);
    assert!(near(*l5.last().unwrap(), 17.0, 20.0, 0.0), "{l5:?}");
}

#[test]
fn a_radius_change_on_an_arc_under_compensation_alarms() {
    // D2 (r = 3, was 5) on a G03 about (20, 20) from (20, 0): the corner
    // before the arc is worked out with the old radius, so the arc would
    // start 15 from its centre, at (20, 5), and end with the new one 17
    // from it, at (37, 20). No circle does that (one event cannot say it,
    // grbl refuses it, a Fanuc alarms PS0020). E320 at the G03 word (line
    // 6, column 4), and nothing of the arc or after it moves.
    let prog = "G10 L12 P1 R5.\n\
                G10 L12 P2 R3.\n\
                G00 X0 Y-20.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                X20.\n\
                D2 G03 X40. Y20. I0. J20.\n\
                G01 Y40.\n\
                G40 X60.\n\
                M30\n";
    let (ev, out) = run(prog);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code, d.line, d.column), (Code::E320, 6, 4), "{d:?}");
    assert!(ends(&ev, 6).is_empty() && ends(&ev, 7).is_empty());
}

#[test]
fn a_d_word_in_a_modal_arc_block_under_g41_changes_the_radius() {
    // As above, but the arc block is modal G03 after another G03 (the
    // usual way to write a chain of arcs). Its D2 must change the radius
    // to 3 as in any motion block, not be dropped: here it is in force at
    // an arc that is not the first after the start-up, so E320 at the
    // first word of line 6 (the block has no G word). Ignoring it would
    // cut on with r = 5 though the program asks for 3.
    let prog = "G10 L12 P1 R5.\n\
                G10 L12 P2 R3.\n\
                G00 X0 Y-20.\n\
                G41 D1 G01 X0 Y0 F100.\n\
                G03 X20. Y20. I0. J20.\n\
                X0 Y40. I-20. J0. D2\n\
                G01 X-20.\n\
                G40 Y0\n\
                M30\n";
    let (_, out) = run(prog);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code, d.line), (Code::E320, 6), "{d:?}");
}

#[test]
fn a_d_word_without_g41_selects_the_radius_for_the_next_g41() {
    // Fanuc keeps D modal: `T1 M06 D1` and `G43 Z10. H1 D1` store offset 1
    // (r = 5 by G10 L12), and the G41 of line 6 without D uses it. The
    // start-up from (-10, -10) to (0, 0) turns left into x = 0 going +Y
    // (an inside corner on the left): it ends where the offset lines meet,
    // x = -5 and y = x + 5·√2, i.e. (-5, 2.071068); the wall x = 0 up to
    // y = 20 turning right along +X (an outside 90° corner) ends at the
    // intersection (-5, 25).
    let p = "G10 L12 P1 R5.\nT1 M06 D1\nG00 G43 Z10. H1 D1\nG00 X-10. Y-10.\n\
             S1000 M03\nG41 G01 X0 Y0 F100.\nY20.\nX20.\nG40 G00 X30. Y30.\nM30\n";
    let (ev, out) = run(p);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let start = ends(&ev, 6);
    assert!(near(start[0], -5.0, 2.071_068, 10.0), "{start:?}");
    let wall = ends(&ev, 7);
    assert!(near(wall[0], -5.0, 25.0, 10.0), "{wall:?}");
}

#[test]
fn a_d_word_alone_stays_an_error_where_d_is_no_radius_offset() {
    // grbl has no cutter compensation: a lone D is an unused word (E203).
    let d = Dialect::grbl();
    let m = d.machine();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &d, Options::default()).run_str("D1\nM2\n", &mut sink);
    match out {
        Outcome::Alarm(a) => assert_eq!((a.code, a.line, a.column), (Code::E203, 1, 1)),
        other => panic!("{other:?}"),
    }
}
