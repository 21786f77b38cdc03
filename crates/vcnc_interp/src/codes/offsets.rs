//! Offsets that move the program origin or change the tool data without
//! moving the machine: G10 (L2 work offsets, L10–L13 tool offsets), G92
//! (shift, or S spindle clamp) and G52 (local system).
//!
//! G92 and G52 values are absolute program coordinates whatever G90/G91
//! says (Fanuc 0i); G10 adds to the offset under G91 (Syntec 1.2.10). G92
//! cancels the local system of the axes it names (Fanuc 0i, "local
//! coordinate system"), so the preset position is what the axis then reads.
//! G10 L10/L11 write an H length (geometry, wear), L12/L13 a D radius; the
//! value in force for an active G43 is the one latched when H was given.
//!
//! The offsets are the journaled [`Tables`]' own: each code is a method of
//! `Tables` that reads the configuration and the state it needs and writes
//! only the tables; the interpreter then moves the state's origin to them
//! (`State::refresh_origin`) when the code says the origin moved.

use crate::alarms;
use crate::block::convert::Units;
use crate::config::Config;
use crate::dialect::SetOp;
use crate::dialect::{GOp, OffsetDefault};
use crate::state::{State, Tables};
use crate::words::Words;
use crate::words::whole;
use vcnc_syntax::{Diagnostic, Span};

impl Tables {
    /// G10: L2 work offsets, L10–L13 tool offsets; whether the origin
    /// moved (a work offset changed).
    pub(crate) fn set_data(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<bool, Diagnostic> {
        let rules = cfg.dialect.g10;
        let l = w.get(b'L').ok_or_else(|| {
            let forms = if rules.tool_table_l1 {
                "L (1 tool table, 2 work offset, 20 work offset here) and P"
            } else {
                "L (2 work offset, 10/11 H geometry/wear, 12/13 D geometry/wear) and P"
            };
            alarms::needs_word(cmd, "G10", forms)
        })?;
        let which = rules.forms();
        let lowest = if rules.tool_table_l1 { 1.0 } else { 2.0 };
        match whole(&l, b'L', lowest, 20.0, which)? {
            2 => self.set_work_offset(cfg, s, w, cmd, false).map(|()| true),
            20 if rules.from_position_l20 => {
                self.set_work_offset(cfg, s, w, cmd, true).map(|()| true)
            }
            n @ 10..=13 if rules.registers_l10_l13 => {
                self.set_tool_offset(cfg, s, w, cmd, n).map(|()| false)
            }
            1 if rules.tool_table_l1 => self.set_tool_entry(cfg, s, w, cmd).map(|()| false),
            _ => Err(alarms::value_out_of_range(l.span, b'L', l.value, which)),
        }
    }

    /// G10 L2 Pn: sets work offset n (1 = G54 … 6 = G59); with
    /// `from_position` (G10 L20, grbl/LinuxCNC) so that the current position
    /// reads as the axis words. Where G10 L20 exists, P0 is the active
    /// system.
    fn set_work_offset(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
        from_position: bool,
    ) -> Result<(), Diagnostic> {
        if let Some(r) = w.get(b'R') {
            return Err(alarms::word_not_allowed(r.span, b'R'));
        }
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::bad_offset_number(cmd, 0.0))?;
        let rules = cfg.dialect.g10;
        let lowest = if rules.from_position_l20 { 0.0 } else { 1.0 };
        let last = f64::from(rules.last_work_offset);
        if p.point || !(lowest..=last).contains(&p.value) {
            return Err(alarms::bad_offset_number(p.span, p.value));
        }
        let n = match whole(&p, b'P', lowest, last, "P is a work offset number")? {
            0 => s.modal.wcs,
            k => k as usize - 1,
        };
        let values = cfg.named_values(s.units(cfg), w);
        if values.is_empty() {
            return Err(alarms::needs_axes(
                cmd,
                if from_position { "G10 L20" } else { "G10 L2" },
            ));
        }
        let incremental = s.modal.incremental;
        let mut offset = self.work[n];
        for (i, v) in values {
            let value = if from_position {
                // The work offset: the origin at which the tool reads `v`,
                // G52 and G92 kept as they are.
                let m = s.nominal.get(i) - self.local.get(i) - self.shift.get(i);
                s.frame.origin_for(i, m, v)
            } else if incremental && rules.l2_adds_under_g91 {
                // Fanuc adds under G91; grbl and LinuxCNC set L2's values
                // as they are.
                offset.get(i) + v
            } else {
                v
            };
            offset.set(i, value);
        }
        self.set_work(n, offset);
        Ok(())
    }

    /// G10 L10–L13 P R: an H length or D radius, geometry or wear.
    fn set_tool_offset(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
        l: u32,
    ) -> Result<(), Diagnostic> {
        cfg.no_axis_words(w, &[])?;
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G10 L10-L13", "P (the offset number)"))?;
        let n = cfg.offset_number(&p)?;
        let r = w
            .get(b'R')
            .ok_or_else(|| alarms::needs_word(cmd, "G10 L10-L13", "R (the offset value)"))?;
        let value = s.units(cfg).length_mm(&r);
        let incremental = s.modal.incremental;
        let mut tool = self.tool(n);
        let slot = match l {
            10 => &mut tool.h_mm,
            11 => &mut tool.h_wear_mm,
            12 => &mut tool.d_mm,
            _ => &mut tool.d_wear_mm,
        };
        *slot = if incremental { *slot + value } else { value };
        self.set_tool(n, tool);
        Ok(())
    }

    /// LinuxCNC's G10 L1 P R Z: tool P's radius (R) and length (Z) in the
    /// tool table, as given under G91 too (they are table values, not
    /// positions). Other axis words (the lathe's X, the rotary offsets) are
    /// not run.
    fn set_tool_entry(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        cfg.no_axis_words(w, b"Z")?;
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G10 L1", "P (the tool number)"))?;
        // Tool 0 is "no tool" ("P value out of range with G10 L1").
        let n = match cfg.offset_number(&p)? {
            0 => {
                return Err(alarms::value_out_of_range(
                    p.span,
                    b'P',
                    p.value,
                    "G10 L1's P is a tool number from 1",
                ));
            }
            n => n,
        };
        let (r, z) = (w.get(b'R'), w.get(b'Z'));
        if r.is_none() && z.is_none() {
            return Err(alarms::needs_word(
                cmd,
                "G10 L1",
                "R (the tool radius) or Z (its length offset)",
            ));
        }
        let mut tool = self.tool(n);
        if let Some(r) = r {
            tool.d_mm = s.units(cfg).length_mm(&r);
        }
        if let Some(z) = z {
            tool.h_mm = s.units(cfg).length_mm(&z);
        }
        self.set_tool(n, tool);
        Ok(())
    }

    /// G92: preset the current position (axes), or clamp the spindle (S).
    pub(crate) fn preset(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let values = cfg.named_values(s.units(cfg), w);
        // The code's own name for the messages: G92, a Fanuc lathe's G50.
        let name = || {
            let g = cfg
                .dialect
                .g_for(GOp::Set(SetOp::PresetOrClamp))
                .unwrap_or(92.0);
            format!("G{g}")
        };
        if let Some(clamp) = w.get(b'S') {
            if !values.is_empty() {
                return Err(alarms::g92_axes_and_s(clamp.span, &name()));
            }
            // The clamp itself was set with the spindle words (execute.rs).
            return Ok(());
        }
        if values.is_empty() {
            return Err(alarms::needs_axes(cmd, &name()));
        }
        if s.frame.is_transformed() {
            return Err(alarms::g92_under_transform(cmd));
        }
        let nominal = s.nominal;
        let work = self.work.get(s.modal.wcs).copied().unwrap_or_default();
        let (mut local, mut shift) = (self.local, self.shift);
        for (i, v) in values {
            // The shift: the origin at which the tool reads `v`, the work
            // offset kept and G52 cancelled on the axis.
            local.set(i, 0.0);
            let m = nominal.get(i) - work.get(i);
            shift.set(i, s.frame.origin_for(i, m, v));
        }
        self.set_local(local);
        self.set_shift(shift);
        Ok(())
    }

    /// G52: the local system's origin in the work system; zero cancels.
    pub(crate) fn local_system(
        &mut self,
        cfg: &Config<'_>,
        s: &State,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let values = cfg.named_values(s.units(cfg), w);
        if values.is_empty() {
            return Err(alarms::needs_axes(cmd, "G52"));
        }
        let mut local = self.local;
        for (i, v) in values {
            local.set(i, v);
        }
        self.set_local(local);
        Ok(())
    }
}

// What the offset codes read of the configuration: their words' values
// and numbers.
impl Config<'_> {
    /// `(axis index, value in mm)` of each named axis.
    fn named_values(&self, units: Units, w: &Words<'_>) -> Vec<(usize, f64)> {
        self.machine
            .axes
            .iter()
            .enumerate()
            .filter_map(|(i, a)| {
                w.get(a.letter)
                    .map(|word| (i, units.axis_value(&self.axis_words, i, &word)))
            })
            .collect()
    }

    /// E203 on the first axis word of the block but those of `allowed`.
    fn no_axis_words(&self, w: &Words<'_>, allowed: &[u8]) -> Result<(), Diagnostic> {
        match self
            .machine
            .axes
            .iter()
            .filter(|a| !allowed.contains(&a.letter))
            .filter_map(|a| w.get(a.letter))
            .min_by_key(|word| word.span.start)
        {
            Some(word) => Err(alarms::word_not_allowed(word.span, word.addr.0)),
            None => Ok(()),
        }
    }

    /// An H, D or G10 P offset number within the machine's offset registers.
    pub fn offset_number(&self, w: &vcnc_syntax::Word) -> Result<u32, Diagnostic> {
        let max = self.machine.params.offset_registers;
        if w.point || w.value < 0.0 || w.value > f64::from(max) {
            return Err(alarms::bad_tool_offset_number(
                w.span, w.addr.0, w.value, max,
            ));
        }
        whole(w, w.addr.0, 0.0, f64::from(max), "an offset number")
    }

    /// An H or D word's offset number; where the dialect's default is the
    /// tool in the spindle, number 0 is that tool too (LinuxCNC: `H0`,
    /// `D0`); `tool` is the tool in the spindle.
    pub fn offset_word(&self, w: &vcnc_syntax::Word, tool: Option<u32>) -> Result<u32, Diagnostic> {
        match self.offset_number(w)? {
            0 if self.dialect.offset_default == OffsetDefault::ToolInSpindle => {
                self.tool_in_spindle(tool, w.span)
            }
            n => Ok(n),
        }
    }

    /// The tool in the spindle as an offset number (LinuxCNC's G43 without
    /// H, G41/G42 without D) of `tool`: 0, no offset, before the first tool
    /// change.
    pub fn tool_in_spindle(&self, tool: Option<u32>, at: Span) -> Result<u32, Diagnostic> {
        let t = tool.unwrap_or(0);
        let max = self.machine.params.offset_registers;
        if t > max {
            return Err(alarms::bad_tool_offset_number(at, b'T', f64::from(t), max));
        }
        Ok(t)
    }
}
