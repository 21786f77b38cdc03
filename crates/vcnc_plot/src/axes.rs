//! The frame's furniture in a flat picture: the grid with round-number
//! ticks in the display unit (mm or inches) and a scale bar, the X/Y/Z
//! triad of the iso view, a lathe's spindle centre line and chuck side,
//! and the machine's travel limits. Part of the [`crate::scene`], drawn
//! under the path.
//!
//! ```text
//!   Y mm                                lathe half-section:
//!   40 ┼────┼────┼────┼                 X diameter, mm
//!   20 ┼────┼────┼────┼                 ▨│      ┌────────┐
//!    0 └────┴────┴────┴── X mm          ▨│ ─────┘        │   part
//!      0    20   40   60                ▨│─ · ─ · ─ · ─ · ─  spindle axis
//!      |——— 20 mm ———|  (scale bar)   chuck side (−Z)          Z mm
//! ```

use crate::clip::{Clip, Exits, Runs};
use crate::scene::{Anchor, Fit, Item, Stroke, TextSize, line_item, text};
use crate::theme::Palette;
use crate::view::{P3, View};
use vcnc_core::display::DisplayUnits;

/// A "nice" tick step (1, 2 or 5 × 10ⁿ) giving about `n` ticks over `range`.
pub(crate) fn tick_step(range: f64, n: f64) -> f64 {
    let raw = (range / n).max(1e-6);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// A tick label: as many decimals as the step needs.
pub(crate) fn tick_label(v: f64, step: f64) -> String {
    let decimals = if step >= 1.0 {
        0
    } else {
        // step < 1: a small positive count.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let d = (-step.log10()).ceil().clamp(0.0, 6.0) as usize;
        d
    };
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        format!("{:.decimals$}", 0.0)
    } else {
        s
    }
}

fn thin(color: crate::theme::Rgb) -> Stroke {
    Stroke {
        color,
        width: 1.0,
        dash: None,
    }
}

/// Grid, ticks, axis names and a scale bar (a triad in the iso view);
/// `area` is the plot area (x, y, width, height).
pub(crate) fn grid(
    fit: &Fit,
    pal: &Palette,
    units: DisplayUnits,
    area: (f64, f64, f64, f64),
    out: &mut Vec<Item>,
) {
    let (ax, ay, aw, ah) = area;
    if fit.proj.view == View::Iso {
        iso_triad(fit, pal, ax + 36.0, ay + ah - 36.0, out);
        scale_bar(fit, pal, units, area, out);
        return;
    }
    // Plot space is mm; ticks fall on round numbers of the display unit.
    let per = units.of_mm(1.0);
    let (u_lo, v_hi) = fit.uv_at(ax, ay);
    let (u_hi, v_lo) = fit.uv_at(ax + aw, ay + ah);
    let step = tick_step(((u_hi - u_lo).max(v_hi - v_lo)) * per, 8.0);
    let k0 = (u_lo * per / step).ceil();
    let mut k = k0;
    while k * step <= u_hi * per && k - k0 < 200.0 {
        let x = fit.x_of(k * step / per);
        out.push(line_item([x, ay], [x, ay + ah], thin(pal.grid)));
        out.push(text(
            [x, ay + ah + 14.0],
            tick_label(k * step, step),
            TextSize::Small,
            pal.muted,
            Anchor::Middle,
        ));
        k += 1.0;
    }
    // A lathe's up axis is a radius, labelled as a diameter.
    let scale = if fit.proj.diameter_up { 2.0 } else { 1.0 };
    let k0 = (v_lo * per / step).ceil();
    let mut k = k0;
    while k * step <= v_hi * per && k - k0 < 200.0 {
        let y = fit.y_of(k * step / per);
        out.push(line_item([ax, y], [ax + aw, y], thin(pal.grid)));
        out.push(text(
            [ax - 6.0, y + 4.0],
            tick_label(k * step * scale, step * scale),
            TextSize::Small,
            pal.muted,
            Anchor::End,
        ));
        k += 1.0;
    }
    out.push(Item::Shape {
        pts: vec![[ax, ay], [ax, ay + ah], [ax + aw, ay + ah]],
        closed: false,
        stroke: Some(thin(pal.muted)),
        fill: None,
    });
    let [hu, hv] = fit.proj.labels;
    let unit = units.name();
    let up = if fit.proj.diameter_up {
        format!("{hv} diameter, {unit}")
    } else {
        format!("{hv} {unit}")
    };
    out.push(text(
        [ax + aw, ay + ah + 30.0],
        format!("{hu} {unit}"),
        TextSize::Normal,
        pal.text,
        Anchor::End,
    ));
    out.push(text(
        [ax - 6.0, ay - 4.0],
        up,
        TextSize::Normal,
        pal.text,
        Anchor::Start,
    ));
}

/// A bar of a round length at the bottom right of the plot area, for the
/// iso view, which has no grid to read sizes from.
fn scale_bar(
    fit: &Fit,
    pal: &Palette,
    units: DisplayUnits,
    (ax, ay, aw, ah): (f64, f64, f64, f64),
    out: &mut Vec<Item>,
) {
    // The iso view foreshortens every axis alike, by √(2/3).
    let px_per_unit = fit.scale() * (2.0f64 / 3.0).sqrt() / units.of_mm(1.0);
    if !(px_per_unit.is_finite() && px_per_unit > 0.0) {
        return;
    }
    let len = tick_step(aw / 4.0 / px_per_unit, 1.0);
    let w = len * px_per_unit;
    let (x1, y) = (ax + aw - 12.0, ay + ah - 16.0);
    let x0 = x1 - w;
    let s = Stroke {
        color: pal.text,
        width: 1.5,
        dash: None,
    };
    out.push(line_item([x0, y], [x1, y], s));
    out.push(line_item([x0, y - 4.0], [x0, y + 4.0], s));
    out.push(line_item([x1, y - 4.0], [x1, y + 4.0], s));
    out.push(text(
        [(x0 + x1) / 2.0, y - 7.0],
        format!(
            "{} {} (along X, Y or Z)",
            tick_label(len, len),
            units.name()
        ),
        TextSize::Small,
        pal.text,
        Anchor::Middle,
    ));
}

fn iso_triad(fit: &Fit, pal: &Palette, x: f64, y: f64, out: &mut Vec<Item>) {
    for (axis, name) in [
        ([1.0, 0.0, 0.0], "X"),
        ([0.0, 1.0, 0.0], "Y"),
        ([0.0, 0.0, 1.0], "Z"),
    ] {
        let (u, v) = fit.proj.uv(axis);
        let end = [x + 26.0 * u, y - 26.0 * v];
        out.push(line_item(
            [x, y],
            end,
            Stroke {
                color: pal.muted,
                width: 1.5,
                dash: None,
            },
        ));
        out.push(text(
            [x + 36.0 * u, y - 36.0 * v + 4.0],
            name.into(),
            TextSize::Small,
            pal.text,
            Anchor::Middle,
        ));
    }
}

/// The spindle axis of a lathe half-section (X = 0), dash-dot, and the
/// chuck side: the −Z end, where a turning drawing's chuck holds the
/// part, hatched along the left edge of the plot area.
pub(crate) fn lathe(
    fit: &Fit,
    pal: &Palette,
    (ax, ay, aw, ah): (f64, f64, f64, f64),
    out: &mut Vec<Item>,
) {
    let y = fit.y_of(0.0);
    let s = Stroke {
        color: pal.muted,
        width: 1.0,
        dash: None,
    };
    if y >= ay && y <= ay + ah {
        out.push(line_item(
            [ax, y],
            [ax + aw, y],
            Stroke {
                dash: Some([12.0, 3.0]),
                ..s
            },
        ));
    }
    // The jaw (named in the legend): from the axis up a third of the plot
    // area, 9 px wide.
    let bottom = y.clamp(ay, ay + ah);
    let top = (bottom - ah / 3.0).max(ay);
    let (x0, x1) = (ax + 1.0, ax + 10.0);
    out.push(line_item([x1, top], [x1, bottom], s));
    let mut yy = bottom;
    while yy - 9.0 >= top {
        out.push(line_item([x0, yy], [x1, yy - 9.0], s));
        yy -= 6.0;
    }
}

/// The twelve edges of the machine's travel-limit box, dashed, clipped to
/// the frame.
pub(crate) fn limits(
    fit: &Fit,
    pal: &Palette,
    clip: &Clip,
    (lo, hi): (P3, P3),
    out: &mut Vec<Item>,
) {
    let corner =
        |k: usize| -> P3 { [0, 1, 2].map(|i| if k >> i & 1 == 1 { hi[i] } else { lo[i] }) };
    let stroke = Stroke {
        color: pal.muted,
        width: 1.0,
        dash: Some([2.0, 3.0]),
    };
    // Edges of the unit cube: corner pairs that differ in one bit.
    let mut runs = Runs::new(out);
    let mut exits = Exits::default();
    for a in 0..8usize {
        for bit in [1usize, 2, 4] {
            let b = a | bit;
            if b != a {
                runs.line(
                    clip,
                    &mut exits,
                    stroke,
                    fit.xy(corner(a)),
                    fit.xy(corner(b)),
                );
                runs.flush();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers() {
        assert_eq!(tick_step(100.0, 8.0), 10.0);
        assert_eq!(tick_step(0.7, 8.0), 0.1);
        assert_eq!(tick_step(30.0, 8.0), 5.0);
        assert_eq!(tick_label(-0.0001, 0.1), "0.0");
        assert_eq!(tick_label(12.5, 0.5), "12.5");
    }
}
