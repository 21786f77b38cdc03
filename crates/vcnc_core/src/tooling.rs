//! What the tools look like: each tool's cutting shape and sizes, and where
//! those figures came from.
//!
//! The machine's tool table ([`crate::machine::Tool`]) holds offset
//! registers: the H length and D radius a program's G43 and G41 read. This
//! module holds what those registers do not say: whether tool 3 is a ball
//! or a drill, how long its flutes are, how wide its holder is. Plots draw
//! tools to size with it and the material-removal simulation cuts with it.
//!
//! A [`ToolLibrary`] is filled from a tool table file given by the user
//! (`--tools`: LinuxCNC `.tbl` or CSV) or, failing that, from the tool
//! descriptions CAM posts write in a program's header comments. Each tool
//! remembers its [`ToolSource`], so that `vcnc tools` can say where every
//! figure came from. Header comments never fill D registers: a program may
//! be written for wear compensation, where D holds only the wear.
//!
//! Lengths are mm, angles degrees.

use std::collections::BTreeMap;

/// The cutting shape of a tool.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ToolKind {
    /// A flat end mill.
    Flat,
    /// A ball-nose end mill (corner radius = half the diameter).
    Ball,
    /// A bull-nose end mill: a flat bottom with rounded corners.
    Bull {
        /// The corner radius, mm.
        corner_radius_mm: f64,
    },
    /// A drill: a cone of the point angle at the tip.
    Drill {
        /// The included point angle, degrees (118° for a jobber drill).
        point_angle_deg: f64,
    },
    /// A chamfer, spot or engraving V cutter.
    Vee {
        /// The included angle, degrees (90° for a chamfer mill).
        included_angle_deg: f64,
        /// The flat at the tip, mm (0 for a sharp V).
        tip_diameter_mm: f64,
    },
    /// A lathe insert: its nose radius and imaginary tip direction (1–9).
    Turning {
        /// The nose radius, mm.
        nose_radius_mm: f64,
        /// The imaginary tool tip direction, 0–9 (Fanuc numbering).
        tip: u8,
    },
}

/// Where a tool's description came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ToolSource {
    /// A tool table file given with `--tools`, and its 1-based line.
    Table {
        /// The file's name as given.
        file: String,
        /// Its line.
        line: u32,
    },
    /// A comment in the program, and its 1-based line.
    Comment {
        /// Which post wrote it (`"fusion"`, `"mastercam"`, …).
        post: &'static str,
        /// Its line.
        line: u32,
    },
    /// The machine's offset registers (a D radius, a lathe nose radius).
    Registers,
    /// Nothing said: an assumed tool (a flat end mill of 6 mm).
    Assumed,
}

/// One tool's shape and sizes.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolShape {
    /// The tool number (T).
    pub number: u32,
    /// The cutting shape.
    pub kind: ToolKind,
    /// The cutting diameter, mm.
    pub diameter_mm: f64,
    /// The flute (cutting) length, mm, where known.
    pub flute_length_mm: Option<f64>,
    /// The shank diameter above the flutes, mm, where known.
    pub shank_diameter_mm: Option<f64>,
    /// The holder's diameter, mm, where known.
    pub holder_diameter_mm: Option<f64>,
    /// How far the tool sticks out of its holder (tip to holder face), mm,
    /// where known: the shank runs from the flutes up to here, the holder
    /// from here up (the material-removal simulation's holder check).
    pub stickout_mm: Option<f64>,
    /// The gauge length (tip to spindle nose), mm, where known.
    pub length_mm: Option<f64>,
    /// Whether the tool may plunge straight down (`None`: not said).
    pub center_cutting: Option<bool>,
    /// What the table or comment called it.
    pub description: String,
    /// Where these figures came from.
    pub source: ToolSource,
}

impl ToolShape {
    /// The tool assumed when nothing describes tool `number`: a flat end
    /// mill of 6 mm.
    pub fn assumed(number: u32) -> ToolShape {
        ToolShape {
            number,
            kind: ToolKind::Flat,
            diameter_mm: 6.0,
            flute_length_mm: None,
            shank_diameter_mm: None,
            holder_diameter_mm: None,
            stickout_mm: None,
            length_mm: None,
            center_cutting: None,
            description: String::new(),
            source: ToolSource::Assumed,
        }
    }

    /// The radius of the cutting edge, mm.
    pub fn radius_mm(&self) -> f64 {
        self.diameter_mm / 2.0
    }
}

/// A lathe insert's imaginary tip direction as a vector from the nose
/// centre to the tip, (Z, X), each component −1, 0 or 1 (Fanuc numbering,
/// X up and Z right seen from +Y: 1 +Z+X, 2 −Z+X, 3 −Z−X, 4 +Z−X, 5 +Z,
/// 6 +X, 7 −Z, 8 −X; 0 and 9 the centre itself). The tip is the corner of
/// the square around the nose in that direction: nose centre + radius ×
/// this vector.
pub fn tip_direction(tip: u8) -> (f64, f64) {
    match tip {
        1 => (1.0, 1.0),
        2 => (-1.0, 1.0),
        3 => (-1.0, -1.0),
        4 => (1.0, -1.0),
        5 => (1.0, 0.0),
        6 => (0.0, 1.0),
        7 => (-1.0, 0.0),
        8 => (0.0, -1.0),
        _ => (0.0, 0.0),
    }
}

/// The tools a run knows, by number.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolLibrary {
    /// The tools, by number.
    pub tools: BTreeMap<u32, ToolShape>,
}

impl ToolLibrary {
    /// Tool `number`, if described.
    pub fn get(&self, number: u32) -> Option<&ToolShape> {
        self.tools.get(&number)
    }

    /// Adds a tool, replacing one of the same number.
    pub fn insert(&mut self, tool: ToolShape) {
        self.tools.insert(tool.number, tool);
    }

    /// Whether no tool is described.
    pub fn is_empty(&self) -> bool {
        self.tools.is_empty()
    }
}
