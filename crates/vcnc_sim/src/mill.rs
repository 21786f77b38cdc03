//! Milling: moves become Z-map cuts in batches, chains of flat-end-mill
//! feeds skip the discs their neighbours cover, and what each move did
//! becomes collisions and cutting-time statistics.
//!
//! ## Chains (why a move may skip a disc at one of its ends)
//!
//! A flat end mill's bottom over a cell along a straight move is the
//! tip's height where the tool last (going down) or first (going up)
//! covers the cell. Along a chain of such moves A→B→C…, the lowest the
//! tool gets over a cell is therefore reached where the tool's edge
//! leaves the cell on a descending move, enters it on an ascending one, or
//! at a vertex that is a valley of the chain (or one of its ends):
//!
//! ```text
//!   descending  A ●━━━━━● B   band: capsule minus the disc at B (the
//!   level            ╲         tool there is lowered by what follows)
//!   ascending   A ●━━━━━● B   band: capsule minus the disc at A
//!   vertex disc at P: only when the move into P skips its end disc and
//!   the move out of P skips its start disc (a valley), and at a chain's
//!   ends when their move skips them
//! ```
//!
//! Every cut still computes the exact envelope over the cells it visits,
//! so skipping is only ever a saving, and the property test
//! (`tests/reference.rs`) holds the whole against a dense reference.
//! A plunge (more down than across) is never part of a chain, so its
//! removal and the checks on it stay on its own line.

use crate::kernel::Line;
use crate::motion::{Motion, Path};
use crate::report::{Collision, CollisionKind, Report};
use crate::tool::Cutter;
use crate::zmap::{CUT_EPS_MM, Cut, Hit, Shape, ZMap, is_flat};
use vcnc_core::Loc;

/// Cuts applied at once (each worker takes every one of them).
const BATCH: usize = 2048;

/// Deeper than this, a rapid is in the stock, mm.
pub const RAPID_DEPTH_MM: f64 = 0.01;

/// What the report needs of a move once its cuts are applied.
#[derive(Debug, Clone)]
struct Meta {
    loc: Loc,
    rapid: bool,
    seconds: f64,
    end: [f64; 3],
    min_z: f64,
    hit: Hit,
}

/// A chain move waiting for the move after it.
#[derive(Debug, Clone, Copy)]
struct Held {
    cut: Cut,
    meta: usize,
    /// Whether its end disc is left to its neighbours.
    skips_end: bool,
}

/// The milling engine.
#[derive(Debug)]
pub struct Mill {
    /// The stock.
    pub map: ZMap,
    /// Work origin in tip coordinates (messages are in work coordinates).
    pub origin: [f64; 3],
    cuts: Vec<Cut>,
    owner: Vec<usize>,
    metas: Vec<Meta>,
    hits: Vec<Hit>,
    held: Option<Held>,
}

/// Whether `cut` of a move may join a chain: a straight feed of a flat
/// end mill that moves at least as far across as down.
fn chainable(path: &Path, cutter: &Cutter, rapid: bool) -> Option<Line> {
    let Path::Line(l) = path else { return None };
    let across = (l.b[0] - l.a[0]).hypot(l.b[1] - l.a[1]);
    let down = (l.b[2] - l.a[2]).abs();
    (!rapid && is_flat(cutter) && across > 1e-9 && across >= down).then_some(*l)
}

impl Mill {
    /// A milling engine on `map`.
    pub fn new(map: ZMap, origin: [f64; 3]) -> Mill {
        Mill {
            map,
            origin,
            cuts: Vec::with_capacity(BATCH + 8),
            owner: Vec::with_capacity(BATCH + 8),
            metas: Vec::new(),
            hits: Vec::new(),
            held: None,
        }
    }

    fn push(&mut self, cut: Cut, meta: usize) {
        self.cuts.push(cut);
        self.owner.push(meta);
    }

    /// A tool standing at `p` (a vertex of a chain).
    fn disc(p: [f64; 3], cutter: u8) -> Cut {
        Cut {
            shape: Shape::Line(Line { a: p, b: p }),
            cutter,
            skip_start: false,
            skip_end: false,
            check_centre: false,
        }
    }

    /// Lets the held chain move go: its end disc too when nothing after it
    /// continues the chain (`next_skips_start`: what the move after it
    /// does at their shared vertex, `None` when it does not continue).
    fn release(&mut self, next_skips_start: Option<bool>) {
        if let Some(h) = self.held.take() {
            self.push(h.cut, h.meta);
            if h.skips_end && next_skips_start != Some(false) {
                self.push(Self::disc(h.cut.shape.end(), h.cut.cutter), h.meta);
            }
        }
    }

    /// Adds a move cut by `cutters[cutter]`; applies a batch when one is
    /// full.
    pub fn add(&mut self, m: &Motion, cutter: u8, cutters: &[Cutter], report: &mut Report) {
        let Some(c) = cutters.get(usize::from(cutter)) else {
            return;
        };
        let meta = self.metas.len();
        self.metas.push(Meta {
            loc: m.loc.clone(),
            rapid: m.rapid,
            seconds: m.seconds,
            end: m.path.end(),
            min_z: m.path.min_z(),
            hit: Hit::default(),
        });
        let plunge = c.center_cutting == Some(false) && !m.rapid && plunges(&m.path);
        if let Some(line) = chainable(&m.path, c, m.rapid) {
            let ascending = line.b[2] > line.a[2];
            let cut = Cut {
                shape: Shape::Line(line),
                cutter,
                skip_start: ascending,
                skip_end: !ascending,
                check_centre: plunge,
            };
            let continues = self
                .held
                .is_some_and(|h| h.cut.cutter == cutter && h.cut.shape.end() == line.a);
            if continues {
                // The shared vertex needs its own disc only in a valley.
                let valley = self.held.is_some_and(|h| h.skips_end) && ascending;
                if let Some(h) = self.held.take() {
                    self.push(h.cut, h.meta);
                    if valley {
                        self.push(Self::disc(line.a, cutter), h.meta);
                    }
                }
            } else {
                self.release(None);
                if ascending {
                    self.push(Self::disc(line.a, cutter), meta);
                }
            }
            self.held = Some(Held {
                cut,
                meta,
                skips_end: !ascending,
            });
        } else {
            self.release(None);
            let whole = |shape| Cut {
                shape,
                cutter,
                skip_start: false,
                skip_end: false,
                check_centre: false,
            };
            match &m.path {
                Path::Line(l) => self.push(
                    Cut {
                        check_centre: plunge,
                        ..whole(Shape::Line(*l))
                    },
                    meta,
                ),
                Path::Arc(a) => self.push(whole(Shape::Arc(*a)), meta),
                Path::Chords { .. } => {
                    for l in m.path.lines() {
                        self.push(whole(Shape::Line(l)), meta);
                    }
                }
            }
        }
        if self.cuts.len() >= BATCH {
            self.apply(cutters, report);
        }
    }

    /// Applies the cuts gathered so far and reports the moves they finish
    /// (`all`: the held chain move too, at the end of the run).
    pub fn flush(&mut self, cutters: &[Cutter], report: &mut Report, all: bool) {
        if all {
            self.release(None);
        }
        self.apply(cutters, report);
    }

    fn apply(&mut self, cutters: &[Cutter], report: &mut Report) {
        self.map.apply(&self.cuts, cutters, &mut self.hits);
        for (hit, owner) in self.hits.iter().zip(&self.owner) {
            if let Some(m) = self.metas.get_mut(*owner) {
                merge(&mut m.hit, hit);
            }
        }
        self.cuts.clear();
        self.owner.clear();
        // Every move but the held one is complete.
        let keep = self.held.map(|h| h.meta);
        let metas = std::mem::take(&mut self.metas);
        for (k, m) in metas.into_iter().enumerate() {
            if Some(k) == keep {
                self.metas.push(m);
            } else {
                self.retire(&m, report);
            }
        }
        if let Some(h) = &mut self.held {
            h.meta = 0;
        }
    }

    /// Work coordinates of a cell at height `z`.
    fn work(&self, (i, j): (u32, u32), z: f64) -> [f64; 3] {
        let (x, y) = self.map.centre(i as usize, j as usize);
        [x - self.origin[0], y - self.origin[1], z - self.origin[2]]
    }

    fn retire(&self, m: &Meta, report: &mut Report) {
        let h = &m.hit;
        let depth = f64::from(h.depth_mm);
        let end = [
            m.end[0] - self.origin[0],
            m.end[1] - self.origin[1],
            m.end[2] - self.origin[2],
        ];
        let mut collide = |kind, message: String, at| {
            report.collide(Collision {
                line: m.loc.line,
                file: m.loc.file.clone(),
                kind,
                message,
                at,
                repeats: 0,
            });
        };
        if m.rapid && depth > RAPID_DEPTH_MM {
            collide(
                CollisionKind::RapidIntoStock,
                format!("a rapid cuts {depth:.3} mm into the stock"),
                self.work(h.at, m.min_z),
            );
        }
        if h.shank_mm > 0.0 || h.holder_mm > 0.0 {
            let (what, by, reach) = if h.holder_mm > 0.0 {
                ("holder", h.holder_mm, "the tool sticks out of its holder")
            } else {
                ("shank", h.shank_mm, "the flutes reach")
            };
            collide(
                CollisionKind::HolderIntoStock,
                format!(
                    "the {what} runs {by:.3} mm into the stock (the cut is deeper than {reach})"
                ),
                end,
            );
        }
        if h.below {
            collide(
                CollisionKind::BelowStock,
                "the tool cuts through the bottom of the stock".to_string(),
                self.work(h.at, m.min_z),
            );
        }
        if h.centre {
            collide(
                CollisionKind::NonCenterCuttingPlunge,
                "a tool that does not cut at its centre plunges into material".to_string(),
                end,
            );
        }
        if !m.rapid {
            if depth > CUT_EPS_MM {
                report.cutting_s += m.seconds;
            } else {
                report.air_cut_s += m.seconds;
            }
        }
    }
}

fn merge(into: &mut Hit, h: &Hit) {
    if h.depth_mm > into.depth_mm {
        into.depth_mm = h.depth_mm;
        into.at = h.at;
    }
    into.below |= h.below;
    into.shank_mm = into.shank_mm.max(h.shank_mm);
    into.holder_mm = into.holder_mm.max(h.holder_mm);
    into.centre |= h.centre;
}

/// A straight move that goes down more than across.
fn plunges(path: &Path) -> bool {
    match path {
        Path::Line(l) => {
            let across = (l.b[0] - l.a[0]).hypot(l.b[1] - l.a[1]);
            let down = l.a[2] - l.b[2];
            down > 1e-6 && across < down
        }
        _ => false,
    }
}
