//! The motion stage: the one chokepoint every motion of every block passes
//! through on its way out of the interpreter.
//!
//! ```text
//!  codes (G00…G03, G28, cycles …)
//!        │  Move { kind, target (program or machine point), command span }
//!        │  (through `codes/modal.rs`'s `send`: a lathe's corner and G96 first)
//!        ▼
//!   commit ─▶ 1 frame      program → machine (offsets, G68/G51/G51.1, G43)
//!             2 compensation  (G41/G42 — a slot for now: passes moves on)
//!             3 travel     soft limits on the path the tool really follows
//!             4 events     `frame` if it changed, then rapid/feed/arc/…
//!                          (dog-legs of parameter 411, the G31 trigger);
//!                          a straight move that would not move is dropped
//! ```
//!
//! Each stage is its own module with a pure core ([`frame`], [`travel`]);
//! this file only wires them in that fixed order and keeps `State::pos`
//! (machine) and `State::prog` (program) in step. Arc geometry that the
//! program describes (centre from R or I/J/K, three points) is resolved in
//! program coordinates by [`arc`] before the move is committed.

pub(crate) mod arc;
pub(crate) mod comp;
pub(crate) mod line;
pub(crate) mod stage;
pub(crate) mod travel;

use crate::alarms;
use crate::config::Config;
use crate::dialect::ModeOp;
use crate::dialect::{GOp, RapidPath};
use crate::interpreter::Machining;
use crate::state::State;
use crate::state::frame::ArcMap;
use crate::words::Words;
use stage::Stage;
use vcnc_core::events::Loc;
use vcnc_core::events::{ArcDir, Event, Feed, Plane, Pos};
use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_syntax::{Diagnostic, Span};

/// Where a block's axis words point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Goal {
    /// The new programmed point, program coordinates.
    pub prog: Pos,
    /// Axes named (bit i = machine axis i).
    pub named: u32,
    /// The increment of the incremental axes, program coordinates.
    pub delta: Pos,
    /// Every named axis is incremental (and no polar input).
    pub all_incremental: bool,
}

/// Where a move ends.
///
/// Absolute and incremental moves differ once the frame has changed
/// without a move (a new G51, G68 or G51.1): an absolute point goes where
/// the frame puts it, an increment goes that far (transformed) from where
/// the tool is, as Fanuc does — the reason the Syntec manual (1.2.21) warns
/// that the absolute position and the machine part ways after a mirror is
/// cancelled away from its axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Target {
    /// An absolute program point: it goes through the frame.
    Program(Pos),
    /// An incremental move: the increment in program coordinates, added to
    /// the programmed point and, through the frame, to the machine point.
    Relative(Pos),
    /// A machine point (G53, the reference points): no frame.
    Machine(Pos),
}

/// What kind of path a move follows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum MoveKind {
    /// G00: interpolated, or a dog-leg under parameter 411 = 1.
    Rapid,
    /// A rapid that is always one straight line (the lathe cycles' returns,
    /// parallel to the cut they clear).
    StraightRapid,
    /// G01 (and cycle feeds).
    Feed(Feed),
    /// G02/G03: the centre as an offset from the start, program coordinates.
    Arc {
        offset: Pos,
        plane: Plane,
        cw: bool,
        feed: Feed,
    },
    /// G33 and the lathe's threads.
    Thread { lead_mm: f64 },
    /// G31: a feed that stops where the skip signal fires.
    Skip { feed: Feed },
}

/// One motion as the program asks for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Move {
    pub kind: MoveKind,
    pub to: Target,
    /// G09 in the block.
    pub exact_stop: bool,
    /// The command word (motion G word, else the block's first word).
    pub cmd: Span,
}

/// A motion in machine coordinates, after the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct MachineMove {
    pub kind: MachineKind,
    pub from: Pos,
    pub to: Pos,
    pub exact_stop: bool,
}

/// The kind of a machine move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum MachineKind {
    /// A rapid; `true` when it may dog-leg.
    Rapid(bool),
    Feed(Feed),
    Arc {
        /// Centre in the plane (first, second axis), machine coordinates.
        center: (f64, f64),
        plane: Plane,
        dir: ArcDir,
        feed: Feed,
    },
    Thread(f64),
    Skip(Feed),
}

impl MachineMove {
    /// The arc's path, if this move is an arc.
    pub fn arc_path(&self, axes: PlaneAxes) -> Option<ArcPath> {
        let MachineKind::Arc { center, dir, .. } = self.kind else {
            return None;
        };
        let mut c = self.from;
        c.set(axes.a, center.0);
        c.set(axes.b, center.1);
        Some(ArcPath::new(self.from, self.to, c, axes, dir))
    }
}

// Stage 1, the frame: where a move goes in machine coordinates, read from
// the state's frame and points alone.
impl State {
    /// Stage 1: the programmed end point of a move to `to`, and its end in
    /// machine coordinates.
    #[inline(always)]
    fn machine_target(&self, to: Target) -> (Pos, Pos) {
        let frame = &self.frame;
        match to {
            Target::Program(p) => (p, frame.machine_of(p)),
            Target::Relative(delta) => (
                self.prog.plus(delta),
                self.nominal.plus(frame.vector_to_machine(delta)),
            ),
            Target::Machine(m) => (frame.program_of(m), m),
        }
    }

    /// Stage 1: the path of a move in machine coordinates (an arc's centre
    /// from the uncompensated start, its direction under mirror).
    #[inline(always)]
    fn machine_kind(&self, cfg: &Config<'_>, mv: &Move) -> Result<MachineKind, Diagnostic> {
        Ok(match mv.kind {
            MoveKind::Rapid => MachineKind::Rapid(true),
            MoveKind::StraightRapid => MachineKind::Rapid(false),
            MoveKind::Feed(f) => MachineKind::Feed(f),
            MoveKind::Thread { lead_mm } => MachineKind::Thread(lead_mm),
            MoveKind::Skip { feed } => MachineKind::Skip(feed),
            MoveKind::Arc {
                offset,
                plane,
                cw,
                feed,
            } => self.machine_arc(cfg, offset, plane, cw, feed, mv.cmd)?,
        })
    }

    /// [`machine_kind`](Self::machine_kind) of an arc, out of line.
    #[inline(never)]
    fn machine_arc(
        &self,
        cfg: &Config<'_>,
        offset: Pos,
        plane: Plane,
        cw: bool,
        feed: Feed,
        cmd: Span,
    ) -> Result<MachineKind, Diagnostic> {
        let frame = &self.frame;
        let reversed = match frame.arc_map(plane) {
            ArcMap::Similar { reversed } => reversed,
            ArcMap::Uneven => return Err(alarms::arc_uneven_scale(cmd)),
            ArcMap::Tilted => return Err(alarms::arc_tilted(cmd)),
        };
        let axes = cfg.plane_axes(plane, cmd)?;
        let c = self.nominal.plus(frame.vector_to_machine(offset));
        Ok(MachineKind::Arc {
            center: (c.get(axes.a), c.get(axes.b)),
            plane,
            dir: if cw != reversed {
                ArcDir::Cw
            } else {
                ArcDir::Ccw
            },
            feed,
        })
    }
}

// Stages 1 (its bookkeeping) and 4, the events: the stage's own data
// (its events, the move count, the markers) written from the state and
// the configuration it is handed.
impl Stage {
    /// Queues an event of the block: behind a move cutter compensation
    /// still holds, else with the block's events.
    #[inline]
    pub fn emit(&mut self, e: Event) {
        if self.comp.holding() {
            self.comp.queue_event(e);
        } else {
            self.pending.push(e);
        }
    }

    /// The markers a consumer that writes program coordinates needs (the
    /// flattened program; with [`Interpreter::with_program_markers`]),
    /// before the move's events: `machine_move` before
    /// a move to a machine point, with the axes the block names (every axis
    /// when it names none: a bare G28); `placed` when the block names axes
    /// that no program-coordinate move has placed since power-on or since
    /// a machine move. Rare, so a plain move pays one test. Kept outside
    /// `State`: an alarm ends the run, so nothing needs undoing.
    #[cold]
    #[inline(never)]
    fn mark_axes(&mut self, cfg: &Config<'_>, loc: &Loc, (mv, to): (&Move, Pos), w: &Words<'_>) {
        let machine = matches!(mv.to, Target::Machine(_));
        if self.unplaced == 0 && !machine {
            return;
        }
        let bits = |named: bool| {
            cfg.axis_words
                .iter()
                .enumerate()
                .filter(|(_, a)| !named || w.any(a.mask))
                .fold(0u8, |m, (i, _)| m | 1u8 << i)
        };
        let named = bits(true);
        if machine {
            let axes = if named == 0 { bits(false) } else { named };
            self.unplaced |= axes;
            self.emit(Event::MachineMove {
                loc: loc.clone(),
                to,
                axes,
            });
        } else if named & self.unplaced != 0 {
            let axes = named & self.unplaced;
            self.unplaced &= !named;
            self.emit(Event::Placed {
                loc: loc.clone(),
                axes,
            });
        }
    }

    /// Stage 1's bookkeeping once a move is accepted: the programmed and
    /// nominal points move to its end, and the frame it uses is reported
    /// before it (also when it waits in the compensation stage).
    #[inline]
    fn accept_move(
        &mut self,
        s: &mut State,
        loc: &Loc,
        (prog_to, nominal): (Pos, Pos),
        to: Target,
    ) {
        self.moves += 1;
        s.prog = prog_to;
        s.nominal = nominal;
        if !matches!(to, Target::Relative(_)) {
            s.detached = false;
        }
        self.report_frame(s, loc);
    }

    /// Stage 4 of a checked move: its events, and the tool at its end
    /// (or where the skip signal stopped it).
    #[inline(always)]
    fn emit_released(&mut self, cfg: &Config<'_>, s: &mut State, mm: &MachineMove, loc: &Loc) {
        match self.emit_motion(cfg, &mut s.skip_pos, mm, loc) {
            None => s.pos = mm.to,
            Some(stop) => {
                // The skip signal stopped the move short.
                s.pos = stop;
                s.nominal = stop;
                s.prog = s.frame.program_of(stop);
                s.detached = false;
            }
        }
    }

    /// Emits a `frame` event if the frame changed since the last one.
    #[inline]
    pub fn report_frame(&mut self, s: &mut State, loc: &Loc) {
        if s.frame_dirty {
            self.report_changed_frame(s, loc);
        }
    }

    #[cold]
    fn report_changed_frame(&mut self, s: &mut State, loc: &Loc) {
        s.frame_dirty = false;
        let frame = s.frame_info();
        let print = crate::state::fingerprint(&frame);
        if print == s.reported {
            return;
        }
        s.reported = print;
        self.emit(Event::Frame {
            loc: loc.clone(),
            frame,
        });
    }

    /// Stage 4: the events of a machine move from the block at `loc`;
    /// returns where it stopped if that is not its end (a G31 whose skip
    /// signal fired).
    #[inline(always)]
    fn emit_motion(
        &mut self,
        cfg: &Config<'_>,
        skip_pos: &mut Option<Pos>,
        m: &MachineMove,
        loc: &Loc,
    ) -> Option<Pos> {
        if matches!(m.kind, MachineKind::Rapid(_) | MachineKind::Feed(_))
            && same_point(m.from, m.to)
        {
            // A straight move that would not move the machine (the second
            // leg of `G28 X0` from X0, `G91 G28 Z0`, a compensated feed
            // whose offset ends where it starts) is not reported: the one
            // place for every code, as the cycles' steps always were.
            return None;
        }
        let (exact_stop, to) = (m.exact_stop, m.to);
        let pending = &mut self.pending;
        match m.kind {
            MachineKind::Rapid(may_dog_leg) => {
                let legs = match cfg.dialect.rapid {
                    _ if !may_dog_leg => None,
                    RapidPath::ByParameter if cfg.machine.params.g00_mode == 1 => {
                        Some(line::dog_leg(cfg.machine, m.from, m.to))
                    }
                    RapidPath::ByParameter => None,
                    RapidPath::ZPriority => Some(line::z_priority(cfg.machine, m.from, m.to)),
                };
                if let Some((corners, count)) = legs {
                    for &to in &corners[..count] {
                        push_built(pending, || Event::Rapid {
                            loc: loc.clone(),
                            to,
                            exact_stop,
                        });
                    }
                } else {
                    push_built(pending, || Event::Rapid {
                        loc: loc.clone(),
                        to,
                        exact_stop,
                    });
                }
                None
            }
            MachineKind::Feed(feed) => {
                push_built(pending, || Event::Feed {
                    loc: loc.clone(),
                    to,
                    feed,
                    exact_stop,
                });
                None
            }
            MachineKind::Arc {
                center: (ca, cb),
                plane,
                dir,
                feed,
            } => {
                let [la, lb, _] = plane.letters();
                let mut center = m.from;
                if let (Some(a), Some(b)) = (cfg.machine.axis_of(la), cfg.machine.axis_of(lb)) {
                    center.set(a, ca);
                    center.set(b, cb);
                }
                push_built(pending, || Event::Arc {
                    loc: loc.clone(),
                    to,
                    center,
                    plane,
                    dir,
                    feed,
                    exact_stop,
                });
                None
            }
            MachineKind::Thread(lead_mm) => {
                push_built(pending, || Event::Thread {
                    loc: loc.clone(),
                    to,
                    lead_mm,
                });
                None
            }
            MachineKind::Skip(feed) => {
                let hit = line::skip_fraction(cfg.machine, m.from, m.to);
                let to = hit.map_or(m.to, |t| line::lerp(m.from, m.to, t));
                let triggered = hit.is_some();
                push_built(pending, || Event::Skip {
                    loc: loc.clone(),
                    to,
                    feed,
                    triggered,
                });
                *skip_pos = Some(to);
                hit.map(|_| to)
            }
        }
    }
}

/// Appends the event `make` builds, built in its slot: `Vec::push` builds
/// the 200-byte event aside and copies all of it (a call to `memcpy`, a
/// tenth of the interpreter's time on a plain cut) into a buffer the sink's
/// thread read last, where a cut's fields are half of it.
#[inline(always)]
fn push_built(pending: &mut Vec<Event>, make: impl FnOnce() -> Event) {
    pending.extend(std::iter::once_with(make));
}

/// Whether two machine points are the same: every axis within
/// [`vcnc_core::geometry::ZERO_MM`].
#[inline(always)]
fn same_point(a: Pos, b: Pos) -> bool {
    (0..vcnc_core::events::MAX_AXES)
        .all(|i| (a.get(i) - b.get(i)).abs() < vcnc_core::geometry::ZERO_MM)
}

impl<'a> Machining<'_, 'a> {
    /// Sends one move of the block `w` through the stages. Nothing is
    /// changed unless every stage accepts it (and the block as a whole).
    pub(crate) fn commit(&mut self, mv: Move, w: &Words<'_>) -> Result<(), Diagnostic> {
        if self.state.rpm <= 0.0 {
            // Once W104 is given only a per-revolution move needs a look.
            let per_rev = match mv.kind {
                MoveKind::Thread { .. } => true,
                MoveKind::Feed(f) | MoveKind::Arc { feed: f, .. } => {
                    matches!(f, Feed::PerRev(_))
                }
                _ => false,
            };
            if per_rev || !self.stage.spindle_warned {
                self.stopped_spindle(&mv, per_rev)?;
            }
        } else if let MoveKind::Thread { lead_mm } = mv.kind {
            // Syntec 1.2.17: 1 <= S <= maximum feed / lead.
            if self.state.rpm * lead_mm > self.cfg.max_feed {
                return Err(alarms::thread_too_fast(
                    mv.cmd,
                    self.state.rpm,
                    lead_mm,
                    self.cfg.max_feed,
                ));
            }
        }
        // 1 frame
        let cfg = self.cfg;
        let (prog_to, to) = self.state.machine_target(mv.to);
        let kind = self.state.machine_kind(cfg, &mv)?;
        // 2 compensation works from the uncompensated point, the rest
        // from where the tool is.
        let engaged = self.stage.comp.engaged();
        let mm = MachineMove {
            kind,
            from: if engaged {
                self.state.nominal
            } else {
                self.state.pos
            },
            to,
            exact_stop: mv.exact_stop,
        };
        if engaged {
            return self.commit_compensated(prog_to, mm, &mv, w);
        }
        // 3 travel, before anything changes: a move that leaves the
        // machine's limits leaves the state as the block found it (which a
        // plain move block relies on, see `Interpreter::block`).
        if cfg.travel_limited {
            cfg.travel_alarm(&mm, mv.cmd, Some(w))?;
        }
        // The stage's parts, held in locals for the rest of the way.
        let (state, stage, loc) = (&mut *self.state, &mut *self.stage, self.at.loc());
        stage.accept_move(state, loc, (prog_to, mm.to), mv.to);
        // 4 events
        if cfg.markers {
            stage.mark_axes(cfg, loc, (&mv, mm.to), w);
        }
        stage.emit_released(cfg, state, &mm, loc);
        Ok(())
    }

    /// Stage 2 and on for a move while compensation is engaged.
    #[inline(never)]
    fn commit_compensated(
        &mut self,
        prog_to: Pos,
        mm: MachineMove,
        mv: &Move,
        w: &Words<'_>,
    ) -> Result<(), Diagnostic> {
        self.stage
            .accept_move(self.state, self.at.loc(), (prog_to, mm.to), mv.to);
        if !matches!(mv.to, Target::Machine(_)) {
            if self.cfg.markers {
                self.stage
                    .mark_axes(self.cfg, self.at.loc(), (mv, mm.to), w);
            }
            return self.compensate(mm, mv.cmd);
        }
        // A move to a machine point (G28's second leg, G53) is not
        // compensated: the held move ends square to its path, and the
        // next move in the plane starts compensation again.
        self.comp_finish()?;
        if self.state.modal.comp != crate::state::CompSide::Off {
            self.stage.comp.mode = comp::Mode::Starting;
        }
        self.keep_programmed_plane(&mm, mv.cmd)?;
        let at = comp::Origin {
            loc: self.at.loc().clone(),
            src: 0,
            line: None,
            cmd: mv.cmd,
        };
        if self.cfg.markers {
            self.stage
                .mark_axes(self.cfg, self.at.loc(), (mv, mm.to), w);
        }
        self.release(mm, &at, Some(w))
    }

    /// A move with the spindle stopped: a thread or a feed per revolution
    /// cannot move at all (E342); another cut warns once (W104) until the
    /// spindle turns again.
    #[cold]
    fn stopped_spindle(&mut self, mv: &Move, per_rev: bool) -> Result<(), Diagnostic> {
        if per_rev {
            let per_minute = match mv.kind {
                MoveKind::Thread { .. } => None,
                _ => self.cfg.dialect.g_for(GOp::Mode(ModeOp::PerMinute)),
            };
            return Err(alarms::per_rev_spindle_stopped(mv.cmd, per_minute));
        }
        let cut = matches!(mv.kind, MoveKind::Feed(_) | MoveKind::Arc { .. });
        if cut && !self.stage.spindle_warned {
            self.stage.spindle_warned = true;
            self.warn(alarms::cut_spindle_stopped(mv.cmd));
        }
        Ok(())
    }

    /// Stage 3: the soft limits on the path the tool really follows (arcs
    /// included); an alarm points at the axis word of `w` when the move is
    /// the current block's, else at `at`'s command.
    fn check_travel(
        &mut self,
        mm: &MachineMove,
        at: &comp::Origin,
        w: Option<&Words<'_>>,
    ) -> Result<(), Diagnostic> {
        self.cfg
            .travel_alarm(mm, at.cmd, w)
            .map_err(|d| match at.line {
                Some(line) => self.at.locate(d, at.src, &line),
                None => d,
            })
    }

    /// Stages 3 and 4: the travel check and the events of a machine move,
    /// from where the tool is. A travel alarm points at the axis word of
    /// `w` when the move is the current block's, else at `at`'s command.
    /// One copy out of line: the compensation stage calls it from many
    /// places, and inlined copies would crowd the instruction cache.
    #[inline(never)]
    pub(crate) fn release(
        &mut self,
        mm: MachineMove,
        at: &comp::Origin,
        w: Option<&Words<'_>>,
    ) -> Result<(), Diagnostic> {
        let mm = MachineMove {
            from: self.state.pos,
            ..mm
        };
        // 3 travel: nothing to check on a machine without limits.
        if self.cfg.travel_limited {
            self.check_travel(&mm, at, w)?;
        }
        self.report_frame();
        self.stage.emit_released(self.cfg, self.state, &mm, &at.loc);
        Ok(())
    }

    /// Emits a `frame` event if the frame changed since the last one.
    #[inline]
    pub(crate) fn report_frame(&mut self) {
        self.stage.report_frame(self.state, self.at.loc());
    }
}
