//! `vcnc plot`: runs a program into a [`PlotSink`] and writes its back-plot
//! as SVG, PNG or a self-contained HTML page (`docs/plot.md`); without
//! `-o`, the page `NAME.html` in the current directory.
//!
//! One run feeds the plot, the `check` summary and the planner. The plot's
//! [`Clock`] numbers the blocks; for the page, the planner is fed the same
//! events with those numbers as their lines (`Numbered`), and its timeline
//! (`Stamps`) keeps the planned time at the end of each block, so that
//! after the run every vertex is retimed to the planner's seconds — a
//! look-ahead planner knows a block's time only some blocks after it ran.
//! The summary gives the legend its distances, extents and tools. A
//! program that alarms is plotted up to the alarm, which is marked; the
//! picture is written, the alarm is printed like `check` prints it, and the
//! exit code is 1. A progress bar appears on stderr when a plot takes
//! longer than a second on a terminal.

use crate::cli::Options;
use crate::files::Input;
use crate::{Setup, execute, exit_code, files, render, timing};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{BufWriter, IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use vcnc_core::ToolLibrary;
use vcnc_core::display::{DisplayUnits, duration};
use vcnc_interp::{Event, Interpreter, Machine, Outcome, Sink};
use vcnc_output::Summary;
use vcnc_planner::{Blocks, Numbered, Planner, Stamps};
use vcnc_plot::{
    Clock, ColorBy, FitTo, Legend, Look, Page, Plot, PlotOptions, PlotSink, Projection, Source,
    Space, Theme, View,
};

/// Options of `vcnc plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// The main program (`-`: standard input).
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output file; its extension picks the format: .svg, .png or .html (default: the program's name with .html, in the current directory).
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// The view (default: xy, or the xz half-section on a lathe; the page opens in iso); a lathe without a Y axis has only xz.
    #[arg(long, value_enum)]
    pub view: Option<ViewArg>,
    /// What the picture is framed on: the cuts (moves outside are clipped at the edge, marked where they leave) or everything.
    #[arg(long, value_enum, default_value_t = FitArg::Cuts)]
    pub fit: FitArg,
    /// Do not draw rapids (a program of rapids alone still shows them).
    #[arg(long)]
    pub no_rapids: bool,
    /// What colours the cuts (default: depth; in the page, tool when the program uses two tools or more).
    #[arg(long, value_enum)]
    pub color: Option<ColorArg>,
    /// Light or dark picture.
    #[arg(long, value_enum, default_value_t = ThemeArg::Light)]
    pub theme: ThemeArg,
    /// A second program overlaid for comparison (run with the same dialect and machine).
    #[arg(long)]
    pub compare: Option<PathBuf>,
    /// Picture size of SVG and PNG plots, WIDTHxHEIGHT in pixels.
    #[arg(long, default_value = "1200x800", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Simulate the material removal (as `vcnc sim --stock`: box:x0,y0,z0,x1,y1,z1, bar:D,L[,bore] or auto) and show the stock and the finished part on the page (.html only), each with a toggle.
    #[arg(long)]
    pub stock: Option<String>,
}

/// `--fit`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum FitArg {
    /// The cuts, holes and the programmed contour.
    Cuts,
    /// Every move and mark (and the travel limits).
    All,
}

/// `--view`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ViewArg {
    /// Top view: X right, Y up.
    Xy,
    /// Front view: X right, Z up (lathe: Z right, diameter up).
    Xz,
    /// Side view: Y right, Z up.
    Yz,
    /// Isometric view from +X -Y +Z.
    Iso,
}

/// `--color`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ColorArg {
    /// By depth (Z; X on a lathe).
    Depth,
    /// By tool.
    Tool,
    /// By feed rate.
    Feed,
}

/// `--theme`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ThemeArg {
    /// Dark lines on white.
    Light,
    /// Light lines on near-black.
    Dark,
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("{s:?} is not WIDTHxHEIGHT, e.g. 1200x800"))?;
    let parse = |v: &str| -> Result<u32, String> {
        match v.trim().parse::<u32>() {
            Ok(n) if (200..=8000).contains(&n) => Ok(n),
            _ => Err(format!("{v:?}: sizes are whole pixels from 200 to 8000")),
        }
    };
    Ok((parse(w)?, parse(h)?))
}

/// The output formats, from the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Svg,
    Png,
    Html,
}

fn format_of(path: &Path) -> Result<Format, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(Format::Svg),
        Some("png") => Ok(Format::Png),
        Some("html" | "htm") => Ok(Format::Html),
        _ => Err(format!(
            "cannot tell the format of {}: name the output .svg, .png or .html",
            path.display()
        )),
    }
}

/// Most vertices a flat plot keeps (≈ 48 MB); the page keeps fewer, since
/// every vertex goes to the browser.
const FLAT_BUDGET: usize = 1 << 20;
const PAGE_BUDGET: usize = 1 << 19;
/// Most hole and tool-change marks kept.
const MAX_MARKS: usize = 100_000;
/// Merge units across the model in the page (about a pixel of a large
/// screen at the zoom that fits the model).
const PAGE_RESOLUTION: f64 = 2048.0;
/// The page carries at most this much of each program text.
const MAX_SOURCE_BYTES: u64 = 64 << 20;
/// What the page's times are.
const TIME_LABEL: &str = "planned";

/// The plot's clock: the check summary (for the legend) and the block
/// number as the stamp.
struct BlockClock {
    summary: Summary,
    blocks: Blocks,
}

impl Sink for BlockClock {
    fn event(&mut self, event: &Event) {
        self.summary.event(event);
        self.blocks.see(event);
    }
}

impl Clock for BlockClock {
    fn now(&self) -> f64 {
        // Block counts are far below 2^53: exact.
        #[allow(clippy::cast_precision_loss)]
        let n = self.blocks.count() as f64;
        n
    }
}

/// What the options ask for, resolved once.
struct Settings {
    format: Format,
    output: PathBuf,
    view: View,
    projection: Projection,
    look: Look,
    options: PlotOptions,
    lathe: bool,
}

/// The page `vcnc plot FILE` writes without `-o`: FILE's name with
/// `.html`, in the current directory (`stdin.html` for `-`).
fn default_output(file: &Path) -> PathBuf {
    if file.as_os_str() == "-" {
        return PathBuf::from("stdin.html");
    }
    let stem = file
        .file_stem()
        .map_or_else(|| "plot".into(), |s| s.to_os_string());
    let mut name = PathBuf::from(stem);
    name.set_extension("html");
    name
}

/// Resolves the output, view, colours, theme and merge space; `lathe` when
/// the dialect programs an axis in diameters.
fn settings(args: &PlotArgs, machine: &Machine, lathe: bool) -> Result<Settings, String> {
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| default_output(&args.file));
    let format = format_of(&output)?;
    let view = match args.view {
        Some(ViewArg::Xy) => View::Xy,
        Some(ViewArg::Xz) => View::Xz,
        Some(ViewArg::Yz) => View::Yz,
        Some(ViewArg::Iso) => View::Iso,
        None if lathe => View::Xz,
        None if format == Format::Html => View::Iso,
        None => View::Xy,
    };
    if lathe && view != View::Xz && machine.axis_of(b'Y').is_none() {
        return Err(format!(
            "--view {}: a lathe without a Y axis is drawn as its XZ half-section (--view xz)",
            view.name()
        ));
    }
    let projection = Projection::new(view, lathe);
    let color = match args.color {
        Some(ColorArg::Depth) => ColorBy::Depth,
        Some(ColorArg::Tool) => ColorBy::Tool,
        Some(ColorArg::Feed) => ColorBy::Feed,
        // The page picks tool or depth once it knows the tools.
        None if format == Format::Html => ColorBy::Tool,
        None => ColorBy::Depth,
    };
    let theme = match args.theme {
        ThemeArg::Light => Theme::Light,
        ThemeArg::Dark => Theme::Dark,
    };
    let fit = match args.fit {
        FitArg::Cuts => FitTo::Cuts,
        FitArg::All => FitTo::All,
    };
    let (width_px, height_px) = args.size;
    let look = Look {
        theme,
        color,
        width_px,
        height_px,
        fit,
        rapids: !args.no_rapids,
        units: args.opts.units.map_or(DisplayUnits::Mm, Into::into),
    };
    let (space, max_vertices) = match format {
        Format::Html => (
            Space::Volume {
                resolution: PAGE_RESOLUTION,
            },
            PAGE_BUDGET,
        ),
        Format::Svg | Format::Png => {
            let (width_px, height_px) = vcnc_plot::plot_area(width_px, height_px);
            let space = Space::Flat {
                projection,
                width_px,
                height_px,
            };
            (space, FLAT_BUDGET)
        }
    };
    let options = PlotOptions {
        space,
        color,
        max_vertices,
        max_marks: MAX_MARKS,
        fit,
    };
    Ok(Settings {
        format,
        output,
        view,
        projection,
        look,
        options,
        lathe,
    })
}

/// `vcnc plot`.
pub fn plot(args: &PlotArgs) -> Result<ExitCode, String> {
    let started = Instant::now();
    let c = &args.opts;
    let choice = crate::choose::Choice::new(c)?;
    // An unreadable program is a usage error before anything is written.
    let input = Input::from_arg(&args.file)?;
    drop(input.open()?);
    let s = choice.setup(&input)?;
    let set = settings(args, s.machine, s.dialect.diameter.lathe)?;
    if args.stock.is_some() && set.format != Format::Html {
        return Err(
            "--stock shows the stock and the finished part on the page: write .html (a picture of the part is `vcnc sim FILE --stock … -o part.png`)"
                .into(),
        );
    }
    // The simulation's stock is resolved (and a bad one refused) before
    // anything is written.
    let mut sim = Maybe(match &args.stock {
        Some(stock) => Some(crate::sim::for_plot(c, &s, &input, stock)?),
        None => None,
    });
    // Created before the run, so that an output that cannot be written is
    // known before a long program has run.
    let file = std::fs::File::create(&set.output)
        .map_err(|e| format!("cannot write {}: {e}", set.output.display()))?;
    // The page's program text is read and deflated on the second core
    // while the program runs.
    let main_text = (set.format == Format::Html).then(|| main_source(&input));
    let progress = Progress::start(&input, started);
    let clock = BlockClock {
        summary: Summary::new(s.machine),
        blocks: Blocks::default(),
    };
    let sink = PlotSink::with_clock(s.machine, set.options, clock);
    let mut counted = Counted::new(sink, progress.bar());
    let (outcome, diameter, planned_s, stamps) = if set.format == Format::Html {
        let plan = Planner::with_profile(s.machine, s.machine.motion.profile, Stamps::default());
        let mut numbered = Numbered {
            inner: plan,
            blocks: Blocks::default(),
        };
        let mut both = timing::Tee(&mut numbered, &mut sim);
        let (outcome, diameter) =
            execute(c, &s, &input, &mut timing::Tee(&mut counted, &mut both))?;
        let stamps = numbered.inner.into_timeline();
        (outcome, diameter, stamps.sum.total_s, Some(stamps))
    } else {
        let mut plan = timing::planner(s.machine, None);
        let (outcome, diameter) =
            execute(c, &s, &input, &mut timing::Tee(&mut counted, &mut plan))?;
        (outcome, diameter, plan.into_timeline().total_s, None)
    };
    let (mut plot, clock) = counted.inner.into_parts();
    if let Some(stamps) = &stamps {
        plot.retime(planned_s, |stamp| stamps.time_of(stamp));
    }
    let compare = match &args.compare {
        Some(other) => Some(run_compare(other, &s, set.options)?),
        None => None,
    };
    let (meshes, material) = match sim.0 {
        Some(sim) => {
            progress.phase("measuring the part");
            match sim.finish_run() {
                Ok(finished) => {
                    for n in &finished.report.notes {
                        eprintln!("warning: {n}");
                    }
                    let (meshes, row) = crate::sim::page_meshes(&finished);
                    (meshes, Some(row))
                }
                Err(e) => {
                    eprintln!(
                        "warning: the simulation stopped ({e}): the page shows no stock or part"
                    );
                    (Vec::new(), None)
                }
            }
        }
        None => (Vec::new(), None),
    };
    progress.phase(&format!("writing {}", set.output.display()));
    let diameter_axis = s.dialect.diameter.axis.filter(|_| diameter);
    let head = input.head(crate::choose::TOOL_COMMENTS_BYTES)?;
    let tools = s.tool_library(&String::from_utf8_lossy(&head));
    let facts = Facts {
        summary: &clock.summary,
        planned_s,
        outcome: &outcome,
        diameter_axis,
        units: set.look.units,
        tools: &tools,
        material,
    };
    let legend = legend(&input, &s, &facts, args.compare.as_deref());
    let compare = compare.as_ref().map(|p| (p, compare_name(args)));
    let text = main_text.map(|h| {
        h.join()
            .unwrap_or_else(|_| Source::new(input.name(), Vec::new()))
    });
    let page = Written {
        set: &set,
        legend: &legend,
        tools: &tools,
        main_text: text,
        color_given: args.color.is_some(),
        meshes: &meshes,
    };
    let written = write(file, &page, &plot, compare);
    progress.finish();
    written.map_err(|e| format!("cannot write {}: {e}", set.output.display()))?;
    if args.output.is_none() {
        println!("wrote {}", set.output.display());
    }
    report(&input, &plot, &outcome);
    Ok(exit_code(&outcome, false))
}

/// Reads (and deflates, when long) the main program's text on a thread.
fn main_source(input: &Input) -> JoinHandle<Source> {
    let input = input.clone();
    std::thread::spawn(move || {
        let bytes = match &input {
            Input::File(p) => read_capped(p),
            Input::Stdin(text) => text.to_vec(),
        };
        Source::deflated(input.name(), &bytes)
    })
}

fn compare_name(args: &PlotArgs) -> &str {
    args.compare
        .as_deref()
        .and_then(|p| p.to_str())
        .unwrap_or("compared program")
}

/// Runs the compared program on the same dialect and machine.
fn run_compare(other: &Path, s: &Setup, options: PlotOptions) -> Result<Plot, String> {
    let main = files::open_program(other)?;
    let mut store = files::DirStore::new(files::parent_dir(other));
    let mut sink = PlotSink::new(s.machine, options);
    let outcome =
        Interpreter::new(s.machine, s.dialect, s.options).run(main, &mut store, &mut sink);
    if let Outcome::Alarm(d) = &outcome {
        eprintln!(
            "warning: the compared program {} alarms ({} at line {}); it is shown up to there",
            other.display(),
            d.code.as_str(),
            d.line
        );
    }
    Ok(sink.into_plot())
}

/// What the legend reports, from the run.
struct Facts<'a> {
    summary: &'a Summary,
    planned_s: f64,
    outcome: &'a Outcome,
    diameter_axis: Option<u8>,
    units: DisplayUnits,
    tools: &'a ToolLibrary,
    /// The simulation's stock and what it removed (`--stock`).
    material: Option<String>,
}

/// The extents, one axis a line (the legend is narrow), in the display
/// unit; a lathe's X as a diameter.
fn extents_rows(f: &Facts<'_>) -> String {
    let Some((lo, hi)) = f.summary.extents else {
        return "no motion".to_string();
    };
    let u = f.units;
    let s = f.summary;
    let mut rows = Vec::new();
    for (i, l) in s.axis_letters().iter().enumerate() {
        if !s.reports_axis(i) {
            continue;
        }
        let (k, what) = if f.diameter_axis == Some(*l) {
            (2.0, " diameter")
        } else {
            (1.0, "")
        };
        rows.push(format!(
            "{}{what} {} .. {}",
            char::from(*l),
            u.len(k * lo.get(i)),
            u.len(k * hi.get(i))
        ));
    }
    rows.join("\n")
}

/// The legend's rows: what `check` says, shortened, in the display unit;
/// the planned time first, the distance/feed estimate second.
fn legend(input: &Input, s: &Setup, f: &Facts<'_>, compare: Option<&Path>) -> Legend {
    let mut rows = Vec::new();
    let u = f.units;
    let result = match f.outcome {
        Outcome::Ended(code) => format!("ended by {}", code.as_str()),
        Outcome::Stopped => "stopped".to_string(),
        Outcome::Alarm(d) => format!("alarm {} at line {}", d.code.as_str(), d.line),
    };
    rows.push(("result".to_string(), result));
    rows.push((
        "cycle time".to_string(),
        format!(
            "{} planned ({} dist/feed)",
            duration(f.planned_s),
            duration(f.summary.cycle_time_s)
        ),
    ));
    rows.push((
        "distance".to_string(),
        format!(
            "rapid {} {n}, cutting {} {n}",
            u.len(f.summary.rapid_mm),
            u.len(f.summary.cut_mm),
            n = u.name()
        ),
    ));
    rows.push((format!("extents (machine {})", u.name()), extents_rows(f)));
    let tools: Vec<String> = f
        .summary
        .tools
        .iter()
        .map(|t| match f.tools.get(*t) {
            Some(shape) => format!("T{t} dia {}", u.len(shape.diameter_mm)),
            None => format!("T{t}"),
        })
        .collect();
    rows.push((
        "tools".to_string(),
        if tools.is_empty() {
            "none".to_string()
        } else {
            tools.join(" ")
        },
    ));
    if let Some(m) = &f.material {
        rows.push(("material".to_string(), m.clone()));
    }
    Legend {
        title: format!("{} ({})", input.name(), s.dialect.name),
        rows,
        compare: compare.map(|p| p.display().to_string()),
    }
}

/// What is written besides the plot.
struct Written<'a> {
    set: &'a Settings,
    legend: &'a Legend,
    tools: &'a ToolLibrary,
    main_text: Option<Source>,
    color_given: bool,
    /// The simulation's stock and finished part (`--stock`).
    meshes: &'a [vcnc_plot::Mesh],
}

fn write(
    file: std::fs::File,
    w: &Written<'_>,
    plot: &Plot,
    compare: Option<(&Plot, &str)>,
) -> std::io::Result<()> {
    let set = w.set;
    let mut out = BufWriter::with_capacity(1 << 20, file);
    match set.format {
        Format::Svg | Format::Png => {
            let scene = vcnc_plot::scene(
                plot,
                compare.map(|c| c.0),
                &set.projection,
                &set.look,
                w.legend,
            );
            if set.format == Format::Svg {
                vcnc_plot::write_svg(&scene, &mut out)?;
            } else {
                vcnc_plot::write_png(&scene, &mut out)?;
            }
        }
        Format::Html => {
            let mut sources: Vec<Source> = w.main_text.iter().cloned().collect();
            sources.extend(called_sources(plot));
            // One colour per tool says little about a one-tool program.
            let color = if w.color_given || plot.tools.len() >= 2 {
                set.look.color
            } else {
                ColorBy::Depth
            };
            let page = Page {
                theme: set.look.theme,
                color,
                lathe: set.lathe,
                view: set.view,
                fit: set.look.fit,
                rapids: set.look.rapids,
                units: set.look.units,
                legend: w.legend,
                time_label: TIME_LABEL,
                sources: &sources,
                tools: Some(w.tools),
                meshes: w.meshes,
            };
            vcnc_plot::write_html(plot, compare, &page, &mut out)?;
        }
    }
    out.flush()
}

/// A file's first 64 MiB (nothing when it cannot be read again).
fn read_capped(p: &Path) -> Vec<u8> {
    let Ok(f) = std::fs::File::open(p) else {
        return Vec::new();
    };
    let mut bytes = Vec::new();
    let _ = f.take(MAX_SOURCE_BYTES).read_to_end(&mut bytes);
    bytes
}

/// The called programs' texts, in the plot's file order.
fn called_sources(plot: &Plot) -> Vec<Source> {
    plot.files
        .iter()
        .map(|f| Source::deflated(f.to_string(), &read_capped(Path::new(&**f))))
        .collect()
}

/// Prints the alarm (like `check`) or a note on an empty plot.
fn report(input: &Input, plot: &Plot, outcome: &Outcome) {
    if let Outcome::Alarm(d) = outcome {
        eprint!("{}", render::diagnostic(d, input));
        eprintln!("note: the plot shows the path up to the alarm and marks where it stopped");
    } else if plot.moves == 0 {
        eprintln!(
            "warning: {} has no motion: the plot is an empty frame",
            input.name()
        );
    }
}

/// A sink that is there or not (`plot --stock`'s simulation).
struct Maybe<S>(Option<S>);

impl<S: Sink> Sink for Maybe<S> {
    fn event(&mut self, event: &Event) {
        if let Some(s) = &mut self.0 {
            s.event(event);
        }
    }
    /// Never: a simulation that fails says so when it finishes, and the
    /// plot goes on without it.
    fn is_done(&self) -> bool {
        false
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.0.as_mut().map_or(Ok(()), Sink::finish)
    }
}

/// A sink that tells the progress bar how far the run is, every 4096 events.
pub(crate) struct Counted<S> {
    pub(crate) inner: S,
    bar: Option<ProgressBar>,
    events: u64,
    line: u64,
}

impl<S> Counted<S> {
    pub(crate) fn new(inner: S, bar: Option<ProgressBar>) -> Counted<S> {
        Counted {
            inner,
            bar,
            events: 0,
            line: 0,
        }
    }
}

impl<S: Sink> Sink for Counted<S> {
    fn event(&mut self, event: &Event) {
        self.inner.event(event);
        self.events += 1;
        if let Some(loc) = event.loc().filter(|l| l.file.is_none()) {
            self.line = self.line.max(loc.line);
        }
        if self.events & 0xFFF == 0
            && let Some(bar) = &self.bar
        {
            bar.set_position(self.line);
        }
    }
    fn is_done(&self) -> bool {
        self.inner.is_done()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.inner.finish()
    }
}

/// The progress bar: hidden until the plot has run for a second, and only
/// on a terminal (stderr). Its length is the main program's line count,
/// counted by the thread that shows it, so a short plot never pays for it.
pub(crate) struct Progress {
    bar: Option<ProgressBar>,
    done: Arc<AtomicBool>,
}

impl Progress {
    pub(crate) fn start(input: &Input, started: Instant) -> Progress {
        let done = Arc::new(AtomicBool::new(false));
        let Input::File(file) = input else {
            return Progress { bar: None, done };
        };
        if !std::io::stderr().is_terminal() {
            return Progress { bar: None, done };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        let (shown, flag, path) = (bar.clone(), done.clone(), file.clone());
        std::thread::spawn(move || {
            while started.elapsed() < Duration::from_secs(1) {
                if flag.load(Ordering::Relaxed) {
                    return;
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            let lines = count_lines(&path);
            if flag.load(Ordering::Relaxed) {
                return;
            }
            if let Ok(style) = ProgressStyle::with_template(
                "{spinner} {msg} [{elapsed_precise}] {wide_bar} line {pos}/{len}",
            ) {
                shown.set_style(style);
            }
            shown.set_length(lines);
            if shown.message().is_empty() {
                shown.set_message("running");
            }
            shown.set_draw_target(ProgressDrawTarget::stderr());
            shown.enable_steady_tick(Duration::from_millis(100));
        });
        Progress {
            bar: Some(bar),
            done,
        }
    }

    pub(crate) fn bar(&self) -> Option<ProgressBar> {
        self.bar.clone()
    }

    pub(crate) fn phase(&self, msg: &str) {
        if let Some(bar) = &self.bar {
            bar.set_message(msg.to_string());
            if let Some(n) = bar.length() {
                bar.set_position(n);
            }
        }
    }

    pub(crate) fn finish(&self) {
        self.done.store(true, Ordering::Relaxed);
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Lines of a file (0 when it cannot be read).
fn count_lines(path: &Path) -> u64 {
    let Ok(mut f) = std::fs::File::open(path) else {
        return 0;
    };
    let mut buf = vec![0u8; 1 << 16];
    let mut n = 0u64;
    while let Ok(k) = f.read(&mut buf) {
        if k == 0 {
            break;
        }
        n += buf
            .get(..k)
            .map_or(0, |b| b.iter().filter(|c| **c == b'\n').count() as u64);
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_output_the_page_is_named_after_the_program_here() {
        assert_eq!(
            default_output(Path::new("dir/part.nc")),
            PathBuf::from("part.html")
        );
        assert_eq!(
            default_output(Path::new("O1234")),
            PathBuf::from("O1234.html")
        );
        assert_eq!(default_output(Path::new("-")), PathBuf::from("stdin.html"));
    }
}
