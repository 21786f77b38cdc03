//! Rendering for people: alarms like rustc diagnostics (annotate-snippets)
//! and the `vcnc check` summary.

use crate::files::Input;
use annotate_snippets::{AnnotationKind, Level, Renderer, Snippet};
use std::io::{self, Write};
use vcnc_core::display::DisplayUnits;
use vcnc_interp::{Outcome, Pos};
use vcnc_output::Summary;
use vcnc_planner::CycleTime;
use vcnc_syntax::Diagnostic;

/// The source line of a diagnostic, read back from its program, as raw
/// bytes.
fn source_line(d: &Diagnostic, main: &Input) -> Option<Vec<u8>> {
    match &d.file {
        Some(path) => Input::File(path.into()).line_at(d.line_offset),
        None => main.line_at(d.line_offset),
    }
}

/// A byte offset of the raw line as an offset into its lossy UTF-8 text
/// (GBK or Latin-1 comments are not UTF-8), on a character boundary.
fn lossy_offset(raw: &[u8], text: &str, byte: usize) -> usize {
    let mut at = String::from_utf8_lossy(&raw[..byte.min(raw.len())])
        .len()
        .min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// `text` safe to write to a terminal: the control characters that
/// start escape sequences (ESC, BEL, CSI …) shown, not obeyed, the way
/// the source line of an alarm shows them (annotate-snippets' control
/// pictures: ESC is `␛`, BEL `␇`); C1 controls and DEL as `\u{..}`.
/// Newlines and tabs stay. Text from files vcnc reads (tool tables,
/// machine files, file names, messages quoting a program's comments)
/// goes through this before it reaches stderr.
pub fn visible(text: &str) -> std::borrow::Cow<'_, str> {
    let shown = |c: char| c == '\n' || c == '\t' || !c.is_control();
    if text.chars().all(shown) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            c if shown(c) => out.push(c),
            // U+2400 + c: the Control Pictures block.
            '\0'..='\u{1f}' => out.push(char::from_u32(0x2400 + c as u32).unwrap_or('\u{fffd}')),
            c => out.push_str(&c.escape_unicode().to_string()),
        }
    }
    std::borrow::Cow::Owned(out)
}

/// An alarm or a warning with its source line and a caret, like rustc.
pub fn diagnostic(d: &Diagnostic, main: &Input) -> String {
    let file = visible(&d.file.clone().unwrap_or_else(|| main.name())).into_owned();
    let warning = d.code.is_warning();
    let message = visible(&d.message);
    let (level, title) = if warning {
        (Level::WARNING, message.into_owned())
    } else {
        (Level::ERROR, format!("alarm: {message}"))
    };
    let renderer = if std::env::var_os("NO_COLOR").is_none() && io_is_terminal() {
        Renderer::styled()
    } else {
        Renderer::plain()
    };
    let text = match source_line(d, main) {
        Some(raw) => {
            let line = String::from_utf8_lossy(&raw).into_owned();
            let start = lossy_offset(&raw, &line, d.span.start as usize);
            let end = lossy_offset(&raw, &line, d.span.end as usize).max(start);
            let report = [level
                .primary_title(title)
                .id(d.code.as_str())
                .element(
                    Snippet::source(line)
                        .line_start(usize::try_from(d.line).unwrap_or(usize::MAX))
                        .path(file.clone())
                        .annotation(
                            AnnotationKind::Primary
                                .span(start..end.max(start))
                                .label(d.code.as_str()),
                        ),
                )
                .element(Level::HELP.message(visible(&d.help).into_owned()))];
            renderer.render(&report)
        }
        None => format!(
            "{}[{}]: {} at {}:{}:{}\n  help: {}",
            if warning { "warning" } else { "error" },
            d.code.as_str(),
            visible(&d.message),
            file,
            d.line,
            d.column,
            visible(&d.help)
        ),
    };
    format!("{text}\n")
}

/// Warnings shown on the terminal for one program; the rest are counted.
pub const SHOWN_WARNINGS: usize = 20;

/// The warnings of a run for stderr: the first [`SHOWN_WARNINGS`], then
/// how many more there were.
pub fn warnings(s: &Summary, main: &Input) -> String {
    let mut out = String::new();
    for d in s.warnings.iter().take(SHOWN_WARNINGS) {
        out.push_str(&diagnostic(d, main));
    }
    let total = s.warning_total();
    let shown = s.warnings.len().min(SHOWN_WARNINGS) as u64;
    if total > shown {
        out.push_str(&format!(
            "warning: {} more warnings not shown\n",
            total - shown
        ));
    }
    out
}

fn io_is_terminal() -> bool {
    use std::io::IsTerminal;
    io::stderr().is_terminal()
}

pub use vcnc_core::display::duration;

/// The summary block of `vcnc check` for one program: lengths in `units`,
/// a diameter axis shown as a diameter.
pub fn summary(
    out: &mut impl Write,
    name: &str,
    setup: &crate::Setup,
    (s, planned): (&Summary, &CycleTime),
    outcome: &Outcome,
    (diameter_axis, units): (Option<u8>, DisplayUnits),
) -> io::Result<()> {
    let machine = setup.machine;
    writeln!(out, "program    {name} ({})", machine.name)?;
    writeln!(out, "dialect    {}", setup.dialect_text())?;
    match outcome {
        Outcome::Ended(vcnc_interp::EndCode::M99) => writeln!(
            out,
            "result     one pass, ended by M99 (a machine repeats it for ever)"
        )?,
        Outcome::Ended(code) => writeln!(out, "result     ended by {}", code.as_str())?,
        Outcome::Stopped => writeln!(out, "result     stopped (output closed)")?,
        Outcome::Alarm(d) => writeln!(
            out,
            "result     alarm {} at line {}, column {}",
            d.code.as_str(),
            d.line,
            d.column
        )?,
    }
    let mut time = format!(
        "{} (planned: {} profile, look-ahead {} blocks)",
        duration(planned.total_s),
        machine.motion.profile.as_str(),
        machine.motion.lookahead_blocks
    );
    if s.untimed_moves > 0 {
        time.push_str(&format!(
            "; {} feed-per-rev moves with the spindle stopped not counted",
            s.untimed_moves
        ));
    }
    if s.waits > 0 {
        time.push_str(&format!(
            "; plus {} wait{} for the operator",
            s.waits,
            if s.waits == 1 { "" } else { "s" }
        ));
    }
    writeln!(out, "cycle time {time}")?;
    writeln!(
        out,
        "dist/feed  {} (distance/feed estimate, no acceleration)",
        duration(s.cycle_time_s)
    )?;
    let unit = units.name();
    writeln!(out, "rapid      {} {unit}", units.len(s.rapid_mm))?;
    writeln!(out, "cutting    {} {unit}", units.len(s.cut_mm))?;
    let centre = if s.contour_extents.is_some() {
        ", tool centre"
    } else {
        ""
    };
    match s.extents {
        Some(ext) => writeln!(
            out,
            "extents    {} (machine {unit}{centre})",
            extents_in(s, ext, diameter_axis, units)
        )?,
        None => writeln!(out, "extents    no motion")?,
    }
    if let Some(ext) = s.work_extents() {
        writeln!(
            out,
            "work       {} (work coordinates, {unit}{centre})",
            extents_in(s, ext, diameter_axis, units)
        )?;
    }
    if let Some(ext) = s.contour_extents {
        writeln!(
            out,
            "contour    {} (programmed, where cutter compensation ran)",
            extents_in(s, ext, diameter_axis, units)
        )?;
    }
    let tools: Vec<String> = s.tools.iter().map(|t| format!("T{t}")).collect();
    writeln!(
        out,
        "tools      {}",
        if tools.is_empty() {
            "none".to_string()
        } else {
            tools.join(" ")
        }
    )?;
    if !s.holes.is_empty() {
        let total: u64 = s.holes.iter().map(|(_, n)| n).sum();
        let per_tool: Vec<String> = s
            .holes
            .iter()
            .map(|(t, n)| match t {
                Some(t) => format!("T{t} {n}"),
                None => format!("no tool {n}"),
            })
            .collect();
        writeln!(out, "holes      {total} ({})", per_tool.join(", "))?;
    }
    match s.spindle_rpm {
        Some((lo, hi)) if (hi - lo).abs() < 1e-9 => writeln!(out, "spindle    {lo:.0} rpm")?,
        Some((lo, hi)) => writeln!(out, "spindle    {lo:.0} .. {hi:.0} rpm")?,
        None => writeln!(out, "spindle    not started")?,
    }
    if !s.unset_variables.is_empty() {
        writeln!(out, "unset vars {}", unset_text(s))?;
    }
    if s.warning_total() > 0 {
        let by_code: Vec<String> = s
            .warning_counts
            .iter()
            .map(|(c, n)| format!("{} {n}", c.as_str()))
            .collect();
        writeln!(
            out,
            "warnings   {} ({})",
            s.warning_total(),
            by_code.join(", ")
        )?;
    }
    if !machine.has_travel_limits() {
        writeln!(
            out,
            "travel     not checked: the machine has no travel limits (give --machine FILE)"
        )?;
    }
    Ok(())
}

/// `#101 (line 5), #24 (O9010.nc line 3)`: variables read but never set.
fn unset_text(s: &Summary) -> String {
    let parts: Vec<String> = s
        .unset_variables
        .iter()
        .map(|v| match &v.file {
            Some(f) => {
                let name = std::path::Path::new(&**f)
                    .file_name()
                    .map_or_else(|| f.to_string(), |n| n.to_string_lossy().into_owned());
                format!("{} ({name} line {})", v.name, v.line)
            }
            None => format!("{} (line {})", v.name, v.line),
        })
        .collect();
    format!("{} read but never set: {}", parts.len(), parts.join(", "))
}

/// The extents of `ext`, one axis after the other, in `units` (rotary
/// axes stay in degrees; a diameter axis shown as diameters).
pub fn extents_in(
    s: &Summary,
    (lo, hi): (Pos, Pos),
    diameter_axis: Option<u8>,
    units: DisplayUnits,
) -> String {
    let parts: Vec<String> = s
        .axis_letters()
        .iter()
        .enumerate()
        .filter(|(i, _)| s.reports_axis(*i))
        .map(|(i, l)| {
            let linear = matches!(l, b'X' | b'Y' | b'Z' | b'U' | b'V' | b'W');
            let show = |mm: f64| {
                if linear {
                    units.len(mm)
                } else {
                    format!("{mm:.3}")
                }
            };
            if diameter_axis == Some(*l) {
                format!(
                    "{} diameter {} .. {}",
                    char::from(*l),
                    show(2.0 * lo.get(i)),
                    show(2.0 * hi.get(i))
                )
            } else {
                format!(
                    "{} {} .. {}",
                    char::from(*l),
                    show(lo.get(i)),
                    show(hi.get(i))
                )
            }
        })
        .collect();
    parts.join("   ")
}
