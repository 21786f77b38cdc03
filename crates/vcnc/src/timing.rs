//! `vcnc time FILE…`: the cycle time of each program planned on the machine
//! model (`vcnc_planner`) and its split — cutting, rapid, dwell, tool
//! changes, spindle, settling into position, per tool and per program file
//! — as text or JSON lines; and the planned time that `vcnc check` prints
//! beside the distance/feed estimate.

use crate::cli::{TimeArgs, TimeFormat};
use crate::files::Input;
use std::io::Write;
use std::process::ExitCode;
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

/// `vcnc time`.
pub fn time(a: &TimeArgs) -> Result<ExitCode, String> {
    let mut worst = ExitCode::SUCCESS;
    let mut out = std::io::stdout().lock();
    let paths: Vec<&std::path::Path> = a.files.iter().map(std::path::PathBuf::as_path).collect();
    let s = crate::setup(&a.opts, &paths)?;
    for file in &a.files {
        let input = Input::from_arg(file)?;
        let profile = a
            .profile
            .map(ProfileShape::from)
            .unwrap_or(s.machine.motion.profile);
        let mut summary = Summary::new(&s.machine);
        let mut plan = planner(&s.machine, Some(profile));
        let (outcome, _) = crate::execute(&a.opts, &s, &input, &mut Tee(&mut summary, &mut plan))?;
        let t = plan.into_timeline();
        if let Outcome::Alarm(d) = &outcome {
            eprint!("{}", crate::render::diagnostic(d, &input));
            worst = ExitCode::from(1);
        }
        let name = input.name();
        let r = match a.format {
            TimeFormat::Text => text(&mut out, &name, &s.machine, profile, &t, &summary, &outcome),
            TimeFormat::Json => json(&mut out, &name, profile, &t, &summary, &outcome),
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

fn text(
    out: &mut impl Write,
    name: &str,
    machine: &Machine,
    profile: ProfileShape,
    t: &CycleTime,
    s: &Summary,
    outcome: &Outcome,
) -> std::io::Result<()> {
    writeln!(
        out,
        "program     {} ({}, {} profile)",
        name,
        machine.name,
        profile.as_str()
    )?;
    writeln!(out, "result      {}", result_text(outcome))?;
    writeln!(out, "total       {}", clock(t.total_s))?;
    writeln!(
        out,
        "cutting     {} over {:.3} mm",
        clock(t.cutting_s),
        t.cutting_mm
    )?;
    writeln!(
        out,
        "rapid       {} over {:.3} mm",
        clock(t.rapid_s),
        t.rapid_mm
    )?;
    writeln!(out, "dwell       {}", clock(t.dwell_s))?;
    writeln!(out, "tool change {}", clock(t.tool_change_s))?;
    writeln!(out, "spindle     {}", clock(t.spindle_s))?;
    writeln!(out, "in position {}", clock(t.in_position_s))?;
    let tools: Vec<String> = t
        .per_tool
        .iter()
        .map(|(tool, sec)| match tool {
            Some(n) => format!("T{n} {}", clock(*sec)),
            None => format!("no tool {}", clock(*sec)),
        })
        .collect();
    writeln!(out, "per tool    {}", tools.join(", "))?;
    let files: Vec<String> = t
        .per_file
        .iter()
        .map(|(f, sec)| format!("{} {}", f.as_deref().unwrap_or("main"), clock(*sec)))
        .collect();
    writeln!(out, "per file    {}", files.join(", "))?;
    writeln!(
        out,
        "dist/feed   {} (no acceleration)",
        clock(s.cycle_time_s)
    )?;
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
    writeln!(
        out,
        "{{\"file\":{},\"result\":{}{alarm},\"profile\":\"{}\",\"total_s\":{},\"cutting_s\":{},\
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

/// `12.345 s` below a minute, `1:02:03.4 (3723.4 s)` above.
pub fn clock(seconds: f64) -> String {
    if seconds < 60.0 {
        return format!("{seconds:.3} s");
    }
    // Tenths of a finite, positive time below 2^53, rounded as the
    // figure in parentheses is (119.96 s is 2:00.0, never 1:59.9).
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let all = (seconds * 10.0).round().min(9.0e15) as u64;
    let (h, m, s, tenths) = (all / 36_000, all / 600 % 60, all / 10 % 60, all % 10);
    if h > 0 {
        format!("{h}:{m:02}:{s:02}.{tenths} ({seconds:.1} s)")
    } else {
        format!("{m}:{s:02}.{tenths} ({seconds:.1} s)")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn clock_rounds_like_its_seconds() {
        assert_eq!(super::clock(119.96), "2:00.0 (120.0 s)");
        assert_eq!(super::clock(3725.26), "1:02:05.3 (3725.3 s)");
        assert_eq!(super::clock(12.3456), "12.346 s");
    }
}
