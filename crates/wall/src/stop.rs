//! A stop request shared between a caller and a running search: the caller (a Ctrl-C handler,
//! a Python binding watching for KeyboardInterrupt, a GUI) raises it, the search sees it at its
//! next budget check and returns its best so far, as when a deadline passes.

use std::fmt;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A shared stop flag. Clones share the flag; two `Stop`s are equal when they are the same flag.
#[derive(Clone, Default)]
pub struct Stop(Arc<AtomicBool>);

impl Stop {
    /// A new, lowered flag.
    pub fn new() -> Self {
        Stop::default()
    }

    /// Asks every search holding this flag to stop.
    pub fn raise(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether a stop was asked.
    pub fn raised(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

impl PartialEq for Stop {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl fmt::Debug for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Stop({})", self.raised())
    }
}

/// Whether an optional flag was raised.
pub fn raised(stop: &Option<Stop>) -> bool {
    stop.as_ref().is_some_and(Stop::raised)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_one_flag() {
        let a = Stop::new();
        let b = a.clone();
        assert!(!b.raised());
        a.raise();
        assert!(b.raised());
        assert_eq!(a, b);
        assert_ne!(a, Stop::new());
        assert!(raised(&Some(b)));
        assert!(!raised(&None));
    }
}
