//! Colours: the light and dark themes and the three ways of colouring cuts
//! (depth ramp, tool palette, feed ramp), shared by every writer so that an
//! SVG, a PNG and the HTML page of one program look alike.
//!
//! The ramps are quantized (32 depth steps, 16 feed steps) so that
//! neighbouring segments share a colour and merge into one drawn path, and
//! so that output is byte-stable. The colours are our own picks: a blue →
//! teal → green → amber depth ramp (deep is dark and blue, high is warm),
//! a ten-colour tool palette whose neighbours differ in hue and lightness,
//! and rapids in red, dashed, as most controllers show them.

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// Linear blend towards `other` by `t` (0..=1).
    pub fn mix(self, other: Rgb, t: f64) -> Rgb {
        let t = t.clamp(0.0, 1.0);
        let c = |a: u8, b: u8| -> u8 {
            let v = f64::from(a) + (f64::from(b) - f64::from(a)) * t;
            // Clamped to 0..=255 before the conversion.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let out = v.round().clamp(0.0, 255.0) as u8;
            out
        };
        Rgb(c(self.0, other.0), c(self.1, other.1), c(self.2, other.2))
    }
}

/// Light or dark.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Theme {
    /// Dark lines on white.
    Light,
    /// Light lines on near-black.
    Dark,
}

/// The colours of one theme.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Palette {
    /// Page background.
    pub background: Rgb,
    /// Legend panel background.
    pub panel: Rgb,
    /// Text.
    pub text: Rgb,
    /// Secondary text, axes, ticks.
    pub muted: Rgb,
    /// Grid lines.
    pub grid: Rgb,
    /// Rapid moves.
    pub rapid: Rgb,
    /// The programmed contour under cutter compensation.
    pub contour: Rgb,
    /// The compared program's path.
    pub compare: Rgb,
    /// Start point (off every ramp, so a mark is never read as a cut).
    pub start: Rgb,
    /// Hole marks.
    pub hole: Rgb,
    /// Tool change marks.
    pub tool_change: Rgb,
    /// The alarm mark.
    pub alarm: Rgb,
    /// Cuts before any tool change when colouring by tool.
    pub no_tool: Rgb,
    /// Depth ramp stops, deep to high.
    pub depth: [Rgb; 4],
    /// Feed ramp stops, slow to fast.
    pub feed: [Rgb; 3],
    /// Tool palette.
    pub tools: [Rgb; 10],
}

/// The palette of a theme.
pub fn palette(theme: Theme) -> Palette {
    match theme {
        Theme::Light => Palette {
            background: Rgb(255, 255, 255),
            panel: Rgb(244, 245, 247),
            text: Rgb(28, 30, 36),
            muted: Rgb(110, 116, 128),
            grid: Rgb(232, 234, 238),
            rapid: Rgb(214, 48, 39),
            contour: Rgb(156, 39, 176),
            compare: Rgb(255, 150, 0),
            start: Rgb(28, 30, 36),
            hole: Rgb(20, 20, 20),
            tool_change: Rgb(0, 110, 200),
            alarm: Rgb(220, 0, 0),
            no_tool: Rgb(90, 96, 110),
            depth: [
                Rgb(35, 50, 150),
                Rgb(20, 130, 140),
                Rgb(80, 170, 60),
                Rgb(225, 160, 20),
            ],
            feed: [Rgb(40, 90, 200), Rgb(40, 160, 90), Rgb(230, 120, 20)],
            tools: [
                Rgb(31, 119, 180),
                Rgb(44, 160, 44),
                Rgb(148, 103, 189),
                Rgb(140, 86, 75),
                Rgb(227, 119, 194),
                Rgb(23, 190, 207),
                Rgb(188, 189, 34),
                Rgb(255, 127, 14),
                Rgb(70, 70, 70),
                Rgb(0, 90, 80),
            ],
        },
        Theme::Dark => Palette {
            background: Rgb(18, 20, 26),
            panel: Rgb(30, 33, 41),
            text: Rgb(228, 230, 235),
            muted: Rgb(150, 156, 168),
            grid: Rgb(40, 44, 54),
            rapid: Rgb(255, 95, 80),
            contour: Rgb(220, 120, 255),
            compare: Rgb(255, 190, 60),
            start: Rgb(235, 235, 240),
            hole: Rgb(240, 240, 240),
            tool_change: Rgb(90, 180, 255),
            alarm: Rgb(255, 60, 60),
            no_tool: Rgb(170, 176, 190),
            depth: [
                Rgb(70, 90, 230),
                Rgb(30, 180, 190),
                Rgb(120, 220, 90),
                Rgb(255, 205, 60),
            ],
            feed: [Rgb(80, 140, 255), Rgb(70, 210, 130), Rgb(255, 150, 50)],
            tools: [
                Rgb(90, 170, 240),
                Rgb(100, 220, 100),
                Rgb(190, 150, 240),
                Rgb(210, 150, 120),
                Rgb(255, 150, 220),
                Rgb(60, 230, 240),
                Rgb(225, 225, 80),
                Rgb(255, 160, 60),
                Rgb(200, 200, 200),
                Rgb(60, 200, 170),
            ],
        },
    }
}

/// Steps of the depth ramp.
pub const DEPTH_STEPS: u32 = 32;
/// Steps of the feed ramp.
pub const FEED_STEPS: u32 = 16;

/// The colour at `t` (0..=1) of a ramp through `stops`, quantized to
/// `steps` colours.
pub fn ramp(stops: &[Rgb], t: f64, steps: u32) -> Rgb {
    let n = steps.max(2) - 1;
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.5
    };
    // 0..=n, so the conversion is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let k = (t * f64::from(n)).round() as u32;
    let q = f64::from(k) / f64::from(n);
    let segments = stops.len().saturating_sub(1).max(1);
    let x = q * segments as f64;
    // x is in 0..=segments.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let i = (x.floor() as usize).min(segments - 1);
    match (stops.get(i), stops.get(i + 1)) {
        (Some(a), Some(b)) => a.mix(*b, x - i as f64),
        (Some(a), None) => *a,
        _ => Rgb(128, 128, 128),
    }
}

/// Where `v` sits in `lo..=hi` (0.5 when the range is empty).
pub fn fraction(v: f64, lo: f64, hi: f64) -> f64 {
    if hi - lo > 1e-9 {
        ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
    } else {
        0.5
    }
}

/// The colour of tool index `tool` (0: no tool yet).
pub fn tool_color(p: &Palette, tool: u16) -> Rgb {
    match usize::from(tool).checked_sub(1) {
        Some(i) => p.tools[i % p.tools.len()],
        None => p.no_tool,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_starts_and_ends_at_its_stops_and_is_quantized() {
        let p = palette(Theme::Light);
        assert_eq!(ramp(&p.depth, 0.0, DEPTH_STEPS), p.depth[0]);
        assert_eq!(ramp(&p.depth, 1.0, DEPTH_STEPS), p.depth[3]);
        // Values closer than half a step share a colour.
        assert_eq!(
            ramp(&p.depth, 0.500, DEPTH_STEPS),
            ramp(&p.depth, 0.505, DEPTH_STEPS)
        );
        assert_eq!(ramp(&p.depth, f64::NAN, 4), ramp(&p.depth, 0.5, 4));
    }
}
