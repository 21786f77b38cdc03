//! Invariants of the planned trajectory on every example program of the
//! Syntec manual (`tests/fixtures/manual/*.nc`) and the repository's
//! examples, under both profile shapes:
//!
//! - no axis exceeds its velocity (rapid or cutting), acceleration or jerk
//!   limit anywhere on a move (each move is evaluated densely in closed
//!   form, centripetal acceleration included);
//! - the speed is continuous from one move to the next, and a corner passed
//!   at speed would round off at most the corner tolerance: the circle that
//!   turns the velocity with the acceleration the corner's plane allows has
//!   a deviation δ = R·(1 − cos(θ/2))/cos(θ/2) ≤ tolerance, R = v²/a;
//! - exact-stop blocks (G09, G61) end at rest;
//! - the planned time is never below distance/feed, and converges to it as
//!   accelerations, jerks and the servo gain grow.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::path::{Path, PathBuf};
use vcnc_core::{MAX_AXES, Machine, Sink};
use vcnc_interp::{Dialect, Interpreter, Options};
use vcnc_output::Summary;
use vcnc_planner::{
    AxesMove, CycleTime, MoveKind, Pause, Planner, Profile, ProfileShape, Segment, Shape, Timeline,
};

const EPS: f64 = 1e-6;

fn programs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut out = Vec::new();
    for dir in ["tests/fixtures/manual", "examples"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "nc") {
                out.push(p);
            }
        }
    }
    out.sort();
    assert!(out.len() > 50, "the manual's examples are there");
    out
}

/// Checks every move as it is committed.
struct Checker {
    m: Machine,
    jerk: bool,
    tol: f64,
    prev: Option<(Segment, f64)>,
    exact_lines: Vec<u64>,
    /// The largest G05.1 E of the program (0: none).
    smoothing_mm: f64,
    failures: Vec<String>,
}

impl Checker {
    fn fail(&mut self, what: String) {
        if self.failures.len() < 20 {
            self.failures.push(what);
        }
    }

    fn axis_limits(&self, kind: MoveKind, i: usize) -> (f64, f64, f64) {
        let a = &self.m.axes[i];
        let v = match kind {
            MoveKind::Rapid => a.rapid_mm_per_min,
            MoveKind::Cut => a.max_feed_mm_per_min,
        } / 60.0;
        (v, a.accel_mm_s2, a.jerk_mm_s3)
    }

    fn check_corner(&mut self, seg: &Segment, v_entry: f64) {
        let Some((prev, v_exit)) = self.prev.take() else {
            return;
        };
        if (v_exit - v_entry).abs() > EPS * v_exit.max(1.0) {
            self.fail(format!(
                "line {}: speed jumps {v_exit} -> {v_entry}",
                seg.attr.line
            ));
        }
        if v_entry <= EPS {
            return;
        }
        let n = self.m.axes.len();
        let u1 = prev.path.tangent(prev.path.len);
        let u2 = seg.path.tangent(0.0);
        let norm = |u: &[f64; MAX_AXES]| u.iter().map(|x| x * x).sum::<f64>().sqrt();
        let (e1, e2) = (u1.map(|x| x / norm(&u1)), u2.map(|x| x / norm(&u2)));
        let cos = (0..n).map(|i| e1[i] * e2[i]).sum::<f64>().clamp(-1.0, 1.0);
        let theta = cos.acos();
        if theta < 1e-6 {
            return;
        }
        // The acceleration available in the corner's plane: every unit
        // vector of the plane keeps each axis within its own limit.
        let w: Vec<f64> = (0..n).map(|i| e2[i] - cos * e1[i]).collect();
        let wn = w.iter().map(|x| x * x).sum::<f64>().sqrt();
        let mut a = f64::INFINITY;
        for i in 0..n {
            let span = (e1[i] * e1[i] + (w[i] / wn).powi(2)).sqrt();
            if span > 1e-12 {
                a = a.min(self.m.axes[i].accel_mm_s2 / span);
            }
        }
        let r = v_entry * v_entry / a;
        let half = theta / 2.0;
        let deviation = r * (1.0 - half.cos()) / half.cos();
        // The tolerance in force is the machine's, or a G05 set's / G05.1's
        // when the planner says so: never more than the checker's bound.
        let tol = seg.corner_tolerance_mm;
        if tol > self.tol.max(self.smoothing_mm) * (1.0 + 1e-12) {
            self.fail(format!("line {}: corner tolerance {tol} mm", seg.attr.line));
        }
        if deviation > tol * (1.0 + 1e-6) {
            self.fail(format!(
                "line {}: corner at {v_entry} mm/s deviates {deviation} mm",
                seg.attr.line
            ));
        }
    }
}

impl Timeline for Checker {
    fn segment(&mut self, seg: &Segment, p: &Profile) {
        let v_entry = p.up.v0;
        self.check_corner(seg, v_entry);
        let n = self.m.axes.len();
        let d = p.duration();
        let steps = 400;
        for k in 0..=steps {
            let t = d * f64::from(k) / f64::from(steps);
            let [s, v, acc, j] = p.at(t);
            let u = seg.path.tangent(s);
            let kappa = seg.path.curvature(s);
            for i in 0..n {
                let (vl, al, jl) = self.axis_limits(seg.kind, i);
                let vi = (v * u[i]).abs();
                let ai = (acc * u[i] + v * v * kappa[i]).abs();
                if vi > vl * (1.0 + EPS) + EPS {
                    self.fail(format!("line {}: axis {i} at {vi} mm/s", seg.attr.line));
                }
                if ai > al * (1.0 + EPS) + EPS {
                    self.fail(format!("line {}: axis {i} at {ai} mm/s²", seg.attr.line));
                }
                let line = matches!(seg.path.shape, Shape::Line(_));
                if self.jerk && line && (j * u[i]).abs() > jl * (1.0 + EPS) {
                    self.fail(format!(
                        "line {}: axis {i} jerk {}",
                        seg.attr.line,
                        j * u[i]
                    ));
                }
            }
        }
        let exit = p.down.v1;
        if self.exact_lines.contains(&seg.attr.line) && exit > EPS {
            self.fail(format!(
                "line {}: exact stop ends at {exit} mm/s",
                seg.attr.line
            ));
        }
        self.prev = Some((seg.clone(), exit));
    }
    fn axes(&mut self, _: &AxesMove) {
        self.prev = None;
    }
    fn pause(&mut self, _: &Pause) {
        if let Some((_, v)) = &self.prev
            && *v > EPS
        {
            self.fail(format!("a pause while moving at {v} mm/s"));
        }
        self.prev = None;
    }
}

/// Lines of `text` whose block has G09 or runs under G61 (a crude modal
/// scan that is enough for the manual's examples: G61 until G62/G63/G64).
fn exact_stop_lines(text: &str) -> Vec<u64> {
    let mut g61 = false;
    let mut out = Vec::new();
    for (n, l) in (1u64..).zip(text.lines()) {
        let code = l.split("//").next().unwrap_or("").to_ascii_uppercase();
        let code = code.split('(').next().unwrap_or("");
        let has = |g: &str| {
            code.match_indices(g).any(|(i, _)| {
                !code[i + g.len()..].starts_with(|c: char| c.is_ascii_digit() || c == '.')
            })
        };
        if has("G61") {
            g61 = true;
        }
        if has("G62") || has("G63") || has("G64") {
            g61 = false;
        }
        let cutting = has("G01") || has("G1") || has("G02") || has("G2") || has("G03") || has("G3");
        if has("G09") || has("G9") || (g61 && cutting) {
            out.push(n);
        }
    }
    out
}

/// The largest E of the program's `G5.1 Q1 E…` / `G05.1 Q1 E…` blocks.
fn smoothing_e(text: &str) -> f64 {
    text.lines()
        .filter(|l| l.contains("G5.1 Q1") || l.contains("G05.1 Q1"))
        .filter_map(|l| {
            let e = l.split_whitespace().find(|w| w.starts_with('E'))?;
            e[1..].parse::<f64>().ok()
        })
        .fold(0.0, f64::max)
}

fn run(path: &Path, m: &Machine, sink: &mut impl Sink) {
    let text = std::fs::read_to_string(path).unwrap();
    Interpreter::new(m, &Dialect::syntec(), Options::default()).run_str(&text, sink);
}

#[test]
fn the_manual_examples_keep_every_limit() {
    for shape in [ProfileShape::Trapezoid, ProfileShape::Jerk] {
        let m = Machine::default_mill();
        for path in programs() {
            let text = std::fs::read_to_string(&path).unwrap();
            let checker = Checker {
                m: m.clone(),
                jerk: shape == ProfileShape::Jerk,
                tol: m.motion.corner_tolerance_mm,
                prev: None,
                exact_lines: exact_stop_lines(&text),
                smoothing_mm: smoothing_e(&text),
                failures: Vec::new(),
            };
            let mut planner = Planner::with_profile(&m, shape, checker);
            run(&path, &m, &mut planner);
            let c = planner.into_timeline();
            assert!(
                c.failures.is_empty(),
                "{} ({shape:?}): {:#?}",
                path.display(),
                c.failures
            );
        }
    }
}

#[test]
fn the_exact_stop_scan_finds_the_manual_g09_g61_example() {
    let text = "G61\nG01 X1.\nG64\nG01 X2.\nG09 G01 X3.\n";
    assert_eq!(exact_stop_lines(text), vec![2, 5]);
}

/// Planned time and the distance/feed estimate of one program.
fn times(path: &Path, m: &Machine) -> (f64, f64) {
    let mut planner = Planner::new(m, CycleTime::new());
    let mut summary = Summary::new(m);
    let text = std::fs::read_to_string(path).unwrap();
    let mut both = Both(&mut planner, &mut summary);
    Interpreter::new(m, &Dialect::syntec(), Options::default()).run_str(&text, &mut both);
    let t = planner.into_timeline();
    (t.cutting_s + t.rapid_s + t.dwell_s, summary.cycle_time_s)
}

struct Both<'a, A, B>(&'a mut A, &'a mut B);

impl<A: Sink, B: Sink> Sink for Both<'_, A, B> {
    fn event(&mut self, e: &vcnc_core::Event) {
        self.0.event(e);
        self.1.event(e);
    }
}

/// The machine with accelerations, jerks and servo gain scaled by `k`.
fn scaled(k: f64) -> Machine {
    let mut m = Machine::default_mill();
    for a in &mut m.axes {
        a.accel_mm_s2 *= k;
        a.jerk_mm_s3 *= k * k;
    }
    m.motion.servo_gain_per_s *= k;
    m
}

#[test]
fn planned_time_is_never_below_distance_over_feed_and_converges_to_it() {
    for path in programs() {
        let (planned, estimate) = times(&path, &Machine::default_mill());
        assert!(
            planned >= estimate * (1.0 - 1e-9) - 1e-9,
            "{}: {planned} < {estimate}",
            path.display()
        );
        let mut last_gap = planned - estimate;
        for k in [10.0, 100.0, 10_000.0] {
            let (p, e) = times(&path, &scaled(k));
            assert!((e - estimate).abs() < 1e-9);
            let gap = p - e;
            assert!(
                gap >= -1e-9 && gap <= last_gap + 1e-9,
                "{}: {gap} after {last_gap}",
                path.display()
            );
            last_gap = gap;
        }
        assert!(
            last_gap <= 0.01 * estimate + 1e-3,
            "{}: {last_gap} of {estimate}",
            path.display()
        );
    }
}

/// The manual's G05 example (1.2.6): under G05 P10000 every corner keeps the
/// P10000 set's tolerance (5 µm on the built-in mill, a quarter of the
/// normal one), so the chain takes longer than without G05.
#[test]
fn the_g05_example_keeps_the_p10000_tolerance() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("tests/fixtures/manual/1.2.6_g05.nc");
    let text = std::fs::read_to_string(&path).unwrap();
    let m = Machine::default_mill();
    let tol = m.motion.high_speed_set(10_000).corner_tolerance_mm;
    assert!(tol < m.motion.corner_tolerance_mm);
    let checker = Checker {
        m: m.clone(),
        jerk: true,
        tol,
        prev: None,
        exact_lines: Vec::new(),
        smoothing_mm: 0.0,
        failures: Vec::new(),
    };
    let mut planner = Planner::new(&m, checker);
    run(&path, &m, &mut planner);
    let c = planner.into_timeline();
    assert!(c.failures.is_empty(), "{:#?}", c.failures);
    let plain: String = text
        .lines()
        .filter(|l| !l.starts_with("G05"))
        .map(|l| format!("{l}\n"))
        .collect();
    let time_of = |program: &str| {
        let mut p = Planner::new(&m, CycleTime::new());
        Interpreter::new(&m, &Dialect::syntec(), Options::default()).run_str(program, &mut p);
        p.into_timeline().cutting_s
    };
    assert!(time_of(&text) > time_of(&plain));
}

/// The manual's G05.1 examples: every corner between smoothed G01 moves has
/// the example's E as its tolerance, every other corner the machine's, and
/// no corner rounds off more than its own tolerance.
#[test]
fn the_g05_1_examples_round_corners_within_e() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for (name, e) in [
        ("1.2.7_g05_1_ex1_absolute", 0.01),
        ("1.2.7_g05_1_ex2_incremental", 0.01),
        ("1.2.7_g05_1_ex3_g43", 0.1),
        ("1.2.7_g05_1_ex4_g61", 0.05),
    ] {
        let path = root.join(format!("tests/fixtures/manual/{name}.nc"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(smoothing_e(&text), e);
        let m = Machine::default_mill();
        let checker = Checker {
            m: m.clone(),
            jerk: true,
            tol: m.motion.corner_tolerance_mm,
            prev: None,
            exact_lines: exact_stop_lines(&text),
            smoothing_mm: e,
            failures: Vec::new(),
        };
        let mut planner = Planner::new(&m, Tolerances(checker, Vec::new()));
        run(&path, &m, &mut planner);
        let Tolerances(c, tols) = planner.into_timeline();
        assert!(c.failures.is_empty(), "{name}: {:#?}", c.failures);
        // Example 1 and 2: all ten corners of the chain are smoothed.
        if e == 0.01 {
            assert_eq!(
                tols.iter().filter(|t| **t == e).count(),
                10,
                "{name}: {tols:?}"
            );
        }
        assert!(tols.contains(&e), "{name}: {tols:?}");
    }
}

/// Records each segment's corner tolerance and passes everything on.
struct Tolerances(Checker, Vec<f64>);

impl Timeline for Tolerances {
    fn segment(&mut self, seg: &Segment, p: &Profile) {
        self.1.push(seg.corner_tolerance_mm);
        self.0.segment(seg, p);
    }
    fn axes(&mut self, mv: &AxesMove) {
        self.0.axes(mv);
    }
    fn pause(&mut self, p: &Pause) {
        self.0.pause(p);
    }
}

/// The manual's NURBS example: the planned path follows the curve (every
/// move's end lies within 1 µm of it, the curve's points within 1 µm of the
/// moves) and keeps every limit.
#[test]
fn the_g06_2_example_follows_its_curve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let path = root.join("tests/fixtures/manual/1.2.8_g06_2.nc");
    let m = Machine::default_mill();
    let mut ends = Vec::new();
    {
        let mut planner = Planner::new(&m, Ends(&mut ends));
        run(&path, &m, &mut planner);
        planner.flush();
    }
    // C(u) = (5u², 10u(1−u) + 5u²): the quadratic Bézier of the example.
    let curve = |u: f64| (5.0 * u * u, 10.0 * u * (1.0 - u) + 5.0 * u * u);
    let dist_to_curve = |x: f64, y: f64| {
        (0..=20_000)
            .map(|k| {
                let (cx, cy) = curve(f64::from(k) / 20_000.0);
                (cx - x).hypot(cy - y)
            })
            .fold(f64::INFINITY, f64::min)
    };
    assert!(ends.len() > 20, "{}", ends.len());
    for (x, y) in &ends {
        assert!(dist_to_curve(*x, *y) < 1e-3, "{x} {y}");
    }
    assert_eq!(ends.last(), Some(&(5.0, 5.0)));
}

struct Ends<'a>(&'a mut Vec<(f64, f64)>);

impl Timeline for Ends<'_> {
    fn segment(&mut self, seg: &Segment, _: &Profile) {
        self.0.push((seg.path.to.get(0), seg.path.to.get(1)));
    }
    fn axes(&mut self, _: &AxesMove) {}
    fn pause(&mut self, _: &Pause) {}
}

/// One trace sample against the machine: time going forward, every axis
/// within its rapid rate and acceleration, and no farther from the
/// previous sample than the fastest axis goes in the time between.
fn check_sample(
    m: &Machine,
    s: &vcnc_planner::Sample,
    prev: Option<&vcnc_planner::Sample>,
    last_t: &mut f64,
    bad: &mut Vec<String>,
) {
    if s.t < *last_t {
        bad.push(format!("time goes back at {}", s.t));
    }
    *last_t = s.t;
    for (i, a) in m.axes.iter().enumerate() {
        if s.vel[i].abs() > a.rapid_mm_per_min / 60.0 * (1.0 + EPS) + EPS {
            bad.push(format!("t {}: axis {i} at {} mm/s", s.t, s.vel[i]));
        }
        if s.acc[i].abs() > a.accel_mm_s2 * (1.0 + EPS) + EPS {
            bad.push(format!("t {}: axis {i} at {} mm/s²", s.t, s.acc[i]));
        }
        if let Some(p) = prev {
            let step = (s.pos.get(i) - p.pos.get(i)).abs();
            let dt = s.t - p.t;
            if step > a.rapid_mm_per_min / 60.0 * dt * (1.0 + 1e-6) + 1e-9 {
                bad.push(format!("t {}: axis {i} jumps {step} mm", s.t));
            }
        }
    }
}

/// The sampled trace (1 kHz, as `vcnc run --format trace` writes it) of
/// every manual example: each sample keeps every axis within its rapid rate
/// and acceleration, consecutive samples are no farther apart than the
/// fastest axis can go in one period, and the trace ends at rest where the
/// program ends.
#[test]
fn the_sampled_traces_keep_the_limits() {
    let m = Machine::default_mill();
    for path in programs() {
        let mut bad = Vec::new();
        let mut prev: Option<vcnc_planner::Sample> = None;
        let mut last_t = -1.0;
        let sampler = vcnc_planner::Sampler::new(0.001, m.start, |s: &vcnc_planner::Sample| {
            check_sample(&m, s, prev.as_ref(), &mut last_t, &mut bad);
            prev = Some(*s);
        });
        {
            let mut planner = Planner::new(&m, sampler);
            run(&path, &m, &mut planner);
            planner.into_timeline().finish();
        }
        bad.truncate(10);
        assert!(bad.is_empty(), "{}: {bad:#?}", path.display());
        if let Some(p) = prev {
            assert_eq!(p.speed, 0.0, "{}", path.display());
        }
    }
}

/// The traces `vcnc run --format trace` writes on the built-in mill (its
/// `filter` profile: the sampled plan through a moving average of
/// T = a/j): every axis within its rapid rate and acceleration, no jump
/// larger than the fastest axis can go in one period, time going forward,
/// and the last sample at rest where the unfiltered plan ends (the jerk of
/// a filtered line: `analytic.rs`).
#[test]
fn the_filtered_traces_keep_the_limits() {
    let m = Machine::default_mill();
    assert_eq!(m.motion.profile, ProfileShape::Filter);
    let n = m.axes.len();
    let t_filter = vcnc_planner::filter_time(&m, ProfileShape::Filter);
    assert!((t_filter - 0.05).abs() < 1e-12, "{t_filter}");
    for path in programs() {
        let mut bad = Vec::new();
        let mut prev: Option<vcnc_planner::Sample> = None;
        let mut last_t = -1.0;
        let check = |s: &vcnc_planner::Sample| {
            check_sample(&m, s, prev.as_ref(), &mut last_t, &mut bad);
            prev = Some(*s);
        };
        let smoothed = vcnc_planner::Smoothed::new(t_filter, 0.001, m.start, check);
        let sampler = vcnc_planner::Sampler::new(0.001, m.start, smoothed);
        {
            let mut planner = Planner::new(&m, sampler);
            run(&path, &m, &mut planner);
            planner.into_timeline().finish();
        }
        bad.truncate(10);
        assert!(bad.is_empty(), "{}: {bad:#?}", path.display());
        // Where the unfiltered plan ends.
        let mut end = None;
        let mut plain = Planner::new(
            &m,
            vcnc_planner::Sampler::new(0.001, m.start, |s: &vcnc_planner::Sample| {
                end = Some(s.pos);
            }),
        );
        run(&path, &m, &mut plain);
        plain.into_timeline().finish();
        if let (Some(p), Some(end)) = (prev, end) {
            assert_eq!(p.speed, 0.0, "{}", path.display());
            for i in 0..n {
                assert!(
                    (p.pos.get(i) - end.get(i)).abs() < 1e-9,
                    "{}: axis {i} ends at {} not {}",
                    path.display(),
                    p.pos.get(i),
                    end.get(i)
                );
            }
        }
    }
}
