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

use crate::Sink;
use crate::alarms;
use crate::block::words::Words;
use crate::dialect::Dialect;
use crate::events::{EndCode, Event};
use crate::flow::{Flow, ProgramStore, first_value};
use crate::machine::Machine;
use crate::state::{State, Tables};
use vcnc_syntax::{
    Block, Cursor, Diagnostic, Line, MemSource, ReadError, Span, TextSource, clamp_u32, column_of,
    lex_block,
};

/// How one machine axis is addressed in the dialect.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AxisWord {
    /// Its letter (absolute under G90).
    pub letter: u8,
    /// Its always-incremental word (U for X on a lathe).
    pub inc: Option<u8>,
    /// Programmed in diameters under G23.
    pub diameter: bool,
    /// A rotary axis (degrees).
    pub rotary: bool,
}

impl AxisWord {
    fn of(letter: u8, dialect: &Dialect) -> AxisWord {
        AxisWord {
            letter,
            inc: dialect
                .incremental_words
                .iter()
                .find(|(_, a)| *a == letter)
                .map(|(w, _)| *w),
            diameter: dialect.diameter.axis == Some(letter),
            rotary: matches!(letter, b'A' | b'B' | b'C'),
        }
    }

    fn mask(&self) -> u32 {
        crate::dialect::bit(self.letter) | self.inc.map_or(0, crate::dialect::bit)
    }
}

/// Operator switches.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    /// Skip blocks that start with `/`.
    pub block_delete: bool,
    /// Stop at M01.
    pub optional_stop: bool,
}

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

/// What the run loop does after a block.
pub(crate) enum Step {
    Next,
    /// Continue at this cursor of the (possibly new) current frame's source.
    Jump(Cursor),
    End(EndCode),
    /// The program ran into `%` or another program's `O` header.
    ProgramEnd,
}

/// The interpreter. Create one per run.
pub struct Interpreter<'a> {
    pub(crate) machine: &'a Machine,
    pub(crate) dialect: &'a Dialect,
    pub(crate) opts: Options,
    pub(crate) state: State,
    /// Work and tool offsets (journaled writes).
    pub(crate) tables: Tables,
    pub(crate) flow: Flow,
    /// Letters that address axes (axis letters and incremental words).
    pub(crate) axis_mask: u32,
    /// How each machine axis is written, in axis order.
    pub(crate) axis_words: Vec<AxisWord>,
    executed: u64,
    /// How far each source has been read (a line's offset + 1, by source
    /// index), and the sum: a block budget that grows with the text read,
    /// so that only blocks run again count against the runaway limit.
    read_high: Vec<u64>,
    read_total: u64,
    /// Moves committed so far (a block compares it to know if it moved).
    pub(crate) moves: u64,
    /// The cutter compensation stage, and its copy taken before a block
    /// while it is engaged.
    pub(crate) comp: crate::motion::comp::Comp,
    comp_saved: crate::motion::comp::Comp,
    /// The source and line of the block being executed (for alarms about
    /// moves that compensation releases later).
    pub(crate) cur_line: Option<(usize, Line)>,
    /// Events of the block being executed, sent when it succeeds.
    pub(crate) pending: Vec<Event>,
    /// What the program's length words look like (warning W101).
    pub(crate) points: crate::block::convert::PointStyle,
    /// W104 was given and the spindle has not turned since (or it turns:
    /// no check needed until it stops).
    pub(crate) spindle_warned: bool,
    /// The highest cutting feed, mm/min (the control's clamp).
    pub(crate) max_feed: f64,
}

impl<'a> Interpreter<'a> {
    /// An interpreter at power-on state.
    pub fn new(machine: &'a Machine, dialect: &'a Dialect, opts: Options) -> Interpreter<'a> {
        let axis_words: Vec<AxisWord> = machine
            .axes
            .iter()
            .map(|a| AxisWord::of(a.letter, dialect))
            .collect();
        Interpreter {
            machine,
            dialect,
            opts,
            state: State::power_on(machine, dialect),
            tables: Tables::new(machine),
            flow: Flow::new(Box::new(MemSource(Vec::<u8>::new()))),
            axis_mask: axis_words.iter().fold(0, |m, a| m | a.mask()),
            axis_words,
            executed: 0,
            read_high: Vec::new(),
            read_total: 0,
            moves: 0,
            comp: Default::default(),
            comp_saved: Default::default(),
            cur_line: None,
            pending: Vec::new(),
            points: crate::block::convert::PointStyle::new(machine, dialect),
            spindle_warned: false,
            max_feed: machine.max_feed_mm_per_min(),
        }
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
        match result {
            Ok(Some(code)) => Outcome::Ended(code),
            Ok(None) => Outcome::Stopped,
            Err(d) => {
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
        let lex = self.dialect.lex;
        let mut col = 0usize;
        loop {
            let src = self.flow.frames.last().map_or(0, |f| f.source);
            let Some(line) = self.next_line(src)? else {
                match self.end_of_program(sink)? {
                    Some(code) => return Ok(Some(code)),
                    None => continue,
                }
            };
            self.flow.loc.line = line.number;
            self.note_read(src, line.offset);
            let mut i = std::mem::take(&mut col);
            loop {
                // Lex straight from the reader's buffer: no copy of the line.
                let lexed = match self.flow.source(src) {
                    Some(s) if i < s.reader.bytes(&line).len() => {
                        lex_block(s.reader.bytes(&line), i, &lex, &mut block)
                    }
                    _ => break,
                };
                let start = i;
                i = lexed.map_err(|d| {
                    let d = self.locate(d, src, &line);
                    self.semicolon_hint(d, src, &line, start)
                })?;
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
                let depth = self.flow.frames.len();
                self.cur_line = Some((src, line));
                let step = self.block(&block, here, next, store, sink).map_err(|d| {
                    let d = self.locate(d, src, &line);
                    self.semicolon_hint(d, src, &line, start)
                })?;
                if sink.is_done() {
                    return Ok(None);
                }
                if !matches!(step, Step::ProgramEnd) {
                    // Remembered by the level that ran it (a call's caller,
                    // not a return's callee), for alarms at its end.
                    if let Some(f) = self.flow.frames.get_mut(depth.wrapping_sub(1)) {
                        f.last = Some((line, block.first_span()));
                    }
                }
                match step {
                    Step::Next => {}
                    Step::Jump(to) => {
                        self.flow.seek_current(to);
                        col = to.col as usize;
                        break;
                    }
                    Step::End(code) => return Ok(Some(code)),
                    Step::ProgramEnd => match self.end_of_program(sink)? {
                        Some(code) => return Ok(Some(code)),
                        None => break,
                    },
                }
            }
        }
    }

    /// Counts text read for the first time towards the block budget.
    #[inline]
    fn note_read(&mut self, src: usize, offset: u64) {
        if src >= self.read_high.len() {
            self.read_high.resize(src + 1, 0);
        }
        if let Some(high) = self.read_high.get_mut(src)
            && offset + 1 > *high
        {
            self.read_total += offset + 1 - *high;
            *high = offset + 1;
        }
    }

    /// The next line of source `src`.
    fn next_line(&mut self, src: usize) -> Result<Option<Line>, Diagnostic> {
        let Some(source) = self.flow.source(src) else {
            return Ok(None);
        };
        match source.reader.next_line() {
            Ok(line) => Ok(line),
            Err(ReadError::TooLong { offset, line }) => {
                let file = self.flow.loc.file.clone();
                let mut d = alarms::line_too_long();
                d.line = line;
                d.column = 1;
                d.line_offset = offset;
                d.file = file.as_deref().map(str::to_string);
                Err(d)
            }
            Err(ReadError::Io(e)) => {
                let at = source.reader.position();
                let mut d =
                    alarms::program_unreadable(Span::new(0, 1), source.number.unwrap_or(0), &e);
                d.line = at.line;
                d.column = 1;
                d.line_offset = at.offset;
                d.file = source.name.as_deref().map(str::to_string);
                Err(d)
            }
        }
    }

    /// Fills in line, column and file of a diagnostic raised in `line` of
    /// source `src` (cold path: the line is read again for the column).
    pub(crate) fn locate(&mut self, mut d: Diagnostic, src: usize, line: &Line) -> Diagnostic {
        if d.is_located() {
            // Raised about an earlier block (a move compensation held).
            return d;
        }
        let text = self
            .flow
            .source(src)
            .map(|s| s.reader.reread(line))
            .unwrap_or_default();
        d.line = line.number;
        d.column = column_of(&text, d.span.start);
        d.line_offset = line.offset;
        d.file = self
            .flow
            .source(src)
            .and_then(|s| s.name.as_deref().map(str::to_string));
        d
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
        let text = self
            .flow
            .source(src)
            .map(|s| s.reader.reread(line))
            .unwrap_or_default();
        let before = text.get(..start).unwrap_or_default().trim_ascii_end();
        if before.ends_with(b";") {
            d.help = format!(
                "`;` ends the block in the {} dialect, so the text after it is read as words: write comments in ( ), or run with --dialect grbl where `;` starts a comment ({})",
                self.dialect.name, d.help
            );
        }
        d
    }

    /// One non-empty block: block delete, tape marks, headers, then execution.
    fn block<S: Sink>(
        &mut self,
        block: &Block,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
        sink: &mut S,
    ) -> Result<Step, Diagnostic> {
        if block.deleted.is_some() && self.opts.block_delete {
            return Ok(Step::Next);
        }
        if block.percent || first_value(block, b'O').is_some() {
            let started = self.flow.frames.last().is_some_and(|f| f.started);
            return self.program_boundary(block, started, next);
        }
        if let Some(f) = self.flow.frames.last_mut() {
            f.started = true;
        }
        self.executed += 1;
        if self.executed
            > self
                .machine
                .limits
                .max_executed_blocks
                .saturating_add(self.read_total)
        {
            return Err(alarms::block_limit(
                block.first_span(),
                self.machine.limits.max_executed_blocks,
            ));
        }
        let mut words = Words::new(block);
        words.fill(self.dialect, self.machine, self.axis_mask)?;
        for a in self.axis_words.iter().filter(|a| a.inc.is_some()) {
            if let (Some(_), Some(inc)) = (words.get(a.letter), a.inc.and_then(|l| words.get(l))) {
                return Err(alarms::absolute_and_incremental(
                    inc.span, a.letter, inc.addr.0,
                ));
            }
        }
        // All or nothing: events wait in `pending`, the state is restored
        // whole and the tables' writes are undone if the block alarms.
        let saved = self.state;
        let jumps = self.flow.jumps;
        let comp_engaged = self.comp.engaged();
        if comp_engaged {
            self.comp_saved.clone_from(&self.comp);
        }
        self.pending.clear();
        let result = if words.is_plain_motion(self.axis_mask) {
            // Only axis words, F and a motion code: nothing but a move.
            self.execute_motion_only(&words).map(|()| Step::Next)
        } else {
            self.execute(&words, here, next, store)
        };
        match &result {
            Ok(_) => {
                self.tables.commit();
                for e in &self.pending {
                    sink.event(e);
                }
            }
            Err(_) => {
                self.state = saved;
                self.flow.jumps = jumps;
                self.tables.rollback();
                if comp_engaged {
                    std::mem::swap(&mut self.comp, &mut self.comp_saved);
                } else {
                    self.comp = crate::motion::comp::Comp::default();
                }
            }
        }
        result
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
            if let Some(f) = self.flow().frame_mut() {
                f.start = next;
                f.program = next;
            }
            return Ok(Step::Next);
        }
        Ok(Step::ProgramEnd)
    }

    /// The current program ran out of blocks.
    fn end_of_program<S: Sink>(&mut self, sink: &mut S) -> Result<Option<EndCode>, Diagnostic> {
        let frame = self.flow.frame();
        let last = frame.last;
        let span = last.map_or(Span::new(0, 1), |(_, s)| s);
        match last {
            Some((line, _)) => self.flow.loc.line = line.number,
            // An empty program ends on its (empty) first line.
            None => self.flow.loc.line = self.flow.loc.line.max(1),
        }
        self.flow.loc.file = self.flow.source(frame.source).and_then(|s| s.name.clone());
        if self.flow.frames.len() == 1 {
            let mut w = alarms::no_program_end(span);
            if let Some((line, _)) = last {
                w = self.locate(w, frame.source, &line);
            }
            self.pending.clear();
            self.pending.push(Event::Warning(w));
        }
        match self.finish_program(span, sink) {
            Ok(Step::End(code)) => Ok(Some(code)),
            Ok(_) => Ok(None),
            Err(d) => Err(match last {
                Some((line, _)) => self.locate(d, frame.source, &line),
                None => d,
            }),
        }
    }

    /// End of the main program (an `end` event) or of a subprogram (E406).
    fn finish_program<S: Sink>(&mut self, span: Span, sink: &mut S) -> Result<Step, Diagnostic> {
        if self.flow().frames.len() > 1 {
            let code = self.flow().frame().returns_with;
            return Err(alarms::sub_without_return(span, code));
        }
        // A G01 whose `,C`/`,R` waits for a move that never comes.
        self.check_corner_at_end()?;
        // Compensation ends with the program: its last move leaves first
        // (after the warning that the program has no end code).
        self.comp_finish()?;
        self.report_frame();
        for e in self.pending.drain(..) {
            sink.event(&e);
        }
        let loc = self.flow().loc.clone();
        sink.event(&Event::End {
            loc,
            code: EndCode::Eof,
        });
        Ok(Step::End(EndCode::Eof))
    }

    /// Counts a jump against the runaway limit.
    pub(crate) fn count_jump(&mut self, span: Span) -> Result<(), Diagnostic> {
        let max = self.machine.limits.max_jumps;
        let flow = self.flow();
        if flow.jumps >= max {
            return Err(alarms::jump_limit(span, max));
        }
        flow.jumps += 1;
        Ok(())
    }
}
