//! G12/G13 circular pockets: Haas's (I, K, Q, D, L, Z; in and out along
//! half circles) and Mach3's (I only; straight out and back). The expected
//! moves are worked out by hand from the manuals' descriptions
//! (docs/dialects.md, "The haas dialect" and "The mach3 dialect"): the
//! tool centre runs at the radius less D's radius, tangent half circles of
//! half that radius lead in from and out to the centre.

use crate::common::{Store, alarm_of, mill_with_tools, run, run_on};
use vcnc_interp::{ArcDir, Event, Feed};
use vcnc_syntax::Code;

/// The motion events of line `line` as short text: `feed x y z @f`,
/// `cw x y z c cx cy`, `rapid x y z` (program = machine here: no offsets).
fn moves(events: &[Event], line: u64) -> Vec<String> {
    let r = |v: f64| {
        let v = (v * 1000.0).round() / 1000.0;
        if v == 0.0 { 0.0 } else { v }
    };
    events
        .iter()
        .filter(|e| e.loc().is_some_and(|l| l.line == line))
        .filter_map(|e| match e {
            Event::Rapid { to, .. } => Some(format!(
                "rapid {} {} {}",
                r(to.get(0)),
                r(to.get(1)),
                r(to.get(2))
            )),
            Event::Feed { to, feed, .. } => {
                let Feed::PerMin(f) = feed else { return None };
                Some(format!(
                    "feed {} {} {} @{}",
                    r(to.get(0)),
                    r(to.get(1)),
                    r(to.get(2)),
                    r(*f)
                ))
            }
            Event::Arc {
                to, center, dir, ..
            } => Some(format!(
                "{} {} {} {} c {} {}",
                if *dir == ArcDir::Cw { "cw" } else { "ccw" },
                r(to.get(0)),
                r(to.get(1)),
                r(to.get(2)),
                r(center.get(0)),
                r(center.get(1))
            )),
            _ => None,
        })
        .collect()
}

const HAAS_START: &str = "G21 G90 G17 G40\nT1 M06\nS1000 M03\n";

#[test]
fn haas_g12_with_i_only_cuts_one_circle_less_the_cutter_radius() {
    // The manual's "G12 I1.5 F10. Z-1.2 D01 (finish pocket clockwise)" in
    // mm: D1 is 5 mm, so the tool centre runs on a 10 mm circle about
    // X10 Y20 (where the block puts it), at Z-4 reached at the centre.
    let program = format!("{HAAS_START}G00 Z5.\nG12 X10. Y20. I15. F300. Z-4. D01\nG00 Z5.\nM30\n");
    let r = run_on(&mill_with_tools(), "haas", &program, Store::default(), &[]);
    crate::common::ended(&r);
    assert_eq!(
        moves(&r.events, 5),
        [
            "rapid 10 20 5",
            "feed 10 20 -4 @300",
            // Lead-in: half circle of diameter 10 from the centre, clockwise
            // (over +Y), tangent to the circle at X20.
            "cw 20 20 -4 c 15 20",
            "cw 20 20 -4 c 10 20",
            // Lead-out: the other half circle, back to the centre.
            "cw 10 20 -4 c 15 20",
        ]
    );
    // G12 is one-shot: the next block rapids up from the centre.
    assert_eq!(moves(&r.events, 6), ["rapid 10 20 5"]);
}

#[test]
fn under_g51_the_circle_is_scaled_and_the_cutter_radius_is_not() {
    // G51 P2 about the origin doubles the programmed 8 mm circle to 16 mm;
    // the tool (D1 = 5 mm) runs inside it on 11 mm, as a G42 contour of the
    // same circle would: the offset is the machine's, not scaled (Haas's
    // G51: cutter compensation values are not affected). Program
    // coordinates carry the scale: the circle reached is X5.5 (11 / 2).
    let program =
        format!("{HAAS_START}G00 X0. Y0. Z5.\nG51 X0. Y0. P2.\nG12 I8. Z-2. F500. D01\nG50\nM30\n");
    let r = run_on(&mill_with_tools(), "haas", &program, Store::default(), &[]);
    crate::common::ended(&r);
    let far = r
        .events
        .iter()
        .filter(|e| e.loc().is_some_and(|l| l.line == 6))
        .filter_map(|e| match e {
            vcnc_interp::Event::Arc { to, .. } => Some(to.get(0).hypot(to.get(1))),
            _ => None,
        })
        .fold(0.0_f64, f64::max);
    assert!((far - 11.0).abs() < 1e-9, "tool centre reaches {far}");
}

#[test]
fn haas_g13_with_k_and_q_steps_out_and_g91_l_goes_deeper_each_time() {
    // "G91 … L: multiple Z depth pass" — radii 8, 13, 18 and the finish 20,
    // less D1's 5 mm: 3, 8, 13, 15; twice, 2 mm deeper each time.
    let program = format!(
        "{HAAS_START}G00 X0. Y0. Z1.\nG01 Z0. F100.\nG91 G13 I8. K20. Q5. Z-2. L2 D01 F200.\nG90 G00 Z5.\nM30\n"
    );
    let r = run_on(&mill_with_tools(), "haas", &program, Store::default(), &[]);
    crate::common::ended(&r);
    let pass = |z: &str| {
        vec![
            format!("feed 0 0 {z} @200"),
            format!("ccw 3 0 {z} c 1.5 0"),
            format!("ccw 3 0 {z} c 0 0"),
            format!("feed 8 0 {z} @200"),
            format!("ccw 8 0 {z} c 0 0"),
            format!("feed 13 0 {z} @200"),
            format!("ccw 13 0 {z} c 0 0"),
            format!("feed 15 0 {z} @200"),
            format!("ccw 15 0 {z} c 0 0"),
            format!("ccw 0 0 {z} c 7.5 0"),
        ]
    };
    let mut expected = pass("-2");
    expected.extend(pass("-4"));
    assert_eq!(moves(&r.events, 6), expected);
}

#[test]
fn haas_d0_programs_the_tool_centre_and_d_is_remembered() {
    // D00: no compensation, I is the tool centre's radius. A later G12
    // without D uses the last D given, even after G40 (Haas manual).
    let program =
        format!("{HAAS_START}G00 X0. Y0. Z0.\nG12 I6. F100. D00\nD01\nG40\nG12 I6.\nM30\n");
    let r = run_on(&mill_with_tools(), "haas", &program, Store::default(), &[]);
    crate::common::ended(&r);
    assert_eq!(
        moves(&r.events, 5),
        ["cw 6 0 0 c 3 0", "cw 6 0 0 c 0 0", "cw 0 0 0 c 3 0"]
    );
    assert_eq!(
        moves(&r.events, 8),
        ["cw 1 0 0 c 0.5 0", "cw 1 0 0 c 0 0", "cw 0 0 0 c 0.5 0"]
    );
}

#[test]
fn mach3_g12_goes_straight_out_along_x_round_and_back() {
    // "The tool is moved in the X direction by the value of the I word and
    // a circle is cut … with the original X and Y coordinates as the
    // centre. The tool is returned to the centre."
    let program = "G21 G90 G17\nG0 X10 Y10 Z-1\nF100\nG13 I-4\nG12 I2.5\nM30\n";
    let r = run("mach3", program, Store::default(), &[]);
    crate::common::ended(&r);
    assert_eq!(
        moves(&r.events, 4),
        [
            "feed 6 10 -1 @100",
            "ccw 6 10 -1 c 10 10",
            "feed 10 10 -1 @100"
        ]
    );
    assert_eq!(
        moves(&r.events, 5),
        [
            "feed 12.5 10 -1 @100",
            "cw 12.5 10 -1 c 10 10",
            "feed 10 10 -1 @100"
        ]
    );
}

#[test]
fn bad_circular_pockets_alarm_where_the_mistake_is_and_move_nothing() {
    let tools = mill_with_tools();
    let haas = |body: &str| {
        let program = format!("{HAAS_START}G00 X0. Y0. Z1.\n{body}\nM30\n");
        alarm_of(&run_on(&tools, "haas", &program, Store::default(), &[]))
    };
    // No I.
    assert_eq!(haas("G12 F100. Z-1. D01"), (Code::E312, 5, 1));
    // K not beyond I.
    assert_eq!(haas("G12 I10. K8. Q1. F100. D01"), (Code::E109, 5, 10));
    // Q without K, K without Q.
    assert_eq!(haas("G13 I10. Q1. F100. D01"), (Code::E312, 5, 10));
    assert_eq!(haas("G13 I10. K12. F100. D01"), (Code::E312, 5, 1));
    // Q not positive, I not positive.
    assert_eq!(haas("G12 I10. K12. Q0 F100. D01"), (Code::E109, 5, 15));
    assert_eq!(haas("G12 I-10. F100. D00"), (Code::E109, 5, 5));
    // A radius the 5 mm cutter cannot cut.
    assert_eq!(haas("G12 I5. F100. D01"), (Code::E325, 5, 5));
    // No register D201 on the built-in machine (200 registers).
    assert_eq!(haas("G12 I10. F100. D201"), (Code::E503, 5, 16));
    // L0, and a plane other than XY.
    assert_eq!(haas("G12 I10. F100. D01 L0"), (Code::E109, 5, 20));
    assert_eq!(haas("G18 G12 I10. F100. D01"), (Code::E210, 5, 5));
    // J is no word of G12.
    assert_eq!(haas("G12 I10. J2. F100. D01").0, Code::E203);
    // Too many circles: 0.001 mm steps over 50 mm.
    assert_eq!(haas("G12 I10. K60. Q0.001 F100. D01"), (Code::E326, 5, 1));
    // Mach3: I only, no axis words, no feed.
    let mach3 = |body: &str| {
        let program = format!("G21 G90 G17\nG0 X10 Y10\n{body}\nM30\n");
        alarm_of(&run("mach3", &program, Store::default(), &[]))
    };
    assert_eq!(mach3("G12 F100"), (Code::E312, 3, 1));
    assert_eq!(mach3("G12 I0 F100"), (Code::E109, 3, 5));
    assert_eq!(mach3("G12 I2 X1 F100"), (Code::E203, 3, 8));
    assert_eq!(mach3("G12 I2").0, Code::E301);
}

#[test]
fn a_haas_radius_without_a_point_among_points_warns_w101() {
    // Haas reads I15 in the least increment (0.015 mm), as X15 would be.
    let program = format!("{HAAS_START}G00 X1. Y1. Z0.\nG12 I15 F100. D00\nM30\n");
    let r = run_on(&mill_with_tools(), "haas", &program, Store::default(), &[]);
    crate::common::ended(&r);
    let w: Vec<_> = r
        .events
        .iter()
        .filter_map(|e| match e {
            Event::Warning(d) => Some((d.code, d.line, d.column)),
            _ => None,
        })
        .collect();
    assert_eq!(w, [(Code::W101, 5, 5)]);
    assert_eq!(moves(&r.events, 5)[1], "cw 1.015 1 0 c 1 1");
}
