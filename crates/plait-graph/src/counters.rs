//! How many times this process loaded and compiled a pipeline: a render
//! promises to do each once per change, and a test holds it to that
//! (`PLAIT_COUNT=1 plait render …` prints them).

use std::sync::atomic::{AtomicUsize, Ordering};

pub(crate) static LOADS: AtomicUsize = AtomicUsize::new(0);
pub(crate) static COMPILES: AtomicUsize = AtomicUsize::new(0);

/// Calls of [`crate::load`] so far.
pub fn loads() -> usize {
    LOADS.load(Ordering::Relaxed)
}

/// Calls of [`crate::compile`] and [`crate::compile_with`] so far.
pub fn compiles() -> usize {
    COMPILES.load(Ordering::Relaxed)
}
