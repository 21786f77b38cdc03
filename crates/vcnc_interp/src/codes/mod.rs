//! What the G and M codes do, one family per file. Each function takes the
//! validated words of its block and either changes the state (offsets,
//! transforms, tool length) or builds moves for the motion stage
//! (`crate::motion`); none of them emits a motion event itself. Their moves
//! reach the motion stage through `modal.rs`'s `send`.

pub(crate) mod calls;
pub(crate) mod circle_cut;
pub(crate) mod comp;
pub(crate) mod corner;
pub(crate) mod cycles;
pub(crate) mod lathe_cycles;
pub(crate) mod modal;
pub(crate) mod mrc;
pub(crate) mod ngc_rough;
pub(crate) mod ngc_thread;
pub(crate) mod nurbs;
pub(crate) mod offsets;
pub(crate) mod pockets;
pub(crate) mod profile;
pub(crate) mod refs;
pub(crate) mod rough;
pub(crate) mod smoothing;
pub(crate) mod threads;
pub(crate) mod tool_length;
pub(crate) mod transforms;
pub(crate) mod turning;
pub(crate) mod turning_cycles;
pub(crate) mod turret;
