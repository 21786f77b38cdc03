//! LinuxCNC's lathe threading cycle G76 (`--dialect linuxcnc-lathe`), as
//! its G-code reference describes it and rs274 2.9 runs it.
//!
//! ```text
//!   G76 P(pitch) Z(end) I(peak offset) J(first depth) K(full depth)
//!       [R(degression) Q(compound angle) H(spring passes) E(taper) L(0–3)]
//!
//!   drive line x0 (where the tool is)   ●─────────────────────── retract
//!   thread peak x0 + I                   ╲ rapid in              x0 ∓ (K−d)
//!   pass depth d beyond the peak          ●━━━━━ thread ━━━━━●
//!   pass n: d = J·n^(1/R) while below K, then K, then H spring passes at K
//! ```
//!
//! I < 0 is an outside thread (the cut goes towards −X), I > 0 an inside
//! one; I, J and K are X lengths (diameters under G7). A pass at depth d
//! starts d·tan Q along Z from the start (the compound infeed) and ends
//! (K − d)·tan Q short of Z; it retracts to x0 ∓ (K − d), so the last pass
//! leaves the tool at the drive line at Z. E (with L 1: entry, 2: exit, 3:
//! both) tapers K in over E along Z, the taper's lead scaled so that Z
//! still advances one pitch per turn (rs274's √(K² + E²)/E). The checked
//! reference is rs274's output (`tests/fixtures/linuxcnc_lathe_cycles`).

use crate::alarms;
use crate::codes::cycles::positive;
use crate::codes::turning_cycles::How;
use crate::interpreter::Machining;
use crate::plane::{P2, Xz};
use crate::words::Words;
use crate::words::whole;
use vcnc_syntax::{Diagnostic, Span};

/// Most passes one G76 may make.
const MAX_PASSES: u32 = 10_000;

/// What a G76 block asks for, in mm and radians.
struct Thread {
    pitch_mm: f64,
    z_end: f64,
    peak_mm: f64,
    first_mm: f64,
    full_mm: f64,
    degression: f64,
    tan_q: f64,
    spring: u32,
    taper_mm: f64,
    taper_in: bool,
    taper_out: bool,
}

/// The depths of the passes: J·n^(1/R) while below K, then K, then the
/// spring passes at K.
fn depths(t: &Thread, cmd: Span) -> Result<Vec<f64>, Diagnostic> {
    let mut out = Vec::new();
    for n in 1..=MAX_PASSES {
        let d = t.first_mm * f64::from(n).powf(1.0 / t.degression);
        // Within the length tolerance: J 0.3, K 0.9 is three passes for
        // rs274, though 0.3 · 3 falls short of 0.9 in binary.
        if d >= t.full_mm - crate::plane::ZERO_MM {
            out.extend(std::iter::repeat_n(t.full_mm, 1 + t.spring as usize));
            return Ok(out);
        }
        out.push(d);
    }
    Err(alarms::cycle_parameters(
        cmd,
        "G76 would make more than 10000 passes: J is too small for K",
    ))
}

/// The moves of every pass, from the drive point `a` (radius, Z).
fn ngc_thread_moves(a: Xz, t: &Thread, cmd: Span) -> Result<Vec<(How, Xz)>, Diagnostic> {
    let dz = t.z_end - a.1;
    if dz.abs() < crate::plane::ZERO_MM {
        return Err(alarms::cycle_parameters(
            cmd,
            "G76's Z is where the tool already is",
        ));
    }
    let (s, zdir) = (t.peak_mm.signum(), dz.signum());
    let taper = t.pitch_mm * t.full_mm.hypot(t.taper_mm) / t.taper_mm.max(f64::MIN_POSITIVE);
    let mut moves = Vec::new();
    for d in depths(t, cmd)? {
        let cut = a.0 + t.peak_mm + s * d;
        let out = a.0 - s * (t.full_mm - d);
        let z_start = a.1 + zdir * d * t.tan_q;
        let z_stop = t.z_end - zdir * (t.full_mm - d) * t.tan_q;
        moves.push((How::Rapid, P2(out, z_start)));
        if t.taper_in {
            moves.push((How::Thread(taper), P2(cut - s * t.full_mm, z_start)));
            moves.push((How::Thread(taper), P2(cut, z_start + zdir * t.taper_mm)));
        } else {
            moves.push((How::Rapid, P2(cut, z_start)));
        }
        if t.taper_out {
            moves.push((How::Thread(t.pitch_mm), P2(cut, z_stop - zdir * t.taper_mm)));
            moves.push((How::Thread(taper), P2(cut - s * t.full_mm, z_stop)));
        } else {
            moves.push((How::Thread(t.pitch_mm), P2(cut, z_stop)));
        }
        moves.push((How::Rapid, P2(out, z_stop)));
    }
    Ok(moves)
}

impl<'a> Machining<'_, 'a> {
    /// G76 of LinuxCNC's lathe mode.
    pub(crate) fn ngc_thread_cycle(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        let t = self.ngc_thread_words(w, cmd, axes)?;
        let start = self.here_xz(axes);
        let moves = ngc_thread_moves(start, &t, cmd)?;
        self.cycle_moves(&moves, axes, w, cmd)
    }

    fn ngc_thread_words(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        axes: (usize, usize),
    ) -> Result<Thread, Diagnostic> {
        let need = |l: u8, what: &str| w.get(l).ok_or_else(|| alarms::needs_word(cmd, "G76", what));
        if let Some(x) = w.get(b'X') {
            return Err(alarms::word_not_allowed(x.span, b'X'));
        }
        let pitch = need(b'P', "P (the thread pitch)")?;
        need(b'Z', "Z (the thread's end)")?;
        let i = need(b'I', "I (the thread peak's offset from the drive line)")?;
        let j = need(b'J', "J (the first cut's depth)")?;
        let k = need(b'K', "K (the full thread depth)")?;
        let pitch_mm = positive(
            pitch,
            self.units().length_mm(&pitch),
            "G76's P is the pitch, more than 0",
        )?;
        let first_mm = positive(
            j,
            self.units().x_length_mm(&j),
            "G76's J is the first cut's depth, more than 0",
        )?;
        let full_mm = positive(
            k,
            self.units().x_length_mm(&k),
            "G76's K is the full thread depth, more than 0",
        )?;
        let peak_mm = self.units().x_length_mm(&i);
        if peak_mm == 0.0 {
            return Err(alarms::value_out_of_range(
                i.span,
                b'I',
                i.value,
                "G76's I is the peak's offset from the drive line: negative outside, positive inside, not 0",
            ));
        }
        let degression = match w.get(b'R') {
            Some(r) if r.value >= 1.0 => r.value,
            Some(r) => {
                return Err(alarms::value_out_of_range(
                    r.span,
                    b'R',
                    r.value,
                    "G76's R, the depth degression, is 1 or more",
                ));
            }
            None => 1.0,
        };
        let tan_q = match w.get(b'Q') {
            Some(q) if q.value.abs() < 90.0 => q.value.to_radians().tan(),
            Some(q) => {
                return Err(alarms::value_out_of_range(
                    q.span,
                    b'Q',
                    q.value,
                    "G76's Q is the compound angle, under 90 degrees",
                ));
            }
            None => 0.0,
        };
        let spring = match w.get(b'H') {
            Some(h) => whole(
                &h,
                b'H',
                0.0,
                f64::from(MAX_PASSES),
                "H is the number of spring passes",
            )?,
            None => 0,
        };
        let taper_mm = match w.get(b'E') {
            Some(e) if e.value >= 0.0 => self.units().length_mm(&e),
            Some(e) => {
                return Err(alarms::value_out_of_range(
                    e.span,
                    b'E',
                    e.value,
                    "G76's E is the taper's length along Z, not negative",
                ));
            }
            None => 0.0,
        };
        let ends = match w.get(b'L') {
            Some(l) => whole(
                &l,
                b'L',
                0.0,
                3.0,
                "L picks the tapered ends: 0 none, 1 entry, 2 exit, 3 both",
            )?,
            None => 0,
        };
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        Ok(Thread {
            pitch_mm,
            z_end: goal.prog.get(axes.1),
            peak_mm,
            first_mm,
            full_mm,
            degression,
            tan_q,
            spring,
            taper_mm,
            taper_in: taper_mm > 0.0 && ends & 1 != 0,
            taper_out: taper_mm > 0.0 && ends & 2 != 0,
        })
    }
}
