//! Property test: any sequence of motion events — lines, arcs of every
//! plane and direction (helices included), holes, tool changes, frames,
//! contours, an alarm — collects into a plot whose vertex count stays
//! within its budget, and lays out and draws as SVG, PNG and HTML without
//! a panic, in every view.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_core::{ArcDir, Cycle, Event, Feed, FrameInfo, Loc, Machine, Plane, Pos, Sink};
use vcnc_plot::{
    ColorBy, Legend, Look, Page, PlotOptions, PlotSink, Projection, Space, Theme, View,
};

fn pos() -> impl Strategy<Value = Pos> {
    (-500.0..500.0f64, -500.0..500.0f64, -100.0..100.0f64)
        .prop_map(|(x, y, z)| Pos([x, y, z, 0.0, 0.0, 0.0]))
}

fn event() -> impl Strategy<Value = Event> {
    let loc = (1u64..1000).prop_map(|line| Loc { line, file: None });
    prop_oneof![
        (loc.clone(), pos()).prop_map(|(loc, to)| Event::Rapid {
            loc,
            to,
            exact_stop: false
        }),
        (loc.clone(), pos(), 1.0..5000.0f64).prop_map(|(loc, to, f)| Event::Feed {
            loc,
            to,
            feed: Feed::PerMin(f),
            exact_stop: false
        }),
        (loc.clone(), pos(), pos(), 0..3u8, any::<bool>()).prop_map(|(loc, to, center, p, cw)| {
            Event::Arc {
                loc,
                to,
                center,
                plane: [Plane::Xy, Plane::Zx, Plane::Yz][usize::from(p)],
                dir: if cw { ArcDir::Cw } else { ArcDir::Ccw },
                feed: Feed::PerRev(0.1),
                exact_stop: false,
            }
        }),
        (loc.clone(), pos()).prop_map(|(loc, at)| Event::Hole {
            loc,
            cycle: Cycle::G81,
            at
        }),
        (loc.clone(), 0u32..40).prop_map(|(loc, tool)| Event::ToolChange { loc, tool }),
        (loc.clone(), pos()).prop_map(|(loc, origin)| Event::Frame {
            loc,
            frame: FrameInfo {
                origin,
                linear: Some([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
                tool_offset: Pos::default()
            },
        }),
        (loc, pos(), pos()).prop_map(|(loc, from, to)| Event::Contour {
            loc,
            from,
            to,
            arc: None
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn any_events_plot_within_budget_and_draw(events in prop::collection::vec(event(), 0..120), view in 0..4u8) {
        let machine = Machine::default_mill();
        let view = [View::Xy, View::Xz, View::Yz, View::Iso][usize::from(view)];
        let projection = Projection::new(view, false);
        let look = Look { theme: Theme::Dark, color: ColorBy::Feed, width_px: 400, height_px: 300 };
        let (width_px, height_px) = vcnc_plot::plot_area(400, 300);
        let flat = PlotOptions {
            space: Space::Flat { projection, width_px, height_px },
            color: ColorBy::Feed,
            max_vertices: 64,
            max_marks: 16,
        };
        let volume = PlotOptions { space: Space::Volume { resolution: 2048.0 }, ..flat };
        for options in [flat, volume] {
            let mut sink = PlotSink::new(&machine, options);
            for e in &events {
                sink.event(e);
            }
            let plot = sink.into_plot();
            prop_assert!(plot.path.vertices.len() <= 64, "{}", plot.path.vertices.len());
            prop_assert!(plot.holes.len() <= 16);
            let scene = vcnc_plot::scene(&plot, Some(&plot), &projection, &look, &Legend::default());
            let mut out = Vec::new();
            vcnc_plot::write_svg(&scene, &mut out).unwrap();
            vcnc_plot::write_png(&scene, &mut out).unwrap();
            let page = Page {
                theme: Theme::Light,
                color: ColorBy::Tool,
                lathe: false,
                legend: &Legend::default(),
                time_label: "none",
                sources: &[],
            };
            vcnc_plot::write_html(&plot, Some((&plot, "same")), &page, &mut out).unwrap();
        }
    }
}
