//! A first pass over the events for `--stock auto`: where the program
//! cuts, with which tools, and how many moves it makes (the replay's
//! frame spacing).
//!
//! The automatic stock of a mill is the cutting moves' XY extents grown
//! by their tools' radii, its top at work Z0 or the highest level a cut
//! moves across at (a program that faces from above zero), its bottom
//! 1 mm under the deepest cut. A lathe's is a bar as wide as the largest
//! radius a cut reaches, from Z0 (or the highest Z a cut moves across X
//! at) to 1 mm past the deepest cut. Work coordinates are those of the
//! first cutting move, as the simulation places stock.

use crate::motion::{Motion, Path, Tracker};
use crate::sim::Tools;
use crate::stock::StockSpec;
use vcnc_core::{Event, Machine, Sink, ToolLibrary};

/// The survey sink.
#[derive(Debug)]
pub struct Survey {
    tracker: Tracker,
    tools: Tools,
    lathe: bool,
    origin: Option<[f64; 3]>,
    /// (x0, y0, z0, x1, y1, z1) of cutting tips, grown by the tool radius
    /// in XY (tip coordinates).
    extents: Option<[f64; 6]>,
    /// Highest tip Z of a cut that moves across.
    across_top: f64,
    /// Moves seen.
    pub moves: u64,
}

impl Survey {
    /// A survey on `machine` with `library`'s tools.
    pub fn new(machine: &Machine, library: &ToolLibrary, lathe: bool) -> Survey {
        Survey {
            tracker: Tracker::new(machine),
            tools: Tools::new(library, lathe),
            lathe,
            origin: None,
            extents: None,
            across_top: f64::NEG_INFINITY,
            moves: 0,
        }
    }

    fn points(m: &Motion) -> Vec<[f64; 3]> {
        match &m.path {
            Path::Line(l) => vec![l.a, l.b],
            Path::Arc(a) => (0..=64).map(|k| a.point_at(f64::from(k) / 64.0)).collect(),
            Path::Chords { from, points } => std::iter::once(*from)
                .chain(points.iter().copied())
                .collect(),
        }
    }

    fn motion(&mut self, m: &Motion) {
        self.moves += 1;
        if m.rapid || m.rotary {
            return;
        }
        if self.origin.is_none() {
            self.origin = Some(self.tracker.origin());
        }
        let i = usize::from(self.tools.index(m.tool));
        let grow = if self.lathe {
            0.0
        } else {
            self.tools.cutters.get(i).map_or(3.0, |c| c.radius)
        };
        let pts = Self::points(m);
        let (s, e) = (m.path.start(), m.path.end());
        // Moving across: XY on a mill, X (the radius) on a lathe.
        let across = if self.lathe {
            (e[0] - s[0]).abs() > 1e-6
        } else {
            (e[0] - s[0]).hypot(e[1] - s[1]) > 1e-6 || matches!(m.path, Path::Arc(_))
        };
        for p in &pts {
            let b = self.extents.get_or_insert([
                p[0] - grow,
                p[1] - grow,
                p[2],
                p[0] + grow,
                p[1] + grow,
                p[2],
            ]);
            *b = [
                b[0].min(p[0] - grow),
                b[1].min(p[1] - grow),
                b[2].min(p[2]),
                b[3].max(p[0] + grow),
                b[4].max(p[1] + grow),
                b[5].max(p[2]),
            ];
            if across {
                self.across_top = self.across_top.max(p[2]);
            }
        }
    }

    /// The automatic stock in work coordinates, `None` when nothing cuts.
    pub fn stock(&self) -> Option<StockSpec> {
        let (o, b) = (self.origin?, self.extents?);
        let top = (self.across_top - o[2]).max(0.0);
        let bottom = b[2] - o[2] - 1.0;
        if self.lathe {
            // A bar runs from Z0 (its face) back past the deepest cut.
            let spec = StockSpec::Bar {
                diameter: 2.0 * (b[3] - o[0]),
                length: -bottom,
                bore: 0.0,
            };
            return spec.check().ok().map(|()| spec);
        }
        let spec = StockSpec::Box {
            min: [b[0] - o[0], b[1] - o[1], bottom.min(top - 1.0)],
            max: [b[3] - o[0], b[4] - o[1], top],
        };
        spec.check().ok().map(|()| spec)
    }
}

impl Sink for Survey {
    fn event(&mut self, e: &Event) {
        if let Some(m) = self.tracker.event(e) {
            self.motion(&m);
        }
    }
}
