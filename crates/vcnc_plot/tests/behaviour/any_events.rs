//! Property test: any sequence of motion events — lines, arcs of every
//! plane and direction (helices included), NURBS curves valid or not,
//! holes, tool changes, frames, contours, an alarm — collects into a plot whose vertex count stays
//! within its budget, and lays out and draws as SVG, PNG and HTML without
//! a panic, in every view.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_core::display::DisplayUnits;
use vcnc_core::{
    ArcDir, Cycle, Event, Feed, FrameInfo, Loc, Machine, Nurbs, Plane, Pos, Sink, ToolLibrary,
    ToolShape,
};
use vcnc_plot::{
    ColorBy, FitTo, Legend, Look, Mesh, Page, PlotOptions, PlotSink, Projection, Source, Space,
    Theme, View,
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
        // Any NURBS, valid or not (knots out of order, weights ≤ 0).
        (
            loc.clone(),
            2u8..5,
            prop::collection::vec(pos(), 0..6),
            prop::collection::vec(-1.0..10.0f64, 0..12),
            prop::collection::vec(-0.5..3.0f64, 0..6),
        )
            .prop_map(|(loc, order, points, knots, weights)| Event::Nurbs {
                loc,
                curve: std::sync::Arc::new(Nurbs {
                    order,
                    knots,
                    points,
                    weights,
                }),
                feed: Feed::PerMin(300.0),
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
        let fit = if view == View::Xz { FitTo::All } else { FitTo::Cuts };
        let look = Look {
            theme: Theme::Dark,
            color: ColorBy::Feed,
            width_px: 400,
            height_px: 300,
            fit,
            rapids: view != View::Yz,
            units: if view == View::Iso { DisplayUnits::In } else { DisplayUnits::Mm },
        };
        let (width_px, height_px) = vcnc_plot::plot_area(400, 300);
        let flat = PlotOptions {
            space: Space::Flat { projection, width_px, height_px },
            color: ColorBy::Feed,
            max_vertices: 64,
            max_marks: 16,
            fit,
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
            let mut tools = ToolLibrary::default();
            tools.insert(ToolShape::assumed(3));
            let mesh = Mesh {
                name: "stock".into(),
                color: vcnc_plot::Rgb(200, 200, 200),
                visible: true,
                positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                // One good triangle and one whose indices are out of range.
                triangles: vec![[0, 1, 2], [0, 7, 9]],
            };
            let page = Page {
                theme: Theme::Light,
                color: ColorBy::Tool,
                lathe: false,
                view,
                fit,
                rapids: false,
                units: DisplayUnits::Mm,
                legend: &Legend::default(),
                time_label: "none",
                sources: &[Source::new("prog".into(), b"G1 X1\n".to_vec())],
                tools: Some(&tools),
                meshes: std::slice::from_ref(&mesh),
            };
            vcnc_plot::write_html(&plot, Some((&plot, "same")), &page, &mut out).unwrap();
        }
    }
}
