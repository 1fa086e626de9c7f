//! Errors of the crew readers and of instance construction, with the place they refer to.

use std::fmt;
use thiserror::Error;

/// A place in an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// The input as a whole.
    Whole,
    /// A 1-based line number.
    Line(usize),
    /// A pixel (column, row).
    Pixel(u32, u32),
    /// A grid cell (column, row).
    Cell(u32, u32),
}

/// A crew input error: the input's name, the place, and what is wrong.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub struct CrewError {
    /// Name of the input (usually the file path).
    pub source_name: String,
    /// Where in the input.
    pub location: Location,
    /// What is wrong, in one line.
    pub reason: String,
}

impl CrewError {
    /// A new error.
    pub fn new(source_name: &str, location: Location, reason: impl Into<String>) -> Self {
        CrewError {
            source_name: source_name.to_string(),
            location,
            reason: reason.into(),
        }
    }
}

impl fmt::Display for CrewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Location::Whole => write!(f, "{}: {}", self.source_name, self.reason),
            Location::Line(l) => write!(f, "{}:{}: {}", self.source_name, l, self.reason),
            Location::Pixel(x, y) => {
                write!(f, "{}: pixel ({x}, {y}): {}", self.source_name, self.reason)
            }
            Location::Cell(x, y) => {
                write!(f, "{}: cell ({x}, {y}): {}", self.source_name, self.reason)
            }
        }
    }
}
