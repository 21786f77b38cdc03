//! The `[motion]` section of the machine file: how the planner
//! (`vcnc_planner`) turns events into a timed trajectory — the profile
//! shape, the look-ahead window, the corner tolerance, the servo's settling
//! and the times of tool changes and spindle starts and stops — and the
//! parameter sets of the Syntec G05 high-speed high-precision mode.
//!
//! Per-axis limits (rapid rate, maximum feed, acceleration, jerk, in-position
//! windows) live with the axes in `machine.rs`; this file holds what is
//! shared by the whole machine. Every key has a default, so machine files
//! written before the planner existed stay valid (`docs/machine.md`).

use crate::machine::MachineError;
use serde::Deserialize;

/// Largest look-ahead window: it bounds the planner's memory.
pub const MAX_LOOKAHEAD_BLOCKS: u32 = 10_000;

/// The shape of the speed profile along the path.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Profile {
    /// Constant acceleration ramps (infinite jerk).
    Trapezoid,
    /// Jerk-limited ramps (S-curve, seven phases) in every block, each
    /// starting and ending at zero acceleration.
    Jerk,
    /// Acceleration and deceleration after interpolation (Fanuc's
    /// bell-shaped type): the trapezoid plan passed through a moving
    /// average of T = a/j, the slowest axis' (`docs/planner.md`).
    Filter,
}

impl Profile {
    /// `"trapezoid"`, `"jerk"` or `"filter"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Profile::Trapezoid => "trapezoid",
            Profile::Jerk => "jerk",
            Profile::Filter => "filter",
        }
    }
}

/// One G05 parameter set (P1–P5, P10000).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HighSpeedSet {
    /// The P number: 1 to 5 or 10000.
    pub p: u32,
    /// Blocks of look-ahead in this mode.
    pub lookahead_blocks: u32,
    /// Corner tolerance in this mode, mm.
    pub corner_tolerance_mm: f64,
}

/// Machine-wide motion settings.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Motion {
    /// Speed profile shape.
    pub profile: Profile,
    /// Blocks the planner looks ahead (outside G05).
    pub lookahead_blocks: u32,
    /// Largest distance a blended corner may pass from the programmed
    /// corner point (junction deviation), mm.
    pub corner_tolerance_mm: f64,
    /// Position loop gain: how fast the following error settles into the
    /// in-position window after an exact stop, 1/s.
    pub servo_gain_per_s: f64,
    /// Time of one tool change (M06), s.
    pub tool_change_s: f64,
    /// Time for the spindle to start or reverse and reach its speed, s.
    pub spindle_start_s: f64,
    /// Time for the spindle to stop (M05, M19), s.
    pub spindle_stop_s: f64,
    /// G05 parameter sets.
    pub high_speed: Vec<HighSpeedSet>,
}

impl Default for Motion {
    fn default() -> Motion {
        Motion {
            profile: Profile::Trapezoid,
            lookahead_blocks: 200,
            corner_tolerance_mm: 0.02,
            servo_gain_per_s: 50.0,
            tool_change_s: 4.0,
            spindle_start_s: 1.0,
            spindle_stop_s: 0.8,
            high_speed: Vec::new(),
        }
    }
}

impl Motion {
    /// The settings of G05 P`p`: the machine file's set, or the built-in
    /// one (1,000 blocks, a quarter of the corner tolerance, at most 5 µm).
    pub fn high_speed_set(&self, p: u32) -> HighSpeedSet {
        self.high_speed
            .iter()
            .find(|s| s.p == p)
            .copied()
            .unwrap_or(HighSpeedSet {
                p,
                lookahead_blocks: 1000,
                corner_tolerance_mm: (self.corner_tolerance_mm / 4.0).min(0.005),
            })
    }

    pub(crate) fn check(&self) -> Result<(), MachineError> {
        check_lookahead(self.lookahead_blocks, "motion.lookahead_blocks")?;
        check_positive(self.corner_tolerance_mm, "motion.corner_tolerance_mm")?;
        check_positive(self.servo_gain_per_s, "motion.servo_gain_per_s")?;
        for (v, name) in [
            (self.tool_change_s, "motion.tool_change_s"),
            (self.spindle_start_s, "motion.spindle_start_s"),
            (self.spindle_stop_s, "motion.spindle_stop_s"),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(MachineError(format!("{name} must be a time >= 0")));
            }
        }
        for (i, s) in self.high_speed.iter().enumerate() {
            if !matches!(s.p, 1..=5 | 10_000) {
                return Err(MachineError(format!(
                    "motion.high_speed[{i}].p is 1 to 5 or 10000, not {}",
                    s.p
                )));
            }
            if self.high_speed[..i].iter().any(|o| o.p == s.p) {
                return Err(MachineError(format!(
                    "motion.high_speed: P{} is defined twice",
                    s.p
                )));
            }
            check_lookahead(s.lookahead_blocks, "motion.high_speed.lookahead_blocks")?;
            check_positive(
                s.corner_tolerance_mm,
                "motion.high_speed.corner_tolerance_mm",
            )?;
        }
        Ok(())
    }
}

fn check_lookahead(n: u32, name: &str) -> Result<(), MachineError> {
    if (2..=MAX_LOOKAHEAD_BLOCKS).contains(&n) {
        Ok(())
    } else {
        Err(MachineError(format!(
            "{name} is 2 to {MAX_LOOKAHEAD_BLOCKS}, not {n}"
        )))
    }
}

fn check_positive(v: f64, name: &str) -> Result<(), MachineError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(MachineError(format!("{name} must be positive")))
    }
}

#[cfg(test)]
mod tests {
    use crate::machine::{DEFAULT_LATHE_TOML, DEFAULT_MILL_TOML, Machine};
    use crate::motion::Profile;

    /// A machine file written before the planner: every motion key has its
    /// default, the axes their default jerk and windows.
    #[test]
    fn an_old_machine_file_gets_the_defaults() {
        let old = "name = \"old\"\n[[axes]]\nletter = \"x\"\nmin_mm = -10.0\nmax_mm = 10.0\n\
                   rapid_mm_per_min = 6000.0\nmax_feed_mm_per_min = 3000.0\naccel_mm_s2 = 500.0\n";
        let m = Machine::from_toml(old).unwrap();
        assert_eq!(m.motion.profile, Profile::Trapezoid);
        assert_eq!(m.motion.lookahead_blocks, 200);
        assert_eq!(m.axes[0].jerk_mm_s3, 500.0 / 0.05);
        assert_eq!(m.axes[0].in_position_mm, 0.01);
        let set = m.motion.high_speed_set(10_000);
        assert_eq!(
            (set.lookahead_blocks, set.corner_tolerance_mm),
            (1000, 0.005)
        );
    }

    #[test]
    fn the_built_in_machines_define_their_motion() {
        let mill = Machine::from_toml(DEFAULT_MILL_TOML).unwrap();
        assert_eq!(mill.motion.profile, Profile::Filter);
        assert_eq!(mill.motion.high_speed.len(), 6);
        assert_eq!(mill.motion.high_speed_set(1).corner_tolerance_mm, 0.002);
        let lathe = Machine::from_toml(DEFAULT_LATHE_TOML).unwrap();
        assert_eq!(lathe.motion.tool_change_s, 2.0);
    }

    #[test]
    fn bad_motion_settings_are_explained() {
        let cases = [
            (
                "lookahead_blocks = 200",
                "lookahead_blocks = 1",
                "lookahead_blocks",
            ),
            (
                "corner_tolerance_mm = 0.02",
                "corner_tolerance_mm = -1.0",
                "corner_tolerance_mm",
            ),
            (
                "tool_change_s = 4.0",
                "tool_change_s = -4.0",
                "tool_change_s",
            ),
            ("p = 5\n", "p = 6\n", "high_speed"),
            ("p = 5\n", "p = 4\n", "twice"),
            ("jerk_mm_s3 = 40000.0", "jerk_mm_s3 = 0.0", "jerk_mm_s3"),
            // a/j = 2000 s, and 1e300/1e-300 overflows: both refused.
            ("jerk_mm_s3 = 40000.0", "jerk_mm_s3 = 1.0", "at most 10 s"),
            (
                "accel_mm_s2 = 2000.0\njerk_mm_s3 = 40000.0",
                "accel_mm_s2 = 1e300\njerk_mm_s3 = 1e-300",
                "at most 10 s",
            ),
            ("profile = \"filter\"", "profile = \"bell\"", "profile"),
        ];
        for (from, to, says) in cases {
            assert!(DEFAULT_MILL_TOML.contains(from), "{from}");
            let bad = DEFAULT_MILL_TOML.replacen(from, to, 1);
            let e = Machine::from_toml(&bad).unwrap_err();
            assert!(e.0.contains(says), "{to}: {e}");
        }
    }
}
