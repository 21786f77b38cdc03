//! M98 calls and M99 returns (Syntec manual chapter 2, item 11).
//!
//! - `M98 P p`: run program `O p` (same file, or the program store), then
//!   continue after the M98. `H n` starts at `N n` of that program; with no
//!   P, `H n` calls `N n` of the current program. `L k` runs it k times.
//! - `M99`: return after the call (or run the next repetition). In a main
//!   program it starts the program again.
//! - `M99 P n`: return to `N n` of the calling program (in a main program:
//!   jump to its `N n`).
//!
//! Every call, repetition and jump counts against `limits.max_jumps`, and
//! nesting against `limits.max_call_depth`, so a runaway loop alarms.

use crate::alarms;
use crate::flow::{Frame, ProgramStore};
use crate::interpreter::{Interpreter, Step};
use crate::words::Words;
use crate::words::whole;
use vcnc_core::events::EndCode;
use vcnc_syntax::{Cursor, Diagnostic, Span};

impl Interpreter<'_> {
    /// M98.
    pub(crate) fn call(
        &mut self,
        w: &Words<'_>,
        m: Span,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
        local: bool,
    ) -> Result<Step, Diagnostic> {
        // M98 P program [H sequence]; Haas M97 P sequence (of this program).
        let (program_letter, seq_letter) = if local {
            (None, b'P')
        } else {
            (Some(b'P'), b'H')
        };
        let program = program_letter.and_then(|l| w.get(l)).map(|p| {
            whole(&p, b'P', 0.0, 99_999_999.0, "P is a program number").map(|n| (n, p.span))
        });
        let program = program.transpose()?;
        let seq = w.get(seq_letter).map(|h| {
            whole(&h, h.addr.0, 0.0, 99_999_999.0, "a sequence number").map(|n| (n, h.span))
        });
        let seq = seq.transpose()?;
        let runs = match w.get(b'L') {
            Some(l) => whole(&l, b'L', 1.0, 99_999_999.0, "L is a repeat count")?,
            None => 1,
        };
        if program.is_none() && seq.is_none() {
            return Err(if local {
                alarms::needs_word(m, "M97", "P (a sequence number of this program)")
            } else {
                alarms::needs_word(m, "M98", "P (a program number) or H (a sequence number)")
            });
        }
        self.check_call_depth(m)?;
        let lex = self.cfg.dialect.lex;
        let caller = self.flow().frame();
        let (source, program_start) = match program {
            Some((n, span)) => match self.flow().find_program(n, &lex, store) {
                Ok(Some(found)) => found,
                Ok(None) => return Err(alarms::program_not_found(span, n)),
                Err(e) => return Err(alarms::program_unreadable(span, n, &e)),
            },
            None => (caller.source, caller.program),
        };
        let mut start = program_start;
        if let Some((n, span)) = seq {
            start = self
                .flow()
                .find_sequence(source, program_start, n, &lex)
                .ok_or_else(|| alarms::sequence_not_found(span, n))?;
        }
        let _ = here;
        // Every check has passed: only now does the flow change.
        self.count_jump(m)?;
        let flow = self.flow();
        flow.frames.push(Frame {
            source,
            start,
            program: program_start,
            last: None,
            ret: next,
            runs_left: runs,
            started: seq.is_some(),
            returns_with: "M99",
            // A subprogram shares its caller's locals.
            locals: caller.locals,
            call: crate::flow::CallKind::Sub,
            number: program.map_or(caller.number, |(n, _)| Some(n)),
        });
        Ok(Step::Jump(start))
    }

    /// A call of a subroutine of the running program (lathe G20, LinuxCNC's
    /// O CALL): a level at `start` of the same source and locals, returning
    /// to `ret` with `returns_with`.
    pub(crate) fn enter_local_sub(
        &mut self,
        start: Cursor,
        ret: Cursor,
        returns_with: &'static str,
    ) {
        let caller = self.flow().frame();
        self.enter_sub_in(caller.source, start, ret, returns_with);
    }

    /// A call of a subroutine at `start` of source `source` (the running
    /// one, or LinuxCNC's subroutine file) with the caller's locals.
    pub(crate) fn enter_sub_in(
        &mut self,
        source: usize,
        start: Cursor,
        ret: Cursor,
        returns_with: &'static str,
    ) {
        let caller = self.flow().frame();
        let program = if source == caller.source {
            caller.program
        } else {
            Cursor::default()
        };
        self.flow().frames.push(Frame {
            source,
            start,
            program,
            last: None,
            ret,
            runs_left: 1,
            started: true,
            returns_with,
            locals: caller.locals,
            call: crate::flow::CallKind::Sub,
            number: caller.number,
        });
    }

    /// E406 when one more call level would pass `limits.max_call_depth`.
    pub(crate) fn check_call_depth(&self, at: Span) -> Result<(), Diagnostic> {
        let depth = self.flow.frames.len() as u64;
        let max = self.cfg.machine.limits.max_call_depth;
        if depth > u64::from(max) {
            return Err(alarms::nesting_too_deep(at, max));
        }
        Ok(())
    }

    /// M99.
    pub(crate) fn ret(&mut self, w: &Words<'_>, m: Span, here: Cursor) -> Result<Step, Diagnostic> {
        let target = w.get(b'P').map(|p| {
            whole(&p, b'P', 0.0, 99_999_999.0, "M99 P is a sequence number").map(|n| (n, p.span))
        });
        let target = target.transpose()?;
        // The limit is checked (and the jump counted) before anything moves:
        // an M99 that alarms leaves the flow as it was.
        self.count_jump(m)?;
        let lex = self.cfg.dialect.lex;
        let flow = self.flow();
        let frame = flow.frame();
        if flow.frames.len() == 1 {
            // A main program: start again, or jump to N n.
            let to = match target {
                Some((n, span)) => flow
                    .find_sequence(frame.source, frame.program, n, &lex)
                    .ok_or_else(|| alarms::sequence_not_found(span, n))?,
                None => frame.start,
            };
            if (to.offset, to.col) <= (here.offset, here.col) && !self.macros.used {
                // Back to an earlier block: nothing in a program without
                // variables can end the loop, so a machine runs it for
                // ever (a bar feeder); one pass is the run. A program that
                // uses variables can count its passes: it loops, bounded
                // by the runaway limits.
                self.machining().warn(alarms::main_program_repeats(m));
                return self.end_program(EndCode::M99);
            }
            return Ok(Step::Jump(to));
        }
        if frame.runs_left > 1 && target.is_none() {
            if let Some(f) = flow.frame_mut() {
                f.runs_left -= 1;
                f.started = false;
            }
            return Ok(Step::Jump(frame.start));
        }
        let caller = flow
            .frames
            .len()
            .checked_sub(2)
            .and_then(|i| flow.frames.get(i).copied())
            .unwrap_or(frame);
        let to = match target {
            Some((n, span)) => flow
                .find_sequence(caller.source, caller.program, n, &lex)
                .ok_or_else(|| alarms::sequence_not_found(span, n))?,
            None => frame.ret,
        };
        let left = flow.frames.pop();
        self.leave_level(left);
        Ok(Step::Jump(to))
    }
}

/// The lathe's program flow (seed 003): G20 L calls the blocks from `N L`
/// as a subroutine until G24; G25 L jumps to `N L`; G26 L Q repeats the
/// blocks from `N L` up to the G26 block so that they run Q times in all
/// ("the number of cycles depends on the value of Q"). Like M98/M99, every
/// call and jump counts against `limits.max_jumps`.
impl Interpreter<'_> {
    /// The `N` number of an L word, found in the current program.
    fn label(&mut self, w: &Words<'_>, cmd: Span) -> Result<Cursor, Diagnostic> {
        let (n, at) = sequence_word(w, cmd)?;
        let lex = self.cfg.dialect.lex;
        let frame = self.flow().frame();
        self.flow()
            .find_sequence(frame.source, frame.program, n, &lex)
            .ok_or_else(|| alarms::sequence_not_found(at, n))
    }

    /// G20 L: call `N L` of this program until G24.
    pub(crate) fn sub_call(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        next: Cursor,
    ) -> Result<Step, Diagnostic> {
        let start = self.label(w, cmd)?;
        self.check_call_depth(cmd)?;
        self.count_jump(cmd)?;
        self.enter_local_sub(start, next, "G24");
        Ok(Step::Jump(start))
    }

    /// G24: back after the G20 that called.
    pub(crate) fn sub_return(&mut self, cmd: Span) -> Result<Step, Diagnostic> {
        if self.flow().frames.len() < 2 {
            return Err(alarms::return_without_call(cmd));
        }
        self.count_jump(cmd)?;
        let left = self.flow().frames.pop();
        self.leave_level(left);
        Ok(Step::Jump(left.map(|f| f.ret).unwrap_or_default()))
    }

    /// G25 L: continue at `N L`.
    pub(crate) fn jump(&mut self, w: &Words<'_>, cmd: Span) -> Result<Step, Diagnostic> {
        let to = self.label(w, cmd)?;
        self.count_jump(cmd)?;
        Ok(Step::Jump(to))
    }

    /// G26 L Q: back to `N L` until the body has run Q times.
    pub(crate) fn loop_back(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        here: Cursor,
    ) -> Result<Step, Diagnostic> {
        let q = w.get(b'Q').ok_or_else(|| {
            alarms::needs_word(cmd, "G26", "Q (how many times the loop body runs)")
        })?;
        let runs = whole(
            &q,
            b'Q',
            1.0,
            99_999_999.0,
            "Q is how many times the loop body runs",
        )?;
        // Its head was paired before the first G26 of the program ran
        // (`macros/structure.rs`); its L is still read here, so a missing
        // or malformed L alarms as it does after G20 and G25.
        let (n, at) = sequence_word(w, cmd)?;
        let frame = self.flow().frame();
        let program = (self.program_key(), frame.source, frame.program);
        let head =
            self.macros
                .structure
                .lathe_loop(&mut self.flow, self.cfg.dialect, program, here)?;
        let to = head.ok_or_else(|| alarms::sequence_not_found(at, n))?;
        let key = (frame.source, here.offset, here.col);
        let left = self.flow().loops.get(&key).copied().unwrap_or(runs - 1);
        if left == 0 {
            self.flow().loops.remove(&key);
            return Ok(Step::Next);
        }
        self.count_jump(cmd)?;
        let loops = &mut self.flow().loops;
        if loops.len() >= 4096 && !loops.contains_key(&key) {
            loops.clear();
        }
        loops.insert(key, left - 1);
        Ok(Step::Jump(to))
    }
}

/// The sequence number in the L word of a lathe G20, G25 or G26, and
/// where it stands.
fn sequence_word(w: &Words<'_>, cmd: Span) -> Result<(u32, Span), Diagnostic> {
    let l = w
        .get(b'L')
        .ok_or_else(|| alarms::needs_word(cmd, "this code", "L (the sequence number to go to)"))?;
    let n = whole(&l, b'L', 1.0, 99_999_999.0, "L is a sequence number")?;
    Ok((n, l.span))
}
