//! What the program cuts into: a block or a bar, from `--stock`, from the
//! stock a CAM post wrote in the program's header comments, or guessed
//! from the cuts (`auto`, in `survey.rs`).
//!
//! ```text
//!   --stock box:x0,y0,z0,x1,y1,z1   a block, work coordinates, mm
//!   --stock bar:D,L[,bore]          a bar of diameter D from Z0 to Z−L
//!   --stock auto                    the cuts' extents (the default)
//!   (stockMin:0.00mm, 0.00mm, -12.70mm)      Carbide Create's header
//!   (stockMax:152.40mm, 101.60mm, 0.00mm)
//!   ( Material Size)                         Vectric's header: a block
//!   ( X= 600.000, Y= 400.000, Z= 18.000)     from its XY and Z origins
//! ```
//!
//! Work coordinates are those in force at the program's first cutting
//! move (the sink places the stock there). Numbers are read by a checked
//! reader: only digits, a sign and a point, finite.

/// A stock as the user or the program describes it, work coordinates, mm.
#[derive(Debug, Clone, PartialEq)]
pub enum StockSpec {
    /// A block.
    Box {
        /// Lower corner.
        min: [f64; 3],
        /// Upper corner.
        max: [f64; 3],
    },
    /// A bar on the lathe's axis from Z0 to Z−length.
    Bar {
        /// Outside diameter.
        diameter: f64,
        /// Length.
        length: f64,
        /// Bore diameter (0: solid).
        bore: f64,
    },
    /// Guess it from the cuts.
    Auto,
}

/// Where a stock came from, for the report.
#[derive(Debug, Clone, PartialEq)]
pub enum StockOrigin {
    /// `--stock`.
    Option,
    /// A header comment of the program: its line and the post that wrote
    /// it.
    Header {
        /// 1-based line.
        line: u32,
        /// `"Carbide Create"`, `"Vectric"`.
        post: &'static str,
    },
    /// Guessed from the cuts.
    Auto,
}

/// Reads a number: optional sign, digits, at most one point; finite.
fn number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let ok = !t.is_empty()
        && t.bytes()
            .all(|b| b.is_ascii_digit() || b == b'.' || b == b'-' || b == b'+')
        && t.bytes().filter(|b| *b == b'.').count() <= 1
        && t.bytes().skip(1).all(|b| b != b'-' && b != b'+')
        && t.bytes().any(|b| b.is_ascii_digit());
    match t.parse::<f64>() {
        Ok(v) if ok && v.is_finite() && v.abs() < 1e7 => Ok(v),
        _ => Err(format!("{t:?} is not a number of mm")),
    }
}

fn numbers(text: &str) -> Result<Vec<f64>, String> {
    text.split(',').map(number).collect()
}

impl StockSpec {
    /// Reads `--stock`: `box:x0,y0,z0,x1,y1,z1`, `bar:D,L[,bore]` or
    /// `auto`.
    pub fn parse(text: &str) -> Result<StockSpec, String> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("auto") {
            return Ok(StockSpec::Auto);
        }
        let (kind, rest) = t.split_once(':').ok_or_else(|| {
            format!("--stock {t:?}: write box:x0,y0,z0,x1,y1,z1, bar:D,L[,bore] or auto")
        })?;
        let v = numbers(rest).map_err(|e| format!("--stock {t:?}: {e}"))?;
        let spec = match (kind.to_ascii_lowercase().as_str(), v.as_slice()) {
            ("box", [x0, y0, z0, x1, y1, z1]) => StockSpec::Box {
                min: [*x0, *y0, *z0],
                max: [*x1, *y1, *z1],
            },
            ("bar", [d, l]) => StockSpec::Bar {
                diameter: *d,
                length: *l,
                bore: 0.0,
            },
            ("bar", [d, l, b]) => StockSpec::Bar {
                diameter: *d,
                length: *l,
                bore: *b,
            },
            ("box", _) => {
                return Err(format!(
                    "--stock {t:?}: a box is six numbers, x0,y0,z0,x1,y1,z1 (work mm)"
                ));
            }
            ("bar", _) => {
                return Err(format!(
                    "--stock {t:?}: a bar is its diameter and length, and optionally a bore: D,L[,bore]"
                ));
            }
            _ => return Err(format!("--stock {t:?}: the kinds are box, bar and auto")),
        };
        spec.check().map_err(|e| format!("--stock {t:?}: {e}"))?;
        Ok(spec)
    }

    /// An empty or inverted stock is an error.
    pub fn check(&self) -> Result<(), String> {
        match self {
            StockSpec::Box { min, max } => {
                for (k, axis) in ["X", "Y", "Z"].iter().enumerate() {
                    if min[k].partial_cmp(&max[k]) != Some(std::cmp::Ordering::Less) {
                        return Err(format!(
                            "the block is empty or inverted in {axis} ({} .. {}): give the lower corner first",
                            min[k], max[k]
                        ));
                    }
                }
                Ok(())
            }
            StockSpec::Bar {
                diameter,
                length,
                bore,
            } => {
                if !(*diameter > 0.0 && *length > 0.0) {
                    Err(format!(
                        "the bar is empty (diameter {diameter}, length {length}): both must be more than 0"
                    ))
                } else if !(*bore >= 0.0 && bore < diameter) {
                    Err(format!(
                        "the bore ({bore}) must be at least 0 and less than the diameter ({diameter})"
                    ))
                } else {
                    Ok(())
                }
            }
            StockSpec::Auto => Ok(()),
        }
    }

    /// How people read it: `box X 0 .. 100  Y 0 .. 50  Z -20 .. 0`.
    pub fn describe(&self) -> String {
        match self {
            StockSpec::Box { min, max } => format!(
                "box X {} .. {}  Y {} .. {}  Z {} .. {}",
                fmt(min[0]),
                fmt(max[0]),
                fmt(min[1]),
                fmt(max[1]),
                fmt(min[2]),
                fmt(max[2])
            ),
            StockSpec::Bar {
                diameter,
                length,
                bore,
            } => {
                let bore = if *bore > 0.0 {
                    format!(", bore {}", fmt(*bore))
                } else {
                    String::new()
                };
                format!(
                    "bar diameter {} from Z0 to Z-{}{bore}",
                    fmt(*diameter),
                    fmt(*length)
                )
            }
            StockSpec::Auto => "auto".to_string(),
        }
    }
}

/// A length with at most three decimals, no trailing zeros.
pub fn fmt(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// Header lines searched for a stock comment.
const HEADER_LINES: usize = 300;

/// The stock a CAM post wrote in the program's first lines, if any, with
/// its line. Inch values (a unit suffix `in`, or a G20 in the header)
/// are converted to mm.
pub fn from_header(text: &str) -> Option<(StockSpec, StockOrigin)> {
    let lines: Vec<&str> = text.lines().take(HEADER_LINES).collect();
    let inch = lines.iter().any(|l| has_g20(l));
    carbide(&lines, inch).or_else(|| vectric(&lines, inch))
}

/// Whether a line has a G20 word outside its comments.
fn has_g20(line: &str) -> bool {
    let mut depth = 0u32;
    let code: String = line
        .chars()
        .filter(|c| {
            match c {
                '(' => depth += 1,
                ')' => depth = depth.saturating_sub(1),
                _ => return depth == 0,
            }
            false
        })
        .take_while(|c| *c != ';')
        .collect::<String>()
        .to_ascii_uppercase()
        .replace(' ', "");
    code.match_indices("G20").any(|(i, _)| {
        !code[i + 3..].starts_with(|c: char| c.is_ascii_digit() || c == '.')
            && !code[..i].ends_with(|c: char| c.is_ascii_digit() || c == '.')
    })
}

/// The comment text of a line `( … )`, trimmed.
fn comment(line: &str) -> Option<&str> {
    let l = line.trim();
    let inner = l.strip_prefix('(')?.strip_suffix(')')?;
    Some(inner.trim())
}

/// Three numbers with an optional unit suffix each: `0.00mm, 0.00mm,
/// -12.70mm`; inches when a suffix says `in` or `inch` is set.
fn triple(text: &str, inch: bool) -> Option<[f64; 3]> {
    let mut out = [0.0; 3];
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() != 3 {
        return None;
    }
    for (o, p) in out.iter_mut().zip(parts) {
        let p = p.trim();
        let (num, scale) = if let Some(n) = p.strip_suffix("mm") {
            (n, 1.0)
        } else if let Some(n) = p.strip_suffix("in") {
            (n, 25.4)
        } else {
            (p, if inch { 25.4 } else { 1.0 })
        };
        *o = number(num).ok()? * scale;
    }
    Some(out)
}

fn carbide(lines: &[&str], inch: bool) -> Option<(StockSpec, StockOrigin)> {
    let find = |key: &str| {
        lines.iter().enumerate().find_map(|(i, l)| {
            let c = comment(l)?;
            let rest = c.strip_prefix(key)?;
            Some((i, triple(rest, inch)?))
        })
    };
    let (line, min) = find("stockMin:")?;
    let (_, max) = find("stockMax:")?;
    let spec = StockSpec::Box { min, max };
    spec.check().ok()?;
    Some((
        spec,
        StockOrigin::Header {
            line: u32::try_from(line + 1).unwrap_or(u32::MAX),
            post: "Carbide Create",
        },
    ))
}

/// `X= 600.000, Y= 400.000, Z= 18.000` (Z optional).
fn vectric_size(c: &str, inch: bool) -> Option<[f64; 3]> {
    let mut out = [0.0; 3];
    for part in c.split(',') {
        let (k, v) = part.split_once('=')?;
        let slot = match k.trim() {
            "X" => 0,
            "Y" => 1,
            "Z" => 2,
            _ => return None,
        };
        let v = number(v).ok()? * if inch { 25.4 } else { 1.0 };
        if let Some(o) = out.get_mut(slot) {
            *o = v;
        }
    }
    Some(out)
}

fn vectric(lines: &[&str], inch: bool) -> Option<(StockSpec, StockOrigin)> {
    let at = lines
        .iter()
        .position(|l| comment(l).is_some_and(|c| c.eq_ignore_ascii_case("Material Size")))?;
    let size = vectric_size(comment(lines.get(at + 1)?)?, inch)?;
    let setting = |key: &str| {
        lines.iter().find_map(|l| {
            let c = comment(l)?;
            let (k, v) = c.split_once('=')?;
            k.trim()
                .eq_ignore_ascii_case(key)
                .then(|| v.trim().to_ascii_lowercase())
        })
    };
    // Vectric's defaults: XY zero at the lower-left corner, Z zero on the
    // material's surface; its header may say otherwise.
    let centred = setting("XY Origin for Material").is_some_and(|v| v.contains("cent"));
    let on_bed = setting("Z Origin for Material").is_some_and(|v| v.contains("bed"));
    let (x0, y0) = if centred {
        (-size[0] / 2.0, -size[1] / 2.0)
    } else {
        (0.0, 0.0)
    };
    let (z0, z1) = if on_bed {
        (0.0, size[2])
    } else {
        (-size[2], 0.0)
    };
    let spec = StockSpec::Box {
        min: [x0, y0, z0],
        max: [x0 + size[0], y0 + size[1], z1],
    };
    spec.check().ok()?;
    Some((
        spec,
        StockOrigin::Header {
            line: u32::try_from(at + 2).unwrap_or(u32::MAX),
            post: "Vectric",
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stock_options_read_and_refuse() {
        assert_eq!(
            StockSpec::parse("box:0,0,-10,100,50,0"),
            Ok(StockSpec::Box {
                min: [0.0, 0.0, -10.0],
                max: [100.0, 50.0, 0.0]
            })
        );
        assert_eq!(
            StockSpec::parse("bar:50,80,20"),
            Ok(StockSpec::Bar {
                diameter: 50.0,
                length: 80.0,
                bore: 20.0
            })
        );
        assert!(
            StockSpec::parse("box:0,0,0,100,50,0")
                .unwrap_err()
                .contains("Z")
        );
        assert!(
            StockSpec::parse("box:10,0,-1,0,50,0")
                .unwrap_err()
                .contains("inverted")
        );
        assert!(StockSpec::parse("bar:0,10").unwrap_err().contains("empty"));
        assert!(
            StockSpec::parse("bar:10,10,12")
                .unwrap_err()
                .contains("bore")
        );
        assert!(StockSpec::parse("box:inf,0,0,1,1,1").is_err());
        assert!(StockSpec::parse("box:1e400,0,0,1,1,1").is_err());
        assert!(StockSpec::parse("cube:1").is_err());
    }

    #[test]
    fn carbide_create_headers_give_a_block() {
        let text = "(Design File: x.c2d)\n(stockMin:0.00mm, 0.00mm, -12.70mm)\n(stockMax:152.40mm, 101.60mm, 0.00mm)\nG90\n";
        let (spec, origin) = from_header(text).unwrap();
        assert_eq!(
            spec,
            StockSpec::Box {
                min: [0.0, 0.0, -12.7],
                max: [152.4, 101.6, 0.0]
            }
        );
        assert_eq!(
            origin,
            StockOrigin::Header {
                line: 2,
                post: "Carbide Create"
            }
        );
        let inch = "(stockMin:0.000in, 0.000in, -1.000in)\n(stockMax:2.000in, 1.000in, 0.000in)\n";
        let (spec, _) = from_header(inch).unwrap();
        assert_eq!(
            spec,
            StockSpec::Box {
                min: [0.0, 0.0, -25.4],
                max: [50.8, 25.4, 0.0]
            }
        );
    }

    #[test]
    fn vectric_headers_give_a_block_from_their_origins() {
        let text = "( Material Size)\n( X= 100.000, Y= 50.000, Z= 18.000)\nG21\n";
        let (spec, _) = from_header(text).unwrap();
        assert_eq!(
            spec,
            StockSpec::Box {
                min: [0.0, 0.0, -18.0],
                max: [100.0, 50.0, 0.0]
            }
        );
        let inch = "( Material Size)\n( X= 2.000, Y= 1.000, Z= 0.500)\nG20 G90\n";
        let (spec, _) = from_header(inch).unwrap();
        assert_eq!(
            spec,
            StockSpec::Box {
                min: [0.0, 0.0, -12.7],
                max: [50.8, 25.4, 0.0]
            }
        );
        assert_eq!(from_header("G0 X1\n(no stock here)\n"), None);
    }
}
