//! `vcnc check`: one program in detail, or many in parallel with one line
//! each; text, JSON or SARIF reports.
//!
//! ```text
//!   paths ─▶ programs (files; directories walked; `-` = stdin)
//!        ─▶ rayon: one interpreter per program, a Summary sink each
//!        ─▶ results in path order ─▶ text | json | sarif ─▶ exit code
//! ```
//!
//! Programs are independent, so they are checked on all cores; each run
//! streams its file as `run` does, so memory is one summary per program.

use crate::choose::{Choice, Setup};
use crate::cli::{CheckArgs, CheckFormat};
use crate::files::{self, Input};
use crate::offload::Offload;
use crate::{execute, render, timing};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde_json::{Value, json};
use std::io::{IsTerminal, Write};
use std::process::ExitCode;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use vcnc_interp::{Outcome, Pos};
use vcnc_output::Summary;
use vcnc_planner::CycleTime;
use vcnc_syntax::{Code, Diagnostic};

/// One program's result.
struct Checked {
    input: Input,
    /// `Err`: the program could not be read at all.
    run: Result<Ran, String>,
}

/// The dialect and machine a program ran on, and why.
struct Chosen {
    dialect: &'static str,
    /// `haas (auto: G187, …)`.
    text: String,
    evidence: Vec<String>,
    confidence: &'static str,
    doubtful: bool,
    machine: String,
}

impl Chosen {
    fn of(s: &Setup) -> Chosen {
        Chosen {
            dialect: s.dialect.name,
            text: s.dialect_text(),
            evidence: s.evidence(),
            confidence: s.confidence(),
            doubtful: s.doubtful(),
            machine: s.machine.name.clone(),
        }
    }
}

struct Ran {
    chosen: Chosen,
    outcome: Outcome,
    summary: Summary,
    /// The cycle time planned on the machine model.
    planned: CycleTime,
    diameter: bool,
    /// The material-removal simulation (`--stock`).
    sim: Option<crate::sim::CheckSim>,
}

impl Checked {
    fn alarm(&self) -> Option<&Diagnostic> {
        match &self.run {
            Ok(Ran {
                outcome: Outcome::Alarm(d),
                ..
            }) => Some(d),
            _ => None,
        }
    }

    fn warnings(&self) -> u64 {
        self.run.as_ref().map_or(0, |r| r.summary.warning_total())
    }

    fn crashed(&self) -> bool {
        self.run
            .as_ref()
            .is_ok_and(|r| r.sim.as_ref().is_some_and(crate::sim::CheckSim::crashed))
    }
}

/// Runs the check and reports it.
pub fn check(args: &CheckArgs) -> Result<ExitCode, String> {
    let choice = Choice::new(&args.opts)?;
    let (inputs, single_file) = files::inputs(&args.paths)?;
    if single_file
        && args.format == CheckFormat::Text
        && let Some(input) = inputs.first()
    {
        return detailed(args, &choice, input);
    }
    let results = check_all(args, &choice, inputs)?;
    let mut out = std::io::stdout().lock();
    let written = match args.format {
        CheckFormat::Text => text_report(&mut out, &results, !choice.is_forced()),
        CheckFormat::Json => {
            let doc = json_report(args, &choice, &results);
            writeln!(out, "{doc:#}")
        }
        CheckFormat::Sarif => {
            let doc = sarif_report(&results);
            writeln!(out, "{doc:#}")
        }
    };
    crate::reported(written)?;
    if results.iter().any(|r| r.run.is_err()) {
        return Ok(ExitCode::from(2));
    }
    let alarms = results.iter().any(|r| r.alarm().is_some() || r.crashed());
    let warned = results.iter().any(|r| r.warnings() > 0);
    Ok(if alarms || (args.deny_warnings && warned) {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// One program: the summary block, warnings and the alarm on stderr.
fn detailed(args: &CheckArgs, choice: &Choice, input: &Input) -> Result<ExitCode, String> {
    let s = &choice.setup(input)?;
    // One program: the summary and the planner on the second core.
    let machine = s.machine;
    let mut beside =
        Offload::start(|| timing::Tee(Summary::new(machine), timing::planner(machine, None)));
    let (outcome, diameter) = execute(&args.opts, s, input, &mut beside)?;
    let timing::Tee(summary, plan) = beside.join()?;
    let planned = plan.into_timeline();
    eprint!("{}", render::warnings(&summary, input));
    if args.opts.keep_going {
        // Every alarm the run went on after, in program order.
        for d in &summary.alarms {
            eprint!("{}", render::diagnostic(d, input));
        }
    } else if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, input));
    }
    let mut out = std::io::stdout().lock();
    let diameter_axis = s.dialect.diameter.axis.filter(|_| diameter);
    crate::reported(render::summary(
        &mut out,
        &input.name(),
        s,
        (&summary, &planned),
        &outcome,
        (
            diameter_axis,
            args.opts
                .units
                .map_or(vcnc_core::display::DisplayUnits::Mm, Into::into),
        ),
    ))?;
    let mut crashed = false;
    if let Some(stock) = &args.stock {
        let sim = crate::sim::for_check(&args.opts, s, input, stock)?;
        crate::reported(sim.write(&mut out, input))?;
        crashed = sim.crashed();
    }
    let denied = args.deny_warnings && summary.warning_total() > 0;
    Ok(crate::exit_code(&outcome, denied || crashed))
}

/// Checks every program on the thread pool, in input order; each gets
/// its own dialect and machine.
fn check_all(
    args: &CheckArgs,
    choice: &Choice,
    inputs: Vec<Input>,
) -> Result<Vec<Checked>, String> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(n) = args.jobs {
        pool = pool.num_threads(n.max(1));
    }
    let pool = pool
        .build()
        .map_err(|e| format!("cannot start threads: {e}"))?;
    let progress = Progress::new(inputs.len());
    if args.opts.variables.is_some() {
        // One variable memory, as on the control: the programs run one
        // after the other in input order, each reading the kept variables
        // the one before wrote (never two writers of the file at once).
        let results = inputs
            .into_iter()
            .map(|input| {
                let run = choice
                    .setup(&input)
                    .and_then(|s| check_one(args, &s, &input));
                progress.tick();
                Checked { input, run }
            })
            .collect();
        progress.done();
        return Ok(results);
    }
    let results = pool.install(|| {
        inputs
            .into_par_iter()
            .map(|input| {
                let run = choice
                    .setup(&input)
                    .and_then(|s| check_one(args, &s, &input));
                progress.tick();
                Checked { input, run }
            })
            .collect()
    });
    progress.done();
    Ok(results)
}

/// One program of many.
fn check_one(args: &CheckArgs, s: &Setup, input: &Input) -> Result<Ran, String> {
    let mut summary = Summary::new(s.machine);
    let mut plan = timing::planner(s.machine, None);
    let sink = &mut timing::Tee(&mut summary, &mut plan);
    let (outcome, diameter) = execute(&args.opts, s, input, sink)?;
    let sim = match &args.stock {
        Some(stock) => Some(crate::sim::for_check(&args.opts, s, input, stock)?),
        None => None,
    };
    Ok(Ran {
        chosen: Chosen::of(s),
        outcome,
        summary,
        planned: plan.into_timeline(),
        diameter,
        sim,
    })
}

/// A progress bar on a terminal, shown once the check has taken a second.
struct Progress {
    start: Instant,
    total: usize,
    state: Mutex<(usize, Option<ProgressBar>)>,
    terminal: bool,
}

impl Progress {
    fn new(total: usize) -> Progress {
        Progress {
            start: Instant::now(),
            total,
            state: Mutex::new((0, None)),
            terminal: std::io::stderr().is_terminal(),
        }
    }

    fn tick(&self) {
        if !self.terminal {
            return;
        }
        let Ok(mut state) = self.state.lock() else {
            return;
        };
        state.0 += 1;
        if state.1.is_none() && self.start.elapsed() > Duration::from_secs(1) {
            let bar = ProgressBar::new(self.total as u64);
            if let Ok(style) =
                ProgressStyle::with_template("{bar:40} {pos}/{len} programs, {eta} left")
            {
                bar.set_style(style);
            }
            state.1 = Some(bar);
        }
        let done = state.0 as u64;
        if let Some(bar) = &state.1 {
            bar.set_position(done);
        }
    }

    fn done(&self) {
        if let Ok(state) = self.state.lock()
            && let Some(bar) = &state.1
        {
            bar.finish_and_clear();
        }
    }
}

/// One line per program (with its dialect when each was detected: `[grbl]`,
/// `[grbl?]` when unsure), then the totals.
fn text_report(out: &mut impl Write, results: &[Checked], detected: bool) -> std::io::Result<()> {
    let (mut ended, mut alarms, mut warned, mut warnings, mut unreadable) = (0, 0, 0, 0u64, 0);
    for r in results {
        let ran = match &r.run {
            Ok(ran) => ran,
            Err(e) => {
                unreadable += 1;
                writeln!(
                    out,
                    "{}: error: {}",
                    crate::render::visible(&r.input.name()),
                    crate::render::visible(&e.to_string())
                )?;
                continue;
            }
        };
        let name = if detected {
            let doubt = if ran.chosen.doubtful { "?" } else { "" };
            format!("{} [{}{doubt}]", r.input.name(), ran.chosen.dialect)
        } else {
            r.input.name()
        };
        let w = ran.summary.warning_total();
        warnings += w;
        warned += usize::from(w > 0);
        let warn_text = match w {
            0 => String::new(),
            1 => ", 1 warning".to_string(),
            n => format!(", {n} warnings"),
        };
        match &ran.outcome {
            Outcome::Alarm(d) => {
                alarms += 1;
                let place = d
                    .file
                    .as_deref()
                    .map_or(String::new(), |f| format!(" in {f}"));
                writeln!(
                    out,
                    "{name}: alarm {} at line {}, column {}{place}: {}{warn_text}",
                    d.code.as_str(),
                    d.line,
                    d.column,
                    d.message
                )?;
            }
            Outcome::Ended(code) => {
                ended += 1;
                writeln!(
                    out,
                    "{name}: ended by {}, {}{warn_text}",
                    code.as_str(),
                    render::duration(ran.planned.total_s)
                )?;
            }
            Outcome::Stopped => writeln!(out, "{name}: stopped{warn_text}")?,
        }
    }
    write!(
        out,
        "{} programs: {ended} ran to the end, {alarms} stopped by an alarm, {warned} with warnings ({warnings} in all)",
        results.len()
    )?;
    if unreadable > 0 {
        write!(out, ", {unreadable} unreadable")?;
    }
    writeln!(out)
}

fn diagnostic_json(d: &Diagnostic) -> Value {
    let mut v = json!({
        "code": d.code.as_str(),
        "line": d.line,
        "column": d.column,
        "message": d.message,
        "help": d.help,
    });
    if let (Some(file), Some(obj)) = (&d.file, v.as_object_mut()) {
        obj.insert("file".into(), json!(file));
    }
    v
}

fn pos_json(s: &Summary, p: &Pos) -> Value {
    let mut m = serde_json::Map::new();
    for (i, l) in s.axis_letters().iter().enumerate() {
        if s.reports_axis(i) {
            m.insert(
                char::from(l.to_ascii_lowercase()).to_string(),
                json!(p.get(i)),
            );
        }
    }
    Value::Object(m)
}

fn summary_json(s: &Summary, planned: &CycleTime, diameter: bool) -> Value {
    let holes: u64 = s.holes.iter().map(|(_, n)| n).sum();
    json!({
        "cycle_time_s": planned.total_s,
        "distance_feed_s": s.cycle_time_s,
        "rapid_mm": s.rapid_mm,
        "cut_mm": s.cut_mm,
        "extents": s.extents.map(|(lo, hi)| json!({"min": pos_json(s, &lo), "max": pos_json(s, &hi)})),
        "work_extents": s.work_extents().map(|(lo, hi)| json!({"min": pos_json(s, &lo), "max": pos_json(s, &hi)})),
        "tools": s.tools,
        "holes": holes,
        "spindle_rpm": s.spindle_rpm.map(|(lo, hi)| json!([lo, hi])),
        "waits": s.waits,
        "diameter_programming": diameter,
        "unset_variables": s.unset_variables.iter().map(|v| json!({
            "name": &*v.name,
            "line": v.line,
            "file": v.file.as_deref(),
        })).collect::<Vec<_>>(),
    })
}

/// The JSON report: one document (docs/cli.md).
fn json_report(args: &CheckArgs, choice: &Choice, results: &[Checked]) -> Value {
    let files: Vec<Value> = results
        .iter()
        .map(|r| {
            let mut v = json!({ "path": r.input.name() });
            let Some(obj) = v.as_object_mut() else {
                return v;
            };
            match &r.run {
                Err(e) => {
                    obj.insert("result".into(), json!("error"));
                    obj.insert("error".into(), json!(e));
                }
                Ok(ran) => {
                    let (result, end) = match &ran.outcome {
                        Outcome::Ended(code) => ("ended", Some(code.as_str())),
                        Outcome::Alarm(_) => ("alarm", None),
                        Outcome::Stopped => ("stopped", None),
                    };
                    obj.insert("dialect".into(), json!(ran.chosen.dialect));
                    obj.insert("dialect_evidence".into(), json!(ran.chosen.evidence));
                    obj.insert("dialect_confidence".into(), json!(ran.chosen.confidence));
                    obj.insert("machine".into(), json!(ran.chosen.machine));
                    obj.insert("result".into(), json!(result));
                    obj.insert("end".into(), json!(end));
                    obj.insert("alarm".into(), json!(r.alarm().map(diagnostic_json)));
                    let warnings: Vec<Value> =
                        ran.summary.warnings.iter().map(diagnostic_json).collect();
                    obj.insert("warnings".into(), json!(warnings));
                    obj.insert("warning_count".into(), json!(ran.summary.warning_total()));
                    obj.insert(
                        "summary".into(),
                        summary_json(&ran.summary, &ran.planned, ran.diameter),
                    );
                    if let Some(sim) = &ran.sim {
                        obj.insert("sim".into(), sim.json());
                    }
                }
            }
            v
        })
        .collect();
    let count = |f: &dyn Fn(&Checked) -> bool| results.iter().filter(|r| f(r)).count();
    let dialect = match &args.opts.dialect {
        Some(d) if choice.is_forced() => d.to_ascii_lowercase(),
        _ => crate::choose::AUTO.to_string(),
    };
    let machine = match choice.machine_name() {
        Some(m) => m.to_string(),
        None => crate::choose::AUTO.to_string(),
    };
    json!({
        "version": 1,
        "dialect": dialect,
        "machine": machine,
        "deny_warnings": args.deny_warnings,
        "files": files,
        "totals": {
            "programs": results.len(),
            "ended": count(&|r| matches!(r.run, Ok(Ran { outcome: Outcome::Ended(_), .. }))),
            "alarms": count(&|r| r.alarm().is_some()),
            "with_warnings": count(&|r| r.warnings() > 0),
            "warnings": results.iter().map(Checked::warnings).sum::<u64>(),
            "unreadable": count(&|r| r.run.is_err()),
        },
    })
}

/// A path as a SARIF artifact URI reference (relative paths stay
/// relative): `/` separators, and every byte but the unreserved characters
/// of RFC 3986 and `/` percent-encoded (`my part.nc` → `my%20part.nc`).
fn uri(name: &str) -> String {
    let mut out = String::with_capacity(name.len());
    for b in name.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/".contains(&b) {
            out.push(char::from(b));
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

fn sarif_result(d: &Diagnostic, main: &str) -> Value {
    let file = d.file.as_deref().map_or_else(|| uri(main), uri);
    json!({
        "ruleId": d.code.as_str(),
        "level": if d.code.is_warning() { "warning" } else { "error" },
        "message": { "text": format!("{} ({})", d.message, d.help) },
        "locations": [{
            "physicalLocation": {
                "artifactLocation": { "uri": file },
                "region": { "startLine": d.line.max(1), "startColumn": d.column.max(1) },
            }
        }],
    })
}

/// SARIF 2.1.0: one run, a rule per code used, a result per alarm and
/// warning.
fn sarif_report(results: &[Checked]) -> Value {
    let mut used: Vec<Code> = Vec::new();
    let mut out = Vec::new();
    let mut artifacts = Vec::new();
    for r in results {
        let name = r.input.name();
        let Ok(ran) = &r.run else {
            continue;
        };
        artifacts.push(json!({
            "location": { "uri": uri(&name) },
            "properties": {
                "dialect": ran.chosen.dialect,
                "dialectEvidence": ran.chosen.evidence,
                "dialectConfidence": ran.chosen.confidence,
                "dialectText": ran.chosen.text,
            },
        }));
        for d in ran.summary.warnings.iter().chain(r.alarm()) {
            used.push(d.code);
            out.push(sarif_result(d, &name));
        }
    }
    used.sort();
    used.dedup();
    let rules: Vec<Value> = used
        .iter()
        .map(|c| {
            json!({
                "id": c.as_str(),
                "shortDescription": { "text": c.title() },
                "helpUri": "https://github.com/vcnc/vcnc/blob/main/docs/alarms.md",
            })
        })
        .collect();
    json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": {
                "driver": {
                    "name": "vcnc",
                    "version": env!("CARGO_PKG_VERSION"),
                    "informationUri": "https://github.com/vcnc/vcnc",
                    "rules": rules,
                }
            },
            "artifacts": artifacts,
            "results": out,
        }],
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn sarif_uris_are_percent_encoded() {
        assert_eq!(super::uri("parts\\my part#2.nc"), "parts/my%20part%232.nc");
        assert_eq!(super::uri("é.nc"), "%C3%A9.nc");
    }
}
