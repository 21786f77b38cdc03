//! One block, in three phases: validate ([`crate::words`]: which codes and
//! words, nothing executed; below this folder, as the motion stage and the
//! codes read its table too), convert ([`convert`]: what each value means
//! in mm, degrees, seconds, and where the axis words point in program
//! coordinates), execute ([`execute`]: the fixed order of a block).
//!
//! The interpreter (`interpreter.rs`) wraps each block so that it is all or
//! nothing: a copy of the state is taken before, restored if any phase
//! alarms, and the block's events reach the sink only when it succeeds.

pub(crate) mod convert;
pub(crate) mod execute;
