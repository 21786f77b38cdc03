//! A block's last two phases: convert ([`convert`]: what each value means
//! in mm, degrees, seconds, and where the axis words point in program
//! coordinates) and execute ([`execute`]: the fixed order of a block). The
//! first, validation ([`crate::words`]: which codes and words, nothing
//! executed), sits lower, as the motion stage and the codes read its table
//! too.
//!
//! The interpreter (`interpreter.rs`) wraps each block so that it is all or
//! nothing: a copy of the state is taken before, restored if any phase
//! alarms, and the block's events reach the sink only when it succeeds.

pub(crate) mod convert;
pub(crate) mod execute;
