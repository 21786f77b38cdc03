//! System variables: what a macro reads of the controller's state and the
//! few it may write.
//!
//! ```text
//!   Fanuc 0i (fanuc, haas)                      R/W   unit
//!   #2001–#2200, #10001–#10999  H wear n        R/W   input unit (inch under G20)
//!   #2201–#2400, #11001–#11999  H geometry n    R/W
//!   #12001–#12999, #13001–…     D wear, D geometry    (tool compensation memory C)
//!   #3000  alarm with the block's comment        W
//!   #3001 ms, #3002 h  clock (does not run)      R/W
//!   #3003, #3004  single block / feed hold       R/W   kept, no effect
//!   #3006  stop with the block's comment         W
//!   #3901, #3902  parts machined / required      R/W
//!   #4001–#4022, #4201–#4222  modal G code of group n   R
//!   #4107 D #4109 F #4111 H #4115 O #4119 S #4120 T (+200 the same)  R
//!   #5001+a  end point of the last block, program coordinates   R
//!   #5021+a  machine position; #5041+a work position (tool offset in); #5061+a skip
//!   #5081+a  tool length offset                                   R
//!   #5221+20k+a  work offset G54+k (k 0–5)      R/W
//!
//!   Syntec: #1000 interpolation G code, #1003/#1004 G90/G91, #1015 G40–G42,
//!   #1016 G43/G44/G49 (R); #4001–#5500 user parameters (R, vacant: no
//!   parameter file)
//! ```
//!
//! `a` counts the machine's axes from 0 (X Y Z A B C on the built-in mill).
//! Every other number of the system range alarms E605 (not a variable, or
//! one that needs the real machine: I/O signals, the date), and a write to a
//! read-only one alarms E606.

use super::Evaluator;
use crate::alarms;
use crate::dialect::ModeOp;
use crate::dialect::{GOp, MachineVars, VarTable};
use crate::state::{CompSide, Motion, ToolLength};
use vcnc_core::events::Pos;
use vcnc_syntax::macros::Value;
use vcnc_syntax::{Diagnostic, Span};

/// A tool offset variable: (offset number, which field).
#[derive(Clone, Copy)]
enum ToolField {
    HWear,
    HGeom,
    DWear,
    DGeom,
}

fn tool_var(n: u32) -> Option<(u32, ToolField)> {
    match n {
        2001..=2200 => Some((n - 2000, ToolField::HWear)),
        2201..=2400 => Some((n - 2200, ToolField::HGeom)),
        10_001..=10_999 => Some((n - 10_000, ToolField::HWear)),
        11_001..=11_999 => Some((n - 11_000, ToolField::HGeom)),
        12_001..=12_999 => Some((n - 12_000, ToolField::DWear)),
        13_001..=13_999 => Some((n - 13_000, ToolField::DGeom)),
        _ => None,
    }
}

impl<'a> Evaluator<'_, 'a> {
    /// mm (or degrees) → the program's input unit for axis `i`.
    fn to_input(&self, i: usize, mm: f64) -> f64 {
        let rotary = matches!(
            self.cfg.machine.axes.get(i).map(|a| a.letter),
            Some(b'A' | b'B' | b'C')
        );
        if rotary {
            return mm;
        }
        let diameter = self.state.modal.diameter
            && self.cfg.dialect.diameter.axis == self.cfg.machine.axes.get(i).map(|a| a.letter);
        let v = mm / self.state.unit_mm();
        if diameter { 2.0 * v } else { v }
    }

    fn length_input(&self, mm: f64) -> f64 {
        mm / self.state.unit_mm()
    }

    /// Reads system variable `#n`.
    pub(crate) fn system_read(&mut self, n: u32, span: Span) -> Result<Value, Diagnostic> {
        let v = match self.macros.rules.variables {
            VarTable::Fanuc => self.fanuc_read(n, span)?,
            VarTable::Syntec => self.syntec_read(n, span)?,
        };
        Ok(v)
    }

    fn fanuc_read(&mut self, n: u32, span: Span) -> Result<Value, Diagnostic> {
        let d = |x: f64| Ok(Value::Double(x));
        if let Some((k, field)) = tool_var(n) {
            let t = self.tables.tool(self.offset_register(k, n, span)?);
            let mm = match field {
                ToolField::HWear => t.h_wear_mm,
                ToolField::HGeom => t.h_mm,
                ToolField::DWear => t.d_wear_mm,
                ToolField::DGeom => t.d_mm,
            };
            return d(self.length_input(mm));
        }
        match n {
            3001 | 3002 => d(self.macros.vars.clock[(n - 3001) as usize]),
            3003 | 3004 => d(self.macros.vars.control[(n - 3003) as usize]),
            3901 | 3902 => d(self.macros.vars.parts[(n - 3901) as usize]),
            4001..=4022 => Ok(self.modal_code(n - 4000)),
            4201..=4222 => Ok(self.modal_code(n - 4200)),
            4102..=4130 => Ok(self.modal_word(n - 4100)),
            4302..=4330 => Ok(self.modal_word(n - 4300)),
            5001..=5006 | 5021..=5026 | 5041..=5046 | 5061..=5066 | 5081..=5086 => {
                self.position_var(n, span)
            }
            5221..=5340 => {
                let (k, a) = self.work_var(n, span)?;
                let w = self.tables.work.get(k).copied().unwrap_or_default();
                d(self.to_input(a, w.get(a)))
            }
            5401..=6000 if self.macros.rules.machine_vars == MachineVars::HaasToolLife => {
                d(self.macros.vars.tool_life.get(&n).copied().unwrap_or(0.0))
            }
            3000 | 3006 => Err(alarms::no_such_variable_why(
                span,
                n,
                "it can only be written",
            )),
            _ => Err(alarms::system_variable_missing(span, n)),
        }
    }

    fn syntec_read(&mut self, n: u32, span: Span) -> Result<Value, Diagnostic> {
        let m = &self.state.modal;
        let code = |c: i64| Ok(Value::Long(c));
        match n {
            1000 => Ok(match m.motion {
                Motion::Rapid => Value::Long(0),
                Motion::Linear => Value::Long(1),
                Motion::ArcCw => Value::Long(2),
                Motion::ArcCcw => Value::Long(3),
                Motion::Thread | Motion::ThreadInch => Value::Long(33),
                // LinuxCNC's G33.1 (not a Syntec dialect, for completeness).
                Motion::RigidTap => Value::Double(33.1),
                Motion::ThreePointArc => Value::Long(5),
                // G06.2 has no whole code.
                Motion::Nurbs => Value::Double(6.2),
                // Fanuc lathe system A (not a Syntec dialect, for completeness).
                Motion::TurnCycle => Value::Long(90),
                Motion::ThreadingCycle => Value::Long(92),
                Motion::FaceCycle => Value::Long(94),
            }),
            1003 | 1004 => code(if m.incremental { 91 } else { 90 }),
            1015 => code(match m.comp {
                CompSide::Off => 40,
                CompSide::Left => 41,
                CompSide::Right => 42,
            }),
            1016 => code(match m.tool_length {
                ToolLength::Off => 49,
                ToolLength::Plus => 43,
                ToolLength::Minus => 44,
            }),
            // User parameters: no parameter file off-machine.
            4001..=5500 => Ok(Value::Null),
            _ => Err(alarms::system_variable_missing(span, n)),
        }
    }

    /// An H/D offset number of a tool offset variable, within the machine's
    /// registers.
    fn offset_register(&self, k: u32, n: u32, span: Span) -> Result<u32, Diagnostic> {
        if k == 0 || k > self.cfg.machine.params.offset_registers {
            return Err(alarms::no_such_variable_why(
                span,
                n,
                &format!(
                    "offset {k} is beyond the machine's {} registers",
                    self.cfg.machine.params.offset_registers
                ),
            ));
        }
        Ok(k)
    }

    /// `#5221+20k+a`: (work system k, axis a).
    fn work_var(&self, n: u32, span: Span) -> Result<(usize, usize), Diagnostic> {
        let base = n - 5221;
        let (k, a) = ((base / 20) as usize, (base % 20) as usize);
        if k > 5 || a >= self.cfg.machine.axes.len() {
            return Err(alarms::system_variable_missing(span, n));
        }
        Ok((k, a))
    }

    fn position_var(&self, n: u32, span: Span) -> Result<Value, Diagnostic> {
        let (base, a) = ((n - 5001) / 20, ((n - 5001) % 20) as usize);
        if a >= self.cfg.machine.axes.len() {
            return Err(alarms::system_variable_missing(span, n));
        }
        let s = &self.state;
        let mm = match base {
            0 => s.prog.get(a),
            1 => s.pos.get(a),
            2 => s.frame.work_of(s.pos).get(a),
            3 => s.frame.work_of(s.skip_pos.unwrap_or(s.pos)).get(a),
            _ => s.frame.tool.get(a),
        };
        Ok(Value::Double(self.to_input(a, mm)))
    }

    /// `#4001 + g - 1`: the G code in force in modal group `g` (Fanuc
    /// numbering); vacant for groups vcnc does not keep.
    fn modal_code(&self, g: u32) -> Value {
        let m = &self.state.modal;
        let c: f64 = match g {
            1 => match m.motion {
                Motion::Rapid => 0.0,
                Motion::Linear => 1.0,
                Motion::ArcCw => 2.0,
                Motion::ArcCcw => 3.0,
                Motion::Thread => 33.0,
                Motion::RigidTap => 33.1,
                Motion::ThreadInch => 32.0,
                Motion::ThreePointArc => 5.0,
                Motion::Nurbs => 6.2,
                // Fanuc lathe system A: the modal turning cycles.
                Motion::TurnCycle => 90.0,
                Motion::ThreadingCycle => 92.0,
                Motion::FaceCycle => 94.0,
            },
            2 => match m.plane {
                vcnc_core::events::Plane::Xy => 17.0,
                vcnc_core::events::Plane::Zx => 18.0,
                vcnc_core::events::Plane::Yz => 19.0,
            },
            3 => {
                if m.incremental {
                    91.0
                } else {
                    90.0
                }
            }
            5 => {
                if m.inverse_time {
                    93.0
                } else if m.per_rev {
                    95.0
                } else {
                    94.0
                }
            }
            6 => {
                // The dialect's own codes: G20/G21, or Syntec's G70/G71.
                let fanuc = self
                    .cfg
                    .dialect
                    .g(20.0)
                    .is_some_and(|d| d.op == GOp::Mode(ModeOp::Inch));
                match (fanuc, m.inch) {
                    (true, true) => 20.0,
                    (true, false) => 21.0,
                    (false, true) => 70.0,
                    (false, false) => 71.0,
                }
            }
            7 => match m.comp {
                CompSide::Off => 40.0,
                CompSide::Left => 41.0,
                CompSide::Right => 42.0,
            },
            8 => match m.tool_length {
                ToolLength::Off => 49.0,
                ToolLength::Plus => 43.0,
                ToolLength::Minus => 44.0,
            },
            9 => self.state.cycle.code.map_or(80.0, |c| {
                c.as_str()
                    .get(1..)
                    .and_then(|d| d.parse().ok())
                    .unwrap_or(80.0)
            }),
            10 => {
                if m.return_r {
                    99.0
                } else {
                    98.0
                }
            }
            12 => {
                if m.macro_call {
                    66.0
                } else {
                    67.0
                }
            }
            13 => {
                if m.css {
                    96.0
                } else {
                    97.0
                }
            }
            14 => match m.wcs {
                0..=5 => 54.0 + m.wcs as f64,
                // G59.1–G59.9.
                k => 59.0 + (k as f64 - 5.0) / 10.0,
            },
            15 => match m.path {
                vcnc_core::events::PathMode::ExactStop => 61.0,
                vcnc_core::events::PathMode::Surface => 62.0,
                vcnc_core::events::PathMode::Tapping => 63.0,
                vcnc_core::events::PathMode::Cutting => 64.0,
            },
            17 => {
                if m.polar {
                    16.0
                } else {
                    15.0
                }
            }
            _ => return Value::Null,
        };
        Value::Double(c)
    }

    /// `#4100 + w`: the last D, F, H, O, S, T.
    fn modal_word(&self, w: u32) -> Value {
        let s = &self.state;
        match w {
            7 => Value::Double(f64::from(s.d_number)),
            9 => Value::Double(s.feed),
            11 => Value::Double(f64::from(s.h_number)),
            15 => {
                let number = self.flow.frames.last().and_then(|f| f.number);
                number.map_or(Value::Null, |n| Value::Double(f64::from(n)))
            }
            19 => Value::Double(s.s_value),
            20 => s
                .tool_selected
                .map_or(Value::Null, |t| Value::Double(f64::from(t))),
            _ => Value::Null,
        }
    }

    /// Writes system variable `#n`.
    pub(crate) fn system_write(
        &mut self,
        n: u32,
        v: Value,
        span: Span,
        comment: Option<&str>,
    ) -> Result<(), Diagnostic> {
        if self.macros.rules.variables == VarTable::Syntec {
            return match n {
                1000 | 1003 | 1004 | 1015 | 1016 | 4001..=5500 => {
                    Err(alarms::read_only_variable(span, '#', n))
                }
                _ => Err(alarms::system_variable_missing(span, n)),
            };
        }
        let x = v.number();
        if let Some((k, field)) = tool_var(n) {
            let k = self.offset_register(k, n, span)?;
            let mm = x.ok_or_else(|| alarms::vacant_value(span, "a tool offset"))?
                * self.state.unit_mm();
            let mut t = self.tables.tool(k);
            match field {
                ToolField::HWear => t.h_wear_mm = mm,
                ToolField::HGeom => t.h_mm = mm,
                ToolField::DWear => t.d_wear_mm = mm,
                ToolField::DGeom => t.d_mm = mm,
            }
            self.tables.set_tool(k, t);
            return Ok(());
        }
        match n {
            3000 => {
                let id = x.unwrap_or(0.0);
                Err(alarms::program_alarm(span, id, comment.unwrap_or("")))
            }
            3001 | 3002 => {
                self.macros.vars.clock[(n - 3001) as usize] = x.unwrap_or(0.0);
                Ok(())
            }
            3003 | 3004 => {
                self.macros.vars.control[(n - 3003) as usize] = x.unwrap_or(0.0);
                Ok(())
            }
            3006 => {
                self.message(comment.unwrap_or("").to_string(), true);
                Ok(())
            }
            3901 | 3902 => {
                self.macros.vars.parts[(n - 3901) as usize] = x.unwrap_or(0.0);
                Ok(())
            }
            5221..=5340 => {
                let (k, a) = self.work_var(n, span)?;
                let value = x.ok_or_else(|| alarms::vacant_value(span, "a work offset"))?;
                let mut w: Pos = self.tables.work.get(k).copied().unwrap_or_default();
                let rotary = matches!(
                    self.cfg.machine.axes.get(a).map(|ax| ax.letter),
                    Some(b'A' | b'B' | b'C')
                );
                w.set(
                    a,
                    if rotary {
                        value
                    } else {
                        value * self.state.unit_mm()
                    },
                );
                self.tables.set_work(k, w);
                if self.state.modal.wcs == k {
                    self.state.refresh_origin(self.tables);
                }
                Ok(())
            }
            5401..=6000 if self.macros.rules.machine_vars == MachineVars::HaasToolLife => {
                self.macros.vars.tool_life.insert(n, x.unwrap_or(0.0));
                Ok(())
            }
            4001..=4330 | 5001..=5106 => Err(alarms::read_only_variable(span, '#', n)),
            _ => Err(alarms::system_variable_missing(span, n)),
        }
    }
}
