//! `vcnc sim` and `check --stock` from the command line: the report's
//! text and JSON fields, collisions at their line and column, exit codes,
//! the output files, stocks from header comments, and bad stocks as
//! usage errors. The volumes and collisions themselves are tested against
//! closed forms in `crates/vcnc_sim/tests`; here the expected numbers are
//! the same hand-worked ones (a 50 × 10 × 2 slot with round ends).

use crate::common::vcnc;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh directory with `program` written as `name`.
fn program(name: &str, text: &str) -> (PathBuf, String) {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("vcnc-sim-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let s = path.to_str().unwrap().to_string();
    (dir, s)
}

fn out(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn err(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

/// D1 = 5: tool 1 is a 10 mm flat end mill from its register.
const MACHINE: &str = "name = \"test mill\"\n\
    table_z_mm = -50.0\n\
    [[axes]]\nletter = \"x\"\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
    [[axes]]\nletter = \"y\"\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
    [[axes]]\nletter = \"z\"\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
    [tools.1]\nd_mm = 5.0\n";

const SLOT: &str = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\nG01 Z-2. F300\nG01 X50.\nG00 Z5.\nM30\n";

/// `vcnc CMD FILE --dialect fanuc --machine M --stock STOCK EXTRA…`.
fn on_mill(cmd: &str, file: &str, m: &str, stock: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        cmd,
        file,
        "--dialect",
        "fanuc",
        "--machine",
        m,
        "--stock",
        stock,
    ];
    args.extend_from_slice(extra);
    vcnc(&args)
}

fn machine(dir: &Path) -> String {
    let p = dir.join("machine.toml");
    std::fs::write(&p, MACHINE).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn sim_reports_the_slot_as_json() {
    let (dir, file) = program("slot.nc", SLOT);
    let m = machine(&dir);
    let o = on_mill(
        "sim",
        &file,
        &m,
        "box:-20,-20,-10,70,20,0",
        &["--format", "json"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let v: Value = serde_json::from_str(&out(&o)).unwrap();
    let want = 50.0 * 10.0 * 2.0 + std::f64::consts::PI * 25.0 * 2.0;
    let removed = v["removed_mm3"].as_f64().unwrap();
    assert!((removed - want).abs() < 0.01 * want, "{removed} vs {want}");
    assert_eq!(v["stock_mm3"].as_f64(), Some(90.0 * 40.0 * 10.0));
    assert_eq!(v["resolution_mm"].as_f64(), Some(0.1));
    assert_eq!(v["collisions"], serde_json::json!([]));
    // Cutting 50 + 7 mm at 300 mm/min: 11.4 s, the plunge's 5 mm of air
    // above the stock included in the plunge (which cuts).
    assert!(v["air_cut_s"].as_f64().unwrap() < 1e-9);
}

#[test]
fn a_rapid_into_the_stock_is_reported_at_its_line_and_column() {
    let text = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\n   G00 Z-2.\nG00 Z5.\nM30\n";
    let (dir, file) = program("crash.nc", text);
    let m = machine(&dir);
    let args = [
        "sim",
        &file,
        "--dialect",
        "fanuc",
        "--machine",
        &m,
        "--stock",
        "box:-20,-20,-10,70,20,0",
    ];
    let o = vcnc(&args);
    assert_eq!(o.status.code(), Some(1), "a collision fails the run");
    let text = out(&o);
    assert!(
        text.contains(&format!(
            "{file}:4:4: rapid_into_stock: a rapid cuts 2.000 mm into the stock"
        )),
        "{text}"
    );
    assert!(text.contains("collisions 1"), "{text}");
    let mut json_args = args.to_vec();
    json_args.extend(["--format", "json"]);
    let v: Value = serde_json::from_str(&out(&vcnc(&json_args))).unwrap();
    let c = &v["collisions"][0];
    assert_eq!(
        (c["line"].as_u64(), c["column"].as_u64()),
        (Some(4), Some(4))
    );
    assert_eq!(c["kind"], "rapid_into_stock");
    assert!(c["message"].as_str().unwrap().contains("2.000 mm"));
}

#[test]
fn check_with_a_stock_adds_the_simulation_line() {
    let (dir, file) = program("slot.nc", SLOT);
    let m = machine(&dir);
    let o = on_mill("check", &file, &m, "box:-20,-20,-10,70,20,0", &[]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let text = out(&o);
    let line = text
        .lines()
        .find(|l| l.starts_with("sim "))
        .expect("a sim line");
    assert!(
        line.contains("mm³ of 36000.000 mm³, 0 collisions"),
        "{line}"
    );
    // Through the bottom: the collision fails the check.
    let deep = SLOT.replace("Z-2.", "Z-12.");
    let (_, file) = program("deep.nc", &deep);
    let o = on_mill("check", &file, &m, "box:-20,-20,-10,70,20,0", &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(out(&o).contains(":4:1: below_stock"), "{}", out(&o));
}

#[test]
fn the_table_in_the_machine_file_is_a_fixture() {
    let text = "G21 G90 G17\nT1 M06\nG00 X100. Y100. Z5.\nG01 Z-55. F300\nG00 Z5.\nM30\n";
    let (dir, file) = program("table.nc", text);
    let m = machine(&dir);
    let o = on_mill("sim", &file, &m, "box:0,0,-10,50,50,0", &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        out(&o).contains(":4:1: fixture: the tool reaches the machine table"),
        "{}",
        out(&o)
    );
}

#[test]
fn bad_stocks_and_resolutions_are_usage_errors() {
    let (dir, file) = program("slot.nc", SLOT);
    let m = machine(&dir);
    for (stock, res, says) in [
        ("box:0,0,0,10,10,0", "0.1", "inverted in Z"),
        ("box:0,0,-1,10", "0.1", "six numbers"),
        ("bar:20,10", "0.1", "a mill cuts a block"),
        ("box:0,0,-1,1000,1000,0", "0.001", "more than the bound"),
        ("box:0,0,-1,10,10,0", "-1", "more than 0"),
    ] {
        let res = format!("--resolution={res}");
        let o = on_mill("sim", &file, &m, stock, &[&res]);
        assert_eq!(o.status.code(), Some(2), "{stock}: {}", err(&o));
        assert!(err(&o).contains(says), "{stock}: {}", err(&o));
        assert!(out(&o).is_empty());
    }
}

#[test]
fn a_header_comment_gives_the_stock_and_no_cuts_remove_nothing() {
    let text = "(stockMin:0.00mm, 0.00mm, -5.00mm)\n(stockMax:40.00mm, 30.00mm, 0.00mm)\nG21 G90\nG00 X10. Y10. Z5.\nM30\n";
    let (_, file) = program("header.nc", text);
    let o = vcnc(&["sim", &file, "--dialect", "fanuc"]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let t = out(&o);
    assert!(
        t.contains("stock      box X 0 .. 40  Y 0 .. 30  Z -5 .. 0 (work mm; Carbide Create header comment, line 1)"),
        "{t}"
    );
    assert!(t.contains("removed    0.000 mm³ of 6000.000 mm³"), "{t}");
}

#[test]
fn outputs_are_written_in_their_formats() {
    let (dir, file) = program("slot.nc", SLOT);
    let m = machine(&dir);
    let (stl, png, html) = (dir.join("p.stl"), dir.join("p.png"), dir.join("p.html"));
    let o = on_mill(
        "sim",
        &file,
        &m,
        "box:-20,-20,-10,70,20,0",
        &[
            "-o",
            stl.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
            "-o",
            html.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let stl = std::fs::read(&stl).unwrap();
    let n = u32::from_le_bytes(stl[80..84].try_into().unwrap()) as usize;
    assert_eq!(stl.len(), 84 + 50 * n);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(page.contains("<script id=\"sim-data\" type=\"application/json\">{\"title\":"));
    assert!(page.contains("\"kind\":\"mill\""));
    let o = vcnc(&["sim", &file, "-o", "part.obj"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(err(&o).contains("name the output .stl, .png or .html"));
}

#[test]
fn a_lathe_example_turns_its_bar() {
    let o = vcnc(&[
        "sim",
        "--dialect",
        "fanuc-lathe",
        "--machine",
        "examples/fanuc-lathe/turret.toml",
        "examples/fanuc-lathe/01_od_rough_finish.nc",
        "--stock",
        "bar:62,60",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", err(&o));
    let v: Value = serde_json::from_str(&out(&o)).unwrap();
    // The profile stays inside Ø62 from Z0 to Z−50: something is turned
    // off, less than the bar.
    let (removed, stock) = (
        v["removed_mm3"].as_f64().unwrap(),
        v["stock_mm3"].as_f64().unwrap(),
    );
    assert!(removed > 0.0 && removed < stock, "{removed} of {stock}");
    assert_eq!(v["resolution_mm"], Value::Null);
}

/// A slot 2 mm deep, then a second pass along it 8 mm deep, its plunge
/// indented to column 4: a tool with 5 mm of flutes passes the first, and
/// on the second its shank (from 5 mm above the tip, Z−3) stands 1 mm in
/// the material the first pass left at Z−2.
const TWO_PASSES: &str = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\nG01 Z-2. F300\nG01 X20.\n\
    G00 Z5.\nG00 X0.\n   G01 Z-8. F300\nG01 X20.\nG00 Z5.\nM30\n";

/// `sim FILE --dialect fanuc --stock box:-20,-20,-10,40,20,0 EXTRA…`.
fn two_passes(file: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "sim",
        file,
        "--dialect",
        "fanuc",
        "--stock",
        "box:-20,-20,-10,40,20,0",
    ];
    args.extend_from_slice(extra);
    vcnc(&args)
}

#[test]
fn a_tool_table_s_flute_length_puts_the_shank_into_the_stock_at_its_line() {
    let (dir, file) = program("passes.nc", TWO_PASSES);
    let tools = dir.join("tools.csv");
    std::fs::write(
        &tools,
        "tool,diameter,corner_radius,length,flute_length,holder_diameter\n1,10,0,,5,30\n",
    )
    .unwrap();
    let o = two_passes(&file, &["--tools", tools.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "a collision fails the run");
    let t = out(&o);
    assert!(t.contains("tools      T1 10 mm flat end mill"), "{t}");
    let shank = "holder_into_stock: the shank runs 1.000 mm into the stock \
                 (the cut is deeper than the flutes reach)";
    // Line 8 plunges to Z−8 in the slot of line 5 (its floor at Z−2): the
    // flutes go first and cut the column, so the shank (no wider than the
    // cutter) meets only the wall of its own hole. Line 9 then runs the
    // shank (from Z−3 up) through the slot's floor at Z−2 ahead: 1 mm.
    assert!(!t.contains(&format!("{file}:8:4:")), "{t}");
    assert!(
        t.contains(&format!("{file}:9:1: {shank} at X20 Y0 Z-8")),
        "{t}"
    );
    assert!(t.contains("collisions 1"), "{t}");
    let json = two_passes(
        &file,
        &["--tools", tools.to_str().unwrap(), "--format", "json"],
    );
    let v: Value = serde_json::from_str(&out(&json)).unwrap();
    let c = &v["collisions"][0];
    assert_eq!(
        (c["line"].as_u64(), c["column"].as_u64(), c["kind"].as_str()),
        (Some(9), Some(1), Some("holder_into_stock"))
    );
    // Flutes of 10 mm reach past the 8 mm pass: nothing to report.
    std::fs::write(&tools, "tool,diameter,flute_length\n1,10,10\n").unwrap();
    let o = two_passes(&file, &["--tools", tools.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", out(&o));
    assert!(out(&o).contains("collisions 0"), "{}", out(&o));
}

#[test]
fn a_tool_table_s_stickout_puts_the_holder_into_the_stock() {
    // Flutes 5 mm, the holder (30 mm across) 10 mm above the tip: a
    // plunge to Z−12 into the block's top at Z0 puts the holder's face at
    // Z−2, 2 mm into the material around the hole.
    let text = "G21 G90 G17\nT1 M06\nG00 X0. Y0. Z5.\nG01 Z-12. F300\nG00 Z5.\nM30\n";
    let (dir, file) = program("holder.nc", text);
    let tools = dir.join("tools.csv");
    std::fs::write(
        &tools,
        "tool,diameter,flute_length,shank_diameter,holder_diameter,stickout\n1,10,5,10,30,10\n",
    )
    .unwrap();
    let o = vcnc(&[
        "sim",
        &file,
        "--dialect",
        "fanuc",
        "--stock",
        "box:-20,-20,-20,40,20,0",
        "--tools",
        tools.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let t = out(&o);
    assert!(
        t.contains(&format!(
            "{file}:4:1: holder_into_stock: the holder runs 2.000 mm into the stock \
             (the cut is deeper than the tool sticks out of its holder) at X0 Y0 Z-12"
        )),
        "{t}"
    );
    // A necked tool (a 6 mm shank, a holder 9.9 mm across) plunging past
    // its flutes stays inside the 10 mm hole its flutes cut first: nothing.
    std::fs::write(
        &tools,
        "tool,diameter,flute_length,shank_diameter,holder_diameter,stickout\n1,10,5,6,9.9,10\n",
    )
    .unwrap();
    let o = vcnc(&[
        "sim",
        &file,
        "--dialect",
        "fanuc",
        "--stock",
        "box:-20,-20,-20,40,20,0",
        "--tools",
        tools.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", out(&o));
    assert!(out(&o).contains("collisions 0"), "{}", out(&o));
}

#[test]
fn a_cam_header_s_flute_length_is_checked_without_a_table() {
    // Carbide Create's CutViewer line: a 10 mm flat end mill with 5 mm of
    // flutes, for the tool of the next T word (three lines further on).
    let text = format!("(TOOL/MILL,10.00, 0.00, 5.00, 0.00)\n{TWO_PASSES}");
    let (_, file) = program("cam.nc", &text);
    let o = two_passes(&file, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    let t = out(&o);
    assert!(t.contains("tools      T1 10 mm flat end mill"), "{t}");
    assert!(
        t.contains(&format!(
            "{file}:10:1: holder_into_stock: the shank runs 1.000 mm"
        )),
        "{t}"
    );
    assert!(!err(&o).contains("not described"), "{}", err(&o));
}
