//! The planner against closed forms worked out by hand: a single line
//! (trapezoid, triangle, S-curve), a square under G61 and under G64, a
//! circle at its centripetal limit, a G00 dog-leg under parameter 411 = 1,
//! a dwell and a feed-per-revolution move. The programs run through the
//! interpreter, so the events are the ones `vcnc time` plans.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_core::{Event, Loc, Pos, Sink};
use vcnc_interp::{Dialect, Interpreter, Machine, Options};
use vcnc_planner::{CycleTime, Planner};

/// X, Y, Z alike: 100 mm/s feed limit, 200 mm/s rapid, a = 1000 mm/s²,
/// j = 20000 mm/s³, servo gain 50/s, in-position 0.01 mm, tolerance 0.02.
fn machine(extra_params: &str, profile: &str) -> Machine {
    let axis = |l: &str| {
        format!(
            "[[axes]]\nletter = \"{l}\"\nmin_mm = -1000.0\nmax_mm = 1000.0\n\
             rapid_mm_per_min = 12000.0\nmax_feed_mm_per_min = 6000.0\n\
             accel_mm_s2 = 1000.0\njerk_mm_s3 = 20000.0\nin_position_mm = 0.01\n\
             in_position_rapid_mm = 0.01\n"
        )
    };
    let text = format!(
        "name = \"test\"\n{}{}{}[parameters]\n{extra_params}\n[motion]\nprofile = \"{profile}\"\n\
         corner_tolerance_mm = 0.02\nservo_gain_per_s = 50.0\ntool_change_s = 3.0\n\
         spindle_start_s = 1.0\nspindle_stop_s = 0.5\n",
        axis("x"),
        axis("y"),
        axis("z")
    );
    Machine::from_toml(&text).expect("test machine")
}

fn plan(m: &Machine, program: &str) -> CycleTime {
    let mut planner = Planner::new(m, CycleTime::new());
    Interpreter::new(m, &Dialect::fanuc(), Options::default()).run_str(program, &mut planner);
    planner.into_timeline()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// The settling after an exact stop at a = 1000 along one axis:
/// lag a/K² = 0.4 mm decays as e^(−50 t) into 0.01 mm.
fn settle_one_axis() -> f64 {
    (0.4f64 / 0.01).ln() / 50.0
}

/// Time of a trapezoid over `l` from `v0` to `v1` cruising at `v`.
fn trapezoid(l: f64, v0: f64, v: f64, v1: f64, a: f64) -> f64 {
    l / v + (v - v0).powi(2) / (2.0 * a * v) + (v - v1).powi(2) / (2.0 * a * v)
}

#[test]
fn a_long_line_is_a_trapezoid() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "G1 X100. F6000\nM30\n");
    // L/v + v/a = 1 + 0.1.
    assert!(close(t.cutting_s, 1.1), "{}", t.cutting_s);
    assert!(close(t.total_s, 1.1));
}

#[test]
fn a_short_line_is_a_triangle() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "G1 X5. F6000\nM30\n");
    // The peak √(a·L) = 70.7 mm/s stays below the feed: 2·√(L/a).
    assert!(
        close(t.cutting_s, 2.0 * (5.0f64 / 1000.0).sqrt()),
        "{}",
        t.cutting_s
    );
}

#[test]
fn a_long_line_under_jerk_is_an_s_curve() {
    let m = machine("", "jerk");
    let t = plan(&m, "G1 X100. F6000\nM30\n");
    // Δv = 100 ≥ a²/j = 50: each ramp takes v/a + a/j and covers v/2 of it,
    // so the line takes L/v + v/a + a/j.
    assert!(close(t.cutting_s, 1.0 + 0.1 + 0.05), "{}", t.cutting_s);
    // A short one never reaches a: L = 2·v0... from rest, T = 2·(2L/j)^(1/3)·…
    let short = plan(&m, "G1 X0.1 F6000\nM30\n");
    // Two ramps without a constant-acceleration phase: each covers L/2 =
    // j·s³ (s = √(Δv/j)) and lasts 2s, so T = 4·(L/(2j))^(1/3).
    let expected = 4.0 * (0.05f64 / 20_000.0).cbrt();
    assert!(
        close(short.cutting_s, expected),
        "{} {expected}",
        short.cutting_s
    );
}

/// The filter profile (acceleration and deceleration after interpolation):
/// the trapezoid plan, and at each stop the moving average's T = a/j
/// (0.05 s here) to run out. A long line takes L/v + v/a + T, which is the
/// S-curve's L/v + v/a + a/j: a moving average of T turns each ramp of a
/// into one whose acceleration rises at a/T = j. A short line is the
/// triangle 2·√(L/a) and T, not the S-curve's cube root.
#[test]
fn a_long_line_under_the_filter_takes_the_s_curves_time() {
    let m = machine("", "filter");
    let t = plan(&m, "G1 X100. F6000\nM30\n");
    assert!(close(t.cutting_s, 1.0 + 0.1 + 0.05), "{}", t.cutting_s);
    assert!(close(t.total_s, t.cutting_s));
    let short = plan(&m, "G1 X0.1 F6000\nM30\n");
    let expected = 2.0 * (0.1f64 / 1000.0).sqrt() + 0.05;
    assert!(
        close(short.cutting_s, expected),
        "{} {expected}",
        short.cutting_s
    );
}

/// A rapid and a cut, each ending at rest: each gets its run-out, counted
/// as its own kind of time (the axes still move), and the rapid its
/// settling. Rapid: L/v + v/a = 0.5 + 0.2; cut: 1.0 + 0.1.
#[test]
fn the_filter_runs_out_after_every_stop_as_the_stopped_moves_time() {
    let m = machine("", "filter");
    let t = plan(&m, "G0 X100.\nG1 X0. F6000\nM30\n");
    assert!(close(t.rapid_s, 0.7 + 0.05), "{}", t.rapid_s);
    assert!(close(t.cutting_s, 1.1 + 0.05), "{}", t.cutting_s);
    assert!(
        close(t.in_position_s, settle_one_axis()),
        "{}",
        t.in_position_s
    );
}

/// The trace of that line through the moving average (1 kHz, T = 50
/// samples): the acceleration rises and falls at a/T = j = 20000 mm/s³ at
/// most, reaches a = 1000 mm/s² and the feed 100 mm/s, and the line ends
/// at rest at X100 after L/v + v/a + T.
#[test]
fn the_filtered_trace_of_a_line_is_jerk_limited() {
    use vcnc_planner::{Sample, Sampler, Smoothed};
    let m = machine("", "filter");
    let mut samples: Vec<Sample> = Vec::new();
    let sink = |s: &Sample| samples.push(*s);
    let smoothed = Smoothed::new(0.05, 0.001, m.start, sink);
    let mut planner = Planner::new(&m, Sampler::new(0.001, m.start, smoothed));
    Interpreter::new(&m, &Dialect::fanuc(), Options::default())
        .run_str("G1 X100. F6000\nM30\n", &mut planner);
    planner.into_timeline().finish();
    let (mut top_a, mut top_v, mut top_j) = (0.0f64, 0.0f64, 0.0f64);
    for w in samples.windows(2) {
        let j = (w[1].acc[0] - w[0].acc[0]) / (w[1].t - w[0].t);
        top_j = top_j.max(j.abs());
        top_a = top_a.max(w[1].acc[0].abs());
        top_v = top_v.max(w[1].vel[0]);
    }
    assert!(top_j <= 20_000.0 * (1.0 + 1e-6), "{top_j}");
    assert!(close(top_a, 1000.0), "{top_a}");
    assert!(close(top_v, 100.0), "{top_v}");
    let last = samples.last().expect("samples");
    assert!(close(last.pos.get(0), 100.0) && last.speed == 0.0);
    assert!((last.t - 1.15).abs() < 0.0015, "{}", last.t);
}

/// 0.1 mm chords of a circle of R 5 blended at F6000: the filter plans
/// them as trapezoids do and adds one T where the chain stops, while the
/// per-block S-curve starts every block's ramp from zero acceleration and
/// takes longer (`docs/planner.md`, Profiles).
#[test]
fn short_blended_chords_run_as_trapezoids_under_the_filter() {
    let mut chords = String::from("G64 G1 X5. F6000\n");
    for k in 1..=314 {
        let a = f64::from(k) * 0.02;
        chords.push_str(&format!("X{:.4} Y{:.4}\n", 5.0 * a.cos(), 5.0 * a.sin()));
    }
    chords.push_str("M30\n");
    let trapezoid = plan(&machine("", "trapezoid"), &chords);
    let filter = plan(&machine("", "filter"), &chords);
    let jerk = plan(&machine("", "jerk"), &chords);
    assert!(
        close(filter.cutting_s, trapezoid.cutting_s + 0.05),
        "{} {}",
        filter.cutting_s,
        trapezoid.cutting_s
    );
    assert!(
        jerk.cutting_s > 1.1 * filter.cutting_s,
        "{} {}",
        jerk.cutting_s,
        filter.cutting_s
    );
}

#[test]
fn a_square_under_g61_stops_at_every_corner_and_under_g64_blends() {
    let m = machine("", "trapezoid");
    let square = "G1 X20. F6000\nY20.\nX0.\nY0.\nM30\n";
    let g61 = plan(&m, &format!("G61\n{square}"));
    // Four 20 mm sides from rest to rest, each L/v + v/a = 0.3 s, and four
    // settlings into position.
    assert!(close(g61.cutting_s, 1.2), "{}", g61.cutting_s);
    assert!(close(g61.in_position_s, 4.0 * settle_one_axis()));
    let g64 = plan(&m, &format!("G64\n{square}"));
    // 90° corners: R = δ·cos45°/(1 − cos45°), v_c = √(a·R).
    let c = std::f64::consts::FRAC_1_SQRT_2;
    let vc = (1000.0 * 0.02 * c / (1.0 - c)).sqrt();
    let expected = trapezoid(20.0, 0.0, 100.0, vc, 1000.0)
        + 2.0 * trapezoid(20.0, vc, 100.0, vc, 1000.0)
        + trapezoid(20.0, vc, 100.0, 0.0, 1000.0);
    assert!(
        close(g64.cutting_s, expected),
        "{} {expected}",
        g64.cutting_s
    );
    assert_eq!(g64.in_position_s, 0.0);
    assert!(g64.total_s < g61.total_s);
}

#[test]
fn a_g09_block_stops_once() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "G1 X20. F6000\nG09 Y20.\nX0.\nM30\n");
    assert!(
        close(t.in_position_s, settle_one_axis()),
        "{}",
        t.in_position_s
    );
}

#[test]
fn a_circle_runs_at_its_centripetal_limit() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "G1 X10. F6000\nG91 G2 I-10. F6000\nM30\n");
    // v = √(0.8·a·r) = 89.44 mm/s < 100; the circle starts and ends at rest
    // (the corner into it is tangent here, but the line ahead reaches only
    // its own limit) — plan the circle alone to get a closed form.
    let alone = plan(&m, "G91 G2 X0. Y0. I10. F6000\nM30\n");
    let v = (0.8f64 * 1000.0 * 10.0).sqrt();
    let l = 2.0 * std::f64::consts::PI * 10.0;
    // Tangential acceleration on the arc: 0.6·a.
    let expected = trapezoid(l, 0.0, v, 0.0, 600.0);
    assert!(
        close(alone.cutting_s, expected),
        "{} {expected}",
        alone.cutting_s
    );
    assert!(t.cutting_s > alone.cutting_s);
}

#[test]
fn a_dog_leg_rapid_times_each_axis_alone() {
    let m = machine("g00_mode = 1", "trapezoid");
    let t = plan(&m, "G0 X100. Y10.\nM30\n");
    // X: 100 mm at 200 mm/s: L/v + v/a = 0.7 s; Y: 10 mm, peak √(a·L) =
    // 100 < 200: 2·√(L/a) = 0.2 s. The slower axis decides.
    assert!(close(t.rapid_s, 0.7), "{}", t.rapid_s);
    assert!(close(t.in_position_s, settle_one_axis()));
    // The same block run twice in a row (a subprogram's L repeat) is two
    // moves, not one dog-leg: the second leg moves the same axis again.
    let rapid = |x: f64| Event::Rapid {
        loc: Loc {
            line: 7,
            file: None,
        },
        to: Pos([x, 0.0, 0.0, 0.0, 0.0, 0.0]),
        exact_stop: false,
    };
    let mut p = Planner::new(&m, CycleTime::new());
    p.event(&rapid(50.0));
    p.event(&rapid(100.0));
    let twice = p.into_timeline();
    // 50 mm at 200 mm/s: L/v + v/a = 0.45 s, twice, and two settlings.
    assert!(close(twice.rapid_s, 0.9), "{}", twice.rapid_s);
    assert!(close(twice.in_position_s, 2.0 * settle_one_axis()));
    // Interpolated (411 = 0) the line is limited by X's rate along it.
    let m0 = machine("g00_mode = 0", "trapezoid");
    let t0 = plan(&m0, "G0 X100. Y10.\nM30\n");
    let l = 101f64.sqrt() * 10.0;
    let v = 200.0 * l / 100.0;
    let a = 1000.0 * l / 100.0;
    assert!(close(t0.rapid_s, l / v + v / a), "{}", t0.rapid_s);
}

#[test]
fn a_dwell_is_its_time() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "G04 X2.5\nM30\n");
    assert!(close(t.total_s, 2.5));
    assert!(close(t.dwell_s, 2.5));
}

#[test]
fn feed_per_revolution_runs_at_the_spindle_speed() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "S1000 M03\nG95 G1 X100. F0.1\nM30\n");
    // 0.1 mm/rev at 1000 rpm = 1.6667 mm/s.
    let v = 0.1 * 1000.0 / 60.0;
    assert!(
        close(t.cutting_s, 100.0 / v + v / 1000.0),
        "{}",
        t.cutting_s
    );
    assert!(close(t.spindle_s, 1.0));
    // With the spindle stopped the interpreter alarms (E342) before the
    // move: nothing reaches the planner to time.
    let stopped = plan(&m, "G95 G1 X100. F0.1\nM30\n");
    assert_eq!((stopped.untimed_moves, stopped.cutting_s), (0, 0.0));
}

#[test]
fn tool_changes_are_timed_and_split_per_tool() {
    let m = machine("", "trapezoid");
    let t = plan(&m, "T1 M06\nG1 X100. F6000\nT2 M06\nG1 X0.\nM30\n");
    assert!(close(t.tool_change_s, 6.0));
    assert_eq!(t.per_tool.len(), 2);
    assert!(close(t.per_tool[0].1, 3.0 + 1.1));
    assert!(close(t.per_tool[1].1, 3.0 + 1.1));
}

#[test]
fn a_stopping_macro_message_stops_the_motion_like_m00() {
    let m = machine("", "trapezoid");
    // #3006 waits for cycle start: the move before it ends at rest, as
    // before an M00. Two 50 mm trapezoids: 2 · (50/100 + 100/1000) = 1.2 s,
    // where the one 100 mm line takes 1.1 s.
    let message = plan(&m, "G1 X50. F6000\n#3006 = 1 (CHECK)\nX100.\nM30\n");
    let m00 = plan(&m, "G1 X50. F6000\nM00\nX100.\nM30\n");
    assert!(
        close(message.cutting_s, m00.cutting_s),
        "{}",
        message.cutting_s
    );
    assert!(close(message.cutting_s, 1.2), "{}", message.cutting_s);
    // Syntec's MSG() only shows its text: one 100 mm line, 1.1 s.
    let mut planner = Planner::new(&m, CycleTime::new());
    Interpreter::new(&m, &Dialect::syntec(), Options::default()).run_str(
        "%@MACRO\nG1 X50. F6000;\nMSG(\"CHECK\");\nX100.;\nM30;\n",
        &mut planner,
    );
    let shown = planner.into_timeline();
    assert!(close(shown.cutting_s, 1.1), "{}", shown.cutting_s);
}

/// Whatever the period, the filtered trace is at rest where the plan
/// stops: the average holds the whole periods within T, so the run-out of
/// T after an exact stop (G61 here) fills it with samples at rest before
/// the next move starts, and the last row is the end point at rest.
#[test]
fn the_filtered_trace_is_at_rest_at_every_stop_whatever_the_period() {
    use vcnc_planner::{Sample, Sampler, Smoothed};
    let m = machine("", "filter");
    for period in [0.001, 0.007, 0.011, 0.019, 0.02, 0.033, 0.05, 0.2] {
        let mut samples: Vec<Sample> = Vec::new();
        let sink = |s: &Sample| samples.push(*s);
        let smoothed = Smoothed::new(0.05, period, m.start, sink);
        let mut planner = Planner::new(&m, Sampler::new(period, m.start, smoothed));
        Interpreter::new(&m, &Dialect::fanuc(), Options::default())
            .run_str("G61 G1 X10. F6000\nY10.\nM30\n", &mut planner);
        planner.into_timeline().finish();
        // The last sample before Y starts to move is at rest at (10, 0).
        let turn = samples
            .iter()
            .rposition(|s| s.pos.get(1) == 0.0)
            .expect("a sample before Y moves");
        let s = samples[turn];
        assert!(
            s.speed == 0.0 && close(s.pos.get(0), 10.0),
            "period {period}: {s:?}"
        );
        let last = samples.last().expect("samples");
        assert!(
            last.speed == 0.0 && last.acc[0] == 0.0 && last.acc[1] == 0.0,
            "period {period}: {last:?}"
        );
        assert!(close(last.pos.get(0), 10.0) && close(last.pos.get(1), 10.0));
    }
}
