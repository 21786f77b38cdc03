//! What a tool's name says: the shape and size people and CAM systems
//! write in a tool's description — `End Mill {6 mm}` (Vectric), `End mill
//! 3mm` (Estlcam), `1/2 FLAT ENDMILL`, `.25 SPOT`, `3'' FACE MILL`
//! (Mastercam), `60° V-Bit (0.5 inch)`, `6MM BALL NOSE 2FL`.
//!
//! Used where a post writes only a name (Vectric's tool list, Estlcam's
//! tool changes) and for the kind of a tool whose size is given elsewhere
//! (a Mastercam `TOOL DIA.`, a `.tbl` comment). Words are English, with the
//! German of Estlcam's defaults (Fräser, Kugel, Bohrer, Gravierstichel).
//!
//! ```text
//!   "60° V-Bit {0.5 inch}"  ->  kind Vee 60°, diameter 12.7 mm
//!   tokens: "60°" angle · "V-Bit" kind · "0.5" "inch" size with its unit
//! ```

use super::ToolKind;
use crate::decimal;

/// A length unit written in a name or assumed from the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Unit {
    Mm,
    Inch,
}

impl Unit {
    pub(crate) fn to_mm(self, v: f64) -> f64 {
        match self {
            Unit::Mm => v,
            Unit::Inch => v * 25.4,
        }
    }
}

/// What a name says.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Named {
    /// The shape, when a word names one.
    pub kind: Option<ToolKind>,
    /// The cutting diameter, mm, when the name gives a size.
    pub diameter_mm: Option<f64>,
}

/// The included angle a V tool has when its name gives none (a chamfer
/// mill or spot drill of 90°).
const DEFAULT_VEE_DEG: f64 = 90.0;
/// A jobber drill's point angle.
const DRILL_POINT_DEG: f64 = 118.0;

/// Reads a tool name; bare numbers are in `unit`.
pub(crate) fn read(name: &str, unit: Unit) -> Named {
    let lower = name.to_lowercase();
    let tokens = tokens(&lower);
    Named {
        kind: kind(&lower, angle(&tokens)),
        diameter_mm: size(&tokens, unit),
    }
}

/// The shape a name's words give. `angle`: a V tool's included angle if
/// the name writes one.
pub(crate) fn kind(lower: &str, angle: Option<f64>) -> Option<ToolKind> {
    let has = |words: &[&str]| words.iter().any(|w| lower.contains(w));
    let vee = |a: Option<f64>| ToolKind::Vee {
        included_angle_deg: a.unwrap_or(DEFAULT_VEE_DEG),
        tip_diameter_mm: 0.0,
    };
    if has(&["ball", "kugel"]) {
        Some(ToolKind::Ball)
    } else if has(&[
        "v-bit",
        "vbit",
        "v bit",
        "v-carve",
        "v-cutter",
        "chamfer",
        "countersink",
        "counter sink",
        "engrav",
        "gravier",
        "stichel",
        "spot",
        "center drill",
        "centre drill",
    ]) {
        Some(vee(angle))
    } else if has(&["drill", "bohrer"]) {
        Some(ToolKind::Drill {
            point_angle_deg: DRILL_POINT_DEG,
        })
    } else if has(&[
        "end mill",
        "endmill",
        "flat",
        "face mill",
        "shell mill",
        "slot",
        "fräser",
        "fraser",
        "router",
    ]) {
        Some(ToolKind::Flat)
    } else {
        None
    }
}

/// Splits a lower-case name into words at blanks, brackets, commas and
/// the separators CAM posts use; `1/4"` and `60°` stay whole.
fn tokens(lower: &str) -> Vec<&str> {
    lower
        .split(|c: char| c.is_whitespace() || "{}()[],|=:".contains(c))
        .filter(|t| !t.is_empty())
        .take(64)
        .collect()
}

/// A V tool's included angle: `60°`, `60deg`, `60 deg`, `90DEG`.
fn angle(tokens: &[&str]) -> Option<f64> {
    for (i, t) in tokens.iter().enumerate() {
        let next_is_deg = tokens
            .get(i + 1)
            .is_some_and(|n| matches!(*n, "deg" | "degree" | "degrees" | "°"));
        let bare = t
            .strip_suffix('°')
            .or_else(|| t.strip_suffix("deg"))
            .or(next_is_deg.then_some(*t));
        if let Some(a) = bare
            .and_then(decimal::parse)
            .filter(|a| *a > 0.0 && *a < 180.0)
        {
            return Some(a);
        }
    }
    None
}

/// The cutting diameter a name writes: a number with its unit (`6mm`,
/// `6 mm`, `0.25 inch`, `1/4"`, `3''`), else the first bare size (`1/2`,
/// `.25`, `6.`) in `unit`. Angles, flute counts (`2fl`, `4 flute`), corner
/// radii (`r0.5`) and drill numbers (`#7`) are not sizes.
fn size(tokens: &[&str], unit: Unit) -> Option<f64> {
    let mut bare = None;
    for (i, t) in tokens.iter().enumerate() {
        let next = tokens.get(i + 1).copied().unwrap_or("");
        if let Some((v, u)) = with_unit(t) {
            return positive(u.to_mm(v));
        }
        if let Some(v) = number(t) {
            if let Some(u) = unit_word(next) {
                return positive(u.to_mm(v));
            }
            let not_a_size = matches!(next, "deg" | "°" | "fl" | "flute" | "flutes" | "fl.");
            if bare.is_none() && !not_a_size {
                bare = Some(v);
            }
        }
    }
    bare.and_then(|v| positive(unit.to_mm(v)))
}

fn positive(v: f64) -> Option<f64> {
    (v > 0.0 && v.is_finite()).then_some(v)
}

/// A token that carries its unit: `6mm`, `0.25in`, `0.25inch`, `1/4"`, `3''`.
fn with_unit(t: &str) -> Option<(f64, Unit)> {
    for (suffix, unit) in [
        ("mm", Unit::Mm),
        ("inches", Unit::Inch),
        ("inch", Unit::Inch),
        ("in", Unit::Inch),
        ("''", Unit::Inch),
        ("\"", Unit::Inch),
    ] {
        if let Some(v) = t.strip_suffix(suffix).and_then(number) {
            return Some((v, unit));
        }
    }
    None
}

fn unit_word(t: &str) -> Option<Unit> {
    match t {
        "mm" => Some(Unit::Mm),
        "in" | "inch" | "inches" | "\"" | "''" => Some(Unit::Inch),
        _ => None,
    }
}

/// A decimal (`6`, `.25`, `6.`) or a fraction (`1/4`, `1-1/2`).
fn number(t: &str) -> Option<f64> {
    if let Some((whole, frac)) = t.split_once('-') {
        let w = decimal::whole(whole, 1000).and_then(|w| u32::try_from(w).ok());
        if let (Some(w), Some(f)) = (w, fraction(frac)) {
            return Some(f64::from(w) + f);
        }
    }
    fraction(t).or_else(|| decimal::parse(t))
}

fn fraction(t: &str) -> Option<f64> {
    let (n, d) = t.split_once('/')?;
    let small = |s: &str| decimal::whole(s, 1000).and_then(|v| u32::try_from(v).ok());
    let (n, d) = (small(n)?, small(d)?);
    (d > 0).then(|| f64::from(n) / f64::from(d))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn named(name: &str) -> (Option<ToolKind>, Option<f64>) {
        let n = read(name, Unit::Mm);
        (n.kind, n.diameter_mm.map(|d| (d * 1e6).round() / 1e6))
    }

    #[test]
    fn vectric_and_estlcam_names() {
        assert_eq!(named("End Mill {6 mm}"), (Some(ToolKind::Flat), Some(6.0)));
        assert_eq!(
            named("End Mill {0.2500 inch} UpDown"),
            (Some(ToolKind::Flat), Some(6.35))
        );
        assert_eq!(named("End mill 3mm"), (Some(ToolKind::Flat), Some(3.0)));
        let v = named("V-Bit {60 deg}");
        assert_eq!(
            v,
            (
                Some(ToolKind::Vee {
                    included_angle_deg: 60.0,
                    tip_diameter_mm: 0.0
                }),
                None
            )
        );
        assert_eq!(named("Ball Nose (3 mm)").0, Some(ToolKind::Ball));
    }

    #[test]
    fn mastercam_names() {
        let n = read("1/2 FLAT ENDMILL", Unit::Inch);
        assert_eq!(n.kind, Some(ToolKind::Flat));
        assert_eq!(n.diameter_mm, Some(12.7));
        let n = read("3'' FACE MILL / SHELL MILL", Unit::Inch);
        assert!((n.diameter_mm.unwrap_or(0.0) - 76.2).abs() < 1e-9);
        let n = read("6MM BALL NOSE 2FL", Unit::Inch);
        assert_eq!((n.kind, n.diameter_mm), (Some(ToolKind::Ball), Some(6.0)));
        assert!(matches!(
            read(".25 SPOT", Unit::Inch).kind,
            Some(ToolKind::Vee { .. })
        ));
        assert!(matches!(
            read("STANDARD DRILL - 0.16", Unit::Inch).kind,
            Some(ToolKind::Drill { .. })
        ));
    }

    #[test]
    fn angles_and_flutes_are_not_sizes() {
        assert_eq!(named("60° V-Bit").1, None);
        assert_eq!(named("4 FLUTE 10 END MILL").1, Some(10.0));
        assert_eq!(named("nothing here"), (None, None));
    }
}
