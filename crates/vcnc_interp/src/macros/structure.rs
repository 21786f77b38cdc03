//! Loop and branch structure, found before a program's statements run.
//!
//! ```text
//!   WHILE [#1 LT 3] DO 1  ──Exit──▶ after END 1      IF c THEN ──If──▶ clauses, end
//!     …                                                …
//!   END 1                 ──Back──▶ the WHILE         ELSEIF c THEN ──Skip──▶ after END_IF
//!                                                      …
//!   FOR #1 := 1 TO 5 DO ──Exit──▶ after END_FOR       END_IF;
//!     EXIT;             ──Exit──▶ after END_FOR
//!   END_FOR;            ──Back──▶ the FOR
//! ```
//!
//! The first time a program runs a macro statement (a Syntec `%@MACRO`
//! file: before its first statement), the whole program — from its start to
//! `%`, the next `O` header or the end of the text — is read once with a
//! stack of the open structures: DO/END that do not pair (END without DO,
//! overlapping loops `DO 1 … DO 2 … END 1`, more than three nested loops,
//! a loop number other than 1–3), an IF without END_IF, an ELSE after ELSE,
//! an EXIT outside a loop or structures nested more than ten deep alarm
//! E611 there, before they run. What the scan learns is kept as links from
//! each statement to where it jumps, so a loop's END never searches, and
//! as the text range of each Macro B DO loop, so a GOTO into a loop from
//! outside it alarms (E614, `exec.rs`).
//! Memory is bounded: at most [`LINK_LIMIT`] links in a run.
//!
//! The seed lathe's `G26 L n Q q` (seed 003) closes a loop whose head is
//! the block labelled `N n` of its program. The first G26 a program runs
//! pairs every G26 of that program with its head in one pass over the
//! program's blocks (the first block labelled `N n`, wherever it stands,
//! as the controller's sequence search finds it), kept as a `Back` link
//! like a loop's END; `codes/calls.rs` follows the link, and a G26 whose
//! label the program lacks has none (E404 when it runs).
//!
//! LinuxCNC's O-words (`o100 while` … `o100 endwhile`, `sub`, `if`, `do`,
//! `repeat`, `break`, `call`) are linked here too (`structure/owords.rs`),
//! once per source: they pair by label within a subroutine's scope rather
//! than by nesting, so each source's statements are listed with their
//! label, scope and line, and each is linked to where it jumps (its end,
//! its head, the next branch to test, its loop, the sub it calls), which
//! `exec.rs` follows.

use super::{Compiled, FastMap, Key, key};
use crate::alarms;
use crate::dialect::{Dialect, FlowOp, GOp};
use crate::flow::{Flow, whole_u32};
use crate::interpreter::Interpreter;
use std::rc::Rc;
use vcnc_syntax::macros::{Lang, StmtKind, parse_iso_block};
use vcnc_syntax::{Addr, Cursor, Diagnostic, ReadError, lex_block};

mod owords;

pub(crate) use owords::{Callee, OFlow, OLink, OStep, Statements, defined_twice, unpaired};

/// Most links kept in a run (E611 beyond).
const LINK_LIMIT: usize = 65_536;
/// Fanuc: three nested DO loops.
const DO_NESTING: usize = 3;
/// Syntec: structures nested at most ten deep (its COM-007).
const SYNTEC_NESTING: usize = 10;

/// One clause of an IF: its condition (the ELSEIF statement; `None` for
/// ELSE) and where its body starts.
#[derive(Debug)]
pub(crate) struct Clause {
    pub cond: Option<Rc<Compiled>>,
    pub body: Cursor,
}

#[derive(Debug)]
pub(crate) struct IfChain {
    /// The ELSEIF and ELSE clauses after the IF's own.
    pub clauses: Vec<Clause>,
    /// After END_IF.
    pub end: Cursor,
}

#[derive(Debug)]
pub(crate) struct CaseTable {
    pub labels: Vec<(Vec<i64>, Cursor)>,
    pub otherwise: Option<Cursor>,
    pub end: Cursor,
}

/// Where a statement jumps.
#[derive(Debug, Clone)]
pub(crate) enum Link {
    /// A loop's head when its condition fails (after its end); EXIT.
    Exit(Cursor),
    /// A loop's end: back to its head (UNTIL: to the body).
    Back(Cursor),
    /// ELSEIF, ELSE or a case label run into from the body before it:
    /// after END_IF / END_CASE.
    Skip(Cursor),
    /// An IF's other clauses.
    If(Rc<IfChain>),
    /// A CASE's labels.
    Case(Rc<CaseTable>),
}

/// A position in a source: (line offset, column), in text order.
pub(crate) type Pos = (u64, u32);

fn pos(c: Cursor) -> Pos {
    (c.offset, c.col)
}

/// The range of a Macro B `DO m … END m` loop that a GOTO may leave but
/// not enter from outside (Fanuc 0i).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LoopRange {
    /// The first statement after `WHILE … DO m` (a target at the WHILE
    /// itself enters the loop at its test, as running into it does).
    pub body: Pos,
    /// Just after `END m`: the END belongs to the range.
    pub end: Pos,
    /// The line of the WHILE, and the loop's number (for the message).
    pub line: u64,
    pub m: u8,
}

impl LoopRange {
    pub fn holds(&self, at: Cursor) -> bool {
        (self.body..self.end).contains(&pos(at))
    }
}

/// Links of the programs scanned so far.
#[derive(Default)]
pub(crate) struct Structure {
    pub links: FastMap<Key, Link>,
    /// The DO loops of each program scanned, by program.
    scanned: FastMap<Key, Rc<[LoopRange]>>,
    last: Option<Key>,
    /// LinuxCNC's O-word statements of each source read, by source id.
    owords: Vec<(u32, Rc<Statements>)>,
    /// The programs whose lathe G26 loops are paired.
    lathe_paired: FastMap<Key, ()>,
}

impl Structure {
    /// The DO loops of program `pk`, when it has been scanned.
    pub fn loops(&self, pk: Key) -> Option<Rc<[LoopRange]>> {
        self.scanned.get(&pk).cloned()
    }
}

/// A structure still open during the scan.
enum Open {
    Do {
        m: u8,
        head: Rc<Compiled>,
    },
    If {
        head: Rc<Compiled>,
        clauses: Vec<Clause>,
        heads: Vec<Key>,
        has_else: bool,
    },
    Case {
        head: Rc<Compiled>,
        labels: Vec<(Vec<i64>, Cursor)>,
        heads: Vec<Key>,
        otherwise: Option<Cursor>,
    },
    Loop {
        head: Rc<Compiled>,
        exits: Vec<Key>,
    },
}

impl Open {
    fn head(&self) -> &Rc<Compiled> {
        match self {
            Open::Do { head, .. }
            | Open::If { head, .. }
            | Open::Case { head, .. }
            | Open::Loop { head, .. } => head,
        }
    }
    fn name(&self) -> &'static str {
        match self {
            Open::Do { .. } => "DO",
            Open::If { .. } => "IF",
            Open::Case { .. } => "CASE",
            Open::Loop { head, .. } => match head.st.kind {
                StmtKind::For { .. } => "FOR",
                StmtKind::Repeat => "REPEAT",
                _ => "WHILE",
            },
        }
    }
}

type Fault = (Rc<Compiled>, Diagnostic);

/// What pairing a program finds: the links and the DO loops' ranges.
type Paired = (Vec<(Key, Link)>, Vec<LoopRange>);

/// The pairing of one program's statements.
struct Pairing {
    id: u32,
    stack: Vec<Open>,
    links: Vec<(Key, Link)>,
    loops: Vec<LoopRange>,
}

impl Pairing {
    fn new(id: u32) -> Pairing {
        Pairing {
            id,
            stack: Vec::new(),
            links: Vec::new(),
            loops: Vec::new(),
        }
    }

    fn k(&self, c: &Compiled) -> Key {
        key(self.id, c.here)
    }

    fn fail(c: &Rc<Compiled>, what: String, help: &str) -> Fault {
        (Rc::clone(c), alarms::bad_structure(c.st.first, what, help))
    }

    fn push(&mut self, open: Open, c: &Rc<Compiled>) -> Result<(), Fault> {
        let syntec = !matches!(open, Open::Do { .. });
        if syntec && self.stack.len() >= SYNTEC_NESTING {
            return Err(Pairing::fail(
                c,
                format!("structures are nested more than {SYNTEC_NESTING} deep"),
                "move the inner part into a subprogram",
            ));
        }
        self.stack.push(open);
        Ok(())
    }

    /// The innermost open structure must be `want`, else this closer does
    /// not pair.
    fn closes(&mut self, c: &Rc<Compiled>, closer: &str, want: &str) -> Result<Open, Fault> {
        match self.stack.last() {
            Some(top) if top.name() == want => Ok(self.stack.pop().unwrap_or(Open::Loop {
                head: Rc::clone(c),
                exits: Vec::new(),
            })),
            Some(top) => Err(Pairing::fail(
                c,
                format!(
                    "{closer} does not close the {} of line {}, which is still open",
                    top.name(),
                    top.head().here.line
                ),
                &format!("close the {} first", top.name()),
            )),
            None => Err(Pairing::fail(
                c,
                format!("{closer} has no {want} to close"),
                &format!("remove it, or add the {want} it belongs to"),
            )),
        }
    }

    fn statement(&mut self, c: &Rc<Compiled>) -> Result<(), Fault> {
        let k = self.k(c);
        match &c.st.kind {
            StmtKind::While { m, .. } => self.open_do(c, *m),
            StmtKind::End(m) => self.end_do(c, *m),
            StmtKind::If(_) => self.push(
                Open::If {
                    head: Rc::clone(c),
                    clauses: Vec::new(),
                    heads: Vec::new(),
                    has_else: false,
                },
                c,
            ),
            StmtKind::ElseIf(_) | StmtKind::Else
                if matches!(
                    self.stack.last(),
                    Some(Open::If {
                        has_else: false,
                        ..
                    })
                ) =>
            {
                if let Some(Open::If {
                    clauses,
                    heads,
                    has_else,
                    ..
                }) = self.stack.last_mut()
                {
                    let is_else = matches!(c.st.kind, StmtKind::Else);
                    clauses.push(Clause {
                        cond: (!is_else).then(|| Rc::clone(c)),
                        body: c.next,
                    });
                    heads.push(k);
                    *has_else = is_else;
                }
                Ok(())
            }
            StmtKind::Else
                if matches!(
                    self.stack.last(),
                    Some(Open::Case {
                        otherwise: None,
                        ..
                    })
                ) =>
            {
                if let Some(Open::Case {
                    otherwise, heads, ..
                }) = self.stack.last_mut()
                {
                    *otherwise = Some(c.next);
                    heads.push(k);
                }
                Ok(())
            }
            StmtKind::ElseIf(_) | StmtKind::Else => Err(Pairing::fail(
                c,
                format!(
                    "{} has no open IF (or CASE) to belong to, or comes after its ELSE",
                    if matches!(c.st.kind, StmtKind::Else) {
                        "ELSE"
                    } else {
                        "ELSEIF"
                    }
                ),
                "check the IF … ELSEIF … ELSE … END_IF order",
            )),
            StmtKind::EndIf => {
                let Open::If {
                    head,
                    clauses,
                    heads,
                    ..
                } = self.closes(c, "END_IF", "IF")?
                else {
                    return Ok(());
                };
                self.links.push((
                    self.k(&head),
                    Link::If(Rc::new(IfChain {
                        clauses,
                        end: c.next,
                    })),
                ));
                for h in heads {
                    self.links.push((h, Link::Skip(c.next)));
                }
                Ok(())
            }
            StmtKind::Case(_) => self.push(
                Open::Case {
                    head: Rc::clone(c),
                    labels: Vec::new(),
                    heads: Vec::new(),
                    otherwise: None,
                },
                c,
            ),
            StmtKind::CaseLabel(values) => match self.stack.last_mut() {
                Some(Open::Case {
                    labels,
                    heads,
                    otherwise: None,
                    ..
                }) => {
                    labels.push((values.clone(), c.next));
                    heads.push(k);
                    Ok(())
                }
                _ => Err(Pairing::fail(
                    c,
                    "a case label outside a CASE (or after its ELSE)".into(),
                    "put labels between CASE … OF and ELSE / END_CASE",
                )),
            },
            StmtKind::EndCase => {
                let Open::Case {
                    head,
                    labels,
                    heads,
                    otherwise,
                } = self.closes(c, "END_CASE", "CASE")?
                else {
                    return Ok(());
                };
                self.links.push((
                    self.k(&head),
                    Link::Case(Rc::new(CaseTable {
                        labels,
                        otherwise,
                        end: c.next,
                    })),
                ));
                for h in heads {
                    self.links.push((h, Link::Skip(c.next)));
                }
                Ok(())
            }
            StmtKind::For { .. } | StmtKind::WhileDo(_) | StmtKind::Repeat => self.push(
                Open::Loop {
                    head: Rc::clone(c),
                    exits: Vec::new(),
                },
                c,
            ),
            StmtKind::EndFor | StmtKind::EndWhile | StmtKind::Until(_) => {
                let (closer, want) = match c.st.kind {
                    StmtKind::EndFor => ("END_FOR", "FOR"),
                    StmtKind::EndWhile => ("END_WHILE", "WHILE"),
                    _ => ("UNTIL … END_REPEAT", "REPEAT"),
                };
                let Open::Loop { head, exits } = self.closes(c, closer, want)? else {
                    return Ok(());
                };
                let back = if matches!(head.st.kind, StmtKind::Repeat) {
                    head.next
                } else {
                    head.here
                };
                self.links.push((k, Link::Back(back)));
                self.links.push((self.k(&head), Link::Exit(c.next)));
                for e in exits {
                    self.links.push((e, Link::Exit(c.next)));
                }
                Ok(())
            }
            StmtKind::Exit => {
                let inner = self.stack.iter_mut().rev().find_map(|o| match o {
                    Open::Loop { exits, .. } => Some(exits),
                    _ => None,
                });
                match inner {
                    Some(exits) => {
                        exits.push(k);
                        Ok(())
                    }
                    None => Err(Pairing::fail(
                        c,
                        "EXIT is not inside a FOR, WHILE or REPEAT loop".into(),
                        "EXIT leaves the innermost loop; use GOTO to leave anything else",
                    )),
                }
            }
            _ => Ok(()),
        }
    }

    fn open_do(&mut self, c: &Rc<Compiled>, m: u8) -> Result<(), Fault> {
        let open: Vec<(u8, u64)> = self
            .stack
            .iter()
            .filter_map(|o| match o {
                Open::Do { m, head } => Some((*m, head.here.line)),
                _ => None,
            })
            .collect();
        if let Some((_, line)) = open.iter().find(|(n, _)| *n == m) {
            return Err(Pairing::fail(
                c,
                format!(
                    "DO {m} is already open (line {line}): nested loops need different numbers"
                ),
                "number nested loops 1, 2, 3 from the outside in",
            ));
        }
        if open.len() >= DO_NESTING {
            return Err(Pairing::fail(
                c,
                format!("more than {DO_NESTING} DO loops are nested"),
                "move the inner loop into a subprogram or a macro",
            ));
        }
        self.stack.push(Open::Do {
            m,
            head: Rc::clone(c),
        });
        Ok(())
    }

    fn end_do(&mut self, c: &Rc<Compiled>, m: u8) -> Result<(), Fault> {
        match self.stack.last() {
            Some(Open::Do { m: top, .. }) if *top == m => {}
            Some(Open::Do { m: top, head }) => {
                let line = head.here.line;
                return Err(Pairing::fail(
                    c,
                    format!("END {m} cannot close DO {top} (line {line}): the loops overlap"),
                    &format!("close DO {top} with END {top} first"),
                ));
            }
            _ => {
                return Err(Pairing::fail(
                    c,
                    format!("END {m} has no DO {m} before it"),
                    &format!("add WHILE [...] DO {m} before it, or remove it"),
                ));
            }
        }
        if let Some(Open::Do { head, .. }) = self.stack.pop() {
            self.links.push((self.k(c), Link::Back(head.here)));
            self.links.push((self.k(&head), Link::Exit(c.next)));
            self.loops.push(LoopRange {
                body: pos(head.next),
                end: pos(c.next),
                line: head.here.line,
                m,
            });
        }
        Ok(())
    }

    /// The program ended: what is still open alarms at its head.
    fn finish(mut self) -> Result<Paired, Fault> {
        if let Some(open) = self.stack.pop() {
            let head = Rc::clone(open.head());
            let what = match &open {
                Open::Do { m, .. } => format!("DO {m} has no END {m} before the program ends"),
                Open::If { .. } => "IF has no END_IF before the program ends".into(),
                Open::Case { .. } => "CASE has no END_CASE before the program ends".into(),
                Open::Loop { .. } => format!(
                    "{} has no {} before the program ends",
                    open.name(),
                    match open.name() {
                        "FOR" => "END_FOR",
                        "REPEAT" => "UNTIL … END_REPEAT",
                        _ => "END_WHILE",
                    }
                ),
            };
            return Err(Pairing::fail(
                &head,
                what,
                "close every loop and branch in the program that opens it",
            ));
        }
        Ok((self.links, self.loops))
    }
}

impl Interpreter<'_> {
    /// The program of the current level, as a key.
    pub(crate) fn program_key(&self) -> Key {
        let f = self.flow.frames.last().map(|f| (f.source, f.program));
        let (src, at) = f.unwrap_or((0, Cursor::default()));
        key(self.source_id(src), at)
    }

    /// Pairs the current ISO program's loops if not done yet.
    pub(crate) fn ensure_structure(&mut self, src: usize) -> Result<(), Diagnostic> {
        self.ensure(src, false)
    }

    /// Pairs the current `%@MACRO` program's structures if not done yet.
    #[inline]
    pub(crate) fn ensure_macro_structure(&mut self, src: usize) -> Result<(), Diagnostic> {
        self.ensure(src, true)
    }

    fn ensure(&mut self, src: usize, macro_file: bool) -> Result<(), Diagnostic> {
        let pk = self.program_key();
        if self.macros.structure.last == Some(pk) {
            return Ok(());
        }
        if !self.macros.structure.scanned.contains_key(&pk) {
            let program = self
                .flow
                .frames
                .last()
                .map_or(Cursor::default(), |f| f.program);
            let back = self.flow.source(src).map(|s| s.reader.position());
            let pairing = if macro_file {
                self.scan_macro(src, program)?
            } else {
                self.scan_iso(src, program)?
            };
            if let (Some(back), Some(s)) = (back, self.flow.source(src)) {
                s.reader.seek(back);
            }
            self.macros.moved_reader = true;
            let (links, loops) = match pairing.finish() {
                Ok(found) => found,
                Err((c, d)) => return Err(self.locate_compiled(d, src, &c)),
            };
            let s = &mut self.macros.structure;
            if s.links.len() + links.len() > LINK_LIMIT {
                return Err(alarms::bad_structure(
                    vcnc_syntax::Span::new(0, 1),
                    format!("more than {LINK_LIMIT} loop and branch statements in one run"),
                    "split the program",
                ));
            }
            s.links.extend(links);
            if s.scanned.len() >= LINK_LIMIT {
                s.scanned.clear();
            }
            s.scanned.insert(pk, loops.into());
        }
        self.macros.structure.last = Some(pk);
        Ok(())
    }

    fn scan_macro(&mut self, src: usize, program: Cursor) -> Result<Pairing, Diagnostic> {
        let id = self.source_id(src);
        let mut pairing = Pairing::new(id);
        let mut at = program;
        let mut first = true;
        while let Some(c) = self.read_statement(src, at)? {
            self.macros.remember(key(id, at), &c);
            if matches!(c.st.kind, StmtKind::Percent) && !first {
                break;
            }
            first = false;
            if c.st.kind.is_structure() {
                pairing
                    .statement(&c)
                    .map_err(|(c, d)| self.locate_compiled(d, src, &c))?;
            }
            at = c.next;
        }
        Ok(pairing)
    }

    fn scan_iso(&mut self, src: usize, program: Cursor) -> Result<Pairing, Diagnostic> {
        let id = self.source_id(src);
        let lex = self.cfg.dialect.lex;
        let syn = self.macros.rules.syntax(Lang::MacroB, &lex);
        let mut pairing = Pairing::new(id);
        let mut block = vcnc_syntax::Block::default();
        let mut col = program.col as usize;
        if let Some(s) = self.flow.source(src) {
            s.reader.seek(Cursor { col: 0, ..program });
        }
        let mut seen = false;
        while let Some(s) = self.flow.source(src) {
            let line = match s.reader.next_line() {
                Ok(Some(l)) => l,
                Ok(None) | Err(ReadError::Io(_)) => break,
                Err(ReadError::TooLong { .. }) => continue,
            };
            let bytes = s.reader.bytes(&line).to_vec();
            let bytes = bytes.as_slice();
            let mut i = std::mem::take(&mut col);
            // Every loop statement holds a D (DO, END) or, abbreviated,
            // EN (`EN1`): other lines only matter when they end the program.
            let boundary_like = bytes
                .iter()
                .find(|b| !b.is_ascii_whitespace())
                .is_some_and(|b| matches!(b, b'%' | b'O' | b'o'));
            let loop_like = bytes.iter().any(|b| matches!(b, b'D' | b'd'))
                || bytes.windows(2).any(|w| w.eq_ignore_ascii_case(b"EN"));
            if !boundary_like && !loop_like {
                seen |= bytes.iter().any(|b| !b.is_ascii_whitespace());
                continue;
            }
            let mut found: Vec<Rc<Compiled>> = Vec::new();
            let mut ended = false;
            while i < bytes.len() {
                let start = i;
                match lex_block(bytes, i, &lex, &mut block) {
                    Ok(n) => {
                        i = n;
                        let boundary =
                            block.percent || crate::flow::first_value(&block, b'O').is_some();
                        if boundary && seen {
                            ended = true;
                            break;
                        }
                        seen |= !boundary && !block.is_empty();
                    }
                    Err(_) => {
                        seen = true;
                        match parse_iso_block(bytes, start, &syn) {
                            Ok(Some((st, next))) => {
                                if matches!(st.kind, StmtKind::While { .. } | StmtKind::End(_)) {
                                    let here = Cursor {
                                        offset: line.offset,
                                        line: line.number,
                                        col: vcnc_syntax::clamp_u32(start),
                                    };
                                    found.push(Rc::new(Compiled {
                                        st,
                                        lang: Lang::MacroB,
                                        here,
                                        next: Cursor {
                                            col: vcnc_syntax::clamp_u32(next),
                                            ..here
                                        },
                                        lines: Box::new([(0, line)]),
                                        target: std::cell::Cell::new(None),
                                    }));
                                }
                                i = next;
                            }
                            Ok(None) => break,
                            Err(d) if loop_keyword(bytes, start) || opens_loop(bytes, start) => {
                                return Err(self.locate(d, src, &line));
                            }
                            Err(_) => break,
                        }
                    }
                }
            }
            for c in &found {
                pairing
                    .statement(c)
                    .map_err(|(c, d)| self.locate_compiled(d, src, &c))?;
            }
            if ended {
                break;
            }
        }
        Ok(pairing)
    }
}

/// Whether the block at `start` holds `DO m` (a digit after DO, blanks
/// between), after a `]`: an unreadable `WX[#1 GT 0] DO 1` meant to open a
/// loop, so its own error is reported rather than "END 1 has no DO 1"
/// later.
fn opens_loop(bytes: &[u8], start: usize) -> bool {
    let rest = bytes.get(start..).unwrap_or_default();
    let Some(close) = rest.iter().rposition(|b| *b == b']') else {
        return false;
    };
    let after = rest.get(close + 1..).unwrap_or_default();
    let after: Vec<u8> = after
        .iter()
        .copied()
        .filter(|b| !matches!(b, b' ' | b'\t'))
        .collect();
    after.len() >= 3 && after[..2].eq_ignore_ascii_case(b"DO") && after[2].is_ascii_digit()
}

/// Whether the block at `start` begins (after `/` and an N label) with
/// WHILE, DO or END (or Macro B's abbreviations WH, EN): its syntax error is
/// reported by the scan.
fn loop_keyword(bytes: &[u8], start: usize) -> bool {
    let mut i = start;
    let skip = |i: &mut usize, f: &dyn Fn(u8) -> bool| {
        while bytes.get(*i).is_some_and(|b| f(*b)) {
            *i += 1;
        }
    };
    skip(&mut i, &|b| matches!(b, b' ' | b'\t' | b'/'));
    if matches!(bytes.get(i), Some(b'N' | b'n')) {
        i += 1;
        skip(&mut i, &|b| b.is_ascii_digit() || b == b' ' || b == b'\t');
    }
    let rest = bytes.get(i..).unwrap_or_default();
    ["WHILE", "DO", "END", "WH", "EN"]
        .iter()
        .any(|k| rest.len() >= k.len() && rest[..k.len()].eq_ignore_ascii_case(k.as_bytes()))
}

impl Structure {
    /// The head of the lathe loop that the G26 at `here` closes: the
    /// program `pk` (source `src`, starting at `program`) is paired the
    /// first time one of its G26 blocks runs. `None`: the program has no
    /// block labelled with the G26's L.
    pub(crate) fn lathe_loop(
        &mut self,
        flow: &mut Flow,
        dialect: &Dialect,
        (pk, src, program): (Key, usize, Cursor),
        here: Cursor,
    ) -> Result<Option<Cursor>, Diagnostic> {
        if !self.lathe_paired.contains_key(&pk) {
            let links = pair_lathe_loops(flow, dialect, pk.0, src, program);
            if self.links.len() + links.len() > LINK_LIMIT {
                return Err(alarms::bad_structure(
                    vcnc_syntax::Span::new(0, 1),
                    format!("more than {LINK_LIMIT} loop and branch statements in one run"),
                    "split the program",
                ));
            }
            self.links.extend(links);
            if self.lathe_paired.len() >= LINK_LIMIT {
                self.lathe_paired.clear();
            }
            self.lathe_paired.insert(pk, ());
        }
        Ok(match self.links.get(&key(pk.0, here)) {
            Some(Link::Back(head)) => Some(*head),
            _ => None,
        })
    }
}

/// Every G26 of the program at `program` of source `src` (id `id`) with
/// the first block labelled by its L, in one pass over the program.
fn pair_lathe_loops(
    flow: &mut Flow,
    dialect: &Dialect,
    id: u32,
    src: usize,
    program: Cursor,
) -> Vec<(Key, Link)> {
    let is_loop = |w: &vcnc_syntax::Word| {
        w.addr == Addr::letter(b'G')
            && dialect
                .g(w.value)
                .is_some_and(|d| d.op == GOp::Flow(FlowOp::Loop))
    };
    let whole = |w: &vcnc_syntax::Word| (!w.point).then(|| whole_u32(w.value)).flatten();
    let mut labels: FastMap<u32, Cursor> = FastMap::default();
    let mut loops: Vec<(Cursor, Option<u32>)> = Vec::new();
    let lex = dialect.lex;
    flow.walk(src, program, &lex, true, false, |block, at, _| {
        for w in block.words() {
            if w.addr == Addr::letter(b'N')
                && let Some(n) = whole(w)
            {
                labels.entry(n).or_insert(at);
            }
        }
        if block.words().iter().any(is_loop) {
            let l = block.words().iter().find(|w| w.addr == Addr::letter(b'L'));
            loops.push((at, l.and_then(whole)));
        }
        false
    });
    loops
        .into_iter()
        .filter_map(|(at, l)| {
            let head = labels.get(&l?)?;
            Some((key(id, at), Link::Back(*head)))
        })
        .collect()
}
