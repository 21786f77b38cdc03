//! G74 and G75 (peck drilling and grooving) and G76 (multiple threading),
//! the multiple repetitive cycles of the Fanuc lathe that need no profile.
//!
//! G74/G75 peck along one axis and step along the other:
//!
//! ```text
//!   G74: pecks along Z by Δk (Q), steps in X by Δi (P)    ┌─A  (e: retract
//!   G75: pecks along X by Δi (P), steps in Z by Δk (Q)    │     after each
//!   each position: feed Δk, back e, feed Δk+e, … to the   ▼     peck; Δd (R):
//!   end, relief Δd across, rapid back out, next position  ══    relief at the
//!   then back to A.                                             bottom)
//! ```
//!
//! G76 threads in passes of constant area (Fanuc 0i-TF):
//!
//! ```text
//!   depth of pass n: Dn = Δd·√n, at least D(n-1) + Δdmin, until k − d;
//!   then m finishing passes at k (the first cuts the allowance d, the others
//!   are spring passes). Each pass starts Dn·tan(a/2) along the thread from
//!   A (flank infeed along the tool's angle a), threads to the end with the
//!   chamfer-out r (tenths of the lead), goes out to A's X and back to A.
//!
//!   X ▲ A ●──────────────────────┐      k: thread height (radius)
//!     │    ╲ (rapid)             │      X: the thread's root at its end
//!     │     ●━━━━━━thread━━━━━━━┓│      i (R): taper, X at A's Z minus X at
//!     └───────────────────────────▶ Z      the end
//! ```

use crate::alarms;
use crate::codes::turning_cycles::How;
use crate::interpreter::Machining;
use crate::plane::{P2, Xz, ZERO_MM};
use crate::words::Words;
use crate::words::whole;
use vcnc_syntax::{Diagnostic, Span, Word};

/// Most pecks, positions or passes one block may make.
const MAX_STEPS: usize = 10_000;

/// The tool angles G76 accepts (Fanuc: 80, 60, 55, 30, 29, 0 degrees).
const ANGLES: [u32; 6] = [0, 29, 30, 55, 60, 80];

/// A word of the two-block form (`two`) or its one-block spelling (`one`,
/// the FS15 tape format Haas writes): either, not both (E203 on the
/// one-block word).
fn either(w: &Words<'_>, two: u8, one: u8) -> Result<Option<Word>, Diagnostic> {
    match (w.get(two), w.get(one)) {
        (Some(_), Some(o)) => Err(alarms::spelled_twice(o.span, two, one)),
        (t, o) => Ok(t.or(o)),
    }
}

/// G76's height and first depth as its alarms name them: (letter, name,
/// rule), in the two-block and the one-block form.
type Amount = (u8, &'static str, &'static str);
const HEIGHT_P: Amount = (
    b'P',
    "the thread height P",
    "the thread height is more than 0",
);
const HEIGHT_K: Amount = (
    b'K',
    "the thread height K",
    "the thread height is more than 0",
);
const FIRST_Q: Amount = (
    b'Q',
    "the first depth of cut Q",
    "the first depth of cut is more than 0",
);
const FIRST_D: Amount = (
    b'D',
    "the first depth of cut D",
    "the first depth of cut is more than 0",
);

/// The one-block G76's words beside K and D (FS15 tape format, Haas): R is
/// the two-block form's (E203: the taper is I), Haas's Q the thread's start
/// angle (a multi-start thread: the spindle's phase, not the tool's path),
/// P the infeed (only P1, one flank at constant area, is run), A the tool
/// angle for this cycle. Returns the angle (`modal` without A).
fn one_block_thread_angle(w: &Words<'_>, modal: f64) -> Result<f64, Diagnostic> {
    if let Some(r) = w.get(b'R') {
        return Err(alarms::other_cycle_form(
            r.span,
            b'R',
            "the two-block form: the one-block form writes the taper as I",
        ));
    }
    if let Some(q) = w.get(b'Q') {
        whole(
            &q,
            b'Q',
            0.0,
            360_000.0,
            "Q is the thread's start angle in 0.001°, 0-360000",
        )?;
    }
    if let Some(p) = w.get(b'P')
        && (p.point || p.value != 1.0)
    {
        return Err(alarms::cycle_parameters(
            p.span,
            "in the one-block G76 (with K and D) P picks the infeed, and only P1 \
             (one flank, constant area) is run",
        ));
    }
    match w.get(b'A') {
        Some(a) => Ok(f64::from(whole(
            &a,
            b'A',
            0.0,
            120.0,
            "A is the tool angle 0-120",
        )?)),
        None => Ok(modal),
    }
}

/// E203 on a one-block word (`letters`) in a first block, which has no
/// axis words and sets only the modal values.
fn no_one_block_words(w: &Words<'_>, letters: &[u8]) -> Result<(), Diagnostic> {
    for &l in letters {
        if let Some(word) = w.get(l) {
            return Err(alarms::other_cycle_form(
                word.span,
                l,
                "the one-block form, which writes X/Z in the same block",
            ));
        }
    }
    Ok(())
}

/// The cumulative depths (radius, mm) of G76's passes before the
/// finishing ones: Δd·√n, each at least `min_step` deeper than the last,
/// the last exactly `height − allowance`. `None` beyond [`MAX_STEPS`].
pub(crate) fn thread_depths(
    first: f64,
    min_step: f64,
    height: f64,
    allowance: f64,
) -> Option<Vec<f64>> {
    let rough_to = height - allowance;
    let mut out = Vec::new();
    if rough_to <= ZERO_MM {
        return Some(out);
    }
    let mut prev = 0.0;
    for n in 1..=MAX_STEPS {
        // n ≤ 10,000: exact in f64.
        #[allow(clippy::cast_precision_loss)]
        let mut d = first * (n as f64).sqrt();
        if d - prev < min_step {
            d = prev + min_step;
        }
        if d >= rough_to - ZERO_MM {
            out.push(rough_to);
            return Some(out);
        }
        out.push(d);
        prev = d;
    }
    None
}

/// The moves of G74/G75 in (peck axis, step axis) coordinates.
fn peck_moves(
    a: P2,
    end: P2,
    peck: f64,
    step: f64,
    retract: f64,
    relief: f64,
    feed: vcnc_core::events::Feed,
) -> Vec<(How, P2)> {
    let (dp, ds) = (
        (end.0 - a.0).signum(),
        if end.1 == a.1 {
            1.0
        } else {
            (end.1 - a.1).signum()
        },
    );
    let mut moves = Vec::new();
    let mut s = a.1;
    loop {
        if moves.is_empty() {
            // The first position is A's.
        } else {
            moves.push((How::Rapid, P2(a.0, s)));
        }
        let mut cur = a.0;
        loop {
            let next = if (end.0 - cur).abs() <= peck + ZERO_MM {
                end.0
            } else {
                cur + dp * peck
            };
            moves.push((How::Cut(feed), P2(next, s)));
            if next == end.0 {
                break;
            }
            moves.push((How::Rapid, P2(next - dp * retract, s)));
            cur = next;
        }
        let out_s = s - ds * relief;
        if relief > 0.0 {
            moves.push((How::Cut(feed), P2(end.0, out_s)));
        }
        moves.push((How::Rapid, P2(a.0, out_s)));
        if (end.1 - s).abs() <= ZERO_MM {
            break;
        }
        s = if (end.1 - s).abs() <= step + ZERO_MM {
            end.1
        } else {
            s + ds * step
        };
    }
    moves.push((How::Rapid, a));
    moves
}

impl<'a> Machining<'_, 'a> {
    /// G74 (`face`) or G75.
    pub(crate) fn peck_cycle(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        face: bool,
    ) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        if !w.any(self.cfg.axis_mask) {
            // The first block: R, the retract after each peck.
            no_one_block_words(w, b"IKD")?;
            for l in [b'P', b'Q'] {
                if let Some(word) = w.get(l) {
                    return Err(alarms::word_not_allowed(word.span, l));
                }
            }
            if let Some(r) = w.get(b'R') {
                self.state.lathe.mrc.peck_retract_mm = self.units().length_mm(&r).abs();
            }
            return Ok(());
        }
        let a = self.here_xz(axes);
        let end = P2::of(&self.state.target(self.cfg, w, false).prog, axes);
        // (peck axis, step axis): G74 pecks along Z, G75 along X.
        let (pa, sa, pe, se) = if face {
            (a.1, a.0, end.1, end.0)
        } else {
            (a.0, a.1, end.0, end.1)
        };
        // Two-block P, Q, R or one-block I, K, D (FS15 format, Haas).
        let (x_word, z_word) = (either(w, b'P', b'I')?, either(w, b'Q', b'K')?);
        let relief_word = either(w, b'R', b'D')?;
        let x_amount = x_word.map(|p| self.units().length_mm(&p).abs());
        let z_amount = z_word.map(|q| self.units().length_mm(&q).abs());
        let (peck, step, peck_word, step_word) = if face {
            (z_amount, x_amount, z_word, x_word)
        } else {
            (x_amount, z_amount, x_word, z_word)
        };
        if (pe - pa).abs() < ZERO_MM {
            return Err(alarms::cycle_parameters(
                cmd,
                "the cycle's end point is where it starts along the pecks",
            ));
        }
        let peck = match peck {
            Some(p) if p > 0.0 => p,
            _ => {
                let span = peck_word.map_or(cmd, |x| x.span);
                return Err(alarms::zero_amount(span, "the depth of each peck"));
            }
        };
        let stepping = (se - sa).abs() > ZERO_MM;
        let step = match step {
            Some(s) if s > 0.0 => s,
            _ if !stepping => 1.0,
            _ => {
                let span = step_word.map_or(cmd, |x| x.span);
                return Err(alarms::zero_amount(span, "the step between positions"));
            }
        };
        let relief = relief_word.map_or(0.0, |r| self.units().length_mm(&r).abs());
        let retract = self.state.lathe.mrc.peck_retract_mm;
        let count = ((pe - pa).abs() / peck).ceil() * (((se - sa).abs() / step).floor() + 2.0);
        if count > MAX_STEPS as f64 {
            return Err(alarms::too_many_cycle_moves(cmd));
        }
        let feed = self.feed(cmd)?;
        let moves = peck_moves(P2(pa, sa), P2(pe, se), peck, step, retract, relief, feed);
        let xz: Vec<(How, Xz)> = moves
            .into_iter()
            .map(|(how, q)| (how, if face { q.swapped() } else { q }))
            .collect();
        let suspended = self.suspend_comp()?;
        self.cycle_moves(&xz, axes, w, cmd)?;
        self.resume_comp(suspended);
        Ok(())
    }

    /// G76, first or second block.
    pub(crate) fn thread_cycle_multi(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        if !w.any(self.cfg.axis_mask) {
            no_one_block_words(w, b"KDIA")?;
            return self.thread_first_block(w);
        }
        let a = self.here_xz(axes);
        let goal = self.state.target(self.cfg, w, false);
        let (has_x, has_z) = (
            goal.named & (1 << axes.0) != 0,
            goal.named & (1 << axes.1) != 0,
        );
        if !has_x || !has_z {
            return Err(alarms::needs_word(
                cmd,
                "G76",
                "X (or U) and Z (or W): the thread's root at its end",
            ));
        }
        let (root, z_end) = (goal.prog.get(axes.0), goal.prog.get(axes.1));
        // The one-block form (FS15 tape format, Haas): K the height, D the
        // first depth, I the taper, A the tool angle; P then picks the
        // infeed (1: one flank, the depth of each pass by constant area).
        let one_block = w.get(b'K').is_some() || w.get(b'D').is_some();
        let (height_of, first_of, taper_letter, tool_angle_deg) = if one_block {
            let angle = one_block_thread_angle(w, self.state.lathe.mrc.tool_angle_deg)?;
            (HEIGHT_K, FIRST_D, b'I', angle)
        } else {
            if let Some(word) = w.get(b'I').or(w.get(b'A')) {
                return Err(alarms::other_cycle_form(
                    word.span,
                    word.addr.0,
                    "the one-block form, with K (the height) and D (the first depth)",
                ));
            }
            (HEIGHT_P, FIRST_Q, b'R', self.state.lathe.mrc.tool_angle_deg)
        };
        let height = self.thread_amount(w, height_of, cmd)?;
        let first = self.thread_amount(w, first_of, cmd)?;
        let taper_word = w.get(taper_letter);
        let lead_mm = match w.get(b'F') {
            Some(f) if f.value > 0.0 => f.value * self.unit_mm(),
            _ => return Err(alarms::thread_without_lead(cmd)),
        };
        let taper = taper_word.map_or(0.0, |r| self.units().length_mm(&r));
        let (dir_x, dir_z) = ((root - a.0).signum(), (z_end - a.1).signum());
        if (root - a.0).abs() < ZERO_MM || (z_end - a.1).abs() < ZERO_MM {
            return Err(alarms::cycle_parameters(
                cmd,
                "the thread's end must differ from the start point in X and Z",
            ));
        }
        let mrc = self.state.lathe.mrc;
        let mut depths = thread_depths(first, mrc.min_depth_mm, height, mrc.allowance_mm)
            .ok_or_else(|| alarms::too_many_cycle_moves(cmd))?;
        depths.extend(std::iter::repeat_n(height, mrc.finish_count as usize));
        let half_angle = (tool_angle_deg / 2.0).to_radians().tan();
        let crest_end = root - dir_x * height;
        let length = (z_end - a.1).abs();
        let mut moves = Vec::new();
        for d in depths {
            let x_end = crest_end + dir_x * d;
            let shift = d * half_angle;
            if shift >= length {
                return Err(alarms::cycle_parameters(
                    cmd,
                    "the flank infeed moves the pass start past the thread's end",
                ));
            }
            let z_start = a.1 + dir_z * shift;
            let x_start = x_end + taper * (z_start - z_end) / (a.1 - z_end);
            moves.push((How::Rapid, P2(x_start, z_start)));
            moves.extend(self.thread_with_chamfer(
                P2(x_start, z_start),
                P2(x_end, z_end),
                a.0,
                lead_mm,
            ));
            moves.push((How::Rapid, P2(a.0, z_end)));
            moves.push((How::Rapid, a));
        }
        let suspended = self.suspend_comp()?;
        self.cycle_moves(&moves, axes, w, cmd)?;
        self.resume_comp(suspended);
        Ok(())
    }

    /// G76's height or first depth in `w`: a positive length (E109 if
    /// negative, E346 if zero or missing).
    fn thread_amount(
        &self,
        w: &Words<'_>,
        (letter, name, rule): Amount,
        cmd: Span,
    ) -> Result<f64, Diagnostic> {
        match w.get(letter) {
            Some(word) if self.units().length_mm(&word) > 0.0 => Ok(self.units().length_mm(&word)),
            Some(word) if word.value < 0.0 => Err(alarms::value_out_of_range(
                word.span, letter, word.value, rule,
            )),
            word => Err(alarms::zero_amount(word.map_or(cmd, |x| x.span), name)),
        }
    }

    /// G76 P(m r a) Q(Δdmin) R(d).
    fn thread_first_block(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        if let Some(p) = w.get(b'P') {
            let v = whole(
                &p,
                b'P',
                0.0,
                999_999.0,
                "G76 P is mmrraa: finishing passes, chamfer, tool angle",
            )?;
            let (m, r, angle) = (v / 10_000, (v / 100) % 100, v % 100);
            if m == 0 {
                return Err(alarms::zero_amount(
                    p.span,
                    "the number of finishing passes (P's first two digits)",
                ));
            }
            if !ANGLES.contains(&angle) {
                return Err(alarms::value_out_of_range(
                    p.span,
                    b'P',
                    p.value,
                    "the tool angle (P's last two digits) is 80, 60, 55, 30, 29 or 0",
                ));
            }
            let mrc = &mut self.state.lathe.mrc;
            mrc.finish_count = m;
            // r < 100 and angle < 100: both fit.
            mrc.chamfer_tenths = u8::try_from(r).unwrap_or(0);
            mrc.tool_angle_deg = f64::from(angle);
        }
        if let Some(q) = w.get(b'Q') {
            self.state.lathe.mrc.min_depth_mm = self.units().length_mm(&q).abs();
        }
        if let Some(r) = w.get(b'R') {
            self.state.lathe.mrc.allowance_mm = self.units().length_mm(&r).abs();
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depths_follow_the_square_root_until_the_allowance() {
        let d = thread_depths(0.3, 0.0, 1.0, 0.1).unwrap();
        // 0.3, 0.4243, 0.5196, 0.6, 0.6708, 0.7348, 0.7937, 0.8485, then 0.9.
        assert_eq!(d.len(), 9);
        assert!((d[1] - 0.3 * 2f64.sqrt()).abs() < 1e-12);
        assert_eq!(d[8], 0.9);
        // A minimum step larger than √n's increments takes over.
        let d = thread_depths(0.3, 0.2, 1.0, 0.0).unwrap();
        let want = [0.3, 0.5, 0.7, 0.9, 1.0];
        assert_eq!(d.len(), want.len());
        assert!(
            d.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12),
            "{d:?}"
        );
    }
}
