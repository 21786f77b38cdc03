//! The cycle time of a run and its split: cutting, rapid, dwell, tool
//! changes, spindle starts and stops, settling into position, and the total
//! per tool and per program file — what `vcnc time` prints.

use crate::ramp::Profile;
use crate::timeline::{Attr, AxesMove, MoveKind, Pause, PauseKind, Segment, Timeline};
use std::sync::Arc;
use vcnc_core::Pos;

/// Sums a planned timeline.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CycleTime {
    /// Everything, s.
    pub total_s: f64,
    /// Cutting moves (G01, arcs, threads, skips, NURBS).
    pub cutting_s: f64,
    /// Rapids.
    pub rapid_s: f64,
    /// Dwells (G04).
    pub dwell_s: f64,
    /// Tool changes.
    pub tool_change_s: f64,
    /// Spindle starts, reversals and stops.
    pub spindle_s: f64,
    /// Settling into the in-position window after exact stops.
    pub in_position_s: f64,
    /// Cutting path length, mm.
    pub cutting_mm: f64,
    /// Rapid path length, mm.
    pub rapid_mm: f64,
    /// Planned moves.
    pub moves: u64,
    /// Moves that could not be timed.
    pub untimed_moves: u64,
    /// Time per tool (`None`: before the first tool change), in order of use.
    pub per_tool: Vec<(Option<u32>, f64)>,
    /// Time per program file (`None`: the main program), in order of use.
    pub per_file: Vec<(Option<Arc<str>>, f64)>,
    last_tool: usize,
    last_file: usize,
    /// The last move was a rapid: a filter's run-out after it is rapid
    /// time.
    last_rapid: bool,
}

impl CycleTime {
    /// An empty sum.
    pub fn new() -> CycleTime {
        CycleTime::default()
    }

    /// Adds `seconds` to the total, its tool and its file: almost always
    /// the tool and file of the time before, which is checked first.
    fn add(&mut self, seconds: f64, attr: &Attr) {
        self.total_s += seconds;
        match self.per_tool.get_mut(self.last_tool) {
            Some(e) if e.0 == attr.tool => e.1 += seconds,
            _ => self.add_other_tool(seconds, attr.tool),
        }
        match self.per_file.get_mut(self.last_file) {
            Some(e) if e.0 == attr.file => e.1 += seconds,
            _ => self.add_other_file(seconds, &attr.file),
        }
    }

    #[cold]
    fn add_other_tool(&mut self, seconds: f64, tool: Option<u32>) {
        self.last_tool = match self.per_tool.iter().position(|e| e.0 == tool) {
            Some(i) => i,
            None => {
                self.per_tool.push((tool, 0.0));
                self.per_tool.len() - 1
            }
        };
        if let Some(e) = self.per_tool.get_mut(self.last_tool) {
            e.1 += seconds;
        }
    }

    #[cold]
    fn add_other_file(&mut self, seconds: f64, file: &Option<Arc<str>>) {
        self.last_file = match self.per_file.iter().position(|e| e.0 == *file) {
            Some(i) => i,
            None => {
                self.per_file.push((file.clone(), 0.0));
                self.per_file.len() - 1
            }
        };
        if let Some(e) = self.per_file.get_mut(self.last_file) {
            e.1 += seconds;
        }
    }
}

impl Timeline for CycleTime {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        let t = profile.duration();
        self.moves += 1;
        self.last_rapid = seg.kind == MoveKind::Rapid;
        match seg.kind {
            MoveKind::Cut => {
                self.cutting_s += t;
                self.cutting_mm += seg.path.len;
            }
            MoveKind::Rapid => {
                self.rapid_s += t;
                self.rapid_mm += seg.path.len;
            }
        }
        self.add(t, &seg.attr);
    }

    fn axes(&mut self, mv: &AxesMove) {
        self.moves += 1;
        self.last_rapid = true;
        self.rapid_s += mv.duration_s;
        let mut d2 = 0.0;
        for i in 0..vcnc_core::MAX_AXES {
            let d = mv.to.get(i) - mv.from.get(i);
            d2 += d * d;
        }
        self.rapid_mm += d2.sqrt();
        self.add(mv.duration_s, &mv.attr);
    }

    fn pause(&mut self, p: &Pause) {
        match p.kind {
            PauseKind::Dwell => self.dwell_s += p.seconds,
            PauseKind::ToolChange => self.tool_change_s += p.seconds,
            PauseKind::Spindle => self.spindle_s += p.seconds,
            PauseKind::InPosition => self.in_position_s += p.seconds,
            PauseKind::Filter if self.last_rapid => self.rapid_s += p.seconds,
            PauseKind::Filter => self.cutting_s += p.seconds,
        }
        self.add(p.seconds, &p.attr);
    }

    fn untimed(&mut self, _: Pos, _: Pos, _: &Attr) {
        self.untimed_moves += 1;
    }
}
