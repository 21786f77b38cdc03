//! The "execute" phase of one validated block, in a fixed order:
//!
//! ```text
//!  1 modal G codes (units, distance, plane, feed mode, G96/G97, work system,
//!    path mode, polar input, cycle return level)
//!  2 F, S, T     3 M06     4 M03/M04/M05/M19     5 M08/M09
//!  6 the frame: G43/G44/G49, G15/G16, G50, G69 (no axis words) and the
//!    codes that take the axis words as arguments: G10, G92, G52, G51,
//!    G51.1/G50.1, G68, G04
//!  7 G28/G29/G30/G53/G31, or the modal motion, or the tool length move
//!  8 M00/M01/M02/M30/M98/M99
//! ```
//!
//! Modal codes come first so that `G96 S130 M03`, `G91 X10` and `G70 F10`
//! read their words in the mode the same block selects (Fanuc behaviour);
//! program flow comes last so that a block's motion happens before it ends
//! or jumps. A block is all or nothing (see `interpreter.rs`), so a step may
//! change the state before a later step alarms.

use crate::alarms;
use crate::config::Config;
use crate::dialect::{
    AxisWords, GOp, Group, MGroup, MOp, ProgramStop, SurfaceSpeedOn, ThreadLead, ToolChangeSpindle,
    ToolLengthChange, ToolWords, bit,
};
use crate::dialect::{FlowOp, ModeOp, MotionOp, PaceOp, SetOp};
use crate::flow::ProgramStore;
use crate::interpreter::Machining;
use crate::interpreter::{AfterAlarm, Interpreter, Step};
use crate::motion::stage::Stage;
use crate::state::{Motion, State};
use crate::words::{ALWAYS, Words};
use vcnc_core::events::{EndCode, Event, PathMode, Plane, SpindleDir, StopCode};
use vcnc_syntax::{Addr, Block, Cursor, Diagnostic, Span};

impl Words<'_> {
    /// Axis and arc words, F, N and at most a motion code: the common block
    /// of a CAM program, which does nothing but move.
    pub(crate) fn is_plain_motion(&self, axis_mask: u32) -> bool {
        !self.has_codes && self.present() & !(axis_mask | PLAIN_EXTRA) == 0
    }

    /// Whether the block carries words beyond axes, F and N (arc words),
    /// which then have to be checked against the motion.
    fn has_arc_words(&self, axis_mask: u32) -> bool {
        self.ext_present != 0 || self.present() & !(axis_mask | bit(b'F') | bit(b'N')) != 0
    }
}

impl Interpreter<'_> {
    /// A plain move that [`moves_in_place`](Stage::moves_in_place)
    /// accepted, all or nothing with the stage's mark instead of a copy of
    /// the state.
    #[inline(always)]
    pub(crate) fn move_in_place(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let mark = Stage::mark_move(&self.state);
        #[cfg(debug_assertions)]
        let whole = self.state;
        let result = self.execute_motion_only(w);
        if result.is_err() {
            Stage::rollback_move(mark, &mut self.state);
            #[cfg(debug_assertions)]
            debug_assert!(
                self.state == whole,
                "a plain move changed a field that the stage's MoveMark does not keep"
            );
        }
        result
    }

    /// [`move_in_place`](Self::move_in_place) under compensation, for a
    /// block that [`moves_in_place`](Stage::moves_in_place) accepts.
    #[inline(never)]
    pub(crate) fn compensated_move_in_place(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let mark = self.stage.mark_compensated_move(&self.state);
        #[cfg(debug_assertions)]
        let whole = (self.state, self.stage.comp.clone());
        let result = self.execute_motion_only(w);
        if result.is_err() {
            self.stage.rollback_compensated_move(mark, &mut self.state);
            #[cfg(debug_assertions)]
            debug_assert!(
                self.state == whole.0 && self.stage.comp == whole.1,
                "a compensated move changed a field that the stage's CompensatedMoveMark does not keep"
            );
        }
        result
    }

    /// A block that [`Words::is_plain_motion`] accepts: nothing to do but move.
    pub(crate) fn execute_motion_only(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let (mut m, points) = self.machining_and_points();
        m.motion_words(w)?;
        if points.active {
            m.note_points(points, w);
        }
        m.motion_only(w)
    }

    pub(crate) fn execute(
        &mut self,
        w: &Words<'_>,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let (mut m, points) = self.machining_and_points();
        let path_before = m.modes(w)?;
        if points.active {
            m.note_points(points, w);
        }
        let tool_moved = m.words(w, path_before)?;
        let moves_before = m.stage.moves;
        let mut resume = None;
        match w.axis_user {
            // G70–G73 read their profile from the program text.
            Some(user) if user.def.op.reads_profile() => {
                resume = self
                    .profile_cycle(user.def.op, user.span, w, next)
                    .inspect_err(|_| self.looping.after_alarm = Some(next))?;
            }
            Some(user) => m.axis_code(user.def.op, user.span, w)?,
            None => m.modal_motion(w)?,
        }
        self.machining().after_motion(w, tool_moved, moves_before)?;
        // Calls and returns are resolved last: an unknown program or
        // sequence alarms after the motion, which the alarm then drops.
        let flow = self.prepare_flow(w, here, next, store)?;
        self.program_flow(w, flow.or(resume.map(Step::Jump)))
    }

    /// Step 8: stops, ends, calls and returns (already resolved).
    fn program_flow(&mut self, w: &Words<'_>, flow: Option<Step>) -> Result<Step, Diagnostic> {
        let Some(m) = w.m_of(MGroup::Flow) else {
            return Ok(flow.unwrap_or(Step::Next));
        };
        match m.def.op {
            MOp::Stop => self.machining().program_stop(StopCode::M00),
            MOp::OptionalStop if self.cfg.opts.optional_stop => {
                self.machining().program_stop(StopCode::M01)
            }
            MOp::End => return self.end_program(EndCode::M02),
            MOp::EndRewind => return self.end_program(EndCode::M30),
            // Calls and returns were resolved before (`prepare_flow`); the
            // other M codes are not of the flow group.
            MOp::OptionalStop
            | MOp::Call
            | MOp::Return
            | MOp::LocalCall
            | MOp::SpindleCw
            | MOp::SpindleCcw
            | MOp::SpindleStop
            | MOp::SpindleOrient
            | MOp::RigidTap
            | MOp::ToolChange
            | MOp::CoolantOn
            | MOp::CoolantOff => {}
        }
        Ok(flow.unwrap_or(Step::Next))
    }

    /// Under [`Options::keep_going`](crate::Options::keep_going), after the
    /// alarm of a block that ends the program or returns from a subprogram
    /// (M02, M30, M99): that end or return, on its own, from the state as
    /// it was before the block. The rest of the block is dropped as any
    /// alarmed block is, but its flow still decides where the run goes on —
    /// else an alarmed M99 (after a held `,C`, say) leaves the subprogram
    /// without a return, the run ends with E406 and the caller's remaining
    /// blocks go unchecked. [`AfterAlarm::Next`] when the block has no
    /// such code or its flow part alarms too: the run then goes on with the
    /// next block, as after any alarm — [`AfterAlarm::NextMoved`] when that
    /// was a return whose `P` sequence was searched for (the search moved
    /// the reader).
    #[cold]
    #[inline(never)]
    pub(crate) fn flow_after_alarm(&mut self, block: &Block, here: Cursor) -> AfterAlarm {
        let mut words = Words::new(block);
        if words
            .fill(self.cfg.dialect, self.cfg.machine, self.cfg.axis_mask)
            .is_err()
        {
            return AfterAlarm::Next;
        }
        let Some(m) = words.m_of(MGroup::Flow) else {
            return AfterAlarm::Next;
        };
        // A block that calls a macro is that call, not a flow block.
        let m_macro = (words.other_m.iter().flatten())
            .any(|o| self.cfg.machine.m_macros.contains_key(&o.def));
        if words.macro_call.is_some() || m_macro {
            return AfterAlarm::Next;
        }
        let jumps = self.flow.jumps;
        let saved = self.state;
        let mark = self.stage.begin(false);
        let result = match m.def.op {
            MOp::Return => self.ret(&words, m.span, here),
            MOp::End => self.end_program(EndCode::M02),
            MOp::EndRewind => self.end_program(EndCode::M30),
            MOp::Stop
            | MOp::OptionalStop
            | MOp::Call
            | MOp::LocalCall
            | MOp::SpindleCw
            | MOp::SpindleCcw
            | MOp::SpindleStop
            | MOp::SpindleOrient
            | MOp::RigidTap
            | MOp::ToolChange
            | MOp::CoolantOn
            | MOp::CoolantOff => return AfterAlarm::Next,
        };
        match result {
            Ok(step) => {
                self.tables.commit();
                AfterAlarm::Flow(step)
            }
            Err(_) => {
                self.stage.abandon(mark);
                self.flow.jumps = jumps;
                self.state = saved;
                self.tables.rollback();
                // Only a return searches the program (for its P).
                if m.def.op == MOp::Return {
                    AfterAlarm::NextMoved
                } else {
                    AfterAlarm::Next
                }
            }
        }
    }

    /// The end of the run: compensation's last move leaves first, then the
    /// frame, then the `end` event.
    pub(crate) fn end_program(&mut self, code: EndCode) -> Result<Step, Diagnostic> {
        self.machining().comp_finish()?;
        self.machining().report_frame();
        if let Some(e) = self.unset_report() {
            self.machining().emit(|_| e);
        }
        if let Some(w) = self.whole_units_report() {
            self.machining().emit(|_| w);
        }
        self.machining().emit(|loc| Event::End { loc, code });
        Ok(Step::End(code))
    }

    /// Resolves M98/M99 of the block into the jump it will make.
    fn prepare_flow(
        &mut self,
        w: &Words<'_>,
        here: Cursor,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Option<Step>, Diagnostic> {
        if let Some(g) = w.axis_user
            && let GOp::Flow(flow) = g.def.op
        {
            match flow {
                FlowOp::SubCall => return self.sub_call(w, g.span, next).map(Some),
                FlowOp::SubReturn => return self.sub_return(g.span).map(Some),
                FlowOp::Jump => return self.jump(w, g.span).map(Some),
                // A finished loop continues after its block, but pairing
                // the program's loops may have moved the reader: re-read
                // from `next`.
                FlowOp::Loop => {
                    let step = self.loop_back(w, g.span, here)?;
                    return Ok(Some(if matches!(step, Step::Next) {
                        Step::Jump(next)
                    } else {
                        step
                    }));
                }
                // Macro calls leave before execution (`Interpreter::block`).
                FlowOp::MacroCall | FlowOp::MacroModal | FlowOp::MacroModalCancel => {}
            }
        }
        let Some(m) = w.m_of(MGroup::Flow) else {
            return Ok(None);
        };
        match m.def.op {
            MOp::Call => self.call(w, m.span, here, next, store, false).map(Some),
            MOp::Return => self.ret(w, m.span, here).map(Some),
            MOp::LocalCall => self.call(w, m.span, here, next, store, true).map(Some),
            // Stops and ends run after the motion (`program_flow`).
            MOp::Stop
            | MOp::OptionalStop
            | MOp::End
            | MOp::EndRewind
            | MOp::SpindleCw
            | MOp::SpindleCcw
            | MOp::SpindleStop
            | MOp::SpindleOrient
            | MOp::RigidTap
            | MOp::ToolChange
            | MOp::CoolantOn
            | MOp::CoolantOff => Ok(None),
        }
    }
}

impl Machining<'_, '_> {
    /// Step 1: the checks of the block's codes against the modes in
    /// force, then its modal codes (returns the path mode before them).
    fn modes(&mut self, w: &Words<'_>) -> Result<PathMode, Diagnostic> {
        self.check_comp_changes(w)?;
        self.check_cycle_plane(w)?;
        if self.state.modal.high_speed {
            self.check_high_speed(w)?;
        }
        let path_before = self.state.modal.path;
        let plane_before = self.state.modal.plane;
        let (wcs_before, inch_before) = (self.state.modal.wcs, self.state.modal.inch);
        for at in w.modal_codes() {
            self.apply_modal(at.def.op);
        }
        if self.stage.nurbs.is_some() {
            self.check_curve_pending(w)?;
        }
        self.cycle_modes(w)?;
        if w.group(Group::Wcs).is_some() {
            self.state.refresh_origin(self.tables);
        }
        if self.cfg.markers {
            self.report_modes(wcs_before, inch_before);
        }
        let (allowed, ext) = self.allowed_letters(w);
        w.check_used(allowed, ext)
            .map_err(|d| cancelled_cycle_hint(d, w))?;
        if self.cfg.dialect.polar_words {
            self.state.check_polar_words(self.cfg, w, plane_before)?;
        }
        Ok(path_before)
    }

    /// Steps 2–6: F, S, T, M06, the spindle, coolant, the other M codes,
    /// the frame codes without axis words, compensation and the settings
    /// (returns whether a tool length offset moved the tool).
    fn words(&mut self, w: &Words<'_>, path_before: PathMode) -> Result<bool, Diagnostic> {
        if self.state.modal.path != path_before {
            let mode = self.state.modal.path;
            self.emit(|loc| Event::PathMode { loc, mode });
        }
        if w.group(Group::Path).is_some_and(|g| {
            g.def.op == GOp::Mode(ModeOp::PathCutting) && g.def.letters & bit(b'P') != 0
        }) {
            self.blend_tolerance(w)?;
        }
        self.feed_word(w)?;
        self.tool_words(w)?;
        self.spindle_words(w)?;
        if let Some(m) = w.m_of(MGroup::Coolant) {
            let on = m.def.op == MOp::CoolantOn;
            self.state.coolant = on;
            self.emit(|loc| Event::Coolant { loc, on });
        }
        self.other_m_codes(w);
        let tool_moved = self.frame_codes(w)?;
        self.state.smoothing.frame_change(w);
        self.comp_codes(w)?;
        self.setting_codes(w)?;
        Ok(tool_moved)
    }

    /// After step 7's motion: a held corner's check, a tool length offset
    /// that moves by itself, EIA G99, the compensation's block end and a
    /// frame changed without a move.
    fn after_motion(
        &mut self,
        w: &Words<'_>,
        tool_moved: bool,
        moves_before: u64,
    ) -> Result<(), Diagnostic> {
        if self.state.lathe.corner.is_some() {
            self.check_corner_cut(w)?;
        }
        if tool_moved && self.stage.moves == moves_before {
            match self.cfg.dialect.tool_length_change {
                ToolLengthChange::MovesNow => self.tool_length_move(w)?,
                ToolLengthChange::AtNextMove => {
                    let s = &mut *self.state;
                    s.prog = s.frame.program_of(s.nominal);
                    s.detached = false;
                }
            }
        }
        if let Some(g99) = w.once(GOp::Pace(PaceOp::Junction)) {
            // EIA G99: the junction after this block's cut may blend.
            let cuts = matches!(
                self.state.modal.motion,
                Motion::Linear | Motion::ArcCw | Motion::ArcCcw
            );
            if !cuts || self.stage.moves == moves_before || w.axis_user.is_some() {
                return Err(alarms::needs_word(
                    g99.span,
                    "G99",
                    "a G01, G02 or G03 move",
                ));
            }
            self.emit(|loc| Event::Junction { loc, blend: true });
        }
        if self.stage.comp.engaged() {
            self.comp_block_end(w.first)?;
        }
        // A frame changed without a move is reported with its block, before
        // the block's stop or end.
        self.report_frame();
        Ok(())
    }
    /// A plain block's words before its move: D, the motion code, the
    /// letters the motion allows, polar words.
    fn motion_words(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        if w.get(b'D').is_some() {
            // A D word (a new radius, or outside G41/G42 the offset the
            // next G41/G42 uses) reaches the compensation stage; a plain
            // block has no G40/G41/G42, so without D there is nothing to do.
            self.comp_codes(w)?;
        }
        if let Some(motion) = w.group(Group::Motion) {
            self.apply_modal(motion.def.op);
            if self.state.cycle.code.is_some() {
                self.cycle_modes(w)?;
            }
        }
        if w.has_arc_words(self.cfg.axis_mask) {
            let (allowed, ext) = self.allowed_letters(w);
            w.check_used(allowed, ext)?;
            if self.cfg.dialect.polar_words {
                self.state
                    .check_polar_words(self.cfg, w, self.state.modal.plane)?;
            }
        }
        Ok(())
    }

    /// A plain block's F and its move.
    fn motion_only(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        self.feed_word(w)?;
        self.modal_motion(w)?;
        if self.state.lathe.corner.is_some() {
            self.check_corner_cut(w)?;
        }
        if self.stage.comp.engaged() {
            self.comp_block_end(w.first)?;
        }
        Ok(())
    }
}

/// Letters a plain motion block may carry besides the axes.
const PLAIN_EXTRA: u32 =
    bit(b'F') | bit(b'N') | bit(b'R') | bit(b'I') | bit(b'J') | bit(b'K') | bit(b'D');

/// E109 for a negative F (a feed or a thread's lead).
fn not_negative_feed(f: &vcnc_syntax::Word) -> Result<(), Diagnostic> {
    if f.value < 0.0 {
        return Err(alarms::value_out_of_range(
            f.span,
            b'F',
            f.value,
            "a feed is not negative",
        ));
    }
    Ok(())
}

/// The centre-offset letters of a plane.
fn plane_offsets(plane: Plane) -> u32 {
    match plane {
        Plane::Xy => bit(b'I') | bit(b'J'),
        Plane::Zx => bit(b'I') | bit(b'K'),
        Plane::Yz => bit(b'J') | bit(b'K'),
    }
}

/// The bit of an extended address in `Words::ext_present`.
fn ext_bit(a: Addr) -> u8 {
    a.extended_index().map_or(0, |i| 1 << i)
}

/// E203 in a block with a cycle code and a group-01 code: the help says
/// that the group-01 code cancelled the cycle (Syntec 1.2.31).
#[cold]
fn cancelled_cycle_hint(mut d: Diagnostic, w: &Words<'_>) -> Diagnostic {
    if let (Some(cycle), Some(_)) = (w.group(Group::Cycle), w.group(Group::Motion))
        && matches!(cycle.def.op, GOp::Cycle(_))
        && d.code.as_str() == "E203"
    {
        d.help = "a group-01 code (G00–G03) cancels the canned cycle in its block (Syntec 1.2.31): remove it to drill, or cancel the cycle in a block of its own".to_string();
    }
    d
}

impl<'a> Machining<'_, 'a> {
    /// Step 1: one modal code written in the block. The frame codes,
    /// compensation, the cycles and G66 have steps of their own (6, the
    /// compensation stage, `cycle_modes`, the macro call); the one-shot
    /// roles have no modal group.
    fn apply_modal(&mut self, op: GOp) {
        match op {
            GOp::Motion(m) => self.state.modal.motion = m,
            GOp::Mode(m) => self.apply_mode(m),
            GOp::Flow(FlowOp::MacroModalCancel) => self.state.modal.macro_call = false,
            GOp::Flow(
                FlowOp::SubCall
                | FlowOp::SubReturn
                | FlowOp::Jump
                | FlowOp::Loop
                | FlowOp::MacroCall
                | FlowOp::MacroModal,
            )
            | GOp::Frame(_)
            | GOp::Comp(_)
            | GOp::Cycle(_)
            | GOp::Move(_)
            | GOp::Set(_)
            | GOp::Pace(_)
            | GOp::Turn(_) => {}
        }
    }

    /// Step 1 for a modal setting.
    fn apply_mode(&mut self, op: ModeOp) {
        let m = &mut self.state.modal;
        match op {
            ModeOp::RadiusMode => m.diameter = false,
            ModeOp::DiameterMode => m.diameter = true,
            ModeOp::PlaneXy => m.plane = Plane::Xy,
            ModeOp::PlaneZx => m.plane = Plane::Zx,
            ModeOp::PlaneYz => m.plane = Plane::Yz,
            ModeOp::Absolute => m.incremental = false,
            ModeOp::Incremental => m.incremental = true,
            ModeOp::PerMinute => {
                m.per_rev = false;
                m.inverse_time = false;
            }
            ModeOp::PerRev => {
                m.per_rev = true;
                m.inverse_time = false;
            }
            ModeOp::InverseTime => {
                m.per_rev = false;
                m.inverse_time = true;
            }
            ModeOp::ArcCentersAbsolute => m.arc_absolute = true,
            ModeOp::ArcCentersIncremental => m.arc_absolute = false,
            ModeOp::Inch => m.inch = true,
            ModeOp::Metric => m.inch = false,
            ModeOp::SurfaceSpeed => m.css = true,
            ModeOp::SpindleRpm => m.css = false,
            ModeOp::WorkSystem(n) => m.wcs = usize::from(n),
            ModeOp::CancelOffsets => {
                // Lathe G53/G500: no work system, no G92 shift, no local
                // offset — machine coordinates are program coordinates.
                m.wcs = usize::from(crate::dialect::WORK_NONE);
                self.tables.set_shift(vcnc_core::events::Pos::default());
                self.tables.set_local(vcnc_core::events::Pos::default());
            }
            ModeOp::PathExact => m.path = PathMode::ExactStop,
            ModeOp::PathSurface => m.path = PathMode::Surface,
            ModeOp::PathTapping => m.path = PathMode::Tapping,
            ModeOp::PathCutting => m.path = PathMode::Cutting,
            ModeOp::ReturnInitial => m.return_r = false,
            ModeOp::ReturnR => m.return_r = true,
        }
    }

    /// Letters and extended addresses this block may carry, given its
    /// codes and the modal motion.
    fn allowed_letters(&self, w: &Words<'_>) -> (u32, u8) {
        let mut allowed = ALWAYS | w.code_letters();
        if self.state.modal.tool_length != crate::state::ToolLength::Off {
            // Under G43/G44 an H word alone changes the offset.
            allowed |= bit(b'H');
        } else if w.get(b'H').is_some_and(|h| h.value == 0.0)
            && self.cfg.dialect.h_is_length_offset()
        {
            // H0 is "no tool length offset" (its register is always 0):
            // posts write it beside G49 or G53 (`G49 H0`, `G53 G00 H0 Z0`).
            allowed |= bit(b'H');
        }
        if self.comp_on_reads_d() || self.d_alone_is_radius() {
            // Under G41/G42 a D word alone changes the radius; outside them
            // it selects the offset the next G41/G42 uses (Fanuc: D is
            // modal; `T1 M06 D1`, `G43 Z10. H1 D1`). Where G41 reads no D
            // (fanuc-lathe: the radius is T's nose) D stays unused.
            allowed |= bit(b'D');
        }
        if self.state.cycle.code.is_some() && w.axis_user.is_none() {
            // In cycle mode a drilling block may change the cycle's data.
            allowed |= self.cfg.dialect.cycles.words;
        }
        let mut ext = 0u8;
        match w.axis_user.map(|u| u.def.axes) {
            Some(AxisWords::Refuse) => {}
            Some(AxisWords::ClaimAbsolute) => allowed |= self.cfg.machine.axis_letter_mask(),
            Some(_) => allowed |= self.cfg.axis_mask,
            None => {
                allowed |= self.cfg.axis_mask;
                if self.cfg.dialect.polar_words {
                    // LinuxCNC's `@`/`^` stand for X and Y in every motion.
                    ext |= ext_bit(Addr::AT) | ext_bit(Addr::CARET);
                }
                match self.state.modal.motion {
                    Motion::ArcCw | Motion::ArcCcw => {
                        allowed |= bit(b'R')
                            | self.cfg.dialect.arc_letters
                            | plane_offsets(self.state.modal.plane);
                        ext |= ext_bit(Addr::CR) | ext_bit(Addr::COMMA_C) | ext_bit(Addr::COMMA_R);
                    }
                    Motion::ThreePointArc => ext |= ext_bit(Addr::IX) | ext_bit(Addr::IZ),
                    Motion::Nurbs => allowed |= bit(b'K') | bit(b'R'),
                    // Fanuc lathe: chamfer and corner R at a G01's end.
                    Motion::Linear => ext |= ext_bit(Addr::COMMA_C) | ext_bit(Addr::COMMA_R),
                    // G90/G92/G94 taper.
                    Motion::TurnCycle | Motion::ThreadingCycle | Motion::FaceCycle => {
                        allowed |= bit(b'R');
                    }
                    // LinuxCNC's G33 K: the lead, modal blocks too.
                    Motion::Thread if self.cfg.dialect.thread_lead == ThreadLead::K => {
                        allowed |= bit(b'K');
                    }
                    // LinuxCNC's G33.1: K, the pitch, in every block.
                    Motion::RigidTap => allowed |= bit(b'K'),
                    Motion::Rapid | Motion::Thread | Motion::ThreadInch => {}
                }
            }
        }
        (allowed, ext)
    }

    /// Step 2a: F — a feed, a thread lead under G32/G33, or a code's own
    /// value when the code reads F (lathe G04 F seconds, G31 F percent).
    #[inline]
    fn feed_word(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        // Most blocks have no F: that test in the caller, the rest apart.
        match w.get(b'F') {
            Some(f) => self.feed_word_given(w, f),
            None => Ok(()),
        }
    }

    /// [`feed_word`](Self::feed_word) for the block's F word `f`.
    #[inline(never)]
    fn feed_word_given(&mut self, w: &Words<'_>, f: vcnc_syntax::Word) -> Result<(), Diagnostic> {
        if w.code_letters() & bit(b'F') != 0 {
            return Ok(());
        }
        not_negative_feed(&f)?;
        match self.state.modal.motion {
            Motion::Thread | Motion::ThreadingCycle
                if w.axis_user.is_none() && self.cfg.dialect.thread_lead != ThreadLead::K =>
            {
                self.state.thread_lead_mm = Some(self.lead_mm(&f)?)
            }
            Motion::ThreadInch if w.axis_user.is_none() => {
                self.state.thread_lead_mm = Some(f.value * crate::block::convert::MM_PER_INCH);
            }
            _ => self.set_feed(f),
        }
        Ok(())
    }

    /// F as a thread's lead in mm: in program units, or under
    /// [`ThreadLead::FHundredths`] 0.01 mm when written without a point.
    fn lead_mm(&self, f: &vcnc_syntax::Word) -> Result<f64, Diagnostic> {
        let plain = !f.point
            && self.cfg.dialect.thread_lead == ThreadLead::FHundredths
            && self.cfg.machine.params.decimal_input
                != vcnc_core::machine::DecimalInput::Calculator;
        if !plain {
            return Ok(f.value * self.unit_mm());
        }
        if self.state.modal.inch {
            return Err(alarms::lead_without_point_in_inch(f.span));
        }
        Ok(f.value * 0.01)
    }

    /// F as the feed of the cutting moves that follow.
    fn set_feed(&mut self, f: vcnc_syntax::Word) {
        self.state.feed = f.value;
        let mm_per_min = f.value * self.unit_mm() * self.state.feed_factor;
        // Under G93 F is no rate: the move checks its own.
        let rate = !self.state.modal.per_rev && !self.state.modal.inverse_time;
        if rate && mm_per_min > self.cfg.max_feed {
            self.warn(alarms::feed_clamped(f.span, mm_per_min, self.cfg.max_feed));
        }
    }

    /// The words of a G70–G73 profile block beyond its move, which G70
    /// runs before the move (`codes/profile.rs` has checked that nothing
    /// else is there): steps 1 (G96/G97, G98/G99; G00–G03 and G40–G42 are
    /// the profile's own), 2 (F is a feed whatever the modal motion: G70
    /// cuts), 2b T, 4 spindle, 5 coolant and builder M codes, and G04 in
    /// the place of step 6. A frame a T changed is reported here, with the
    /// T block's line.
    pub(crate) fn profile_words(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        for at in w.modal_codes() {
            if matches!(at.def.group, Group::SpindleMode | Group::FeedMode) {
                self.apply_modal(at.def.op);
            }
        }
        if let Some(f) = w.get(b'F') {
            not_negative_feed(&f)?;
            self.set_feed(f);
        }
        self.tool_words(w)?;
        self.spindle_words(w)?;
        if let Some(m) = w.m_of(MGroup::Coolant) {
            let on = m.def.op == MOp::CoolantOn;
            self.state.coolant = on;
            self.emit(|loc| Event::Coolant { loc, on });
        }
        self.other_m_codes(w);
        if let Some(g04) = w.once(GOp::Pace(PaceOp::Dwell)) {
            self.axis_code(GOp::Pace(PaceOp::Dwell), g04.span, w)?;
        }
        self.report_frame();
        Ok(())
    }

    /// Step 2b: T selects, M06 changes (a lathe turret indexes on T).
    fn tool_words(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        if self.cfg.dialect.tool_words == ToolWords::TurretOffset {
            return self.turret_word(w);
        }
        if let Some(t) = w.get(b'T') {
            let n = crate::words::whole(&t, b'T', 0.0, 99_999_999.0, "T is a tool number")?;
            self.state.tool_selected = Some(n);
        }
        if let Some(m6) = w.m_of(MGroup::Tool) {
            let tool = self
                .state
                .tool_selected
                .ok_or_else(|| alarms::m06_without_tool(m6.span))?;
            self.state.tool_active = Some(tool);
            if self.cfg.dialect.tool_change == ToolChangeSpindle::Stops
                && matches!(self.state.spindle, SpindleDir::Cw | SpindleDir::Ccw)
            {
                self.cycle_spindle(SpindleDir::Stop);
            }
            self.emit(|loc| Event::ToolChange { loc, tool });
        }
        Ok(())
    }

    /// Steps 2c and 4: S, G96/G97 and the spindle M codes, one event at most.
    fn spindle_words(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let clamp_block = w
            .axis_user
            .is_some_and(|a| a.def.op == GOp::Set(SetOp::PresetOrClamp));
        if let Some(s) = w.get(b'S') {
            if s.value < 0.0 {
                return Err(alarms::value_out_of_range(
                    s.span,
                    b'S',
                    s.value,
                    "a spindle speed is not negative",
                ));
            }
            if clamp_block {
                // G92 S: the highest speed G96 may ask for.
                self.state.max_rpm = Some(s.value);
            } else {
                self.state.s_value = s.value;
            }
        }
        let s_word = w.get(b'S').filter(|_| !clamp_block);
        let mode = w.group(Group::SpindleMode);
        // LinuxCNC's `G96 D2500 S120`: D is the highest speed.
        if let Some(d) = mode
            .filter(|m| {
                m.def.op == GOp::Mode(ModeOp::SurfaceSpeed) && m.def.letters & bit(b'D') != 0
            })
            .and_then(|_| w.get(b'D'))
        {
            self.state.max_rpm = Some(d.value);
        }
        if mode.is_some_and(|m| m.def.op == GOp::Mode(ModeOp::SpindleRpm)) && s_word.is_none() {
            // G97 alone keeps the speed the spindle turns at (Fanuc).
            self.state.s_value = self.state.rpm;
        }
        let m = w.m_of(MGroup::Spindle);
        if m.is_some_and(|a| a.def.op == MOp::RigidTap) {
            // M29 S: the speed waits for the tapping cycle, which turns
            // the spindle itself (Fanuc rigid tapping).
            self.state.rigid_tap = true;
            return Ok(());
        }
        let dir = match m.map(|a| a.def.op) {
            Some(MOp::SpindleCw) => SpindleDir::Cw,
            Some(MOp::SpindleCcw) => SpindleDir::Ccw,
            Some(MOp::SpindleStop) => SpindleDir::Stop,
            Some(MOp::SpindleOrient) => SpindleDir::Orient,
            _ => self.state.spindle,
        };
        let turning = matches!(dir, SpindleDir::Cw | SpindleDir::Ccw);
        // Under G96 the speed follows the tool's diameter, the clamp and the units.
        let css_input = self.state.modal.css
            && (w.m_of(MGroup::Tool).is_some() || clamp_block || w.group(Group::Units).is_some());
        let changed = m.is_some() || (turning && (s_word.is_some() || mode.is_some() || css_input));
        if !changed {
            return Ok(());
        }
        // An alarm about the speed points at what set it: G96, S, else the M code.
        let why = mode
            .map(|a| a.span)
            .or(s_word.map(|s| s.span))
            .or(m.map(|a| a.span));
        let (mut rpm, surface) = if turning {
            self.spindle_rpm(why.unwrap_or(w.first))?
        } else {
            (0.0, None)
        };
        let max_rpm = self.cfg.machine.params.max_spindle_rpm;
        if max_rpm > 0.0 && rpm > max_rpm {
            // The warning points at the speed asked for when there is one.
            self.warn(alarms::spindle_clamped(
                s_word.map(|s| s.span).or(why).unwrap_or(w.first),
                rpm,
                max_rpm,
            ));
            rpm = max_rpm;
        }
        if turning
            && m.is_none()
            && (rpm - self.state.rpm).abs() < 1e-9
            && self.state.spindle == dir
        {
            return Ok(());
        }
        self.state.spindle = dir;
        self.state.rpm = rpm;
        if rpm > 0.0 {
            self.stage.spindle_warned = false;
        }
        self.emit(|loc| Event::Spindle {
            loc,
            dir,
            rpm,
            surface_m_per_min: surface,
        });
        Ok(())
    }

    /// The speed the spindle turns at now: S rpm, or the surface speed over
    /// the active tool's diameter under G96, clamped by G92 S.
    pub(crate) fn spindle_rpm(&self, span: Span) -> Result<(f64, Option<f64>), Diagnostic> {
        if !self.state.modal.css {
            return Ok((self.state.s_value, None));
        }
        // S is m/min, or ft/min in inch mode.
        let surface_m_per_min = self.surface_m_per_min();
        if self.cfg.dialect.surface_speed == SurfaceSpeedOn::WorkDiameter {
            let rpm = self.work_css_rpm(self.state.prog, surface_m_per_min, span)?;
            return Ok((rpm, Some(surface_m_per_min)));
        }
        let radius = self
            .state
            .tool_active
            .map(|t| self.tables.tool(t))
            .map(|t| t.d_mm + t.d_wear_mm);
        let diameter_mm = radius
            .filter(|r| *r > 0.0)
            .map(|r| 2.0 * r)
            .ok_or_else(|| alarms::css_without_diameter(span))?;
        let rpm = 1000.0 * surface_m_per_min / (std::f64::consts::PI * diameter_mm);
        let rpm = self.state.max_rpm.map_or(rpm, |max| rpm.min(max));
        Ok((rpm, Some(surface_m_per_min)))
    }

    /// M00, or M01 with the optional-stop switch on: the program waits for
    /// the operator; on most controls the spindle and coolant stop first.
    fn program_stop(&mut self, code: StopCode) {
        if self.cfg.dialect.program_stop == ProgramStop::StopsSpindleAndCoolant {
            if self.state.spindle != SpindleDir::Stop {
                self.state.spindle = SpindleDir::Stop;
                self.state.rpm = 0.0;
                self.emit(|loc| Event::Spindle {
                    loc,
                    dir: SpindleDir::Stop,
                    rpm: 0.0,
                    surface_m_per_min: None,
                });
            }
            if self.state.coolant {
                self.state.coolant = false;
                self.emit(|loc| Event::Coolant { loc, on: false });
            }
        }
        self.emit(|loc| Event::Stop { loc, code });
    }

    /// Syntec 1.2.6: M codes are invalid in high-speed mode; G05 P0 leaves it.
    fn check_high_speed(&self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let m =
            w.m.iter()
                .flatten()
                .map(|m| m.span)
                .chain(w.other_m.iter().flatten().map(|m| m.span))
                .min_by_key(|s| s.start);
        match m {
            Some(span) => Err(alarms::m_code_in_high_speed(span)),
            None => Ok(()),
        }
    }

    /// Step 6b: one-shot settings without axis words (G28.1/G30.1, G92.1,
    /// G92.2/G92.3, G187, LinuxCNC's G4).
    fn setting_codes(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        for at in w.once_codes() {
            match at.def.op {
                GOp::Set(SetOp::RefStore(n)) => self.store_reference(n),
                GOp::Set(SetOp::ShiftCancel) => {
                    self.tables.set_shift(vcnc_core::events::Pos::default());
                    self.state.refresh_origin(self.tables);
                }
                GOp::Set(SetOp::ShiftSuspend(on)) => {
                    self.tables.suspend_shift(on);
                    self.state.refresh_origin(self.tables);
                }
                GOp::Pace(PaceOp::Smoothing) => {
                    let (on, tolerance_mm) = crate::state::Smoothing::haas_level(w, self.units());
                    self.emit(|loc| Event::Smoothing {
                        loc,
                        on,
                        tolerance_mm,
                    });
                }
                GOp::Pace(PaceOp::LookAhead) => {
                    let corner_mm = self.cfg.machine.motion.corner_tolerance_mm;
                    if let Some(t) = self.state.smoothing.look_ahead(w, at.span, corner_mm)? {
                        self.report_smoothing(t);
                    }
                }
                // A G4 that leaves the axis words to the motion (LinuxCNC:
                // the dwell, then the block's move).
                GOp::Pace(PaceOp::DwellP) if !at.def.takes_axes() => {
                    self.axis_code(GOp::Pace(PaceOp::DwellP), at.span, w)?;
                }
                // The rest of the one-shot codes take the axis words (step
                // 7), or act in steps of their own: G09 with its move, EIA's
                // G99 after it, calls in step 8.
                GOp::Set(
                    SetOp::Data | SetOp::LocalSystem | SetOp::PresetOrClamp | SetOp::ProgramZero,
                )
                | GOp::Pace(_)
                | GOp::Move(_)
                | GOp::Cycle(_)
                | GOp::Turn(_)
                | GOp::Flow(_)
                | GOp::Frame(_)
                | GOp::Motion(_)
                | GOp::Mode(_)
                | GOp::Comp(_) => {}
            }
        }
        Ok(())
    }

    /// LinuxCNC's (and grbl posts') `G64 P`: blend within P of the
    /// programmed path, a `smoothing` event the planner reads as G05.1's;
    /// `G64` without P blends as fast as the machine allows (its own corner
    /// tolerance: smoothing off). Q, the naive-CAM merge of collinear
    /// moves, is read and not modelled.
    fn blend_tolerance(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let tolerance_mm = match w.get(b'P') {
            Some(p) if p.value < 0.0 => {
                return Err(alarms::value_out_of_range(
                    p.span,
                    b'P',
                    p.value,
                    "G64's P is a path tolerance, not negative",
                ));
            }
            Some(p) => self.units().length_mm(&p),
            None => 0.0,
        };
        // Only a change reaches the planner (a bare G64 on every safe-start
        // line would otherwise send `off` with nothing on).
        if tolerance_mm == self.state.smoothing.reported_mm {
            return Ok(());
        }
        self.state.smoothing.reported_mm = tolerance_mm;
        let on = tolerance_mm > 0.0;
        self.emit(|loc| Event::Smoothing {
            loc,
            on,
            tolerance_mm,
        });
        Ok(())
    }

    /// Step 5b: the machine builder's M codes and the controller's own
    /// auxiliary ones pass through as `aux` events (the machine file's
    /// description first); unknown ones (on a machine that is not strict)
    /// warn.
    fn other_m_codes(&mut self, w: &Words<'_>) {
        for m in w.other_m.iter().flatten() {
            let description = self.cfg.machine.m_codes.get(&m.def).cloned().or_else(|| {
                self.cfg
                    .dialect
                    .aux_m(m.def)
                    .map(|a| std::sync::Arc::<str>::from(a.what))
            });
            match description {
                Some(description) => {
                    self.emit(|loc| Event::Aux {
                        loc,
                        code: m.def,
                        description,
                    });
                }
                None => self.warn(alarms::unknown_m_ignored(
                    m.span,
                    m.def,
                    self.cfg.dialect.name,
                )),
            }
        }
    }

    /// Reports a warning about the current block (located in its line); it
    /// reaches the sink with the block's events.
    #[cold]
    pub(crate) fn warn(&mut self, d: Diagnostic) {
        let d = match self.stage.cur_line {
            Some((src, line)) => self.at.locate(d, src, &line),
            None => d,
        };
        self.emit(|_| Event::Warning(d));
    }

    /// `work_system` and `units` events when the block changed them (with
    /// [`Interpreter::with_program_markers`]).
    #[cold]
    #[inline(never)]
    fn report_modes(&mut self, wcs_before: usize, inch_before: bool) {
        let m = self.state.modal;
        if m.wcs != wcs_before {
            let system = u8::try_from(m.wcs)
                .ok()
                .filter(|n| *n < crate::dialect::WORK_NONE);
            self.emit(|loc| Event::WorkSystem { loc, system });
        }
        if m.inch != inch_before {
            self.emit(|loc| Event::Units { loc, inch: m.inch });
        }
    }

    /// The `smoothing` event of what the smoothing state decided
    /// (`codes/smoothing.rs`), out of line: a G01 asks for it rarely.
    #[inline(never)]
    pub(crate) fn report_smoothing(&mut self, tolerance_mm: f64) {
        self.emit(crate::state::Smoothing::event(tolerance_mm));
    }

    /// Adds an event of the current block; it reaches the sink when the
    /// block has succeeded.
    pub(crate) fn emit(&mut self, make: impl FnOnce(vcnc_core::events::Loc) -> Event) {
        let e = make(self.at.loc().clone());
        self.stage.emit(e);
    }
}

impl Stage {
    /// Whether a plain motion block `w` is a G00/G01 that the stage's
    /// [`MoveMark`](Self::mark_move) (or under compensation its
    /// [`CompensatedMoveMark`](Self::mark_compensated_move)) can undo: no canned cycle,
    /// lathe corner, G96 or an unfinished G06.2 curve in force (each changes more before it can
    /// alarm), compensation either off or holding a move with nothing
    /// queued behind it, and nothing in the block beyond axes, F and N (no
    /// arc word, D or `,C`/`,R`).
    #[inline(always)]
    pub(crate) fn moves_in_place(
        &self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        comp_engaged: bool,
    ) -> bool {
        if (comp_engaged && !self.comp.can_mark())
            || self.nurbs.is_some()
            || s.cycle.code.is_some()
            || s.lathe.corner.is_some()
            || s.modal.css
            || w.has_arc_words(cfg.axis_mask)
        {
            return false;
        }
        match w.group(Group::Motion) {
            Some(m) => matches!(
                m.def.op,
                GOp::Motion(MotionOp::Rapid) | GOp::Motion(MotionOp::Linear)
            ),
            None => matches!(s.modal.motion, Motion::Rapid | Motion::Linear),
        }
    }
}
