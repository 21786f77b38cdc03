//! One-shot (group 00) codes that take the block's axis words: G04 dwell,
//! G05 high-speed mode, G28/G29/G30 reference returns, G53 machine-coordinate
//! moves; and the dispatch of every code that takes the axis words.
//!
//! ```text
//!   G28 X Y:  start ──rapid──▶ intermediate (program coords) ──rapid──▶ reference 1
//!   G29 X Y:  here  ──rapid──▶ that intermediate ──rapid──▶ commanded point
//! ```
//!
//! Only the named axes move, as in Fanuc 0i. The intermediate point is kept
//! per axis in program coordinates and goes through the frame like any
//! programmed point (so under G51.1 the mirror applies up to it, Syntec
//! 1.2.21); the reference point is a machine position. G29 after a change
//! of work system passes through the same program point in the new system.

use crate::alarms;
use crate::dialect::{BareReturn, DwellP, G53Incremental, G53WithoutAxes, GOp};
use crate::dialect::{CycleOp, FrameOp, MoveOp, PaceOp, SetOp, TurnOp};
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::words::Words;
use crate::words::{dwell_not_negative, whole};
use vcnc_core::events::Event;
use vcnc_syntax::{Diagnostic, Span};

impl<'a> Machining<'_, 'a> {
    /// Steps 6 and 7: the code that takes the block's axis words. Each
    /// role is matched whole: an operation that takes no axis words (its
    /// table row neither claims nor refuses them) does nothing here.
    pub(crate) fn axis_code(
        &mut self,
        op: GOp,
        cmd: Span,
        w: &Words<'_>,
    ) -> Result<(), Diagnostic> {
        match op {
            GOp::Move(m) => self.move_code(m, cmd, w),
            GOp::Set(s) => self.set_code(s, cmd, w),
            GOp::Pace(p) => self.pace_code(p, cmd, w),
            GOp::Frame(f) => self.frame_axis_code(f, cmd, w),
            GOp::Cycle(c) => self.cycle_axis_code(c, cmd, w),
            GOp::Turn(t) => self.turn_axis_code(t, cmd, w),
            // Program flow runs in step 8; the modal roles move by the
            // modal motion.
            GOp::Flow(_) | GOp::Motion(_) | GOp::Mode(_) | GOp::Comp(_) => Ok(()),
        }
    }

    /// The moves of G28, G29, G30, G53, G31, G38 and the seed lathe's
    /// G74/G76.
    fn move_code(&mut self, op: MoveOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            MoveOp::RefReturn => self.reference_return(w, cmd, 1),
            MoveOp::RefReturnN => {
                let n = match w.get(b'P') {
                    Some(p) => whole(&p, b'P', 1.0, 4.0, "P is a reference point number")?,
                    None => 2,
                };
                self.reference_return(w, cmd, n as usize)
            }
            MoveOp::RefFrom => self.return_from_reference(w, cmd),
            MoveOp::MachineCoords => self.machine_move(w, cmd),
            MoveOp::Skip => self.skip(w, cmd),
            MoveOp::RefXThenZ => self.reference_x_then_z(w, cmd),
            MoveOp::StartPoint => {
                let to = self.cfg.machine.start;
                self.straight(MoveKind::Rapid, Target::Machine(to), w, cmd)
            }
            MoveOp::Probe { must_trip } => self.probe(w, cmd, must_trip),
        }
    }

    /// G10, G92, G52 and the seed lathe's G75. G28.1/G30.1 and G92.1
    /// take no axis words (step 6b).
    fn set_code(&mut self, op: SetOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            SetOp::Data => {
                if self.tables.set_data(self.cfg, self.state, w, cmd)? {
                    self.state.refresh_origin(self.tables);
                }
                Ok(())
            }
            SetOp::PresetOrClamp => {
                self.tables.preset(self.cfg, self.state, w, cmd)?;
                self.state.refresh_origin(self.tables);
                Ok(())
            }
            SetOp::LocalSystem => {
                self.tables.local_system(self.cfg, self.state, w, cmd)?;
                self.state.refresh_origin(self.tables);
                Ok(())
            }
            SetOp::ProgramZero => self.program_zero(w, cmd),
            SetOp::RefStore(_) | SetOp::ShiftCancel | SetOp::ShiftSuspend(_) => Ok(()),
        }
    }

    /// The dwells and the settings that read the block's words. G09,
    /// G187 and EIA's G99 take no axis words.
    fn pace_code(&mut self, op: PaceOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            PaceOp::Dwell => self.dwell(w, cmd),
            PaceOp::DwellSeconds => self.dwell_seconds(w),
            PaceOp::DwellOrWait => self.dwell_or_wait(w),
            PaceOp::DwellP => self.dwell_p(w, cmd),
            PaceOp::HighSpeed => self.high_speed(w, cmd),
            PaceOp::PathSmoothing => {
                let look_ahead = (self.cfg.dialect.g(8.0))
                    .is_some_and(|d| d.op == GOp::Pace(PaceOp::LookAhead))
                    .then_some(self.cfg.machine.motion.corner_tolerance_mm);
                let now = (self.state.modal.path, self.unit_mm(), look_ahead);
                if let Some(t) = self.state.smoothing.path_smoothing(w, cmd, now)? {
                    self.report_smoothing(t);
                }
                Ok(())
            }
            PaceOp::FeedUp => self.feed_step(1, cmd),
            PaceOp::FeedDown => self.feed_step(-1, cmd),
            PaceOp::OverrideCancel => {
                self.set_magnification(100.0);
                Ok(())
            }
            PaceOp::OverrideSet => self.magnification(w, cmd),
            PaceOp::ExactStopOnce | PaceOp::Smoothing | PaceOp::LookAhead | PaceOp::Junction => {
                Ok(())
            }
        }
    }

    /// G51, G51.1/G50.1, G68 and G43.1, which read the axis words as
    /// their data; the other frame codes take none (step 6).
    fn frame_axis_code(&mut self, op: FrameOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            FrameOp::ScaleOn => {
                let next = (self.tables.transforms).scaled((self.cfg, self.state), w, cmd)?;
                self.use_transforms(next, cmd)
            }
            FrameOp::MirrorOn | FrameOp::MirrorOff => {
                let on = matches!(op, FrameOp::MirrorOn);
                let read = (self.cfg, &*self.state);
                let next = (self.tables.transforms).mirrored(read, w, (cmd, on))?;
                self.use_transforms(next, cmd)
            }
            FrameOp::RotateOn => {
                let next = (self.tables.transforms).rotated((self.cfg, self.state), w, cmd)?;
                self.use_transforms(next, cmd)
            }
            FrameOp::ToolLengthDynamic => self.dynamic_tool_length(w, cmd),
            FrameOp::ToolLengthPlus
            | FrameOp::ToolLengthMinus
            | FrameOp::ToolLengthCancel
            | FrameOp::PolarOn
            | FrameOp::PolarOff
            | FrameOp::ScaleOff
            | FrameOp::RotateOff => Ok(()),
        }
    }

    /// The hole patterns and pockets; the drilling cycles are modal (the
    /// modal motion drills) and G80 takes no axis words.
    fn cycle_axis_code(&mut self, op: CycleOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            CycleOp::PatternCircle
            | CycleOp::PatternLine
            | CycleOp::PatternArc
            | CycleOp::PatternGrid => self.pattern(op, w, cmd),
            CycleOp::PocketRect | CycleOp::PocketCircle => self.pocket(op, w, cmd),
            CycleOp::CircleCut(dir, form) => self.circle_cut(dir, form, w, cmd),
            CycleOp::Drill(..) | CycleOp::Cancel => Ok(()),
        }
    }

    /// The lathes' one-block cycles; G70–G73 read their profile from the
    /// program text instead (`profile_cycle`).
    fn turn_axis_code(&mut self, op: TurnOp, cmd: Span, w: &Words<'_>) -> Result<(), Diagnostic> {
        match op {
            TurnOp::CylinderCycle => self.cylinder_cycle(w, cmd),
            TurnOp::ThreadCycle => self.thread_cycle(w, cmd),
            TurnOp::FacePeckCycle => self.peck_cycle(w, cmd, true),
            TurnOp::GrooveCycle => self.peck_cycle(w, cmd, false),
            TurnOp::ThreadMultiCycle => self.thread_cycle_multi(w, cmd),
            TurnOp::NgcThreadCycle => self.ngc_thread_cycle(w, cmd),
            TurnOp::FinishCycle
            | TurnOp::NgcFinishCycle
            | TurnOp::NgcRoughCycle { .. }
            | TurnOp::RoughTurnCycle
            | TurnOp::RoughFaceCycle
            | TurnOp::PatternCycle => Ok(()),
        }
    }

    /// G04: P whole milliseconds (Haas: seconds with a point), or X (a
    /// lathe's U) seconds (milliseconds without a point).
    fn dwell(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let x = match (w.get(b'X'), w.get(b'U')) {
            (Some(_), Some(u)) => return Err(alarms::word_not_allowed(u.span, b'U')),
            (x, u) => x.or(u),
        };
        let seconds = match (w.get(b'P'), x) {
            (Some(_), Some(x)) => return Err(alarms::word_not_allowed(x.span, x.addr.0)),
            (Some(p), None) if p.point && self.cfg.dialect.dwell_p == DwellP::SecondsWithPoint => {
                dwell_not_negative(&p)?;
                p.value
            }
            (Some(p), None) => {
                f64::from(whole(
                    &p,
                    b'P',
                    0.0,
                    99_999_999.0,
                    "G04 P is whole milliseconds (use X for seconds)",
                )?) / 1000.0
            }
            (None, Some(x)) => {
                dwell_not_negative(&x)?;
                self.units().seconds(&x)
            }
            // Syntec 1.2.5: the dwell is X or P; a bare G04 says nothing.
            (None, None) => {
                return Err(alarms::needs_word(
                    cmd,
                    "G04",
                    "X (seconds) or P (milliseconds)",
                ));
            }
        };
        // Manual 1.2.5: 0.001 to 9999.999 s (0 is the exact-stop check).
        if seconds > 9_999.999 {
            let word = x.or(w.get(b'P')).unwrap_or_default();
            return Err(alarms::value_out_of_range(
                word.span,
                word.addr.0,
                word.value,
                "a dwell is at most 9999.999 s",
            ));
        }
        self.emit(|loc| Event::Dwell { loc, seconds });
        Ok(())
    }

    /// grbl G4 P: seconds (whole units), P required.
    fn dwell_p(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G4", "P (the dwell in seconds)"))?;
        self.dwell_p_seconds(&p)
    }

    /// A dwell of P seconds (milliseconds without a point in least-increment
    /// dialects), 0 to 9999.999 s.
    fn dwell_p_seconds(&mut self, p: &vcnc_syntax::Word) -> Result<(), Diagnostic> {
        let seconds = self.units().seconds(p);
        if !(0.0..=9_999.999).contains(&seconds) {
            return Err(alarms::value_out_of_range(
                p.span,
                b'P',
                p.value,
                "a dwell is 0 to 9999.999 s",
            ));
        }
        self.emit(|loc| Event::Dwell { loc, seconds });
        Ok(())
    }

    /// G38.2–G38.5: a probing move, a skip that fires where the machine
    /// file's probe (skip) signal is, whether the probe moves toward the
    /// work (contact made) or away (contact lost): the signal changes where
    /// the path crosses it. G38.2/G38.4 alarm when it does not.
    fn probe(&mut self, w: &Words<'_>, cmd: Span, must_trip: bool) -> Result<(), Diagnostic> {
        // Only this move's events: `pending` also holds earlier blocks'.
        let from = self.stage.pending.len();
        self.skip(w, cmd)?;
        let tripped = self
            .stage
            .pending
            .get(from..)
            .unwrap_or_default()
            .iter()
            .rev()
            .find_map(|e| match e {
                Event::Skip { triggered, .. } => Some(*triggered),
                _ => None,
            })
            .unwrap_or(false);
        if must_trip && !tripped {
            return Err(alarms::probe_not_tripped(cmd));
        }
        Ok(())
    }

    /// G28.1 / G30.1: the current machine position becomes reference
    /// point 1 / 2 (grbl's stored G28/G30 positions).
    pub(crate) fn store_reference(&mut self, n: u8) {
        let pos = self.state.pos;
        self.tables.set_reference(usize::from(n) - 1, pos);
    }

    /// EIA G04: P seconds with a point, milliseconds without; no P is the
    /// chapter's untimed dwell, which waits for the operator like M00.
    fn dwell_or_wait(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let Some(p) = w.get(b'P') else {
            self.emit(|loc| Event::Wait {
                loc,
                reason: vcnc_core::events::WaitReason::CycleStart,
            });
            return Ok(());
        };
        self.dwell_p_seconds(&p)
    }

    /// Syntec G05 P10000 / P1–P5 (on) and P0 (off), manual 1.2.6: recorded
    /// for the planner; the path itself is unchanged here.
    fn high_speed(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G05", "P (0 off, 1-5 or 10000 on)"))?;
        let n = whole(&p, b'P', 0.0, 10_000.0, "G05 P is 0, 1-5 or 10000")?;
        if !matches!(n, 0..=5 | 10_000) {
            return Err(alarms::value_out_of_range(
                p.span,
                b'P',
                p.value,
                "G05 P is 0, 1-5 or 10000",
            ));
        }
        self.state.modal.high_speed = n != 0;
        self.state.high_speed_p = n;
        self.emit(|loc| Event::HighSpeed {
            loc,
            on: n != 0,
            p: n,
        });
        Ok(())
    }

    /// G28 (n = 1) and G30 Pn.
    fn reference_return(&mut self, w: &Words<'_>, cmd: Span, n: usize) -> Result<(), Diagnostic> {
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let (mid, named) = (goal.prog, goal.named);
        let reference = self.tables.reference.get(n - 1).copied().flatten();
        if named == 0 && self.cfg.dialect.bare_return == BareReturn::NeedsAxes {
            return Err(alarms::needs_axes(cmd, "a reference return"));
        }
        let reference = reference
            .ok_or_else(|| alarms::no_reference(w.get(b'P').map_or(cmd, |p| p.span), n))?;
        if named == 0 {
            // Haas, grbl: every axis goes straight to the reference point.
            return self.straight(MoveKind::Rapid, Target::Machine(reference), w, cmd);
        }
        for i in 0..self.cfg.machine.axes.len() {
            if named & (1 << i) != 0 {
                self.state.intermediate.set(i, mid.get(i));
            }
        }
        // Axis indices are below MAX_AXES (6): the mask fits in a byte.
        self.state.intermediate_axes |= (named & 0x3f) as u8;
        // Both legs move like G00 (dog-legs with parameter 411 = 1); the
        // block is all or nothing, so a second leg that alarms drops the first.
        self.straight(MoveKind::Rapid, self.state.move_target(&goal), w, cmd)?;
        let mut end = self.settled_tool_pos()?;
        for i in 0..self.cfg.machine.axes.len() {
            if named & (1 << i) != 0 {
                end.set(i, reference.get(i));
            }
        }
        self.straight(MoveKind::Rapid, Target::Machine(end), w, cmd)
    }

    /// G29: back through the intermediate point to the commanded point.
    fn return_from_reference(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let mut named = 0u32;
        let mut mid = self.state.prog;
        let mut target = self.state.prog;
        for (i, axis) in self.cfg.machine.axes.iter().enumerate() {
            let Some(word) = w.get(axis.letter) else {
                continue;
            };
            if self.state.intermediate_axes & (1 << i) == 0 {
                return Err(alarms::g29_without_g28(cmd, axis.letter));
            }
            let m = self.state.intermediate.get(i);
            let v = self.units().axis_value(&self.cfg.axis_words, i, &word);
            mid.set(i, m);
            target.set(
                i,
                if self.state.modal.incremental {
                    m + v
                } else {
                    v
                },
            );
            named |= 1 << i;
        }
        if named == 0 {
            return Err(alarms::needs_axes(cmd, "G29"));
        }
        self.straight(MoveKind::Rapid, Target::Program(mid), w, cmd)?;
        self.straight(MoveKind::Rapid, Target::Program(target), w, cmd)
    }

    /// G53: a rapid to machine coordinates (absolute only). Without axis
    /// words, and under G91, the dialect's G53 rule alarms or lets the
    /// block go on without it.
    fn machine_move(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        if self.state.modal.incremental {
            return match self.cfg.dialect.g53_incremental {
                G53Incremental::Alarm => Err(alarms::g53_incremental(cmd)),
                G53Incremental::Ignored => {
                    self.warn(alarms::g53_ignored_incremental(cmd));
                    Ok(())
                }
            };
        }
        let mut to = self.settled_tool_pos()?;
        let mut named = 0;
        for (i, axis) in self.cfg.machine.axes.iter().enumerate() {
            if let Some(word) = w.get(axis.letter) {
                to.set(i, self.units().axis_value(&self.cfg.axis_words, i, &word));
                named |= 1 << i;
            }
        }
        if named == 0 {
            return match self.cfg.dialect.g53_without_axes {
                G53WithoutAxes::Alarm if w.group(crate::dialect::Group::Motion).is_none() => {
                    Err(alarms::needs_axes(cmd, "G53"))
                }
                _ => Ok(()),
            };
        }
        self.straight(MoveKind::Rapid, Target::Machine(to), w, cmd)
    }
}
