//! Macro statements: assignments, jumps, loops, branches and calls of
//! procedures, run with the guarantees of a block.
//!
//! A statement counts as an executed block (the runaway budget), every
//! backward jump and every GOTO counts against `limits.max_jumps`, and its
//! events (messages, a frame changed by a work-offset variable) wait in the
//! block's `pending` list until it has succeeded. An alarm leaves the
//! variables as they were: an assignment writes last, after everything that
//! can fail.
//!
//! ```text
//!   Macro B   WHILE [c] DO m   c holds: next block; else after END m
//!             END m            back to the WHILE (it tests again)
//!             IF [c] GOTO n    GOTO n: the first N n of the program
//!   Syntec    IF/ELSEIF        the first clause whose condition holds; a
//!                              clause's end skips to after END_IF
//!             CASE e OF        the label holding e, else ELSE, else END_CASE
//!             FOR v := a TO b BY s   v := a, then v += s at END_FOR, while
//!                              v <= b (s > 0) or v >= b (s < 0)
//!             REPEAT … UNTIL c END_REPEAT   again while c fails
//!             EXIT             after the innermost loop
//! ```

use super::Evaluator;
use super::structure::{Callee, Link, OLink, OStep};
use super::{Compiled, key};
use crate::alarms;
use crate::flow::ProgramStore;
use crate::interpreter::{Interpreter, Step};
use std::rc::Rc;
use vcnc_core::Sink;
use vcnc_core::events::Event;
use vcnc_syntax::macros::{BinOp, Expr, Kw, Lang, StmtKind, Target, Value, VarKind};
use vcnc_syntax::{Cursor, Diagnostic, Span};

impl Interpreter<'_> {
    /// Runs a statement that is not a word block, all or nothing.
    pub(crate) fn macro_statement<S: Sink>(
        &mut self,
        c: &Rc<Compiled>,
        src: usize,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        if let Some(f) = self.flow.frames.last_mut() {
            f.started = true;
        }
        self.count_executed(c.st.first)?;
        let mark = self.stage.pending.len();
        let jumps = self.flow.jumps;
        let result = self.statement(c, src);
        match &result {
            Ok(_) => {
                self.tables.commit();
                self.machining().report_frame();
                self.hand_over_when_full(sink);
            }
            Err(_) => {
                self.stage.pending.truncate(mark);
                self.tables.rollback();
                self.flow.jumps = jumps;
            }
        }
        result
    }

    fn statement(&mut self, c: &Rc<Compiled>, src: usize) -> Result<Step, Diagnostic> {
        let lang = c.lang;
        let first = c.st.first;
        match &c.st.kind {
            StmtKind::Assign { target, value } => {
                self.evaluator()
                    .assign(target, value, lang, c.st.comment.as_deref())?;
                Ok(Step::Next)
            }
            StmtKind::Goto { word, target } => self.goto(c, src, *word, target),
            StmtKind::IfGoto { cond, word, target } => {
                let held = self.evaluator().holds(cond, lang);
                if self.or_false(held, c, src, |_, _, _, _| Ok(Step::Next))? {
                    self.goto(c, src, *word, target)
                } else {
                    Ok(Step::Next)
                }
            }
            StmtKind::IfThen { cond, then } => {
                if self.evaluator().holds(cond, lang)?
                    && let StmtKind::Assign { target, value } = then.as_ref()
                {
                    self.evaluator()
                        .assign(target, value, lang, c.st.comment.as_deref())?;
                }
                Ok(Step::Next)
            }
            StmtKind::While { cond, .. } => {
                let go_on = match cond {
                    Some(e) => {
                        let held = self.evaluator().holds(e, lang);
                        self.or_false(held, c, src, Self::follow)?
                    }
                    None => true,
                };
                if go_on {
                    return Ok(Step::Next);
                }
                self.follow(c, src, first)
            }
            StmtKind::WhileDo(cond) => {
                let held = self.evaluator().holds(cond, lang);
                if self.or_false(held, c, src, Self::follow)? {
                    return Ok(Step::Next);
                }
                self.follow(c, src, first)
            }
            StmtKind::Until(cond) => {
                let held = self.evaluator().holds(cond, lang);
                if self.or_false(held, c, src, Self::follow)? {
                    return Ok(Step::Next);
                }
                self.follow(c, src, first)
            }
            StmtKind::End(_)
            | StmtKind::EndWhile
            | StmtKind::Exit
            | StmtKind::ElseIf(_)
            | StmtKind::Else
            | StmtKind::CaseLabel(_) => self.follow(c, src, first),
            StmtKind::EndFor => {
                let to = self.link_to(c, src)?;
                self.macros.for_resume = Some(key(self.source_id(src), to));
                self.count_jump(first)?;
                Ok(Step::Jump(to))
            }
            StmtKind::If(cond) => {
                let held = self.evaluator().holds(cond, lang);
                if self.or_false(held, c, src, Self::else_branch)? {
                    return Ok(Step::Next);
                }
                self.else_branch(c, src, first)
            }
            StmtKind::Case(selector) => self.case(c, src, selector),
            StmtKind::For { var, from, to, by } => {
                self.for_loop(c, src, var, from, to, by.as_ref())
            }
            StmtKind::Call(e) => {
                self.evaluator().eval(e, lang)?;
                Ok(Step::Next)
            }
            StmtKind::EndIf | StmtKind::EndCase | StmtKind::Repeat => Ok(Step::Next),
            // A LinuxCNC line runs through `run_ngc_line` (front.rs), from
            // the statement cache too (`macro_cached`).
            // and an O-word statement through `o_word` (below): neither is
            // counted as a block.
            StmtKind::Words(_) | StmtKind::Percent | StmtKind::Line(_) | StmtKind::OWord { .. } => {
                Ok(Step::Next)
            }
        }
    }

    /// GOTO n: the first block `N n` of the current program; in Macro B
    /// not into a DO loop that does not hold the GOTO.
    /// A condition's value, or under keep-going, when it cannot be
    /// evaluated, its alarm with the run to resume where the condition's
    /// false branch goes (`on_false`: past the loop, to the ELSE):
    /// falling into a loop's body instead, the loop met the same alarm at
    /// each pass up to the alarm limit, or the run ended.
    #[inline(always)]
    fn or_false(
        &mut self,
        held: Result<bool, Diagnostic>,
        c: &Compiled,
        src: usize,
        on_false: fn(&mut Self, &Compiled, usize, Span) -> Result<Step, Diagnostic>,
    ) -> Result<bool, Diagnostic> {
        match held {
            Ok(held) => Ok(held),
            Err(d) => Err(self.false_after_alarm(d, c, src, on_false)),
        }
    }

    /// [`Self::or_false`]'s alarm, out of line.
    #[cold]
    #[inline(never)]
    fn false_after_alarm(
        &mut self,
        d: Diagnostic,
        c: &Compiled,
        src: usize,
        on_false: fn(&mut Self, &Compiled, usize, Span) -> Result<Step, Diagnostic>,
    ) -> Diagnostic {
        if self.cfg.opts.keep_going
            && let Ok(Step::Jump(to)) = on_false(self, c, src, c.st.first)
        {
            self.looping.after_alarm = Some(to);
        }
        d
    }

    fn goto(
        &mut self,
        c: &Compiled,
        src: usize,
        word: Span,
        target: &Expr,
    ) -> Result<Step, Diagnostic> {
        let span = target.span;
        let v = self.evaluator().eval(target, c.lang)?;
        let Some(x) = v.number() else {
            return Err(alarms::vacant_value(span, "the sequence number of a GOTO"));
        };
        if x.fract() != 0.0 || !(0.0..=99_999_999.0).contains(&x) {
            return Err(alarms::macro_domain(
                span,
                &format!("GOTO {x}: a sequence number is a whole number 0 to 99999999"),
            ));
        }
        // Whole and in range, checked above.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = x as u32;
        let lex = self.cfg.dialect.lex;
        let frame = self.flow.frame();
        let to = self
            .flow
            .find_sequence(frame.source, frame.program, n, &lex)
            .ok_or_else(|| alarms::sequence_not_found(span, n))?;
        if super::eval::arith(c.lang).goto_into_loop_alarms {
            self.not_into_a_loop(c, src, word, n, to)?;
        }
        self.count_jump(span)?;
        Ok(Step::Jump(to))
    }

    /// Fanuc 0i: a branch may leave a DO–END range but not enter one from
    /// outside. Syntec MACRO loops are not checked: its §4.8 shows a GOTO
    /// back into a FOR running (and only advises against it).
    fn not_into_a_loop(
        &mut self,
        c: &Compiled,
        src: usize,
        word: Span,
        n: u32,
        to: Cursor,
    ) -> Result<(), Diagnostic> {
        // Pairs the program's loops if a call scanned another since.
        self.ensure_structure(src)?;
        let Some(loops) = self.macros.structure.loops(self.program_key()) else {
            return Ok(());
        };
        match loops.iter().find(|r| r.holds(to) && !r.holds(c.here)) {
            Some(r) => Err(alarms::goto_into_loop(word, n, r.m, r.line)),
            None => Ok(()),
        }
    }

    /// The statement's link, found by the structure scan.
    fn link(&self, c: &Compiled, src: usize) -> Result<Link, Diagnostic> {
        self.macros
            .structure
            .links
            .get(&key(self.source_id(src), c.here))
            .cloned()
            .ok_or_else(|| {
                alarms::bad_structure(
                    c.st.first,
                    "this statement has no matching loop or branch statement".into(),
                    "check the pairing of the program's loops and branches",
                )
            })
    }

    fn link_to(&self, c: &Compiled, src: usize) -> Result<Cursor, Diagnostic> {
        if let Some(to) = c.target.get() {
            return Ok(to);
        }
        let to = match self.link(c, src)? {
            Link::Exit(to) | Link::Back(to) | Link::Skip(to) => to,
            Link::If(chain) => chain.end,
            Link::Case(table) => table.end,
        };
        // Links never change once found: the next pass jumps at once.
        c.target.set(Some(to));
        Ok(to)
    }

    /// Jumps where the statement's link says (a loop's end or head, a
    /// branch's end), counting the jump.
    fn follow(&mut self, c: &Compiled, src: usize, span: Span) -> Result<Step, Diagnostic> {
        let to = self.link_to(c, src)?;
        self.count_jump(span)?;
        Ok(Step::Jump(to))
    }

    /// An IF whose condition failed: the first ELSEIF that holds, the ELSE,
    /// or after END_IF.
    fn else_branch(&mut self, c: &Compiled, src: usize, span: Span) -> Result<Step, Diagnostic> {
        let Link::If(chain) = self.link(c, src)? else {
            return self.follow(c, src, span);
        };
        let mut to = chain.end;
        for clause in &chain.clauses {
            match &clause.cond {
                None => {
                    to = clause.body;
                    break;
                }
                Some(cond) => {
                    let StmtKind::ElseIf(e) = &cond.st.kind else {
                        continue;
                    };
                    let holds = self
                        .evaluator()
                        .holds(e, cond.lang)
                        .map_err(|d| self.locate_compiled(d, src, cond))?;
                    if holds {
                        to = clause.body;
                        break;
                    }
                }
            }
        }
        self.count_jump(span)?;
        Ok(Step::Jump(to))
    }

    fn case(&mut self, c: &Compiled, src: usize, selector: &Expr) -> Result<Step, Diagnostic> {
        let v = self.evaluator().eval(selector, c.lang)?;
        let Some(x) = v.number() else {
            return Err(alarms::vacant_value(
                selector.span,
                "the selector of a CASE",
            ));
        };
        let Link::Case(table) = self.link(c, src)? else {
            return self.follow(c, src, c.st.first);
        };
        let hit = (x.fract() == 0.0)
            .then(|| {
                table
                    .labels
                    .iter()
                    .find(|(values, _)| values.iter().any(|v| *v as f64 == x))
            })
            .flatten()
            .map(|(_, body)| *body);
        let to = hit.or(table.otherwise).unwrap_or(table.end);
        self.count_jump(c.st.first)?;
        Ok(Step::Jump(to))
    }

    #[allow(clippy::too_many_arguments)]
    fn for_loop(
        &mut self,
        c: &Compiled,
        src: usize,
        var: &Target,
        from: &Expr,
        to: &Expr,
        by: Option<&Expr>,
    ) -> Result<Step, Diagnostic> {
        let lang = c.lang;
        let here = key(self.source_id(src), c.here);
        let stepping = self.macros.for_resume == Some(here);
        let (kind, n) = self.evaluator().target_var(var, lang)?;
        let step = match by {
            Some(e) => {
                let v = self.evaluator().eval(e, lang)?;
                if v.number().is_none() {
                    return Err(alarms::vacant_value(e.span, "the step of a FOR"));
                }
                v
            }
            None => Value::Long(1),
        };
        let s = step.number().unwrap_or(1.0);
        if s == 0.0 {
            let span = by.map_or(c.st.first, |e| e.span);
            return Err(alarms::macro_domain(
                span,
                "a FOR step of 0 never ends the loop",
            ));
        }
        let value = if stepping {
            let cur = self.evaluator().read_var(kind, n, var.span())?;
            super::eval::binary(lang, BinOp::Add, cur, step, var.span())?
        } else {
            let v = self.evaluator().eval(from, lang)?;
            if v.number().is_none() {
                return Err(alarms::vacant_value(from.span, "the start of a FOR"));
            }
            v
        };
        let end = self.evaluator().eval(to, lang)?;
        let Some(last) = end.number() else {
            return Err(alarms::vacant_value(to.span, "the end of a FOR"));
        };
        self.evaluator()
            .write_var(kind, n, value, var.span(), None)?;
        self.macros.for_resume = None;
        let x = value.number().unwrap_or(0.0);
        let go_on = if s > 0.0 { x <= last } else { x >= last };
        if go_on {
            Ok(Step::Next)
        } else {
            self.follow(c, src, c.st.first)
        }
    }
}

impl<'a> Evaluator<'_, 'a> {
    /// Whether a condition holds: a number other than 0 (vacant: no).
    pub(crate) fn holds(&mut self, e: &Expr, lang: Lang) -> Result<bool, Diagnostic> {
        Ok(self.eval(e, lang)?.number().is_some_and(|x| x != 0.0))
    }

    /// The variable an assignment writes: (kind, number).
    fn target_var(&mut self, t: &Target, lang: Lang) -> Result<(VarKind, u32), Diagnostic> {
        match t {
            Target::Fixed(kind, n, _) => Ok((*kind, *n)),
            Target::Indirect(kind, e, span) => {
                let v = self.eval(e, lang)?;
                Ok((*kind, self.var_number(*kind, v, *span)?))
            }
            // Only LinuxCNC's lines name parameters, and `ngc.rs` writes them.
            Target::Named(_, span) => Err(vcnc_syntax::macros::ngc_expected(
                *span,
                "a numbered variable (named parameters are LinuxCNC's)",
            )),
        }
    }

    fn assign(
        &mut self,
        t: &Target,
        value: &Expr,
        lang: Lang,
        comment: Option<&str>,
    ) -> Result<(), Diagnostic> {
        let (kind, n) = self.target_var(t, lang)?;
        let v = self.eval(value, lang)?;
        self.write_var(kind, n, v, t.span(), comment)
    }

    /// A message for the operator: `stop` when the program waits (#3006).
    pub(crate) fn message(&mut self, text: String, stop: bool) {
        let text: std::sync::Arc<str> = text.into();
        self.machining()
            .emit(|loc| Event::Message { loc, text, stop });
    }
}

impl Interpreter<'_> {
    /// Runs the LinuxCNC O-word statement `c` of source `src`: its
    /// operands evaluated, then its link followed (`structure.rs` found
    /// it). Forward jumps are free; a loop's jump back, a CONTINUE and a
    /// call count against `limits.max_jumps`, a call against
    /// `limits.max_call_depth`. It is not counted as a block: rs274 runs
    /// no motion for it.
    pub(crate) fn o_word(
        &mut self,
        c: &Compiled,
        src: usize,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let StmtKind::OWord {
            kw,
            label,
            operands,
        } = &c.st.kind
        else {
            return Ok(Step::Next);
        };
        let (kw, span) = (*kw, c.st.first);
        let unpaired = |wanted: &str| super::structure::unpaired(span, label, kw, wanted);
        let statements = self.oword_statements(src)?;
        let (lacks, link) = statements
            .index(c.here.offset)
            .and_then(|i| statements.links.get(i))
            .ok_or_else(|| unpaired("place in the program"))?;
        let values = match self.evaluator().ngc_values(operands) {
            Ok(values) => values,
            Err(d) if lacks.is_none() && self.cfg.opts.keep_going => {
                return Err(self.condition_alarm(c, kw, label, link, d));
            }
            Err(d) => return Err(d),
        };
        if let Some(wanted) = lacks {
            return Err(unpaired(wanted));
        }
        let value = values.first().copied();
        let step = match (kw, link) {
            (_, OLink::Call(callee)) => {
                self.o_call(*callee, label, span, c.next, &values, store)?
            }
            (Kw::EndSub | Kw::Return, _) => self.o_return(span, value)?,
            _ => {
                let cond = || value.ok_or_else(|| unpaired("[condition]"));
                let flow = self.macros.oword.get_or_insert_with(Box::default);
                match flow.follow((kw, label, c.here.offset), link, cond, unpaired)? {
                    OStep::Next => Step::Jump(c.next),
                    OStep::Jump(to) => Step::Jump(to),
                    OStep::Back(to) => {
                        self.count_jump(span)?;
                        Step::Jump(to)
                    }
                }
            }
        };
        // The statements' scan may have moved the reader: go on from here.
        self.macros.moved_reader = false;
        Ok(match step {
            Step::Next => Step::Jump(c.next),
            s => s,
        })
    }

    /// Under keep-going, the alarm of an O-word statement whose operand
    /// cannot be evaluated: an `if`, `elseif`, `while` or `repeat` goes on
    /// as if its condition were false (past the loop, to the next branch),
    /// where the run resumes after the alarm (`Looping::after_alarm`) —
    /// falling into the body instead, a `while` met its alarm again at
    /// each pass until the alarm limit, and the rest of the program went
    /// unchecked. Other statements go on with the next line.
    #[cold]
    fn condition_alarm(
        &mut self,
        c: &Compiled,
        kw: Kw,
        label: &str,
        link: &OLink,
        d: Diagnostic,
    ) -> Diagnostic {
        if !matches!(kw, Kw::If | Kw::ElseIf | Kw::While | Kw::Repeat) {
            return d;
        }
        let span = c.st.first;
        let unpaired = |wanted: &str| super::structure::unpaired(span, label, kw, wanted);
        let flow = self.macros.oword.get_or_insert_with(Box::default);
        let to = match flow.follow((kw, label, c.here.offset), link, || Ok(0.0), unpaired) {
            Ok(OStep::Next) | Err(_) => c.next,
            Ok(OStep::Jump(to) | OStep::Back(to)) => to,
        };
        self.macros.moved_reader = false;
        self.looping.after_alarm = Some(to);
        d
    }

    /// O CALL: a level of the flow like a subprogram's, the locals saved,
    /// #1… the arguments; the body is this source's sub, or the file
    /// `NAME.ngc`'s.
    fn o_call(
        &mut self,
        callee: Callee,
        label: &str,
        span: Span,
        ret: Cursor,
        args: &[f64],
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let (source, start) = match callee {
            Callee::Here(start) => (None, start),
            Callee::File => {
                let (src, start) = self.sub_file(label, span, store)?;
                (Some(src), start)
            }
            Callee::Twice(n) => {
                return Err(super::structure::defined_twice(
                    span,
                    label,
                    n,
                    "this program",
                ));
            }
        };
        self.check_call_depth(span)?;
        self.count_jump(span)?;
        let saved = self.macros.ngc.get_or_insert_with(Box::default).enter(args);
        let flow = self.macros.oword.get_or_insert_with(Box::default);
        let repeats = flow.repeats.len();
        flow.saved.push((saved, repeats));
        match source {
            None => self.enter_local_sub(start, ret, "endsub"),
            Some(src) => self.enter_sub_in(src, start, ret, "endsub"),
        }
        Ok(Step::Jump(start))
    }

    /// ENDSUB or RETURN: the caller's locals back, `#<_value>` set.
    fn o_return(&mut self, span: Span, value: Option<f64>) -> Result<Step, Diagnostic> {
        let flow = self.macros.oword.get_or_insert_with(Box::default);
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
}
