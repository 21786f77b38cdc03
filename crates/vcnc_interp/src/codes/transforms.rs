//! Programmable transforms that take the block's axis words as their
//! centre: G51 scaling (Syntec 1.2.20), G51.1/G50.1 mirror (1.2.21) and G68
//! rotation (1.2.28). The cancels without axis words (G50, G69) are in
//! `tool_length.rs` with the other frame codes; the maths is in
//! `state/frame.rs`.
//!
//! ```text
//!   G51 X Y Z P      uniform factor P about (X, Y, Z)
//!   G51 X Y Z I J K  a factor per axis (a negative one mirrors)
//!   G51.1 X60.       mirror about x = 60;   G50.1 X0 cancels X's mirror
//!   G68 X Y R        rotate by R degrees (counter-clockwise) in the plane
//! ```
//!
//! Centre words are absolute program coordinates (also under G91 and G16);
//! an omitted centre coordinate is the programmed point's. Factors and
//! angles written without a decimal point are in 0.001 units (`P500` is
//! 0.5, `R90000` is 90°), as Fanuc reads them by default.
//!
//! Each code is a method of the [`Transforms`] in force that returns the
//! next ones, read from the block with the configuration and the state it
//! needs; the interpreter puts them in force (`use_transforms`), the one
//! step that writes the tables and the frame.

use crate::alarms;
use crate::block::convert::Units;
use crate::config::Config;
use crate::interpreter::Machining;
use crate::state::State;
use crate::state::frame::{Transform, Transforms, plane_rows};
use crate::words::Words;
use vcnc_syntax::{Diagnostic, Span, Word};

/// Largest scale factor (Fanuc 0i: 999.999 with 0.001 units).
const MAX_SCALE: f64 = 999.999;

impl Transforms {
    /// The X, Y, Z centre words of a transform, program coordinates; an
    /// omitted one is the programmed point's coordinate.
    fn centre(cfg: &Config<'_>, s: &State, w: &Words<'_>) -> [f64; 3] {
        let mut c = [0.0; 3];
        for (k, letter) in [b'X', b'Y', b'Z'].iter().enumerate() {
            let Some(i) = cfg.machine.axis_of(*letter) else {
                continue;
            };
            c[k] = match w.get(*letter) {
                Some(word) => s.units(cfg).axis_value(&cfg.axis_words, i, &word),
                None => s.prog.get(i),
            };
        }
        c
    }

    /// A factor word: as written with a point, in 0.001 units without.
    fn factor(units: Units, word: &Word) -> Result<f64, Diagnostic> {
        let k = units.angle_deg(word);
        if k == 0.0 || k.abs() > MAX_SCALE {
            return Err(alarms::bad_scale_factor(word.span, word.addr.0, k));
        }
        Ok(k)
    }

    /// G51: scaling about a centre.
    pub fn scaled(
        &self,
        (cfg, s): (&Config<'_>, &State),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<Transforms, Diagnostic> {
        let units = s.units(cfg);
        let per_axis = [b'I', b'J', b'K'].map(|l| w.get(l));
        let factor = match (w.get(b'P'), per_axis.iter().flatten().next()) {
            (Some(_), Some(ijk)) => return Err(alarms::scale_p_and_ijk(ijk.span)),
            (Some(p), None) => [Transforms::factor(units, &p)?; 3],
            (None, Some(_)) => {
                let mut f = [1.0; 3];
                for (k, word) in per_axis.iter().enumerate() {
                    if let Some(word) = word {
                        f[k] = Transforms::factor(units, word)?;
                    }
                }
                f
            }
            (None, None) => {
                return Err(alarms::needs_word(
                    cmd,
                    "G51",
                    "P (one factor for every axis) or I/J/K (a factor per axis)",
                ));
            }
        };
        let t = Transform::Scale {
            factor,
            centre: Transforms::centre(cfg, s, w),
        };
        Ok(self.with(t))
    }

    /// G51.1 (on) and G50.1 (off, for the named axes or all).
    pub fn mirrored(
        &self,
        (cfg, s): (&Config<'_>, &State),
        w: &Words<'_>,
        (cmd, on): (Span, bool),
    ) -> Result<Transforms, Diagnostic> {
        let centre = Transforms::centre(cfg, s, w);
        let named = [b'X', b'Y', b'Z'].map(|l| w.get(l).is_some());
        let mut about = match self.like(&Transform::Mirror { about: [None; 3] }) {
            Some(Transform::Mirror { about }) => about,
            _ => [None; 3],
        };
        if on {
            if !named.contains(&true) {
                return Err(alarms::needs_axes(cmd, "G51.1"));
            }
            for k in 0..3 {
                if named[k] {
                    about[k] = Some(centre[k]);
                }
            }
        } else {
            let all = !named.contains(&true);
            for k in 0..3 {
                if all || named[k] {
                    about[k] = None;
                }
            }
        }
        let t = Transform::Mirror { about };
        let next = if about.iter().all(Option::is_none) {
            self.without(&t)
        } else {
            self.with(t)
        };
        Ok(next)
    }

    /// G68: rotation in the active plane.
    pub fn rotated(
        &self,
        (cfg, s): (&Config<'_>, &State),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<Transforms, Diagnostic> {
        let plane = s.modal.plane;
        let normal = plane.letters()[2];
        if let Some(word) = w.get(normal) {
            return Err(alarms::word_not_allowed(word.span, normal));
        }
        let (i, j) = plane_rows(plane);
        let letters = [b'X', b'Y', b'Z'];
        if cfg.machine.axis_of(letters[i]).is_none() || cfg.machine.axis_of(letters[j]).is_none() {
            return Err(alarms::arc_without_center(cmd, plane.as_str()));
        }
        let r = w
            .get(b'R')
            .ok_or_else(|| alarms::needs_word(cmd, "G68", "R (the angle of rotation)"))?;
        let t = Transform::Rotate {
            plane,
            degrees: s.units(cfg).angle_deg(&r),
            centre: Transforms::centre(cfg, s, w),
        };
        Ok(self.with(t))
    }
}

impl<'a> Machining<'_, 'a> {
    /// Puts `next` in force. The programmed point stays what it was and the
    /// machine does not move: the next absolute move goes where the new
    /// frame puts its point (Fanuc; Syntec 1.2.20's figure).
    pub(crate) fn use_transforms(&mut self, next: Transforms, cmd: Span) -> Result<(), Diagnostic> {
        let a = next
            .compose()
            .ok_or_else(|| alarms::singular_transform(cmd))?;
        if next != self.tables.transforms {
            self.tables.set_transforms(next);
            self.state.frame.set_affine(a);
            self.state.frame_dirty = true;
            self.state.detached = true;
        }
        Ok(())
    }
}
