//! `vcnc plot`: runs a program into a [`PlotSink`] and writes its back-plot
//! as SVG, PNG or a self-contained HTML page (`docs/plot.md`).
//!
//! One run feeds both the plot and the `check` summary: the summary is the
//! plot's [`Clock`] (its distance/feed time estimate dates every vertex —
//! the seam where the planner's times will come in) and gives the legend
//! its cycle time, extents and tools. A program that alarms is plotted up
//! to the alarm, which is marked; the picture is written, the alarm is
//! printed like `check` prints it, and the exit code is 1. A progress bar
//! appears on stderr when a plot takes longer than a second on a terminal.

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
use std::time::{Duration, Instant};
use vcnc_interp::{Event, Interpreter, Outcome, Sink};
use vcnc_output::Summary;
use vcnc_plot::{
    Clock, ColorBy, Legend, Look, Page, Plot, PlotOptions, PlotSink, Projection, Source, Space,
    Theme, View,
};

/// Options of `vcnc plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// The main program.
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output file; its extension picks the format: .svg, .png or .html.
    #[arg(short, long)]
    pub output: PathBuf,
    /// View of SVG and PNG plots (default: xy, or the xz half-section under a lathe dialect).
    #[arg(long, value_enum)]
    pub view: Option<ViewArg>,
    /// What colours the cuts (default: depth; tool in the HTML page).
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

/// The check summary as the plot's clock: distance/feed estimate.
struct Estimate(Summary);

impl Sink for Estimate {
    fn event(&mut self, event: &Event) {
        self.0.event(event);
    }
}

impl Clock for Estimate {
    fn elapsed_s(&self) -> f64 {
        self.0.cycle_time_s
    }
}

/// What the times of the plot are, for the legend and the page.
const TIME_LABEL: &str = "distance/feed estimate";

/// What the options ask for, resolved once.
struct Settings {
    format: Format,
    projection: Projection,
    look: Look,
    options: PlotOptions,
    lathe: bool,
}

/// Resolves the view, colours, theme and merge space; `lathe` when the
/// dialect programs an axis in diameters.
fn settings(args: &PlotArgs, format: Format, lathe: bool) -> Settings {
    let view = match args.view {
        Some(ViewArg::Xy) => View::Xy,
        Some(ViewArg::Xz) => View::Xz,
        Some(ViewArg::Yz) => View::Yz,
        Some(ViewArg::Iso) => View::Iso,
        None if lathe => View::Xz,
        None => View::Xy,
    };
    let projection = Projection::new(view, lathe);
    let color = match (args.color, format) {
        (Some(ColorArg::Depth), _) => ColorBy::Depth,
        (Some(ColorArg::Tool), _) | (None, Format::Html) => ColorBy::Tool,
        (Some(ColorArg::Feed), _) => ColorBy::Feed,
        (None, _) => ColorBy::Depth,
    };
    let theme = match args.theme {
        ThemeArg::Light => Theme::Light,
        ThemeArg::Dark => Theme::Dark,
    };
    let (width_px, height_px) = args.size;
    let look = Look {
        theme,
        color,
        width_px,
        height_px,
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
    };
    Settings {
        format,
        projection,
        look,
        options,
        lathe,
    }
}

/// `vcnc plot`.
pub fn plot(args: &PlotArgs) -> Result<ExitCode, String> {
    let started = Instant::now();
    let format = format_of(&args.output)?;
    let c = &args.opts;
    let s = crate::setup(c, &[args.file.as_path()])?;
    let input = Input::File(args.file.clone());
    // An unreadable program is a usage error before anything is written.
    drop(input.open()?);
    let set = settings(args, format, s.dialect.diameter.axis.is_some());
    // Created before the run, so that an output that cannot be written is
    // known before a long program has run.
    let file = std::fs::File::create(&args.output)
        .map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    let progress = Progress::start(&args.file, started);
    let sink = PlotSink::with_clock(&s.machine, set.options, Estimate(Summary::new(&s.machine)));
    let mut counted = Counted::new(sink, progress.bar());
    // The legend's cycle time is the planned one, as `check` prints; the
    // vertices are dated by the distance/feed estimate as they stream.
    let mut plan = timing::planner(&s.machine, None);
    let (outcome, diameter) = execute(c, &s, &input, &mut timing::Tee(&mut counted, &mut plan))?;
    let planned = plan.into_timeline();
    let (plot, Estimate(summary)) = counted.inner.into_parts();
    let compare = match &args.compare {
        Some(other) => Some(run_compare(other, &s, set.options)?),
        None => None,
    };
    progress.phase(&format!("writing {}", args.output.display()));
    let diameter_axis = s.dialect.diameter.axis.filter(|_| diameter);
    let legend = legend(
        &args.file,
        &s,
        (&summary, planned.total_s),
        &outcome,
        diameter_axis,
        args.compare.as_deref(),
    );
    let compare = compare.as_ref().map(|p| (p, compare_name(args)));
    let written = write(file, args, &set, &plot, compare, &legend);
    progress.finish();
    written.map_err(|e| format!("cannot write {}: {e}", args.output.display()))?;
    report(&input, &plot, &outcome);
    Ok(exit_code(&outcome, false))
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
    let mut sink = PlotSink::new(&s.machine, options);
    let outcome =
        Interpreter::new(&s.machine, &s.dialect, s.options).run(main, &mut store, &mut sink);
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

/// The legend's rows: what `check` says, shortened.
fn legend(
    file: &Path,
    s: &Setup,
    (summary, planned_s): (&Summary, f64),
    outcome: &Outcome,
    diameter_axis: Option<u8>,
    compare: Option<&Path>,
) -> Legend {
    let mut rows = Vec::new();
    let result = match outcome {
        Outcome::Ended(code) => format!("ended by {}", code.as_str()),
        Outcome::Stopped => "stopped".to_string(),
        Outcome::Alarm(d) => format!("alarm {} at line {}", d.code.as_str(), d.line),
    };
    rows.push(("result".to_string(), result));
    rows.push((
        "cycle time".to_string(),
        format!(
            "{} planned ({} dist/feed)",
            render::duration(planned_s),
            render::duration(summary.cycle_time_s)
        ),
    ));
    rows.push((
        "distance".to_string(),
        format!(
            "rapid {:.3} mm, cutting {:.3} mm",
            summary.rapid_mm, summary.cut_mm
        ),
    ));
    // One axis a line: the legend is narrow.
    let extents = match summary.extents {
        Some(ext) => render::extents_text(summary, ext, diameter_axis)
            .split("   ")
            .collect::<Vec<_>>()
            .join("\n"),
        None => "no motion".to_string(),
    };
    rows.push(("extents (machine mm)".to_string(), extents));
    let tools: Vec<String> = summary.tools.iter().map(|t| format!("T{t}")).collect();
    rows.push((
        "tools".to_string(),
        if tools.is_empty() {
            "none".to_string()
        } else {
            tools.join(" ")
        },
    ));
    Legend {
        title: format!("{} ({})", file.display(), s.dialect.name),
        rows,
        compare: compare.map(|p| p.display().to_string()),
    }
}

fn write(
    file: std::fs::File,
    args: &PlotArgs,
    set: &Settings,
    plot: &Plot,
    compare: Option<(&Plot, &str)>,
    legend: &Legend,
) -> std::io::Result<()> {
    let mut out = BufWriter::with_capacity(1 << 20, file);
    match set.format {
        Format::Svg | Format::Png => {
            let scene = vcnc_plot::scene(
                plot,
                compare.map(|c| c.0),
                &set.projection,
                &set.look,
                legend,
            );
            if set.format == Format::Svg {
                vcnc_plot::write_svg(&scene, &mut out)?;
            } else {
                vcnc_plot::write_png(&scene, &mut out)?;
            }
        }
        Format::Html => {
            let sources = sources(&args.file, plot);
            let page = Page {
                theme: set.look.theme,
                color: set.look.color,
                lathe: set.lathe,
                legend,
                time_label: TIME_LABEL,
                sources: &sources,
            };
            vcnc_plot::write_html(plot, compare, &page, &mut out)?;
        }
    }
    out.flush()
}

/// The program texts the page shows: the main program, then the called
/// programs in the plot's file order (a file that cannot be read again is
/// left out; a text over 64 MiB is cut there).
fn sources(main: &Path, plot: &Plot) -> Vec<Source> {
    let read = |p: &Path| -> Vec<u8> {
        let Ok(f) = std::fs::File::open(p) else {
            return Vec::new();
        };
        let mut bytes = Vec::new();
        let _ = f.take(MAX_SOURCE_BYTES).read_to_end(&mut bytes);
        bytes
    };
    let mut out = vec![Source {
        name: main.display().to_string(),
        bytes: read(main),
    }];
    for f in &plot.files {
        out.push(Source {
            name: f.to_string(),
            bytes: read(Path::new(&**f)),
        });
    }
    out
}

/// Prints the alarm (like `check`) or a note on an empty plot.
fn report(input: &Input, plot: &Plot, outcome: &Outcome) {
    if let Outcome::Alarm(d) = outcome {
        eprint!("{}", render::diagnostic(d, input));
        eprintln!("note: the plot shows the path up to the alarm and marks where it stopped");
    } else if plot.path.vertices.len() <= 1 {
        eprintln!(
            "warning: {} has no motion: the plot shows only the start point",
            input.name()
        );
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
    pub(crate) fn start(file: &Path, started: Instant) -> Progress {
        let done = Arc::new(AtomicBool::new(false));
        if !std::io::stderr().is_terminal() {
            return Progress { bar: None, done };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        let (shown, flag, path) = (bar.clone(), done.clone(), file.to_path_buf());
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
