//! What the tools look like: each tool's cutting shape and sizes, and where
//! those figures came from.
//!
//! The machine's tool table ([`crate::machine::Tool`]) holds offset
//! registers: the H length and D radius a program's G43 and G41 read. This
//! module holds what those registers do not say: whether tool 3 is a ball
//! or a drill, how long its flutes are, how wide its holder is. Plots draw
//! tools to size with it and the material-removal simulation cuts with it.
//!
//! A [`ToolLibrary`] comes from one of two pure functions (no file I/O: the
//! caller reads the text):
//!
//! - [`read_table`]`(text, file_name)`: a tool table the user gives with
//!   `--tools` — LinuxCNC's `.tbl` or a CSV with a header (`table.rs`). It
//!   describes each tool and holds the offsets the table gives
//!   ([`TableOffsets`]), which [`ToolLibrary::fill_registers`] writes into
//!   the run's machine. A malformed table is a [`ToolTableError`] naming
//!   the file, the line and what is wrong.
//! - [`from_comments`]`(program_text)`: the tool descriptions CAM posts
//!   write in a program's comments — Fusion 360/HSM, Mastercam, SolidCAM,
//!   Vectric, Estlcam, and the CutViewer `TOOL/MILL` line of Carbide Create
//!   (`comments.rs`, names read by `names.rs`). It never fails and never
//!   holds offsets: a program may be written for wear compensation, where
//!   D holds only the wear, so a comment's diameter must not become a D
//!   register.
//!
//! A reader of shapes (the plot, the simulation, `vcnc tools`) takes the
//! table's word first and the comments' for the rest:
//!
//! ```text
//!   let tools = table.unwrap_or_default().or_else(&from_comments(&program_text));
//!   let shape = tools.shape(n);   // ToolShape::assumed(n) when nothing says
//! ```
//!
//! Each tool remembers its [`ToolSource`], so that `vcnc tools` can say
//! where every figure came from. Tool 0 stands for the tool in the spindle
//! when the program never names one (a one-tool program whose header
//! describes its cutter but that has no T word).
//!
//! Lengths are mm, angles degrees.

mod comments;
mod names;
mod table;

pub use comments::from_comments;
pub use table::{ToolTableError, read_table};

use crate::machine::Machine;
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
        /// Whose format it is: `"fusion"` (Fusion 360/HSM), `"mastercam"`,
        /// `"solidcam"`, `"vectric"`, `"estlcam"`, `"cutviewer"` (CutViewer's
        /// `TOOL/MILL`, written by Carbide Create) or `"name"` (a T number
        /// and a tool name in any comment).
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
    /// The cutting diameter, mm (0 when a description gives only the
    /// shape: a V bit named by its angle).
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

/// What a tool table says of a tool's offset registers: the values
/// [`ToolLibrary::fill_registers`] writes into the machine's register of
/// the same number (LinuxCNC's rule: H and D numbers are tool numbers).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct TableOffsets {
    /// The tool length offset (`.tbl` Z, CSV `length`), mm: the H
    /// register's geometry and a lathe register's Z offset.
    pub length_mm: Option<f64>,
    /// A lathe's X offset (`.tbl` X, a radius as machine X is one), mm.
    pub x_mm: Option<f64>,
    /// The cutting radius (half the table's diameter), mm: the D register's
    /// geometry and a lathe register's nose radius.
    pub radius_mm: Option<f64>,
    /// LinuxCNC's lathe tool orientation (`.tbl` Q, 1–9) when the table
    /// gives one.
    pub orientation: Option<u8>,
    /// The table's line, for `vcnc tools`.
    pub line: u32,
}

/// How a dialect numbers the imaginary tool tip directions it reads from
/// the machine's `tip` (`[tools.N] tip` in the machine file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TipNumbering {
    /// Fanuc's (fanuc-lathe, haas-lathe): 3 is an OD turning tool.
    Fanuc,
    /// LinuxCNC's lathe orientation (linuxcnc-lathe): the table's Q as is.
    LinuxCnc,
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

/// The Fanuc tip direction of LinuxCNC's lathe tool orientation `q` (a
/// `.tbl`'s Q): the same directions mirrored in X (1↔4, 2↔3, 6↔8; 5 and 7
/// stay; 9, the nose centre, and anything else is Fanuc's 0), as rs274
/// offsets a G41/G42 path for each orientation
/// (`tests/fixtures/linuxcnc_lathe_comp`).
pub fn fanuc_tip_of_linuxcnc(q: u8) -> u8 {
    match q {
        1 => 4,
        2 => 3,
        3 => 2,
        4 => 1,
        6 => 8,
        8 => 6,
        5 | 7 => q,
        _ => 0,
    }
}

/// The tools a run knows, by number.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ToolLibrary {
    /// The tools, by number.
    pub tools: BTreeMap<u32, ToolShape>,
    /// The offsets a tool table gives, by tool number (empty for a library
    /// read from comments).
    pub offsets: BTreeMap<u32, TableOffsets>,
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

    /// Tool `number`'s shape, or the one assumed when nothing describes it
    /// ([`ToolShape::assumed`]).
    pub fn shape(&self, number: u32) -> ToolShape {
        self.get(number)
            .cloned()
            .unwrap_or_else(|| ToolShape::assumed(number))
    }

    /// This library, with `other`'s tools where this one describes none
    /// (a tool table, then the program's comments). Offsets are this
    /// library's only.
    pub fn or_else(mut self, other: &ToolLibrary) -> ToolLibrary {
        for (n, t) in &other.tools {
            self.tools.entry(*n).or_insert_with(|| t.clone());
        }
        self
    }

    /// Writes the table's offsets into `machine`'s registers of the same
    /// numbers, over what the machine file says: the length into H and a
    /// lathe's Z geometry, the radius into D and the nose radius, X into a
    /// lathe's X geometry, the orientation into `tip` (numbered as the
    /// dialect reads it). Wear values stay the machine file's; registers
    /// the table does not list stay as they are.
    pub fn fill_registers(&self, machine: &mut Machine, tips: TipNumbering) {
        for (n, o) in &self.offsets {
            let reg = machine.tools.entry(*n).or_default();
            if let Some(l) = o.length_mm {
                reg.h_mm = l;
                reg.z_mm = l;
            }
            if let Some(r) = o.radius_mm {
                reg.d_mm = r;
                reg.nose_radius_mm = r;
            }
            if let Some(x) = o.x_mm {
                reg.x_mm = x;
            }
            if let Some(q) = o.orientation {
                reg.tip = match tips {
                    TipNumbering::Fanuc => fanuc_tip_of_linuxcnc(q),
                    TipNumbering::LinuxCnc => q,
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_comes_first_and_comments_fill_in() {
        let table = read_table("T1 D6\n", "t.tbl").unwrap_or_default();
        let comments =
            from_comments("(T1 D=3. CR=0. - flat end mill)\n(T2 D=4. CR=2. - ball end mill)\n");
        let tools = table.or_else(&comments);
        assert_eq!(tools.shape(1).diameter_mm, 6.0);
        assert_eq!(tools.shape(2).kind, ToolKind::Ball);
        assert_eq!(tools.shape(9).source, ToolSource::Assumed);
        assert_eq!(tools.offsets.keys().copied().collect::<Vec<_>>(), vec![1]);
    }
}
