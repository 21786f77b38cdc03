//! A shaded picture of the finished part (PNG).
