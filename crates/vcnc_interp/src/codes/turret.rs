//! T words as a Fanuc lathe reads them, and G96 on the work diameter.
//!
//! ```text
//!   T 01 01      station 01 (the turret indexes: a `tool_change` event
//!     │  └ offset register 01: X/Z geometry + wear move the tool tip,
//!     │                        nose radius + tip direction for G41/G42
//!     └ T0100: same station, offset cancelled; T0002: offset 2 only
//! ```
//!
//! The offset is a tool offset of the frame (`machine = program + origin +
//! tool offset`, on X and Z), applied like grbl's G43.1: nothing moves in
//! the T block, the programmed position reads the new offset and the next
//! move goes where it puts the program point (Fanuc applies a T offset with
//! the next move). Registers come from the machine file's `[tools.N]`
//! (`x_mm`, `z_mm`, their wear, `nose_radius_mm`, `tip`).
//!
//! Under G96 a lathe keeps the surface speed on the work diameter under the
//! tool, twice the program X: rpm = 1000·S / (π·D), clamped by G50 S and by
//! the spindle's top speed (`max_spindle_rpm`). The speed follows every
//! move: a `spindle` event precedes a move whose end point asks for another
//! speed (a Fanuc computes a rapid's speed for its end point; vcnc does so
//! for every move, so the event stream has one speed per move).

use crate::alarms;
use crate::dialect::SurfaceSpeedOn;
use crate::interpreter::Machining;
use crate::motion::{Move, Target};
use crate::words::Words;
use crate::words::whole;
use vcnc_core::events::{Event, Pos, SpindleDir};
use vcnc_syntax::{Diagnostic, Span};

impl<'a> Machining<'_, 'a> {
    /// Step 2b under `ToolWords::TurretOffset`: index the turret, apply
    /// the offset.
    pub(crate) fn turret_word(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let Some(t) = w.get(b'T') else { return Ok(()) };
        let n = whole(
            &t,
            b'T',
            0.0,
            9999.0,
            "T is the turret station and offset register, two digits each (T0101)",
        )?;
        let (station, register) = (n / 100, n % 100);
        if register > self.cfg.machine.params.offset_registers {
            return Err(alarms::bad_tool_offset_number(
                t.span,
                b'T',
                t.value,
                self.cfg.machine.params.offset_registers,
            ));
        }
        if station != 0 && self.state.tool_active != Some(station) {
            self.state.tool_selected = Some(station);
            self.state.tool_active = Some(station);
            self.emit(|loc| Event::ToolChange { loc, tool: station });
        }
        let tool = self.tables.tool(register);
        let mut offset = Pos::default();
        if let Some(x) = self.cfg.machine.axis_of(b'X') {
            offset.set(x, tool.x_mm + tool.x_wear_mm);
        }
        if let Some(z) = self.cfg.machine.axis_of(b'Z') {
            offset.set(z, tool.z_mm + tool.z_wear_mm);
        }
        self.state.lathe.offset = register;
        self.state.lathe.tip = tool.tip;
        self.state.d_number = register;
        self.state.comp_d_mm = tool.nose_radius_mm + tool.nose_radius_wear_mm;
        if offset != self.state.frame.tool {
            let s = &mut self.state;
            s.frame.tool = offset;
            s.frame_dirty = true;
            s.prog = s.frame.program_of(s.nominal);
            s.detached = false;
        }
        Ok(())
    }

    /// G96 on a lathe: the spindle speed for the surface speed
    /// `surface_m_per_min` with the tool at program point `at`.
    pub(crate) fn work_css_rpm(
        &self,
        at: Pos,
        surface_m_per_min: f64,
        span: Span,
    ) -> Result<f64, Diagnostic> {
        let x = self.cfg.machine.axis_of(b'X').map_or(0.0, |i| at.get(i));
        let diameter_mm = 2.0 * x.abs();
        let mut rpm = if diameter_mm > vcnc_core::geometry::ZERO_MM {
            1000.0 * surface_m_per_min / (std::f64::consts::PI * diameter_mm)
        } else {
            f64::INFINITY
        };
        if let Some(max) = self.state.max_rpm {
            rpm = rpm.min(max);
        }
        let top = self.cfg.machine.params.max_spindle_rpm;
        if top > 0.0 {
            rpm = rpm.min(top);
        }
        if !rpm.is_finite() {
            return Err(alarms::css_at_center_unclamped(span));
        }
        Ok(rpm)
    }

    /// Before a move under G96 on a lathe: the spindle speed its end point
    /// asks for, as a `spindle` event when it changes.
    pub(crate) fn css_follow(&mut self, mv: &Move) -> Result<(), Diagnostic> {
        let turning = matches!(self.state.spindle, SpindleDir::Cw | SpindleDir::Ccw);
        if !turning || self.cfg.dialect.surface_speed != SurfaceSpeedOn::WorkDiameter {
            return Ok(());
        }
        let to = match mv.to {
            Target::Program(p) => p,
            Target::Relative(d) => self.state.prog.plus(d),
            Target::Machine(m) => self.state.frame.program_of(m),
        };
        let surface = self.surface_m_per_min();
        let rpm = self.work_css_rpm(to, surface, mv.cmd)?;
        if (rpm - self.state.rpm).abs() < 1e-9 {
            return Ok(());
        }
        self.state.rpm = rpm;
        let dir = self.state.spindle;
        self.emit(|loc| Event::Spindle {
            loc,
            dir,
            rpm,
            surface_m_per_min: Some(surface),
        });
        Ok(())
    }

    /// S under G96 in m/min (ft/min in inch mode).
    pub(crate) fn surface_m_per_min(&self) -> f64 {
        if self.state.modal.inch {
            self.state.s_value * 0.3048
        } else {
            self.state.s_value
        }
    }
}
