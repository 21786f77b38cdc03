//! The "convert" phase: what a word's value means in mm, seconds or counts.
//!
//! A length or angle written without a decimal point is in least input
//! increments (0.001 mm, 0.0001 inch, 0.001°) unless the machine reads
//! numbers calculator-style; inch values become mm here, so nothing after
//! this module knows the program's units. Integer words (P, L, H, T, N) must
//! be whole and in range.

use crate::alarms;
use crate::config::Config;
use crate::dialect::AxisWord;
use crate::dialect::SetOp;
use crate::dialect::{IntegerWords, PolarIncremental, bit};
use crate::interpreter::Interpreter;
use crate::interpreter::Machining;
use crate::motion::Goal;
use crate::state::PointStyle;
use crate::state::{Modal, Motion, State};
use crate::words::Words;
use vcnc_core::events::{Plane, Pos};
use vcnc_syntax::{Addr, Diagnostic, Word};

/// mm per inch.
pub const MM_PER_INCH: f64 = 25.4;

/// How the words of a block read as numbers: the program's units and
/// diameter programming (the modal codes in force), and whether a word
/// without a decimal point is in whole units (the dialect's integers, a
/// calculator-style machine). A view taken when a word is read
/// ([`State::units`]): the conversions need neither the rest of the
/// state nor the interpreter. It reads the modal codes only when a word
/// needs them, as a plain pointed length does not ask whether X is a
/// diameter.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Units {
    /// G20: inches (else mm).
    inch: bool,
    /// Lathe G23: the diameter axis is programmed in diameters.
    diameter: bool,
    /// A word without a point is in whole units all the same.
    whole_words: bool,
}

impl Units {
    /// The units of the modal codes `modal`; `whole_words` as the run's
    /// configuration says (`Config::whole_words`). The flags are copied
    /// out, so that a loop over words keeps them in registers.
    #[inline]
    pub fn new(modal: &Modal, whole_words: bool) -> Units {
        Units {
            inch: modal.inch,
            diameter: modal.diameter,
            whole_words,
        }
    }

    /// Whether the word is in whole units (else least increments).
    #[inline]
    fn whole(self, w: &Word) -> bool {
        w.point || self.whole_words
    }

    /// A length word in mm.
    #[inline]
    pub fn length_mm(self, w: &Word) -> f64 {
        let v = if self.whole(w) {
            w.value
        } else {
            w.value * if self.inch { 0.0001 } else { 0.001 }
        };
        if self.inch { v * MM_PER_INCH } else { v }
    }

    /// An X-direction length that follows diameter programming (lathe G23
    /// halves it): axis words, and the cycles' X depths.
    #[inline]
    pub fn x_length_mm(self, w: &Word) -> f64 {
        let v = self.length_mm(w);
        if self.diameter { v / 2.0 } else { v }
    }

    /// The value of an axis word: mm (a radius for a diameter axis), or
    /// degrees for a rotary axis.
    #[inline]
    pub fn axis_mm(self, a: &AxisWord, w: &Word) -> f64 {
        if a.rotary {
            self.angle_deg(w)
        } else if a.diameter {
            self.x_length_mm(w)
        } else {
            self.length_mm(w)
        }
    }

    /// The value of the word of machine axis `i` among `axes`.
    pub fn axis_value(self, axes: &[AxisWord], i: usize, w: &Word) -> f64 {
        match axes.get(i) {
            Some(a) => self.axis_mm(a, w),
            None => self.length_mm(w),
        }
    }

    /// A time word (G04 X): seconds with a point, milliseconds without.
    pub fn seconds(self, w: &Word) -> f64 {
        if self.whole(w) {
            w.value
        } else {
            w.value * 0.001
        }
    }

    /// An angle word in degrees (0.001° without a decimal point), whatever
    /// the length unit.
    #[inline]
    pub fn angle_deg(self, w: &Word) -> f64 {
        if self.whole(w) {
            w.value
        } else {
            w.value * 0.001
        }
    }
}

impl Interpreter<'_> {
    /// W109 at the program's end: no length had a decimal point, and read
    /// in least increments the longest it wrote and the span of the linear
    /// axes' program positions at the ends of its blocks (the power-on
    /// position left out) are both under 1 mm — whole units, most likely.
    pub(crate) fn whole_units_report(&mut self) -> Option<vcnc_core::events::Event> {
        let p = &self.points;
        if !p.active || p.seen_point {
            return None;
        }
        let (first, longest) = (p.first_plain.as_ref()?, p.longest?);
        if longest.2 >= 1.0 {
            return None;
        }
        // Where the last block ended counts too.
        let (lo, hi) = PointStyle::grown(p.reach, self.state.prog);
        let span_mm = self
            .cfg
            .axis_words
            .iter()
            .enumerate()
            .filter(|(_, a)| !a.rotary)
            .map(|(i, _)| hi.get(i) - lo.get(i))
            .fold(0.0f64, f64::max);
        if span_mm >= 1.0 {
            return None;
        }
        let lathe = self.cfg.dialect.diameter.lathe;
        let whole: Vec<&str> = crate::dialect::Dialect::all()
            .iter()
            .filter(|d| d.integers == IntegerWords::WholeUnits)
            .filter(|d| d.diameter.lathe == lathe)
            .map(|d| d.name)
            .collect();
        let w = alarms::whole_units_likely(first, longest, &whole);
        Some(vcnc_core::events::Event::Warning(w))
    }
}

impl<'a> Machining<'_, 'a> {
    /// Program units → mm factor.
    pub(crate) fn unit_mm(&self) -> f64 {
        self.state.unit_mm()
    }

    /// How this block's words read (the units in force now: a G20/G21 of
    /// the block has already been executed).
    #[inline]
    pub(crate) fn units(&self) -> Units {
        self.state.units(self.cfg)
    }

    /// Letters other than axes that are lengths in this block (warning
    /// W101): an arc's I, J, K and R, a cycle's R and Q, G10 L10–L13's R.
    fn length_letters(&self, w: &Words<'_>) -> u32 {
        let mut m = 0;
        let arc = matches!(self.state.modal.motion, Motion::ArcCw | Motion::ArcCcw);
        if arc && w.axis_user.is_none() {
            m |= bit(b'I') | bit(b'J') | bit(b'K') | bit(b'R');
        }
        if self.state.cycle.code.is_some() {
            m |= bit(b'R') | bit(b'Q');
        }
        if w.axis_user.is_some_and(|u| {
            matches!(
                u.def.op,
                crate::dialect::GOp::Cycle(crate::dialect::CycleOp::CircleCut(..))
            )
        }) {
            m |= bit(b'I') | bit(b'K') | bit(b'Q');
        }
        if w.once(crate::dialect::GOp::Set(SetOp::Data)).is_some()
            && w.get(b'L')
                .is_some_and(|l| (10.0..=13.0).contains(&l.value))
        {
            m |= bit(b'R');
        }
        m & !self.cfg.axis_mask
    }
}

impl State {
    /// Program units → mm factor.
    pub(crate) fn unit_mm(&self) -> f64 {
        if self.modal.inch { MM_PER_INCH } else { 1.0 }
    }

    /// How this block's words read (the units in force now: a G20/G21 of
    /// the block has already been executed).
    #[inline]
    pub(crate) fn units(&self, cfg: &Config<'_>) -> Units {
        Units::new(&self.modal, cfg.whole_words)
    }
}

/// Stage 1's target: where the block's axis words point in program
/// coordinates.
impl State {
    /// Target of the block's axis words in program coordinates, absolute
    /// or incremental from the programmed point (an incremental word such
    /// as U always counts from there); axes not named keep their program
    /// coordinate. Under G16 the plane's first and second axis words are a
    /// radius and an angle.
    pub(crate) fn target(&mut self, cfg: &Config<'_>, w: &Words<'_>, incremental: bool) -> Goal {
        // Locals, the goal built at the end: the caller reads `named` and
        // `all_incremental` back as one 8-byte word, which waited for their
        // last 4- and 1-byte stores when they were updated in place.
        let (mut named, mut all_incremental) = (0u32, true);
        let (mut prog, mut delta) = (self.prog, Pos::default());
        let present = w.present();
        let units = self.units(cfg);
        for (i, a) in cfg.axis_words.iter().enumerate() {
            if present & a.rest == 0 {
                break;
            }
            if present & a.mask == 0 {
                continue;
            }
            let (word, inc) = match w.get(a.letter) {
                Some(word) => (word, incremental),
                None => match a.inc.and_then(|l| w.get(l)) {
                    Some(word) => (word, true),
                    None => continue,
                },
            };
            let v = units.axis_mm(a, &word);
            if inc {
                prog.set(i, self.prog.get(i) + v);
                delta.set(i, v);
            } else {
                prog.set(i, v);
                all_incremental = false;
            }
            named |= 1 << i;
        }
        if cfg.dialect.polar_words {
            let polar = self.ngc_polar_target(cfg, w, incremental, &mut prog);
            if polar != 0 {
                named |= polar;
                all_incremental = false;
            }
        }
        if self.modal.polar {
            let polar = self.polar_target(cfg, w, incremental, &mut prog);
            if polar != 0 {
                named |= polar;
                all_incremental = false;
            }
        }
        Goal {
            prog,
            named,
            delta,
            all_incremental,
        }
    }

    /// The target of a move to `goal`: an increment from where the tool is
    /// when every named axis is incremental and the transforms changed
    /// since the last absolute move (the tool is then not where the frame
    /// puts the programmed point), else a program point.
    pub(crate) fn move_target(&self, goal: &Goal) -> crate::motion::Target {
        if goal.all_incremental && self.detached {
            crate::motion::Target::Relative(goal.delta)
        } else {
            crate::motion::Target::Program(goal.prog)
        }
    }

    /// G16: the plane's first axis word is a radius, the second an angle in
    /// degrees (counter-clockwise), both about the program origin; an
    /// omitted one keeps the last. Under G91 the angle adds to the last
    /// angle, and the radius as the dialect's [`PolarIncremental`] says:
    /// it adds to the last radius (Syntec), or it is measured from the
    /// current position, the block's polar centre (Fanuc):
    ///
    /// ```text
    ///   G90 X10. Y90.   then   G91 X5. Y90.
    ///
    ///   Syntec: about the origin,        Fanuc: about the current point,
    ///   radius 10+5, angle 90+90         radius 5, angle 90+90
    ///     -> X-15 Y0                       -> X-5 Y10
    /// ```
    ///
    /// Writes the cartesian point into `to`, remembers the radius and
    /// angle (about the origin), and returns the axes it set.
    fn polar_target(
        &mut self,
        cfg: &Config<'_>,
        w: &Words<'_>,
        incremental: bool,
        to: &mut Pos,
    ) -> u32 {
        let [la, lb, _] = self.modal.plane.letters();
        let (Some(ia), Some(ib)) = (cfg.machine.axis_of(la), cfg.machine.axis_of(lb)) else {
            return 0;
        };
        let (r_word, a_word) = (w.get(la), w.get(lb));
        if r_word.is_none() && a_word.is_none() {
            return 0;
        }
        let here_centred =
            cfg.dialect.polar_incremental == PolarIncremental::CentreAtCurrentPosition;
        let (last_r, last_deg) = if here_centred {
            self.polar_here(ia, ib)
        } else {
            self.polar
        };
        let units = self.units(cfg);
        let r = r_word.map(|word| units.length_mm(&word));
        let deg = a_word.map(|word| units.angle_deg(&word));
        if let (true, Some(r), true) = (incremental, r, here_centred) {
            return self.polar_about_here(r, last_deg + deg.unwrap_or(0.0), [ia, ib], to);
        }
        let (r, deg) = if incremental {
            (last_r + r.unwrap_or(0.0), last_deg + deg.unwrap_or(0.0))
        } else {
            (r.unwrap_or(last_r), deg.unwrap_or(last_deg))
        };
        self.polar = (r, deg);
        let (s, c) = deg.to_radians().sin_cos();
        to.set(ia, r * c);
        to.set(ib, r * s);
        (1 << ia) | (1 << ib)
    }

    /// Fanuc's "last" radius and angle: the current point's own (Mitsubishi
    /// M700V §6.12 for an omitted radius or angle), also after a move that
    /// was not polar (G53, G28, G92) or a plane change. While the tool is
    /// where the last polar block put it, that block's radius and angle
    /// as they were accumulated, so that a bolt circle's angles add up
    /// exactly rather than through `atan2`.
    fn polar_here(&self, ia: usize, ib: usize) -> (f64, f64) {
        let (a, b) = (self.prog.get(ia), self.prog.get(ib));
        let (last_r, last_deg) = self.polar;
        let (s, c) = last_deg.to_radians().sin_cos();
        if (a - last_r * c).hypot(b - last_r * s) <= crate::plane::ZERO_MM {
            return self.polar;
        }
        let r = a.hypot(b);
        // At the origin the angle is none: 0, not the direction of a
        // rounding residue (10 at 90° leaves X at 6e-16).
        let deg = if r <= crate::plane::ZERO_MM {
            0.0
        } else {
            b.atan2(a).to_degrees()
        };
        (r, deg)
    }

    /// Fanuc's G91 polar block with a radius: the point `r` from the
    /// current point at `deg`. The last radius and angle become the new
    /// point's own about the origin, which a later block that omits them
    /// keeps (FANUC Series 16/18-MC §9.2; Mitsubishi M700V §6.12: an
    /// omitted radius is "the distance between the polar coordinate center
    /// [the work zero] and current position").
    fn polar_about_here(&mut self, r: f64, deg: f64, [ia, ib]: [usize; 2], to: &mut Pos) -> u32 {
        let (s, c) = deg.to_radians().sin_cos();
        let (a, b) = (self.prog.get(ia) + r * c, self.prog.get(ib) + r * s);
        to.set(ia, a);
        to.set(ib, b);
        self.polar = (a.hypot(b), b.atan2(a).to_degrees());
        (1 << ia) | (1 << ib)
    }

    /// LinuxCNC's polar words: `@` a distance and `^` an angle in degrees,
    /// counter-clockwise from +X, always in X and Y whatever the plane
    /// (rs274 checked: G18 and G19 blocks move X and Y). Under G90 both are
    /// about the program origin; under G91 each adds to the current point's
    /// own distance or angle from the origin. A missing word keeps the
    /// current point's. Writes X and Y into `to` and returns the axes set;
    /// [`Self::check_polar_words`] has refused what rs274 refuses.
    fn ngc_polar_target(
        &self,
        cfg: &Config<'_>,
        w: &Words<'_>,
        incremental: bool,
        to: &mut Pos,
    ) -> u32 {
        let (r_word, a_word) = (w.get_ext(Addr::AT), w.get_ext(Addr::CARET));
        if r_word.is_none() && a_word.is_none() {
            return 0;
        }
        let (Some(ix), Some(iy)) = (cfg.machine.axis_of(b'X'), cfg.machine.axis_of(b'Y')) else {
            return 0;
        };
        let (x, y) = (self.prog.get(ix), self.prog.get(iy));
        let (here_r, here_deg) = (x.hypot(y), y.atan2(x).to_degrees());
        let r = r_word.map(|word| word.value * self.unit_mm());
        let deg = a_word.map(|word| word.value);
        let (r, deg) = if incremental {
            (here_r + r.unwrap_or(0.0), here_deg + deg.unwrap_or(0.0))
        } else {
            (r.unwrap_or(here_r), deg.unwrap_or(here_deg))
        };
        let (s, c) = deg.to_radians().sin_cos();
        to.set(ix, r * c);
        to.set(iy, r * s);
        (1 << ix) | (1 << iy)
    }

    /// What rs274 refuses in a block with `@` or `^`: a plane other than
    /// G17 before the block (rs274 checks the plane the block starts in:
    /// `G18 G1 @1 ^2` runs, `G17 G1 @1 ^2` after G18 does not), X or Y
    /// beside them ("Cannot specify both polar coordinate and X word"),
    /// `@` without `^`
    /// at the origin under G90 ("Must specify angle in polar coordinate if
    /// at the origin"), and either word at the origin under G91 ("motion
    /// with polar coordinates is indeterminate when at the origin").
    pub(crate) fn check_polar_words(
        &self,
        cfg: &Config<'_>,
        w: &Words<'_>,
        plane_before: Plane,
    ) -> Result<(), Diagnostic> {
        let (r_word, a_word) = (w.get_ext(Addr::AT), w.get_ext(Addr::CARET));
        let Some(first) = r_word.or(a_word) else {
            return Ok(());
        };
        if plane_before != Plane::Xy {
            return Err(alarms::polar_outside_xy(first.span, &first.addr.name()));
        }
        for l in [b'X', b'Y'] {
            if let Some(word) = w.get(l) {
                return Err(alarms::polar_and_axis(word.span, first.addr.name(), l));
            }
        }
        let (Some(ix), Some(iy)) = (cfg.machine.axis_of(b'X'), cfg.machine.axis_of(b'Y')) else {
            return Err(alarms::needs_axes(first.span, "a polar word (X and Y)"));
        };
        let at_origin = self.prog.get(ix) == 0.0 && self.prog.get(iy) == 0.0;
        if !at_origin {
            return Ok(());
        }
        if self.modal.incremental {
            return Err(alarms::polar_incremental_at_origin(first.span));
        }
        if let (Some(r), None) = (r_word, a_word) {
            return Err(alarms::needs_word(
                r.span,
                "@ at the program origin",
                "^, the angle (LinuxCNC: \"must specify angle in polar coordinate if at the origin\")",
            ));
        }
        Ok(())
    }

    /// The polar radius and angle that `to` has (after a G16 move).
    pub(crate) fn polar_of(&self, cfg: &Config<'_>, to: Pos) -> (f64, f64) {
        let [la, lb, _] = self.modal.plane.letters();
        match (cfg.machine.axis_of(la), cfg.machine.axis_of(lb)) {
            (Some(ia), Some(ib)) => {
                let (x, y) = (to.get(ia), to.get(ib));
                (x.hypot(y), y.atan2(x).to_degrees())
            }
            _ => (0.0, 0.0),
        }
    }
}

/// W101 and W109: what the program's length words look like.
impl Machining<'_, '_> {
    /// Warning W101: a length word without a decimal point in a program
    /// that otherwise writes points — the least-increment trap (`X35` is
    /// 0.035 mm). A program that never writes a point is consistent (tape
    /// format) and silent; so are whole-unit dialects.
    #[inline]
    pub(crate) fn note_points(&mut self, points: &mut PointStyle, w: &Words<'_>) {
        if !points.active {
            return;
        }
        // The common case costs a few mask tests, in the caller: no
        // point-less length, and points already seen (or none in this
        // block either); first on all letters, which spares the letters'
        // sorting in most blocks.
        if w.plain_values() == 0 && (points.seen_point || w.pointed() == 0) {
            return;
        }
        self.note_points_by_letter(points, w);
    }

    /// [`note_points`](Self::note_points) past its common case.
    #[inline(never)]
    fn note_points_by_letter(&mut self, points: &mut PointStyle, w: &Words<'_>) {
        // W109: where the program has been since its first length without
        // a point (the block before this one ended here), and before it
        // once the tool has left its power-on position.
        if !points.seen_point
            && (points.first_plain.is_some() || self.state.pos != self.cfg.machine.start)
        {
            points.reached(self.state.prog);
        }
        let extra = self.length_letters(w);
        let mask = self.cfg.axis_mask | extra;
        let plain = w.plain_values() & mask;
        if plain == 0 && (points.seen_point || w.pointed() & mask == 0) {
            return;
        }
        // A code that refuses axes reads its letters its own way (G04 X is
        // a time).
        if w.axis_user
            .is_some_and(|u| u.def.axes == crate::dialect::AxisWords::Refuse)
        {
            return;
        }
        // Under G16 the plane's second axis word is an angle.
        let polar_angle = if self.state.modal.polar {
            let [_, lb, _] = self.state.modal.plane.letters();
            self.cfg.machine.axis_of(lb)
        } else {
            None
        };
        let inch = self.state.modal.inch;
        let length = |mm: f64| {
            if inch {
                (mm / MM_PER_INCH, " in")
            } else {
                (mm, " mm")
            }
        };
        for i in 0..self.cfg.axis_words.len() {
            let Some(a) = self.cfg.axis_words.get(i).copied() else {
                continue;
            };
            let Some(word) = w.get(a.letter).or_else(|| a.inc.and_then(|l| w.get(l))) else {
                continue;
            };
            let shown = if a.rotary || polar_angle == Some(i) {
                (self.units().angle_deg(&word), "°")
            } else {
                length(self.units().axis_mm(&a, &word))
            };
            self.note_point(points, word, shown);
        }
        for l in b'A'..=b'Z' {
            if extra & bit(l) != 0
                && let Some(word) = w.get(l)
            {
                self.note_point(points, word, length(self.units().length_mm(&word)));
            }
        }
    }

    /// One length word for W101: a point marks the program's style (and
    /// releases a warning held for an earlier plain word), a plain word
    /// in a pointed program warns. `shown` is its value and unit.
    fn note_point(&mut self, points: &mut PointStyle, word: Word, (shown, unit): (f64, &str)) {
        if word.value == 0.0 {
            return;
        }
        if word.point {
            if !points.seen_point {
                points.seen_point = true;
                if let Some(d) = points.first_plain.take() {
                    points.warned += 1;
                    self.emit(|_| vcnc_core::events::Event::Warning(d));
                }
            }
        } else if !points.seen_point {
            // W109: the longest length written without a point, as read.
            let read_mm = (if unit == " in" {
                shown * MM_PER_INCH
            } else {
                shown
            })
            .abs();
            if unit != "°" && points.longest.is_none_or(|(_, _, mm)| read_mm > mm) {
                points.longest = Some((word.addr.0, word.value, read_mm));
            }
        }
        if !word.point && points.warned < PointStyle::MAX_WARNINGS {
            // Built only when it is kept: in a program without points
            // every length word comes here, and the constructor formats.
            let d =
                || alarms::least_increment_trap(word.span, word.addr.0, word.value, shown, unit);
            if points.seen_point {
                points.warned += 1;
                self.warn(d());
            } else if points.first_plain.is_none() {
                let d = d();
                let d = match self.stage.cur_line {
                    Some((src, line)) => self.at.locate(d, src, &line),
                    None => d,
                };
                points.first_plain = Some(d);
            }
        }
    }
}
