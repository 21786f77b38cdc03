//! How people read figures: one duration format and one length unit for
//! every output a person reads (`check`'s summary, `time`, plot legends,
//! the viewer page), so that the same program shows the same numbers
//! everywhere.
//!
//! Machine-readable outputs (JSON, events) stay in mm and seconds; only
//! text meant for a person goes through here.

/// The unit lengths are shown in (`--units`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DisplayUnits {
    /// Millimetres.
    #[default]
    Mm,
    /// Inches.
    In,
}

impl DisplayUnits {
    /// Reads `mm` or `in` (any case).
    pub fn parse(text: &str) -> Option<DisplayUnits> {
        match text.to_ascii_lowercase().as_str() {
            "mm" | "metric" => Some(DisplayUnits::Mm),
            "in" | "inch" | "inches" => Some(DisplayUnits::In),
            _ => None,
        }
    }

    /// The unit's short name.
    pub fn name(self) -> &'static str {
        match self {
            DisplayUnits::Mm => "mm",
            DisplayUnits::In => "in",
        }
    }

    /// A length in mm, in this unit.
    pub fn of_mm(self, mm: f64) -> f64 {
        match self {
            DisplayUnits::Mm => mm,
            DisplayUnits::In => mm / 25.4,
        }
    }

    /// Decimals a length is shown with (3 in mm, 4 in inches).
    pub fn decimals(self) -> usize {
        match self {
            DisplayUnits::Mm => 3,
            DisplayUnits::In => 4,
        }
    }

    /// A length in mm written in this unit with its decimals, no unit name.
    pub fn len(self, mm: f64) -> String {
        format!("{:.*}", self.decimals(), self.of_mm(mm))
    }
}

/// A duration as people read it: `41.7s`, `1m 02.3s`, `1h 00m 00.0s`.
/// Rounded to the tenth shown first, so 59.96 s is `1m 00.0s`, never
/// `60.0s`.
pub fn duration(s: f64) -> String {
    let total = (s.max(0.0) * 10.0).round() / 10.0;
    let h = (total / 3600.0).floor();
    let m = ((total - h * 3600.0) / 60.0).floor();
    let sec = total - h * 3600.0 - m * 60.0;
    if h > 0.0 {
        format!("{h}h {m:02}m {sec:04.1}s")
    } else if m > 0.0 {
        format!("{m}m {sec:04.1}s")
    } else {
        format!("{sec:.1}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_round_before_they_split() {
        assert_eq!(duration(59.96), "1m 00.0s");
        assert_eq!(duration(3599.96), "1h 00m 00.0s");
        assert_eq!(duration(61.24), "1m 01.2s");
        assert_eq!(duration(0.04), "0.0s");
    }

    #[test]
    fn inches_show_four_decimals() {
        assert_eq!(DisplayUnits::In.len(25.4), "1.0000");
        assert_eq!(DisplayUnits::Mm.len(25.4), "25.400");
        assert_eq!(DisplayUnits::parse("IN"), Some(DisplayUnits::In));
        assert_eq!(DisplayUnits::parse("ft"), None);
    }
}
