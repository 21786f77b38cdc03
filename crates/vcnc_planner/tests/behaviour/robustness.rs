//! The planner on arbitrary event streams (positions, feeds, arcs, modes,
//! G05 sets, G99 markers, smoothing, dwells, spindle and tool events in any
//! order): it never panics, its time is finite and never negative, the
//! split adds up, and memory stays within the look-ahead window; the
//! `filter` profile is the trapezoid plan and its run-outs.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_core::{ArcDir, Event, Feed, Loc, Machine, PathMode, Plane, Pos, Sink, SpindleDir};
use vcnc_planner::{CycleTime, Planner, ProfileShape};

fn pos() -> impl Strategy<Value = Pos> {
    (-50.0..50.0f64, -50.0..50.0f64, -20.0..20.0f64)
        .prop_map(|(x, y, z)| Pos([x, y, z, 0.0, 0.0, 0.0]))
}

fn feed() -> impl Strategy<Value = Feed> {
    prop_oneof![
        (0.0..20_000.0f64).prop_map(Feed::PerMin),
        (0.0..2.0f64).prop_map(Feed::PerRev),
    ]
}

fn event() -> impl Strategy<Value = Event> {
    let loc = (1u64..50).prop_map(|line| Loc { line, file: None });
    prop_oneof![
        4 => (loc.clone(), pos(), any::<bool>()).prop_map(|(loc, to, exact_stop)| Event::Rapid { loc, to, exact_stop }),
        8 => (loc.clone(), pos(), feed(), any::<bool>()).prop_map(|(loc, to, feed, exact_stop)| Event::Feed { loc, to, feed, exact_stop }),
        3 => (loc.clone(), pos(), pos(), any::<bool>(), feed()).prop_map(|(loc, to, center, cw, feed)| Event::Arc {
            loc, to, center, plane: Plane::Xy, dir: if cw { ArcDir::Cw } else { ArcDir::Ccw }, feed, exact_stop: false,
        }),
        1 => (loc.clone(), 0.0..3.0f64).prop_map(|(loc, seconds)| Event::Dwell { loc, seconds }),
        1 => (loc.clone(), 0u32..4).prop_map(|(loc, tool)| Event::ToolChange { loc, tool }),
        1 => (loc.clone(), 0u8..3, 0.0..5000.0f64).prop_map(|(loc, d, rpm)| Event::Spindle {
            loc, dir: [SpindleDir::Cw, SpindleDir::Ccw, SpindleDir::Stop][usize::from(d)], rpm, surface_m_per_min: None,
        }),
        1 => (loc.clone(), 0u8..4).prop_map(|(loc, m)| Event::PathMode {
            loc, mode: [PathMode::ExactStop, PathMode::Surface, PathMode::Tapping, PathMode::Cutting][usize::from(m)],
        }),
        1 => (loc.clone(), prop_oneof![Just(0u32), Just(1), Just(3), Just(10_000)]).prop_map(|(loc, p)| Event::HighSpeed { loc, on: p != 0, p }),
        1 => loc.clone().prop_map(|loc| Event::Junction { loc, blend: true }),
        1 => (loc, any::<bool>(), 0.001..0.5f64).prop_map(|(loc, on, t)| Event::Smoothing { loc, on, tolerance_mm: t }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn any_event_stream_plans_to_a_finite_time(events in prop::collection::vec(event(), 0..200), shape in 0usize..3, dogleg: bool) {
        let mut m = Machine::default_mill();
        m.params.g00_mode = u8::from(dogleg);
        let shape = [ProfileShape::Trapezoid, ProfileShape::Jerk, ProfileShape::Filter][shape];
        let mut p = Planner::with_profile(&m, shape, CycleTime::new());
        for e in &events {
            p.event(e);
        }
        let t = p.into_timeline();
        prop_assert!(t.total_s.is_finite() && t.total_s >= 0.0, "{t:?}");
        let parts = t.cutting_s + t.rapid_s + t.dwell_s + t.tool_change_s + t.spindle_s + t.in_position_s;
        prop_assert!((parts - t.total_s).abs() <= 1e-9 * t.total_s.max(1.0));
        for (_, s) in &t.per_tool {
            prop_assert!(s.is_finite() && *s >= 0.0);
        }
    }
}

/// Counts the `filter` profile's run-outs and sums everything else.
#[derive(Default)]
struct RunOuts {
    time: CycleTime,
    run_outs: u64,
}

impl vcnc_planner::Timeline for RunOuts {
    fn segment(&mut self, seg: &vcnc_planner::Segment, p: &vcnc_planner::Profile) {
        self.time.segment(seg, p);
    }
    fn axes(&mut self, mv: &vcnc_planner::AxesMove) {
        self.time.axes(mv);
    }
    fn pause(&mut self, p: &vcnc_planner::Pause) {
        if p.kind == vcnc_planner::PauseKind::Filter {
            self.run_outs += 1;
        }
        self.time.pause(p);
    }
    fn untimed(&mut self, from: Pos, to: Pos, attr: &vcnc_planner::Attr) {
        self.time.untimed(from, to, attr);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// On any event stream the `filter` profile is the trapezoid plan and
    /// T per run-out: the same moves, distances, dwells, tool changes,
    /// spindle and settling times, cutting + rapid longer by exactly T
    /// times the run-outs, and at most one run-out a move.
    #[test]
    fn the_filter_is_the_trapezoid_plan_and_its_run_outs(events in prop::collection::vec(event(), 0..200), dogleg: bool) {
        let mut m = Machine::default_mill();
        m.params.g00_mode = u8::from(dogleg);
        let t = vcnc_planner::filter_time(&m, ProfileShape::Filter);
        prop_assert!((t - 0.05).abs() < 1e-12);
        let plan = |shape| {
            let mut p = Planner::with_profile(&m, shape, RunOuts::default());
            for e in &events {
                p.event(e);
            }
            p.into_timeline()
        };
        let (trap, filt) = (plan(ProfileShape::Trapezoid), plan(ProfileShape::Filter));
        prop_assert_eq!(trap.run_outs, 0);
        let (a, b) = (&trap.time, &filt.time);
        prop_assert_eq!((a.moves, a.untimed_moves), (b.moves, b.untimed_moves));
        prop_assert_eq!((a.cutting_mm, a.rapid_mm), (b.cutting_mm, b.rapid_mm));
        prop_assert_eq!((a.dwell_s, a.tool_change_s, a.spindle_s, a.in_position_s),
            (b.dwell_s, b.tool_change_s, b.spindle_s, b.in_position_s));
        #[allow(clippy::cast_precision_loss)] // a few hundred run-outs
        let extra = t * filt.run_outs as f64;
        let moving = |c: &CycleTime| c.cutting_s + c.rapid_s;
        prop_assert!((moving(b) - moving(a) - extra).abs() <= 1e-9 * moving(b).max(1.0),
            "{} {} {}", moving(a), moving(b), extra);
        prop_assert!((b.total_s - a.total_s - extra).abs() <= 1e-9 * b.total_s.max(1.0));
        prop_assert!(filt.run_outs <= b.moves, "{} run-outs, {} moves", filt.run_outs, b.moves);
    }
}
