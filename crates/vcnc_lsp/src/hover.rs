//! Hover: what the code or address under the cursor means in the
//! document's dialect, and the modal state and work position at the end of
//! its block.
//!
//! ```text
//!   cursor ─▶ scan::tokens(line) ─▶ G83 ─▶ explain::Query ─▶ explain(query, dialect)
//!                                      └─▶ analysis::state_after(line) ─▶ State
//!                                                      └──────────────────┴─▶ Markdown
//! ```
//!
//! The meaning comes from the interpreter's own tables
//! (`vcnc_interp::explain`, the same as `vcnc explain`), never from a list
//! kept here; the modal codes are named by finding the table row whose
//! operation the state holds, so a dialect that writes inches as G70
//! shows G70.

use crate::analysis::{Job, state_after};
use crate::scan::{self, Kind};
use crate::text::{interp_line, lines};
use lsp_types::{Hover, HoverContents, MarkupContent, MarkupKind, Position};
use std::fmt::Write as _;
use std::sync::atomic::AtomicBool;
use vcnc_interp::dialect::{CompOp, FrameOp, GOp, ModeOp};
use vcnc_interp::explain::{Explanation, Query, code_name, explain};
use vcnc_interp::state::{CompSide, ToolLength};
use vcnc_interp::{Dialect, Machine, Plane, State};

/// The hover at `pos` of the job's document (`None`: nothing to explain
/// there, or cancelled).
pub fn hover(job: &Job, pos: Position, cancel: &AtomicBool) -> Option<Hover> {
    let text = job.text.as_str();
    let offset = job.text.offset(pos);
    let (start, line) = lines(text).find(|(s, l)| *s <= offset && offset <= s + l.len())?;
    let dialect = job.choice.dialect();
    let tokens = scan::tokens(line, &dialect.lex);
    let token = scan::at(&tokens, offset - start)?;
    let query = match (token.kind, token.letter, token.value) {
        (Kind::Code, b'G', Some(v)) => Query::G(v),
        (Kind::Code, b'M', Some(v)) => Query::M(whole(v)?),
        (Kind::Code | Kind::Address, l, _) if l.is_ascii_uppercase() => Query::Address(l),
        _ => return None,
    };
    let mut md = String::new();
    write_explanation(&mut md, &explain(query, &dialect));
    let _ = write!(md, "\n\n*{} dialect, {}*", job.choice.name, job.choice.why);
    let number = interp_line(text, start);
    match state_after(job, number, cancel) {
        Some(state) => write_state(&mut md, &state, &dialect, &job.machine(), number),
        None => {
            let _ = write!(
                md,
                "\n\n---\nLine {number} does not run (the program ends or alarms before it)."
            );
        }
    }
    Some(Hover {
        contents: HoverContents::Markup(MarkupContent {
            kind: MarkupKind::Markdown,
            value: md,
        }),
        range: Some(job.text.range(start + token.start, start + token.end)),
    })
}

/// An M code's number, when it is whole and in range.
fn whole(v: f64) -> Option<u32> {
    (v.fract() == 0.0 && (0.0..10_000.0).contains(&v)).then(|| {
        // Whole and below 10,000: the conversion is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = v as u32;
        n
    })
}

fn write_explanation(md: &mut String, e: &Explanation) {
    let _ = match e {
        Explanation::Code {
            code,
            meaning,
            group,
            reads,
            axis_words,
        } => {
            let _ = write!(md, "**{code}**: {meaning}\n\ngroup {group}");
            if !reads.is_empty() {
                let _ = write!(md, " · reads {reads}");
            }
            match axis_words {
                Some(a) => write!(md, " · {a}"),
                None => Ok(()),
            }
        }
        Explanation::Auxiliary { code, meaning } => {
            write!(md, "**{code}**: passed on to the machine: {meaning}")
        }
        Explanation::NotRun { code, reason } => {
            write!(
                md,
                "**{code}**: listed by the controller, not run by vcnc: {reason}"
            )
        }
        Explanation::Address {
            letter,
            meaning,
            read_by,
        } => {
            let _ = write!(md, "**{letter}**: {meaning}");
            if read_by.is_empty() {
                Ok(())
            } else {
                write!(md, "\n\nread by {}", read_by.join(" "))
            }
        }
        Explanation::Unknown { code } => write!(md, "**{code}**: not a code of this dialect"),
    };
}

/// The G code of `op` in the dialect's table, if it has one.
fn code_of(dialect: &Dialect, op: GOp) -> Option<String> {
    dialect
        .g_rows()
        .find(|(_, def)| def.op == op)
        .map(|(c, _)| code_name('G', c))
}

/// The modal codes the state holds, as the dialect writes them.
fn modal_codes(s: &State, d: &Dialect) -> Vec<String> {
    let m = &s.modal;
    let mut ops = vec![GOp::Motion(m.motion)];
    ops.push(GOp::Mode(match m.plane {
        Plane::Xy => ModeOp::PlaneXy,
        Plane::Zx => ModeOp::PlaneZx,
        Plane::Yz => ModeOp::PlaneYz,
    }));
    ops.push(GOp::Mode(if m.incremental {
        ModeOp::Incremental
    } else {
        ModeOp::Absolute
    }));
    ops.push(GOp::Mode(match (m.inverse_time, m.per_rev) {
        (true, _) => ModeOp::InverseTime,
        (false, true) => ModeOp::PerRev,
        (false, false) => ModeOp::PerMinute,
    }));
    ops.push(GOp::Mode(if m.inch {
        ModeOp::Inch
    } else {
        ModeOp::Metric
    }));
    ops.push(GOp::Comp(match m.comp {
        CompSide::Off => CompOp::Cancel,
        CompSide::Left => CompOp::Left,
        CompSide::Right => CompOp::Right,
    }));
    ops.push(GOp::Frame(match m.tool_length {
        ToolLength::Off => FrameOp::ToolLengthCancel,
        ToolLength::Plus => FrameOp::ToolLengthPlus,
        ToolLength::Minus => FrameOp::ToolLengthMinus,
    }));
    if let Ok(n) = u8::try_from(m.wcs) {
        ops.push(GOp::Mode(ModeOp::WorkSystem(n)));
    }
    let mut codes: Vec<String> = ops.into_iter().filter_map(|op| code_of(d, op)).collect();
    if let Some(cycle) = s.cycle.code {
        codes.insert(1, cycle.as_str().to_string());
    }
    codes
}

/// A coordinate in program units: mm with 3 decimals, inches with 4.
fn coordinate(v_mm: f64, inch: bool, rotary: bool) -> String {
    match (rotary, inch) {
        (true, _) => format!("{v_mm:.3}°"),
        (false, true) => format!("{:.4}", v_mm / 25.4),
        (false, false) => format!("{v_mm:.3}"),
    }
}

fn write_state(md: &mut String, s: &State, d: &Dialect, machine: &Machine, line: u64) {
    let codes = modal_codes(s, d).join(" ");
    let _ = write!(md, "\n\n---\nAt the end of line {line}: `{codes}`");
    let units = if s.modal.inch { "in/min" } else { "mm/min" };
    let feed = if s.modal.per_rev {
        format!("F{} per rev", s.feed)
    } else {
        format!("F{} {units}", s.feed)
    };
    let _ = write!(md, " · {feed}");
    let spindle = match s.spindle {
        vcnc_interp::SpindleDir::Cw => "M03",
        vcnc_interp::SpindleDir::Ccw => "M04",
        vcnc_interp::SpindleDir::Stop | vcnc_interp::SpindleDir::Orient => "M05",
    };
    let _ = write!(md, " · S{} {spindle}", s.s_value);
    if let Some(t) = s.tool_active {
        let _ = write!(md, " · T{t} in the spindle");
    }
    let p = s.program_pos();
    let axes: Vec<String> = machine
        .axes
        .iter()
        .enumerate()
        .filter(|(i, a)| !matches!(a.letter, b'A' | b'B' | b'C') || p.get(*i) != 0.0)
        .map(|(i, a)| {
            let rotary = matches!(a.letter, b'A' | b'B' | b'C');
            format!(
                "{}{}",
                char::from(a.letter),
                coordinate(p.get(i), s.modal.inch, rotary)
            )
        })
        .collect();
    let _ = write!(md, "\n\nWork position: {}", axes.join(" "));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::Choice;

    fn job(text: &str, dialect: &'static str) -> Job {
        Job::for_text(
            text,
            Choice {
                name: dialect,
                why: "test".into(),
            },
        )
    }

    fn markdown(h: Hover) -> String {
        match h.contents {
            HoverContents::Markup(m) => m.value,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_peck_cycle_is_explained_with_the_state_after_its_block() {
        let text = "G90 G54 G17 G00 X10. Y20. Z5.\nG83 Z-12. R2. Q3. F80.\nG80\nM30\n";
        let j = job(text, "fanuc");
        let h = hover(&j, Position::new(1, 1), &AtomicBool::new(false)).unwrap();
        assert_eq!(h.range.unwrap().start, Position::new(1, 0));
        let md = markdown(h);
        assert!(md.contains("**G83**") && md.contains("peck"), "{md}");
        assert!(md.contains("group 09 canned cycles"), "{md}");
        // After the cycle block: G83 in force, absolute, G54, F80, and the
        // tool back at the initial level Z5 above the last hole (G98).
        assert!(
            md.contains("G83") && md.contains("G90") && md.contains("G54"),
            "{md}"
        );
        assert!(md.contains("F80"), "{md}");
        assert!(md.contains("X10.000 Y20.000 Z5.000"), "{md}");
    }

    #[test]
    fn inch_programs_show_inches_and_the_dialects_own_codes() {
        // Syntec writes inches as G70.
        let text = "G70 G91 G01 X1. F10.\nM30\n";
        let md = markdown(
            hover(
                &job(text, "syntec"),
                Position::new(0, 14),
                &AtomicBool::new(false),
            )
            .unwrap(),
        );
        assert!(md.contains("**X**"), "{md}");
        assert!(md.contains("`G1 G17 G91 G94 G70 G40 G49 G54`"), "{md}");
        assert!(md.contains("F10 in/min"), "{md}");
        // One inch moved; the rotary axes, never moved, are left out.
        assert!(
            md.contains("X1.0000 Y0.0000 Z0.0000\n") || md.ends_with("X1.0000 Y0.0000 Z0.0000"),
            "{md}"
        );
    }

    #[test]
    fn comments_and_blank_places_have_no_hover() {
        let j = job("G00 X0 (HOME)\n\nM30\n", "fanuc");
        assert!(hover(&j, Position::new(0, 9), &AtomicBool::new(false)).is_none());
        assert!(hover(&j, Position::new(1, 0), &AtomicBool::new(false)).is_none());
    }
}
