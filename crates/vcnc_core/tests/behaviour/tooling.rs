//! Tool descriptions: the tool tables of `--tools` (LinuxCNC `.tbl`, CSV)
//! and the CAM posts' header comments (`tests/fixtures/tools/`), read by
//! `vcnc_core::tooling`. Expected figures are worked out by hand from the
//! fixtures (an inch is 25.4 mm; a `.tbl` D and a CSV diameter are
//! diameters, a register holds a radius).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_core::Machine;
use vcnc_core::machine::DEFAULT_MILL_TOML;
use vcnc_core::tooling::{
    TipNumbering, ToolKind, ToolLibrary, ToolShape, ToolSource, from_comments, read_table,
};

fn fixture(name: &str) -> String {
    let path = format!(
        "{}/../../tests/fixtures/tools/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn tool(lib: &ToolLibrary, n: u32) -> &ToolShape {
    lib.get(n)
        .unwrap_or_else(|| panic!("tool {n} not described: {:?}", lib.tools.keys()))
}

fn comment_post(t: &ToolShape) -> (&'static str, u32) {
    match t.source {
        ToolSource::Comment { post, line } => (post, line),
        ref s => panic!("tool {} from {s:?}", t.number),
    }
}

// --- LinuxCNC .tbl ---------------------------------------------------------

#[test]
fn a_linuxcnc_mill_table_gives_shapes_and_offsets() {
    let lib = read_table(&fixture("mill.tbl"), "mill.tbl").unwrap();
    assert_eq!(
        lib.tools.keys().copied().collect::<Vec<_>>(),
        vec![1, 2, 7, 12]
    );
    let t1 = tool(&lib, 1);
    assert_eq!(t1.kind, ToolKind::Flat);
    assert!(close(t1.diameter_mm, 6.0));
    assert_eq!(t1.description, "6 mm flat end mill");
    assert_eq!(
        t1.source,
        ToolSource::Table {
            file: "mill.tbl".into(),
            line: 2
        }
    );
    // "ball" in the comment; D is a diameter: radius 1.5875.
    assert_eq!(tool(&lib, 2).kind, ToolKind::Ball);
    let o2 = lib.offsets[&2];
    assert!(close(o2.radius_mm.unwrap(), 1.5875) && close(o2.length_mm.unwrap(), 31.5));
    assert!(matches!(tool(&lib, 7).kind, ToolKind::Drill { .. }));
    assert_eq!(lib.offsets[&7].line, 5, "the blank line 4 counts");
    // Lower-case words read like upper-case ones.
    assert!(matches!(
        tool(&lib, 12).kind,
        ToolKind::Vee {
            included_angle_deg,
            ..
        } if close(included_angle_deg, 90.0)
    ));
}

#[test]
fn a_table_fills_h_and_d_of_the_same_number_and_nothing_else() {
    let lib = read_table(&fixture("mill.tbl"), "mill.tbl").unwrap();
    let mut m = Machine::from_toml(DEFAULT_MILL_TOML).unwrap();
    m.tools.entry(1).or_default().d_wear_mm = -0.02;
    m.tools.entry(40).or_default().d_mm = 8.0;
    lib.fill_registers(&mut m, TipNumbering::Fanuc);
    let r1 = m.tools[&1];
    assert!(close(r1.h_mm, 25.0) && close(r1.d_mm, 3.0));
    assert!(close(r1.d_wear_mm, -0.02), "the machine file's wear stays");
    assert!(close(m.tools[&7].h_mm, -2.5) && close(m.tools[&7].d_mm, 5.0));
    assert!(
        close(m.tools[&40].d_mm, 8.0),
        "a register the table does not list stays"
    );
}

#[test]
fn a_lathe_table_gives_nose_radius_offsets_and_orientation() {
    let lib = read_table(&fixture("lathe.tbl"), "lathe.tbl").unwrap();
    // Q2 (LinuxCNC) is Fanuc's tip 3, Q3 Fanuc's 2: the shapes use Fanuc's.
    assert_eq!(
        tool(&lib, 1).kind,
        ToolKind::Turning {
            nose_radius_mm: 0.4,
            tip: 3
        }
    );
    assert_eq!(
        tool(&lib, 6).kind,
        ToolKind::Turning {
            nose_radius_mm: 0.4,
            tip: 2
        }
    );
    let mut fanuc = Machine::from_toml(vcnc_core::machine::DEFAULT_FANUC_LATHE_TOML).unwrap();
    lib.fill_registers(&mut fanuc, TipNumbering::Fanuc);
    let r = fanuc.tools[&1];
    assert!(close(r.x_mm, -1.5) && close(r.z_mm, 2.25) && close(r.nose_radius_mm, 0.4));
    assert_eq!((r.tip, fanuc.tools[&6].tip), (3, 2));
    let mut lcnc = Machine::from_toml(vcnc_core::machine::DEFAULT_FANUC_LATHE_TOML).unwrap();
    lib.fill_registers(&mut lcnc, TipNumbering::LinuxCnc);
    assert_eq!((lcnc.tools[&1].tip, lcnc.tools[&6].tip), (2, 3));
}

// --- CSV -------------------------------------------------------------------

#[test]
fn a_csv_table_gives_sizes_shapes_and_registers_in_its_units() {
    let lib = read_table(&fixture("tools.csv"), "tools.csv").unwrap();
    let t1 = tool(&lib, 1);
    assert_eq!(t1.kind, ToolKind::Flat);
    assert_eq!(
        (t1.length_mm, t1.flute_length_mm, t1.holder_diameter_mm),
        (Some(40.0), Some(20.0), Some(25.0))
    );
    // Row 2 in inches: 0.25 in = 6.35 mm, corner 0.125 in = half: a ball.
    let t2 = tool(&lib, 2);
    assert_eq!(t2.kind, ToolKind::Ball);
    assert!(close(t2.diameter_mm, 6.35));
    assert!(close(t2.length_mm.unwrap(), 38.1));
    assert_eq!(t2.holder_diameter_mm, None, "an empty cell is not known");
    assert_eq!(
        tool(&lib, 3).kind,
        ToolKind::Bull {
            corner_radius_mm: 1.0
        }
    );
    let mut m = Machine::from_toml(DEFAULT_MILL_TOML).unwrap();
    lib.fill_registers(&mut m, TipNumbering::Fanuc);
    assert!(close(m.tools[&2].d_mm, 3.175) && close(m.tools[&2].h_mm, 38.1));
    assert!(close(m.tools[&3].d_mm, 5.0) && close(m.tools[&3].h_mm, 0.0));
}

#[test]
fn csv_columns_come_in_any_order_and_units_is_optional() {
    let lib = read_table("diameter,tool\n8,4\n", "t.csv").unwrap();
    assert!(close(tool(&lib, 4).diameter_mm, 8.0));
}

#[test]
fn csv_shank_and_stickout_columns_give_the_holder_its_place() {
    let lib = read_table(
        "tool,diameter,flute_length,shank_diameter,holder_diameter,stickout,units\n\
         1,10,5,8,30,25,mm\n2,0.25,1,,1.5,,in\n",
        "t.csv",
    )
    .unwrap();
    let t1 = tool(&lib, 1);
    assert_eq!(
        (t1.shank_diameter_mm, t1.holder_diameter_mm, t1.stickout_mm),
        (Some(8.0), Some(30.0), Some(25.0))
    );
    let t2 = tool(&lib, 2);
    assert!(close(t2.holder_diameter_mm.unwrap(), 38.1));
    assert_eq!((t2.shank_diameter_mm, t2.stickout_mm), (None, None));
}

// --- malformed tables: file, line, what --------------------------------------

#[test]
fn a_malformed_table_is_a_located_error() {
    let cases: &[(&str, u32, &str)] = &[
        ("T1 P1 D6\nT2 P2 Dsix\n", 2, "`Dsix`"),
        (
            "T1 P1 D6\nT1 P2 D3\n",
            2,
            "tool 1 is listed twice (first on line 1)",
        ),
        ("P1 D6\n", 1, "no T word"),
        ("T0 D6\n", 1, "whole number from 1"),
        ("T1 D-6\n", 1, "not negative"),
        ("T1 D1e400\n", 1, "`D1e400`"),
        ("T1 DNaN\n", 1, "`DNaN`"),
        ("T1 Q12 D1\n", 1, "0 to 9"),
        ("T1 K5\n", 1, "not a tool table word"),
        ("; nothing\n\n", 0, "no tool"),
        (
            "tool,diameter\n1,6\n2\n",
            3,
            "1 cells where the header names 2",
        ),
        ("tool,diameter,colour\n", 1, "unknown column `colour`"),
        ("tool,length\n1,5\n", 1, "no `diameter` column"),
        ("tool,diameter,units\n1,6,ft\n", 2, "units `ft`"),
        (
            "tool,diameter,corner_radius\n1,6,4\n",
            2,
            "more than half the diameter",
        ),
        ("tool,diameter\n1,-2\n", 2, "not a length"),
        ("tool,diameter,tool\n", 1, "named twice"),
    ];
    for (text, line, needle) in cases {
        let e = read_table(text, "bad.tbl").expect_err(text);
        assert_eq!(e.file, "bad.tbl");
        assert_eq!(e.line, *line, "{text:?}: {e}");
        assert!(e.message.contains(needle), "{text:?}: {e}");
        assert!(!e.help.is_empty());
    }
}

// --- CAM comments ------------------------------------------------------------

#[test]
fn fusion_tool_lists_in_the_program_units() {
    // A public Fusion program of the corpus (mm).
    let corpus = std::fs::read_to_string(format!(
        "{}/../../corpus/mill-fanuc/jobline-issue-3-fusion-g18.nc",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let lib = from_comments(&corpus);
    let t1 = tool(&lib, 1);
    assert_eq!(
        (t1.kind, t1.description.as_str()),
        (ToolKind::Flat, "flat end mill")
    );
    assert!(close(t1.diameter_mm, 6.0));
    assert_eq!(comment_post(t1), ("fusion", 4));
    assert!(lib.offsets.is_empty(), "comments never give offsets");

    let lib = from_comments(&fixture("fusion_inch.nc"));
    assert!(close(tool(&lib, 1).diameter_mm, 50.8));
    assert!(close(tool(&lib, 2).diameter_mm, 9.525));
    assert_eq!(tool(&lib, 3).kind, ToolKind::Ball);
    assert!(matches!(
        tool(&lib, 4).kind,
        ToolKind::Bull { corner_radius_mm } if close(corner_radius_mm, 0.762)
    ));
    // TAPER is half the included angle.
    assert!(matches!(
        tool(&lib, 5).kind,
        ToolKind::Vee { included_angle_deg, .. } if close(included_angle_deg, 90.0)
    ));
    assert!(matches!(tool(&lib, 6).kind, ToolKind::Drill { .. }));
}

#[test]
fn mastercam_tool_lists_both_styles() {
    let lib = from_comments(&fixture("mastercam.nc"));
    let t1 = tool(&lib, 1);
    assert!(matches!(t1.kind, ToolKind::Vee { .. }), "{t1:?}");
    assert!(close(t1.diameter_mm, 6.35));
    assert_eq!(comment_post(t1), ("mastercam", 5));
    let t2 = tool(&lib, 2);
    assert_eq!(
        (t2.kind, t2.description.as_str()),
        (ToolKind::Flat, "1/2 FLAT ENDMILL")
    );
    assert!(close(t2.diameter_mm, 12.7));
    // "DIA. OFF. - 5" is a register; the last "DIA. -" is the size.
    assert!(close(tool(&lib, 5).diameter_mm, 1.5875));
    assert!(close(tool(&lib, 6).diameter_mm, 50.8));
    assert_eq!(lib.tools.len(), 4);
}

#[test]
fn solidcam_vectric_estlcam_and_carbide_create() {
    let lib = from_comments(&fixture("solidcam.nc"));
    assert!(close(tool(&lib, 1).diameter_mm, 10.0) && close(tool(&lib, 2).diameter_mm, 6.0));
    assert_eq!(comment_post(tool(&lib, 2)), ("solidcam", 4));

    let lib = from_comments(&fixture("vectric.nc"));
    assert!(close(tool(&lib, 1).diameter_mm, 6.0));
    assert_eq!(
        tool(&lib, 2).kind,
        ToolKind::Vee {
            included_angle_deg: 60.0,
            tip_diameter_mm: 0.0
        }
    );
    assert!(
        close(tool(&lib, 5).diameter_mm, 6.35),
        "{{0.2500 inch}} in a mm program"
    );
    assert_eq!(comment_post(tool(&lib, 5)), ("vectric", 11));
    assert_eq!(lib.tools.len(), 3, "the toolpath list is not a tool list");

    let lib = from_comments(&fixture("estlcam.nc"));
    assert!(close(tool(&lib, 1).diameter_mm, 3.0));
    assert_eq!(tool(&lib, 2).kind, ToolKind::Ball);
    assert_eq!(comment_post(tool(&lib, 2)), ("estlcam", 16));
    // No T word: the one required tool is the tool in the spindle, 0.
    let lib = from_comments(&fixture("estlcam_one_tool.nc"));
    assert_eq!(lib.tools.keys().copied().collect::<Vec<_>>(), vec![0]);
    assert!(close(tool(&lib, 0).diameter_mm, 3.0));

    let lib = from_comments(&fixture("carbide_create.nc"));
    let t102 = tool(&lib, 102);
    assert_eq!(t102.kind, ToolKind::Flat);
    assert!(close(t102.diameter_mm, 3.17));
    assert_eq!(t102.flute_length_mm, Some(12.7));
    assert_eq!(comment_post(t102), ("cutviewer", 11));
    // A 90° V bit with a 0.03 mm tip, 10 mm tall: 0.03 + 2·10·tan 45° across.
    let t390 = tool(&lib, 390);
    assert_eq!(
        t390.kind,
        ToolKind::Vee {
            included_angle_deg: 90.0,
            tip_diameter_mm: 0.03
        }
    );
    assert!(close(t390.diameter_mm, 20.03));
}

#[test]
fn a_cutviewer_line_waits_for_the_tool_change_past_other_code() {
    // Regression: any line of code after `TOOL/MILL` used to drop it, so
    // a header that sets G21 before `M6T1` described no tool.
    let text = "(TOOL/MILL,10.00, 0.00, 5.00, 0.00)\nG21 G90 G17\nG28 G91 Z0\nM06 T1\nM30\n";
    let lib = from_comments(text);
    let t1 = tool(&lib, 1);
    assert!(close(t1.diameter_mm, 10.0));
    assert_eq!(t1.flute_length_mm, Some(5.0));
    assert_eq!(comment_post(t1), ("cutviewer", 1));
}

#[test]
fn comments_that_describe_no_tool_give_none() {
    let text = "(T1 is for facing)\n(TOOL CHANGE)\n(D=5)\n(X = 5)\nG0 X1 (T2 D=x)\nM30\n";
    assert!(from_comments(text).is_empty());
}
