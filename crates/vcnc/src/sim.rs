//! `vcnc sim`: runs a program into a material-removal simulation
//! (`vcnc_sim`) and reports what the cut leaves — the volume removed, the
//! time spent cutting air, collisions at their line and column — and
//! writes the finished part (STL, PNG, a replay page). `check --stock`
//! adds one summary line from the same run.
//!
//! ```text
//!   --stock | header comment | auto ─▶ (survey pass: auto stock, frames)
//!   Setup::tool_library(program)     ─▶ Simulation sink ─▶ Finished
//!        ─▶ report (text | json) · part.stl · part.png · part.html
//! ```
//!
//! The tools come from one function, `Setup::tool_library`: the `--tools`
//! table, else the CAM header's tool list, else the machine's offset
//! registers (a D radius, a lathe's nose radius and tip); a tool nothing
//! describes is an assumed 6 mm flat end mill, said as a warning.

use crate::cli::Options;
use crate::files::{self, Input};
use crate::plot::{Counted, Progress};
use crate::{Setup, render};
use clap::{Args, ValueEnum};
use serde_json::{Value, json};
use std::io::{BufRead, BufWriter, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use vcnc_core::ToolLibrary;
use vcnc_interp::{Interpreter, Outcome, Sink};
use vcnc_sim::render::{ColorBy, RenderView};
use vcnc_sim::{Finished, Part, SimOptions, Simulation, StockOrigin, StockSpec, Survey};

/// Options of `vcnc sim`.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// The main program (`-`: standard input).
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// The stock: box:x0,y0,z0,x1,y1,z1 (work mm), bar:D,L[,bore] (lathes: from Z0 to Z−L), or auto (the cuts' extents); default: the stock a CAM post wrote in the program's header, else auto.
    #[arg(long)]
    pub stock: Option<String>,
    /// Z-map cell size, mm (default: 0.1, or the longer side / 4000 on large parts).
    #[arg(long)]
    pub resolution: Option<f64>,
    /// Output files; each one's extension picks its format: .stl (the finished part), .png (a shaded picture), .html (a replay page).
    #[arg(short, long)]
    pub output: Vec<PathBuf>,
    /// Report format.
    #[arg(long, value_enum, default_value_t = SimFormat::Text)]
    pub format: SimFormat,
    /// What colours the PNG: depth, or the tool that cut each place last.
    #[arg(long, value_enum, default_value_t = SimColor::Depth)]
    pub color: SimColor,
    /// The PNG's view.
    #[arg(long, value_enum, default_value_t = SimView::Iso)]
    pub view: SimView,
}

/// `--format` of `vcnc sim`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SimFormat {
    /// For people.
    Text,
    /// One JSON object (docs/sim.md).
    Json,
}

/// `--color` of `vcnc sim`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SimColor {
    /// By depth.
    Depth,
    /// By the tool that cut last.
    Tool,
}

/// `--view` of `vcnc sim`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum SimView {
    /// Isometric, from +X −Y +Z.
    Iso,
    /// From above (a lathe: the side).
    Top,
}

/// Frames of the replay page.
const REPLAY_FRAMES: u32 = 60;

/// The program's first bytes, where CAM posts write their header.
const HEAD_BYTES: u64 = 64 << 10;

/// The program's first bytes as text.
fn head(input: &Input) -> String {
    let bytes = match input {
        Input::File(p) => {
            let mut buf = Vec::new();
            if let Ok(f) = std::fs::File::open(p) {
                let _ = f.take(HEAD_BYTES).read_to_end(&mut buf);
            }
            buf
        }
        Input::Stdin(b) => b.iter().take(64 << 10).copied().collect(),
    };
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Runs the program into `sink` without writing the variables file (a
/// pass before the simulation).
fn pass<S: Sink>(c: &Options, s: &Setup, input: &Input, sink: &mut S) -> Result<Outcome, String> {
    let main = input.open()?;
    let dir = c.program_dir.clone().unwrap_or_else(|| input.dir());
    let mut store = files::DirStore::new(dir);
    let mut interp = Interpreter::new(s.machine, s.dialect, s.options);
    if let Some(path) = &c.variables {
        let kept = crate::variables::read(path)?;
        interp
            .restore_variables(&kept)
            .map_err(|e| format!("variables file {}: {e}", path.display()))?;
    }
    Ok(interp.run(main, &mut store, sink))
}

/// What a simulation needs before its run.
struct Plan {
    options: SimOptions,
    library: ToolLibrary,
}

/// Resolves the stock (`--stock`, a header comment, or a survey pass) and
/// the tools.
fn plan(
    c: &Options,
    s: &Setup,
    input: &Input,
    (stock, resolution): (Option<&str>, Option<f64>),
    replay: bool,
) -> Result<Plan, String> {
    let lathe = s.dialect.diameter.lathe;
    let text = head(input);
    let library = s.tool_library(&text);
    let (mut spec, mut origin) = match stock {
        Some(t) => (StockSpec::parse(t)?, StockOrigin::Option),
        None => vcnc_sim::from_header(&text).unwrap_or((StockSpec::Auto, StockOrigin::Auto)),
    };
    if lathe && matches!(spec, StockSpec::Box { .. }) && origin != StockOrigin::Option {
        // A mill post's header on a lathe program says nothing of its bar.
        (spec, origin) = (StockSpec::Auto, StockOrigin::Auto);
    }
    vcnc_sim::check_setup(&spec, resolution, lathe).map_err(|e| match &origin {
        StockOrigin::Header { line, post } => {
            format!("{}:{line}: the {post} stock comment: {e}", input.name())
        }
        _ => e,
    })?;
    let mut frames = None;
    if spec == StockSpec::Auto || replay {
        let mut survey = Survey::new(s.machine, &library, lathe);
        pass(c, s, input, &mut survey)?;
        if spec == StockSpec::Auto
            && let Some(found) = survey.stock()
        {
            spec = found;
            vcnc_sim::check_setup(&spec, resolution, lathe)
                .map_err(|e| format!("the automatic stock ({}): {e}", spec.describe()))?;
        }
        if replay {
            frames = Some((REPLAY_FRAMES, survey.moves));
        }
    }
    let workers = std::thread::available_parallelism().map_or(1, usize::from);
    Ok(Plan {
        options: SimOptions {
            stock: spec,
            stock_origin: origin,
            resolution_mm: resolution,
            lathe,
            workers,
            replay: frames,
        },
        library,
    })
}

/// The output formats, from the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Output {
    Stl,
    Png,
    Html,
}

fn output_of(path: &Path) -> Result<Output, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("stl") => Ok(Output::Stl),
        Some("png") => Ok(Output::Png),
        Some("html" | "htm") => Ok(Output::Html),
        _ => Err(format!(
            "cannot tell the format of {}: name the output .stl, .png or .html",
            path.display()
        )),
    }
}

/// `vcnc sim`.
pub fn sim(args: &SimArgs) -> Result<ExitCode, String> {
    let started = Instant::now();
    let outputs: Vec<(PathBuf, Output)> = args
        .output
        .iter()
        .map(|p| output_of(p).map(|o| (p.clone(), o)))
        .collect::<Result<_, _>>()?;
    let c = &args.opts;
    let input = Input::from_arg(&args.file)?;
    drop(input.open()?);
    let choice = crate::choose::Choice::new(c)?;
    let s = choice.setup(&input)?;
    let replay = outputs.iter().any(|(_, o)| *o == Output::Html);
    let progress = Progress::start(&input, started);
    let p = plan(
        c,
        &s,
        &input,
        (args.stock.as_deref(), args.resolution),
        replay,
    )?;
    let table = s.machine.table_z_mm;
    let sim = Simulation::new(s.machine, &p.library, table, p.options.clone())?;
    let mut counted = Counted::new(sim, progress.bar());
    let (outcome, _) = crate::execute(c, &s, &input, &mut counted)?;
    progress.phase("measuring the part");
    let finished = counted.inner.finish_run()?;
    let columns = columns(&input, &finished);
    for (path, kind) in &outputs {
        progress.phase(&format!("writing {}", path.display()));
        write_output(path, *kind, args, &finished, &input)?;
    }
    progress.finish();
    let mut out = std::io::stdout().lock();
    let written = match args.format {
        SimFormat::Text => text(&mut out, &input, &s, &outcome, &finished, &columns),
        SimFormat::Json => {
            let doc = report_json(&input, &outcome, &finished, &columns);
            writeln!(out, "{doc:#}")
        }
    };
    crate::reported(written)?;
    for n in &finished.report.notes {
        eprintln!("warning: {n}");
    }
    if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, &input));
    }
    let crashed = !finished.report.collisions.is_empty();
    Ok(if crashed {
        ExitCode::from(1)
    } else {
        crate::exit_code(&outcome, false)
    })
}

/// The column of each collision's block: its first word (a `/` block
/// delete and blanks skipped), read back from the program.
fn columns(input: &Input, f: &Finished) -> Vec<u32> {
    let mut wanted: Vec<(Option<&str>, u64)> = f
        .report
        .collisions
        .iter()
        .map(|c| (c.file.as_deref(), c.line))
        .collect();
    wanted.sort_unstable();
    wanted.dedup();
    let mut found = std::collections::HashMap::new();
    let mut by_file: std::collections::BTreeMap<Option<&str>, Vec<u64>> = Default::default();
    for (file, line) in wanted {
        by_file.entry(file).or_default().push(line);
    }
    for (file, lines) in by_file {
        let reader: Box<dyn BufRead> = match (file, input) {
            (Some(path), _) => match std::fs::File::open(path) {
                Ok(f) => Box::new(std::io::BufReader::new(f)),
                Err(_) => continue,
            },
            (None, Input::File(path)) => match std::fs::File::open(path) {
                Ok(f) => Box::new(std::io::BufReader::new(f)),
                Err(_) => continue,
            },
            (None, Input::Stdin(bytes)) => Box::new(std::io::Cursor::new(bytes.to_vec())),
        };
        let last = lines.last().copied().unwrap_or(0);
        for (n, line) in (1u64..).zip(reader.split(b'\n')) {
            if n > last {
                break;
            }
            let Ok(line) = line else { break };
            if lines.binary_search(&n).is_ok() {
                found.insert((file.map(str::to_string), n), first_word_column(&line));
            }
        }
    }
    f.report
        .collisions
        .iter()
        .map(|c| {
            found
                .get(&(c.file.as_deref().map(str::to_string), c.line))
                .copied()
                .unwrap_or(1)
        })
        .collect()
}

/// The 1-based column of a block's first word.
pub(crate) fn first_word_column(line: &[u8]) -> u32 {
    let mut i = 0;
    while let Some(b) = line.get(i) {
        if !(b.is_ascii_whitespace() || *b == b'/') {
            break;
        }
        i += 1;
        // `/2` is block delete 2: its digit is not the block's first word.
        if *b == b'/' && line.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
    }
    if i >= line.len() {
        i = 0;
    }
    u32::try_from(i + 1).unwrap_or(1)
}

fn write_output(
    path: &Path,
    kind: Output,
    args: &SimArgs,
    f: &Finished,
    input: &Input,
) -> Result<(), String> {
    let file =
        std::fs::File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    let mut out = BufWriter::with_capacity(1 << 20, file);
    let written = match kind {
        Output::Stl => match &f.part {
            Part::Mill(map, origin) => {
                let field =
                    vcnc_sim::mesh::HeightField::of(map, *origin, vcnc_sim::mesh::MAX_MESH_CELLS);
                vcnc_sim::mesh::write_stl(&mut out, &|emit| field.triangles(emit))
            }
            Part::Lathe(s) => {
                vcnc_sim::mesh::write_stl(&mut out, &|emit| vcnc_sim::mesh::revolve(s, emit))
            }
            Part::Empty => return Err("nothing was simulated: no STL to write".into()),
        },
        Output::Png => {
            let color = match args.color {
                SimColor::Depth => ColorBy::Depth,
                SimColor::Tool => ColorBy::Tool,
            };
            let view = match args.view {
                SimView::Iso => RenderView::Iso,
                SimView::Top => RenderView::Top,
            };
            vcnc_sim::render::write_png(&f.part, view, color, (1200, 800), &mut out)
        }
        Output::Html => {
            let title = format!("{} — vcnc sim", input.name());
            vcnc_sim::page::write_html(f, &title, &mut out)
        }
    };
    written
        .and_then(|()| out.flush())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn result_text(outcome: &Outcome) -> String {
    match outcome {
        Outcome::Ended(code) => format!("ended by {}", code.as_str()),
        Outcome::Stopped => "stopped".to_string(),
        Outcome::Alarm(d) => format!(
            "alarm {} at line {}, column {} (simulated up to there)",
            d.code.as_str(),
            d.line,
            d.column
        ),
    }
}

fn text(
    out: &mut impl Write,
    input: &Input,
    s: &Setup,
    outcome: &Outcome,
    f: &Finished,
    columns: &[u32],
) -> std::io::Result<()> {
    let r = &f.report;
    writeln!(
        out,
        "program    {} ({} dialect, {})",
        input.name(),
        s.dialect.name,
        s.machine.name
    )?;
    writeln!(out, "result     {}", result_text(outcome))?;
    writeln!(out, "stock      {}", r.stock)?;
    if let (Some(res), Some((nx, ny))) = (r.resolution_mm, r.grid) {
        writeln!(
            out,
            "grid       {res:.4} mm cells, {nx} × {ny} ({} MB)",
            nx * ny * 5 / 1_000_000
        )?;
    }
    let tools: Vec<String> = f.tools.cutters.iter().map(|c| c.label.clone()).collect();
    let tools = if s.dialect.diameter.lathe {
        f.tools
            .inserts
            .iter()
            .map(|i| format!("T{} nose R{} tip {}", i.number, i.nose_mm, i.tip))
            .collect()
    } else {
        tools
    };
    writeln!(
        out,
        "tools      {}",
        if tools.is_empty() {
            "none".to_string()
        } else {
            tools.join(", ")
        }
    )?;
    let pct = if r.stock_mm3 > 0.0 {
        100.0 * r.removed_mm3 / r.stock_mm3
    } else {
        0.0
    };
    writeln!(
        out,
        "removed    {:.3} mm³ of {:.3} mm³ ({pct:.1} %)",
        r.removed_mm3, r.stock_mm3
    )?;
    writeln!(
        out,
        "air cut    {} of {} at feed",
        render::duration(r.air_cut_s),
        render::duration(r.air_cut_s + r.cutting_s)
    )?;
    if r.not_simulated > 0 {
        let first = r
            .first_not_simulated
            .as_ref()
            .map_or(String::new(), |(l, _)| format!(", the first at line {l}"));
        writeln!(
            out,
            "not simulated {} moves with rotary axes (4/5-axis is out of scope){first}",
            r.not_simulated
        )?;
    }
    writeln!(out, "collisions {}", r.collision_total)?;
    for (c, col) in r.collisions.iter().zip(columns) {
        let file = c
            .file
            .as_deref()
            .map_or_else(|| input.name(), str::to_string);
        let again = if c.repeats > 0 {
            format!(" ({} more moves of the block)", c.repeats)
        } else {
            String::new()
        };
        writeln!(
            out,
            "{file}:{}:{col}: {}: {} at X{} Y{} Z{}{again}",
            c.line,
            c.kind.as_str(),
            c.message,
            vcnc_sim::stock::fmt(c.at[0]),
            vcnc_sim::stock::fmt(c.at[1]),
            vcnc_sim::stock::fmt(c.at[2])
        )?;
    }
    Ok(())
}

/// The collisions as JSON (`[{line, column, kind, message, …}]`).
fn collisions_json(f: &Finished, columns: &[u32]) -> Value {
    f.report
        .collisions
        .iter()
        .zip(columns)
        .map(|(c, col)| {
            let mut v = json!({
                "line": c.line,
                "column": col,
                "kind": c.kind.as_str(),
                "message": c.message,
                "at": {"x": c.at[0], "y": c.at[1], "z": c.at[2]},
                "repeats": c.repeats,
            });
            if let (Some(file), Some(o)) = (&c.file, v.as_object_mut()) {
                o.insert("file".into(), json!(&**file));
            }
            v
        })
        .collect()
}

fn report_json(input: &Input, outcome: &Outcome, f: &Finished, columns: &[u32]) -> Value {
    let r = &f.report;
    json!({
        "program": input.name(),
        "result": result_text(outcome),
        "stock": r.stock,
        "stock_mm3": r.stock_mm3,
        "removed_mm3": r.removed_mm3,
        "air_cut_s": r.air_cut_s,
        "cutting_s": r.cutting_s,
        "resolution_mm": r.resolution_mm,
        "grid": r.grid.map(|(nx, ny)| json!([nx, ny])),
        "collisions": collisions_json(f, columns),
        "collision_count": r.collision_total,
        "not_simulated": r.not_simulated,
        "moves": r.moves,
        "notes": r.notes,
    })
}

/// The simulation `plot --stock` runs beside the plot: the stock resolved
/// (a survey pass for `auto`), the tools from the same place as the plot's.
pub(crate) fn for_plot(
    c: &Options,
    s: &Setup,
    input: &Input,
    stock: &str,
) -> Result<Simulation, String> {
    let p = plan(c, s, input, (Some(stock), None), false)?;
    Simulation::new(s.machine, &p.library, s.machine.table_z_mm, p.options)
}

/// The plot page's meshes from a finished simulation — the stock (hidden
/// at first: it would hide the part) and the finished part — and the
/// legend's row for it.
pub(crate) fn page_meshes(f: &Finished) -> (Vec<vcnc_plot::Mesh>, String) {
    let r = &f.report;
    let row = format!(
        "{}\nremoved {:.1} of {:.1} mm³, {} collision{}{}",
        r.stock,
        r.removed_mm3,
        r.stock_mm3,
        r.collision_total,
        if r.collision_total == 1 { "" } else { "s" },
        if r.collision_total > 0 {
            " (vcnc sim lists them)"
        } else {
            ""
        }
    );
    let Some((stock, part)) = vcnc_sim::mesh::stock_and_part(&f.part) else {
        return (Vec::new(), row);
    };
    let mesh = |name: &str, color, visible, m: vcnc_sim::mesh::Indexed| vcnc_plot::Mesh {
        name: name.to_string(),
        color,
        visible,
        positions: m.positions,
        triangles: m.triangles,
    };
    let meshes = vec![
        mesh("stock", vcnc_plot::Rgb(150, 165, 185), false, stock),
        mesh("finished part", vcnc_plot::Rgb(215, 150, 70), true, part),
    ];
    (meshes, row)
}

/// What `check --stock` adds to a program's report.
pub(crate) struct CheckSim {
    finished: Finished,
    columns: Vec<u32>,
}

/// Simulates one program for `check --stock`.
pub(crate) fn for_check(
    c: &Options,
    s: &Setup,
    input: &Input,
    stock: &str,
) -> Result<CheckSim, String> {
    let p = plan(c, s, input, (Some(stock), None), false)?;
    let mut sim = Simulation::new(s.machine, &p.library, s.machine.table_z_mm, p.options)?;
    pass(c, s, input, &mut sim)?;
    let finished = sim.finish_run()?;
    let columns = columns(input, &finished);
    Ok(CheckSim { finished, columns })
}

impl CheckSim {
    /// Whether the simulation found collisions.
    pub(crate) fn crashed(&self) -> bool {
        !self.finished.report.collisions.is_empty()
    }

    /// The summary line and one line per collision.
    pub(crate) fn write(&self, out: &mut impl Write, input: &Input) -> std::io::Result<()> {
        let r = &self.finished.report;
        writeln!(
            out,
            "sim        removed {:.3} mm³ of {:.3} mm³, {} collision{}",
            r.removed_mm3,
            r.stock_mm3,
            r.collision_total,
            if r.collision_total == 1 { "" } else { "s" }
        )?;
        for (c, col) in r.collisions.iter().zip(&self.columns) {
            let file = c
                .file
                .as_deref()
                .map_or_else(|| input.name(), str::to_string);
            writeln!(
                out,
                "  {file}:{}:{col}: {}: {}",
                c.line,
                c.kind.as_str(),
                c.message
            )?;
        }
        Ok(())
    }

    /// The JSON of `check --format json`.
    pub(crate) fn json(&self) -> Value {
        let r = &self.finished.report;
        json!({
            "stock": r.stock,
            "stock_mm3": r.stock_mm3,
            "removed_mm3": r.removed_mm3,
            "air_cut_s": r.air_cut_s,
            "resolution_mm": r.resolution_mm,
            "collisions": collisions_json(&self.finished, &self.columns),
        })
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_first_word_skips_blanks_and_block_delete() {
        assert_eq!(super::first_word_column(b"G00 X1"), 1);
        assert_eq!(super::first_word_column(b"   G00 X1"), 4);
        assert_eq!(super::first_word_column(b"/2 N10 G00"), 4);
        assert_eq!(super::first_word_column(b""), 1);
    }
}
