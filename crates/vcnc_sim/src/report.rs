//! What a simulation found: volumes, the time spent cutting air, and the
//! collisions, each located at the block that caused it.

use std::sync::Arc;

/// The kind of a collision (its `kind` in JSON).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum CollisionKind {
    /// A rapid that removes material more than 0.01 mm deep.
    RapidIntoStock,
    /// The shank or the holder touches the stock.
    HolderIntoStock,
    /// Removal through the bottom of the stock.
    BelowStock,
    /// The tool reaches the machine table (`table_z_mm`).
    Fixture,
    /// A tool that does not cut at its centre plunges into material.
    NonCenterCuttingPlunge,
}

impl CollisionKind {
    /// `rapid_into_stock`, …
    pub fn as_str(self) -> &'static str {
        match self {
            CollisionKind::RapidIntoStock => "rapid_into_stock",
            CollisionKind::HolderIntoStock => "holder_into_stock",
            CollisionKind::BelowStock => "below_stock",
            CollisionKind::Fixture => "fixture",
            CollisionKind::NonCenterCuttingPlunge => "non_center_cutting_plunge",
        }
    }
}

/// One collision.
#[derive(Debug, Clone, PartialEq)]
pub struct Collision {
    /// The block's line.
    pub line: u64,
    /// Its file, when not the main program.
    pub file: Option<Arc<str>>,
    /// What happened.
    pub kind: CollisionKind,
    /// Said for people.
    pub message: String,
    /// Where, work coordinates (x, y, z), mm.
    pub at: [f64; 3],
    /// How many moves of the same block did the same (one is reported).
    pub repeats: u64,
}

/// Most collisions kept; the rest are counted.
pub const MAX_COLLISIONS: usize = 1000;

/// The result of a simulation.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Report {
    /// The stock as used, said for people.
    pub stock: String,
    /// The stock's volume, mm³.
    pub stock_mm3: f64,
    /// The volume removed, mm³.
    pub removed_mm3: f64,
    /// Time at feed in moves that removed nothing, s.
    pub air_cut_s: f64,
    /// Time at feed in moves that cut, s.
    pub cutting_s: f64,
    /// The Z-map's cell size, mm (`None` on a lathe).
    pub resolution_mm: Option<f64>,
    /// The Z-map's cells along X and Y.
    pub grid: Option<(usize, usize)>,
    /// Collisions, in program order, at most [`MAX_COLLISIONS`].
    pub collisions: Vec<Collision>,
    /// All collisions found (repeats folded), including those not kept.
    pub collision_total: u64,
    /// Moves with rotary axes, not simulated.
    pub not_simulated: u64,
    /// The first of them.
    pub first_not_simulated: Option<(u64, Option<Arc<str>>)>,
    /// Moves simulated.
    pub moves: u64,
    /// Notes for people (assumed tools, the grid's size).
    pub notes: Vec<String>,
}

impl Report {
    /// Records a collision, folding repeats of the same block and kind.
    pub fn collide(&mut self, c: Collision) {
        if let Some(last) = self
            .collisions
            .iter_mut()
            .rev()
            .take(8)
            .find(|o| o.kind == c.kind && o.line == c.line && o.file == c.file)
        {
            last.repeats += 1;
            return;
        }
        self.collision_total += 1;
        if self.collisions.len() < MAX_COLLISIONS {
            self.collisions.push(c);
        }
    }
}
