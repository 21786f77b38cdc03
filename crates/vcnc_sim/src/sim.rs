//! The simulation as a [`Sink`]: follows the events, places the stock at
//! the first cut, feeds every move to the milling Z-map or the lathe
//! section, and checks what needs no stock (the table, rotary axes).
//!
//! ```text
//!   events ─▶ Tracker ─▶ Motion ─┬─ before the first cut: held (≤ 65,536)
//!                                ├─ Mill: ZMap cuts in batches (rayon)
//!                                └─ Lathe: Section polygons
//!   finish ─▶ Finished { report, part }  ─▶ STL · PNG · page
//! ```
//!
//! The stock is given in work coordinates, and a program sets its work
//! offset before it cuts but not always before it moves: moves before the
//! first cutting move wait (bounded) until it comes, and the stock is
//! placed with the work origin in force then.

use crate::lathe::Section;
use crate::mill::Mill;
use crate::motion::{Motion, Tracker};
use crate::replay::Replay;
use crate::report::{Collision, CollisionKind, Report};
use crate::stock::{StockOrigin, StockSpec, fmt};
use crate::tool::{Cutter, Insert};
use crate::zmap::ZMap;
use std::collections::BTreeMap;
use vcnc_core::{Event, Machine, Sink, ToolLibrary, ToolShape, ToolSource};

/// Moves held before the first cut.
const MAX_HELD: usize = 1 << 16;

/// The default cell size, mm.
pub const DEFAULT_RESOLUTION_MM: f64 = 0.1;

/// Cells along the longer side past which the default grid coarsens.
pub const DEFAULT_MAX_CELLS_ACROSS: f64 = 4000.0;

/// What to simulate and how.
#[derive(Debug, Clone)]
pub struct SimOptions {
    /// The stock, work coordinates (`Auto` must be resolved by a
    /// [`crate::Survey`] first).
    pub stock: StockSpec,
    /// Where it came from.
    pub stock_origin: StockOrigin,
    /// Cell size of the Z-map (`None`: [`DEFAULT_RESOLUTION_MM`], or the
    /// longer side / 4000 on large parts).
    pub resolution_mm: Option<f64>,
    /// Turning (X is the radius): the lathe engine.
    pub lathe: bool,
    /// Threads applying cuts.
    pub workers: usize,
    /// Record this many replay frames over `total_moves` moves.
    pub replay: Option<(u32, u64)>,
}

/// The tools of a run: the library's shapes as cutters, an assumed flat
/// end mill (on a lathe a sharp insert) for a tool nobody describes (said
/// in the report's notes).
#[derive(Debug, Clone)]
pub struct Tools {
    library: ToolLibrary,
    /// Cutters in the order first used.
    pub cutters: Vec<Cutter>,
    /// Inserts (lathe), same order.
    pub inserts: Vec<Insert>,
    index: BTreeMap<Option<u32>, u8>,
    /// One line per assumed tool.
    pub notes: Vec<String>,
    /// A lathe's: an undescribed tool is a sharp insert, not a mill.
    lathe: bool,
}

impl Tools {
    /// The tools `library` describes, on a lathe or a mill.
    pub fn new(library: &ToolLibrary, lathe: bool) -> Tools {
        Tools {
            library: library.clone(),
            cutters: Vec::new(),
            inserts: Vec::new(),
            index: BTreeMap::new(),
            notes: Vec::new(),
            lathe,
        }
    }

    /// The index of the cutter for `tool` (the spindle's), added on first
    /// use; at most 255 tools are told apart (later ones share the last).
    pub fn index(&mut self, tool: Option<u32>) -> u8 {
        if let Some(i) = self.index.get(&tool) {
            return *i;
        }
        let Ok(i) = u8::try_from(self.cutters.len()) else {
            return u8::MAX;
        };
        let number = tool.unwrap_or(0);
        let shape = match self.library.get(number) {
            Some(s) => s.clone(),
            None if self.lathe => ToolShape {
                kind: vcnc_core::ToolKind::Turning {
                    nose_radius_mm: 0.0,
                    tip: 0,
                },
                diameter_mm: 0.0,
                ..ToolShape::assumed(number)
            },
            None => ToolShape::assumed(number),
        };
        if shape.source == ToolSource::Assumed {
            let as_what = if self.lathe {
                "a sharp insert (no nose radius)".to_string()
            } else {
                format!("a {} mm flat end mill", shape.diameter_mm)
            };
            self.notes.push(match tool {
                Some(t) => format!(
                    "T{t} is not described (no tool table entry, no D register, no nose radius): cut as {as_what}"
                ),
                None => format!("no tool is selected before the first move: cut as {as_what}"),
            });
        }
        self.cutters.push(Cutter::from_shape(&shape));
        self.inserts.push(Insert::from_shape(&shape));
        self.index.insert(tool, i);
        i
    }
}

/// The stock as placed: machine-fixed tip coordinates.
#[derive(Debug)]
enum Engine {
    /// Before the first cut: moves waiting for the stock.
    Waiting(Vec<Motion>),
    /// Milling.
    Mill(Mill),
    /// Turning.
    Lathe(Section),
    /// Nothing to simulate (no stock could be placed).
    Off,
}

/// The finished part.
#[derive(Debug)]
pub enum Part {
    /// The milled stock.
    Mill(ZMap, [f64; 3]),
    /// The turned section.
    Lathe(Section),
    /// Nothing was simulated.
    Empty,
}

/// A simulation's outcome: the report, the part and its replay.
#[derive(Debug)]
pub struct Finished {
    /// Volumes, air time, collisions.
    pub report: Report,
    /// The finished part.
    pub part: Part,
    /// Frames of the replay, when asked for.
    pub replay: Option<Replay>,
    /// The tools used, in first-use order.
    pub tools: Tools,
}

/// The simulation sink.
#[derive(Debug)]
pub struct Simulation {
    tracker: Tracker,
    options: SimOptions,
    table_z_mm: Option<f64>,
    tools: Tools,
    engine: Engine,
    report: Report,
    replay: Option<Replay>,
    moves: u64,
    error: Option<String>,
}

/// The Z-map's cell size for a stock of `w` × `d` mm.
pub fn resolution_for(w: f64, d: f64, asked: Option<f64>) -> f64 {
    asked.unwrap_or_else(|| DEFAULT_RESOLUTION_MM.max(w.max(d) / DEFAULT_MAX_CELLS_ACROSS))
}

/// Checks a stock and a resolution before any run: an empty or inverted
/// stock, a resolution that is not a positive length, or a grid past the
/// memory bound are errors.
pub fn check_setup(stock: &StockSpec, resolution: Option<f64>, lathe: bool) -> Result<(), String> {
    stock.check()?;
    if let Some(r) = resolution
        && !(r.is_finite() && r > 0.0)
    {
        return Err(format!(
            "--resolution {r}: give a cell size in mm, more than 0"
        ));
    }
    match stock {
        StockSpec::Box { min, max } if !lathe => {
            let (w, d) = (max[0] - min[0], max[1] - min[1]);
            let r = resolution_for(w, d, resolution);
            ZMap::new((0.0, 0.0, w, d), (0.0, 1.0), r, 1).map(|_| ())
        }
        StockSpec::Bar { .. } if lathe => Ok(()),
        StockSpec::Box { .. } => Err("a lathe turns a bar: give --stock bar:D,L[,bore]".into()),
        StockSpec::Bar { .. } => {
            Err("a mill cuts a block: give --stock box:x0,y0,z0,x1,y1,z1".into())
        }
        // What a survey found no cuts for: nothing to simulate.
        StockSpec::Auto => Ok(()),
    }
}

impl Simulation {
    /// A simulation on `machine` with the tools `library` describes.
    /// `table_z_mm` is the machine table's height (machine Z of the tip).
    pub fn new(
        machine: &Machine,
        library: &ToolLibrary,
        table_z_mm: Option<f64>,
        options: SimOptions,
    ) -> Result<Simulation, String> {
        check_setup(&options.stock, options.resolution_mm, options.lathe)?;
        let replay = options
            .replay
            .map(|(frames, total)| Replay::new(frames, total));
        Ok(Simulation {
            tracker: Tracker::new(machine),
            table_z_mm,
            tools: Tools::new(library, options.lathe),
            engine: Engine::Waiting(Vec::new()),
            report: Report::default(),
            replay,
            moves: 0,
            error: None,
            options,
        })
    }

    /// Places the stock with the work origin in force now.
    fn place(&mut self) {
        let origin = self.tracker.origin();
        let held = match std::mem::replace(&mut self.engine, Engine::Off) {
            Engine::Waiting(h) => h,
            other => {
                self.engine = other;
                return;
            }
        };
        let workers = self.options.workers.max(1);
        let engine = match &self.options.stock {
            StockSpec::Box { min, max } if !self.options.lathe => {
                let (w, d) = (max[0] - min[0], max[1] - min[1]);
                let res = resolution_for(w, d, self.options.resolution_mm);
                let rect = (
                    min[0] + origin[0],
                    min[1] + origin[1],
                    max[0] + origin[0],
                    max[1] + origin[1],
                );
                match ZMap::new(rect, (min[2] + origin[2], max[2] + origin[2]), res, workers) {
                    Ok(map) => {
                        self.report.resolution_mm = Some(map.dx.max(map.dy));
                        self.report.grid = Some((map.nx, map.ny));
                        Engine::Mill(Mill::new(map, origin))
                    }
                    Err(e) => {
                        self.error = Some(e);
                        Engine::Off
                    }
                }
            }
            StockSpec::Bar {
                diameter,
                length,
                bore,
            } if self.options.lathe => Engine::Lathe(Section::bar(
                origin[0], origin[2], origin[2], *length, *diameter, *bore,
            )),
            _ => Engine::Off,
        };
        self.report.stock = match (&self.options.stock, &engine) {
            (StockSpec::Auto, _) => "none: the program has no cutting moves".to_string(),
            _ => describe(&self.options),
        };
        self.engine = engine;
        for m in held {
            self.simulate(&m);
        }
    }

    fn simulate(&mut self, m: &Motion) {
        // Rapids before any tool is in the spindle (G28, the approach to the
        // tool change) cut nothing; a cut without a tool is made by the
        // assumed one.
        if m.tool.is_none() && m.rapid {
            return;
        }
        let tool = self.tools.index(m.tool);
        match &mut self.engine {
            Engine::Mill(mill) => mill.add(m, tool, &self.tools.cutters, &mut self.report),
            Engine::Lathe(section) => {
                if let Some(insert) = self.tools.inserts.get(usize::from(tool)) {
                    section.add(m, insert, &mut self.report);
                }
            }
            Engine::Waiting(_) | Engine::Off => {}
        }
        self.moves += 1;
        if let Some(replay) = &mut self.replay
            && replay.due(self.moves)
        {
            if let Engine::Mill(mill) = &mut self.engine {
                mill.flush(&self.tools.cutters, &mut self.report, true);
            }
            match &self.engine {
                Engine::Mill(mill) => replay.record_map(&mill.map, m.loc.line),
                Engine::Lathe(s) => replay.record_section(s, m.loc.line),
                _ => {}
            }
        }
    }

    fn motion(&mut self, m: Motion) {
        if m.rotary {
            self.report.not_simulated += 1;
            if self.report.first_not_simulated.is_none() {
                self.report.first_not_simulated = Some((m.loc.line, m.loc.file.clone()));
            }
            return;
        }
        self.report.moves += 1;
        if let Some(table) = self.table_z_mm {
            self.fixture(&m, table);
        }
        let cutting = !m.rapid;
        if let Engine::Waiting(held) = &mut self.engine {
            if !cutting && held.len() < MAX_HELD {
                held.push(m);
                return;
            }
            held.push(m);
            self.place();
            return;
        }
        self.simulate(&m);
    }

    /// The tip reaches the machine table.
    fn fixture(&mut self, m: &Motion, table: f64) {
        // A move that ends on the table, or dips to it between its ends;
        // not the move that leaves it.
        let (start, end, low) = (m.path.start()[2], m.path.end()[2], m.path.min_z());
        let dips = low < start.min(end) - 1e-9;
        if !self.options.lathe && (end <= table || (dips && low <= table)) {
            let o = self.tracker.origin();
            let e = m.path.end();
            self.report.collide(Collision {
                line: m.loc.line,
                file: m.loc.file.clone(),
                kind: CollisionKind::Fixture,
                message: format!(
                    "the tool reaches the machine table (machine Z {} at the tip, table at {})",
                    fmt(low),
                    fmt(table)
                ),
                at: [e[0] - o[0], e[1] - o[1], e[2] - o[2]],
                repeats: 0,
            });
        }
    }

    /// Ends the simulation: applies what is pending and measures the part.
    pub fn finish_run(mut self) -> Result<Finished, String> {
        if let Engine::Waiting(_) = self.engine {
            self.place();
        }
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let part = match std::mem::replace(&mut self.engine, Engine::Off) {
            Engine::Mill(mut mill) => {
                mill.flush(&self.tools.cutters, &mut self.report, true);
                self.report.stock_mm3 = mill.map.stock_mm3();
                self.report.removed_mm3 = mill.map.removed_mm3();
                if let Some(r) = &mut self.replay {
                    r.record_map(&mill.map, 0);
                }
                Part::Mill(mill.map, mill.origin)
            }
            Engine::Lathe(s) => {
                self.report.stock_mm3 = s.stock_mm3;
                self.report.removed_mm3 = s.removed_mm3();
                if let Some(r) = &mut self.replay {
                    r.record_section(&s, 0);
                }
                Part::Lathe(s)
            }
            Engine::Waiting(_) | Engine::Off => Part::Empty,
        };
        self.report.notes.append(&mut self.tools.notes.clone());
        Ok(Finished {
            report: self.report,
            part,
            replay: self.replay,
            tools: self.tools,
        })
    }
}

fn describe(o: &SimOptions) -> String {
    let from = match &o.stock_origin {
        StockOrigin::Option => "--stock".to_string(),
        StockOrigin::Header { line, post } => format!("{post} header comment, line {line}"),
        StockOrigin::Auto => "auto: the cuts' extents".to_string(),
    };
    format!("{} (work mm; {from})", o.stock.describe())
}

impl Sink for Simulation {
    fn event(&mut self, e: &Event) {
        if self.error.is_some() {
            return;
        }
        if let Some(m) = self.tracker.event(e) {
            self.motion(m);
        }
    }

    fn is_done(&self) -> bool {
        self.error.is_some()
    }
}
