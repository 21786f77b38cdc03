//! The macro front end: compiled statements, the hook the ISO run loop
//! calls when the lexer rejects a block, and the reader of Syntec `%@MACRO`
//! files, whose statements span lines.
//!
//! ```text
//!   ISO line ── lex_block ── ok ──────────────────▶ block()
//!                   └─ error ─▶ macro_block ─▶ parse_iso_block ─▶ Compiled ─▶ run_compiled
//!   ISO line ── (cache hit at this column) ───────────────────────────────────▶ run_compiled
//!   %@MACRO ──── run_macro_file: cache or read_statement (lines joined) ─────▶ run_compiled
//! ```
//!
//! A compiled statement is cached by where the run loop looks for it
//! (source id, line offset, column), so a loop's second pass neither lexes
//! nor parses. Its text offsets are "virtual": offsets into the joined
//! lines, mapped back to a line and a column through its line map when an
//! alarm or a warning is located.

use super::structure::unpaired;
use super::{Key, LineMap, key};
use crate::alarms;
use crate::dialect::{IsoMacros, MacroFiles};
use crate::flow::ProgramStore;
use crate::interpreter::{Interpreter, Step};
use std::rc::Rc;
use vcnc_core::Sink;
use vcnc_syntax::macros::{Lang, MValue, MWord, Statement, StmtKind, Value};
use vcnc_syntax::macros::{o_statement, o_word_statement};
use vcnc_syntax::macros::{parse_iso_block, parse_syntec_statement, syntec_extent};
use vcnc_syntax::{Block, Cursor, Diagnostic, Line, ReadError, Span, Word};

/// Most lines one Syntec statement may span (E603 beyond).
const MAX_STATEMENT_LINES: usize = 64;
/// Most bytes of one Syntec statement's text (E603 beyond).
const MAX_STATEMENT_BYTES: usize = 16 * 1024;

/// Letters whose values are whole numbers: a macro value is rounded for
/// them (Fanuc rounds `M#1`, `S[1000.5]`; G codes keep their value).
const WHOLE_LETTERS: &[u8] = b"DHLMNOPST";

/// A statement parsed once, run many times.
#[derive(Debug)]
pub(crate) struct Compiled {
    pub st: Statement,
    pub lang: Lang,
    /// Where the statement starts (for labels, loops and messages).
    pub here: Cursor,
    /// Where the next statement starts.
    pub next: Cursor,
    /// The lines its text came from.
    pub lines: LineMap,
    /// Where its loop or branch link jumps, once looked up.
    pub target: std::cell::Cell<Option<Cursor>>,
}

impl Compiled {
    /// A statement written on one line, from byte `start` to `end` of it.
    fn on_line(
        st: Statement,
        lang: Lang,
        line: &Line,
        (start, end): (usize, usize),
    ) -> Rc<Compiled> {
        let here = Cursor {
            offset: line.offset,
            line: line.number,
            col: vcnc_syntax::clamp_u32(start),
        };
        Rc::new(Compiled {
            st,
            lang,
            here,
            next: Cursor {
                col: vcnc_syntax::clamp_u32(end),
                ..here
            },
            lines: Box::new([(0, *line)]),
            target: std::cell::Cell::new(None),
        })
    }

    /// The line holding virtual offset `at`, and the offset within it.
    pub fn line_of(&self, at: u32) -> (Line, u32) {
        let (start, line) = self
            .lines
            .iter()
            .rev()
            .find(|(s, _)| *s <= at)
            .or(self.lines.first())
            .copied()
            .unwrap_or_default();
        (line, at - start.min(at))
    }

    /// The first line.
    pub fn first_line(&self) -> Line {
        self.lines.first().map(|(_, l)| *l).unwrap_or_default()
    }
}

impl Interpreter<'_> {
    /// The unique id of source `src`.
    #[inline]
    pub(crate) fn source_id(&self, src: usize) -> u32 {
        self.flow
            .sources
            .get(src)
            .and_then(Option::as_ref)
            .map_or(0, |s| s.id)
    }

    /// Whether source `src` is a Syntec `%@MACRO` file (its first line
    /// says so); remembered per source.
    pub(crate) fn is_macro_file(&mut self, src: usize) -> bool {
        if self.macros.rules.files == MacroFiles::None {
            return false;
        }
        // Asked before every line: the answer for the same source, with no
        // source installed since, is the last one.
        let (last_src, generation, answer) = self.macros.last_file;
        if last_src == src && generation == self.flow.next_id {
            return answer;
        }
        let answer = self.detect_macro_file(src);
        self.macros.last_file = (src, self.flow.next_id, answer);
        answer
    }

    fn detect_macro_file(&mut self, src: usize) -> bool {
        let id = self.source_id(src);
        if let Some(b) = self.macros.macro_files.get(&id) {
            return *b;
        }
        let Some(s) = self.flow.source(src) else {
            return false;
        };
        let back = s.reader.position();
        s.reader.seek(Cursor::default());
        let first = match s.reader.next_line() {
            Ok(Some(l)) => s.reader.bytes(&l).to_vec(),
            _ => Vec::new(),
        };
        s.reader.seek(back);
        let text = String::from_utf8_lossy(&first);
        let is = text
            .trim_start_matches('\u{FEFF}')
            .trim()
            .eq_ignore_ascii_case("%@MACRO");
        if self.macros.macro_files.len() > 4096 {
            self.macros.macro_files.clear();
        }
        self.macros.macro_files.insert(id, is);
        is
    }

    /// A cached macro statement where the ISO run loop stands: runs it and
    /// moves `i` past it.
    #[inline]
    pub(crate) fn macro_cached<S: Sink>(
        &mut self,
        src: usize,
        line: &Line,
        i: &mut usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Option<(Step, Span)>, Diagnostic> {
        let k: Key = (self.source_id(src), line.offset, vcnc_syntax::clamp_u32(*i));
        let Some(c) = self.macros.cached(k) else {
            return Ok(None);
        };
        *i = c.next.col as usize;
        // LinuxCNC's lines and O-word statements, the only statements
        // compiled under its language (one test of a byte).
        if c.lang == Lang::Ngc {
            return self.cached_ngc_line(&c, src, line, block, store, sink);
        }
        match self.run_compiled(&c, src, block, store, sink) {
            Ok(ran) => Ok(Some(ran)),
            Err(d) => self.compiled_alarm(d, src, line, &c),
        }
    }

    /// The alarm of a cached Macro B or Syntec statement: as on its first
    /// pass, the end of the run, or under keep-going an alarm after which
    /// the run goes on after the statement — or where it said (a loop's
    /// condition that alarmed reads as false: [`Self::or_false`]).
    #[cold]
    #[inline(never)]
    fn compiled_alarm(
        &mut self,
        d: Diagnostic,
        src: usize,
        line: &Line,
        c: &Compiled,
    ) -> Result<Option<(Step, Span)>, Diagnostic> {
        let d = self.located(d, src, line, c.here.col as usize);
        let to = self.go_on_after(d)?.unwrap_or(c.next);
        Ok(Some((Step::Jump(to), c.st.first)))
    }

    /// A cached LinuxCNC line or O-word statement, run as on its first
    /// pass.
    #[inline(never)]
    fn cached_ngc_line<S: Sink>(
        &mut self,
        c: &Compiled,
        src: usize,
        line: &Line,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Option<(Step, Span)>, Diagnostic> {
        let ran = match c.st.kind {
            StmtKind::OWord { .. } => self.o_word(c, src, store),
            _ => self.run_ngc_line(c, block, store, sink),
        };
        match ran {
            Ok(step) => Ok(Some((step, c.st.first))),
            Err(d) => self.ngc_line_alarm(d, src, line, c.here.col as usize, c.st.first),
        }
    }

    /// The alarm of a cached LinuxCNC line is that of a block the lexer
    /// rejected, as on the line's first pass: placed with the `;` hint,
    /// and under keep-going the run goes on with the next line — `None`,
    /// the line's end being where the run loop now stands (a LinuxCNC
    /// line is read to its end), so that it finds nothing more on it —
    /// or where the statement said (an O-word condition that alarmed
    /// reads as false: [`Self::condition_alarm`]).
    #[cold]
    #[inline(never)]
    fn ngc_line_alarm(
        &mut self,
        d: Diagnostic,
        src: usize,
        line: &Line,
        start: usize,
        first: Span,
    ) -> Result<Option<(Step, Span)>, Diagnostic> {
        let d = self.located(d, src, line, start);
        let after = self.go_on_after(d)?;
        Ok(after.map(|to| (Step::Jump(to), first)))
    }

    /// The lexer rejected the block at `start`: if it is a macro statement,
    /// compile it, remember it and run it; otherwise the lexer's
    /// diagnostic stands.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn macro_block<S: Sink>(
        &mut self,
        src: usize,
        line: &Line,
        start: usize,
        lexed: Diagnostic,
        i: &mut usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<(Step, Span), Diagnostic> {
        // E604 from the lexer is LinuxCNC's O-word flow (`o100 while`),
        // which Macro B would misread as its own WHILE.
        match self.macros.rules.iso {
            IsoMacros::Ngc if lexed.code == vcnc_syntax::Code::E604 => {
                return self.oword_block(src, line, start, lexed, i, store);
            }
            // Mach3: parameters, but O-word flow stays E604.
            IsoMacros::NgcParams if lexed.code == vcnc_syntax::Code::E604 => return Err(lexed),
            IsoMacros::Ngc | IsoMacros::NgcParams => {
                return self.ngc_block(src, line, start, lexed, i, block, store, sink);
            }
            IsoMacros::None | IsoMacros::CustomMacroB => {}
        }
        if self.macros.rules.iso == IsoMacros::None || lexed.code == vcnc_syntax::Code::E604 {
            return Err(lexed);
        }
        let syn = self
            .macros
            .rules
            .syntax(Lang::MacroB, &self.cfg.dialect.lex);
        let parsed = match self.flow.source(src) {
            Some(s) => parse_iso_block(s.reader.bytes(line), start, &syn)?,
            None => None,
        };
        let Some((st, next_col)) = parsed else {
            return Err(self.no_macro_syntax(src, line, lexed));
        };
        let c = Compiled::on_line(st, Lang::MacroB, line, (start, next_col));
        let here = c.here;
        let id = self.source_id(src);
        self.macros.remember(key(id, here), &c);
        self.looping.macro_active = true;
        // Before the first macro statement of a program runs, its loops are
        // paired (the scan moves the reader: the statement then re-reads).
        self.ensure_structure(src)?;
        *i = next_col;
        self.run_compiled(&c, src, block, store, sink)
    }

    /// A LinuxCNC O-word statement (`o100 while [#1 LT 3]`), first met:
    /// its source's statements listed and linked (once,
    /// `structure.rs`), it is compiled, kept in the statement cache and
    /// run (`exec.rs`). `lexed` is the lexer's alarm, kept for a line that
    /// is no O-word statement.
    fn oword_block(
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
        let Some(o) = o_statement(&bytes, start) else {
            return Err(lexed);
        };
        *i = bytes.len();
        let statements = self.oword_statements(src)?;
        if statements.index(line.offset).is_none() {
            let span = Span::new(start, bytes.len());
            return Err(unpaired(span, &o.label, o.kw, "place in the program"));
        }
        let st = o_word_statement(&bytes, start, o)?;
        let c = Compiled::on_line(st, Lang::Ngc, line, (start, bytes.len()));
        self.macros.remember(key(self.source_id(src), c.here), &c);
        self.looping.macro_active = true;
        let step = self.o_word(&c, src, store)?;
        Ok((step, c.st.first))
    }

    /// A LinuxCNC line with parameters or expressions (`macros/ngc.rs`),
    /// first met: parsed, kept in the statement cache like a Macro B
    /// block (later passes run it from there without lexing), and run. A
    /// line without `#` or `[` keeps the lexer's alarm.
    #[allow(clippy::too_many_arguments)] // macro_block's own
    fn ngc_block<S: Sink>(
        &mut self,
        src: usize,
        line: &Line,
        start: usize,
        lexed: Diagnostic,
        i: &mut usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<(Step, Span), Diagnostic> {
        let Some(s) = self.flow.source(src) else {
            return Err(lexed);
        };
        let bytes = s.reader.bytes(line);
        let text = &bytes[start.min(bytes.len())..];
        if !text.iter().any(|c| matches!(c, b'#' | b'[')) {
            return Err(lexed);
        }
        let end = bytes.len();
        let mut st = vcnc_syntax::macros::parse_ngc_line(bytes, start)?;
        if !matches!(st.kind, StmtKind::Line(_)) {
            return Err(lexed);
        }
        // The block is the whole line (where an alarm at its end points).
        st.first = Span::new(start, end);
        let c = Compiled::on_line(st, Lang::Ngc, line, (start, end));
        let here = c.here;
        let id = self.source_id(src);
        self.macros.remember(key(id, here), &c);
        self.looping.macro_active = true;
        let step = self.run_ngc_line(&c, block, store, sink)?;
        *i = end;
        Ok((step, c.st.first))
    }

    /// Runs a LinuxCNC line: its words evaluated with the parameters as
    /// they were, the block run, then its settings applied. Its alarms are
    /// those of a block the lexer rejected: located in the line (and under
    /// keep-going the run goes on with the next line).
    fn run_ngc_line<S: Sink>(
        &mut self,
        c: &Compiled,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        self.ngc_words(&c.st, block)?;
        if block.is_empty() {
            return Ok(Step::Next);
        }
        self.macro_words_block(block, c.here, c.next, store, sink)
    }

    /// The words of a LinuxCNC line `st`, evaluated into `block` with the
    /// parameters as they were; its settings are applied (block delete
    /// skips those of a `/` line too).
    fn ngc_words(&mut self, st: &Statement, block: &mut Block) -> Result<(), Diagnostic> {
        let StmtKind::Line(items) = &st.kind else {
            block.clear();
            return Ok(());
        };
        let deleted = st.deleted.is_some();
        let read = self.evaluator().ngc_line(items)?;
        if !(deleted && self.cfg.opts.block_delete) {
            let params = self.macros.ngc.get_or_insert_with(Box::default);
            params.commit(&read);
        }
        self.macros.used = true;
        block.clear();
        for w in &read.words {
            if !block.push(*w) {
                return Err(vcnc_syntax::diagnostics::too_many_words(
                    w.span,
                    vcnc_syntax::MAX_WORDS,
                ));
            }
        }
        block.deleted = deleted.then_some(1);
        Ok(())
    }

    /// The lexer's alarm for a block without macro syntax, except that a
    /// word whose value is a Syntec `@` variable (`Y@1`) in an ISO program
    /// of a controller with `%@MACRO` files says where `@` variables live.
    #[cold]
    fn no_macro_syntax(&mut self, src: usize, line: &Line, lexed: Diagnostic) -> Diagnostic {
        if lexed.code != vcnc_syntax::Code::E104 || self.macros.rules.files != MacroFiles::Syntec {
            return lexed;
        }
        let Some(s) = self.flow.source(src) else {
            return lexed;
        };
        let bytes = s.reader.bytes(line);
        let span = lexed.span;
        let value = bytes
            .get(span.start as usize + 1..)
            .and_then(|rest| rest.iter().find(|b| !matches!(b, b' ' | b'\t')));
        match (value, bytes.get(span.start as usize)) {
            (Some(b'@'), Some(letter)) => vcnc_syntax::diagnostics::at_variable_in_iso(
                span,
                char::from(letter.to_ascii_uppercase()),
            ),
            _ => lexed,
        }
    }

    /// A profile block (fanuc-lathe G70–G73, P..Q) the lexer rejected: a
    /// word block with expressions (`N10 G00 X#1`) is evaluated into `block`
    /// with the variables as they stand when the cycle reads its profile
    /// (Fanuc reads the profile then too); any other macro statement is
    /// E344. Returns where the next block starts.
    pub(crate) fn profile_macro_block(
        &mut self,
        bytes: &[u8],
        start: usize,
        lexed: Diagnostic,
        block: &mut Block,
    ) -> Result<usize, Diagnostic> {
        // E604 from the lexer is LinuxCNC's O-word flow (`o100 while`),
        // which Macro B would misread as its own WHILE.
        if self.macros.rules.iso == IsoMacros::None || lexed.code == vcnc_syntax::Code::E604 {
            return Err(lexed);
        }
        if matches!(self.macros.rules.iso, IsoMacros::Ngc | IsoMacros::NgcParams) {
            // LinuxCNC's `o<Q> sub` profile: rs274 runs the sub's blocks,
            // so its expressions read (and its settings write) the
            // program's parameters, numbered and named.
            let text = &bytes[start.min(bytes.len())..];
            if !text.iter().any(|c| matches!(c, b'#' | b'[')) {
                return Err(lexed);
            }
            let st = vcnc_syntax::macros::parse_ngc_line(bytes, start)?;
            if !matches!(st.kind, StmtKind::Line(_)) {
                return Err(lexed);
            }
            self.ngc_words(&st, block)?;
            return Ok(bytes.len());
        }
        let syn = self
            .macros
            .rules
            .syntax(Lang::MacroB, &self.cfg.dialect.lex);
        let Some((st, next)) = parse_iso_block(bytes, start, &syn)? else {
            return Err(lexed);
        };
        let StmtKind::Words(words) = &st.kind else {
            return Err(alarms::profile_word(
                st.first,
                "a macro statement (assignment, IF, GOTO, WHILE, END)",
            ));
        };
        self.eval_words(words, Lang::MacroB, block)?;
        block.deleted = st.deleted;
        Ok(next)
    }

    /// Runs a compiled statement; alarms come back located.
    pub(crate) fn run_compiled<S: Sink>(
        &mut self,
        c: &Rc<Compiled>,
        src: usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<(Step, Span), Diagnostic> {
        let multi = c.lines.len() > 1;
        if multi {
            self.macros.span_map = Some(Rc::clone(c));
        }
        let result = self.run_statement(c, src, block, store, sink);
        let result = result.map_err(|d| self.locate_compiled(d, src, c));
        if multi {
            self.macros.span_map = None;
        }
        let mut step = result?;
        if std::mem::take(&mut self.macros.moved_reader) && matches!(step, Step::Next) {
            // A scan moved the reader: continue by seeking to the next statement.
            step = Step::Jump(c.next);
        }
        Ok((step, c.st.first))
    }

    /// Places an alarm raised by `c` in its line.
    pub(crate) fn locate_compiled(
        &mut self,
        mut d: Diagnostic,
        src: usize,
        c: &Compiled,
    ) -> Diagnostic {
        if d.is_located() {
            return d;
        }
        let (line, start) = c.line_of(d.span.start);
        let len = d.span.end.saturating_sub(d.span.start);
        d.span = Span {
            start,
            end: start + len,
        };
        // Located against its own line: no multi-line remapping again.
        let saved = self.macros.span_map.take();
        let d = self.locate(d, src, &line);
        self.macros.span_map = saved;
        d
    }

    fn run_statement<S: Sink>(
        &mut self,
        c: &Rc<Compiled>,
        src: usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        if c.st.deleted.is_some() && self.cfg.opts.block_delete {
            return Ok(Step::Next);
        }
        match &c.st.kind {
            StmtKind::Words(words) => {
                // What evaluating the words emits (a Syntec `MSG()` in an
                // expression) comes before the block's mark: it was always
                // dropped (the block's start cleared `pending`), and must
                // not now stay behind to reach the sink.
                let mark = self.stage.pending.len();
                let evaluated = self.eval_words(words, c.lang, block);
                self.stage.pending.truncate(mark);
                evaluated?;
                if block.is_empty() {
                    return Ok(Step::Next);
                }
                self.macro_words_block(block, c.here, c.next, store, sink)
            }
            StmtKind::Percent => {
                block.clear();
                block.percent = true;
                self.macro_words_block(block, c.here, c.next, store, sink)
            }
            _ => self.macro_statement(c, src, sink),
        }
    }

    /// Evaluates a word block into `block`: the literal block the lexer
    /// would have made. A vacant value omits its word (Fanuc: `X#1`).
    fn eval_words(
        &mut self,
        words: &[MWord],
        lang: Lang,
        block: &mut Block,
    ) -> Result<(), Diagnostic> {
        block.clear();
        for w in words {
            let (value, point) = match &w.value {
                MValue::Literal { value, point } => (*value, *point),
                MValue::Expr(e) => {
                    // Fanuc 0i: ROUND in an NC address rounds to the
                    // address's least input increment.
                    if super::eval::arith(lang).round_in_increments {
                        self.macros.round_per_unit = self.increments_per_unit(w.addr.0);
                    }
                    let v = self.evaluator().eval(e, lang);
                    self.macros.round_per_unit = None;
                    match v? {
                        Value::Null => continue,
                        v => word_value(w.addr.0, v, lang, w.span)?,
                    }
                }
            };
            let word = Word {
                addr: w.addr,
                value,
                point,
                span: w.span,
            };
            if !block.push(word) {
                return Err(vcnc_syntax::diagnostics::too_many_words(
                    w.span,
                    vcnc_syntax::MAX_WORDS,
                ));
            }
        }
        Ok(())
    }

    /// Runs the statements of the `%@MACRO` file `src` until the flow
    /// leaves it. `Some(end)` when the run is over.
    pub(crate) fn run_macro_file<S: Sink>(
        &mut self,
        src: usize,
        col: &mut usize,
        block: &mut Block,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Option<Option<vcnc_core::events::EndCode>>, Diagnostic> {
        loop {
            let Some(s) = self.flow.source(src) else {
                return Ok(None);
            };
            let p = s.reader.position();
            let at = Cursor {
                col: vcnc_syntax::clamp_u32(*col),
                ..p
            };
            self.ensure_macro_structure(src)?;
            let id = self.source_id(src);
            let c = match self.macros.cached(key(id, at)) {
                Some(c) => c,
                None => match self.read_statement(src, at)? {
                    Some(c) => {
                        self.macros.remember(key(id, at), &c);
                        c
                    }
                    None => {
                        return match self.end_of_program(sink)? {
                            Some(code) => Ok(Some(Some(code))),
                            None => Ok(None),
                        };
                    }
                },
            };
            let depth = self.flow.frames.len();
            self.flow.loc.line = c.here.line;
            let line = c.first_line();
            self.stage.cur_line = Some((src, line));
            let (step, first) = match self.run_compiled(&c, src, block, store, sink) {
                Ok(ran) => ran,
                // Under keep-going the run goes on with the next statement
                // (or where the alarmed one's reading says).
                Err(d) => (
                    self.go_on_after(d)?.map_or(Step::Next, Step::Jump),
                    c.st.first,
                ),
            };
            let step = match step {
                Step::Next => Step::Jump(c.next),
                s => s,
            };
            let (first_line, first_at) = c.line_of(first.start);
            let first = Span {
                start: first_at,
                end: first_at + first.end.saturating_sub(first.start),
            };
            if let crate::interpreter::After::Return(end) =
                self.after_block(step, depth, first_line, first, col, sink)?
            {
                return Ok(Some(end));
            }
            if self.flow.frames.last().map_or(0, |f| f.source) != src {
                return Ok(None);
            }
        }
    }

    /// The next line of `src`, counted towards the block budget; an
    /// unreadable line alarms.
    fn statement_line(&mut self, src: usize) -> Result<Option<(Line, Vec<u8>)>, Diagnostic> {
        let Some(s) = self.flow.source(src) else {
            return Ok(None);
        };
        match s.reader.next_line() {
            Ok(Some(l)) => {
                let bytes = s.reader.bytes(&l).to_vec();
                self.note_read(src, l.offset);
                Ok(Some((l, bytes)))
            }
            Ok(None) => Ok(None),
            Err(ReadError::TooLong { offset, line }) => {
                let mut d = alarms::line_too_long();
                d.line = line;
                d.column = 1;
                d.line_offset = offset;
                Err(d)
            }
            Err(ReadError::Io(e)) => Err(alarms::program_unreadable(Span::new(0, 1), 0, &e)),
        }
    }

    /// Reads and compiles the Syntec statement at `at`; `None` at the end
    /// of the text.
    pub(crate) fn read_statement(
        &mut self,
        src: usize,
        at: Cursor,
    ) -> Result<Option<Rc<Compiled>>, Diagnostic> {
        if let Some(s) = self.flow.source(src) {
            s.reader.seek(Cursor { col: 0, ..at });
        }
        let mut text = std::mem::take(&mut self.macros.text);
        let result = self.read_into(src, at, &mut text);
        self.macros.text = text;
        result
    }

    fn read_into(
        &mut self,
        src: usize,
        at: Cursor,
        text: &mut Vec<u8>,
    ) -> Result<Option<Rc<Compiled>>, Diagnostic> {
        text.clear();
        let mut lines: Vec<(u32, Line)> = Vec::new();
        let Some((line, bytes)) = self.statement_line(src)? else {
            return Ok(None);
        };
        text.extend_from_slice(&bytes);
        lines.push((0, line));
        let mut start = (at.col as usize).min(text.len());
        let syn = self
            .macros
            .rules
            .syntax(Lang::Syntec, &self.cfg.dialect.lex);
        let (first, end) = loop {
            let ext = syntec_extent(text, start);
            if ext.empty {
                // Only blanks and comments left: the statement starts on a later line.
                let Some((line, bytes)) = self.statement_line(src)? else {
                    return Ok(None);
                };
                text.clear();
                text.extend_from_slice(&bytes);
                lines.clear();
                lines.push((0, line));
                start = 0;
                continue;
            }
            if !ext.incomplete {
                break (ext.start, ext.end);
            }
            if lines.len() >= MAX_STATEMENT_LINES || text.len() >= MAX_STATEMENT_BYTES {
                let (l, s) = (lines[0].1, start);
                let d = alarms::statement_too_long(
                    Span::new(s, s + 1),
                    MAX_STATEMENT_LINES,
                    MAX_STATEMENT_BYTES,
                );
                return Err(self.locate(d, src, &l));
            }
            match self.statement_line(src)? {
                Some((line, bytes)) => {
                    text.push(b'\n');
                    lines.push((vcnc_syntax::clamp_u32(text.len()), line));
                    text.extend_from_slice(&bytes);
                }
                // The text ends inside the statement: it is the last one.
                None => break (start, text.len()),
            }
        };
        let lines: LineMap = lines.into_boxed_slice();
        let placed = |lines: &LineMap, v: usize| -> Cursor {
            let v = vcnc_syntax::clamp_u32(v);
            let (s, l) = lines
                .iter()
                .rev()
                .find(|(s, _)| *s <= v)
                .copied()
                .unwrap_or((0, Line::default()));
            Cursor {
                offset: l.offset,
                line: l.number,
                col: v - s,
            }
        };
        let here = placed(&lines, first);
        let next = placed(&lines, end);
        let st = match parse_syntec_statement(text, first, end, &syn) {
            Ok(st) => st,
            Err(d) => {
                let c = Compiled {
                    st: Statement {
                        kind: StmtKind::Percent,
                        first: d.span,
                        seq: None,
                        deleted: None,
                        comment: None,
                    },
                    lang: Lang::Syntec,
                    here,
                    next,
                    lines,
                    target: std::cell::Cell::new(None),
                };
                return Err(self.locate_compiled(d, src, &c));
            }
        };
        Ok(Some(Rc::new(Compiled {
            st,
            lang: Lang::Syntec,
            here,
            next,
            lines,
            target: std::cell::Cell::new(None),
        })))
    }
}

/// A macro value as a word's value: `(value, point)` read like a literal
/// written that way.
///
/// Macro B values are in the program's units: a length reads like a number
/// written with a decimal point (`X#1` with #1 = 5 is 5 mm), whole-number
/// addresses get the value rounded (`M#1`, `S#2`, `P#3`: Fanuc rounds them).
/// A Syntec Long reads like a literal without a point (least increments:
/// the reason its STD function exists), a Double like one with a point.
pub(crate) fn word_value(
    letter: u8,
    v: Value,
    lang: Lang,
    span: Span,
) -> Result<(f64, bool), Diagnostic> {
    let x = v.number().unwrap_or(0.0);
    if !x.is_finite() || x.abs() >= 1e9 {
        return Err(vcnc_syntax::diagnostics::number_out_of_range(
            span,
            char::from(letter),
        ));
    }
    let whole = WHOLE_LETTERS.contains(&letter);
    Ok(match (lang, v) {
        (_, _) if letter == b'G' => (x, false),
        (_, Value::Long(_)) if super::eval::arith(lang).longs => (x, false),
        (_, _) if whole => (x.round(), false),
        _ => (x, true),
    })
}
