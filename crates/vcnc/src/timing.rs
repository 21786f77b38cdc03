//! `vcnc time PATH…`: the cycle time of each program (directories walked as
//! `check` walks them) planned on the machine model (`vcnc_planner`) and
//! its split — cutting, rapid, dwell, tool changes, spindle, settling into
//! position, per tool and per program file — as text or JSON lines; and
//! the planned time that `vcnc check` prints beside the distance/feed
//! estimate, in the same format (`vcnc_core::display::duration`).

use crate::choose::{Choice, Setup};
use crate::cli::{TimeArgs, TimeFormat};
use crate::files;
use std::io::Write;
use std::process::ExitCode;
use vcnc_core::display::{DisplayUnits, duration};
use vcnc_interp::{Event, Machine, Outcome, Sink};
use vcnc_output::Summary;
use vcnc_planner::{CycleTime, Planner, ProfileShape};

/// Sends every event to two sinks.
pub struct Tee<A, B>(pub A, pub B);

impl<A: Sink, B: Sink> Sink for Tee<A, B> {
    fn event(&mut self, event: &Event) {
        self.0.event(event);
        self.1.event(event);
    }
    fn is_done(&self) -> bool {
        self.0.is_done() || self.1.is_done()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}

/// The planner `check` and `time` run: the machine's own profile unless
/// one is asked for.
pub fn planner(machine: &Machine, profile: Option<ProfileShape>) -> Planner<CycleTime> {
    let shape = profile.unwrap_or(machine.motion.profile);
    Planner::with_profile(machine, shape, CycleTime::new())
}

/// `vcnc time`: each program (directories walked as `check` walks them)
/// on its own dialect and machine.
pub fn time(a: &TimeArgs) -> Result<ExitCode, String> {
    let mut worst = ExitCode::SUCCESS;
    let mut out = std::io::stdout().lock();
    let choice = Choice::new(&a.opts)?;
    let (inputs, _) = files::inputs(&a.files)?;
    for (n, input) in inputs.iter().enumerate() {
        let s = choice.setup(input)?;
        let profile = a
            .profile
            .map(ProfileShape::from)
            .unwrap_or(s.machine.motion.profile);
        let mut summary = Summary::new(s.machine);
        let mut plan = planner(s.machine, Some(profile));
        let (outcome, _) = crate::execute(&a.opts, &s, input, &mut Tee(&mut summary, &mut plan))?;
        let t = plan.into_timeline();
        if let Outcome::Alarm(d) = &outcome {
            eprint!("{}", crate::render::diagnostic(d, input));
            worst = ExitCode::from(1);
        }
        let name = input.name();
        let r = match a.format {
            TimeFormat::Text => {
                let gap = if n > 0 { "\n" } else { "" };
                write!(out, "{gap}").and_then(|()| {
                    let report = Report {
                        name: &name,
                        setup: &s,
                        profile,
                        t: &t,
                        summary: &summary,
                    };
                    text(
                        &mut out,
                        &report,
                        &outcome,
                        a.opts
                            .units
                            .map_or(vcnc_core::display::DisplayUnits::Mm, Into::into),
                    )
                })
            }
            TimeFormat::Json => json(&mut out, &name, &s, profile, &t, &summary, &outcome),
        };
        match r {
            Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => return Ok(worst),
            r => r.map_err(|e| e.to_string())?,
        }
    }
    Ok(worst)
}

fn result_text(o: &Outcome) -> String {
    match o {
        Outcome::Ended(code) => format!("ended by {}", code.as_str()),
        Outcome::Stopped => "stopped".into(),
        Outcome::Alarm(d) => format!("alarm {} at line {}", d.code.as_str(), d.line),
    }
}

/// What one program's text report shows.
struct Report<'a> {
    name: &'a str,
    setup: &'a Setup<'a>,
    profile: ProfileShape,
    t: &'a CycleTime,
    summary: &'a Summary,
}

/// The text report: the planned time first and the distance/feed estimate
/// second, in `check`'s format, then the split.
fn text(
    out: &mut impl Write,
    r: &Report<'_>,
    outcome: &Outcome,
    units: DisplayUnits,
) -> std::io::Result<()> {
    let (t, s) = (r.t, r.summary);
    writeln!(
        out,
        "program     {} ({}, {} profile)",
        r.name,
        r.setup.machine.name,
        r.profile.as_str()
    )?;
    writeln!(out, "dialect     {}", r.setup.dialect_text())?;
    writeln!(out, "result      {}", result_text(outcome))?;
    writeln!(out, "cycle time  {} (planned)", duration(t.total_s))?;
    writeln!(
        out,
        "dist/feed   {} (distance/feed estimate, no acceleration)",
        duration(s.cycle_time_s)
    )?;
    let unit = units.name();
    writeln!(
        out,
        "cutting     {} over {} {unit}",
        duration(t.cutting_s),
        units.len(t.cutting_mm)
    )?;
    writeln!(
        out,
        "rapid       {} over {} {unit}",
        duration(t.rapid_s),
        units.len(t.rapid_mm)
    )?;
    writeln!(out, "dwell       {}", duration(t.dwell_s))?;
    writeln!(out, "tool change {}", duration(t.tool_change_s))?;
    writeln!(out, "spindle     {}", duration(t.spindle_s))?;
    writeln!(out, "in position {}", duration(t.in_position_s))?;
    let tools: Vec<String> = t
        .per_tool
        .iter()
        .map(|(tool, sec)| match tool {
            Some(n) => format!("T{n} {}", duration(*sec)),
            None => format!("no tool {}", duration(*sec)),
        })
        .collect();
    writeln!(out, "per tool    {}", tools.join(", "))?;
    let files: Vec<String> = t
        .per_file
        .iter()
        .map(|(f, sec)| format!("{} {}", f.as_deref().unwrap_or("main"), duration(*sec)))
        .collect();
    writeln!(out, "per file    {}", files.join(", "))?;
    if t.untimed_moves > 0 {
        writeln!(
            out,
            "untimed     {} moves (feed per revolution with the spindle stopped)",
            t.untimed_moves
        )?;
    }
    Ok(())
}

fn json(
    out: &mut impl Write,
    name: &str,
    setup: &Setup,
    profile: ProfileShape,
    t: &CycleTime,
    s: &Summary,
    outcome: &Outcome,
) -> std::io::Result<()> {
    let tools: Vec<String> = t
        .per_tool
        .iter()
        .map(|(tool, sec)| {
            let tool = tool.map_or("null".to_string(), |n| n.to_string());
            format!("{{\"tool\":{tool},\"seconds\":{}}}", num(*sec))
        })
        .collect();
    let files: Vec<String> = t
        .per_file
        .iter()
        .map(|(f, sec)| {
            let f = f.as_deref().map_or("null".to_string(), json_str);
            format!("{{\"file\":{f},\"seconds\":{}}}", num(*sec))
        })
        .collect();
    let (result, alarm) = match outcome {
        Outcome::Ended(code) => (code.as_str().to_string(), None),
        Outcome::Stopped => ("stopped".to_string(), None),
        Outcome::Alarm(d) => ("alarm".to_string(), Some(d.code.as_str())),
    };
    let alarm = alarm.map_or(String::new(), |a| format!(",\"alarm\":{}", json_str(a)));
    let evidence: Vec<String> = setup.evidence().iter().map(|e| json_str(e)).collect();
    let dialect = format!(
        ",\"dialect\":{},\"dialect_evidence\":[{}],\"dialect_confidence\":\"{}\"",
        json_str(setup.dialect.name),
        evidence.join(","),
        setup.confidence()
    );
    writeln!(
        out,
        "{{\"file\":{}{dialect},\"result\":{}{alarm},\"profile\":\"{}\",\"total_s\":{},\"cutting_s\":{},\
         \"rapid_s\":{},\"dwell_s\":{},\"tool_change_s\":{},\"spindle_s\":{},\
         \"in_position_s\":{},\"cutting_mm\":{},\"rapid_mm\":{},\"distance_feed_s\":{},\
         \"untimed_moves\":{},\"per_tool\":[{}],\"per_file\":[{}]}}",
        json_str(name),
        json_str(&result),
        profile.as_str(),
        num(t.total_s),
        num(t.cutting_s),
        num(t.rapid_s),
        num(t.dwell_s),
        num(t.tool_change_s),
        num(t.spindle_s),
        num(t.in_position_s),
        num(t.cutting_mm),
        num(t.rapid_mm),
        num(s.cycle_time_s),
        t.untimed_moves,
        tools.join(","),
        files.join(",")
    )
}

/// A number rounded to a microsecond / nanometre, shortest form.
fn num(v: f64) -> String {
    let r = (v * 1e6).round() / 1e6;
    if r.is_finite() {
        format!("{r}")
    } else {
        "null".into()
    }
}

fn json_str(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if u32::from(c) < 0x20 => out.push_str(&format!("\\u{:04x}", u32::from(c))),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
