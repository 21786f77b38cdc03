//! Adversarial review of the day's last changes (D without G41/G42, words
//! in G70–G73 profiles, E614): each test guards one bug found in review,
//! with the expected values worked out by hand in its comments.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Interpreter, Options, Outcome, VecSink};

use crate::common;

use common::{ends, near, run_str as run};

/// Offset 1 is r = 5; `select` (line 2) is the block that should select
/// it; the G41 of line 5 has no D. The start-up from (-10, -10) to (0, 0)
/// turns left into x = 0 going +Y (inside on the left): it ends where the
/// offset lines meet, x = -5 and y = x + 5·√2 = 2.071068; the wall x = 0
/// up to y = 20, turning right along +X (outside 90°), ends at (-5, 25).
fn d_then_g41(select: &str) -> String {
    format!(
        "G10 L12 P1 R5.\n{select}\nG00 X-10. Y-10. Z10.\nS1000 M03\n\
         G41 G01 X0 Y0 F100.\nY20.\nX20.\nG40 G00 X30. Y30.\nM30\n"
    )
}

fn assert_radius_5(dialect: &Dialect, select: &str) {
    let (ev, out) = run(dialect, &d_then_g41(select));
    assert!(matches!(out, Outcome::Ended(_)), "{select}: {out:?}");
    let start = ends(&ev, 5);
    assert!(
        start.len() == 1 && near(start[0], -5.0, 2.071_068, 10.0),
        "{select}: {start:?}"
    );
    let wall = ends(&ev, 6);
    assert!(
        wall.len() == 1 && near(wall[0], -5.0, 25.0, 10.0),
        "{select}: {wall:?}"
    );
}

#[test]
fn a_d_word_alone_on_its_line_selects_the_radius_for_the_next_g41() {
    // `D1` alone is a block of plain words (no G or M code); it was taken
    // as a motion-only block, which reads D only under G41/G42, so the D
    // was accepted and dropped: the G41 ran with D0 (r = 0).
    for dialect in [Dialect::fanuc(), Dialect::syntec(), Dialect::haas()] {
        assert_radius_5(&dialect, "D1");
    }
}

#[test]
fn a_d_word_in_a_plain_move_selects_the_radius_for_the_next_g41() {
    // The same with D in a move without codes (X0 Y0 is where the tool
    // is: an empty move).
    assert_radius_5(&Dialect::fanuc(), "X0 Y0 D1");
}

#[test]
fn a_d_word_in_a_plain_arc_block_on_a_mill_selects_the_radius_and_keeps_the_arc() {
    // Line 5 carries D1 in a block of plain words under modal G02: on a
    // mill D is no diameter, so the arc stays the semicircle from
    // (-15, -10) to (-10, -10) about (-12.5, -10) (R2.5), and D1 (r = 5)
    // is the radius of the G41 of line 6, whose start-up and wall are
    // those of `d_then_g41`: (-5, 2.071068) and (-5, 25).
    let p = "G10 L12 P1 R5.\nG00 X-20. Y-10. Z10.\nS1000 M03\nG02 X-15. Y-10. R2.5 F100.\n\
             X-10. R2.5 D1\nG41 G01 X0 Y0\nY20.\nX20.\nG40 G00 X30. Y30.\nM30\n";
    let (ev, out) = run(&Dialect::fanuc(), p);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let arc = ev
        .iter()
        .find_map(|e| match e {
            Event::Arc {
                loc, to, center, ..
            } if loc.line == 5 => Some((*to, *center)),
            _ => None,
        })
        .expect("the arc of line 5");
    assert!(
        near(arc.0, -10.0, -10.0, 10.0) && near(arc.1, -12.5, -10.0, 10.0),
        "{arc:?}"
    );
    let start = ends(&ev, 6);
    assert!(
        start.len() == 1 && near(start[0], -5.0, 2.071_068, 10.0),
        "{start:?}"
    );
    let wall = ends(&ev, 7);
    assert!(
        wall.len() == 1 && near(wall[0], -5.0, 25.0, 10.0),
        "{wall:?}"
    );
}

#[test]
fn a_d_word_under_g42_on_the_fanuc_lathe_is_unused() {
    // fanuc-lathe's G41/G42 read no D: the radius is the nose radius of
    // the T offset (T0101: 0.8 mm on the built-in machine). A D under G42
    // was taken as a radius register and D0 silently turned the nose
    // radius compensation off (line 7 then ended at Z-20 on the profile).
    // The dialect has no D: E203 at the D (line 7, column 7).
    let d = Dialect::fanuc_lathe();
    let m = d.machine();
    let mut sink = VecSink::default();
    let p = "G21 G99 G18\nT0101\nG97 S500 M03\nG00 X42. Z2.\nG42 G01 X20. Z0 F0.1\nZ-10.\n\
             Z-20. D0\nX40. Z-30.\nG40 G00 X50.\nM30\n";
    let out = Interpreter::new(&m, &d, Options::default()).run_str(p, &mut sink);
    match out {
        Outcome::Alarm(a) => {
            assert_eq!((a.code, a.line, a.column), (vcnc_syntax::Code::E203, 7, 7))
        }
        other => panic!("{other:?}"),
    }
}
