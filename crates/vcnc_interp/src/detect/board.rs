//! The scoring of `--dialect auto`: every rule's evidence as a note that
//! adds points to the dialects it supports, and what each dialect's own
//! tables say would alarm there (a misfit, which costs more than any note
//! gives). Lathe or mill is decided first, on the notes that are not about
//! one kind's dialects; then the best dialect of that kind; the confidence
//! is the margin over the closest dialect that would run the program
//! differently (`differs`), and the evidence what tells the two apart.

use super::scan::{AXIS_LETTERS, NONE, Scan, Shape};
use super::{Confidence, Detection};
use crate::dialect::{
    BareReturn, Dialect, GOp, Group, IntegerWords, IsoMacros, MGroup, MacroFiles, bit,
};
use crate::dialect::{MotionOp, MoveOp};
use std::collections::BTreeSet;
use std::sync::OnceLock;
use vcnc_syntax::Semicolon;

/// Below this margin over the other kind, its evidence is said too.
const KIND_SAID_BELOW: i32 = 40;

/// How close a dialect that runs the program alike must come to be named.
const ALIKE_WITHIN: i32 = 30;

/// A code that would alarm (E201, E203, E101) in a dialect: heavy.
const MISFIT: i32 = 40;
/// A code a dialect's document lists but vcnc does not run there (E201 says
/// why): the program may be of that family, but one that runs it fits
/// better.
const UNSUPPORTED: i32 = 15;

/// An M code some dialects know (or their built-in machines list) and
/// others pass on with W105.
const KNOWN_M: i32 = 8;

/// One piece of evidence: its text, and what it adds to each dialect.
struct Note {
    text: String,
    weight: i32,
    /// Dialects it supports (index bits).
    supports: u32,
}

/// The scores and the notes that made them.
pub(super) struct Board {
    score: Vec<i32>,
    /// The scores without the evidence that only compares dialects of one
    /// kind (how integers are written): lathe or mill is decided on these.
    kind_score: Vec<i32>,
    notes: Vec<Note>,
    /// What would alarm in each dialect (`G21`, `G64 P`, `; comments`).
    misfits: Vec<BTreeSet<String>>,
}

fn mask_of(all: &[Dialect], f: impl Fn(&Dialect) -> bool) -> u32 {
    all.iter()
        .enumerate()
        .filter(|(_, d)| f(d))
        .fold(0, |m, (i, _)| m | (1 << i))
}

fn mask_of_indexed(all: &[Dialect], f: impl Fn(usize, &Dialect) -> bool) -> u32 {
    all.iter()
        .enumerate()
        .filter(|(i, d)| f(*i, d))
        .fold(0, |m, (i, _)| m | (1 << i))
}

/// Every dialect.
fn full(all: &[Dialect]) -> u32 {
    mask_of(all, |_| true)
}

/// Whether dialect `i` (`d`) knows M `m`: its table, its auxiliary
/// ranges, or its built-in machine's `[m_codes]`.
fn knows_m(i: usize, d: &Dialect, m: u16) -> bool {
    d.m(f64::from(m)).is_some()
        || d.aux_m(u32::from(m)).is_some_and(|a| !a.is_user_macro())
        || machine_m_codes()
            .get(i)
            .is_some_and(|codes| codes.contains(&u32::from(m)))
}

/// The M codes each dialect's built-in machine lists, read once.
fn machine_m_codes() -> &'static [Vec<u32>] {
    static CODES: OnceLock<Vec<Vec<u32>>> = OnceLock::new();
    CODES.get_or_init(|| {
        let mut read: Vec<(&'static str, Vec<u32>)> = Vec::new();
        Dialect::all()
            .iter()
            .map(|d| {
                if let Some((_, codes)) = read
                    .iter()
                    .find(|(t, _)| std::ptr::eq(*t, d.default_machine))
                {
                    return codes.clone();
                }
                let codes: Vec<u32> = vcnc_core::machine::Machine::from_toml(d.default_machine)
                    .map(|m| m.m_codes.keys().copied().collect())
                    .unwrap_or_default();
                read.push((d.default_machine, codes.clone()));
                codes
            })
            .collect()
    })
}

fn named(all: &[Dialect], names: &[&str]) -> u32 {
    mask_of(all, |d| names.contains(&d.name))
}

pub(super) fn is_lathe(d: &Dialect) -> bool {
    d.diameter.lathe
}

impl Board {
    pub(super) fn new(n: usize) -> Board {
        Board {
            score: vec![0; n],
            kind_score: vec![0; n],
            notes: Vec::new(),
            misfits: vec![BTreeSet::new(); n],
        }
    }

    /// Evidence for the dialects of `supports`.
    fn note(&mut self, text: impl Into<String>, weight: i32, supports: u32) {
        for (i, s) in self.kind_score.iter_mut().enumerate() {
            if supports & (1 << i) != 0 {
                *s += weight;
            }
        }
        self.note_within_kind(text, weight, supports);
    }

    /// Evidence that compares dialects of one kind only.
    fn note_within_kind(&mut self, text: impl Into<String>, weight: i32, supports: u32) {
        for (i, s) in self.score.iter_mut().enumerate() {
            if supports & (1 << i) != 0 {
                *s += weight;
            }
        }
        self.notes.push(Note {
            text: text.into(),
            weight,
            supports,
        });
    }

    /// Something that would alarm in every dialect outside `fits`.
    fn misfit_outside(&mut self, text: &str, fits: u32) {
        for i in 0..self.score.len() {
            if fits & (1 << i) == 0 {
                self.misfit(i, text.to_string());
            }
        }
    }

    /// Adds to dialect `i`'s scores.
    fn add(&mut self, i: usize, points: i32) {
        for s in [&mut self.score, &mut self.kind_score] {
            if let Some(s) = s.get_mut(i) {
                *s += points;
            }
        }
    }

    fn misfit(&mut self, i: usize, what: String) {
        self.misfit_by(i, what, MISFIT);
    }

    /// Something that costs dialect `i` `points` (the first six things).
    fn misfit_by(&mut self, i: usize, what: String, points: i32) {
        if let Some(set) = self.misfits.get_mut(i)
            && set.len() < 6
            && set.insert(what)
        {
            self.add(i, -points);
        }
    }

    /// The codes of every block shape, asked of each dialect's tables:
    /// what would alarm where, and the M codes only some dialects (or
    /// their built-in machines) know.
    pub(super) fn codes(&mut self, all: &[Dialect], scan: &Scan) {
        for shape in scan.shapes.keys() {
            for (i, d) in all.iter().enumerate() {
                if let Some((what, points)) = misfit(d, shape) {
                    self.misfit_by(i, what, points);
                }
            }
        }
        let flow = |m: u16| {
            all.iter().any(|d| {
                d.m(f64::from(m))
                    .is_some_and(|def| def.group == MGroup::Flow)
            })
        };
        for &m in &scan.m_seen {
            let knows = mask_of_indexed(all, |i, d| knows_m(i, d, m));
            if knows == 0 || knows == full(all) {
                continue;
            }
            if flow(m) {
                // M98, M99, M97: a call or return nothing else runs.
                self.misfit_outside(&format!("M{m}"), knows);
            } else {
                self.note(format!("M{m}"), KNOWN_M, knows);
            }
        }
    }

    /// Lexical and macro syntax: `;`, `//`, `%@MACRO`, `#`, O words, `$`.
    pub(super) fn syntax(&mut self, all: &[Dialect], scan: &Scan) {
        if scan.macro_file || scan.syntec_statements {
            let fits = mask_of(all, |d| d.macros.files == MacroFiles::Syntec);
            self.note("%@MACRO", 100, fits);
            self.misfit_outside("%@MACRO", fits);
        }
        if scan.semicolon_comments {
            let fits = mask_of(all, |d| d.lex.semicolon == Semicolon::Comment);
            self.note("\"; comments\"", 10, fits);
            self.misfit_outside("; comments", fits);
        } else if scan.semicolon_ends > 2 {
            let fits = mask_of(all, |d| d.lex.semicolon == Semicolon::EndOfBlock);
            self.note("\";\" block ends", 5, fits);
        }
        if scan.slash_comments {
            let fits = mask_of(all, |d| d.lex.slash_comments);
            self.note("\"//\" comments", 5, fits);
            self.misfit_outside("// comments", fits);
        }
        let ngc = mask_of(all, |d| d.macros.iso == IsoMacros::Ngc);
        if let Some(o) = &scan.o_words {
            self.note(o.clone(), 40, ngc);
            self.misfit_outside(o, ngc);
        }
        if let Some(p) = &scan.named_params {
            self.note(p.clone(), 40, ngc);
            self.misfit_outside(p, ngc);
        }
        if let Some(c) = &scan.ngc_comment {
            self.note(format!("\"{c}\" comments"), 15, ngc);
        }
        if scan.polar {
            self.note("\"^\" polar words", 15, ngc);
        }
        if let Some(k) = scan.macro_b {
            let fits = mask_of(all, |d| d.macros.iso == IsoMacros::CustomMacroB);
            self.note(format!("Custom Macro B ({k})"), 15, fits);
            self.misfit_outside(k, fits);
        } else if scan.numbered_vars {
            let fits = mask_of(all, |d| d.macros.iso != IsoMacros::None);
            self.misfit_outside("# variables", fits);
        }
        if scan.colon_number {
            let fits = mask_of(all, |d| d.lex.colon_is_o);
            self.note("\":\" program number", 10, fits);
            self.misfit_outside(": program number", fits);
        }
        if scan.program_number {
            // `O1234`: the number M98 P calls a program by; a `%` before it
            // is the tape format industrial controls read.
            let fits = mask_of(all, |d| d.m(98.0).is_some_and(|m| m.group == MGroup::Flow));
            let text = if scan.percent_start {
                "% and O number"
            } else {
                "O number"
            };
            self.note(text, if scan.percent_start { 12 } else { 8 }, fits);
        }
        for ext in &scan.extended {
            let fits = mask_of(all, |d| d.lex.extended.all().iter().any(|(t, _)| t == ext));
            self.note(format!("\"{ext}\""), 30, fits);
            self.misfit_outside(ext, fits);
        }
        if let Some(d) = &scan.grbl_dollar {
            self.note(format!("\"{d}\" line"), 40, named(all, &["grbl"]));
        }
    }

    /// Names of controls and posts in the header comments.
    pub(super) fn header(&mut self, all: &[Dialect], scan: &Scan) {
        let mut done = 0u32;
        for comment in &scan.comments {
            let upper = comment.to_ascii_uppercase();
            for (k, rule) in HEADER_NAMES.iter().enumerate() {
                if done & (1 << k) != 0 {
                    continue;
                }
                let Some((at, word)) = rule
                    .0
                    .iter()
                    .find_map(|w| word_at(&upper, w).map(|at| (at, *w)))
                else {
                    continue;
                };
                done |= 1 << k;
                let supports = named(all, rule.1);
                let text = around(comment, at, word.len());
                self.note(format!("\"{text}\" header"), rule.2, supports);
            }
        }
    }

    /// The file name's extension.
    pub(super) fn extension(&mut self, all: &[Dialect], name: Option<&str>) {
        let Some(ext) = name
            .and_then(|n| std::path::Path::new(n).extension())
            .and_then(|e| e.to_str())
        else {
            return;
        };
        let ext = ext.to_ascii_lowercase();
        match ext.as_str() {
            // LinuxCNC's own extension (documented since the linuxcnc
            // dialect came).
            "ngc" => {
                let ngc = mask_of(all, |d| d.macros.iso == IsoMacros::Ngc);
                self.note(".ngc file", 30, ngc);
            }
            // Vectric's and SheetCam's Mach3 posts write `.tap` (the
            // extension Mach3's file dialog offers first).
            "tap" => {
                let mach3 = mask_of(all, |d| d.macros.iso == IsoMacros::NgcParams);
                self.note(".tap file", 20, mach3);
            }
            // Hobby CAM's extension (3D printers' too).
            "gcode" => {
                let comment = mask_of(all, |d| d.lex.semicolon == Semicolon::Comment);
                self.note(".gcode file", 5, comment);
            }
            _ => {}
        }
    }

    /// Lathe or mill: the lathe's signs against the mill's.
    pub(super) fn kind(&mut self, all: &[Dialect], scan: &Scan) {
        let k = &scan.kind;
        let lathes = mask_of(all, is_lathe);
        let mills = mask_of(all, |d| !is_lathe(d));
        let signs = self.notes.len();
        if let Some(t) = &k.turret {
            self.note(t.clone(), 25, lathes);
        }
        if let Some(g50) = &k.g50_s {
            self.note(g50.clone(), 15, lathes);
        }
        if k.g96 {
            self.note("G96 S", 10, lathes);
        }
        if k.uw > 0 {
            self.note("U/W words", 15, lathes);
        }
        // A rotary-axis program (`G1 X10 A90`: a 4th axis wrapping X
        // around A) moves X and Z alone too, but it is a mill's.
        if k.x > 0 && k.z > 0 && k.y == 0 && !k.rotary() && k.x + k.z >= 4 {
            self.note("X and Z only", 20, lathes);
        }
        if k.plane_header == Some(180) {
            self.note("G18 header", 15, lathes);
        }
        if self.notes.len() == signs && scan.blocks > 0 {
            // Lathe programs show their kind (T0101, G18, X and Z only);
            // a program that shows none is a mill's.
            self.note("no lathe sign", 20, mills);
        }
        if k.plane_header == Some(170) {
            self.note("G17 header", 10, mills);
        }
        if k.y > 0 {
            self.note("Y moves", 20, mills);
        }
        if let Some(code) = &k.system_b_cycle {
            // Only a Fanuc lathe in system B has G77-G79 as cycles; the
            // system is the machine's (docs/machine.md), which detection
            // cannot set: the evidence says what to write.
            self.note(
                format!("{code} cycle (Fanuc lathe G-code system B: set gcode_system = \"B\" in the machine file)"),
                30,
                named(all, &["fanuc-lathe"]),
            );
        }
        if k.two_block_g71 {
            self.note("two-block G71 U R", 30, named(all, &["fanuc-lathe"]));
        }
        if k.one_block_g71_d {
            self.note("one-block G71 with D", 30, named(all, &["haas-lathe"]));
        }
        if k.one_block_g76 {
            self.note("one-block G76 with K D", 20, named(all, &["haas-lathe"]));
        }
        if k.two_block_g76 {
            self.note("two-block G76 P Q R", 20, named(all, &["fanuc-lathe"]));
        }
        if k.laser_m4 && k.s_on_moves >= 3 && k.z == 0 {
            self.note("laser M4 with S on moves", 15, named(all, &["grbl"]));
        }
    }

    /// Whole-unit integers against least-increment ones. A lathe's
    /// integers count only toward lathes that read X as a diameter from
    /// power-on (the Fanuc convention of lathe programs): LinuxCNC's lathe
    /// (a radius until G7) is told by its own signs.
    pub(super) fn integers(&mut self, all: &[Dialect], scan: &Scan) {
        let l = &scan.lengths;
        let counts = |d: &Dialect| !is_lathe(d) || d.diameter.at_power_on;
        let whole = mask_of(all, |d| counts(d) && d.integers == IntegerWords::WholeUnits);
        let least = mask_of(all, |d| {
            counts(d) && d.integers == IntegerWords::LeastIncrement
        });
        let first = l.first_plain.clone().unwrap_or_default();
        if l.plain_count == 0 {
            // `Z15.`, `F1000.`: the style of Fanuc-family posts, which
            // write the point a control of theirs needs.
            let trailing = l.trailing + l.f_trailing;
            if trailing >= 2 && trailing * 4 >= l.pointed + l.f_pointed {
                let example = l.first_trailing.clone().unwrap_or_default();
                self.note_within_kind(format!("numbers written \"{example}\""), 8, least);
            }
            return;
        }
        let mut sorted = l.plain.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
        let largest = sorted.last().copied().unwrap_or(0.0);
        if median >= 1000.0 || largest >= 10_000.0 {
            self.note_within_kind(format!("least-increment integers ({first})"), 25, least);
        } else if l.pointed > 0 {
            // `X20` beside `X1.5`: written for a control that reads both
            // as millimetres.
            self.note_within_kind(
                format!("whole-unit integers ({first} beside points)"),
                25,
                whole,
            );
        } else if largest < 1000.0 {
            // Read as least increments, the whole part would fit in 1 mm.
            self.note_within_kind(format!("whole-unit integers ({first})"), 30, whole);
        } else {
            self.note_within_kind(format!("whole-unit integers ({first})"), 20, whole);
        }
    }

    /// The best score; the evidence that supports it; the confidence.
    pub(super) fn decide(&mut self, all: &[Dialect], scan: &Scan) -> Detection {
        for (i, p) in PRIOR.iter().enumerate() {
            self.add(i, *p);
        }
        let best_of = |scores: &[i32], f: &dyn Fn(usize) -> bool| {
            (0..all.len())
                .filter(|i| f(*i))
                .max_by(|a, b| scores.get(*a).cmp(&scores.get(*b)).then(b.cmp(a)))
        };
        let lathe = |i: usize| all.get(i).is_some_and(is_lathe);
        // Lathe or mill first, on the evidence that is not about one
        // kind's dialects; then the best dialect of that kind.
        let kind_lathe = best_of(&self.kind_score, &|_| true).is_some_and(lathe);
        let best = best_of(&self.score, &|i| lathe(i) == kind_lathe).unwrap_or(0);
        let Some(winner) = all.get(best) else {
            return Detection {
                dialect: "fanuc",
                evidence: Vec::new(),
                confidence: Confidence::Low,
                runner_up: None,
                alike: Vec::new(),
            };
        };
        // The closest dialects that would run the program differently:
        // of the same kind on every score, of the other on the kind scores.
        let gap = |r: usize| {
            let scores = if lathe(r) == kind_lathe {
                &self.score
            } else {
                &self.kind_score
            };
            scores.get(best).copied().unwrap_or(0) - scores.get(r).copied().unwrap_or(0)
        };
        let closest = |same_kind: bool| {
            (0..all.len())
                .filter(|i| *i != best && (lathe(*i) == kind_lathe) == same_kind)
                .filter(|i| all.get(*i).is_some_and(|d| differs(winner, d, scan)))
                .min_by(|a, b| gap(*a).cmp(&gap(*b)).then(a.cmp(b)))
        };
        let (same, other) = (closest(true), closest(false));
        let rival = match (same, other) {
            (Some(s), Some(o)) if gap(o) < gap(s) => Some(o),
            (Some(s), _) => Some(s),
            (None, o) => o,
        };
        let margin = rival.map_or(i32::MAX, gap);
        // Close dialects that would run it the same, best first.
        let mut alike: Vec<usize> = (0..all.len())
            .filter(|i| *i != best && lathe(*i) == kind_lathe)
            .filter(|i| gap(*i) <= ALIKE_WITHIN)
            .filter(|i| all.get(*i).is_some_and(|d| !differs(winner, d, scan)))
            .collect();
        alike.sort_by_key(|i| (gap(*i), *i));
        alike.truncate(3);
        // What tells it from its own kind's closest dialect; and what tells
        // its kind when that was close, or when it is a lathe (whose signs
        // are worth saying).
        let mut evidence = self.evidence_for(best, same);
        if let Some(o) = other
            && (kind_lathe || gap(o) < KIND_SAID_BELOW || evidence.is_empty())
        {
            for e in self.evidence_for(best, Some(o)) {
                if !evidence.contains(&e) {
                    evidence.push(e);
                }
            }
        }
        if evidence.is_empty() {
            evidence = self.evidence_for(best, None);
        }
        let confidence = if margin >= 20 {
            Confidence::High
        } else {
            Confidence::Low
        };
        evidence.truncate(3);
        Detection {
            dialect: winner.name,
            evidence,
            confidence,
            runner_up: match confidence {
                Confidence::Low => rival.and_then(|r| all.get(r)).map(|d| d.name),
                Confidence::High => None,
            },
            alike: alike
                .iter()
                .filter_map(|i| all.get(*i))
                .map(|d| d.name)
                .collect(),
        }
    }

    /// What speaks for dialect `w` against `rival`: codes that would alarm
    /// there and not in `w`, then the notes that support `w` and not the
    /// rival, strongest first; without a rival, the strongest notes that
    /// do not support every dialect.
    fn evidence_for(&self, w: usize, rival: Option<usize>) -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        let mine = self.misfits.get(w);
        if let Some(r) = rival.and_then(|r| self.misfits.get(r)) {
            for m in r.iter().filter(|m| mine.is_none_or(|s| !s.contains(*m))) {
                // Notes already say `%@MACRO`, `; comments` …: codes only.
                if m.starts_with(['G', 'M']) && out.len() < 2 {
                    out.push(m.clone());
                }
            }
        }
        let everyone = (1u32 << self.score.len()) - 1;
        let mut notes: Vec<&Note> = self
            .notes
            .iter()
            .filter(|n| n.weight > 0 && n.supports & (1 << w) != 0 && n.supports != everyone)
            .collect();
        let against_rival = |n: &Note| rival.is_some_and(|r| n.supports & (1 << r) == 0);
        notes.sort_by(|a, b| {
            against_rival(b)
                .cmp(&against_rival(a))
                .then(b.weight.cmp(&a.weight))
        });
        for n in notes {
            // Against a rival, only what the rival lacks.
            if (rival.is_none() || against_rival(n)) && !out.contains(&n.text) {
                out.push(n.text.clone());
            }
        }
        out
    }

    /// The scores and notes, for `vcnc`'s tests and for tuning.
    pub(super) fn explain(&self, all: &[Dialect]) -> String {
        let mut out = String::new();
        for (i, d) in all.iter().enumerate() {
            let misfits: Vec<&str> = self
                .misfits
                .get(i)
                .map(|m| m.iter().map(String::as_str).collect())
                .unwrap_or_default();
            out.push_str(&format!(
                "{:>15} {:>5}  misfits: {}\n",
                d.name,
                self.score.get(i).copied().unwrap_or(0),
                misfits.join(", ")
            ));
        }
        for n in &self.notes {
            let names: Vec<&str> = all
                .iter()
                .enumerate()
                .filter(|(i, _)| n.supports & (1 << i) != 0)
                .map(|(_, d)| d.name)
                .collect();
            out.push_str(&format!(
                "  {:+} {} → {}\n",
                n.weight,
                n.text,
                names.join(" ")
            ));
        }
        out
    }
}

/// Where a word appears in upper-case text as a whole word.
fn word_at(upper: &str, word: &str) -> Option<usize> {
    upper.match_indices(word).map(|(at, _)| at).find(|&at| {
        let before = upper.get(..at).and_then(|b| b.chars().next_back());
        let after = upper.get(at + word.len()..).and_then(|a| a.chars().next());
        !before.is_some_and(|c| c.is_ascii_alphanumeric())
            && !after.is_some_and(|c| c.is_ascii_alphabetic())
    })
}

/// A comment as evidence: whole when short, else the words around the
/// name it matched (`…gcodes/mach3.gcode)`).
fn around(comment: &str, at: usize, len: usize) -> String {
    const WHOLE: usize = 32;
    const SIDE: usize = 12;
    if comment.chars().count() <= WHOLE {
        return comment.to_string();
    }
    let mut start = at.saturating_sub(SIDE);
    while !comment.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = (at + len + SIDE).min(comment.len());
    while !comment.is_char_boundary(end) {
        end += 1;
    }
    let mut out = String::new();
    if start > 0 {
        out.push('…');
    }
    out.push_str(comment.get(start..end).unwrap_or(comment).trim());
    if end < comment.len() {
        out.push('…');
    }
    out
}

/// Names in header comments: the words (upper case, whole words), the
/// dialects they point at, and the weight.
const HEADER_NAMES: &[(&[&str], &[&str], i32)] = &[
    (&["HAAS"], &["haas", "haas-lathe"], 40),
    (&["FANUC"], &["fanuc", "fanuc-lathe"], 30),
    (&["SYNTEC"], &["syntec"], 40),
    (
        &[
            "LINUXCNC",
            "EMC2",
            "EMC",
            "PLASMAC",
            "QTPLASMAC",
            "GMOCCAPY",
        ],
        &["linuxcnc", "linuxcnc-lathe"],
        40,
    ),
    (&["GRBL", "GRBLHAL"], &["grbl"], 40),
    // Mach3 and Mach4 posts name their control (Vectric's "Mach2/3").
    (
        &["MACH3", "MACH4", "MACH 3", "MACH 4", "MACH2/3", "MACH2"],
        &["mach3"],
        40,
    ),
    // Hobby CAM and senders that write for grbl.
    (
        &[
            "ESTLCAM",
            "CARBIDE CREATE",
            "EASEL",
            "JSCUT",
            "BCNC",
            "UNIVERSAL GCODE SENDER",
            "CNCJS",
            "CANDLE",
            "LIGHTBURN",
            "LASERWEB",
            "SHAPEOKO",
            "X-CARVE",
            "CAMBAM",
            "GCODETOOLS",
            "SKETCHUCAM",
        ],
        &["grbl"],
        20,
    ),
    // Controls that read Fanuc's codes with their own extras.
    (
        &["MAZAK", "MITSUBISHI", "BROTHER", "HURCO", "DOOSAN", "OKUMA"],
        &["fanuc", "fanuc-lathe"],
        10,
    ),
    (
        &["LATHE", "TURNING", "TURN CENTER", "TURNING CENTER"],
        &["fanuc-lathe", "haas-lathe", "linuxcnc-lathe", "lathe"],
        10,
    ),
    (
        &["VMC", "MILL", "MACHINING CENTER", "ROUTER"],
        &["syntec", "fanuc", "haas", "grbl", "linuxcnc", "eia"],
        10,
    ),
];

/// Ties broken toward the commoner reading: a program with no industrial
/// sign (no `%` and O number, no code only Fanuc's family knows) is hobby
/// CAM output for grbl more often than not; Fanuc before Syntec (they
/// differ only in G20/G21 against G70/G71) and before Haas, grbl before
/// LinuxCNC (a subset that runs the same), the Fanuc lathe before Haas's;
/// EIA-274-D, the seed lathe and Mach3 (which reads what LinuxCNC reads,
/// and takes any M code as a macro) only on their own evidence. In
/// [`Dialect::NAMES`] order.
const PRIOR: [i32; 11] = [
    // syntec fanuc lathe eia grbl haas fanuc-lathe haas-lathe linuxcnc linuxcnc-lathe mach3
    2, 3, -4, -6, 4, 0, 2, 0, 1, 0, -30,
];

/// What would alarm when dialect `d` runs a block of `shape`, and what it
/// costs: an unknown G code, or a word the block's codes do not read (`G21
/// G64 P` in Fanuc, `U` on a mill), [`MISFIT`]; a code its document lists
/// but vcnc does not run, [`UNSUPPORTED`].
fn misfit(d: &Dialect, shape: &Shape) -> Option<(String, i32)> {
    let mut reads = 0u32;
    let mut motion = false;
    let mut unsupported = None;
    for &code in shape.g.iter().filter(|c| **c != NONE) {
        let value = f64::from(code) / 10.0;
        let name = g_name(code);
        match d.g(value) {
            Some(def)
                if def.op == GOp::Move(MoveOp::RefReturn)
                    && shape.letters & AXIS_LETTERS == 0
                    && d.bare_return == BareReturn::NeedsAxes =>
            {
                // `G28` alone: every axis home on Haas and grbl, an alarm
                // on Fanuc.
                return Some((format!("{name} alone"), MISFIT));
            }
            Some(def) => {
                reads |= def.letters;
                motion |= matches!(def.group, Group::Motion | Group::Cycle);
                if matches!(
                    def.op,
                    GOp::Motion(MotionOp::ArcCw) | GOp::Motion(MotionOp::ArcCcw)
                ) {
                    reads |= ARC_LETTERS | d.arc_letters;
                }
            }
            // Listed by its document but not run: the program may belong
            // here all the same (the alarm will say why), but a dialect
            // that runs it fits better.
            None if d.unsupported_reason(value).is_some() => {
                reads |= CHECKED;
                unsupported.get_or_insert(name);
            }
            None => return Some((name, MISFIT)),
        }
    }
    if !motion
        && shape.modal != NONE
        && let Some(def) = d.g(f64::from(shape.modal) / 10.0)
    {
        reads |= def.letters;
        if matches!(
            def.op,
            GOp::Motion(MotionOp::ArcCw) | GOp::Motion(MotionOp::ArcCcw)
        ) {
            reads |= ARC_LETTERS | d.arc_letters;
        }
    }
    for &m in shape.m.iter().filter(|m| **m != NONE) {
        if let Some(def) = d.m(f64::from(m)) {
            reads |= def.letters;
        } else if let Some(aux) = d.aux_m(u32::from(m)) {
            reads |= aux.letters;
        } else {
            // A machine builder's M code (`M11 P1`): it may read them.
            reads |= CHECKED;
        }
    }
    for &(word, _) in d.incremental_words {
        reads |= bit(word);
    }
    let stray = shape.letters & CHECKED & !reads;
    if stray == 0 {
        return unsupported.map(|u| (u, UNSUPPORTED));
    }
    // `G21 G64 P`: the block's codes (or the motion in force) and the word
    // none of them reads here.
    let letter = (b'A'..=b'Z').find(|l| stray & bit(*l) != 0).unwrap_or(b'?');
    let mut codes: Vec<String> = shape
        .g
        .iter()
        .filter(|c| **c != NONE)
        .map(|c| g_name(*c))
        .collect();
    if codes.is_empty() && shape.modal != NONE {
        codes.push(g_name(shape.modal));
    }
    codes.push(char::from(letter).to_string());
    let what = if codes.len() == 1 {
        format!("{} word", char::from(letter))
    } else {
        codes.join(" ")
    };
    Some((what, MISFIT))
}

/// Letters whose stray use alarms E203 in every dialect that does not read
/// them (others, such as H and D, some dialects take alone).
const CHECKED: u32 = bit(b'P') | bit(b'Q') | bit(b'L') | bit(b'E') | bit(b'U') | bit(b'W');

/// Letters every arc reads.
const ARC_LETTERS: u32 = bit(b'I') | bit(b'J') | bit(b'K') | bit(b'R');

/// `G21`, `G59.1` from × 10.
fn g_name(code: u16) -> String {
    if code.is_multiple_of(10) {
        format!("G{}", code / 10)
    } else {
        format!("G{}.{}", code / 10, code % 10)
    }
}

/// Whether dialect `b` would run the program differently from `a` in a way
/// that matters, as far as the prefix shows: the machine's kind, the
/// reading of integers it writes or of `;`, a code it uses that means
/// something else or nothing there, or a policy of its cycles, dwells or
/// bare G28. (Smaller policies, such as whether M6 stops the spindle, do
/// not make a guess doubtful.)
pub(super) fn differs(a: &Dialect, b: &Dialect, scan: &Scan) -> bool {
    if is_lathe(a) != is_lathe(b) {
        return true;
    }
    if scan.lengths.plain_count > 0 && a.integers != b.integers {
        return true;
    }
    if (scan.semicolon_comments || scan.semicolon_blocks > 0) && a.lex.semicolon != b.lex.semicolon
    {
        return true;
    }
    let op = |d: &Dialect, c: u16| d.g(f64::from(c) / 10.0).map(|g| g.op);
    if scan.g_seen.iter().any(|c| op(a, *c) != op(b, *c)) {
        return true;
    }
    let mop = |d: &Dialect, c: u16| d.m(f64::from(c)).map(|m| m.op);
    if scan.m_seen.iter().any(|c| mop(a, *c) != mop(b, *c)) {
        return true;
    }
    let cycles = scan.g_seen.iter().any(|c| (730..=890).contains(c));
    (cycles && a.cycles != b.cycles)
        || (scan.dwell_p_point && a.dwell_p != b.dwell_p)
        || (scan.bare_g28 && a.bare_return != b.bare_return)
}
