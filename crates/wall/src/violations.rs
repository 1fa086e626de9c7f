//! [`Violations`]: how every validator reports the rules an artefact breaks, the first only
//! (`validate`, `check_trace`) or every one (the `*_violations` functions behind
//! `mason check --all`), from one implementation.
//!
//! ```
//! use mason_wall::violations::Violations;
//! use std::ops::ControlFlow;
//! fn odd(xs: &[u32], v: &mut Violations<u32>) -> ControlFlow<()> {
//!     for &x in xs {
//!         if x % 2 == 1 {
//!             v.report(x)?;
//!         }
//!     }
//!     ControlFlow::Continue(())
//! }
//! let mut first = Violations::first();
//! let _ = odd(&[2, 3, 5], &mut first);
//! assert_eq!(first.into_vec(), vec![3]);
//! let mut every = Violations::every();
//! let _ = odd(&[2, 3, 5], &mut every);
//! assert_eq!(every.into_vec(), vec![3, 5]);
//! ```

use std::ops::ControlFlow;

/// The name of a broken rule: its error variant's name (`Unsupported`, `ZoneShared`,
/// `Conflict`, …), as `mason check` reports it.
pub fn rule<E: std::fmt::Debug>(e: &E) -> String {
    format!("{e:?}")
        .chars()
        .take_while(char::is_ascii_alphanumeric)
        .collect()
}

/// The violations found so far, and whether the check goes on after the first.
#[derive(Clone, Debug, PartialEq)]
pub struct Violations<E> {
    all: bool,
    found: Vec<E>,
}

impl<E> Violations<E> {
    /// Stops at the first violation.
    pub fn first() -> Self {
        Violations {
            all: false,
            found: Vec::new(),
        }
    }

    /// Collects every violation.
    pub fn every() -> Self {
        Violations {
            all: true,
            found: Vec::new(),
        }
    }

    /// Records `e`; `Break` when the check should stop here.
    pub fn report(&mut self, e: E) -> ControlFlow<()> {
        self.found.push(e);
        if self.all {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    }

    /// Whether nothing was found.
    pub fn is_empty(&self) -> bool {
        self.found.is_empty()
    }

    /// What was found, in the order found.
    pub fn into_vec(self) -> Vec<E> {
        self.found
    }

    /// `Ok(value)` when nothing was found, else the first violation.
    pub fn into_result<T>(self, value: T) -> Result<T, E> {
        match self.found.into_iter().next() {
            None => Ok(value),
            Some(e) => Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_stops_and_every_goes_on() {
        let mut first = Violations::first();
        assert!(first.is_empty());
        assert_eq!(first.report("a"), ControlFlow::Break(()));
        assert!(!first.is_empty());
        assert_eq!(first.clone().into_result(7), Err("a"));
        assert_eq!(first.into_vec(), ["a"]);
        let mut every = Violations::every();
        assert_eq!(every.report("a"), ControlFlow::Continue(()));
        assert_eq!(every.report("b"), ControlFlow::Continue(()));
        assert_eq!(every.clone().into_result(7), Err("a"));
        assert_eq!(every.into_vec(), ["a", "b"]);
        let none: Violations<&str> = Violations::every();
        assert!(none.is_empty());
        assert_eq!(none.into_result(7), Ok(7));
    }
}
