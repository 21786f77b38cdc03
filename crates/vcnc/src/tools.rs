//! `vcnc tools FILE`: the tools a program uses and where every figure about
//! them comes from.
//!
//! ```text
//!   program ─▶ run (tool_change events: which tools, from which line)
//!   program text ─▶ tooling::from_comments (CAM header shapes)
//!   --tools FILE ─▶ tooling::read_table (shapes and offsets, in setup)
//!   machine (built-in, file, $$ dump, filled by the table) ─▶ registers
//! ```
//!
//! A tool's shape comes from the tool table, else from the program's
//! comments, else it is not described (plots and the simulation then assume
//! [`ToolShape::assumed`]). Its offset registers (the same number: H n and
//! D n, a lathe's register n) come from the table, the machine file, or the
//! built-in machine, whose offset memory is empty.

use crate::cli::{TimeFormat, ToolsArgs};
use crate::files::Input;
use crate::{MachineFrom, Setup, execute, read_prefix, render, reported};
use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::io::Write;
use std::process::ExitCode;
use vcnc_core::display::DisplayUnits;
use vcnc_core::tooling::{self, ToolKind, ToolLibrary, ToolShape, ToolSource};
use vcnc_interp::{Event, Outcome, Sink};

/// How much of a program `from_comments` reads.
const COMMENTS_READ: u64 = 64 << 20;

/// Where a tool is changed to: its first line and how many changes.
#[derive(Default)]
struct Uses {
    first: BTreeMap<u32, (u64, u32)>,
}

impl Sink for Uses {
    fn event(&mut self, e: &Event) {
        if let Event::ToolChange { loc, tool } = e {
            let entry = self.first.entry(*tool).or_insert((loc.line, 0));
            entry.1 = entry.1.saturating_add(1);
        }
    }
}

/// Runs `vcnc tools`.
pub fn tools(args: &ToolsArgs) -> Result<ExitCode, String> {
    let input = Input::from_arg(&args.file)?;
    let choice = crate::choose::Choice::new(&args.opts)?;
    let s = choice.setup(&input)?;
    // The comments are read from the program's first 64 MiB (the header
    // lists are at the top; a program of hundreds of MiB is not held).
    let text = match &input {
        Input::File(p) => read_prefix(p, "program", COMMENTS_READ)?,
        Input::Stdin(bytes) => {
            let end = bytes
                .len()
                .min(usize::try_from(COMMENTS_READ).unwrap_or(usize::MAX));
            String::from_utf8_lossy(bytes.get(..end).unwrap_or_default()).into_owned()
        }
    };
    let comments = tooling::from_comments(&text);
    let mut uses = Uses::default();
    let (outcome, _) = execute(&args.opts, &s, &input, &mut uses)?;
    let report = Report {
        s: &s,
        comments: &comments,
        uses: &uses,
        units: args.opts.units.map(Into::into).unwrap_or_default(),
    };
    let out = match args.format {
        TimeFormat::Text => report.text(&input),
        TimeFormat::Json => format!("{:#}\n", report.json(&input)),
    };
    reported(std::io::stdout().write_all(out.as_bytes()))?;
    if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, &input));
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

struct Report<'a> {
    s: &'a Setup<'a>,
    comments: &'a ToolLibrary,
    uses: &'a Uses,
    units: DisplayUnits,
}

impl Report<'_> {
    /// Every tool to list: those used, then those described but not used.
    fn numbers(&self) -> Vec<u32> {
        let mut n: Vec<u32> = self.uses.first.keys().copied().collect();
        let described = self
            .comments
            .tools
            .keys()
            .chain(self.s.table.iter().flat_map(|(lib, _)| lib.tools.keys()));
        for t in described {
            if !n.contains(t) {
                n.push(*t);
            }
        }
        n
    }

    /// The shape of tool `n`: the table's, else the comments'.
    fn shape(&self, n: u32) -> Option<&ToolShape> {
        self.s
            .table
            .as_ref()
            .and_then(|(lib, _)| lib.get(n))
            .or_else(|| self.comments.get(n))
    }

    fn lathe(&self) -> bool {
        self.s.dialect.diameter.lathe
    }

    /// Where register `n`'s values come from.
    fn registers_from(&self, n: u32) -> String {
        if let Some((file, o)) =
            (self.s.table.as_ref()).and_then(|(lib, file)| lib.offsets.get(&n).map(|o| (file, o)))
        {
            return format!("{file} line {}", o.line);
        }
        let listed = self.s.machine.tools.contains_key(&n);
        match &self.s.machine_from {
            MachineFrom::BuiltIn => "the built-in machine, whose offset memory is empty".into(),
            MachineFrom::File(f) if listed => format!("machine file {f}"),
            MachineFrom::File(f) => format!("machine file {f}, which does not list it"),
            MachineFrom::GrblSettings(f) => format!("grbl settings {f}, which hold no offsets"),
        }
    }

    fn len(&self, mm: f64) -> String {
        format!("{} {}", self.units.len(mm), self.units.name())
    }

    fn registers_text(&self, n: u32) -> String {
        let r = self.s.machine.tools.get(&n).copied().unwrap_or_default();
        if self.lathe() {
            format!(
                "X {}, Z {}, nose R {}, tip {}",
                self.len(r.x_mm + r.x_wear_mm),
                self.len(r.z_mm + r.z_wear_mm),
                self.len(r.nose_radius_mm + r.nose_radius_wear_mm),
                r.tip
            )
        } else {
            format!(
                "H{n} {}, D{n} {} (radius)",
                self.len(r.h_mm + r.h_wear_mm),
                self.len(r.d_mm + r.d_wear_mm)
            )
        }
    }

    fn shape_text(&self, t: &ToolShape) -> String {
        let d = self.len(t.diameter_mm);
        let mut s = match t.kind {
            ToolKind::Flat => format!("flat end mill, diameter {d}"),
            ToolKind::Ball => format!("ball end mill, diameter {d}"),
            ToolKind::Bull { corner_radius_mm } => format!(
                "bull-nose end mill, diameter {d}, corner radius {}",
                self.len(corner_radius_mm)
            ),
            ToolKind::Drill { point_angle_deg } => {
                format!("drill, diameter {d}, {point_angle_deg}° point")
            }
            ToolKind::Vee {
                included_angle_deg,
                tip_diameter_mm,
            } => {
                let mut v = format!("V cutter {included_angle_deg}°");
                if t.diameter_mm > 0.0 {
                    v.push_str(&format!(", diameter {d}"));
                }
                if tip_diameter_mm > 0.0 {
                    v.push_str(&format!(", tip {}", self.len(tip_diameter_mm)));
                }
                v
            }
            ToolKind::Turning {
                nose_radius_mm,
                tip,
            } => format!(
                "turning tool, nose radius {}, tip {tip}",
                self.len(nose_radius_mm)
            ),
        };
        for (what, v) in [
            ("flutes", t.flute_length_mm),
            ("length", t.length_mm),
            ("shank", t.shank_diameter_mm),
            ("holder", t.holder_diameter_mm),
            ("stickout", t.stickout_mm),
        ] {
            if let Some(v) = v {
                s.push_str(&format!(", {what} {}", self.len(v)));
            }
        }
        s
    }

    fn text(&self, input: &Input) -> String {
        let s = self.s;
        let mut out = format!("program    {} ({} dialect)\n", input.name(), s.dialect.name);
        out.push_str(&match &s.table {
            Some((lib, file)) => format!(
                "tool table {file}: {} tools, their shapes and registers\n",
                lib.tools.len()
            ),
            None => "tool table none (--tools FILE): shapes from the program's comments, which never fill registers\n".into(),
        });
        let numbers = self.numbers();
        if numbers.is_empty() {
            out.push_str(
                "tools      none: the program changes no tool and its comments describe none\n",
            );
        }
        for n in numbers {
            out.push_str(&format!("\nT{n}\n"));
            out.push_str(&match self.uses.first.get(&n) {
                Some((line, 1)) => format!("  used     tool change on line {line}\n"),
                Some((line, k)) => {
                    format!(
                        "  used     tool change on line {line} (and {} more)\n",
                        k - 1
                    )
                }
                None if n == 0 => {
                    "  used     the tool in the spindle: the program changes no tool\n".into()
                }
                None => "  used     no: described, never changed to\n".into(),
            });
            out.push_str(&match self.shape(n) {
                Some(t) => format!(
                    "  shape    {}\n  from     {}\n",
                    self.shape_text(t),
                    source_text(t)
                ),
                None => format!(
                    "  shape    not described: plots and simulation assume a {} mm flat end mill\n",
                    ToolShape::assumed(n).diameter_mm
                ),
            });
            if n != 0 {
                out.push_str(&format!(
                    "  offsets  {}: {}\n",
                    self.registers_text(n),
                    self.registers_from(n)
                ));
            }
        }
        out
    }

    fn json(&self, input: &Input) -> Value {
        let tools: Vec<Value> = self
            .numbers()
            .into_iter()
            .map(|n| {
                let r = self.s.machine.tools.get(&n).copied().unwrap_or_default();
                let registers = if self.lathe() {
                    json!({"x_mm": nm(r.x_mm + r.x_wear_mm), "z_mm": nm(r.z_mm + r.z_wear_mm),
                           "nose_radius_mm": nm(r.nose_radius_mm + r.nose_radius_wear_mm), "tip": r.tip})
                } else {
                    json!({"h_mm": nm(r.h_mm + r.h_wear_mm), "d_mm": nm(r.d_mm + r.d_wear_mm)})
                };
                json!({
                    "tool": n,
                    "first_change_line": self.uses.first.get(&n).map(|u| u.0),
                    "changes": self.uses.first.get(&n).map_or(0, |u| u.1),
                    "shape": self.shape(n).map(shape_json),
                    "registers": registers,
                    "registers_from": self.registers_from(n),
                })
            })
            .collect();
        json!({
            "program": input.name(),
            "dialect": self.s.dialect.name,
            "tool_table": self.s.table.as_ref().map(|(_, f)| f),
            "tools": tools,
        })
    }
}

/// Where a shape came from, for people.
fn source_text(t: &ToolShape) -> String {
    match &t.source {
        ToolSource::Table { file, line } => format!("tool table {file} line {line}"),
        ToolSource::Comment { post, line } => {
            let what = if t.description.is_empty() {
                String::new()
            } else {
                format!(": \"{}\"", t.description)
            };
            format!(
                "comment on line {line}, written by {}{what}",
                post_name(post)
            )
        }
        ToolSource::Registers => "the machine's offset registers".into(),
        ToolSource::Assumed => "nothing: assumed".into(),
    }
}

/// The CAM system behind a comment format.
fn post_name(post: &str) -> &str {
    match post {
        "fusion" => "a Fusion 360/HSM post",
        "mastercam" => "a Mastercam post",
        "solidcam" => "a SolidCAM post",
        "vectric" => "Vectric",
        "estlcam" => "Estlcam",
        "cutviewer" => "a CutViewer TOOL/MILL line (Carbide Create)",
        "name" => "a tool name",
        other => other,
    }
}

/// A length for JSON: to the nanometre, as every vcnc output rounds.
fn nm(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    r + 0.0
}

fn nm_opt(v: Option<f64>) -> Option<f64> {
    v.map(nm)
}

fn shape_json(t: &ToolShape) -> Value {
    let (kind, extra) = match t.kind {
        ToolKind::Flat => ("flat", json!({})),
        ToolKind::Ball => ("ball", json!({})),
        ToolKind::Bull { corner_radius_mm } => {
            ("bull", json!({ "corner_radius_mm": nm(corner_radius_mm) }))
        }
        ToolKind::Drill { point_angle_deg } => {
            ("drill", json!({ "point_angle_deg": point_angle_deg }))
        }
        ToolKind::Vee {
            included_angle_deg,
            tip_diameter_mm,
        } => (
            "vee",
            json!({"included_angle_deg": included_angle_deg, "tip_diameter_mm": nm(tip_diameter_mm)}),
        ),
        ToolKind::Turning {
            nose_radius_mm,
            tip,
        } => (
            "turning",
            json!({"nose_radius_mm": nm(nose_radius_mm), "tip": tip}),
        ),
    };
    let source = match &t.source {
        ToolSource::Table { file, line } => json!({"from": "table", "file": file, "line": line}),
        ToolSource::Comment { post, line } => {
            json!({"from": "comment", "post": post, "line": line})
        }
        ToolSource::Registers => json!({"from": "registers"}),
        ToolSource::Assumed => json!({"from": "assumed"}),
    };
    let mut v = json!({
        "kind": kind,
        "diameter_mm": nm(t.diameter_mm),
        "flute_length_mm": nm_opt(t.flute_length_mm),
        "length_mm": nm_opt(t.length_mm),
        "holder_diameter_mm": nm_opt(t.holder_diameter_mm),
        "shank_diameter_mm": nm_opt(t.shank_diameter_mm),
        "stickout_mm": nm_opt(t.stickout_mm),
        "description": t.description,
        "source": source,
    });
    if let (Some(o), Some(e)) = (v.as_object_mut(), extra.as_object()) {
        o.extend(e.clone());
    }
    v
}
