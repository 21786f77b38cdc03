//! The replay page: one offline HTML file (`page.html`, WebGL 1) with the
//! stock, the finished part and a slider that replays the removal, its
//! data one JSON document in the page (`#sim-data`; the format is in
//! docs/sim.md, kept simple so that the main viewer can take it in).
//!
//! ```text
//!   mill:  {kind, title, summary, grid{nx,ny,x0,y0,x1,y1}, top, bottom,
//!           frames[{line, cells: b64 u32[], heights: b64 f32[]}], collisions[…]}
//!   lathe: {kind, title, summary, stock{z0,r0,z1,r1},
//!           frames[{line, shapes: [[[z, r], …], …]}], collisions[…]}
//! ```
//!
//! A mill frame lists the coarse cells that changed since the frame
//! before (`replay.rs`); the page applies frames in order and starts over
//! from the stock's top to go back. Work coordinates, mm.

use crate::sim::{Finished, Part};
use base64::Engine;
use std::fmt::Write as _;
use std::io::{self, Write};

const TEMPLATE: &str = include_str!("page.html");

fn b64(bytes: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// A JSON string literal of `s`, safe inside a `<script>` element.
fn json_str(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '<' => out.push_str("\\u003c"),
            '>' => out.push_str("\\u003e"),
            '&' => out.push_str("\\u0026"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A finite number as JSON (non-finite: 0).
fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v}")
    } else {
        "0".into()
    }
}

/// The page's data document.
pub fn data(f: &Finished, title: &str) -> String {
    let r = &f.report;
    let mut d = String::new();
    let summary = format!(
        "stock {}; removed {:.3} mm³ of {:.3} mm³; {} collision(s)",
        r.stock, r.removed_mm3, r.stock_mm3, r.collision_total
    );
    let collisions: Vec<String> = r
        .collisions
        .iter()
        .map(|c| {
            format!(
                "{{\"line\":{},\"kind\":{},\"message\":{},\"at\":[{},{},{}]}}",
                c.line,
                json_str(c.kind.as_str()),
                json_str(&c.message),
                num(c.at[0]),
                num(c.at[1]),
                num(c.at[2])
            )
        })
        .collect();
    let _ = write!(
        d,
        "{{\"title\":{},\"summary\":{},\"collisions\":[{}],",
        json_str(title),
        json_str(&summary),
        collisions.join(",")
    );
    match (&f.part, &f.replay) {
        (Part::Mill(map, origin), Some(replay)) if replay.grid.is_some() => {
            let g = replay.grid.as_ref();
            let (nx, ny) = g.map_or((0, 0), |g| (g.nx, g.ny));
            let (x0, y0) = (map.x0 - origin[0], map.y0 - origin[1]);
            let (x1, y1) = (x0 + map.nx as f64 * map.dx, y0 + map.ny as f64 * map.dy);
            // Coarse cells cover whole fine blocks; the last row and column
            // may be partial, so the coarse grid spans a little more.
            let k = g.map_or(1, |g| g.k) as f64;
            let (cx1, cy1) = (x0 + nx as f64 * k * map.dx, y0 + ny as f64 * k * map.dy);
            let _ = (x1, y1);
            let frames: Vec<String> = replay
                .map_frames
                .iter()
                .map(|fr| {
                    let cells: Vec<u8> = fr
                        .changes
                        .iter()
                        .flat_map(|(i, _)| i.to_le_bytes())
                        .collect();
                    let hs: Vec<u8> = fr
                        .changes
                        .iter()
                        .flat_map(|(_, h)| {
                            #[allow(clippy::cast_possible_truncation)] // heights: rounding only
                            let v = (f64::from(*h) - origin[2]) as f32;
                            v.to_le_bytes()
                        })
                        .collect();
                    format!(
                        "{{\"line\":{},\"cells\":\"{}\",\"heights\":\"{}\"}}",
                        fr.line,
                        b64(&cells),
                        b64(&hs)
                    )
                })
                .collect();
            let _ = write!(
                d,
                "\"kind\":\"mill\",\"grid\":{{\"nx\":{nx},\"ny\":{ny},\"x0\":{},\"y0\":{},\"x1\":{},\"y1\":{}}},\"top\":{},\"bottom\":{},\"frames\":[{}]}}",
                num(x0),
                num(y0),
                num(cx1),
                num(cy1),
                num(map.top - origin[2]),
                num(map.bottom - origin[2]),
                frames.join(",")
            );
        }
        (Part::Lathe(s), Some(replay)) => {
            let (z0, r0, z1, r1) = s.stock_box;
            let frames: Vec<String> = replay
                .section_frames
                .iter()
                .map(|(line, shapes)| {
                    let contours: Vec<String> = shapes
                        .iter()
                        .flatten()
                        .map(|c| {
                            let pts: Vec<String> = c
                                .iter()
                                .map(|p| format!("[{},{}]", num(p[0] - s.origin_z), num(p[1])))
                                .collect();
                            format!("[{}]", pts.join(","))
                        })
                        .collect();
                    format!("{{\"line\":{line},\"shapes\":[{}]}}", contours.join(","))
                })
                .collect();
            let _ = write!(
                d,
                "\"kind\":\"lathe\",\"stock\":{{\"z0\":{},\"r0\":{},\"z1\":{},\"r1\":{}}},\"frames\":[{}]}}",
                num(z0 - s.origin_z),
                num(r0),
                num(z1 - s.origin_z),
                num(r1),
                frames.join(",")
            );
        }
        _ => {
            d.push_str(
                "\"kind\":\"none\",\"frames\":[],\"stock\":{\"z0\":0,\"r0\":0,\"z1\":0,\"r1\":0}}",
            );
        }
    }
    d
}

/// Writes the page of a finished simulation.
pub fn write_html(f: &Finished, title: &str, out: &mut dyn Write) -> io::Result<()> {
    let escaped: String = title
        .chars()
        .map(|c| match c {
            '<' => "&lt;".to_string(),
            '>' => "&gt;".to_string(),
            '&' => "&amp;".to_string(),
            c => c.to_string(),
        })
        .collect();
    let page = TEMPLATE
        .replacen("__TITLE__", &escaped, 1)
        .replacen("__DATA__", &data(f, title), 1);
    out.write_all(page.as_bytes())
}
