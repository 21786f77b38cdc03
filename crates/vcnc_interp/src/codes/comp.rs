//! The codes of cutter radius compensation (Syntec 1.2.18): G41/G42 with
//! D, G40, and D alone while compensating. What the compensation does to
//! the path is the motion stage's (`motion/comp/`); here the block sets the
//! mode, the side and the radius.
//!
//! The radius is D's `d_mm + d_wear_mm`, latched when D is given (a later
//! `G10 L12` of that D changes nothing until D is given again); D0 is a
//! radius of 0; a negative value puts the tool on the other side (the
//! manual's direction table). G41/G42/G40 in a block with G02/G03 alarm
//! (E317, "only with G00 and G01"), but for G41/G42 in a dialect that
//! starts compensation on an entry arc (`CompStart::LineOrArc`: rs274).

use crate::alarms;
use crate::dialect::{CompOp, ModeOp, MotionOp};
use crate::dialect::{GOp, Group, OffsetDefault, bit};
use crate::interpreter::Machining;
use crate::motion::comp::Mode;
use crate::state::{CompSide, Motion};
use crate::words::Words;
use vcnc_syntax::Diagnostic;

impl<'a> Machining<'_, 'a> {
    /// Step 6 for G40/G41/G42 and D.
    pub(crate) fn comp_codes(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let code = w.group(Group::CutterComp);
        let arc = w.group(Group::Motion).filter(|m| {
            matches!(
                m.def.op,
                GOp::Motion(MotionOp::ArcCw) | GOp::Motion(MotionOp::ArcCcw)
            )
        });
        if let (Some(c), Some(m)) = (code, arc) {
            // G41/G42 on an arc is an entry arc where the dialect has them;
            // G40 on an arc is never run.
            let entry = self.cfg.dialect.comp_start == crate::dialect::CompStart::LineOrArc
                && c.def.op != GOp::Comp(CompOp::Cancel);
            if !entry {
                return Err(alarms::comp_arc_startup(m.span));
            }
        }
        if let Some(c) = code {
            self.check_comp_when_on(c.def.op, c.span)?;
        }
        if let Some(c) = code
            && matches!(
                c.def.op,
                GOp::Comp(CompOp::LeftDiameter | CompOp::RightDiameter)
            )
        {
            return self.dynamic_comp(w, c.def.op, c.span);
        }
        let d_number = match w.get(b'D').filter(|_| self.reads_d(w)) {
            Some(d) => Some(self.cfg.offset_word(&d, self.state.tool_active)?),
            None => match code {
                Some(c)
                    if c.def.op != GOp::Comp(CompOp::Cancel)
                        && self.cfg.dialect.offset_default == OffsetDefault::ToolInSpindle =>
                {
                    Some(self.cfg.tool_in_spindle(self.state.tool_active, c.span)?)
                }
                _ => None,
            },
        };
        if let Some(n) = d_number {
            let t = self.tables.tool(n);
            self.state.d_number = n;
            if self.cfg.dialect.diameter.lathe {
                // A lathe's tool number (LinuxCNC lathe mode): its nose
                // radius and orientation (LinuxCNC's numbering).
                self.state.comp_d_mm = t.nose_radius_mm + t.nose_radius_wear_mm;
                self.state.lathe.tip = crate::motion::comp::nose::linuxcnc_tip(t.tip);
            } else {
                self.state.comp_d_mm = t.d_mm + t.d_wear_mm;
            }
        }
        let Some(code) = code else { return Ok(()) };
        let side = match code.def.op {
            GOp::Comp(CompOp::Left | CompOp::LeftDiameter) => CompSide::Left,
            GOp::Comp(CompOp::Right | CompOp::RightDiameter) => CompSide::Right,
            _ => CompSide::Off,
        };
        self.set_comp_side(side);
        if side != CompSide::Off && self.state.comp_d_mm == 0.0 {
            self.warn_zero_radius(code.span, side);
        }
        Ok(())
    }

    /// E320 when the dialect refuses to turn compensation on while it is
    /// on (rs274: "Cannot turn cutter radius comp on when on").
    fn check_comp_when_on(&self, op: GOp, at: vcnc_syntax::Span) -> Result<(), Diagnostic> {
        if self.cfg.dialect.comp_when_on != crate::dialect::CompWhenOn::Alarm
            || self.state.modal.comp == CompSide::Off
        {
            return Ok(());
        }
        let g = match op {
            GOp::Comp(CompOp::Left) => "G41",
            GOp::Comp(CompOp::Right) => "G42",
            GOp::Comp(CompOp::LeftDiameter) => "G41.1",
            GOp::Comp(CompOp::RightDiameter) => "G42.1",
            _ => return Ok(()),
        };
        Err(alarms::comp_on_when_on(at, g))
    }

    /// LinuxCNC's G41.1/G42.1 D L: the radius is half the block's D (a
    /// length in program units; negative: the other side, as G41's), no
    /// offset register; L (0–9, LinuxCNC's numbering) is a lathe tool's
    /// orientation, only in the XZ plane, as rs274 refuses it elsewhere
    /// ("G41.1 with L word, but plane is not G18").
    fn dynamic_comp(
        &mut self,
        w: &Words<'_>,
        op: GOp,
        at: vcnc_syntax::Span,
    ) -> Result<(), Diagnostic> {
        let g = if op == GOp::Comp(CompOp::LeftDiameter) {
            "G41.1"
        } else {
            "G42.1"
        };
        let d = w
            .get(b'D')
            .ok_or_else(|| alarms::needs_word(at, g, "D (the tool's diameter)"))?;
        if let Some(l) = w.get(b'L') {
            if self.state.modal.plane != vcnc_core::events::Plane::Zx {
                return Err(alarms::word_not_allowed(l.span, b'L'));
            }
            let tip = crate::words::whole(
                &l,
                b'L',
                0.0,
                9.0,
                "L is a lathe tool's orientation, 0 to 9",
            )?;
            // 0..=9: the cast is exact.
            #[allow(clippy::cast_possible_truncation)]
            let tip = tip as u8;
            self.state.lathe.tip = crate::motion::comp::nose::linuxcnc_tip(tip);
        }
        self.state.d_number = 0;
        self.state.comp_d_mm = self.units().length_mm(&d) / 2.0;
        let side = if op == GOp::Comp(CompOp::LeftDiameter) {
            CompSide::Left
        } else {
            CompSide::Right
        };
        self.set_comp_side(side);
        Ok(())
    }

    /// W108, once per register: G41/G42 with a radius of 0 (an offset
    /// register nobody filled) leaves the path where it is.
    #[cold]
    fn warn_zero_radius(&mut self, span: vcnc_syntax::Span, side: CompSide) {
        let n = self.state.d_number;
        if n == 0 || !self.first_zero_offset(0, n) {
            return;
        }
        let g = if side == CompSide::Left { "G41" } else { "G42" };
        let what = if self.cfg.dialect.diameter.lathe {
            format!("{g} and a tool nose radius of 0 (offset {n})")
        } else {
            format!("{g} D{n} = 0")
        };
        self.warn(alarms::zero_offset(span, &what));
    }

    /// Whether register `n` of `kind` (0: radius, 1: length) has not been
    /// warned about yet (W108), marking it; registers from 63 up share one
    /// mark.
    pub(crate) fn first_zero_offset(&mut self, kind: usize, n: u32) -> bool {
        let bit = 1u64 << n.min(63);
        let Some(marks) = self.stage.zero_offsets_warned.get_mut(kind) else {
            return false;
        };
        let first = *marks & bit == 0;
        *marks |= bit;
        first
    }

    /// G40/G41/G42: the mode the next move in the plane starts, keeps or
    /// cancels (a block's code, or a profile block's run by G70).
    pub(crate) fn set_comp_side(&mut self, side: CompSide) {
        self.state.modal.comp = side;
        match (side, self.stage.comp.mode) {
            (CompSide::Off, Mode::Off) => {}
            (CompSide::Off, Mode::Starting) => self.stage.comp.mode = Mode::Off,
            (CompSide::Off, _) => self.stage.comp.mode = Mode::Cancelling,
            (_, Mode::Off | Mode::Cancelling) => {
                if self.stage.comp.mode == Mode::Off {
                    self.stage.comp.plane = self.state.modal.plane;
                }
                self.stage.comp.mode = if self.stage.comp.holding() {
                    Mode::On
                } else {
                    Mode::Starting
                };
            }
            _ => {}
        }
    }

    /// Whether this block's D is a cutter radius (G41/G42 in it, or
    /// compensation on), not an arc's diameter (a dialect whose arcs read
    /// D: the lathe's).
    fn reads_d(&self, w: &Words<'_>) -> bool {
        w.group(Group::CutterComp).is_some() || self.comp_on_reads_d() || self.d_alone_is_radius()
    }

    /// Whether compensation is on and a D word changes its radius: not on
    /// an arc that reads D as its diameter, nor in a dialect whose G41
    /// reads no D (fanuc-lathe: the radius is the T offset's nose).
    pub(crate) fn comp_on_reads_d(&self) -> bool {
        self.state.modal.comp != CompSide::Off
            && !self.arc_reads_d()
            && self.cfg.dialect.d_is_radius_offset()
    }

    /// Whether the modal motion is an arc that reads D as its diameter
    /// (the lathe's).
    fn arc_reads_d(&self) -> bool {
        self.cfg.dialect.arc_letters & bit(b'D') != 0
            && matches!(self.state.modal.motion, Motion::ArcCw | Motion::ArcCcw)
    }

    /// Whether a D outside G41/G42 is a cutter-radius offset number to
    /// keep for the next G41/G42, not an arc's diameter.
    pub(crate) fn d_alone_is_radius(&self) -> bool {
        self.cfg.dialect.d_is_radius_offset() && !self.arc_reads_d()
    }

    /// E320 when compensation is on and the block changes what it cannot
    /// change under it: the plane, rotation, scaling.
    pub(crate) fn check_comp_changes(&self, w: &Words<'_>) -> Result<(), Diagnostic> {
        if !self.stage.comp.engaged() || self.stage.comp.mode == Mode::Cancelling {
            return Ok(());
        }
        for (group, what) in [
            (Group::Plane, "the plane (G17/G18/G19)"),
            (Group::Rotation, "coordinate rotation (G68/G69)"),
            (Group::Scaling, "scaling (G50/G51)"),
        ] {
            if let Some(g) = w.group(group) {
                let same_plane = group == Group::Plane
                    && matches!(
                        (g.def.op, self.stage.comp.plane),
                        (GOp::Mode(ModeOp::PlaneXy), vcnc_core::events::Plane::Xy)
                            | (GOp::Mode(ModeOp::PlaneZx), vcnc_core::events::Plane::Zx)
                            | (GOp::Mode(ModeOp::PlaneYz), vcnc_core::events::Plane::Yz)
                    );
                if !same_plane {
                    return Err(alarms::not_while_compensating(g.span, what));
                }
            }
        }
        Ok(())
    }
}
