//! Program flow: where blocks come from, subprogram calls and returns, and
//! searches for program and sequence numbers.
//!
//! ```text
//!   frames (call stack)            sources (open program texts)
//!   ┌──────────────────────┐       ┌─────────────────────────────┐
//!   │ main: source 0       │──────▶│ 0: main file (LineReader)   │
//!   │ O0010: source 0, ×2  │──┘    │ 1: O0020.nc from program dir│
//!   │ O0020: source 1      │──────▶│ …                           │
//!   └──────────────────────┘       └─────────────────────────────┘
//! ```
//!
//! Programs are never loaded whole: each source is a streaming
//! [`LineReader`], and a call, return or jump is a seek to a [`Cursor`].
//! Where a program or a sequence number is, is found by a forward scan from
//! the program's start (as Fanuc searches for `M99 P`) and remembered in a
//! bounded cache, so a loop does not rescan and memory stays bounded. Files
//! are opened only through the [`ProgramStore`] trait the caller provides.

use std::collections::HashMap;
use std::io;
use std::sync::Arc;
use vcnc_core::events::Loc;
use vcnc_syntax::{
    Addr, Block, Cursor, LexRules, Line, LineReader, ReadError, TextSource, clamp_u32, lex_block,
    next_block_start,
};

/// How a call level was entered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CallKind {
    /// The main program, M98 or a lathe G20: the caller's locals.
    Sub,
    /// G65, an extended G code or an M-code macro: own locals.
    Macro,
    /// A G66 call after a move: own locals; moves in it do not call again.
    Modal,
}

/// Finds called programs outside the main file.
pub trait ProgramStore {
    /// Opens program `number` (e.g. `O0010.nc` in a directory); `None` when
    /// there is no such program. The string names it in events and alarms.
    fn open(&mut self, number: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>>;

    /// Opens a program by file name without extension: Syntec's extended
    /// G-code macros (`G0200`) and registered M-code macros (`M0123`).
    /// A store that has none returns `None`.
    fn open_named(&mut self, name: &str) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let _ = name;
        None
    }

    /// Opens LinuxCNC's subroutine file `name.ngc` (`o<name> call` of a
    /// subroutine its program does not define), looked up along the
    /// store's program directories. The interpreter passes only a plain
    /// file name (ASCII letters, digits, `_`, `-`, `.`, never a leading
    /// `.`); the store must still refuse a file that resolves outside its
    /// directories (a symbolic link), with an error rather than its text.
    /// A store that has none returns `None`.
    fn open_subroutine(&mut self, name: &str) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let _ = name;
        None
    }
}

/// A store with no programs: every call must be satisfied by the main file.
#[derive(Debug, Default)]
pub struct NoPrograms;

impl ProgramStore for NoPrograms {
    fn open(&mut self, _: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        None
    }
}

/// Most entries of each search cache (about 12 MB at most); a program with
/// more labels than that is still searched correctly, only more slowly.
const CACHE_LIMIT: usize = 262_144;
/// Labels found by a search are kept even beyond `CACHE_LIMIT`, up to this
/// many more, so that a loop back to the same far label does not rescan
/// the file at every turn.
const FOUND_LIMIT: usize = 65_536;
/// Most open sources; beyond that an unused one is closed.
const MAX_SOURCES: usize = 64;

pub(crate) struct Source {
    pub reader: LineReader<Box<dyn TextSource>>,
    pub name: Option<Arc<str>>,
    pub number: Option<u32>,
    /// Unique for the run (a slot reused for another program gets a new
    /// one), so caches keyed by it never mix two programs.
    pub id: u32,
}

/// One level of the call stack.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub source: usize,
    /// Where the program (or the called sequence) starts; repeats go here.
    pub start: Cursor,
    /// Where the program itself starts: N searches (M99 P, M98 H, lathe
    /// G20/G25 L, the pairing of G26 L) begin here even when it was
    /// entered at a label.
    pub program: Cursor,
    /// The last block this level executed (for alarms at its end).
    pub last: Option<(vcnc_syntax::Line, vcnc_syntax::Span)>,
    /// Where the caller continues.
    pub ret: Cursor,
    /// Runs left, this one included (M98 L).
    pub runs_left: u32,
    /// Whether a block has executed in this run (an `O` header or `%` after
    /// that ends the program).
    pub started: bool,
    /// The code that ends this level: `"M99"`, or `"G24"` for a lathe G20.
    pub returns_with: &'static str,
    /// The level of macro locals this program reads and writes (a
    /// subprogram shares its caller's; a macro call has its own).
    pub locals: u32,
    /// How this level was entered.
    pub call: CallKind,
    /// The number of the program running at this level (`#4115`): from
    /// the call's P, or the main program's O header.
    pub number: Option<u32>,
}

impl Frame {
    /// The main program's level.
    fn main() -> Frame {
        Frame {
            source: 0,
            start: Cursor::default(),
            program: Cursor::default(),
            last: None,
            ret: Cursor::default(),
            runs_left: 1,
            started: false,
            returns_with: "M99",
            locals: 0,
            call: CallKind::Sub,
            number: None,
        }
    }
}

pub(crate) struct Flow {
    pub sources: Vec<Option<Source>>,
    pub frames: Vec<Frame>,
    /// Where program headers are, and where they are not (`None`).
    programs: HashMap<(usize, u32), Option<Cursor>>,
    /// Where the header scan of each source stopped (`None`: at its end).
    program_scans: HashMap<usize, Option<Cursor>>,
    sequences: HashMap<(usize, u64, u32, u32), Cursor>,
    /// Where the label scan of each program stopped (`None`: at its end).
    label_scans: HashMap<(usize, u64, u32), Option<Cursor>>,
    scratch: Block,
    /// Calls, returns to a sequence and repeats so far.
    pub jumps: u64,
    /// Lathe G26 loops in progress: jumps left, by the G26 block's place.
    pub loops: HashMap<(usize, u64, u32), u32>,
    /// Location of the block being executed.
    pub loc: Loc,
    /// The id the next installed source gets (it changes whenever a
    /// source is installed, so it also tells that the set changed).
    pub next_id: u32,
}

impl Flow {
    pub fn new(main: Box<dyn TextSource>) -> Flow {
        let main = Source {
            reader: LineReader::new(main),
            name: None,
            number: None,
            id: 0,
        };
        Flow {
            sources: vec![Some(main)],
            frames: vec![Frame::main()],
            programs: HashMap::new(),
            program_scans: HashMap::new(),
            sequences: HashMap::new(),
            label_scans: HashMap::new(),
            scratch: Block::default(),
            jumps: 0,
            loops: HashMap::new(),
            loc: Loc::default(),
            next_id: 1,
        }
    }

    pub fn frame(&self) -> Frame {
        self.frames.last().copied().unwrap_or_else(Frame::main)
    }

    pub fn frame_mut(&mut self) -> Option<&mut Frame> {
        self.frames.last_mut()
    }

    pub fn source(&mut self, i: usize) -> Option<&mut Source> {
        self.sources.get_mut(i).and_then(Option::as_mut)
    }

    /// Seeks the current frame's source to `to`.
    pub fn seek_current(&mut self, to: Cursor) {
        let src = self.frame().source;
        if let Some(s) = self.source(src) {
            s.reader.seek(Cursor { col: 0, ..to });
        }
        self.loc.file = self.source(src).and_then(|s| s.name.clone());
    }

    /// Finds program `number`: in the current source, in the main file, then
    /// in the store. Returns its source and the cursor after its `O` header.
    pub fn find_program(
        &mut self,
        number: u32,
        lex: &LexRules,
        store: &mut dyn ProgramStore,
    ) -> Result<Option<(usize, Cursor)>, io::Error> {
        let current = self.frame().source;
        for src in [current, 0] {
            if let Some(c) = self.program_in(src, number, lex) {
                return Ok(Some((src, c)));
            }
        }
        if let Some(i) = self
            .sources
            .iter()
            .position(|s| s.as_ref().is_some_and(|s| s.number == Some(number)))
        {
            return Ok(Some((i, Cursor::default())));
        }
        match store.open(number) {
            None => Ok(None),
            Some(Err(e)) => Err(e),
            Some(Ok((mut text, name))) => {
                // Probe the first byte so an unreadable program alarms at the
                // call, not somewhere in the middle of it.
                text.read_at(0, &mut [0u8; 1])?;
                let src = Source {
                    reader: LineReader::new(text),
                    name: Some(name.into()),
                    number: Some(number),
                    id: 0,
                };
                Ok(Some((self.install(src), Cursor::default())))
            }
        }
    }

    pub(crate) fn install(&mut self, mut src: Source) -> usize {
        src.id = self.next_id;
        self.next_id = self.next_id.wrapping_add(1);
        if let Some(i) = self.sources.iter().position(Option::is_none) {
            self.sources[i] = Some(src);
            return i;
        }
        if self.sources.len() >= MAX_SOURCES {
            let busy: Vec<usize> = self.frames.iter().map(|f| f.source).collect();
            if let Some(i) = (1..self.sources.len()).find(|i| !busy.contains(i)) {
                self.programs.retain(|k, _| k.0 != i);
                self.program_scans.remove(&i);
                self.sequences.retain(|k, _| k.0 != i);
                self.label_scans.retain(|k, _| k.0 != i);
                self.sources[i] = Some(src);
                return i;
            }
        }
        self.sources.push(Some(src));
        self.sources.len() - 1
    }

    /// Where program `number` starts in source `src` (after its O header).
    /// Every header the scan passes is remembered, and a later miss resumes
    /// where the last scan stopped, so many programs cost one pass in all.
    fn program_in(&mut self, src: usize, number: u32, lex: &LexRules) -> Option<Cursor> {
        if let Some(c) = self.programs.get(&(src, number)) {
            return *c;
        }
        let resume = match self.program_scans.get(&src) {
            Some(None) => return None,
            Some(Some(c)) => *c,
            None => Cursor::default(),
        };
        let mut programs = std::mem::take(&mut self.programs);
        let mut found = None;
        let mut complete = programs.len() < CACHE_LIMIT;
        let end = self.walk(src, resume, lex, false, false, |block, _, after| {
            let Some(n) = first_value(block, b'O') else {
                return false;
            };
            if programs.len() < CACHE_LIMIT {
                programs.entry((src, n)).or_insert(Some(after));
            } else {
                complete = false;
            }
            if n == number {
                found = Some(after);
            }
            found.is_some()
        });
        self.programs = programs;
        if complete {
            bounded_insert(&mut self.program_scans, src, end);
        }
        found
    }

    /// Where the first block at or after `from` starts (blank lines and
    /// comment-only blocks skipped), within the program; `None` at its end.
    pub fn first_block_from(&mut self, src: usize, from: Cursor, lex: &LexRules) -> Option<Cursor> {
        let mut found = None;
        self.walk(src, from, lex, true, true, |block, at, _| {
            if block.is_empty() {
                return false;
            }
            found = Some(at);
            true
        });
        found
    }

    /// Where the flow goes on after the subprogram that starts at `from`:
    /// the block after its first M99 (in the same text, across O headers);
    /// `None` when the text ends first.
    pub fn after_return(&mut self, src: usize, from: Cursor, lex: &LexRules) -> Option<Cursor> {
        self.walk(src, from, lex, false, true, |block, _, _| {
            block
                .words()
                .iter()
                .any(|w| w.addr == Addr::letter(b'M') && !w.point && whole_u32(w.value) == Some(99))
        })
    }

    /// Where the block that starts at `start` of `line` of source `src`
    /// ends: the next block's cursor, as the run loop's lexer found it
    /// (cold: the line is read again).
    #[cold]
    pub(crate) fn cursor_after(
        &mut self,
        src: usize,
        line: &Line,
        start: usize,
        lex: &LexRules,
    ) -> Cursor {
        let text = self
            .source(src)
            .map(|s| s.reader.reread(line))
            .unwrap_or_default();
        let next = lex_block(&text, start, lex, &mut Block::default())
            .unwrap_or_else(|_| next_block_start(&text, start, lex));
        Cursor {
            offset: line.offset,
            line: line.number,
            col: clamp_u32(next),
        }
    }

    /// Finds `N seq` in the program of `src` that starts at `start`: the
    /// first such block from the start. Like [`program_in`](Self::program_in)
    /// it remembers every label it passes and resumes where it stopped.
    pub fn find_sequence(
        &mut self,
        src: usize,
        start: Cursor,
        seq: u32,
        lex: &LexRules,
    ) -> Option<Cursor> {
        let program = (src, start.offset, start.col);
        if let Some(c) = self.sequences.get(&(src, start.offset, start.col, seq)) {
            return Some(*c);
        }
        let (resume, seen) = match self.label_scans.get(&program) {
            Some(None) => return None,
            Some(Some(c)) => (*c, true),
            None => (start, false),
        };
        let mut sequences = std::mem::take(&mut self.sequences);
        let mut found = None;
        let mut complete = sequences.len() < CACHE_LIMIT;
        let end = self.walk(src, resume, lex, true, seen, |block, at, _| {
            for w in block
                .words()
                .iter()
                .filter(|w| w.addr == Addr::letter(b'N') && !w.point)
            {
                let Some(n) = whole_u32(w.value) else {
                    continue;
                };
                if sequences.len() < CACHE_LIMIT {
                    sequences
                        .entry((src, start.offset, start.col, n))
                        .or_insert(at);
                } else {
                    complete = false;
                }
                if n == seq && found.is_none() {
                    found = Some(at);
                }
            }
            found.is_some()
        });
        if let Some(at) = found
            && sequences.len() < CACHE_LIMIT + FOUND_LIMIT
        {
            sequences.insert((src, start.offset, start.col, seq), at);
        }
        self.sequences = sequences;
        if complete {
            bounded_insert(&mut self.label_scans, program, end);
        }
        found
    }

    /// Visits the blocks of `src` from `from` until `visit(block, at,
    /// after)` says stop; returns where to resume (after that block), or
    /// `None` when the text — with `within_program`, the program (`%` or
    /// another O header after its first block) — ran out. Unreadable lines
    /// are skipped: a search is not a syntax check.
    pub(crate) fn walk(
        &mut self,
        src: usize,
        from: Cursor,
        lex: &LexRules,
        within_program: bool,
        mut seen_block: bool,
        mut visit: impl FnMut(&Block, Cursor, Cursor) -> bool,
    ) -> Option<Cursor> {
        let mut block = std::mem::take(&mut self.scratch);
        let source = self.sources.get_mut(src).and_then(Option::as_mut)?;
        source.reader.seek(Cursor { col: 0, ..from });
        let mut col = from.col as usize;
        let mut resume = None;
        'lines: loop {
            let line = match source.reader.next_line() {
                Ok(Some(l)) => l,
                Ok(None) | Err(ReadError::Io(_)) => break,
                Err(ReadError::TooLong { .. }) => continue,
            };
            let bytes = source.reader.bytes(&line);
            let mut i = std::mem::take(&mut col);
            while i < bytes.len() {
                let start = i;
                i = match lex_block(bytes, i, lex, &mut block) {
                    Ok(next) => next,
                    // The words before the error still count: a macro
                    // block `N400 #20 = #20 + 1` is labelled N400. The
                    // blocks after its `;` count too.
                    Err(_) if !block.words().is_empty() => next_block_start(bytes, start, lex),
                    Err(_) => {
                        i = next_block_start(bytes, start, lex);
                        continue;
                    }
                };
                let at = Cursor {
                    offset: line.offset,
                    line: line.number,
                    col: clamp_u32(start),
                };
                let after = Cursor {
                    col: clamp_u32(i),
                    ..at
                };
                let boundary = block.percent || first_value(&block, b'O').is_some();
                if within_program && boundary && seen_block {
                    break 'lines;
                }
                // A `%` or O header before the program's first block is its
                // start, not its end.
                seen_block |= !boundary && !block.is_empty();
                if visit(&block, at, after) {
                    resume = Some(after);
                    break 'lines;
                }
            }
        }
        self.scratch = block;
        resume
    }
}

/// A whole, non-negative number that fits a `u32`.
pub(crate) fn whole_u32(v: f64) -> Option<u32> {
    // In range and whole, so the cast is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    (v >= 0.0 && v <= f64::from(u32::MAX) && v.fract() == 0.0).then_some(v as u32)
}

fn bounded_insert<K: std::hash::Hash + Eq, V>(map: &mut HashMap<K, V>, key: K, value: V) {
    if map.len() >= CACHE_LIMIT {
        map.clear();
    }
    map.insert(key, value);
}

/// The integer value of the block's first word if it has address `letter`.
pub(crate) fn first_value(block: &Block, letter: u8) -> Option<u32> {
    let w = block.words().first()?;
    let whole = w.addr == Addr::letter(letter)
        && !w.point
        && w.value >= 0.0
        && w.value <= f64::from(u32::MAX);
    // Whole (no point) and within u32, so the cast is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    whole.then_some(w.value as u32)
}
