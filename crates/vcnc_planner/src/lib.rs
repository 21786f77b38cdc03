//! `vcnc_planner` turns canonical events into a timed trajectory on the
//! machine model, as a controller's motion planner does: per-axis rapid
//! rates, feed limits, accelerations and jerks; look-ahead over a bounded
//! window; corner speeds within the corner tolerance; arc speeds within the
//! centripetal acceleration; exact stops, dwells, tool changes and spindle
//! times. It implements [`vcnc_core::Sink`] and knows nothing of the
//! interpreter (`docs/planner.md` describes the algorithms and decisions).
//!
//! ```text
//! events ─▶ Planner (Sink) ─▶ Timeline ─┬─▶ CycleTime   (vcnc time, check)
//!                                        ├─▶ Stamps     (a page's times per block)
//!                                        └─▶ Sampler ─▶ Smoothed (run --format trace;
//!                                                           the filter profile's average)
//! ```

mod limits;
mod path;
mod planner;
mod ramp;
mod ring;
mod stamps;
mod time;
mod timeline;
mod trace;

pub use limits::{ARC_NORMAL_SHARE, ARC_TANGENT_SHARE, AxisLimits, corner_speed};
pub use path::{Path, Shape, Vector};
pub use planner::{Planner, filter_time};
pub use ramp::{Kin, Profile, Ramp};
pub use stamps::{Blocks, MAX_STAMPS, Numbered, Stamps};
pub use time::CycleTime;
pub use timeline::{Attr, AxesMove, MoveKind, Pause, PauseKind, Segment, Timeline};
pub use trace::{MAX_FILTER_SAMPLES, Sample, SampleSink, Sampler, Smoothed, filter_samples};
pub use vcnc_core::motion::Profile as ProfileShape;

/// Plans a whole run: feed the events to the returned planner, then call
/// [`Planner::into_timeline`] for the cycle time.
pub fn cycle_time(machine: &vcnc_core::Machine) -> Planner<CycleTime> {
    Planner::new(machine, CycleTime::new())
}
