//! LinuxCNC's O-word structure: the statements of each source listed once
//! and linked to their partners, and the subroutine files `NAME.ngc`.
//!
//! ```text
//!   o100 sub            ──Sub──▶ past o100 endsub (the flow never runs into a body)
//!   o101 if [c]         ──If───▶ the next o101 elseif / else (tested there) or past endif
//!   o101 else           ──Clause──▶ past o101 endif when a branch ran into it
//!   o102 while [c]      ──Loop──▶ past o102 endwhile when c fails
//!   o102 endwhile       ──Back──▶ o102 while
//!   o103 do … o103 while [c]  ──DoWhile──▶ the body while c
//!   o104 repeat [n]     ──Loop──▶ past o104 endrepeat when n < 1
//!   o104 endrepeat      ──Back──▶ the body, while passes are left
//!   o104 break          ──Leave──▶ past the loop's end; continue: to its test
//!   o100 call [1] [2]   ──Call──▶ the body of this source's o100 sub, or NAME.ngc's
//! ```
//!
//! O-words pair by label, not by nesting: a statement's partner is the
//! next one with the same label in its scope (the previous one for a
//! loop's end), and a label lives in the subroutine that holds it (the
//! main program is one more scope). The first O-word statement of a source
//! has its whole text read once (label, keyword, line:
//! `vcnc_syntax::macros::o_statement`), and every statement is linked
//! then, so a jump never searches again. A partner a statement lacks is
//! kept as what it lacks: rs274 reads the whole structure whichever way
//! the flow goes, so an opening statement without its end (or a branch
//! statement without its IF) alarms E611 each time it runs, after its
//! operands are evaluated, and not before.
//!
//! A call of a subroutine the program does not define reads the file
//! `NAME.ngc` of the program directories (LinuxCNC's subroutine path),
//! once, through the `ProgramStore`; the name must be a plain file name,
//! so no call reads outside those directories.

use crate::alarms;
use crate::flow::{Flow, ProgramStore, Source};
use crate::interpreter::Interpreter;
use std::collections::HashMap;
use std::rc::Rc;
use vcnc_syntax::macros::{Kw, o_statement};
use vcnc_syntax::{Cursor, Diagnostic, ReadError, Span};

/// One O-word statement of a source.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    pub label: String,
    pub kw: Kw,
    /// Where its label lives: 0 the main program, i + 1 the body of the
    /// subroutine whose `sub` is statement i (labels are local to a sub).
    pub scope: usize,
    /// A WHILE that closes a DO: the DO's index (found once, at the scan).
    pub closes_do: Option<usize>,
    /// Its line, from its start.
    pub here: Cursor,
    /// Just past its line.
    pub after: Cursor,
}

/// Where a statement goes, or the partner it lacks (what E611's "has no …
/// with the same label" names).
pub(crate) type Dest = Result<Cursor, &'static str>;

/// Where a false IF or ELSEIF goes.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Branch {
    /// Past the ENDIF.
    End(Cursor),
    /// To the next ELSEIF or ELSE, which is tested there (not skipped as
    /// the end of a branch that ran).
    Test(Cursor),
}

/// A BREAK's or CONTINUE's loop.
#[derive(Debug, Clone)]
pub(crate) struct Leave {
    /// Past the loop's end (BREAK), or its test (CONTINUE: a WHILE's head,
    /// else its end, where a REPEAT counts its pass).
    pub to: Cursor,
    /// The labels of the REPEAT loops running that end with it: those
    /// inside the loop, and the loop itself when a BREAK leaves a REPEAT.
    pub ending: Vec<String>,
}

/// The subroutine an O CALL enters.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Callee {
    /// The body of the `sub` with its label in this source.
    Here(Cursor),
    /// None in this source: the file `NAME.ngc`'s.
    File,
    /// Defined this many times in this source.
    Twice(usize),
}

/// What an O-word statement follows when it runs.
#[derive(Debug, Clone)]
pub(crate) enum OLink {
    /// SUB: past its ENDSUB.
    Sub(Dest),
    Call(Callee),
    /// ENDSUB, RETURN, DO, ENDIF: nothing to find.
    Plain,
    /// IF: where it goes when its condition fails.
    If(Result<Branch, &'static str>),
    /// ELSEIF, ELSE: where a failed test goes (`next`, ELSEIF only), and
    /// past the ENDIF when the branch before ran into it (`end`).
    Clause {
        next: Result<Branch, &'static str>,
        end: Dest,
    },
    /// A WHILE closing a DO: back to the DO's body while it holds.
    DoWhile(Cursor),
    /// WHILE, REPEAT: past the loop's end when it does not run.
    Loop(Dest),
    /// ENDWHILE: its WHILE; ENDREPEAT: its REPEAT's body.
    Back(Dest),
    /// BREAK, CONTINUE.
    Leave(Result<Rc<Leave>, &'static str>),
}

/// A source's O-word statements, in file order, and each one's index by
/// its line's offset.
#[derive(Debug, Default)]
pub(crate) struct Statements {
    pub entries: Vec<Entry>,
    pub at: HashMap<u64, usize>,
    /// Each label's SUB statements (more than one: defined twice).
    pub subs: HashMap<String, Vec<usize>>,
    /// Each statement's link, and the partner it lacks wherever the flow
    /// goes (an opening statement's end, a branch statement's IF).
    pub links: Vec<(Option<&'static str>, OLink)>,
}

/// The statements of each (scope, label), in file order: the partner
/// searches of the linking.
struct Index<'e> {
    entries: &'e [Entry],
    by: HashMap<usize, HashMap<&'e str, Vec<usize>>>,
}

impl<'e> Index<'e> {
    fn new(entries: &'e [Entry]) -> Index<'e> {
        let mut by: HashMap<usize, HashMap<&str, Vec<usize>>> = HashMap::new();
        for (i, e) in entries.iter().enumerate() {
            let scope = by.entry(e.scope).or_default();
            scope.entry(e.label.as_str()).or_default().push(i);
        }
        Index { entries, by }
    }

    fn group(&self, scope: usize, label: &str) -> &[usize] {
        self.by
            .get(&scope)
            .and_then(|labels| labels.get(label))
            .map_or(&[][..], Vec::as_slice)
    }

    /// The first statement from index `from` in `scope` with `label`, one
    /// of `kws`.
    fn find(&self, from: usize, scope: usize, label: &str, kws: &[Kw]) -> Option<&'e Entry> {
        let group = self.group(scope, label);
        let start = group.partition_point(|&j| j < from);
        group[start..]
            .iter()
            .map(|&j| &self.entries[j])
            .find(|e| kws.contains(&e.kw))
    }

    /// The last statement before index `before` in `scope` with `label`.
    fn find_back(&self, before: usize, scope: usize, label: &str, kws: &[Kw]) -> Option<&'e Entry> {
        let group = self.group(scope, label);
        let end = group.partition_point(|&j| j < before);
        group[..end]
            .iter()
            .rev()
            .map(|&j| &self.entries[j])
            .find(|e| kws.contains(&e.kw))
    }

    /// Past the next `kw` with the label of statement `i` in `scope`.
    fn past(&self, i: usize, scope: usize, kw: Kw, name: &'static str) -> Dest {
        self.find(i + 1, scope, &self.entries[i].label, &[kw])
            .map(|e| e.after)
            .ok_or(name)
    }

    /// After a false IF or ELSEIF `i`: the next ELSEIF or ELSE, or past
    /// the ENDIF.
    fn branch(&self, i: usize) -> Result<Branch, &'static str> {
        let e = &self.entries[i];
        let kws = [Kw::ElseIf, Kw::Else, Kw::EndIf];
        match self.find(i + 1, e.scope, &e.label, &kws) {
            Some(n) if n.kw == Kw::EndIf => Ok(Branch::End(n.after)),
            Some(n) => Ok(Branch::Test(n.here)),
            None => Err("endif"),
        }
    }

    /// The partner statement `i` needs wherever the flow goes, when it
    /// lacks it: an opening statement's end further on, a branch
    /// statement's IF before it.
    fn lacks(&self, i: usize) -> Option<&'static str> {
        let e = &self.entries[i];
        let end_of = match e.kw {
            Kw::Sub => Some((Kw::EndSub, "endsub")),
            Kw::If => Some((Kw::EndIf, "endif")),
            Kw::Do => Some((Kw::While, "while")),
            Kw::Repeat => Some((Kw::EndRepeat, "endrepeat")),
            Kw::While if e.closes_do.is_none() => Some((Kw::EndWhile, "endwhile")),
            _ => None,
        };
        // A sub's end lives in its own body's scope.
        let end_scope = if e.kw == Kw::Sub { i + 1 } else { e.scope };
        if let Some((kw, name)) = end_of
            && self.find(i + 1, end_scope, &e.label, &[kw]).is_none()
        {
            return Some(name);
        }
        let branch = matches!(e.kw, Kw::ElseIf | Kw::Else | Kw::EndIf);
        (branch && self.find_back(i, e.scope, &e.label, &[Kw::If]).is_none())
            .then_some("if before it")
    }

    /// BREAK or CONTINUE `i`: its loop's start before it, its end after.
    fn leave(&self, i: usize) -> Result<Rc<Leave>, &'static str> {
        let e = &self.entries[i];
        let loops = [Kw::While, Kw::Do, Kw::Repeat];
        let start = self.find_back(i, e.scope, &e.label, &loops).ok_or("loop")?;
        let end_kw = match start.kw {
            Kw::While => Kw::EndWhile,
            Kw::Do => Kw::While,
            _ => Kw::EndRepeat,
        };
        let end = self
            .find(i + 1, e.scope, &e.label, &[end_kw])
            .ok_or("loop end")?;
        // Entries are in file order: the loop's body is a slice of them.
        let entries = self.entries;
        let from = entries.partition_point(|x| x.here.offset <= start.here.offset);
        let to = entries.partition_point(|x| x.here.offset < end.here.offset);
        let breaks = e.kw == Kw::Break;
        let ending = entries[from..to.max(from)]
            .iter()
            .filter(|x| x.kw == Kw::Repeat && x.scope == e.scope)
            .map(|x| x.label.clone())
            .chain((breaks && start.kw == Kw::Repeat).then(|| start.label.clone()))
            .collect();
        let to = match (breaks, start.kw) {
            (true, _) => end.after,
            (false, Kw::While) => start.here,
            (false, _) => end.here,
        };
        Ok(Rc::new(Leave { to, ending }))
    }

    /// Statement `i`'s link.
    fn link(&self, i: usize, subs: &HashMap<String, Vec<usize>>) -> OLink {
        let e = &self.entries[i];
        let sc = e.scope;
        match e.kw {
            Kw::Sub => OLink::Sub(self.past(i, i + 1, Kw::EndSub, "endsub")),
            Kw::Call => OLink::Call(match subs.get(&e.label).map_or(&[][..], Vec::as_slice) {
                [] => Callee::File,
                [one] => Callee::Here(self.entries[*one].after),
                more => Callee::Twice(more.len()),
            }),
            Kw::EndSub | Kw::Return | Kw::Do | Kw::EndIf => OLink::Plain,
            Kw::If => OLink::If(self.branch(i)),
            Kw::ElseIf | Kw::Else => OLink::Clause {
                next: self.branch(i),
                end: self.past(i, sc, Kw::EndIf, "endif"),
            },
            Kw::While => match e.closes_do {
                Some(d) => OLink::DoWhile(self.entries[d].after),
                None => OLink::Loop(self.past(i, sc, Kw::EndWhile, "endwhile")),
            },
            Kw::Repeat => OLink::Loop(self.past(i, sc, Kw::EndRepeat, "endrepeat")),
            Kw::EndWhile => OLink::Back(
                self.find_back(i, sc, &e.label, &[Kw::While])
                    .map(|w| w.here)
                    .ok_or("while"),
            ),
            Kw::EndRepeat => OLink::Back(
                self.find_back(i, sc, &e.label, &[Kw::Repeat])
                    .map(|r| r.after)
                    .ok_or("repeat"),
            ),
            Kw::Break | Kw::Continue => OLink::Leave(self.leave(i)),
        }
    }
}

/// E611: the O-word statement `label kw` (spanning `span`) lacks
/// `wanted`.
pub(crate) fn unpaired(span: Span, label: &str, kw: Kw, wanted: &str) -> Diagnostic {
    alarms::bad_structure(
        span,
        format!("o{label} {kw:?} has no {wanted} with the same label").to_lowercase(),
        "pair every O-word statement with its end under the same label (o100 if … o100 endif)",
    )
}

pub(crate) fn defined_twice(span: Span, label: &str, times: usize, place: &str) -> Diagnostic {
    alarms::bad_structure(
        span,
        format!("o{label} sub is defined {times} times in {place}"),
        "give each subroutine its own label (rs274: \"redefining sub\")",
    )
}

/// The first statement from index `from` in `scope` with `label`, one of
/// `kws` (a G70–G72 profile's end: one search, no index).
fn find<'e>(
    entries: &'e [Entry],
    from: usize,
    scope: usize,
    label: &str,
    kws: &[Kw],
) -> Option<(usize, &'e Entry)> {
    entries
        .iter()
        .enumerate()
        .skip(from)
        .find(|(_, e)| e.scope == scope && e.label == label && kws.contains(&e.kw))
}

/// A subroutine file's name: ASCII letters, digits, `_`, `-` and `.`, not
/// starting with `.` — one file of the directory, never a path.
fn is_file_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name
            .bytes()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'-' | b'.'))
}

/// Lists the O-word statements of `src`'s text, from its start (the
/// reader is moved).
fn list(flow: &mut Flow, src: usize) -> Vec<Entry> {
    let mut entries: Vec<Entry> = Vec::new();
    // The DO each label of each scope has open.
    let mut open_do: HashMap<(usize, String), usize> = HashMap::new();
    // The scope of the statements being read: 0, or i + 1 inside the sub
    // of statement i.
    let mut scope = 0;
    let Some(s) = flow.source(src) else {
        return entries;
    };
    s.reader.seek(Cursor::default());
    loop {
        let line = match s.reader.next_line() {
            Ok(Some(l)) => l,
            Ok(None) | Err(ReadError::Io(_)) => break,
            Err(ReadError::TooLong { .. }) => continue,
        };
        let bytes = s.reader.bytes(&line);
        let Some(st) = o_statement(bytes, 0) else {
            continue;
        };
        let own = scope;
        scope = match st.kw {
            Kw::Sub => entries.len() + 1,
            Kw::EndSub => 0,
            _ => scope,
        };
        let here = Cursor {
            offset: line.offset,
            line: line.number,
            col: 0,
        };
        let key = (own, st.label.clone());
        let closes_do = match st.kw {
            Kw::Do => {
                open_do.insert(key, entries.len());
                None
            }
            Kw::While => open_do.remove(&key),
            _ => None,
        };
        entries.push(Entry {
            label: st.label,
            kw: st.kw,
            scope: own,
            closes_do,
            here,
            after: Cursor {
                col: vcnc_syntax::clamp_u32(bytes.len()),
                ..here
            },
        });
    }
    entries
}

impl Statements {
    /// The statements of a source's text, linked.
    fn linked(entries: Vec<Entry>) -> Statements {
        let at = entries
            .iter()
            .enumerate()
            .map(|(i, e)| (e.here.offset, i))
            .collect();
        let mut subs: HashMap<String, Vec<usize>> = HashMap::new();
        for (i, e) in entries.iter().enumerate().filter(|(_, e)| e.kw == Kw::Sub) {
            subs.entry(e.label.clone()).or_default().push(i);
        }
        let index = Index::new(&entries);
        let links = (0..entries.len())
            .map(|i| (index.lacks(i), index.link(i, &subs)))
            .collect();
        Statements {
            entries,
            at,
            subs,
            links,
        }
    }

    /// The statement on the line at `offset`: its index.
    pub(crate) fn index(&self, offset: u64) -> Option<usize> {
        self.at.get(&offset).copied()
    }

    /// The only `sub` of `label`: its index (`Err`: how many there are).
    fn sub(&self, label: &str) -> Result<usize, usize> {
        match self.subs.get(label).map_or(&[][..], Vec::as_slice) {
            [one] => Ok(*one),
            more => Err(more.len()),
        }
    }
}

impl Flow {
    /// The source of subroutine file `name.ngc`: an open one, else opened
    /// through the store (`None`: the store has no such file).
    fn open_sub_file(
        &mut self,
        name: &str,
        store: &mut dyn ProgramStore,
    ) -> std::io::Result<Option<usize>> {
        let file = format!("{name}.ngc");
        let open = self.sources.iter().position(|s| {
            s.as_ref().is_some_and(|s| {
                s.number.is_none()
                    && s.name
                        .as_deref()
                        .is_some_and(|n| n.rsplit(['/', '\\']).next() == Some(file.as_str()))
            })
        });
        if let Some(i) = open.filter(|&i| i != 0) {
            return Ok(Some(i));
        }
        match store.open_subroutine(name) {
            None => Ok(None),
            Some(Err(e)) => Err(e),
            Some(Ok((mut text, shown))) => {
                // An unreadable file alarms at the call.
                text.read_at(0, &mut [0u8; 1])?;
                let src = Source {
                    reader: vcnc_syntax::LineReader::new(text),
                    name: Some(shown.into()),
                    number: None,
                    id: 0,
                };
                Ok(Some(self.install(src)))
            }
        }
    }
}

impl Interpreter<'_> {
    /// The O-word statements of source `src`, listed and linked once from
    /// its start.
    pub(crate) fn oword_statements(&mut self, src: usize) -> Result<Rc<Statements>, Diagnostic> {
        let id = self.source_id(src);
        let owords = &self.macros.structure.owords;
        if let Some((_, e)) = owords.iter().find(|(i, _)| *i == id) {
            return Ok(Rc::clone(e));
        }
        let entries = list(&mut self.flow, src);
        // The scan moved the reader: the statement's step seeks again.
        self.macros.moved_reader = true;
        let statements = Rc::new(Statements::linked(entries));
        self.macros
            .structure
            .owords
            .push((id, Rc::clone(&statements)));
        Ok(statements)
    }

    /// A call of subroutine `name`, which its program does not define:
    /// the body of the `sub` of the file `NAME.ngc` in the program
    /// directories (LinuxCNC's subroutine path), opened once: (its source,
    /// where the body starts). The name is checked to be a plain file name
    /// before the store sees it, so `o<../x>` or `o</etc/x>` reads nothing.
    pub(crate) fn sub_file(
        &mut self,
        name: &str,
        span: Span,
        store: &mut dyn ProgramStore,
    ) -> Result<(usize, Cursor), Diagnostic> {
        if !is_file_name(name) {
            return Err(alarms::bad_structure(
                span,
                format!(
                    "o<{name}> call: no o<{name}> sub in this program, and `{name}` names no file of the program directory"
                ),
                "a subroutine kept in its own file is called by its file name: letters, digits, _ and - (o<probe> call reads probe.ngc from the --program-dir; no path)",
            ));
        }
        let src = match self.flow.open_sub_file(name, store) {
            Ok(Some(src)) => src,
            Ok(None) => {
                return Err(alarms::bad_structure(
                    span,
                    format!(
                        "o<{name}> call: no o<{name}> sub in this program, and no {name}.ngc in the program directory"
                    ),
                    "define the subroutine in this file, or put it in NAME.ngc in the --program-dir; as in LinuxCNC, names are read in lower case, so the file name must be lower case (o<MySub> call reads mysub.ngc, not MySub.ngc)",
                ));
            }
            Err(e) => return Err(alarms::sub_file_unreadable(span, name, &e)),
        };
        let statements = self.oword_statements(src)?;
        match statements.sub(name) {
            Ok(one) => Ok((src, statements.entries[one].after)),
            Err(0) => Err(alarms::bad_structure(
                span,
                format!("o<{name}> call: {name}.ngc defines no o<{name}> sub"),
                "a subroutine file holds o<NAME> sub … o<NAME> endsub under its own name",
            )),
            Err(more) => Err(defined_twice(span, name, more, &format!("{name}.ngc"))),
        }
    }

    /// LinuxCNC's G70–G72 profile `o<label> sub … o<label> endsub` in the
    /// running source: the source, the `sub` line (its cursor past the
    /// statement) and the `endsub` line's offset.
    pub(crate) fn ngc_sub_lines(
        &mut self,
        label: &str,
        span: Span,
    ) -> Result<(usize, Cursor, u64), Diagnostic> {
        let src = self.flow.frame().source;
        let statements = self.oword_statements(src)?;
        // The scan moved the reader: the cycle reads the profile, then the
        // run goes on after the cycle block (a seek).
        self.macros.moved_reader = false;
        let entries = &statements.entries;
        let missing = || {
            alarms::bad_structure(
                span,
                format!(
                    "no o{label} sub … o{label} endsub in this program for the cycle's profile"
                ),
                "write the profile as a subroutine of this file: o100 sub, its blocks, o100 endsub; Q names it",
            )
        };
        match statements.sub(label) {
            Ok(one) => {
                let sub = &entries[one];
                let (_, end) =
                    find(entries, one + 1, one + 1, label, &[Kw::EndSub]).ok_or_else(missing)?;
                Ok((src, sub.after, end.here.offset))
            }
            Err(0) => Err(missing()),
            Err(more) => Err(defined_twice(span, label, more, "this program")),
        }
    }
}

/// LinuxCNC's O-word flow as it runs (the statements' links are found
/// once, `structure.rs`).
#[derive(Debug, Default)]
pub(crate) struct OFlow {
    /// Repeat loops running: (label, remaining passes).
    pub(crate) repeats: Vec<(String, f64)>,
    /// The ELSEIF or ELSE a false branch jumped to, to be tested (not
    /// skipped as the end of a branch that ran): its line's offset.
    pub(crate) pending: Option<u64>,
    /// The locals of each subroutine call running, and how many repeat
    /// loops ran when it was called (a return leaves the sub's own).
    pub(crate) saved: Vec<(crate::macros::ngc::Saved, usize)>,
}

/// Where an O-word statement goes on.
pub(crate) enum OStep {
    Next,
    /// Forward, free.
    Jump(Cursor),
    /// Back (a loop's pass, a CONTINUE): counted against `max_jumps`.
    Back(Cursor),
}

impl OFlow {
    /// Follows the link of the branch or loop statement `kw` of `label` on
    /// the line at `here`: `cond` is its operand, `unpaired` the alarm for
    /// a partner its link lacks.
    pub(crate) fn follow(
        &mut self,
        (kw, label, here): (Kw, &str, u64),
        link: &OLink,
        cond: impl Fn() -> Result<f64, Diagnostic>,
        unpaired: impl Fn(&str) -> Diagnostic,
    ) -> Result<OStep, Diagnostic> {
        let ahead = |d: &Result<Cursor, &str>| d.map(OStep::Jump).map_err(&unpaired);
        Ok(match link {
            OLink::Sub(end) => ahead(end)?,
            OLink::Plain | OLink::Call(_) => OStep::Next,
            OLink::If(next) => {
                if cond()? != 0.0 {
                    OStep::Next
                } else {
                    OStep::Jump(self.branch(next.map_err(&unpaired)?))
                }
            }
            // Run into from the branch before (not tested): past the ENDIF.
            OLink::Clause { end, .. } if self.pending.take() != Some(here) => ahead(end)?,
            OLink::Clause { next, .. } => {
                if kw == Kw::Else || cond()? != 0.0 {
                    OStep::Next
                } else {
                    OStep::Jump(self.branch(next.map_err(&unpaired)?))
                }
            }
            OLink::DoWhile(body) if cond()? != 0.0 => OStep::Back(*body),
            OLink::DoWhile(_) => OStep::Next,
            OLink::Loop(end) if kw == Kw::Repeat => {
                // rs274 rounds the count half to even: [2.5] is 2 passes.
                let n = cond()?.round_ties_even();
                if n >= 1.0 {
                    self.repeats.push((label.to_string(), n));
                    OStep::Next
                } else {
                    ahead(end)?
                }
            }
            OLink::Loop(end) if cond()? == 0.0 => ahead(end)?,
            OLink::Loop(_) => OStep::Next,
            OLink::Back(body) if kw == Kw::EndRepeat => {
                let body = body.map_err(&unpaired)?;
                match self.again(label) {
                    Some(true) => OStep::Back(body),
                    Some(false) => OStep::Next,
                    None => return Err(unpaired("repeat running")),
                }
            }
            OLink::Back(head) => OStep::Back(head.map_err(&unpaired)?),
            OLink::Leave(lp) => {
                let lp = lp.as_ref().map_err(|w| unpaired(w))?;
                self.leave(&lp.ending);
                match kw {
                    Kw::Continue => OStep::Back(lp.to),
                    _ => OStep::Jump(lp.to),
                }
            }
        })
    }

    /// Where a false IF or ELSEIF goes: past the ENDIF, or to the next
    /// clause, to be tested there.
    fn branch(&mut self, b: Branch) -> Cursor {
        match b {
            Branch::End(to) => to,
            Branch::Test(to) => {
                self.pending = Some(to.offset);
                to
            }
        }
    }

    /// ENDREPEAT of `label`: whether another pass runs (`None`: no repeat
    /// of that label is running).
    fn again(&mut self, label: &str) -> Option<bool> {
        match self.repeats.last_mut() {
            Some((l, left)) if l == label && *left > 1.0 => {
                *left -= 1.0;
                Some(true)
            }
            Some((l, _)) if l == label => {
                self.repeats.pop();
                Some(false)
            }
            _ => None,
        }
    }

    /// BREAK or CONTINUE: the repeat loops running that end with it.
    fn leave(&mut self, ending: &[String]) {
        while self.repeats.last().is_some_and(|(l, _)| ending.contains(l)) {
            self.repeats.pop();
        }
    }
}
