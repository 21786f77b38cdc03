//! grbl's `$$` settings dump read as a machine (`--machine dump.txt`):
//! the settings grbl 1.1 ships with (its `defaults.h`, as `$$` prints
//! them), a router with soft limits on, a grblHAL dump with a fourth axis.
//! Every expected value is the dump's own number, placed by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_core::grbl_settings::{machine, machine_toml};
use vcnc_core::motion::Profile;

fn fixture(name: &str) -> String {
    let path = format!(
        "{}/../../tests/fixtures/machines/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn grbl_defaults_give_rates_accelerations_and_no_limits() {
    let m = machine(&fixture("grbl_defaults.txt"), "grbl_defaults.txt").unwrap();
    assert_eq!(m.name, "grbl machine from grbl_defaults.txt");
    assert_eq!(m.axes.len(), 3);
    for a in &m.axes {
        assert_eq!(a.rapid_mm_per_min, 500.0);
        assert_eq!(a.max_feed_mm_per_min, 500.0);
        assert_eq!(a.accel_mm_s2, 10.0);
        // $20=0: grbl checks no soft limits, so neither does the model.
        assert!(a.min_mm.is_infinite() && a.max_mm.is_infinite());
    }
    assert_eq!(m.motion.profile, Profile::Trapezoid);
    assert_eq!(m.motion.corner_tolerance_mm, 0.010);
    assert_eq!(m.params.max_spindle_rpm, 1000.0);
    assert!(m.tools.is_empty());
}

#[test]
fn soft_limits_make_the_negative_machine_space() {
    let m = machine(&fixture("grbl_soft_limits.txt"), "router.txt").unwrap();
    let travel: Vec<(f64, f64, f64, f64)> = m
        .axes
        .iter()
        .map(|a| (a.min_mm, a.max_mm, a.rapid_mm_per_min, a.accel_mm_s2))
        .collect();
    assert_eq!(
        travel,
        vec![
            (-838.0, 0.0, 5000.0, 400.0),
            (-838.0, 0.0, 5000.0, 400.0),
            (-75.0, 0.0, 1000.0, 50.0),
        ]
    );
    assert_eq!(m.start.get(0), 0.0, "power-on at 0, inside the travel");
    assert_eq!(m.params.max_spindle_rpm, 24000.0);
}

#[test]
fn grblhal_fourth_axis_is_a_without_travel() {
    let m = machine(&fixture("grblhal_4axis.txt"), "hal.txt").unwrap();
    let letters: Vec<u8> = m.axes.iter().map(|a| a.letter).collect();
    assert_eq!(letters, b"XYZA".to_vec());
    let a = &m.axes[3];
    assert_eq!((a.rapid_mm_per_min, a.accel_mm_s2), (7200.0, 300.0));
    assert!(a.min_mm.is_infinite(), "$133=0: no travel limit");
    assert_eq!((m.axes[1].min_mm, m.axes[1].max_mm), (-200.0, 0.0));
}

#[test]
fn the_printed_machine_file_reads_back_to_the_same_machine() {
    for f in [
        "grbl_defaults.txt",
        "grbl_soft_limits.txt",
        "grblhal_4axis.txt",
    ] {
        let toml = machine_toml(&fixture(f), f).unwrap();
        let direct = machine(&fixture(f), f).unwrap();
        assert_eq!(vcnc_core::Machine::from_toml(&toml).unwrap(), direct, "{f}");
        assert!(toml.contains("# $110 max rate"), "{toml}");
    }
}

#[test]
fn a_malformed_dump_is_a_located_error() {
    let base = fixture("grbl_defaults.txt");
    let cases: Vec<(String, u32, &str)> = vec![
        (
            base.replace("$110=500.000", "$110=fast"),
            27,
            "$110 = `fast` is not a number",
        ),
        (
            base.replace("$111=500.000", "$110=400"),
            28,
            "$110 is set twice (first on line 27)",
        ),
        (
            base.replace("$120=10.000", "$120=-10"),
            30,
            "$120 (acceleration",
        ),
        (
            base.replace("$121=10.000", "$121=1e400"),
            31,
            "not a number",
        ),
        (
            base.replace("$0=10", "G0 X10"),
            2,
            "`G0 X10` is not a setting",
        ),
        (
            base.replace("$1=25", "$x=25"),
            3,
            "`$x` is not a setting number",
        ),
        (base.replace("$112=500.000\n", ""), 0, "no $112 for axis Z"),
        ("$0=10\n".to_string(), 0, "no $110 for axis X"),
    ];
    for (text, line, needle) in cases {
        let e = machine(&text, "dump.txt").expect_err(needle);
        assert_eq!((e.file.as_str(), e.line), ("dump.txt", line), "{e}");
        assert!(e.message.contains(needle), "{e}");
    }
}
