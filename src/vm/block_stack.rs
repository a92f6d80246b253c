//! The block stack: the return points of every processing level, innermost last, and beside
//! it what a STEP 7 call saves besides. Its room is fixed when the CPU is made (the profile's
//! nesting limit on every level, plus one), so a block call never allocates and never calls out
//! of the execution loop.

use std::ops::Deref;

#[derive(Debug, Clone)]
pub struct BlockStack<T> {
    frames: Box<[T]>,
    len: usize,
}

impl<T: Copy + Default> BlockStack<T> {
    pub fn with_room(room: usize) -> Self {
        let empty = T::default();
        BlockStack {
            frames: vec![empty; room].into_boxed_slice(),
            len: 0,
        }
    }

    /// The number of return points (not through the slice, which would check its bounds).
    #[inline(always)]
    pub fn len(&self) -> usize {
        self.len
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether `pushes` pushes would find room.
    pub fn has_room_for(&self, pushes: usize) -> bool {
        self.len + pushes <= self.frames.len()
    }

    /// Pushes a return point; `false` when the stack is full.
    #[inline(always)]
    pub fn push(&mut self, frame: T) -> bool {
        match self.frames.get_mut(self.len) {
            Some(slot) => {
                *slot = frame;
                self.len += 1;
                true
            }
            None => false,
        }
    }

    /// Pops the innermost return point. By reference: an `Option<Frame>` would be told apart
    /// from `None` by a byte of the frame, one more test on every block end.
    #[inline(always)]
    pub fn pop(&mut self) -> Option<&T> {
        self.len = self.len.checked_sub(1)?;
        self.frames.get(self.len)
    }
}

impl<T> Deref for BlockStack<T> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        &self.frames[..self.len]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vm::Frame;

    fn frame(pc: u32) -> Frame {
        Frame {
            block: 1,
            start: 0,
            open_db: None,
            params: 0,
            resume: pc,
        }
    }

    #[test]
    fn a_full_stack_refuses_and_an_empty_one_gives_nothing() {
        let mut stack = BlockStack::with_room(2);
        assert!(stack.push(frame(1)));
        assert!(stack.push(frame(2)));
        assert!(!stack.push(frame(3)));
        assert_eq!(stack.len(), 2);
        assert_eq!(stack.last().map(|f| f.pc()), Some(2));
        assert_eq!(stack.pop().map(Frame::pc), Some(2));
        assert_eq!(stack.pop().map(Frame::pc), Some(1));
        assert_eq!(stack.pop(), None);
        assert!(stack.is_empty());
    }
}
