//! Tool tables the user gives with `--tools`: LinuxCNC's `.tbl` and a CSV
//! with a header. [`read_table`] tells them apart by their first line that
//! holds anything (a CSV's header starts with `tool,`), reads every line,
//! and stops at the first mistake with a [`ToolTableError`] naming the
//! file, the line and how to fix it: a run never goes on with half a table.
//!
//! LinuxCNC (`T1 P1 D6.0 Z+25.0 ;6 mm end mill`, LinuxCNC 2.9's
//! `tooldata_read_entry`): words are a letter and a number separated by
//! blanks, `;` starts the tool's comment, a line starting with `;` and a
//! blank line are skipped. T is the tool number, P its pocket (read and
//! not used), D the DIAMETER, X Y Z A B C U V W its offsets, I J a lathe
//! tool's front and back angles, Q a lathe tool's orientation 0–9. LinuxCNC
//! skips a line it cannot read with a message; vcnc refuses the table.
//!
//! Units: a LinuxCNC table is in the machine's units (its INI file's
//! `LINEAR_UNITS`), which the table does not say. vcnc's machines count in
//! mm, so a `.tbl` is read in mm; a table for an inch machine is given as a
//! CSV with `units` = `in` (or converted). LinuxCNC's standalone `rs274`
//! reads tables in inches, which is why the fixture generators scale theirs.
//!
//! CSV: a header line naming the columns — `tool` and `diameter` required,
//! `corner_radius`, `length`, `flute_length`, `shank_diameter`,
//! `holder_diameter`, `stickout` (the tip to the holder's face: the
//! simulation's holder check needs it with `holder_diameter`) and `units`
//! (`mm` or `in`, per row, default mm) optional, in any order — then one
//! tool per line. An empty cell is a figure not known. `#` starts a comment
//! line. The corner radius gives the shape: 0 a flat end mill, half the
//! diameter a ball, between a bull nose.

use super::names::{self, Unit};
use super::{TableOffsets, ToolKind, ToolLibrary, ToolShape, ToolSource, fanuc_tip_of_linuxcnc};
use crate::decimal;

/// Most tools a table may list (a tool changer holds far fewer).
const MAX_TOOLS: usize = 10_000;
/// Highest tool number (LinuxCNC's tool numbers are C ints; vcnc's offset
/// registers are counted in the tens or hundreds).
const MAX_TOOL_NUMBER: u64 = 99_999_999;
/// Longest line read; LinuxCNC's own limit is about 256 characters.
const MAX_LINE: usize = 4096;
/// Largest offset or size accepted, mm (a 10 m tool is a typo).
const MAX_MM: f64 = 10_000.0;

/// Why a tool table was refused: where, what, and how to fix it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ToolTableError {
    /// The file's name as given.
    pub file: String,
    /// The 1-based line (0: the file as a whole).
    pub line: u32,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub help: String,
}

impl std::fmt::Display for ToolTableError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "tool table {}:{}: {} ({})",
            self.file, self.line, self.message, self.help
        )
    }
}

impl std::error::Error for ToolTableError {}

/// Reads a tool table — LinuxCNC `.tbl` or CSV, told apart by the first
/// line that holds anything — from its text. `file_name` is only used to
/// name the file in sources and errors; nothing is read from disk.
pub fn read_table(text: &str, file_name: &str) -> Result<ToolLibrary, ToolTableError> {
    let mut r = Reader {
        file: file_name,
        line: 0,
        lib: ToolLibrary::default(),
    };
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with(';') && !l.starts_with('#'));
    // A `.tbl` line's words hold no comma before its `;` comment.
    let is_csv = first.is_some_and(|l| l.split(';').next().is_some_and(|w| w.contains(',')));
    if is_csv {
        r.csv(text)?;
    } else {
        r.tbl(text)?;
    }
    if r.lib.tools.is_empty() {
        return Err(r.error_at(
            0,
            "the table lists no tool".into(),
            "write one tool per line: `T1 P1 D6.0 Z25.0 ;6 mm end mill` (LinuxCNC) or a CSV with the header `tool,diameter,corner_radius,length,flute_length,holder_diameter,units`",
        ));
    }
    Ok(r.lib)
}

struct Reader<'a> {
    file: &'a str,
    line: u32,
    lib: ToolLibrary,
}

/// What one `.tbl` line says.
#[derive(Default)]
struct TblRow {
    tool: Option<u32>,
    diameter: Option<f64>,
    x: Option<f64>,
    z: Option<f64>,
    q: Option<u8>,
}

impl Reader<'_> {
    fn error_at(&self, line: u32, message: String, help: &str) -> ToolTableError {
        ToolTableError {
            file: self.file.to_string(),
            line,
            message,
            help: help.to_string(),
        }
    }

    fn error(&self, message: String, help: &str) -> ToolTableError {
        self.error_at(self.line, message, help)
    }

    /// The lines of `text`, numbered, each checked for length.
    fn next_line<'t>(&mut self, raw: &'t str) -> Result<&'t str, ToolTableError> {
        self.line = self.line.saturating_add(1);
        if raw.len() > MAX_LINE {
            return Err(self.error(
                format!("the line is {} bytes long", raw.len()),
                "a tool table line is a few words; is this the right file?",
            ));
        }
        Ok(raw.trim_end_matches('\r'))
    }

    fn tbl(&mut self, text: &str) -> Result<(), ToolTableError> {
        for raw in text.lines() {
            let line = self.next_line(raw)?;
            let (words, comment) = match line.split_once(';') {
                Some((w, c)) => (w, c.trim()),
                None => (line, ""),
            };
            if words.trim().is_empty() {
                continue;
            }
            let row = self.tbl_row(words)?;
            let n = row.tool.ok_or_else(|| {
                self.error(
                    "the line has no T word".into(),
                    "every line names its tool: `T3 P3 D6.0 Z25.0`",
                )
            })?;
            self.add_tbl(n, &row, comment)?;
        }
        Ok(())
    }

    fn tbl_row(&self, words: &str) -> Result<TblRow, ToolTableError> {
        let mut row = TblRow::default();
        for w in words.split_whitespace() {
            let mut chars = w.chars();
            let letter = chars.next().map(|c| c.to_ascii_uppercase()).unwrap_or(' ');
            let value = chars.as_str();
            let bad = |what: &str| {
                self.error(
                    format!("`{w}`: {what}"),
                    "words are a letter and a number: T tool, P pocket, D diameter, X Y Z A B C U V W offsets, I J angles, Q orientation",
                )
            };
            match letter {
                'T' => {
                    let n = decimal::whole(value, MAX_TOOL_NUMBER)
                        .filter(|n| *n > 0)
                        .and_then(|n| u32::try_from(n).ok())
                        .ok_or_else(|| bad("a tool number is a whole number from 1"))?;
                    row.tool = Some(n);
                }
                'P' => {
                    decimal::whole(value, MAX_TOOL_NUMBER)
                        .ok_or_else(|| bad("a pocket is a whole number"))?;
                }
                'Q' => {
                    let q = decimal::whole(value, 9)
                        .and_then(|q| u8::try_from(q).ok())
                        .ok_or_else(|| bad("the orientation Q is 0 to 9"))?;
                    row.q = (q != 0).then_some(q);
                }
                'D' | 'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W' | 'I' | 'J' => {
                    let v = decimal::parse(value)
                        .filter(|v| v.abs() <= MAX_MM)
                        .ok_or_else(|| {
                            bad(if value.contains(',') {
                                "not a number: write a decimal point, not a comma"
                            } else {
                                "not a number (or beyond 10,000)"
                            })
                        })?;
                    match letter {
                        'D' if v < 0.0 => return Err(bad("a diameter is not negative")),
                        'D' => row.diameter = Some(v),
                        'X' => row.x = Some(v),
                        'Z' => row.z = Some(v),
                        _ => {}
                    }
                }
                _ => return Err(bad("not a tool table word")),
            }
        }
        Ok(row)
    }

    fn add_tbl(&mut self, n: u32, row: &TblRow, comment: &str) -> Result<(), ToolTableError> {
        let diameter = row.diameter.unwrap_or(0.0);
        let kind = match row.q {
            Some(q) => ToolKind::Turning {
                nose_radius_mm: diameter / 2.0,
                tip: fanuc_tip_of_linuxcnc(q),
            },
            None => names::kind(&comment.to_lowercase(), None).unwrap_or(ToolKind::Flat),
        };
        let offsets = TableOffsets {
            length_mm: row.z,
            x_mm: row.x,
            radius_mm: row.diameter.map(|d| d / 2.0),
            orientation: row.q,
            line: self.line,
        };
        self.add(n, kind, diameter, comment, offsets, None)
    }

    fn add(
        &mut self,
        n: u32,
        kind: ToolKind,
        diameter_mm: f64,
        description: &str,
        offsets: TableOffsets,
        sizes: Option<CsvSizes>,
    ) -> Result<(), ToolTableError> {
        if let Some(first) = self.lib.offsets.get(&n) {
            return Err(self.error(
                format!("tool {n} is listed twice (first on line {})", first.line),
                "keep one line per tool",
            ));
        }
        if self.lib.tools.len() >= MAX_TOOLS {
            return Err(self.error(
                format!("more than {MAX_TOOLS} tools"),
                "split the table; no machine holds this many",
            ));
        }
        let sizes = sizes.unwrap_or_default();
        self.lib.insert(ToolShape {
            number: n,
            kind,
            diameter_mm,
            flute_length_mm: sizes.flute_length_mm,
            shank_diameter_mm: sizes.shank_diameter_mm,
            holder_diameter_mm: sizes.holder_diameter_mm,
            stickout_mm: sizes.stickout_mm,
            length_mm: sizes.length_mm,
            center_cutting: None,
            description: description.chars().take(200).collect(),
            source: ToolSource::Table {
                file: self.file.to_string(),
                line: self.line,
            },
        });
        self.lib.offsets.insert(n, offsets);
        Ok(())
    }
}

/// The CSV columns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Column {
    Tool,
    Diameter,
    CornerRadius,
    Length,
    FluteLength,
    ShankDiameter,
    HolderDiameter,
    Stickout,
    Units,
}

const COLUMNS: [(&str, Column); 9] = [
    ("tool", Column::Tool),
    ("diameter", Column::Diameter),
    ("corner_radius", Column::CornerRadius),
    ("length", Column::Length),
    ("flute_length", Column::FluteLength),
    ("shank_diameter", Column::ShankDiameter),
    ("holder_diameter", Column::HolderDiameter),
    ("stickout", Column::Stickout),
    ("units", Column::Units),
];

const CSV_HELP: &str = "the header is `tool,diameter,corner_radius,length,flute_length,holder_diameter[,shank_diameter,stickout,units]` (tool and diameter required), then one tool a line";

/// The sizes a CSV row gives besides the diameter, mm.
#[derive(Debug, Clone, Copy, Default)]
struct CsvSizes {
    length_mm: Option<f64>,
    flute_length_mm: Option<f64>,
    shank_diameter_mm: Option<f64>,
    holder_diameter_mm: Option<f64>,
    stickout_mm: Option<f64>,
}

impl Reader<'_> {
    fn csv(&mut self, text: &str) -> Result<(), ToolTableError> {
        let mut header: Option<Vec<Column>> = None;
        for raw in text.lines() {
            let line = self.next_line(raw)?;
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') || line.starts_with(';') {
                continue;
            }
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            match &header {
                None => header = Some(self.csv_header(&cells)?),
                Some(cols) => {
                    let cols = cols.clone();
                    self.csv_row(&cols, &cells)?;
                }
            }
        }
        Ok(())
    }

    fn csv_header(&self, cells: &[&str]) -> Result<Vec<Column>, ToolTableError> {
        let mut cols = Vec::new();
        for c in cells {
            let col = COLUMNS
                .iter()
                .find(|(name, _)| c.eq_ignore_ascii_case(name))
                .map(|(_, col)| *col)
                .ok_or_else(|| self.error(format!("unknown column `{c}`"), CSV_HELP))?;
            if cols.contains(&col) {
                return Err(self.error(format!("column `{c}` is named twice"), CSV_HELP));
            }
            cols.push(col);
        }
        if !cols.contains(&Column::Diameter) {
            return Err(self.error("the header has no `diameter` column".into(), CSV_HELP));
        }
        Ok(cols)
    }

    fn csv_row(&mut self, cols: &[Column], cells: &[&str]) -> Result<(), ToolTableError> {
        if cells.len() != cols.len() {
            return Err(self.error(
                format!(
                    "{} cells where the header names {} columns",
                    cells.len(),
                    cols.len()
                ),
                "write one cell per column, empty when not known (`3,6,,,20,`)",
            ));
        }
        let cell = |col: Column| {
            cols.iter()
                .position(|c| *c == col)
                .and_then(|i| cells.get(i))
                .copied()
                .filter(|s| !s.is_empty())
        };
        let unit = match cell(Column::Units).map(str::to_ascii_lowercase).as_deref() {
            None | Some("mm") => Unit::Mm,
            Some("in" | "inch" | "inches") => Unit::Inch,
            Some(other) => {
                return Err(self.error(
                    format!("units `{other}`: use mm or in"),
                    "the units column says mm or in",
                ));
            }
        };
        let tool = cell(Column::Tool)
            .ok_or_else(|| self.error("the row has no tool number".into(), CSV_HELP))?;
        let n = decimal::whole(tool, MAX_TOOL_NUMBER)
            .filter(|n| *n > 0)
            .and_then(|n| u32::try_from(n).ok())
            .ok_or_else(|| {
                self.error(
                    format!("tool `{tool}`: a tool number is a whole number from 1"),
                    CSV_HELP,
                )
            })?;
        let length = |col: Column, name: &str| -> Result<Option<f64>, ToolTableError> {
            let Some(text) = cell(col) else {
                return Ok(None);
            };
            // A length offset may be negative (measured from a reference
            // longer than the tool); sizes may not.
            let lowest = if col == Column::Length { -MAX_MM } else { 0.0 };
            match decimal::parse(text).map(|v| unit.to_mm(v)) {
                Some(v) if (lowest..=MAX_MM).contains(&v) => Ok(Some(v)),
                _ => Err(self.error(
                    format!("{name} `{text}` is not a length ({lowest} to 10,000 mm)"),
                    CSV_HELP,
                )),
            }
        };
        let diameter = length(Column::Diameter, "diameter")?
            .ok_or_else(|| self.error(format!("tool {n} has no diameter"), CSV_HELP))?;
        let corner = length(Column::CornerRadius, "corner_radius")?.unwrap_or(0.0);
        if corner > diameter / 2.0 + 1e-9 {
            return Err(self.error(
                format!(
                    "the corner radius {corner} mm is more than half the diameter {diameter} mm"
                ),
                "a ball end mill's corner radius is half its diameter",
            ));
        }
        let sizes = CsvSizes {
            length_mm: length(Column::Length, "length")?,
            flute_length_mm: length(Column::FluteLength, "flute_length")?,
            shank_diameter_mm: length(Column::ShankDiameter, "shank_diameter")?,
            holder_diameter_mm: length(Column::HolderDiameter, "holder_diameter")?,
            stickout_mm: length(Column::Stickout, "stickout")?,
        };
        let kind = if corner <= 0.0 {
            ToolKind::Flat
        } else if (corner - diameter / 2.0).abs() <= 1e-9 {
            ToolKind::Ball
        } else {
            ToolKind::Bull {
                corner_radius_mm: corner,
            }
        };
        let offsets = TableOffsets {
            length_mm: sizes.length_mm,
            x_mm: None,
            radius_mm: Some(diameter / 2.0),
            orientation: None,
            line: self.line,
        };
        self.add(n, kind, diameter, "", offsets, Some(sizes))
    }
}
