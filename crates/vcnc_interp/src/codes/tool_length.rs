//! Tool length compensation G43/G44/G49 (Syntec 1.2.19) and the step of a
//! block that changes the frame without taking its axis words (G15/G16,
//! G50, G69 and the tool length codes).
//!
//! ```text
//!   G43 H1:  tool_offset.z = +(h + h wear) of offset 1     (spindle moves up
//!   G44 H1:  tool_offset.z = −(h + h wear)                  for a longer tool)
//!   G49, H0: tool_offset.z = 0
//! ```
//!
//! The value is latched when H is given (a later G10 L10 does not move the
//! tool until H is commanded again). The programmed point stays where it
//! is, so the machine moves: with Z in the block to the compensated Z, and
//! in a block that does not move otherwise by a move of Z alone (Fanuc;
//! LinuxCNC applies it at the next move instead) — rapid under G00, at the
//! feed under the other motions.

use crate::alarms;
use crate::dialect::FrameOp;
use crate::dialect::{GOp, Group, OffsetDefault};
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::state::frame::Transform;
use crate::state::{Motion, ToolLength};
use crate::words::Words;
use vcnc_core::events::Pos;
use vcnc_syntax::{Diagnostic, Span};

impl<'a> Machining<'_, 'a> {
    /// Step 6 for codes without axis words. Returns whether the tool
    /// offset changed (the block then moves Z if nothing else moves it).
    pub(crate) fn frame_codes(&mut self, w: &Words<'_>) -> Result<bool, Diagnostic> {
        if let Some(p) = w.group(Group::Polar) {
            let on = p.def.op == GOp::Frame(FrameOp::PolarOn);
            if on && !self.state.modal.polar {
                // Incremental polar moves start from where the tool is.
                self.state.modal.polar = true;
                self.state.polar = self.state.polar_of(self.cfg, self.state.prog);
            }
            self.state.modal.polar = on;
        }
        if let Some(g) = w
            .group(Group::Scaling)
            .filter(|g| g.def.op == GOp::Frame(FrameOp::ScaleOff))
        {
            let next = self.tables.transforms.without(&Transform::Scale {
                factor: [1.0; 3],
                centre: [0.0; 3],
            });
            self.use_transforms(next, g.span)?;
        }
        if let Some(g) = w
            .group(Group::Rotation)
            .filter(|g| g.def.op == GOp::Frame(FrameOp::RotateOff))
        {
            let next = self.tables.transforms.without(&Transform::Rotate {
                plane: vcnc_core::events::Plane::Xy,
                degrees: 0.0,
                centre: [0.0; 3],
            });
            self.use_transforms(next, g.span)?;
        }
        self.tool_length(w)
    }

    /// G43/G44/G49 and an H word under G43/G44.
    fn tool_length(&mut self, w: &Words<'_>) -> Result<bool, Diagnostic> {
        let code = w.group(Group::ToolLength);
        // H belongs to G43/G44 in their block, else to the mode in force
        // (unless an M98 of the block reads it as a sequence number).
        let m98 = w
            .m_of(crate::dialect::MGroup::Flow)
            .is_some_and(|m| m.def.op == crate::dialect::MOp::Call);
        let h = w.get(b'H').filter(|_| {
            code.is_some() || (self.state.modal.tool_length != ToolLength::Off && !m98)
        });
        if code.is_none() && h.is_none() {
            return Ok(false);
        }
        if code.is_some_and(|c| c.def.op == GOp::Frame(FrameOp::ToolLengthDynamic)) {
            // G43.1 takes its value from the axis words (refs.rs dispatch).
            return Ok(false);
        }
        let mode = match code.map(|c| c.def.op) {
            Some(GOp::Frame(FrameOp::ToolLengthPlus)) => ToolLength::Plus,
            Some(GOp::Frame(FrameOp::ToolLengthMinus)) => ToolLength::Minus,
            Some(_) => ToolLength::Off,
            None => self.state.modal.tool_length,
        };
        if let Some(h) = h {
            self.state.h_number = self.cfg.offset_word(&h, self.state.tool_active)?;
        } else if mode != ToolLength::Off
            && code.is_some()
            && self.cfg.dialect.offset_default == OffsetDefault::ToolInSpindle
        {
            let at = code.map_or(w.first, |c| c.span);
            self.state.h_number = self.cfg.tool_in_spindle(self.state.tool_active, at)?;
        }
        let sign = match mode {
            ToolLength::Plus => 1.0,
            ToolLength::Minus => -1.0,
            ToolLength::Off => 0.0,
        };
        let t = self.tables.tool(self.state.h_number);
        let offset = sign * (t.h_mm + t.h_wear_mm);
        let n = self.state.h_number;
        if mode != ToolLength::Off && offset == 0.0 && n != 0 && self.first_zero_offset(1, n) {
            let g = if mode == ToolLength::Plus {
                "G43"
            } else {
                "G44"
            };
            let at = code.map_or(w.first, |c| c.span);
            self.warn(alarms::zero_offset(at, &format!("{g} H{n} = 0")));
        }
        let before = self.state.frame.tool;
        let mut tool = before;
        match self.cfg.machine.axis_of(b'Z') {
            Some(z) => tool.set(z, offset),
            None if offset != 0.0 => {
                let at = code.map_or(w.first, |c| c.span);
                return Err(alarms::tool_length_without_z(at));
            }
            None => {}
        }
        self.state.modal.tool_length = mode;
        if tool == before {
            return Ok(false);
        }
        self.state.frame.tool = tool;
        self.state.frame_dirty = true;
        Ok(true)
    }

    /// grbl/LinuxCNC G43.1 Z: a tool length offset given as a value, not a
    /// register. Nothing moves: the programmed position reads the new
    /// offset, and the next move goes where it puts the program point.
    pub(crate) fn dynamic_tool_length(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let z = self
            .cfg
            .machine
            .axis_of(b'Z')
            .ok_or_else(|| alarms::tool_length_without_z(cmd))?;
        let word = w
            .get(b'Z')
            .ok_or_else(|| alarms::needs_word(cmd, "G43.1", "Z (the tool length offset)"))?;
        for a in self.cfg.axis_words.iter().filter(|a| a.letter != b'Z') {
            if let Some(other) = w.get(a.letter) {
                return Err(alarms::word_not_allowed(other.span, a.letter));
            }
        }
        let mut tool = Pos::default();
        tool.set(z, self.units().length_mm(&word));
        self.state.modal.tool_length = ToolLength::Plus;
        self.state.frame.tool = tool;
        self.state.prog = self.state.frame.program_of(self.state.nominal);
        self.state.detached = false;
        self.state.frame_dirty = true;
        Ok(())
    }

    /// A block that changed the tool offset and did not move: Z moves so
    /// that the programmed point stays where it is.
    pub(crate) fn tool_length_move(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let cmd = w.group(Group::ToolLength).map_or(w.first, |c| c.span);
        let kind = match self.state.modal.motion {
            Motion::Rapid => MoveKind::Rapid,
            _ => MoveKind::Feed(self.feed(cmd)?),
        };
        let to = self.state.prog;
        self.straight(kind, Target::Program(to), w, cmd)
    }
}
