//! The storage of the look-ahead window: a ring of reused slots. A move is
//! written into its slot once; committing the oldest only moves the start,
//! and a new move takes the slot a committed one left. A planned move is a
//! few hundred bytes (its path holds room for an arc), and carrying it
//! through a `VecDeque` by value — built, pushed, popped — copied it
//! several times per block: on a chain of short moves a tenth of the
//! planner's work (`docs/performance.md`).
//!
//! ```text
//!   slots:  [ c | d | e | · | a | b ]     · : free (a committed move's
//!                       ▲       ▲             leftovers, overwritten next)
//!                  next push   head (oldest, index 0)
//! ```
//!
//! It grows like a `Vec` until the window is as long as it gets; the
//! leftovers in free slots are dropped when the slot is reused or the ring
//! is.

use std::ops::{Index, IndexMut};

/// A double-ended queue over reused slots; see the module documentation.
#[derive(Debug)]
pub(crate) struct Ring<T> {
    slots: Vec<T>,
    /// The slot of index 0.
    head: usize,
    len: usize,
}

impl<T> Ring<T> {
    /// An empty ring with room for `n` before it grows.
    pub(crate) fn with_capacity(n: usize) -> Ring<T> {
        Ring {
            slots: Vec::with_capacity(n),
            head: 0,
            len: 0,
        }
    }

    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The slot of index `i` (< `slots.len()`).
    fn slot(&self, i: usize) -> usize {
        let s = self.head + i;
        if s >= self.slots.len() {
            s - self.slots.len()
        } else {
            s
        }
    }

    pub(crate) fn get(&self, i: usize) -> Option<&T> {
        if i < self.len {
            self.slots.get(self.slot(i))
        } else {
            None
        }
    }

    pub(crate) fn get_mut(&mut self, i: usize) -> Option<&mut T> {
        if i < self.len {
            let s = self.slot(i);
            self.slots.get_mut(s)
        } else {
            None
        }
    }

    pub(crate) fn front(&self) -> Option<&T> {
        self.get(0)
    }

    pub(crate) fn back(&self) -> Option<&T> {
        self.get(self.len.wrapping_sub(1))
    }

    pub(crate) fn back_mut(&mut self) -> Option<&mut T> {
        self.get_mut(self.len.wrapping_sub(1))
    }

    /// Appends the value left in a free slot, to be overwritten in place
    /// (no value is built and then moved); `None` when every slot is in
    /// use, and [`Ring::push_back`] must add one.
    pub(crate) fn push_reused(&mut self) -> Option<&mut T> {
        if self.len < self.slots.len() {
            let s = self.slot(self.len);
            self.len += 1;
            self.slots.get_mut(s)
        } else {
            None
        }
    }

    /// Appends `value`, in a free slot if there is one.
    pub(crate) fn push_back(&mut self, value: T) {
        if self.len < self.slots.len() {
            let s = self.slot(self.len);
            if let Some(slot) = self.slots.get_mut(s) {
                *slot = value;
            }
        } else {
            // Full: put the ring in order and grow it at the end.
            self.slots.rotate_left(self.head);
            self.head = 0;
            self.slots.push(value);
        }
        self.len += 1;
    }

    /// Forgets the oldest value (its slot is reused by a later push).
    pub(crate) fn pop_front(&mut self) {
        if self.len > 0 {
            self.head = self.slot(1);
            self.len -= 1;
        }
    }
}

impl<T> Index<usize> for Ring<T> {
    type Output = T;

    fn index(&self, i: usize) -> &T {
        match self.get(i) {
            Some(v) => v,
            None => panic!("ring index {i} out of {}", self.len),
        }
    }
}

impl<T> IndexMut<usize> for Ring<T> {
    fn index_mut(&mut self, i: usize) -> &mut T {
        let len = self.len;
        match self.get_mut(i) {
            Some(v) => v,
            None => panic!("ring index {i} out of {len}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Ring;

    /// The ring keeps order across wrap-around and growth.
    #[test]
    fn a_ring_is_a_queue_across_wraps_and_growth() {
        let mut r = Ring::with_capacity(2);
        let mut model = std::collections::VecDeque::new();
        for k in 0..200u32 {
            // Push more than pop for a while, then the other way round.
            let pushes = if k < 100 { 2 } else { 1 };
            for p in 0..pushes {
                r.push_back(k * 10 + p);
                model.push_back(k * 10 + p);
            }
            if k % 3 != 0 || k >= 100 {
                r.pop_front();
                model.pop_front();
            }
            assert_eq!(r.len(), model.len());
            for (i, v) in model.iter().enumerate() {
                assert_eq!(r[i], *v);
            }
            assert_eq!(r.front(), model.front());
            if k % 7 == 0 {
                match r.push_reused() {
                    Some(slot) => *slot = k,
                    None => r.push_back(k),
                }
                model.push_back(k);
            }
            assert_eq!(r.back(), model.back());
        }
    }
}
