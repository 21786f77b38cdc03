//! The tool descriptions CAM posts write in a program's comments, read
//! into a [`ToolLibrary`] of shapes (never offsets) by [`from_comments`].
//!
//! The formats, as the posts write them (lengths in the program's units —
//! its first G20 or G21 — unless the text names a unit):
//!
//! | post | comment | read |
//! |---|---|---|
//! | Fusion 360 / HSM / Inventor CAM (`writeComment` of the tool table) | `(T1 D=6. CR=0. - ZMIN=-5. - flat end mill)`, `(T3  D=6. CR=0. TAPER=45deg - ZMIN=-1. - chamfer mill)` | number, diameter, corner radius, taper (half the included angle), Fusion's type name |
//! | Mastercam (MPmaster-style posts) | `(T1|.25 SPOT|H1|D1|TOOL DIA. - .25)`, `( 1/16 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .0625)` | number, `TOOL DIA.`/last `DIA.` value, the description's words (H1 D1 are registers, not sizes) |
//! | SolidCAM (GPP `@def_tool` of the generic posts) | `(TOOL 1   DIA 10.)` | number, diameter |
//! | Vectric (VCarve, Aspire: `[TOOLS_USED]` after `(Tools used in this file: )`) | `(1 = End Mill {6 mm})`, `(5 = End Mill {0.2500 inch} UpDown)` | number, the name's size and words |
//! | Estlcam (`(Required tools:)`, `T<t> M06 (Change tool: <n>)`) | `(End mill 3mm)`, `T2 M06 (Change tool: Ball 6mm)` | the name's size and words; the number of the T word beside it |
//! | CutViewer `TOOL/MILL` (Carbide Create, Vectric and Fusion simulation output) | `(TOOL/MILL,3.17, 0.00, 12.70, 0.00)` then `M6T102` | diameter, corner radius, flute height, taper (half-angle); the number of the next T word |
//! | any post | `(T2 1/4" BALL)`, `(T1 6MM FLAT ENDMILL)` | a T number and a name with a tool word |
//!
//! A tool is described by the first comment that describes it (the header
//! list comes before the operations). Where no T word appears at all, a
//! description that names no number is tool 0, the tool in the spindle.

use super::names::{self, Named, Unit};
use super::{ToolKind, ToolLibrary, ToolShape, ToolSource};
use crate::decimal;

/// Most tools read from one program's comments.
const MAX_TOOLS: usize = 10_000;
/// Longest comment read (a tool description is a line).
const MAX_COMMENT: usize = 1024;
/// Most comments read on one line.
const MAX_COMMENTS_PER_LINE: usize = 16;

/// A description found in a comment: which post, which tool (if the
/// comment says), and the shape.
struct Found {
    post: &'static str,
    number: Option<u32>,
    kind: ToolKind,
    diameter_mm: f64,
    flute_length_mm: Option<f64>,
    description: String,
}

/// A list of tool names the header opens (until the first line of code).
#[derive(Clone, Copy, PartialEq, Eq)]
enum List {
    None,
    /// Vectric's `(Tools used in this file: )`.
    Vectric,
    /// Estlcam's `(Required tools:)`.
    Estlcam,
}

/// Reads the tool descriptions CAM posts write in `program_text`'s
/// comments. Never fails: a comment that is not a tool description is
/// passed over. The library holds shapes only, no offsets.
pub fn from_comments(program_text: &str) -> ToolLibrary {
    let mut s = Scan {
        unit: program_unit(program_text),
        lib: ToolLibrary::default(),
        list: List::None,
        pending: None,
        unnumbered: Vec::new(),
        saw_t_word: false,
    };
    for (i, line) in program_text.lines().enumerate() {
        let n = u32::try_from(i + 1).unwrap_or(u32::MAX);
        s.line(line, n);
        if s.lib.tools.len() >= MAX_TOOLS {
            break;
        }
    }
    s.finish();
    s.lib
}

struct Scan {
    unit: Unit,
    lib: ToolLibrary,
    list: List,
    /// A CutViewer `TOOL/MILL` waiting for the T word that follows it.
    pending: Option<(Found, u32)>,
    /// Named tools without a number (Estlcam's list), for tool 0.
    unnumbered: Vec<(Found, u32)>,
    saw_t_word: bool,
}

impl Scan {
    fn line(&mut self, line: &str, n: u32) {
        let (code, comments) = split(line);
        let t_word = t_word(&code);
        if !code.trim().is_empty() {
            self.list = List::None;
        }
        // A `TOOL/MILL` waits for the next T word, however many lines of
        // code come between (a post may write G21, a G28 or a spindle
        // stop before the tool change).
        if let Some(t) = t_word
            && let Some((found, at)) = self.pending.take()
        {
            self.add(
                Found {
                    number: Some(t),
                    ..found
                },
                at,
            );
        }
        self.saw_t_word |= t_word.is_some();
        for c in comments {
            self.comment(c, n, t_word);
        }
    }

    fn comment(&mut self, c: &str, n: u32, t_word: Option<u32>) {
        let lower = c.to_lowercase();
        if lower.contains("tools used in this file") {
            self.list = List::Vectric;
            return;
        }
        if lower.contains("required tools") {
            self.list = List::Estlcam;
            return;
        }
        if let Some(name) = strip_prefix_ci(c, "change tool:") {
            if let Some(found) = named("estlcam", t_word, name, self.unit) {
                self.add(found, n);
            }
            return;
        }
        if let Some(found) = cutviewer(c, self.unit) {
            match t_word {
                Some(t) => self.add(
                    Found {
                        number: Some(t),
                        ..found
                    },
                    n,
                ),
                None => self.pending = Some((found, n)),
            }
            return;
        }
        let found = match self.list {
            List::Vectric => vectric(c, self.unit),
            List::Estlcam => {
                if let Some(f) = named("estlcam", None, c, self.unit) {
                    self.unnumbered.push((f, n));
                }
                None
            }
            List::None => fusion(c, self.unit)
                .or_else(|| mastercam(c, self.unit))
                .or_else(|| solidcam(c, self.unit))
                .or_else(|| generic(c, self.unit)),
        };
        if let Some(f) = found {
            self.add(f, n);
        }
    }

    fn add(&mut self, f: Found, line: u32) {
        let Some(number) = f.number else { return };
        if self.lib.tools.contains_key(&number) || self.lib.tools.len() >= MAX_TOOLS {
            return;
        }
        self.lib.insert(ToolShape {
            number,
            kind: f.kind,
            diameter_mm: f.diameter_mm,
            flute_length_mm: f.flute_length_mm,
            shank_diameter_mm: None,
            holder_diameter_mm: None,
            stickout_mm: None,
            length_mm: None,
            center_cutting: None,
            description: f.description,
            source: ToolSource::Comment { post: f.post, line },
        });
    }

    /// A description still waiting for its number when the program ends
    /// names the tool in the spindle (0) if the program has no T word.
    fn finish(&mut self) {
        if self.saw_t_word || !self.lib.tools.is_empty() {
            return;
        }
        let last = self.pending.take();
        let only = (self.unnumbered.len() == 1).then(|| self.unnumbered.remove(0));
        if let Some((f, line)) = last.or(only) {
            self.add(
                Found {
                    number: Some(0),
                    ..f
                },
                line,
            );
        }
    }
}

/// The code of a line and its comments: `( … )` anywhere, `;` to the end.
fn split(line: &str) -> (String, Vec<&str>) {
    let mut code = String::new();
    let mut comments = Vec::new();
    let mut open: Option<usize> = None;
    for (i, ch) in line.char_indices() {
        match (open, ch) {
            (Some(start), ')') => {
                comments.push(&line[start..i]);
                open = None;
            }
            (Some(_), _) => {}
            (None, '(') => open = Some(i + 1),
            (None, ';') => {
                comments.push(&line[i + 1..]);
                break;
            }
            (None, c) => code.push(c),
        }
        if comments.len() >= MAX_COMMENTS_PER_LINE {
            break;
        }
    }
    if let Some(start) = open {
        comments.push(&line[start..]);
    }
    let comments = comments
        .into_iter()
        .map(str::trim)
        .filter(|c| !c.is_empty() && c.len() <= MAX_COMMENT)
        .collect();
    (code, comments)
}

/// The first T word of a line's code (`T1`, `M6T102`; not the T of a
/// word such as GOTO).
fn t_word(code: &str) -> Option<u32> {
    let b = code.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let is_t = b[i].eq_ignore_ascii_case(&b'T')
            && (i == 0 || !b[i - 1].is_ascii_alphabetic())
            && b.get(i + 1).is_some_and(u8::is_ascii_digit);
        if is_t {
            let digits: String = code[i + 1..]
                .chars()
                .take_while(char::is_ascii_digit)
                .collect();
            return decimal::whole(&digits, u64::from(u32::MAX))
                .and_then(|n| u32::try_from(n).ok());
        }
        i += 1;
    }
    None
}

/// The program's units: its first G20 (inch) or G21 (mm) outside
/// comments; mm if it has neither. (G70/G71, inch and mm on Syntec, are
/// cycles on a lathe, so they are not read.)
fn program_unit(text: &str) -> Unit {
    for line in text.lines() {
        let (code, _) = split(line);
        let up = code.to_ascii_uppercase();
        let b = up.as_bytes();
        for (i, _) in up.match_indices('G') {
            let mut j = i + 1;
            while b.get(j) == Some(&b' ') {
                j += 1;
            }
            while b.get(j) == Some(&b'0') && b.get(j + 1).is_some_and(u8::is_ascii_digit) {
                j += 1;
            }
            let word = b.get(j..j + 2);
            let ends = !b
                .get(j + 2)
                .is_some_and(|c| c.is_ascii_digit() || *c == b'.');
            match word {
                Some(b"20") if ends => return Unit::Inch,
                Some(b"21") if ends => return Unit::Mm,
                _ => {}
            }
        }
    }
    Unit::Mm
}

fn strip_prefix_ci<'a>(text: &'a str, prefix: &str) -> Option<&'a str> {
    let head = text.get(..prefix.len())?;
    head.eq_ignore_ascii_case(prefix)
        .then(|| text.get(prefix.len()..))
        .flatten()
        .map(str::trim)
}

/// `T12` at the start of `text`: the number and the rest.
fn leading_t(text: &str) -> Option<(u32, &str)> {
    let rest = text.strip_prefix(['T', 't'])?;
    let end = rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len());
    let n = decimal::whole(rest.get(..end)?, u64::from(u32::MAX))?;
    Some((u32::try_from(n).ok()?, rest.get(end..)?))
}

/// The shape a corner radius gives a mill of diameter `d`.
fn by_corner(d: f64, cr: f64) -> ToolKind {
    if cr <= 0.0 {
        ToolKind::Flat
    } else if (cr - d / 2.0).abs() <= 1e-6 * d.max(1.0) {
        ToolKind::Ball
    } else {
        ToolKind::Bull {
            corner_radius_mm: cr,
        }
    }
}

/// Fusion 360/HSM: `T1 D=6. CR=0. [TAPER=45deg] - ZMIN=-5. - flat end mill`.
fn fusion(c: &str, unit: Unit) -> Option<Found> {
    let (number, rest) = leading_t(c)?;
    let rest = rest.trim_start();
    strip_prefix_ci(rest, "D=")?;
    let (mut d, mut cr, mut taper) = (None, 0.0, None);
    for token in rest.split_whitespace().take_while(|t| *t != "-") {
        let (key, value) = token.split_once('=')?;
        let lower = value.to_ascii_lowercase();
        let value = lower.strip_suffix("deg").unwrap_or(&lower);
        let v = decimal::parse(value)?;
        match key.to_ascii_uppercase().as_str() {
            "D" => d = Some(unit.to_mm(v)),
            "CR" => cr = unit.to_mm(v),
            "TAPER" => taper = Some(v),
            _ => {}
        }
    }
    let d = d.filter(|d| *d >= 0.0)?;
    let type_name = rest
        .split(" - ")
        .skip(1)
        .map(str::trim)
        .filter(|s| !s.contains('='))
        .last()
        .unwrap_or("");
    let lower = type_name.to_lowercase();
    let kind = if lower.contains("chamfer")
        || lower.contains("spot")
        || lower.contains("center")
        || lower.contains("counter sink")
        || lower.contains("countersink")
    {
        ToolKind::Vee {
            included_angle_deg: taper.map_or(90.0, |t| 2.0 * t),
            tip_diameter_mm: 0.0,
        }
    } else if lower.contains("drill") {
        ToolKind::Drill {
            point_angle_deg: 118.0,
        }
    } else {
        by_corner(d, cr)
    };
    Some(Found {
        post: "fusion",
        number: Some(number),
        kind,
        diameter_mm: d,
        flute_length_mm: None,
        description: type_name.to_string(),
    })
}

/// The value after the last `DIA. -` of a Mastercam comment.
fn mastercam_dia(text: &str) -> Option<f64> {
    let up = text.to_ascii_uppercase();
    let at = up.rfind("DIA. -").or_else(|| up.rfind("DIA.-"))?;
    let after = up.get(at + 4..)?.trim_start_matches([' ', '-']);
    let value: String = after
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    decimal::parse(&value)
}

/// Mastercam: `T1|.25 SPOT|H1|D1|TOOL DIA. - .25` or
/// `1/16 FLAT ENDMILL TOOL - 1 DIA. OFF. - 1 LEN. - 1 DIA. - .0625`.
fn mastercam(c: &str, unit: Unit) -> Option<Found> {
    let (number, description) = if c.contains('|') {
        let mut fields = c.split('|').map(str::trim);
        let (n, rest) = leading_t(fields.next()?)?;
        if !rest.trim().is_empty() {
            return None;
        }
        (n, fields.next().unwrap_or("").to_string())
    } else {
        let up = c.to_ascii_uppercase();
        let at = up.find("TOOL -")?;
        let after = c.get(at + 6..)?.trim_start();
        let digits: String = after.chars().take_while(char::is_ascii_digit).collect();
        let n = u32::try_from(decimal::whole(&digits, u64::from(u32::MAX))?).ok()?;
        let tail = after.get(digits.len()..).unwrap_or("");
        let tail = tail
            .get(..tail.to_ascii_uppercase().find("DIA.").unwrap_or(tail.len()))
            .unwrap_or("");
        let head = c.get(..at).unwrap_or("");
        (
            n,
            format!("{} {}", head.trim(), tail.trim())
                .trim()
                .to_string(),
        )
    };
    let Named { kind, diameter_mm } = names::read(&description, unit);
    let d = mastercam_dia(c).map(|d| unit.to_mm(d)).or(diameter_mm)?;
    Some(Found {
        post: "mastercam",
        number: Some(number),
        kind: kind.unwrap_or(ToolKind::Flat),
        diameter_mm: d,
        flute_length_mm: None,
        description,
    })
}

/// SolidCAM's GPP `@def_tool`: `TOOL 1   DIA 10.`.
fn solidcam(c: &str, unit: Unit) -> Option<Found> {
    let mut words = c.split_whitespace();
    if !words.next()?.eq_ignore_ascii_case("TOOL") {
        return None;
    }
    let n = u32::try_from(decimal::whole(words.next()?, u64::from(u32::MAX))?).ok()?;
    if !words.next()?.eq_ignore_ascii_case("DIA") {
        return None;
    }
    let d = decimal::parse(words.next()?)?;
    if words.next().is_some() || d < 0.0 {
        return None;
    }
    Some(Found {
        post: "solidcam",
        number: Some(n),
        kind: ToolKind::Flat,
        diameter_mm: unit.to_mm(d),
        flute_length_mm: None,
        description: String::new(),
    })
}

/// CutViewer's `TOOL/MILL,diameter,corner radius,height,taper` (taper:
/// half the included angle; a tapered tool's diameter is its tip's).
fn cutviewer(c: &str, unit: Unit) -> Option<Found> {
    let rest = strip_prefix_ci(c, "TOOL/MILL")?.strip_prefix(',')?;
    let v: Vec<f64> = rest
        .split(',')
        .map(decimal::parse)
        .collect::<Option<Vec<f64>>>()?;
    let (d, cr) = (
        unit.to_mm(*v.first()?),
        unit.to_mm(*v.get(1).unwrap_or(&0.0)),
    );
    let height = unit.to_mm(*v.get(2).unwrap_or(&0.0));
    let taper = *v.get(3).unwrap_or(&0.0);
    if d < 0.0 || cr < 0.0 || height < 0.0 || !(0.0..90.0).contains(&taper) {
        return None;
    }
    let (kind, diameter_mm) = if taper > 0.0 {
        let top = d + 2.0 * height * taper.to_radians().tan();
        let kind = ToolKind::Vee {
            included_angle_deg: 2.0 * taper,
            tip_diameter_mm: d,
        };
        (kind, if height > 0.0 { top } else { d })
    } else {
        (by_corner(d, cr), d)
    };
    Some(Found {
        post: "cutviewer",
        number: None,
        kind,
        diameter_mm,
        flute_length_mm: (height > 0.0).then_some(height),
        description: String::new(),
    })
}

/// A Vectric tool list entry: `1 = End Mill {6 mm}` (also `T1 = …`).
fn vectric(c: &str, unit: Unit) -> Option<Found> {
    let (left, name) = c.split_once('=')?;
    let left = left.trim();
    let left = left.strip_prefix(['T', 't']).unwrap_or(left);
    let n = u32::try_from(decimal::whole(left, u64::from(u32::MAX))?).ok()?;
    named("vectric", Some(n), name, unit)
}

/// `T2 1/4" BALL`: a T number and a name with a tool word.
fn generic(c: &str, unit: Unit) -> Option<Found> {
    let (n, rest) = leading_t(c)?;
    let rest = rest.trim_start_matches([' ', '-', ':', '=']);
    let lower = rest.to_lowercase();
    names::kind(&lower, None)?;
    named("name", Some(n), rest, unit)
}

/// A tool known by its name: the kind its words give (else a flat end
/// mill), the size it writes (0 when it writes none: a V bit named by its
/// angle). None when the name says neither.
fn named(post: &'static str, number: Option<u32>, name: &str, unit: Unit) -> Option<Found> {
    let name = name.trim();
    let Named { kind, diameter_mm } = names::read(name, unit);
    if kind.is_none() && diameter_mm.is_none() {
        return None;
    }
    Some(Found {
        post,
        number,
        kind: kind.unwrap_or(ToolKind::Flat),
        diameter_mm: diameter_mm.unwrap_or(0.0),
        flute_length_mm: None,
        description: name.chars().take(200).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn comments_and_code_are_split() {
        let (code, comments) = split("N25 T1 M6 (2D Contour1) ; tail");
        assert_eq!(code.trim(), "N25 T1 M6");
        assert_eq!(comments, vec!["2D Contour1", "tail"]);
        assert_eq!(t_word("M6T102"), Some(102));
        assert_eq!(t_word("GOTO 5"), None);
    }

    #[test]
    fn units_follow_the_first_g20_or_g21() {
        assert_eq!(program_unit("(G20 in a comment)\nG90 G21\n"), Unit::Mm);
        assert_eq!(program_unit("N10 G90 G94 G17\nN15 G20\n"), Unit::Inch);
        assert_eq!(program_unit("G200\nG2.0\n"), Unit::Mm);
    }
}
