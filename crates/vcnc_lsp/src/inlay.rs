//! Inlay hints (off by default; the `vcnc.inlayHints` setting turns them
//! on): the planned time of each CAM operation, at the end of its comment
//! line, from the same planner as `vcnc time` on the same machine.
//!
//! An operation is an outline entry (`symbols`): its time is the sum of
//! the planned time of the main program's lines from its comment to the
//! line before the next operation or program.

use crate::analysis::{Job, line_times};
use crate::symbols::{ItemKind, items};
use crate::text::interp_line;
use lsp_types::{InlayHint, InlayHintLabel};
use std::sync::atomic::AtomicBool;

/// The hints of the job's document (`None`: cancelled).
pub fn operation_times(job: &Job, cancel: &AtomicBool) -> Option<Vec<InlayHint>> {
    let text = job.text.as_str();
    let entries = items(text, &job.choice.dialect());
    let ops: Vec<_> = entries
        .iter()
        .enumerate()
        .filter(|(_, it)| it.kind == ItemKind::Operation)
        .collect();
    if ops.is_empty() {
        return Some(Vec::new());
    }
    let times = line_times(job, cancel)?;
    let mut out = Vec::new();
    for (i, op) in ops {
        let first = usize::try_from(interp_line(text, op.line_start)).unwrap_or(usize::MAX);
        let next = entries
            .get(i + 1..)
            .and_then(|rest| rest.iter().find(|n| n.kind <= ItemKind::Operation))
            .map_or(times.0.len(), |n| {
                usize::try_from(interp_line(text, n.line_start)).unwrap_or(usize::MAX)
            });
        let seconds: f64 = times
            .0
            .get(first..next.max(first))
            .unwrap_or_default()
            .iter()
            .sum();
        out.push(InlayHint {
            position: job.text.position(op.at.1),
            label: InlayHintLabel::String(format!("≈ {}", clock(seconds))),
            kind: None,
            text_edits: None,
            tooltip: None,
            padding_left: Some(true),
            padding_right: None,
            data: None,
        });
    }
    Some(out)
}

/// `42.5 s`, `3 min 05 s`, `1 h 02 min`.
fn clock(s: f64) -> String {
    let s = s.max(0.0);
    if s < 60.0 {
        return format!("{s:.1} s");
    }
    // Rounded and non-negative; a program of 10^15 s is no program.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let whole = s.round().min(1e15) as u64;
    if whole < 3600 {
        format!("{} min {:02} s", whole / 60, whole % 60)
    } else {
        format!("{} h {:02} min", whole / 3600, whole % 3600 / 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::Choice;

    #[test]
    fn each_operation_gets_the_time_of_its_lines() {
        // The built-in Fanuc mill plans; a dwell is planned as exactly its
        // length, so two operations of one dwell each read 2.0 s and 3.0 s.
        let text = "G90 G54\n(OP ONE)\nG04 X2.\n(OP TWO)\nG04 X3.\nM30\n";
        let choice = Choice {
            name: "fanuc",
            why: String::new(),
        };
        let job = Job::for_text(text, choice);
        let hints = operation_times(&job, &AtomicBool::new(false)).unwrap();
        let labels: Vec<String> = hints
            .iter()
            .map(|h| match &h.label {
                InlayHintLabel::String(s) => s.clone(),
                other => format!("{other:?}"),
            })
            .collect();
        assert_eq!(labels, vec!["≈ 2.0 s", "≈ 3.0 s"]);
        assert_eq!(hints[0].position, lsp_types::Position::new(1, 8));
        assert_eq!(clock(185.0), "3 min 05 s");
        assert_eq!(clock(3725.0), "1 h 02 min");
    }
}
