//! The interpreter: an owned state machine that pulls blocks from the
//! program, executes them and pushes canonical events into a [`Sink`].
//!
//! ```text
//!   LineReader ─▶ lex_block ─▶ Words::collect ─▶ execute ─▶ Sink
//!   (flow.rs)     (syntax)     (validate)         (convert, exec)
//! ```
//!
//! One block at a time, in bounded memory: the current line is copied into a
//! small reused buffer, lexed into a reused [`Block`], validated into a
//! stack-allocated [`Words`] table and executed. An alarm anywhere becomes
//! the last event; the block that raised it leaves no motion and no modal
//! change behind. There is no I/O here: program text comes from
//! [`TextSource`]s and called programs from a [`ProgramStore`].

use crate::alarms;
use crate::config::Config;
pub use crate::config::Options;
use crate::dialect::Dialect;
use crate::flow::{Flow, ProgramStore, first_value};
use crate::state::{State, Tables};
use crate::words::Words;
use vcnc_core::Sink;
use vcnc_core::events::{EndCode, Event};
use vcnc_core::machine::Machine;
use vcnc_syntax::{
    Block, Cursor, Diagnostic, Line, MemSource, ReadError, Span, TextSource, clamp_u32, column_of,
    lex_block,
};

/// Events the interpreter gathers before it hands them to the sink
/// ([`Sink::take_events`]): most blocks make one event, and one call per
/// thousand events costs less than one per block; a sink that moves the
/// events to another thread (the CLI's second core) takes the whole buffer
/// without copying one. A batch is whole blocks, so one block of more
/// events (a G83 of many holes) goes over as one batch. A sink that is
/// done is asked after every block, so it is noticed at the first block
/// after the batch that made it done.
pub const HAND_OVER: usize = 1024;

/// The most alarms a run under [`Options::keep_going`] reports before it
/// stops at the next one.
pub const MAX_ALARMS: u32 = 100;

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Normal end: M02, M30 or the end of the main program.
    Ended(EndCode),
    /// Stopped by an alarm (also emitted as the last event).
    Alarm(Diagnostic),
    /// The sink wanted no more events (its reader went away).
    Stopped,
}

/// Where the run loop goes after a block's step.
pub(crate) enum After {
    /// On in this line.
    Next,
    /// The reader moved: read the next line.
    Jumped,
    /// The run is over (`None`: the sink is done).
    Return(Option<EndCode>),
}

/// What the run loop does after a block.
///
/// A word-wide tag, so that the cursor of `Jump` starts at an 8-byte
/// boundary and every payload byte is copied in whole words: with a byte
/// tag the run loop copied bytes 1..32 of each block's step in two 16-byte
/// stores that overlap, and its load of the cursor's line, which spans
/// both, waited for them to reach the cache (40 % of the loop's time).
#[repr(u64)]
pub(crate) enum Step {
    Next,
    /// Continue at this cursor of the (possibly new) current frame's source.
    Jump(Cursor),
    End(EndCode),
    /// The program ran into `%` or another program's `O` header.
    ProgramEnd,
}

/// Where the run goes on after a block's alarm under keep-going
/// ([`Interpreter::flow_after_alarm`]).
pub(crate) enum AfterAlarm {
    /// The block's end or return, obeyed after its alarm.
    Flow(Step),
    /// The next block, where the reader is.
    Next,
    /// The next block, but a failed search moved the reader.
    NextMoved,
}

/// What the run loop keeps between blocks: the runaway budget, and whether
/// a macro statement has run.
pub(crate) struct Looping {
    pub executed: u64,
    /// How far each source has been read (a line's offset + 1, by source
    /// index), and the sum: a block budget that grows with the text read,
    /// so that only blocks run again count against the runaway limit.
    pub read_high: Vec<u64>,
    pub read_total: u64,
    /// Whether the current line was read before (a loop or a repeat): its
    /// blocks are then charged by the events they make, so that a loop
    /// around a block of thousands of holes meets the limit as soon.
    pub rereading: bool,
    /// A macro statement has run (the cache is worth a look before lexing).
    pub macro_active: bool,
    /// Alarms the run went on after (`Options::keep_going`), and the first.
    pub alarms: u32,
    pub first_alarm: Option<Diagnostic>,
    /// Where the program goes on if the block being executed alarms and
    /// the run keeps going: set by a block that reads other lines of the
    /// program (G70–G73 read their profile), whose reading leaves the
    /// reader elsewhere.
    pub after_alarm: Option<Cursor>,
}

/// The interpreter. Create one per run.
pub struct Interpreter<'a> {
    pub(crate) cfg: Config<'a>,
    pub(crate) state: State,
    /// Work and tool offsets (journaled writes).
    pub(crate) tables: Tables,
    pub(crate) flow: Flow,
    pub(crate) looping: Looping,
    pub(crate) stage: crate::motion::stage::Stage,
    /// Variables, compiled macro statements, macro calls.
    pub(crate) macros: Box<crate::macros::Macros>,
    /// What the program's length words look like (warning W101).
    pub(crate) points: crate::state::PointStyle,
}

impl<'a> Interpreter<'a> {
    /// An interpreter at power-on state.
    ///
    /// A Fanuc lathe's codes are numbered by the machine's G-code system
    /// (`gcode_system`): the machine decides, whichever system's table
    /// `dialect` was built with.
    pub fn new(machine: &'a Machine, dialect: &'a Dialect, opts: Options) -> Interpreter<'a> {
        let dialect = dialect.under_system(machine.gcode_system);
        Interpreter {
            cfg: Config::new(machine, dialect, opts),
            state: State::power_on(machine, dialect),
            tables: Tables::new(machine),
            flow: Flow::new(Box::new(MemSource(Vec::<u8>::new()))),
            looping: Looping {
                executed: 0,
                rereading: false,
                read_high: Vec::new(),
                read_total: 0,
                macro_active: false,
                alarms: 0,
                first_alarm: None,
                after_alarm: None,
            },
            stage: crate::motion::stage::Stage::new(machine.axes.len()),
            points: crate::state::PointStyle::new(machine, dialect),
            macros: Box::new(crate::macros::Macros::new(dialect.macros)),
        }
    }

    /// Also emits the events a consumer that writes program coordinates
    /// needs — the flattened program of `vcnc run --format gcode`:
    /// `work_system` and `units` when the program changes them,
    /// `machine_move` before a move to a machine point (G53, a reference
    /// return) and `placed` when a block first places axes in program
    /// coordinates (`docs/events.md`). Off by default: other consumers, and
    /// the JSON-lines contract of `vcnc run`, do without them.
    pub fn with_program_markers(mut self) -> Interpreter<'a> {
        self.cfg.markers = true;
        self
    }

    /// The state after the run (or at the alarm: as it was before the
    /// block that alarmed).
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The work and tool offset tables after the run.
    pub fn tables(&self) -> &Tables {
        &self.tables
    }

    /// Runs a program held in memory with no external programs.
    pub fn run_str<S: Sink>(&mut self, program: &str, sink: &mut S) -> Outcome {
        self.run(
            Box::new(MemSource(program.as_bytes().to_vec())),
            &mut crate::flow::NoPrograms,
            sink,
        )
    }

    /// Runs the main program `main` to its end or first alarm.
    pub fn run<S: Sink>(
        &mut self,
        main: Box<dyn TextSource>,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Outcome {
        self.flow = Flow::new(main);
        let result = self.run_loop(store, sink);
        // What the blocks before the end or the alarm made.
        self.hand_over(sink);
        // Under keep-going the first alarm is the outcome of a run that
        // went on to its end.
        if let (Ok(_), Some(first)) = (&result, self.looping.first_alarm.take()) {
            return Outcome::Alarm(first);
        }
        match result {
            Ok(Some(code)) => Outcome::Ended(code),
            Ok(None) => Outcome::Stopped,
            Err(d) => {
                if let Some(e) = self.unset_report() {
                    sink.event(&e);
                }
                sink.event(&Event::Alarm(d.clone()));
                Outcome::Alarm(d)
            }
        }
    }

    pub(crate) fn flow(&mut self) -> &mut Flow {
        &mut self.flow
    }

    /// Runs blocks until the program ends (`Some`) or the sink is done
    /// (`None`).
    fn run_loop<S: Sink>(
        &mut self,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Option<EndCode>, Diagnostic> {
        let mut block = Block::default();
        let lex = self.cfg.dialect.lex;
        let mut col = 0usize;
        loop {
            let src = self.flow.frames.last().map_or(0, |f| f.source);
            // Syntec `%@MACRO` files are read statement by statement.
            if self.cfg.macro_files && self.is_macro_file(src) {
                match self.run_macro_file(src, &mut col, &mut block, store, sink)? {
                    Some(end) => return Ok(end),
                    None => continue,
                }
            }
            let Some(line) = self.next_line(src)? else {
                match self.end_of_program(sink)? {
                    Some(code) => return Ok(Some(code)),
                    None => continue,
                }
            };
            self.flow.loc.line = line.number;
            self.note_read(src, line.offset);
            // `next_line` made it the current line.
            let mut first_block = true;
            let mut i = std::mem::take(&mut col);
            loop {
                let start = i;
                let depth = self.flow.frames.len();
                // Set again for a later block of the line: a macro
                // statement before it on the line pointed it at the line
                // the statement was compiled from (`macro_cached`).
                if !std::mem::take(&mut first_block) {
                    self.stage.cur_line = Some((src, line));
                }
                // A macro statement compiled on an earlier pass runs as is
                // (a program that never showed macro syntax skips the look).
                let cached = if self.looping.macro_active {
                    self.macro_cached(src, &line, &mut i, &mut block, store, sink)?
                } else {
                    None
                };
                let (step, first) = match cached {
                    Some(ran) => ran,
                    None => {
                        // Lex straight from the reader's buffer: no copy of the line.
                        let lexed = match self.flow.source(src) {
                            Some(s) if i < s.reader.bytes(&line).len() => {
                                lex_block(s.reader.bytes(&line), i, &lex, &mut block)
                            }
                            _ => break,
                        };
                        match lexed {
                            Ok(n) => i = n,
                            Err(d) => {
                                let ran = self.macro_block(
                                    src, &line, start, d, &mut i, &mut block, store, sink,
                                );
                                match ran {
                                    Ok(ran) => {
                                        match self.after_block(
                                            ran.0, depth, line, ran.1, &mut col, sink,
                                        )? {
                                            After::Next => continue,
                                            After::Jumped => break,
                                            After::Return(end) => return Ok(end),
                                        }
                                    }
                                    Err(d) => {
                                        self.statement_alarm(d, src, &line, start, &mut col)?;
                                        break;
                                    }
                                }
                            }
                        }
                        if block.is_empty() {
                            continue;
                        }
                        let here = Cursor {
                            offset: line.offset,
                            line: line.number,
                            col: clamp_u32(start),
                        };
                        let next = Cursor {
                            col: clamp_u32(i),
                            ..here
                        };
                        let step = self
                            .block(&block, here, next, store, sink)
                            .or_else(|d| self.skip_block(d, src, &line, start, &block))?;
                        (step, block.first_span())
                    }
                };
                match self.after_block(step, depth, line, first, &mut col, sink)? {
                    After::Next => {}
                    After::Jumped => break,
                    After::Return(end) => return Ok(end),
                }
            }
        }
    }

    /// An alarm in the block at `start` of `line`, located: the end of the
    /// run, or under keep-going a step on to the next block.
    #[cold]
    #[inline(never)]
    fn skip_block(
        &mut self,
        d: Diagnostic,
        src: usize,
        line: &Line,
        start: usize,
        block: &Block,
    ) -> Result<Step, Diagnostic> {
        let d = self.located(d, src, line, start);
        // A block that read other lines (G70–G73's profile) goes on after
        // itself, not where its reading left the reader.
        let after = self.go_on_after(d)?;
        // An alarmed M02/M30/M99 still ends or returns.
        let here = Cursor {
            offset: line.offset,
            line: line.number,
            col: clamp_u32(start),
        };
        match self.flow_after_alarm(block, here) {
            AfterAlarm::Flow(step) => Ok(step),
            AfterAlarm::Next => Ok(after.map_or(Step::Next, Step::Jump)),
            // The failed return's search (`M99 P` of a missing sequence)
            // moved the reader: the run goes on right after this block.
            AfterAlarm::NextMoved => Ok(Step::Jump(self.flow.cursor_after(
                src,
                line,
                start,
                &self.cfg.dialect.lex,
            ))),
        }
    }

    /// The alarm of a macro statement the run loop met: under keep-going
    /// the rest of the line is the statement's, so the run goes on with
    /// the next line, or where the statement said (`Looping::after_alarm`:
    /// an O-word, Macro B or Syntec condition that alarmed reads as
    /// false), `col` then the column the next line is read from.
    #[cold]
    #[inline(never)]
    fn statement_alarm(
        &mut self,
        d: Diagnostic,
        src: usize,
        line: &Line,
        start: usize,
        col: &mut usize,
    ) -> Result<(), Diagnostic> {
        let d = self.located(d, src, line, start);
        if let Some(to) = self.go_on_after(d)? {
            self.flow.seek_current(to);
            *col = to.col as usize;
        }
        Ok(())
    }

    /// An alarm in a block: the end of the run, or under
    /// [`Options::keep_going`] an `alarm` event after which the run goes on
    /// with the next block, the state as it was before the alarmed one (an
    /// editor shows every mistake of a program at once). Runaway limits
    /// (E404, E405), an unreadable program (E408) and more than
    /// [`MAX_ALARMS`] alarms still end it.
    #[cold]
    ///
    /// Returns where the program goes on when the alarmed block read other
    /// lines of it (`Looping::after_alarm`), else `None`: the next block.
    pub(crate) fn go_on_after(&mut self, d: Diagnostic) -> Result<Option<Cursor>, Diagnostic> {
        let fatal = matches!(
            d.code,
            vcnc_syntax::Code::E404 | vcnc_syntax::Code::E405 | vcnc_syntax::Code::E408
        );
        if !self.cfg.opts.keep_going || fatal || self.looping.alarms >= MAX_ALARMS {
            return Err(d);
        }
        self.looping.alarms += 1;
        if self.looping.first_alarm.is_none() {
            self.looping.first_alarm = Some(d.clone());
        }
        self.stage.pending.push(Event::Alarm(d));
        // The held corner's straight move, if it cannot be made either, is
        // reported like any alarm.
        if let Some(dropped) = self.machining().release_corner()
            && self.looping.alarms < MAX_ALARMS
        {
            self.looping.alarms += 1;
            self.stage.pending.push(Event::Alarm(dropped));
        }
        Ok(self.looping.after_alarm.take())
    }

    /// What follows a block's step: the sink's wish to stop, the level's
    /// last block (for alarms at its end), and the jump or the end.
    #[inline]
    pub(crate) fn after_block<S: Sink>(
        &mut self,
        step: Step,
        depth: usize,
        line: Line,
        first: Span,
        col: &mut usize,
        sink: &mut S,
    ) -> Result<After, Diagnostic> {
        if sink.is_done() {
            return Ok(After::Return(None));
        }
        if !matches!(step, Step::ProgramEnd) {
            // Remembered by the level that ran it (a call's caller,
            // not a return's callee), for alarms at its end.
            if let Some(f) = self.flow.frames.get_mut(depth.wrapping_sub(1)) {
                f.last = Some((line, first));
                // A sink that reads the state after a line of the main
                // text (`Sink::stop_after_line`; false, and gone, for others).
                if f.source == 0 && sink.stop_after_line(line.number) {
                    return Ok(After::Return(None));
                }
            }
        }
        match step {
            Step::Next => Ok(After::Next),
            Step::Jump(to) => {
                self.flow.seek_current(to);
                *col = to.col as usize;
                Ok(After::Jumped)
            }
            Step::End(code) => Ok(After::Return(Some(code))),
            Step::ProgramEnd => match self.end_of_program(sink)? {
                Some(code) => Ok(After::Return(Some(code))),
                None => Ok(After::Jumped),
            },
        }
    }

    /// Counts text read for the first time towards the block budget.
    #[inline]
    pub(crate) fn note_read(&mut self, src: usize, offset: u64) {
        if src >= self.looping.read_high.len() {
            self.looping.read_high.resize(src + 1, 0);
        }
        self.looping.rereading = true;
        if let Some(high) = self.looping.read_high.get_mut(src)
            && offset + 1 > *high
        {
            self.looping.read_total += offset + 1 - *high;
            *high = offset + 1;
            self.looping.rereading = false;
        }
    }

    /// The next line of source `src`, made the current line (the one
    /// alarms and warnings point into).
    ///
    /// In line, and the current line kept here, so that both are written
    /// from the registers the reader took the line in. Copied later from
    /// the line's place in memory, the copy read it in 16-byte loads that
    /// waited for the 8-byte stores which wrote it, on every line (a
    /// quarter of the run loop's time).
    #[inline(always)]
    fn next_line(&mut self, src: usize) -> Result<Option<Line>, Diagnostic> {
        let Some(source) = self.flow.source(src) else {
            return Ok(None);
        };
        match source.reader.next_line() {
            Ok(Some(line)) => {
                self.stage.cur_line = Some((src, line));
                Ok(Some(line))
            }
            Ok(None) => Ok(None),
            Err(e) => Err(self.read_error(src, e)),
        }
    }

    /// The alarm for a line that could not be read.
    #[cold]
    #[inline(never)]
    fn read_error(&mut self, src: usize, e: ReadError) -> Diagnostic {
        let mut d = match e {
            ReadError::TooLong { offset, line } => {
                let mut d = alarms::line_too_long();
                d.line = line;
                d.line_offset = offset;
                d.file = self.flow.loc.file.as_deref().map(str::to_string);
                d
            }
            ReadError::Io(e) => {
                let source = self.flow.source(src);
                let number = source.as_ref().and_then(|s| s.number).unwrap_or(0);
                let mut d = alarms::program_unreadable(Span::new(0, 1), number, &e);
                if let Some(s) = source {
                    let at = s.reader.position();
                    d.line = at.line;
                    d.line_offset = at.offset;
                    d.file = s.name.as_deref().map(str::to_string);
                }
                d
            }
        };
        d.column = 1;
        d
    }

    /// The program text's side of placing a diagnostic.
    pub(crate) fn locator(&mut self) -> Locator<'_> {
        Locator {
            flow: &mut self.flow,
            span_map: &self.macros.span_map,
        }
    }

    /// Fills in line, column and file of a diagnostic raised in `line` of
    /// source `src` (see [`Locator::locate`]).
    pub(crate) fn locate(&mut self, d: Diagnostic, src: usize, line: &Line) -> Diagnostic {
        self.locator().locate(d, src, line)
    }

    /// The machine's side and the record of the program's length words
    /// (W101, W109), which a block's words update on their way.
    #[inline(always)]
    pub(crate) fn machining_and_points(
        &mut self,
    ) -> (Machining<'_, 'a>, &mut crate::state::PointStyle) {
        (
            Machining {
                cfg: &self.cfg,
                state: &mut self.state,
                tables: &mut self.tables,
                stage: &mut self.stage,
                at: Locator {
                    flow: &mut self.flow,
                    span_map: &self.macros.span_map,
                },
            },
            &mut self.points,
        )
    }

    /// The macro evaluator's side of the interpreter.
    pub(crate) fn evaluator(&mut self) -> crate::macros::Evaluator<'_, 'a> {
        crate::macros::Evaluator {
            cfg: &self.cfg,
            state: &mut self.state,
            tables: &mut self.tables,
            stage: &mut self.stage,
            macros: &mut self.macros,
            flow: &mut self.flow,
        }
    }

    /// The machine's side of the interpreter, for the codes that move it.
    #[inline(always)]
    pub(crate) fn machining(&mut self) -> Machining<'_, 'a> {
        self.machining_and_points().0
    }

    /// A diagnostic of the block at `start` of `line`, placed, with the
    /// `;` hint when it applies.
    #[cold]
    pub(crate) fn located(
        &mut self,
        d: Diagnostic,
        src: usize,
        line: &Line,
        start: usize,
    ) -> Diagnostic {
        let d = self.locate(d, src, line);
        self.semicolon_hint(d, src, line, start)
    }

    /// An alarm in the text after a `;` on the same line: the dialect ends
    /// the block there, so a grbl-style comment was read as words. The help
    /// says so.
    #[cold]
    fn semicolon_hint(
        &mut self,
        mut d: Diagnostic,
        src: usize,
        line: &Line,
        start: usize,
    ) -> Diagnostic {
        let reading = matches!(d.code.as_str().as_bytes().get(1), Some(b'1' | b'2'));
        if !reading || start == 0 || d.line != line.number {
            return d;
        }
        let text = self.locator().line_text(src, line);
        let before = text.get(..start).unwrap_or_default().trim_ascii_end();
        if before.ends_with(b";") {
            d.help = format!(
                "`;` ends the block in the {} dialect, so the text after it is read as words: write comments in ( ), or run with --dialect grbl where `;` starts a comment ({})",
                self.cfg.dialect.name, d.help
            );
        }
        d
    }

    /// A block the macro front end evaluated: the same as [`block`], out
    /// of line so that the run loop keeps its own inlined copy.
    ///
    /// [`block`]: Self::block
    #[inline(never)]
    pub(crate) fn macro_words_block<S: Sink>(
        &mut self,
        block: &Block,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        self.block(block, here, next, store, sink)
    }

    /// One non-empty block: block delete, tape marks, headers, then execution.
    /// Inlined into the run loop (its hot path); macro word blocks reach it
    /// through [`macro_words_block`](Self::macro_words_block).
    #[inline(always)]
    fn block<S: Sink>(
        &mut self,
        block: &Block,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        if block.deleted.is_some() && self.cfg.opts.block_delete {
            return Ok(Step::Next);
        }
        if block.percent || first_value(block, b'O').is_some() {
            let started = self.flow.frames.last().is_some_and(|f| f.started);
            return self.program_boundary(block, started, next);
        }
        if let Some(f) = self.flow.frames.last_mut() {
            f.started = true;
        }
        let mut words = Words::new(block);
        self.count_executed(words.first)?;
        if let Err(d) = words.fill(self.cfg.dialect, self.cfg.machine, self.cfg.axis_mask) {
            // Syntec's G200–G999 call macro files of the program directory.
            if d.code == vcnc_syntax::Code::E201
                && self.macros.rules.extended_g == crate::dialect::ExtendedG::Files
                && let Some(step) = self.extended_g_call(block, next, store)?
            {
                return Ok(step);
            }
            return Err(d);
        }
        if let Some(call) = words.macro_call {
            return self.macro_call_block(block, call, next, store);
        }
        if !self.cfg.machine.m_macros.is_empty()
            && let Some(m) = words
                .other_m
                .iter()
                .flatten()
                .find(|m| self.cfg.machine.m_macros.contains_key(&m.def))
        {
            return self.m_macro_call(block, *m, next, store);
        }
        for a in self.cfg.axis_words.iter().filter(|a| a.inc.is_some()) {
            if let (Some(_), Some(inc)) = (words.get(a.letter), a.inc.and_then(|l| words.get(l))) {
                return Err(alarms::absolute_and_incremental(
                    inc.span, a.letter, inc.addr.0,
                ));
            }
        }
        // All or nothing: events wait in `pending`, the state is restored
        // and the tables' writes are undone if the block alarms.
        let jumps = self.flow.jumps;
        let comp_engaged = self.stage.comp.engaged();
        let plain = words.is_plain_motion(self.cfg.axis_mask);
        let in_place = plain
            && self
                .stage
                .moves_in_place(&self.cfg, &self.state, &words, comp_engaged);
        // Under compensation such a block undoes the stage by itself.
        let comp_in_place = comp_engaged && in_place;
        let mark = self.stage.begin(comp_in_place);
        let result = if !plain {
            self.keeping_state(|s| s.execute(&words, here, next, store))
        } else if comp_in_place {
            self.compensated_move_in_place(&words).map(|()| Step::Next)
        } else if in_place {
            // A plain G00/G01 keeps only what it changes before its last
            // check (the copy of the state is most of its cost).
            self.move_in_place(&words).map(|()| Step::Next)
        } else {
            // Only axis words, F and a motion code: nothing but a move.
            self.keeping_state(|s| {
                if s.stage.nurbs.is_some() {
                    s.machining().check_curve_pending(&words)?;
                }
                s.execute_motion_only(&words)
            })
            .map(|()| Step::Next)
        };
        // By value, and the step rebuilt below: moving the whole `Result`
        // on (a `Diagnostic`'s size) read it back in 16-byte loads that
        // waited for the narrower stores that wrote it, on every block.
        let step = match result {
            Ok(step) => step,
            Err(d) => {
                self.stage.abandon(mark);
                self.flow.jumps = jumps;
                self.tables.rollback();
                return Err(d);
            }
        };
        self.tables.commit();
        if self.looping.rereading {
            let made = self.stage.made_since(mark);
            self.looping.executed = self
                .looping
                .executed
                .saturating_add(made.saturating_sub(1) as u64);
        }
        self.hand_over_when_full(sink);
        // Under G66 a block that moves calls the macro after its move.
        let modal_call = self.state.modal.macro_call
            && words.any(self.cfg.axis_mask)
            && words.axis_user.is_none();
        if modal_call && matches!(step, Step::Next) {
            return self.modal_macro_call(next, store);
        }
        Ok(step)
    }

    /// Runs `f` on the state, which is restored whole if it alarms.
    #[inline(always)]
    fn keeping_state<T>(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<T, Diagnostic>,
    ) -> Result<T, Diagnostic> {
        let saved = self.state;
        let result = f(self);
        if result.is_err() {
            self.state = saved;
        }
        result
    }

    /// Counts an executed block (or macro statement) against the runaway
    /// budget, which grows with the program text read.
    #[inline]
    pub(crate) fn count_executed(&mut self, span: Span) -> Result<(), Diagnostic> {
        self.looping.executed += 1;
        if self.looping.executed
            > self
                .cfg
                .machine
                .limits
                .max_executed_blocks
                .saturating_add(self.looping.read_total)
        {
            return Err(alarms::block_limit(
                span,
                self.cfg.machine.limits.max_executed_blocks,
            ));
        }
        Ok(())
    }

    /// `%` or an `O` header: the start of this program, or the end of it.
    fn program_boundary(
        &mut self,
        block: &Block,
        started: bool,
        next: Cursor,
    ) -> Result<Step, Diagnostic> {
        if let Some(w) = block.words().get(1) {
            return Err(alarms::word_not_allowed(w.span, w.addr.0));
        }
        if !started {
            // The tape start `%` and the program's own O header come before
            // its first block: restarts and searches begin after them.
            let number = first_value(block, b'O');
            if let Some(f) = self.flow().frame_mut() {
                f.start = next;
                f.program = next;
                f.number = number.or(f.number);
            }
            return Ok(Step::Next);
        }
        if self.cfg.dialect.o_in_flow == crate::dialect::OInFlow::SkipsSubprogram && !block.percent
        {
            // Mach3: a subprogram written between the main program's blocks
            // runs only when called; the flow goes on after its M99.
            let src = self.flow.frame().source;
            let lex = self.cfg.dialect.lex;
            return Ok(match self.flow.after_return(src, next, &lex) {
                Some(after) => Step::Jump(after),
                None => Step::ProgramEnd,
            });
        }
        Ok(Step::ProgramEnd)
    }

    /// The current program ran out of blocks.
    pub(crate) fn end_of_program<S: Sink>(
        &mut self,
        sink: &mut S,
    ) -> Result<Option<EndCode>, Diagnostic> {
        let frame = self.flow.frame();
        // A called program that ran no block at all (its file or text ends
        // right after its header) is located at the call that entered it.
        let caller = self
            .flow
            .frames
            .len()
            .checked_sub(2)
            .and_then(|i| self.flow.frames.get(i));
        let (last, frame) = match (frame.last, caller) {
            (None, Some(c)) if c.last.is_some() => (c.last, *c),
            _ => (frame.last, frame),
        };
        let span = last.map_or(Span::new(0, 1), |(_, s)| s);
        match last {
            Some((line, _)) => self.flow.loc.line = line.number,
            // An empty program ends on its (empty) first line.
            None => self.flow.loc.line = self.flow.loc.line.max(1),
        }
        self.flow.loc.file = self.flow.source(frame.source).and_then(|s| s.name.clone());
        // What the end makes is dropped if it alarms, as a block's is.
        let mark = self.stage.pending.len();
        if self.flow.frames.len() == 1 {
            let mut w = alarms::no_program_end(span);
            match last {
                Some((line, _)) => w = self.locate(w, frame.source, &line),
                None => {
                    // An empty program: its first line, first column.
                    w.line = 1;
                    w.column = 1;
                    w.file = self.flow.loc.file.as_deref().map(str::to_string);
                }
            }
            self.stage.pending.push(Event::Warning(w));
        }
        match self.finish_program(span, sink) {
            Ok(Step::End(code)) => Ok(Some(code)),
            Ok(_) => Ok(None),
            Err(d) => {
                self.stage.pending.truncate(mark);
                Err(match last {
                    Some((line, _)) => self.locate(d, frame.source, &line),
                    // A program without a block (an empty subprogram): its start.
                    None if !d.is_located() => {
                        let mut d = d;
                        d.line = frame.program.line.max(1);
                        d.column = 1;
                        d.line_offset = frame.program.offset;
                        d.file = self.flow.loc.file.as_deref().map(str::to_string);
                        d
                    }
                    None => d,
                })
            }
        }
    }

    /// End of the main program (an `end` event) or of a subprogram (E406).
    fn finish_program<S: Sink>(&mut self, span: Span, sink: &mut S) -> Result<Step, Diagnostic> {
        if self.flow().frames.len() > 1 {
            let code = self.flow().frame().returns_with;
            return Err(alarms::sub_without_return(span, code));
        }
        // A G01 whose `,C`/`,R` waits for a move that never comes.
        self.machining().check_corner_at_end()?;
        // Compensation ends with the program: its last move leaves first
        // (after the warning that the program has no end code).
        self.machining().comp_finish()?;
        self.machining().report_frame();
        if let Some(e) = self.unset_report() {
            self.stage.pending.push(e);
        }
        if let Some(w) = self.whole_units_report() {
            self.stage.pending.push(w);
        }
        for e in self.stage.pending.drain(..) {
            sink.event(&e);
        }
        let loc = self.flow().loc.clone();
        sink.event(&Event::End {
            loc,
            code: EndCode::Eof,
        });
        Ok(Step::End(EndCode::Eof))
    }

    /// Hands the events waiting in `pending` to the sink.
    pub(crate) fn hand_over<S: Sink>(&mut self, sink: &mut S) {
        if !self.stage.pending.is_empty() {
            sink.take_events(&mut self.stage.pending);
        }
    }

    /// After a block or statement that succeeded: hands the waiting events
    /// over once [`HAND_OVER`] have gathered.
    #[inline]
    pub(crate) fn hand_over_when_full<S: Sink>(&mut self, sink: &mut S) {
        if self.stage.pending.len() >= HAND_OVER {
            self.hand_over(sink);
        }
    }

    /// Counts a jump against the runaway limit.
    pub(crate) fn count_jump(&mut self, span: Span) -> Result<(), Diagnostic> {
        let max = self.cfg.machine.limits.max_jumps;
        let flow = self.flow();
        if flow.jumps >= max {
            return Err(alarms::jump_limit(span, max));
        }
        flow.jumps += 1;
        Ok(())
    }
}

/// What executing a block may ask of the program text: the location its
/// events carry, and where an alarm about a line (this block's, or an
/// earlier one a compensation or a corner held) sits in the source. The
/// codes that move the machine reach the program flow only through it.
pub(crate) struct Locator<'r> {
    flow: &'r mut Flow,
    /// The macro statement being run when it spans lines: a diagnostic's
    /// offset is into its joined text.
    span_map: &'r Option<std::rc::Rc<crate::macros::Compiled>>,
}

impl Locator<'_> {
    /// The location of the block being executed.
    #[inline(always)]
    pub(crate) fn loc(&self) -> &vcnc_core::events::Loc {
        &self.flow.loc
    }

    /// Moves the location of the events to `line` (a held corner or a
    /// profile element emitted at its own line); returns the one before.
    pub(crate) fn set_line(&mut self, line: u64) -> u64 {
        std::mem::replace(&mut self.flow.loc.line, line)
    }

    /// The bytes of `line` of source `src`, read again (cold paths only).
    fn line_text(&mut self, src: usize, line: &Line) -> Vec<u8> {
        self.flow
            .source(src)
            .map(|s| s.reader.reread(line))
            .unwrap_or_default()
    }

    /// Fills in line, column and file of a diagnostic raised in `line` of
    /// source `src` (cold path: the line is read again for the column).
    pub(crate) fn locate(&mut self, d: Diagnostic, src: usize, line: &Line) -> Diagnostic {
        if d.is_located() {
            // Raised about an earlier block (a move compensation held).
            return d;
        }
        // A macro statement spanning lines maps its offsets to their line.
        // Only for a line where the statement starts: an alarm about an
        // earlier block (a move compensation or a corner held) sits on its
        // own line.
        let (mut d, line) = match self.span_map.as_deref() {
            Some(c) if c.here.offset == line.offset => {
                let (l, start) = c.line_of(d.span.start);
                let len = d.span.end.saturating_sub(d.span.start);
                let mut d = d;
                d.span = Span {
                    start,
                    end: start + len,
                };
                (d, l)
            }
            _ => (d, *line),
        };
        let line = &line;
        let text = self.line_text(src, line);
        d.line = line.number;
        d.column = column_of(&text, d.span.start);
        d.line_offset = line.offset;
        d.file = self
            .flow
            .source(src)
            .and_then(|s| s.name.as_deref().map(str::to_string));
        d
    }
}

impl<'r> Locator<'r> {
    pub(crate) fn new(
        flow: &'r mut Flow,
        span_map: &'r Option<std::rc::Rc<crate::macros::Compiled>>,
    ) -> Locator<'r> {
        Locator { flow, span_map }
    }
}

/// The machine's side of the interpreter: what the codes that move the
/// machine may read and change — the run's configuration, the modal state,
/// the offset tables, the motion stage — and, through [`Locator`], where
/// the block stands in the program. Borrowed from the [`Interpreter`] for
/// the length of one code's work; the program flow, the macro variables
/// and the run loop's counters stay out of its reach.
pub(crate) struct Machining<'r, 'a> {
    pub(crate) cfg: &'r Config<'a>,
    pub(crate) state: &'r mut State,
    pub(crate) tables: &'r mut Tables,
    pub(crate) stage: &'r mut crate::motion::stage::Stage,
    pub(crate) at: Locator<'r>,
}
