//! LinuxCNC's O-word statements (`--dialect linuxcnc`): subroutines of
//! the program's own file and the structured flow between them.
//!
//! ```text
//!   o100 sub            (skipped when the flow reaches it)
//!     G1 X#1 Y#2          #1–#30: the call's arguments, local
//!   o100 endsub [#3]    (back to the line after the call; #<_value>)
//!   o100 call [10] [20]
//!   o101 if [#1 GT 0] … o101 elseif […] … o101 else … o101 endif
//!   o102 while [c] … o102 endwhile      o103 do … o103 while [c]
//!   o104 repeat [n] … o104 endrepeat    break / continue / return
//! ```
//!
//! The first O-word statement of a source has `structure.rs`, where all
//! loop and branch pairing lives, read the whole file once for its
//! statements (label, keyword, line: `vcnc_syntax::macros::o_statement`),
//! so that each jump finds where it goes without searching the text again. A statement's partner is the
//! next one with the same label in the file (the previous one for the
//! loops' ends). Every jump counts against `limits.max_jumps`, calls
//! against `limits.max_call_depth`. A call of a subroutine the program
//! does not define reads the file `NAME.ngc` of the program directories
//! (LinuxCNC's subroutine path), once, through the `ProgramStore`; the name
//! must be a plain file name, so no call reads outside those directories.

use super::structure::{Entry, find, find_back};
use crate::alarms;
use crate::flow::ProgramStore;
use crate::interpreter::{Interpreter, Step};
use vcnc_syntax::macros::{Kw, OStmt, o_statement};
use vcnc_syntax::{Cursor, Diagnostic, Line, Span};

/// The flow's own state (the statements of each source are listed by
/// `structure.rs`).
#[derive(Debug, Default)]
pub(crate) struct Flow {
    /// Repeat loops running: (label, remaining passes).
    repeats: Vec<(String, f64)>,
    /// The ELSEIF or ELSE a false branch jumped to, to be tested (not
    /// skipped as the end of a branch that ran).
    pending: Option<u64>,
    /// The locals of each subroutine call running, and how many repeat
    /// loops ran when it was called (a return leaves the sub's own).
    saved: Vec<(super::ngc::Saved, usize)>,
}

/// A jump past the next `kw` with the statement's label in `scope` (its
/// end).
fn past(
    entries: &[Entry],
    from: usize,
    scope: usize,
    st: &OStmt,
    kw: Kw,
    span: Span,
) -> Result<Step, Diagnostic> {
    find(entries, from, scope, &st.label, &[kw])
        .map(|(_, e)| Step::Jump(e.after))
        .ok_or_else(|| unpaired(span, st, &format!("{kw:?}").to_lowercase()))
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

fn defined_twice(span: Span, label: &str, times: usize, place: &str) -> Diagnostic {
    alarms::bad_structure(
        span,
        format!("o{label} sub is defined {times} times in {place}"),
        "give each subroutine its own label (rs274: \"redefining sub\")",
    )
}

fn unpaired(span: Span, st: &OStmt, wanted: &str) -> Diagnostic {
    alarms::bad_structure(
        span,
        format!(
            "o{} {:?} has no {wanted} with the same label",
            st.label, st.kw
        )
        .to_lowercase(),
        "pair every O-word statement with its end under the same label (o100 if … o100 endif)",
    )
}

impl Interpreter<'_> {
    /// Runs the O-word statement of `line` (from `start`); `lexed` is the
    /// lexer's alarm, kept for a line that is no O-word statement.
    pub(crate) fn ngc_oword(
        &mut self,
        src: usize,
        line: &Line,
        start: usize,
        lexed: Diagnostic,
        i: &mut usize,
        store: &mut dyn ProgramStore,
    ) -> Result<(Step, Span), Diagnostic> {
        let Some(s) = self.flow.source(src) else {
            return Err(lexed);
        };
        let bytes = s.reader.bytes(line).to_vec();
        let Some(st) = o_statement(&bytes, start) else {
            return Err(lexed);
        };
        let span = Span::new(start, bytes.len());
        *i = bytes.len();
        let statements = self.oword_statements(src)?;
        let entries = &statements.entries;
        let here_at = *statements
            .at
            .get(&line.offset)
            .ok_or_else(|| unpaired(span, &st, "place in the program"))?;
        let here = entries[here_at].clone();
        let sc = here.scope;
        let values = self.evaluator().ngc_operands(&bytes, st.rest)?;
        let value = values.first().copied();
        let cond = || value.ok_or_else(|| unpaired(span, &st, "[condition]"));
        let next = here_at + 1;
        // An opening statement needs its end further on, whichever way
        // the flow goes (rs274 reads the whole structure).
        let end_of = match st.kw {
            Kw::Sub => Some((Kw::EndSub, "endsub")),
            Kw::If => Some((Kw::EndIf, "endif")),
            Kw::Do => Some((Kw::While, "while")),
            Kw::Repeat => Some((Kw::EndRepeat, "endrepeat")),
            Kw::While if here.closes_do.is_none() => Some((Kw::EndWhile, "endwhile")),
            _ => None,
        };
        // A sub's end lives in its own body's scope.
        let end_scope = if st.kw == Kw::Sub { here_at + 1 } else { sc };
        if let Some((kw, name)) = end_of
            && find(entries, next, end_scope, &st.label, &[kw]).is_none()
        {
            return Err(unpaired(span, &st, name));
        }
        // A branch's other statements need their IF before them.
        if matches!(st.kw, Kw::ElseIf | Kw::Else | Kw::EndIf)
            && find_back(entries, here_at, sc, &st.label, &[Kw::If]).is_none()
        {
            return Err(unpaired(span, &st, "if before it"));
        }
        let step = match st.kw {
            Kw::Sub => past(entries, next, here_at + 1, &st, Kw::EndSub, span)?,
            Kw::Call => {
                let subs = statements
                    .subs
                    .get(&st.label)
                    .map_or(&[][..], Vec::as_slice);
                let (source, start) = match subs {
                    [] => self.sub_file(&st, span, store)?,
                    [one] => (None, entries[*one].after),
                    more => return Err(defined_twice(span, &st.label, more.len(), "this program")),
                };
                self.ngc_call(span, source, start, here.after, &values)?;
                Step::Jump(start)
            }
            Kw::EndSub | Kw::Return => self.ngc_return(span, value)?,
            Kw::If => {
                if cond()? != 0.0 {
                    Step::Next
                } else {
                    self.next_branch(entries, next, sc, &st, span)?
                }
            }
            Kw::ElseIf => {
                if self.oword_flow().pending.take() == Some(here.here.offset) {
                    if cond()? != 0.0 {
                        Step::Next
                    } else {
                        self.next_branch(entries, next, sc, &st, span)?
                    }
                } else {
                    past(entries, next, sc, &st, Kw::EndIf, span)?
                }
            }
            Kw::Else => {
                if self.oword_flow().pending.take() == Some(here.here.offset) {
                    Step::Next
                } else {
                    past(entries, next, sc, &st, Kw::EndIf, span)?
                }
            }
            Kw::EndIf | Kw::Do => Step::Next,
            Kw::While => {
                match here.closes_do.map(|d| &entries[d]) {
                    // `o103 do … o103 while [c]`: back to the body while c.
                    Some(d) if cond()? != 0.0 => {
                        let to = d.after;
                        self.count_jump(span)?;
                        Step::Jump(to)
                    }
                    Some(_) => Step::Next,
                    None if cond()? != 0.0 => Step::Next,
                    None => past(entries, next, sc, &st, Kw::EndWhile, span)?,
                }
            }
            Kw::EndWhile => {
                let start = find_back(entries, here_at, sc, &st.label, &[Kw::While])
                    .ok_or_else(|| unpaired(span, &st, "while"))?
                    .here;
                self.count_jump(span)?;
                Step::Jump(start)
            }
            Kw::Repeat => {
                // rs274 rounds the count half to even: [2.5] is 2 passes.
                let n = cond()?.round_ties_even();
                if n >= 1.0 {
                    self.oword_flow().repeats.push((st.label.clone(), n));
                    Step::Next
                } else {
                    past(entries, next, sc, &st, Kw::EndRepeat, span)?
                }
            }
            Kw::EndRepeat => {
                let start = find_back(entries, here_at, sc, &st.label, &[Kw::Repeat])
                    .ok_or_else(|| unpaired(span, &st, "repeat"))?
                    .after;
                let flow = self.oword_flow();
                match flow.repeats.last_mut() {
                    Some((label, left)) if *label == st.label && *left > 1.0 => {
                        *left -= 1.0;
                        self.count_jump(span)?;
                        Step::Jump(start)
                    }
                    Some((label, _)) if *label == st.label => {
                        flow.repeats.pop();
                        Step::Next
                    }
                    _ => return Err(unpaired(span, &st, "repeat running")),
                }
            }
            Kw::Break | Kw::Continue => self.break_or_continue(entries, here_at, &st, span)?,
        };
        // The statements' scan may have moved the reader: go on from here.
        self.macros.moved_reader = false;
        let step = match step {
            Step::Next => Step::Jump(here.after),
            s => s,
        };
        Ok((step, span))
    }

    fn oword_flow(&mut self) -> &mut Flow {
        self.macros.oword.get_or_insert_with(Box::default)
    }

    /// After a false IF or ELSEIF: to the next ELSEIF or ELSE, to be
    /// tested there, or past the ENDIF.
    fn next_branch(
        &mut self,
        entries: &[Entry],
        from: usize,
        scope: usize,
        st: &OStmt,
        span: Span,
    ) -> Result<Step, Diagnostic> {
        let (_, e) = find(
            entries,
            from,
            scope,
            &st.label,
            &[Kw::ElseIf, Kw::Else, Kw::EndIf],
        )
        .ok_or_else(|| unpaired(span, st, "endif"))?;
        if e.kw == Kw::EndIf {
            return Ok(Step::Jump(e.after));
        }
        self.oword_flow().pending = Some(e.here.offset);
        Ok(Step::Jump(e.here))
    }

    /// BREAK: past the end of the loop with this label; CONTINUE: to its
    /// test (a WHILE), or its end (a REPEAT's pass counts there).
    fn break_or_continue(
        &mut self,
        entries: &[Entry],
        here_at: usize,
        st: &OStmt,
        span: Span,
    ) -> Result<Step, Diagnostic> {
        let scope = entries[here_at].scope;
        let start = find_back(
            entries,
            here_at,
            scope,
            &st.label,
            &[Kw::While, Kw::Do, Kw::Repeat],
        )
        .ok_or_else(|| unpaired(span, st, "loop"))?
        .clone();
        let end_kw = match start.kw {
            Kw::While => Kw::EndWhile,
            Kw::Do => Kw::While,
            _ => Kw::EndRepeat,
        };
        let (_, end) = find(entries, here_at + 1, scope, &st.label, &[end_kw])
            .ok_or_else(|| unpaired(span, st, "loop end"))?;
        let end = end.clone();
        // The repeats running inside the loop end with it (a BREAK also
        // ends the loop's own, when it is a REPEAT).
        // Entries are in file order: the loop's body is a slice of them.
        let from = entries.partition_point(|e| e.here.offset <= start.here.offset);
        let to = entries.partition_point(|e| e.here.offset < end.here.offset);
        let inner: Vec<String> = entries[from..to.max(from)]
            .iter()
            .filter(|e| e.kw == Kw::Repeat && e.scope == scope)
            .map(|e| e.label.clone())
            .chain((st.kw == Kw::Break && start.kw == Kw::Repeat).then(|| start.label.clone()))
            .collect();
        let repeats = &mut self.oword_flow().repeats;
        while repeats.last().is_some_and(|(l, _)| inner.contains(l)) {
            repeats.pop();
        }
        if st.kw == Kw::Break {
            return Ok(Step::Jump(end.after));
        }
        self.count_jump(span)?;
        Ok(Step::Jump(match start.kw {
            Kw::While => start.here,
            _ => end.here,
        }))
    }

    /// O CALL: a level of the flow like a subprogram's, the locals saved;
    /// `source` is a subroutine file's (`None`: the running one's).
    fn ngc_call(
        &mut self,
        span: Span,
        source: Option<usize>,
        start: Cursor,
        ret: Cursor,
        args: &[f64],
    ) -> Result<(), Diagnostic> {
        self.check_call_depth(span)?;
        self.count_jump(span)?;
        let saved = self.macros.ngc.get_or_insert_with(Box::default).enter(args);
        let flow = self.oword_flow();
        let repeats = flow.repeats.len();
        flow.saved.push((saved, repeats));
        match source {
            None => self.enter_local_sub(start, ret, "endsub"),
            Some(src) => self.enter_sub_in(src, start, ret, "endsub"),
        }
        Ok(())
    }

    /// A call of a subroutine its program does not define: the `sub` of
    /// the file `NAME.ngc` in the program directories (LinuxCNC's
    /// subroutine path), opened once. The name is checked to be a plain
    /// file name before the store sees it, so `o<../x>` or `o</etc/x>`
    /// reads nothing.
    fn sub_file(
        &mut self,
        st: &OStmt,
        span: Span,
        store: &mut dyn ProgramStore,
    ) -> Result<(Option<usize>, Cursor), Diagnostic> {
        let name = st.label.as_str();
        if !is_file_name(name) {
            return Err(alarms::bad_structure(
                span,
                format!(
                    "o<{name}> call: no o<{name}> sub in this program, and `{name}` names no file of the program directory"
                ),
                "a subroutine kept in its own file is called by its file name: letters, digits, _ and - (o<probe> call reads probe.ngc from the --program-dir; no path)",
            ));
        }
        let src = match self.open_sub_file(name, store) {
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
        match statements.subs.get(name).map_or(&[][..], Vec::as_slice) {
            [one] => Ok((Some(src), statements.entries[*one].after)),
            [] => Err(alarms::bad_structure(
                span,
                format!("o<{name}> call: {name}.ngc defines no o<{name}> sub"),
                "a subroutine file holds o<NAME> sub … o<NAME> endsub under its own name",
            )),
            more => Err(defined_twice(
                span,
                name,
                more.len(),
                &format!("{name}.ngc"),
            )),
        }
    }

    /// The source of subroutine file `name.ngc`: an open one, else opened
    /// through the store (`None`: the store has no such file).
    fn open_sub_file(
        &mut self,
        name: &str,
        store: &mut dyn ProgramStore,
    ) -> std::io::Result<Option<usize>> {
        let file = format!("{name}.ngc");
        let open = self.flow.sources.iter().position(|s| {
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
                let src = crate::flow::Source {
                    reader: vcnc_syntax::LineReader::new(text),
                    name: Some(shown.into()),
                    number: None,
                    id: 0,
                };
                Ok(Some(self.flow.install(src)))
            }
        }
    }

    /// ENDSUB or RETURN: the caller's locals back, `#<_value>` set.
    fn ngc_return(&mut self, span: Span, value: Option<f64>) -> Result<Step, Diagnostic> {
        let flow = self.oword_flow();
        let Some((saved, repeats)) = flow.saved.pop() else {
            return Err(alarms::bad_structure(
                span,
                "endsub or return with no o-word call to return to".into(),
                "reach a subroutine's body only through o… call",
            ));
        };
        flow.repeats.truncate(repeats);
        flow.pending = None;
        self.macros
            .ngc
            .get_or_insert_with(Box::default)
            .leave(saved, value);
        self.sub_return(span)
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
        match statements.subs.get(label).map_or(&[][..], Vec::as_slice) {
            [one] => {
                let sub = &entries[*one];
                let (_, end) =
                    find(entries, one + 1, one + 1, label, &[Kw::EndSub]).ok_or_else(missing)?;
                Ok((src, sub.after, end.here.offset))
            }
            [] => Err(missing()),
            more => Err(defined_twice(span, label, more.len(), "this program")),
        }
    }
}
